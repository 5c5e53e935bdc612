// SPDX-License-Identifier: BSD-3-Clause
// tcBaseComplex after the feature stages on the bundled bunny and fandisk: the base complex is
// a closed manifold over input vertices with the input's Euler characteristic, every input
// vertex has a base face and barycentrics that sum to 1, corners are base vertices; then the
// base edges over the parameterized meshes against the baseline.
#include "tcBaseComplex.h"
#include "tcFeatureRefinement.h"
#include "tcTestUtilities.h"

#include "tc/common/array_names.h"

#include <vtkCellData.h>
#include <vtkDataArray.h>
#include <vtkExtractEdges.h>
#include <vtkFeatureEdges.h>
#include <vtkNew.h>
#include <vtkPointData.h>
#include <vtkPolyData.h>
#include <vtkRenderWindow.h>
#include <vtkRenderer.h>

#include <cmath>
#include <set>

int TestBaseComplex(int argc, char* argv[])
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
    base->Update();
    vtkPolyData* complex = base->GetOutput(0);
    vtkPolyData* parameterized = base->GetOutput(1);

    TC_CHECK(check, complex->GetNumberOfPolys() >= 4);
    TC_CHECK(check, complex->GetNumberOfPolys() < mesh->GetNumberOfPolys() / 4);
    TC_CHECK(check, tctest::OpenOrNonManifoldEdges(complex) == 0);
    TC_CHECK(check, tctest::Euler(complex) == tctest::Euler(mesh));

    vtkDataArray* inputIds = complex->GetPointData()->GetArray(tc::kInputPointId);
    vtkDataArray* faces = parameterized->GetPointData()->GetArray(tc::kBaseFaceId);
    vtkDataArray* barycentric = parameterized->GetPointData()->GetArray(tc::kBaseBarycentric);
    vtkDataArray* corner = refinement->GetOutput()->GetPointData()->GetArray(tc::kCornerVertex);
    if (!TC_CHECK(check, inputIds && faces && barycentric && corner))
    {
      return 1;
    }
    int bad = 0;
    for (vtkIdType v = 0; v < parameterized->GetNumberOfPoints(); ++v)
    {
      const double f = faces->GetTuple1(v);
      const double* b = barycentric->GetTuple3(v);
      bad += f < 0 || f >= complex->GetNumberOfPolys() ||
        std::abs(b[0] + b[1] + b[2] - 1.0) > 1e-9 || b[0] < -1e-9 || b[1] < -1e-9 || b[2] < -1e-9;
    }
    TC_CHECK(check, bad == 0);
    std::set<vtkIdType> baseVertices;
    for (vtkIdType b = 0; b < inputIds->GetNumberOfTuples(); ++b)
    {
      baseVertices.insert(static_cast<vtkIdType>(inputIds->GetTuple1(b)));
    }
    int missingCorners = 0;
    for (vtkIdType v = 0; v < corner->GetNumberOfTuples(); ++v)
    {
      missingCorners += corner->GetTuple1(v) != 0.0 && baseVertices.count(v) == 0;
    }
    TC_CHECK(check, missingCorners == 0);

    vtkNew<vtkExtractEdges> edges;
    edges->SetInputData(complex);
    edges->Update();
    auto surface = vtkSmartPointer<vtkPolyData>::New();
    surface->ShallowCopy(parameterized);
    auto lines = vtkSmartPointer<vtkPolyData>::New();
    lines->ShallowCopy(edges->GetOutput());
    const double viewport[4] = { 0.5 * m, 0.0, 0.5 * (m + 1), 1.0 };
    renderers[m] = tctest::LabelRenderer(surface, tc::kBaseFaceId, lines, nullptr, viewport);
  }
  vtkSmartPointer<vtkRenderWindow> window = tctest::SideBySide(renderers[0], renderers[1]);
  TC_CHECK(check, tctest::MatchesBaseline(argc, argv, window));
  return check.failures == 0 ? 0 : 1;
}
