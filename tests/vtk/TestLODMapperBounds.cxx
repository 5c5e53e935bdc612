// SPDX-License-Identifier: BSD-3-Clause
// tcLODMapper::GetBounds frames an LOD actor as vtkPolyDataMapper frames a mesh, in a 600 x 600
// view reset by ResetCamera from three directions:
// 1. framing: the bounds are those vtkPolyDataMapper finds for the atlas's finest surface
//    (tc::rebuildMesh), and the two silhouettes at that level agree (intersection over union
//    >= 0.98); framed by the charts' oriented boxes, as the bounds were before, they do not;
// 2. the bundled bunny itself, drawn by vtkPolyDataMapper, against the LOD actor of its atlas
//    built at the defaults and drawn at the mapper's defaults (its 1-pixel error target): the
//    silhouettes agree (intersection over union >= 0.98), and do better than framed by the
//    boxes; the figures at a 1-pixel target and at the finest level are printed beside them.
#include "tcGeometryImages.h"
#include "tcLODMapper.h"
#include "tcTestUtilities.h"

#include "tcAtlasConversion.h"

#include "tc/gim/atlas.h"
#include "tc/gim/geometry_image_mesh.h"

#include "tcMeshConversion.h"

#include <vtkActor.h>
#include <vtkCamera.h>
#include <vtkMultiBlockDataSet.h>
#include <vtkNew.h>
#include <vtkPolyData.h>
#include <vtkPolyDataMapper.h>
#include <vtkRenderWindow.h>
#include <vtkRenderer.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <vector>

namespace
{
constexpr int kSize = 600;

/// The pixels the renderer's one actor covers (depth below the far plane) after ResetCamera
/// (or ResetCamera(bounds)) from the camera's present direction.
std::vector<bool> Silhouette(
  vtkRenderWindow* window, vtkRenderer* renderer, vtkActor* actor, const double* bounds = nullptr)
{
  renderer->RemoveAllViewProps();
  renderer->AddActor(actor);
  if (bounds)
  {
    renderer->ResetCamera(bounds);
  }
  else
  {
    renderer->ResetCamera();
  }
  window->Render();
  std::vector<float> depth(static_cast<size_t>(kSize) * kSize);
  window->GetZbufferData(0, 0, kSize - 1, kSize - 1, depth.data());
  std::vector<bool> covered(depth.size());
  std::transform(depth.begin(), depth.end(), covered.begin(), [](float z) { return z < 1.0f; });
  return covered;
}

double IntersectionOverUnion(const std::vector<bool>& a, const std::vector<bool>& b)
{
  long long both = 0, either = 0;
  for (size_t p = 0; p < a.size(); ++p)
  {
    both += a[p] && b[p];
    either += a[p] || b[p];
  }
  return either > 0 ? static_cast<double>(both) / static_cast<double>(either) : 0.0;
}

/// The union of the charts' oriented boxes (what GetBounds returned before it was exact).
std::array<double, 6> BoxBounds(const tc::Atlas& atlas)
{
  std::array<double, 6> box{ 1e300, -1e300, 1e300, -1e300, 1e300, -1e300 };
  for (const tc::AtlasChart& chart : atlas.charts)
  {
    for (int corner = 0; corner < 8; ++corner)
    {
      for (size_t x = 0; x < 3; ++x)
      {
        double v = chart.box[x];
        for (size_t k = 0; k < 3; ++k)
        {
          v += (corner & (1 << k)) ? chart.box[3 + 3 * k + x] - chart.box[x] : 0.0;
        }
        box[2 * x] = std::min(box[2 * x], v);
        box[2 * x + 1] = std::max(box[2 * x + 1], v);
      }
    }
  }
  return box;
}
/// Camera directions (position, view up) of the three views.
const double kDirections[3][6] = { { 0, 0, 1, 0, 1, 0 }, { 1, 0, 0, 0, 1, 0 },
  { 0, 1, 0, 0, 0, -1 } };
const char* kViews[3] = { "front", "side", "top" };

void LookFrom(vtkRenderer* renderer, int view)
{
  vtkCamera* camera = renderer->GetActiveCamera();
  camera->SetFocalPoint(0, 0, 0);
  camera->SetPosition(kDirections[view][0], kDirections[view][1], kDirections[view][2]);
  camera->SetViewUp(kDirections[view][3], kDirections[view][4], kDirections[view][5]);
}

/// An actor drawing `mesh` with vtkPolyDataMapper.
vtkSmartPointer<vtkActor> PlainActor(vtkPolyData* mesh)
{
  vtkNew<vtkPolyDataMapper> mapper;
  mapper->SetInputData(mesh);
  auto actor = vtkSmartPointer<vtkActor>::New();
  actor->SetMapper(mapper);
  return actor;
}

/// 1. The LOD actor at its finest level against vtkPolyDataMapper on the finest surface.
bool CheckFraming(vtkRenderWindow* window, vtkRenderer* renderer, const tc::Atlas& atlas,
  tcLODMapper* lod, vtkActor* lodActor)
{
  vtkNew<vtkPolyData> finest;
  tcvtk::FromTriMesh(tc::rebuildMesh(atlas, 15).mesh, finest);
  vtkSmartPointer<vtkActor> finestActor = PlainActor(finest);
  double b[6];
  lod->GetBounds(b);
  const double* f = finest->GetBounds();
  double worst = 0.0;
  for (int k = 0; k < 6; ++k)
  {
    worst = std::max(worst, std::abs(b[k] - f[k]));
  }
  std::printf("bounds of the LOD actor and of its finest surface differ by %.3g at most\n", worst);
  bool ok = worst <= 1e-6 * finest->GetLength();
  const std::array<double, 6> boxes = BoxBounds(atlas);
  lod->SetFixedLevel(15);
  for (int view = 0; view < 3; ++view)
  {
    LookFrom(renderer, view);
    const std::vector<bool> reference = Silhouette(window, renderer, finestActor);
    const double iou = IntersectionOverUnion(reference, Silhouette(window, renderer, lodActor));
    const double boxed =
      IntersectionOverUnion(reference, Silhouette(window, renderer, lodActor, boxes.data()));
    std::printf("%s, finest surface: intersection over union %.4f (framed by the charts' boxes "
                "%.4f)\n",
      kViews[view], iou, boxed);
    ok = ok && iou >= 0.98 && boxed < 0.98;
  }
  lod->SetFixedLevel(-1);
  return ok;
}

/// 2. The input bunny against the LOD actor at its defaults, at 1 pixel and at its finest.
bool CheckAgainstTheInput(vtkRenderWindow* window, vtkRenderer* renderer, vtkPolyData* mesh,
  const tc::Atlas& atlas, tcLODMapper* lod, vtkActor* lodActor)
{
  double b[6];
  lod->GetBounds(b);
  const double* m = mesh->GetBounds();
  std::printf("bounds: LOD x %.4f .. %.4f, y %.4f .. %.4f, z %.4f .. %.4f; bunny x %.4f .. "
              "%.4f, y %.4f .. %.4f, z %.4f .. %.4f\n",
    b[0], b[1], b[2], b[3], b[4], b[5], m[0], m[1], m[2], m[3], m[4], m[5]);
  vtkSmartPointer<vtkActor> meshActor = PlainActor(mesh);
  const std::array<double, 6> boxes = BoxBounds(atlas);
  bool ok = true;
  for (int view = 0; view < 3; ++view)
  {
    LookFrom(renderer, view);
    const std::vector<bool> reference = Silhouette(window, renderer, meshActor);
    const double defaults =
      IntersectionOverUnion(reference, Silhouette(window, renderer, lodActor));
    const long long triangles = lod->GetTrianglesDrawn();
    const double boxedDefaults =
      IntersectionOverUnion(reference, Silhouette(window, renderer, lodActor, boxes.data()));
    lod->SetErrorTarget(1.0);
    const double onePixel =
      IntersectionOverUnion(reference, Silhouette(window, renderer, lodActor));
    lod->SetErrorTarget(tc::LodOptions{}.errorPixels);
    lod->SetFixedLevel(15);
    const double finest = IntersectionOverUnion(reference, Silhouette(window, renderer, lodActor));
    lod->SetFixedLevel(-1);
    std::printf("%s, bunny: intersection over union %.4f at the defaults (%lld triangles; framed "
                "by the boxes %.4f), %.4f at a 1-pixel error target, %.4f at the finest level\n",
      kViews[view], defaults, triangles, boxedDefaults, onePixel, finest);
    ok = ok && defaults >= 0.98 && defaults > boxedDefaults + 0.1;
  }
  return ok;
}
} // namespace

int TestLODMapperBounds(int argc, char* argv[])
{
  tctest::Checker check;
  vtkSmartPointer<vtkPolyData> mesh =
    tctest::ReadPrepared(tctest::Arg(argc, argv, "-D") + "/meshes/bunny_npm.off");
  if (!TC_CHECK(check, mesh != nullptr))
  {
    return 1;
  }
  vtkSmartPointer<tcGeometryImages> images = tctest::AtlasStages(mesh);
  tc::Atlas atlas;
  std::string error;
  if (!TC_CHECK(check, tcvtk::ToAtlas(images->GetOutput(), atlas, error)))
  {
    std::printf("%s\n", error.c_str());
    return 1;
  }
  vtkNew<tcLODMapper> lod; // the default settings, the default error target among them
  lod->SetInputConnection(images->GetOutputPort());
  vtkNew<vtkActor> lodActor;
  lodActor->SetMapper(lod);
  vtkNew<vtkRenderer> renderer;
  vtkNew<vtkRenderWindow> window;
  window->SetOffScreenRendering(1);
  window->SetMultiSamples(0);
  window->SetSize(kSize, kSize);
  window->AddRenderer(renderer);
  TC_CHECK(check, CheckFraming(window, renderer, atlas, lod, lodActor));
  TC_CHECK(check, CheckAgainstTheInput(window, renderer, mesh, atlas, lod, lodActor));
  return check.failures == 0 ? 0 : 1;
}
