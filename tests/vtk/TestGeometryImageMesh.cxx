// SPDX-License-Identifier: BSD-3-Clause
// tcGeometryImages -> tcGeometryImageMesh on the bundled bunny: every rebuild (uniform levels
// and random levels per chart, neighbours far apart) is a closed manifold with the input's Euler
// characteristic; the error against the input (tcSurfaceDistance) falls as the level rises;
// then the rebuilt meshes at the finest level and at level 2 against the baseline.
#include "tcBaseComplex.h"
#include "tcFeatureRefinement.h"
#include "tcGeometryImageMesh.h"
#include "tcGeometryImages.h"
#include "tcPathTracing.h"
#include "tcSurfaceDistance.h"
#include "tcTestUtilities.h"

#include "tc/common/array_names.h"

#include <vtkCellData.h>
#include <vtkDataArray.h>
#include <vtkExtractEdges.h>
#include <vtkFeatureEdges.h>
#include <vtkIntArray.h>
#include <vtkMinimalStandardRandomSequence.h>
#include <vtkMultiBlockDataSet.h>
#include <vtkNew.h>
#include <vtkPolyData.h>
#include <vtkRenderWindow.h>
#include <vtkRenderer.h>
#include <vtkTable.h>

int TestGeometryImageMesh(int argc, char* argv[])
{
  tctest::Checker check;
  const std::string data = tctest::Arg(argc, argv, "-D");
  vtkSmartPointer<vtkPolyData> mesh = tctest::ReadPrepared(data + "/meshes/bunny_npm.off");
  if (!TC_CHECK(check, mesh != nullptr))
  {
    return 1;
  }
  // Four samples per input point: the bundled bunny is coarse (1.9K points), and its charts
  // need that many to follow it within 1% at their finest level.
  vtkSmartPointer<tcGeometryImages> images =
    tctest::AtlasStages(mesh, 4 * mesh->GetNumberOfPoints());
  auto* charts = vtkTable::SafeDownCast(images->GetOutput()->GetBlock(0));
  if (!TC_CHECK(check, charts != nullptr && charts->GetNumberOfRows() > 0))
  {
    return 1;
  }
  const vtkIdType nc = charts->GetNumberOfRows();
  vtkDataArray* maxLevels = vtkArrayDownCast<vtkDataArray>(charts->GetColumnByName(tc::kMaxLevel));
  int finest = 0;
  for (vtkIdType c = 0; c < nc; ++c)
  {
    finest = std::max(finest, static_cast<int>(maxLevels->GetTuple1(c)));
  }

  // Uniform levels: closed, same Euler characteristic, error falling with the level.
  vtkNew<tcGeometryImageMesh> rebuild;
  rebuild->SetInputConnection(images->GetOutputPort());
  vtkNew<tcSurfaceDistance> distance;
  distance->SetInputConnection(rebuild->GetOutputPort());
  distance->SetInputData(1, mesh);
  double previous = 1e300;
  double rms = 0.0;
  for (int level = 1; level <= finest; ++level)
  {
    rebuild->SetLevel(level);
    distance->Update();
    vtkPolyData* out = rebuild->GetOutput();
    const double relative = distance->GetHausdorff() / distance->GetDiagonal();
    std::printf("level %d: %lld points, %lld triangles, Hausdorff %.4f%%, RMS %.4f%% of the "
                "diagonal\n",
      level, static_cast<long long>(out->GetNumberOfPoints()),
      static_cast<long long>(out->GetNumberOfPolys()), 100.0 * relative,
      100.0 * distance->GetRmsDistance() / distance->GetDiagonal());
    TC_CHECK(check, tctest::OpenOrNonManifoldEdges(out) == 0);
    TC_CHECK(check, tctest::Euler(out) == tctest::Euler(mesh));
    TC_CHECK(check, relative <= previous * 1.05);
    previous = relative;
    rms = distance->GetRmsDistance() / distance->GetDiagonal();
  }
  // The largest error sits on the ears (measured: input points near the top of the bunny are the
  // farthest from the rebuilt surface); the mean error is far below it.
  TC_CHECK(check, previous < 0.015);
  TC_CHECK(check, rms < 0.001);

  // Random levels per chart: still closed, with the input's Euler characteristic.
  vtkNew<vtkMinimalStandardRandomSequence> random;
  random->SetSeed(7);
  for (int trial = 0; trial < 10; ++trial)
  {
    vtkNew<vtkIntArray> levels;
    for (vtkIdType c = 0; c < nc; ++c)
    {
      random->Next();
      levels->InsertNextValue(static_cast<int>(random->GetValue() * (finest + 1)));
    }
    rebuild->SetChartLevels(levels);
    rebuild->Update();
    TC_CHECK(check, tctest::OpenOrNonManifoldEdges(rebuild->GetOutput()) == 0);
    TC_CHECK(check, tctest::Euler(rebuild->GetOutput()) == tctest::Euler(mesh));
  }
  rebuild->SetChartLevels(nullptr);

  // Picture: the finest level and level 2, coloured by chart.
  vtkSmartPointer<vtkRenderer> renderers[2];
  const int shown[2] = { -1, 2 };
  for (int i = 0; i < 2; ++i)
  {
    rebuild->SetLevel(shown[i]);
    rebuild->Update();
    auto surface = vtkSmartPointer<vtkPolyData>::New();
    surface->DeepCopy(rebuild->GetOutput());
    const double viewport[4] = { 0.5 * i, 0.0, 0.5 * (i + 1), 1.0 };
    renderers[i] = tctest::LabelRenderer(surface, tc::kChartId, nullptr, nullptr, viewport);
  }
  vtkSmartPointer<vtkRenderWindow> window = tctest::SideBySide(renderers[0], renderers[1]);
  TC_CHECK(check, tctest::MatchesBaseline(argc, argv, window));
  return check.failures == 0 ? 0 : 1;
}
