// SPDX-License-Identifier: BSD-3-Clause
// tcFeatureRefinement on the bundled fandisk and bunny: feature lines and corners come out
// with their arrays, every feature-line point is flagged FeatureVertex on the mesh, corners
// match CornerVertex; then refined clusters, feature lines and corners of both meshes against
// the baseline.
#include "tcFeatureRefinement.h"
#include "tcTestUtilities.h"

#include "tc/common/array_names.h"

#include <vtkCellData.h>
#include <vtkDataArray.h>
#include <vtkNew.h>
#include <vtkPointData.h>
#include <vtkPolyData.h>
#include <vtkRenderWindow.h>
#include <vtkRenderer.h>

int TestFeatureRefinement(int argc, char* argv[])
{
  tctest::Checker check;
  const std::string data = tctest::Arg(argc, argv, "-D");
  vtkSmartPointer<vtkRenderer> renderers[2];
  const char* meshes[2] = { "/meshes/fandisk.off", "/meshes/bunny_npm.off" };
  for (int m = 0; m < 2; ++m)
  {
    vtkSmartPointer<vtkPolyData> mesh = tctest::ReadPrepared(data + meshes[m]);
    if (!TC_CHECK(check, mesh != nullptr))
    {
      return 1;
    }
    vtkSmartPointer<tcFeatureRefinement> refinement = tctest::FeatureStages(mesh);
    vtkPolyData* out = refinement->GetOutput();
    vtkPolyData* lines = refinement->GetOutput(1);
    vtkPolyData* corners = refinement->GetOutput(2);
    vtkDataArray* feature = out->GetPointData()->GetArray(tc::kFeatureVertex);
    vtkDataArray* corner = out->GetPointData()->GetArray(tc::kCornerVertex);
    vtkDataArray* lineIds = lines->GetPointData()->GetArray(tc::kInputPointId);
    if (!TC_CHECK(check, feature && corner && lineIds))
    {
      return 1;
    }
    TC_CHECK(check, out->GetCellData()->GetArray(tc::kClusterId) != nullptr);
    TC_CHECK(check, lines->GetCellData()->GetArray(tc::kMeanAbsCurvature) != nullptr);
    if (m == 0)
    {
      TC_CHECK(check, lines->GetNumberOfLines() >= 10); // fandisk's creases
    }
    for (vtkIdType p = 0; p < lineIds->GetNumberOfTuples(); ++p)
    {
      TC_CHECK(check, feature->GetTuple1(static_cast<vtkIdType>(lineIds->GetTuple1(p))) == 1);
    }
    vtkIdType flagged = 0;
    for (vtkIdType v = 0; v < corner->GetNumberOfTuples(); ++v)
    {
      flagged += corner->GetTuple1(v) != 0.0;
    }
    TC_CHECK(check, flagged == corners->GetNumberOfPoints());

    const double viewport[4] = { 0.5 * m, 0.0, 0.5 * (m + 1), 1.0 };
    auto surface = vtkSmartPointer<vtkPolyData>::New();
    surface->ShallowCopy(out);
    auto lineCopy = vtkSmartPointer<vtkPolyData>::New();
    lineCopy->ShallowCopy(lines);
    auto cornerCopy = vtkSmartPointer<vtkPolyData>::New();
    cornerCopy->ShallowCopy(corners);
    renderers[m] = tctest::LabelRenderer(surface, tc::kClusterId, lineCopy, cornerCopy, viewport);
  }
  vtkSmartPointer<vtkRenderWindow> window = tctest::SideBySide(renderers[0], renderers[1]);
  TC_CHECK(check, tctest::MatchesBaseline(argc, argv, window));
  return check.failures == 0 ? 0 : 1;
}
