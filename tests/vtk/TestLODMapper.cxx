// SPDX-License-Identifier: BSD-3-Clause
// tcLODMapper on the atlas of the bundled bunny:
// 1. exactness: for random levels per chart with large gaps, every vertex the shaders draw (read
//    back by transform feedback) is the vertex tc::rebuildMesh builds for the same levels;
// 2. cracks: a chart drawn 4 levels coarser than its three neighbours, seen face on, leaves no
//    background pixel inside the silhouette of the full-resolution drawing (2 pixels in from
//    its rim); with stitching off it does (the check can fail);
// 3. view dependence: of three instances at growing distances, the far ones draw coarser; a
//    frozen selection stays put while the camera moves;
// then the picture: the three distances coloured by level, the stitching close-up, a crowd.
#include "tcGeometryImages.h"
#include "tcLODMapper.h"
#include "tcTestUtilities.h"

#include "tcAtlasConversion.h"

#include "tc/common/array_names.h"
#include "tc/gim/geometry_image_mesh.h"

#include <vtkActor.h>
#include <vtkCamera.h>
#include <vtkDoubleArray.h>
#include <vtkFloatArray.h>
#include <vtkIntArray.h>
#include <vtkMinimalStandardRandomSequence.h>
#include <vtkMultiBlockDataSet.h>
#include <vtkNew.h>
#include <vtkPolyData.h>
#include <vtkProperty.h>
#include <vtkRenderWindow.h>
#include <vtkRenderer.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <vector>

namespace
{
/// Pixels of the renderer's viewport that something covers (depth below the far plane), and
/// its width in pixels.
std::vector<bool> Covered(vtkRenderWindow* window, vtkRenderer* renderer, int* width = nullptr)
{
  window->Render();
  int* size = window->GetSize();
  double* vp = renderer->GetViewport();
  const int x0 = static_cast<int>(vp[0] * size[0]), y0 = static_cast<int>(vp[1] * size[1]);
  const int x1 = static_cast<int>(vp[2] * size[0]) - 1, y1 = static_cast<int>(vp[3] * size[1]) - 1;
  std::vector<float> depth(static_cast<size_t>((x1 - x0 + 1) * (y1 - y0 + 1)));
  window->GetZbufferData(x0, y0, x1, y1, depth.data());
  std::vector<bool> covered(depth.size());
  for (size_t p = 0; p < depth.size(); ++p)
  {
    covered[p] = depth[p] < 1.0f;
  }
  if (width)
  {
    *width = x1 - x0 + 1;
  }
  return covered;
}

/// The inside of a silhouette: covered pixels whose 5 x 5 neighbourhood is all covered. At the
/// rim a coarser chart legitimately covers less (where a side bulged out beyond the chord that
/// now replaces it, the outline itself moves in); a crack is a gap inside the surface.
std::vector<bool> Inside(const std::vector<bool>& covered, int width)
{
  const int height = static_cast<int>(covered.size()) / width;
  std::vector<bool> inside(covered.size(), false);
  for (int y = 2; y + 2 < height; ++y)
  {
    for (int x = 2; x + 2 < width; ++x)
    {
      bool all = true;
      for (int dy = -2; dy <= 2 && all; ++dy)
      {
        for (int dx = -2; dx <= 2 && all; ++dx)
        {
          all = covered[static_cast<size_t>((y + dy) * width + x + dx)];
        }
      }
      inside[static_cast<size_t>(y * width + x)] = all;
    }
  }
  return inside;
}

/// Pixels inside `full` not covered in `drawn`.
long long Holes(const std::vector<bool>& full, const std::vector<bool>& drawn)
{
  long long holes = 0;
  for (size_t p = 0; p < full.size(); ++p)
  {
    holes += full[p] && !drawn[p];
  }
  return holes;
}

vtkNew<vtkDoubleArray> Translations(const std::vector<std::array<double, 3>>& offsets)
{
  vtkNew<vtkDoubleArray> matrices;
  matrices->SetNumberOfComponents(16);
  for (const auto& o : offsets)
  {
    const double m[16] = { 1, 0, 0, o[0], 0, 1, 0, o[1], 0, 0, 1, o[2], 0, 0, 0, 1 };
    matrices->InsertNextTuple(m);
  }
  return matrices;
}
} // namespace

int TestLODMapper(int argc, char* argv[])
{
  tctest::Checker check;
  const std::string data = tctest::Arg(argc, argv, "-D");
  vtkSmartPointer<vtkPolyData> mesh = tctest::ReadPrepared(data + "/meshes/bunny_npm.off");
  if (!TC_CHECK(check, mesh != nullptr))
  {
    return 1;
  }
  // Eight samples per input point: charts reach levels 4 to 6, so that 4-level gaps exist.
  vtkSmartPointer<tcGeometryImages> images =
    tctest::AtlasStages(mesh, 8 * mesh->GetNumberOfPoints());
  images->Update();
  tc::Atlas atlas;
  std::string error;
  if (!TC_CHECK(check, tcvtk::ToAtlas(images->GetOutput(), atlas, error)))
  {
    std::printf("%s\n", error.c_str());
    return 1;
  }
  const vtkIdType nc = static_cast<vtkIdType>(atlas.charts.size());
  const double diagonal = atlas.inputDiagonal;

  vtkNew<tcLODMapper> mapper;
  mapper->SetInputConnection(images->GetOutputPort());
  vtkNew<vtkActor> actor;
  actor->SetMapper(mapper);
  vtkNew<vtkRenderer> renderer;
  renderer->AddActor(actor);
  renderer->SetBackground(1.0, 0.0, 1.0);
  vtkNew<vtkRenderWindow> window;
  window->SetOffScreenRendering(1);
  window->SetSize(400, 400);
  window->AddRenderer(renderer);
  renderer->ResetCamera();

  // 1. Exactness.
  vtkNew<vtkMinimalStandardRandomSequence> random;
  random->SetSeed(11);
  mapper->CaptureVerticesOn();
  for (int trial = 0; trial < 4; ++trial)
  {
    vtkNew<vtkIntArray> levels;
    std::vector<int32_t> chosen;
    for (vtkIdType c = 0; c < nc; ++c)
    {
      random->Next();
      const int finest = atlas.charts[static_cast<size_t>(c)].maxLevel;
      // Half the charts at their extremes, so that neighbours differ by up to 6 levels.
      const double u = random->GetValue();
      const int level = trial == 0 ? finest
        : u < 0.25                 ? 0
        : u < 0.5                  ? finest
                                   : static_cast<int>(u * (finest + 1) * 1.999) % (finest + 1);
      chosen.push_back(level);
      levels->InsertNextValue(level);
    }
    mapper->SetChartLevels(levels);
    window->Render();
    const tc::RebuiltMesh rebuilt = tc::rebuildMesh(atlas, chosen);
    vtkFloatArray* captured = mapper->GetCapturedVertices();
    long long expectedVertices = 0;
    for (int32_t n : chosen)
    {
      expectedVertices += 3LL << (2 * n);
    }
    double worst = 0.0;
    long long mismatched = 0, drawn = 0;
    for (vtkIdType v = 0; v < captured->GetNumberOfTuples(); ++v)
    {
      const float* r = captured->GetPointer(8 * v);
      if (r[3] == -1.0f)
      {
        // A copy past the end of its level's charts in the last instance of a draw: collapsed.
        mismatched += r[0] != 0.0f || r[1] != 0.0f || r[2] != 0.0f;
        continue;
      }
      ++drawn;
      const int c = static_cast<int>(r[3]), i = static_cast<int>(r[4]), j = static_cast<int>(r[5]);
      const int n = static_cast<int>(r[6]);
      if (c < 0 || c >= nc || n != chosen[static_cast<size_t>(c)])
      {
        ++mismatched;
        continue;
      }
      const int32_t point =
        rebuilt.chartVertexPoint[static_cast<size_t>(rebuilt.chartVertexOffsets[static_cast<size_t>(c)] +
          tc::gridVertexIndex(n, i, j))];
      const std::array<double, 3> p = rebuilt.mesh.point(point);
      const double d = std::sqrt((p[0] - r[0]) * (p[0] - r[0]) + (p[1] - r[1]) * (p[1] - r[1]) +
        (p[2] - r[2]) * (p[2] - r[2]));
      worst = std::max(worst, d / diagonal);
    }
    std::printf("exactness %d: %lld vertices drawn (expected %lld), largest distance to "
                "tcGeometryImageMesh %.3g of the diagonal, %lld on a wrong chart or level\n",
      trial, drawn, expectedVertices, worst, mismatched);
    TC_CHECK(check, drawn == expectedVertices);
    TC_CHECK(check, mismatched == 0);
    TC_CHECK(check, worst <= 1e-6);
  }
  mapper->CaptureVerticesOff();

  // 2. Cracks: a chart at level (finest - 4) or lower, its neighbours at their finest, nothing
  //    else drawn, the chart seen face on.
  long long holesStitched = -1, holesUnstitched = -1;
  vtkIdType closeUpChart = -1;
  std::vector<int32_t> closeUp;
  for (vtkIdType c = 0; c < nc && closeUpChart < 0; ++c)
  {
    const tc::AtlasChart& chart = atlas.charts[static_cast<size_t>(c)];
    int coarse = 99;
    for (int k = 0; k < 3; ++k)
    {
      const int nb = chart.neighborChart[static_cast<size_t>(k)];
      coarse = nb < 0 ? -1 : std::min(coarse, atlas.charts[static_cast<size_t>(nb)].maxLevel - 4);
    }
    if (coarse < 0)
    {
      continue;
    }
    std::vector<int32_t> full(static_cast<size_t>(nc), -1);
    full[static_cast<size_t>(c)] = chart.maxLevel;
    for (int k = 0; k < 3; ++k)
    {
      const int nb = chart.neighborChart[static_cast<size_t>(k)];
      full[static_cast<size_t>(nb)] = atlas.charts[static_cast<size_t>(nb)].maxLevel;
    }
    // Face on: along the normal of the plane through the chart's three corners.
    const float* s[3] = { tc::atlasSample(atlas, static_cast<int32_t>(c), 0, 0, 0, 0),
      tc::atlasSample(atlas, static_cast<int32_t>(c), 0, 0, 1, 0),
      tc::atlasSample(atlas, static_cast<int32_t>(c), 0, 0, 0, 1) };
    double e1[3], e2[3], normal[3], center[3];
    for (int x = 0; x < 3; ++x)
    {
      e1[x] = s[1][x] - s[0][x];
      e2[x] = s[2][x] - s[0][x];
      center[x] = (s[0][x] + s[1][x] + s[2][x]) / 3.0;
    }
    vtkMath::Cross(e1, e2, normal);
    vtkMath::Normalize(normal);
    vtkCamera* camera = renderer->GetActiveCamera();
    camera->SetFocalPoint(center);
    camera->SetPosition(center[0] + normal[0], center[1] + normal[1], center[2] + normal[2]);
    camera->SetViewUp(e1);
    vtkNew<vtkIntArray> levels;
    levels->SetArray(full.data(), nc, 1);
    mapper->SetChartLevels(levels);
    // Frame the four charts only: the bounds of their boxes.
    double box[6] = { 1e300, -1e300, 1e300, -1e300, 1e300, -1e300 };
    for (vtkIdType d = 0; d < nc; ++d)
    {
      if (full[static_cast<size_t>(d)] < 0)
      {
        continue;
      }
      const auto& b = atlas.charts[static_cast<size_t>(d)].box;
      for (int corner = 0; corner < 8; ++corner)
      {
        for (int x = 0; x < 3; ++x)
        {
          double v = b[static_cast<size_t>(x)];
          for (int k = 0; k < 3; ++k)
          {
            v += (corner & (1 << k)) ? b[static_cast<size_t>(3 + 3 * k + x)] - b[static_cast<size_t>(x)] : 0.0;
          }
          box[2 * x] = std::min(box[2 * x], v);
          box[2 * x + 1] = std::max(box[2 * x + 1], v);
        }
      }
    }
    renderer->ResetCamera(box);
    int width = 0;
    const std::vector<bool> fullCover = Covered(window, renderer, &width);
    const std::vector<bool> silhouette = Inside(fullCover, width);
    std::vector<int32_t> stitched = full;
    stitched[static_cast<size_t>(c)] = coarse;
    levels->SetArray(stitched.data(), nc, 1);
    mapper->SetChartLevels(levels);
    mapper->StitchingOff();
    const long long unstitched = Holes(silhouette, Covered(window, renderer));
    mapper->StitchingOn();
    const long long holes = Holes(silhouette, Covered(window, renderer));
    // The first chart whose cracks show without stitching is the close-up.
    if (unstitched > 0)
    {
      closeUpChart = c;
      closeUp = stitched;
      holesStitched = holes;
      holesUnstitched = unstitched;
      std::printf("cracks: chart %lld at level %d, neighbours at %d..: %lld background pixels "
                  "inside the full-resolution silhouette (2 px in from its rim) stitched, %lld "
                  "unstitched\n",
        static_cast<long long>(c), coarse, coarse + 4, holes, unstitched);
    }
    levels->SetArray(nullptr, 0, 1);
  }
  TC_CHECK(check, closeUpChart >= 0);
  TC_CHECK(check, holesStitched == 0);
  TC_CHECK(check, holesUnstitched > 0);
  vtkNew<vtkCamera> closeUpCamera;
  closeUpCamera->DeepCopy(renderer->GetActiveCamera());

  // 3. View dependence: three instances at about 3, 6 and 13 sizes from the camera; by eq. 7
  //    each doubling of the distance costs one level. The bias makes the near one about its
  //    finest in this small viewport (each chart covers less than 1/1000 of it).
  mapper->SetChartLevels(nullptr);
  double bounds[6];
  mapper->GetBounds(bounds);
  const double size = bounds[1] - bounds[0];
  const double center[3] = { 0.5 * (bounds[0] + bounds[1]), 0.5 * (bounds[2] + bounds[3]),
    0.5 * (bounds[4] + bounds[5]) };
  mapper->SetInstanceMatrices(Translations({ { -0.6 * size, -0.2 * size, 0 },
    { 0.6 * size, 0.3 * size, -3 * size }, { 4 * size, 2 * size, -10 * size } }));
  mapper->SetColorMode(tcLODMapper::ColorByLevel);
  mapper->SetErrorTarget(0.0); // the paper's area rule (eq. 7), not the default error target
  mapper->SetLODBias(4.0);
  vtkCamera* camera = renderer->GetActiveCamera();
  camera->SetFocalPoint(center[0] + 0.5 * size, center[1] + 0.25 * size, center[2] - 5 * size);
  camera->SetPosition(center[0], center[1], center[2] + 3.0 * size);
  camera->SetViewUp(0, 1, 0);
  camera->SetViewAngle(60);
  renderer->ResetCameraClippingRange();
  window->Render();
  vtkNew<vtkIntArray> levels;
  mapper->GetLevels(levels);
  double mean[3] = { 0, 0, 0 };
  int drawn[3] = { 0, 0, 0 };
  for (vtkIdType c = 0; c < nc; ++c)
  {
    for (int i = 0; i < 3; ++i)
    {
      const int level = levels->GetTypedComponent(c, i);
      if (level >= 0)
      {
        mean[i] += level;
        ++drawn[i];
      }
    }
  }
  for (int i = 0; i < 3; ++i)
  {
    mean[i] /= std::max(1, drawn[i]);
  }
  std::printf("three distances: mean level %.2f, %.2f, %.2f (%d, %d, %d charts drawn); %lld "
              "triangles; selection %.3f ms\n",
    mean[0], mean[1], mean[2], drawn[0], drawn[1], drawn[2],
    static_cast<long long>(mapper->GetTrianglesDrawn()), 1e3 * mapper->GetSelectionSeconds());
  TC_CHECK(check, drawn[0] > 0 && drawn[1] > 0 && drawn[2] > 0);
  TC_CHECK(check, mean[0] > mean[1] + 0.5 && mean[1] > mean[2] + 0.5);
  // A frozen selection survives a camera move; released, it follows the camera.
  mapper->FreezeLODOn();
  const vtkIdType frozen = mapper->GetTrianglesDrawn();
  camera->Dolly(0.25);
  renderer->ResetCameraClippingRange();
  window->Render();
  TC_CHECK(check, mapper->GetTrianglesDrawn() == frozen);
  mapper->FreezeLODOff();
  window->Render();
  std::printf("frozen: %lld triangles; released after the camera moved 4 times as far: %lld\n",
    static_cast<long long>(frozen), static_cast<long long>(mapper->GetTrianglesDrawn()));
  TC_CHECK(check, mapper->GetTrianglesDrawn() < frozen);
  camera->Dolly(4.0);
  renderer->ResetCameraClippingRange();

  // The picture: three distances by level | the close-up by chart | a 5 x 5 crowd by chart.
  renderer->SetViewport(0.0, 0.0, 1.0 / 3.0, 1.0);
  renderer->SetBackground(0.1, 0.1, 0.15);

  vtkNew<tcLODMapper> closeMapper;
  closeMapper->SetInputConnection(images->GetOutputPort());
  vtkNew<vtkIntArray> closeLevels;
  for (int32_t l : closeUp)
  {
    closeLevels->InsertNextValue(l);
  }
  closeMapper->SetChartLevels(closeLevels);
  closeMapper->SetColorMode(tcLODMapper::ColorByChart);
  vtkNew<vtkActor> closeActor;
  closeActor->SetMapper(closeMapper);
  closeActor->GetProperty()->SetRepresentationToWireframe();
  vtkNew<vtkRenderer> closeRenderer;
  closeRenderer->SetViewport(1.0 / 3.0, 0.0, 2.0 / 3.0, 1.0);
  closeRenderer->SetBackground(1.0, 1.0, 1.0);
  closeRenderer->AddActor(closeActor);
  closeRenderer->SetActiveCamera(closeUpCamera);

  vtkNew<tcLODMapper> crowdMapper;
  crowdMapper->SetInputConnection(images->GetOutputPort());
  std::vector<std::array<double, 3>> grid;
  for (int a = 0; a < 5; ++a)
  {
    for (int b = 0; b < 5; ++b)
    {
      grid.push_back({ 1.3 * size * a, 0.0, -1.3 * size * b });
    }
  }
  crowdMapper->SetInstanceMatrices(Translations(grid));
  crowdMapper->SetColorMode(tcLODMapper::ColorByLevel);
  crowdMapper->SetErrorTarget(1.0);
  vtkNew<vtkActor> crowdActor;
  crowdActor->SetMapper(crowdMapper);
  vtkNew<vtkRenderer> crowdRenderer;
  crowdRenderer->SetViewport(2.0 / 3.0, 0.0, 1.0, 1.0);
  crowdRenderer->SetBackground(0.15, 0.1, 0.1);
  crowdRenderer->AddActor(crowdActor);
  crowdRenderer->GetActiveCamera()->SetPosition(-1.0, 1.0, 1.5);
  crowdRenderer->ResetCamera();
  crowdRenderer->GetActiveCamera()->Zoom(1.3);

  window->SetSize(900, 300);
  window->AddRenderer(closeRenderer);
  window->AddRenderer(crowdRenderer);
  window->Render();
  std::printf("crowd: 25 instances, %lld charts drawn, %lld triangles\n",
    static_cast<long long>(crowdMapper->GetChartsDrawn()),
    static_cast<long long>(crowdMapper->GetTrianglesDrawn()));
  TC_CHECK(check, crowdMapper->GetChartsDrawn() > nc);
  TC_CHECK(check, tctest::MatchesBaseline(argc, argv, window));
  return check.failures == 0 ? 0 : 1;
}
