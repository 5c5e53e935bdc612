// SPDX-License-Identifier: BSD-3-Clause
// A crowd rendered three ways along one camera path (Feng et al. 2010, section 6 and Table III):
// tcLODMapper drawing the atlas of the mesh with levels chosen for a screen-space error of at
// most one pixel; a plain vtkPolyDataMapper drawing the full mesh once per instance; and what a
// game engine does, a discrete LOD chain per object (discrete_lod.h) within the same one pixel.
// Prints frames per second, triangles per frame and per second for each, their ratios, with the
// goals of issues 6 and 18; then the LOD selection time for a 100K-chart scene.
//
//   xvfb-run -a tc_bench_lod_rendering [mesh] [instances] [frames]
//     default: bunny_glmark2 (70K; "" for the default), 400 instances (a 20 x 20 grid), 60 frames
#include "bench_common.h"
#include "crowd_path.h"
#include "discrete_lod.h"

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
constexpr double kSpeedupGoal = 10.0;   // LOD crowd vs full meshes, frames per second
constexpr double kSelectionGoal = 1e-3; // seconds per frame for 100K charts
constexpr int kWidth = 1280, kHeight = 720;
constexpr int64_t kChainMinTriangles = 64; // a chain's coarsest level, about gltfpack's floor

struct Run
{
  double seconds = 0.0;
  double triangles = 0.0; // per frame, mean
};

/// Renders the path; `beforeRender` (may be empty) runs once the camera is placed, before each
/// render, and `trianglesOfFrame` after it.
Run Fly(vtkRenderWindow* window, vtkRenderer* renderer, int frames, double extent, double size,
  const std::function<double()>& trianglesOfFrame, const std::function<void()>& beforeRender = {})
{
  Run run;
  tcbench::PlaceCamera(renderer->GetActiveCamera(), 0, frames, extent, size);
  if (beforeRender)
  {
    beforeRender();
  }
  window->Render(); // uploads, shader compilation: not timed
  static_cast<vtkOpenGLRenderWindow*>(window)->WaitForCompletion();
  const auto start = std::chrono::steady_clock::now();
  for (int f = 0; f < frames; ++f)
  {
    tcbench::PlaceCamera(renderer->GetActiveCamera(), f, frames, extent, size);
    if (beforeRender)
    {
      beforeRender();
    }
    window->Render();
    static_cast<vtkOpenGLRenderWindow*>(window)->WaitForCompletion();
    run.triangles += trianglesOfFrame();
  }
  run.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  run.triangles /= frames;
  return run;
}
/// The discrete LOD chain on the crowd's actors: each frame, every actor in view takes the
/// coarsest chain level within `pixels`, the others are hidden.
Run FlyChain(vtkRenderWindow* window, vtkRenderer* renderer, int frames, double extent, double size,
  const tcbench::DiscreteLod& chain, const std::vector<vtkSmartPointer<vtkActor>>& actors,
  const std::vector<tcbench::Sphere>& spheres, double pixels)
{
  double triangles = 0.0;
  const auto choose = [&]()
  {
    triangles = 0.0;
    vtkCamera* camera = renderer->GetActiveCamera();
    for (size_t i = 0; i < actors.size(); ++i)
    {
      const bool seen = tcbench::InFrustum(camera, double(kWidth) / kHeight, spheres[i]);
      actors[i]->SetVisibility(seen);
      if (seen)
      {
        const size_t level = tcbench::ChooseLevel(chain, camera, kHeight, spheres[i], pixels);
        actors[i]->SetMapper(chain.mappers[level]);
        triangles += chain.triangles[level];
      }
    }
  };
  return Fly(
    window, renderer, frames, extent, size, [&]() { return triangles; }, choose);
}

/// The bounding sphere of `mesh` (box centre, half diagonal) placed by each instance matrix.
std::vector<tcbench::Sphere> InstanceSpheres(vtkPolyData* mesh, vtkDoubleArray* matrices)
{
  double b[6];
  mesh->GetBounds(b);
  const double c[4] = { 0.5 * (b[0] + b[1]), 0.5 * (b[2] + b[3]), 0.5 * (b[4] + b[5]), 1.0 };
  std::vector<tcbench::Sphere> spheres(static_cast<size_t>(matrices->GetNumberOfTuples()));
  for (vtkIdType i = 0; i < matrices->GetNumberOfTuples(); ++i)
  {
    double placed[4];
    vtkMatrix4x4::MultiplyPoint(matrices->GetTuple(i), c, placed);
    std::copy(placed, placed + 3, spheres[static_cast<size_t>(i)].center);
    spheres[static_cast<size_t>(i)].radius = 0.5 * mesh->GetLength();
  }
  return spheres;
}
} // namespace

int main(int argc, char* argv[])
{
  std::setvbuf(stdout, nullptr, _IOLBF, 0); // figures appear as they come, also into a file
  const std::string file = argc > 1 && argv[1][0] != 0
    ? argv[1]
    : std::string(TC_SHARED_DATA_DIR) + "/static_medium/bunny_glmark2.obj";
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
  const double size =
    std::max({ bounds[1] - bounds[0], bounds[3] - bounds[2], bounds[5] - bounds[4] });
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
  const Run plain =
    Fly(window, renderer, frames, extent, size, [&]() { return meshTriangles * instances; });

  // The game engine's way: the same actors, each at its chain level.
  tc::TriMesh triMesh;
  std::string error;
  if (!tcvtk::ToTriMesh(mesh, triMesh, error))
  {
    std::fprintf(stderr, "%s\n", error.c_str());
    return 1;
  }
  const tcbench::DiscreteLod chain = tcbench::BuildChain(triMesh, kChainMinTriangles);
  std::printf("discrete LOD chain (meshopt_simplify): triangles / Hausdorff over the diagonal:");
  for (size_t l = 0; l < chain.error.size(); ++l)
  {
    std::printf(" %.0f / %.4f%%", chain.triangles[l], 100.0 * chain.error[l] / mesh->GetLength());
  }
  std::printf("\n");
  const Run discrete = FlyChain(window, renderer, frames, extent, size, chain, actors,
    InstanceSpheres(mesh, matrices), lod->GetErrorTarget());

  auto report = [&](const char* name, const Run& run)
  {
    const double fps = frames / run.seconds;
    std::printf("  %-34s %8.2f fps  %12.0f triangles/frame  %8.2f M triangles/s\n", name, fps,
      run.triangles, 1e-6 * run.triangles * fps);
  };
  std::printf("crowd: %d instances, %d frames at %d x %d\n", instances, frames, kWidth, kHeight);
  report("tcLODMapper, error <= 1 pixel", withLod);
  report("vtkPolyDataMapper, full mesh", plain);
  report("discrete LOD chain, error <= 1 pixel", discrete);
  const double speedup = plain.seconds / withLod.seconds;
  std::printf("  speed-up %.1fx (goal >= %.0fx: %s); per frame for %lld chart instances: LOD "
              "selection %.3f ms, draw list (sort by level, upload) %.3f ms\n",
    speedup, kSpeedupGoal, speedup >= kSpeedupGoal ? "met" : "missed",
    static_cast<long long>(charts ? charts->GetNumberOfRows() * instances : 0),
    1e3 * selection / frames, 1e3 * drawList / frames);
  const double perFrame = withLod.triangles / discrete.triangles;
  std::printf("  per-chart LOD draws %.2fx the triangles of the discrete chain at the same error "
              "(goal <= 1: %s), at %.2fx its frames per second\n",
    perFrame, perFrame <= 1.0 ? "met" : "missed", discrete.seconds / withLod.seconds);

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
    tcbench::PlaceCamera(renderer->GetActiveCamera(), f, selectionFrames, extent, size);
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
