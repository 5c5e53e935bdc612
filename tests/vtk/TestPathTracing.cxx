// SPDX-License-Identifier: BSD-3-Clause
// tcPathTracing after the base complex on the bundled bunny and fandisk: one patch per base
// face, the split mesh is a closed manifold with the input's Euler characteristic and area, every
// path runs between two base vertices; then the patches and paths against the baseline.
#include "tcBaseComplex.h"
#include "tcFeatureRefinement.h"
#include "tcPathTracing.h"
#include "tcTestUtilities.h"

#include "tc/common/array_names.h"

#include <vtkCellArray.h>
#include <vtkCellData.h>
#include <vtkDataArray.h>
#include <vtkExtractEdges.h>
#include <vtkFeatureEdges.h>
#include <vtkFieldData.h>
#include <vtkMassProperties.h>
#include <vtkNew.h>
#include <vtkPointData.h>
#include <vtkPolyData.h>
#include <vtkRenderWindow.h>
#include <vtkRenderer.h>

#include <cmath>
#include <set>

namespace
{
double Area(vtkPolyData* mesh)
{
  vtkNew<vtkMassProperties> mass;
  mass->SetInputData(mesh);
  mass->Update();
  return mass->GetSurfaceArea();
}
}

int TestPathTracing(int argc, char* argv[])
{
  tctest::Checker check;
  const std::string data = tctest::Arg(argc, argv, "-D");
  vtkSmartPointer<vtkRenderer> renderers[2];
  const char* meshes[2] = { "/meshes/bunny_npm.off", "/meshes/fandisk.off" };
  for (int m = 0; m < 2; ++m)
  {
    vtkSmartPointer<vtkPolyData> mesh = tctest::ReadPrepared(data + meshes[m]);
    if (!TC_CHECK(check, mesh != nullptr))
    {
      return 1;
    }
    vtkSmartPointer<tcFeatureRefinement> refinement = tctest::FeatureStages(mesh);
    vtkNew<tcBaseComplex> base;
    base->SetInputConnection(refinement->GetOutputPort());
    vtkNew<tcPathTracing> tracing;
    tracing->SetInputConnection(base->GetOutputPort(1));
    tracing->Update();
    vtkPolyData* patches = tracing->GetOutput(0);
    vtkPolyData* paths = tracing->GetOutput(1);
    const vtkIdType baseFaces = base->GetOutput(0)->GetNumberOfPolys();
    const vtkIdType steiner = patches->GetNumberOfPoints() - mesh->GetNumberOfPoints();
    std::printf("%s: %lld base faces, %lld paths, %lld Steiner points, %lld pieces\n", meshes[m],
      static_cast<long long>(baseFaces), static_cast<long long>(paths->GetNumberOfLines()),
      static_cast<long long>(steiner), static_cast<long long>(patches->GetNumberOfPolys()));

    // One patch per base face; 3 F / 2 paths; the split mesh closed, same Euler and area.
    vtkDataArray* patchId = patches->GetCellData()->GetArray(tc::kPatchId);
    if (!TC_CHECK(check, patchId != nullptr))
    {
      return 1;
    }
    std::set<int> ids;
    for (vtkIdType c = 0; c < patchId->GetNumberOfTuples(); ++c)
    {
      ids.insert(static_cast<int>(patchId->GetTuple1(c)));
    }
    TC_CHECK(check, static_cast<vtkIdType>(ids.size()) == baseFaces);
    TC_CHECK(check, paths->GetNumberOfLines() == 3 * baseFaces / 2);
    TC_CHECK(check, steiner >= 0);
    TC_CHECK(check, tctest::OpenOrNonManifoldEdges(patches) == 0);
    TC_CHECK(check, tctest::Euler(patches) == tctest::Euler(mesh));
    TC_CHECK(check, std::abs(Area(patches) - Area(mesh)) <= 1e-9 * Area(mesh));

    // Every path starts and ends at a base vertex (an input point that is a base vertex).
    vtkDataArray* baseVertices = patches->GetFieldData()->GetArray(tc::kBaseVertexIds);
    vtkDataArray* pathIds = paths->GetPointData()->GetArray(tc::kInputPointId);
    if (!TC_CHECK(check, baseVertices && pathIds))
    {
      return 1;
    }
    std::set<vtkIdType> corners;
    for (vtkIdType b = 0; b < baseVertices->GetNumberOfTuples(); ++b)
    {
      corners.insert(static_cast<vtkIdType>(baseVertices->GetTuple1(b)));
    }
    int badEnds = 0;
    vtkCellArray* lines = paths->GetLines();
    vtkIdType n = 0;
    const vtkIdType* pts = nullptr;
    for (lines->InitTraversal(); lines->GetNextCell(n, pts);)
    {
      badEnds += corners.count(static_cast<vtkIdType>(pathIds->GetTuple1(pts[0]))) == 0;
      badEnds += corners.count(static_cast<vtkIdType>(pathIds->GetTuple1(pts[n - 1]))) == 0;
    }
    TC_CHECK(check, badEnds == 0);

    const double viewport[4] = { 0.5 * m, 0.0, 0.5 * (m + 1), 1.0 };
    auto surface = vtkSmartPointer<vtkPolyData>::New();
    surface->ShallowCopy(patches);
    auto lineCopy = vtkSmartPointer<vtkPolyData>::New();
    lineCopy->ShallowCopy(paths);
    renderers[m] = tctest::LabelRenderer(surface, tc::kPatchId, lineCopy, nullptr, viewport);
  }
  vtkSmartPointer<vtkRenderWindow> window = tctest::SideBySide(renderers[0], renderers[1]);
  TC_CHECK(check, tctest::MatchesBaseline(argc, argv, window));
  return check.failures == 0 ? 0 : 1;
}
