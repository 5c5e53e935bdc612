// SPDX-License-Identifier: BSD-3-Clause
// A crowd rendered two ways along one camera path (Feng et al. 2010, section 6 and Table III):
// tcLODMapper drawing the atlas of the mesh with levels chosen for a screen-space error of at
// most one pixel, and a plain vtkPolyDataMapper drawing the full mesh once per instance. Prints
// frames per second, triangles per frame and per second for both, and their ratio, with the
// goals of issue 6; then the LOD selection time for a 100K-chart scene.
//
//   xvfb-run -a tc_bench_lod_rendering [mesh] [instances] [frames]
//     default: bunny_glmark2 (70K; "" for the default), 400 instances (a 20 x 20 grid), 60 frames
#include "bench_common.h"

#include "tcBaseComplex.h"
#include "tcCurvature.h"
#include "tcFeatureRefinement.h"
#include "tcGeometryImages.h"
#include "tcLODMapper.h"
#include "tcPathTracing.h"
#include "tcSpectralClustering.h"

#include <vtkActor.h>
#include <vtkCamera.h>
#include <vtkDoubleArray.h>
#include <vtkMatrix4x4.h>
#include <vtkMultiBlockDataSet.h>
#include <vtkNew.h>
#include <vtkOpenGLRenderWindow.h>
#include <vtkPolyDataMapper.h>
#include <vtkProperty.h>
#include <vtkRenderWindow.h>
#include <vtkRenderer.h>
#include <vtkTable.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <functional>
#include <string>
#include <vector>

namespace
{
constexpr double kSpeedupGoal = 10.0;  // LOD crowd vs full meshes, frames per second
constexpr double kSelectionGoal = 1e-3; // seconds per frame for 100K charts
constexpr int kWidth = 1280, kHeight = 720;

struct Run
{
  double seconds = 0.0;
  double triangles = 0.0; // per frame, mean
};

/// The camera path: a slow pass over the crowd, lower and closer as it goes, looking ahead.
void PlaceCamera(vtkCamera* camera, int frame, int frames, double extent, double size)
{
  const double t = frames > 1 ? static_cast<double>(frame) / (frames - 1) : 0.0;
  const double x = -0.2 * extent + 0.9 * extent * t;
  camera->SetPosition(x, 1.5 * size + 3.0 * size * (1.0 - t), 2.0 * size);
  camera->SetFocalPoint(x + 0.3 * extent, 0.0, -0.6 * extent);
  camera->SetViewUp(0, 1, 0);
  camera->SetViewAngle(50);
  camera->SetClippingRange(0.05 * size, 4.0 * extent);
}

Run Fly(vtkRenderWindow* window, vtkRenderer* renderer, int frames, double extent, double size,
  const std::function<double()>& trianglesOfFrame)
{
  Run run;
  PlaceCamera(renderer->GetActiveCamera(), 0, frames, extent, size);
  window->Render(); // uploads, shader compilation: not timed
  static_cast<vtkOpenGLRenderWindow*>(window)->WaitForCompletion();
  const auto start = std::chrono::steady_clock::now();
  for (int f = 0; f < frames; ++f)
  {
    PlaceCamera(renderer->GetActiveCamera(), f, frames, extent, size);
    window->Render();
    static_cast<vtkOpenGLRenderWindow*>(window)->WaitForCompletion();
    run.triangles += trianglesOfFrame();
  }
  run.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  run.triangles /= frames;
  return run;
}
} // namespace

int main(int argc, char* argv[])
{
  std::setvbuf(stdout, nullptr, _IOLBF, 0); // figures appear as they come, also into a file
  const std::string file =
    argc > 1 && argv[1][0] != 0 ? argv[1] : std::string(TC_SHARED_DATA_DIR) + "/static_medium/bunny_glmark2.obj";
  const int instances = argc > 2 ? std::max(1, std::atoi(argv[2])) : 400;
  const int frames = argc > 3 ? std::max(2, std::atoi(argv[3])) : 60;
  if (tcbench::Present({ file }).empty())
  {
    return 0;
  }
  vtkSmartPointer<vtkPolyData> mesh = tcbench::Prepared(file);
  std::printf("%s: %lld points, %lld triangles\n", tcbench::BaseName(file).c_str(),
    static_cast<long long>(mesh->GetNumberOfPoints()),
    static_cast<long long>(mesh->GetNumberOfPolys()));

  // The atlas, through the filters with their defaults.
  const auto built = std::chrono::steady_clock::now();
  vtkNew<tcCurvature> curvature;
  curvature->SetInputData(mesh);
  vtkNew<tcSpectralClustering> clustering;
  clustering->SetInputConnection(curvature->GetOutputPort());
  vtkNew<tcFeatureRefinement> refinement;
  refinement->SetInputConnection(clustering->GetOutputPort());
  vtkNew<tcBaseComplex> base;
  base->SetInputConnection(refinement->GetOutputPort());
  vtkNew<tcPathTracing> tracing;
  tracing->SetInputConnection(base->GetOutputPort(1));
  vtkNew<tcGeometryImages> images;
  images->SetInputConnection(tracing->GetOutputPort());
  images->Update();
  auto* charts = vtkTable::SafeDownCast(images->GetOutput()->GetBlock(0));
  std::printf("atlas: %lld charts, built in %.1f s\n",
    static_cast<long long>(charts ? charts->GetNumberOfRows() : 0),
    std::chrono::duration<double>(std::chrono::steady_clock::now() - built).count());

  double bounds[6];
  mesh->GetBounds(bounds);
  const double size = std::max({ bounds[1] - bounds[0], bounds[3] - bounds[2], bounds[5] - bounds[4] });
  const int side = static_cast<int>(std::ceil(std::sqrt(static_cast<double>(instances))));
  const double spacing = 1.6 * size;
  const double extent = spacing * side;
  vtkNew<vtkDoubleArray> matrices;
  matrices->SetNumberOfComponents(16);
  for (int i = 0; i < instances; ++i)
  {
    // On the ground plane y = 0, each turned about the vertical axis so the crowd is not uniform.
    const double a = 0.7 * i;
    const double x = spacing * (i % side), z = -spacing * (i / side);
    const double m[16] = { std::cos(a), 0, std::sin(a), x - 0.5 * (bounds[0] + bounds[1]), 0, 1, 0,
      -bounds[2], -std::sin(a), 0, std::cos(a), z - 0.5 * (bounds[4] + bounds[5]), 0, 0, 0, 1 };
    matrices->InsertNextTuple(m);
  }

  vtkNew<vtkRenderWindow> window;
  window->SetOffScreenRendering(1);
  window->SetSize(kWidth, kHeight);
  vtkNew<vtkRenderer> renderer;
  window->AddRenderer(renderer);

  // tcLODMapper: one actor, every instance.
  vtkNew<tcLODMapper> lod;
  lod->SetInputConnection(images->GetOutputPort());
  lod->SetInstanceMatrices(matrices);
  lod->SetErrorTarget(1.0);
  vtkNew<vtkActor> lodActor;
  lodActor->SetMapper(lod);
  renderer->AddActor(lodActor);
  double selection = 0.0, drawList = 0.0;
  const Run withLod = Fly(window, renderer, frames, extent, size,
    [&]()
    {
      selection += lod->GetSelectionSeconds();
      drawList += lod->GetDrawListSeconds();
      return static_cast<double>(lod->GetTrianglesDrawn());
    });
  renderer->RemoveAllViewProps();

  // The peer: the full mesh per instance, one actor each sharing one mapper.
  vtkNew<vtkPolyDataMapper> full;
  full->SetInputData(mesh);
  full->StaticOn();
  std::vector<vtkSmartPointer<vtkActor>> actors;
  for (int i = 0; i < instances; ++i)
  {
    auto actor = vtkSmartPointer<vtkActor>::New();
    actor->SetMapper(full);
    vtkNew<vtkMatrix4x4> m;
    m->DeepCopy(matrices->GetTuple(i));
    actor->SetUserMatrix(m);
    renderer->AddActor(actor);
    actors.push_back(actor);
  }
  const double meshTriangles = static_cast<double>(mesh->GetNumberOfPolys());
  const Run plain = Fly(window, renderer, frames, extent, size,
    [&]() { return meshTriangles * instances; });

  auto report = [&](const char* name, const Run& run)
  {
    const double fps = frames / run.seconds;
    std::printf("  %-34s %8.2f fps  %12.0f triangles/frame  %8.2f M triangles/s\n", name, fps,
      run.triangles, 1e-6 * run.triangles * fps);
  };
  std::printf("crowd: %d instances, %d frames at %d x %d\n", instances, frames, kWidth, kHeight);
  report("tcLODMapper, error <= 1 pixel", withLod);
  report("vtkPolyDataMapper, full mesh", plain);
  const double speedup = plain.seconds / withLod.seconds;
  std::printf("  speed-up %.1fx (goal >= %.0fx: %s); per frame for %lld chart instances: LOD "
              "selection %.3f ms, draw list (sort by level, upload) %.3f ms\n",
    speedup, kSpeedupGoal, speedup >= kSpeedupGoal ? "met" : "missed",
    static_cast<long long>(charts ? charts->GetNumberOfRows() * instances : 0),
    1e3 * selection / frames, 1e3 * drawList / frames);

  // LOD selection for 100K charts: the crowd's charts, enough instances to pass 100K.
  const vtkIdType perInstance = charts ? charts->GetNumberOfRows() : 1;
  const int many = static_cast<int>((100000 + perInstance - 1) / perInstance);
  vtkNew<vtkDoubleArray> manyMatrices;
  manyMatrices->SetNumberOfComponents(16);
  for (int i = 0; i < many; ++i)
  {
    manyMatrices->InsertNextTuple(matrices->GetTuple(i % instances));
  }
  renderer->RemoveAllViewProps();
  lod->SetInstanceMatrices(manyMatrices);
  renderer->AddActor(lodActor);
  std::vector<double> times, listTimes;
  const int selectionFrames = std::min(frames, 20);
  for (int f = 0; f < selectionFrames; ++f)
  {
    PlaceCamera(renderer->GetActiveCamera(), f, selectionFrames, extent, size);
    window->Render();
    times.push_back(lod->GetSelectionSeconds());
    listTimes.push_back(lod->GetDrawListSeconds());
  }
  std::sort(times.begin(), times.end());
  std::sort(listTimes.begin(), listTimes.end());
  const double median = times[times.size() / 2];
  std::printf("LOD selection for %lld charts (%d instances): median %.3f ms per frame (goal <= "
              "%.0f ms: %s); then the draw list (sort by level, upload): median %.3f ms\n",
    static_cast<long long>(perInstance * many), many, 1e3 * median, 1e3 * kSelectionGoal,
    median <= kSelectionGoal ? "met" : "missed", 1e3 * listTimes[listTimes.size() / 2]);
  const std::string capabilities = window->ReportCapabilities();
  const size_t at = capabilities.find("OpenGL renderer string:");
  std::printf("%s\n",
    at == std::string::npos ? "OpenGL renderer: unknown"
                            : capabilities.substr(at, capabilities.find('\n', at) - at).c_str());
  return 0;
}
