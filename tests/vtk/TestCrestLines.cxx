// SPDX-License-Identifier: BSD-3-Clause
// Crest lines of tcCurvature on the bundled fandisk (a CAD part with sharp creases): lines are
// found, each is above the strength threshold with a valid type, a threshold above the median
// strength keeps at most half; then the lines over the mean-curvature colouring are compared with
// the baseline.
#include "tcCurvature.h"
#include "tcTestUtilities.h"

#include "tc/common/array_names.h"

#include <vtkCellData.h>
#include <vtkDataArray.h>
#include <vtkNew.h>
#include <vtkPolyData.h>
#include <vtkRenderWindow.h>

#include <algorithm>
#include <vector>

int TestCrestLines(int argc, char* argv[])
{
  tctest::Checker check;
  vtkSmartPointer<vtkPolyData> fandisk =
    tctest::ReadPrepared(tctest::Arg(argc, argv, "-D") + "/meshes/fandisk.off");
  if (!TC_CHECK(check, fandisk != nullptr))
  {
    return 1;
  }
  vtkNew<tcCurvature> curvature;
  curvature->SetInputData(fandisk);
  curvature->Update();
  vtkPolyData* crest = curvature->GetOutput(1);
  vtkDataArray* strength = crest->GetCellData()->GetArray(tc::kStrength);
  vtkDataArray* type = crest->GetCellData()->GetArray(tc::kCrestType);
  const vtkIdType lines = crest->GetNumberOfLines();
  TC_CHECK(check, lines >= 10);
  TC_CHECK(check, strength && type);
  if (!strength || !type)
  {
    return 1;
  }
  int ridges = 0;
  int valleys = 0;
  std::vector<double> strengths;
  for (vtkIdType c = 0; c < lines; ++c)
  {
    strengths.push_back(strength->GetTuple1(c));
    TC_CHECK(check, strength->GetTuple1(c) >= curvature->GetCrestStrengthThreshold());
    ridges += type->GetTuple1(c) == 0;
    valleys += type->GetTuple1(c) == 1;
  }
  TC_CHECK(check, ridges + valleys == lines);
  TC_CHECK(check, ridges > 0 && valleys > 0); // fandisk has convex and concave creases

  // A threshold just above the median strength keeps fewer than half of the lines.
  std::sort(strengths.begin(), strengths.end());
  const double median = strengths.empty() ? 0.0 : strengths[strengths.size() / 2];
  vtkNew<tcCurvature> strict;
  strict->SetInputData(fandisk);
  strict->SetCrestStrengthThreshold(median * (1.0 + 1e-9));
  strict->Update();
  const vtkIdType kept = strict->GetOutput(1)->GetNumberOfLines();
  TC_CHECK(check, kept > 0 && 2 * kept <= lines);

  vtkSmartPointer<vtkRenderWindow> window =
    tctest::CurvatureScene(curvature->GetOutput(), tc::kMeanCurvature, crest);
  TC_CHECK(check, tctest::MatchesBaseline(argc, argv, window));
  return check.failures == 0 ? 0 : 1;
}
