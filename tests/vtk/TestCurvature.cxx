// SPDX-License-Identifier: BSD-3-Clause
// tcCurvature on the bundled bunny: every array is there with its shape, k1 >= k2, nothing
// is NaN, mean and Gaussian curvature agree with k1 and k2; then the mean-curvature picture is
// compared with its baseline. Accuracy on analytic surfaces is tested in the core tests.
#include "tcCurvature.h"
#include "tcTestUtilities.h"

#include "tc/common/array_names.h"

#include <vtkCallbackCommand.h>
#include <vtkCellData.h>
#include <vtkDataArray.h>
#include <vtkNew.h>
#include <vtkPointData.h>
#include <vtkPolyData.h>
#include <vtkRenderWindow.h>

#include <cmath>

int TestCurvature(int argc, char* argv[])
{
  tctest::Checker check;
  vtkSmartPointer<vtkPolyData> bunny =
    tctest::ReadPrepared(tctest::Arg(argc, argv, "-D") + "/meshes/bunny_npm.off");
  if (!TC_CHECK(check, bunny != nullptr))
  {
    return 1;
  }
  vtkNew<tcCurvature> curvature;
  curvature->SetInputData(bunny);
  curvature->Update();
  vtkPolyData* out = curvature->GetOutput();
  vtkPointData* pd = out->GetPointData();
  vtkDataArray* k = pd->GetArray(tc::kPrincipalCurvatures);
  vtkDataArray* d = pd->GetArray(tc::kPrincipalDirections);
  vtkDataArray* h = pd->GetArray(tc::kMeanCurvature);
  vtkDataArray* g = pd->GetArray(tc::kGaussianCurvature);
  vtkDataArray* fh = out->GetCellData()->GetArray(tc::kFaceMeanCurvature);
  const bool all = k && d && h && g && fh;
  TC_CHECK(check, all);
  if (!all)
  {
    return 1;
  }
  TC_CHECK(check, k->GetNumberOfComponents() == 2 && d->GetNumberOfComponents() == 6);
  TC_CHECK(check, k->GetNumberOfTuples() == bunny->GetNumberOfPoints());
  TC_CHECK(check, fh->GetNumberOfTuples() == bunny->GetNumberOfPolys());
  int bad = 0;
  double meanH = 0.0;
  for (vtkIdType v = 0; v < out->GetNumberOfPoints(); ++v)
  {
    const double k1 = k->GetComponent(v, 0);
    const double k2 = k->GetComponent(v, 1);
    const double scale = std::abs(k1) + std::abs(k2) + 1e-12;
    bad += !std::isfinite(k1) || !std::isfinite(k2) || k1 < k2 ||
      std::abs(h->GetTuple1(v) - 0.5 * (k1 + k2)) > 1e-9 * scale ||
      std::abs(g->GetTuple1(v) - k1 * k2) > 1e-9 * scale * scale;
    meanH += h->GetTuple1(v);
  }
  TC_CHECK(check, bad == 0);
  // The bunny is a closed, mostly convex surface: its average mean curvature is positive.
  TC_CHECK(check, meanH > 0.0);
  // Crest lines come out on port 1 with their arrays.
  vtkPolyData* crest = curvature->GetOutput(1);
  TC_CHECK(check, crest->GetNumberOfLines() > 0);
  TC_CHECK(check, crest->GetCellData()->GetArray(tc::kStrength) != nullptr);

  vtkSmartPointer<vtkRenderWindow> window =
    tctest::CurvatureScene(out, tc::kMeanCurvature, nullptr);
  TC_CHECK(check, tctest::MatchesBaseline(argc, argv, window));
  return check.failures == 0 ? 0 : 1;
}
