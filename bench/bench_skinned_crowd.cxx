// SPDX-License-Identifier: BSD-3-Clause
// An animated crowd rendered two ways along one camera path (Feng et al. 2010, 5.2, 6 and Table
// III; issue 20): tcLODMapper posing the skinned atlas of a character in its vertex shader, with
// levels chosen for a screen-space error of at most one pixel; and tcSkinnedCrowdMapper
// (skinned_crowd_mapper.h), the character's input mesh skinned by the same vertex-shader function
// (shaders/SkinningVS.glsl), every character in view in one instanced draw. Each character plays
// one of the file's moving animations from its own phase. Prints frames per second, triangles per
// frame and per second of both, their ratio against the goal of issue 20, the LOD selection time
// and the paper's throughput beside ours.
//
// Before timing, a check that both renderers pose: one character drawn by each at a time t1, and
// by the peer at t2, against the CPU reference pose (tc::skinPoints) drawn by vtkPolyDataMapper.
// A renderer that does not pose gives no figures, so a broken peer cannot flatter the ratio.
//
//   xvfb-run -a -s '-screen 0 1280x1024x24 -noreset' tc_bench_skinned_crowd \
//       [mesh] [characters] [frames] [atlas]
//     default: wuson.glb ("" for the default), 400 characters (a 20 x 20 grid), 60 frames; the
//     atlas is built here through the filters (a few seconds) as
//       trichart build wuson.glb -o wuson.exr --fill-holes --split-non-manifold
//     builds it (wuson is open and non-manifold), or read from that .exr file if given.
#include "bench_common.h"
#include "crowd_path.h"
#include "discrete_lod.h" // tcbench::Sphere, InFrustum
#include "skinned_crowd_mapper.h"

#include "tcAtlasReader.h"
#include "tcBaseComplex.h"
#include "tcCurvature.h"
#include "tcFeatureRefinement.h"
#include "tcGeometryImages.h"
#include "tcLODMapper.h"
#include "tcMeshConversion.h"
#include "tcMeshPreparation.h"
#include "tcMeshReader.h"
#include "tcPathTracing.h"
#include "tcSpectralClustering.h"

#include "tc/common/array_names.h"
#include "tc/skinning/skin.h"

#include <vtkActor.h>
#include <vtkCamera.h>
#include <vtkDoubleArray.h>
#include <vtkImageData.h>
#include <vtkIntArray.h>
#include <vtkLogger.h>
#include <vtkMath.h>
#include <vtkMatrix4x4.h>
#include <vtkMultiBlockDataSet.h>
#include <vtkNew.h>
#include <vtkOpenGLRenderWindow.h>
#include <vtkPointData.h>
#include <vtkPoints.h>
#include <vtkPolyDataMapper.h>
#include <vtkPolyDataNormals.h>
#include <vtkProperty.h>
#include <vtkRenderWindow.h>
#include <vtkRenderer.h>
#include <vtkTriangleFilter.h>
#include <vtkUnsignedCharArray.h>
#include <vtkWindowToImageFilter.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <functional>
#include <memory>
#include <string>
#include <vector>

namespace
{
constexpr double kSpeedupGoal = 10.0;     // issue 20: LOD crowd vs skinned input meshes, fps
constexpr double kPaperThroughput = 85e6; // Table III, Boxing Crowd (GeForce 8800 GTS)
constexpr double kErrorTarget = 1.0;      // pixels
// Frames per second of animation time, fixed: both renderers draw the same poses at the same
// frame, however fast each runs.
constexpr double kPlaybackRate = 30.0;
constexpr int kPoseSamples = 16; // times per animation at which the bounding sphere is measured
constexpr int kWidth = 1280, kHeight = 720;

/// One character: its input mesh (triangles, point normals, the skin arrays) and rig.
struct Character
{
  vtkSmartPointer<vtkPolyData> mesh;
  tc::Rig rig;
  tc::SkinWeights skin;
  std::vector<double> bindPoints;
  std::vector<int> animations;       // those that move (duration > 0): what the crowd plays
  double center[4] = { 0, 0, 0, 1 }; // the bind pose's box centre
  double radius = 0;                 // about the centre, in every pose of every animation
  double size = 0;                   // the bind pose's largest extent
  double floor = 0;                  // its lowest y
};

/// Where each character stands, what it plays, from which phase.
struct Crowd
{
  std::vector<tc::Matrix4> places; // rigid, model to world
  std::vector<int> animations;     // indices of the rig's animations
  std::vector<double> phases;      // seconds
  std::vector<tcbench::Sphere> spheres;
  double extent = 0;
  double bounds[6] = { 0, -1, 0, -1, 0, -1 };
};

struct Run
{
  double seconds = 0.0;
  double triangles = 0.0; // per frame, mean
};

/// The skin of `mesh`'s point arrays as the core holds it.
tc::SkinWeights SkinOf(vtkPolyData* mesh)
{
  vtkDataArray* joints = mesh->GetPointData()->GetArray(tc::kSkinIndices);
  vtkDataArray* weights = mesh->GetPointData()->GetArray(tc::kSkinWeights);
  tc::SkinWeights skin;
  for (vtkIdType p = 0; p < mesh->GetNumberOfPoints(); ++p)
  {
    for (int k = 0; k < tc::kMaxInfluences; ++k)
    {
      skin.joints.push_back(static_cast<int32_t>(joints->GetComponent(p, k)));
      skin.weights.push_back(static_cast<float>(weights->GetComponent(p, k)));
    }
  }
  return skin;
}

/// The largest distance from `c.center` of the mesh's points in every pose the crowd plays (and
/// the rest pose), sampled kPoseSamples times per animation.
double PosedRadius(const Character& c)
{
  double r2 = 0.0;
  const auto grow = [&](const std::vector<tc::Matrix4>& matrices)
  {
    const std::vector<double> posed = tc::skinPoints(c.bindPoints, c.skin, matrices);
    for (size_t p = 0; p + 2 < posed.size(); p += 3)
    {
      r2 = std::max(r2, vtkMath::Distance2BetweenPoints(posed.data() + p, c.center));
    }
  };
  grow(tc::poseMatrices(c.rig, -1, 0.0));
  for (const int a : c.animations)
  {
    for (int s = 0; s <= kPoseSamples; ++s)
    {
      grow(tc::poseMatrices(c.rig, a, c.rig.animations[a].duration * s / kPoseSamples));
    }
  }
  return std::sqrt(r2);
}

/// The skinned file `file` in its bind pose, as tcMeshReader reads it, triangulated with a
/// normal per point; false (with a message) when it has no skin or no moving animation.
bool ReadCharacter(const std::string& file, Character& c)
{
  vtkNew<tcMeshReader> reader;
  reader->SetFileName(file.c_str());
  reader->BindPoseOn();
  vtkNew<vtkTriangleFilter> triangles;
  triangles->SetInputConnection(reader->GetOutputPort());
  // One normal per point, no splitting: the peer draws the input's own vertices.
  vtkNew<vtkPolyDataNormals> normals;
  normals->SetInputConnection(triangles->GetOutputPort());
  normals->SplittingOff();
  normals->ConsistencyOff();
  normals->ComputeCellNormalsOff();
  normals->Update();
  c.mesh = vtkSmartPointer<vtkPolyData>::New();
  c.mesh->ShallowCopy(normals->GetOutput());
  const std::string rig = tcvtk::GetTextField(reader->GetOutput()->GetFieldData(), tc::kRig);
  if (rig.empty() || !c.mesh->GetPointData()->GetArray(tc::kSkinIndices) ||
    !c.mesh->GetPointData()->GetArray(tc::kSkinWeights))
  {
    std::fprintf(
      stderr, "%s: no skin (SkinIndices, SkinWeights, Rig): not a skinned file\n", file.c_str());
    return false;
  }
  c.rig = tc::decodeRig(rig);
  c.skin = SkinOf(c.mesh);
  for (vtkIdType p = 0; p < c.mesh->GetNumberOfPoints(); ++p)
  {
    const double* x = c.mesh->GetPoint(p);
    c.bindPoints.insert(c.bindPoints.end(), x, x + 3);
  }
  for (size_t a = 0; a < c.rig.animations.size(); ++a)
  {
    if (c.rig.animations[a].duration > 0.0)
    {
      c.animations.push_back(static_cast<int>(a));
    }
  }
  if (c.animations.empty())
  {
    std::fprintf(stderr, "%s: no animation that moves\n", file.c_str());
    return false;
  }
  double b[6];
  c.mesh->GetBounds(b);
  c.center[0] = 0.5 * (b[0] + b[1]);
  c.center[1] = 0.5 * (b[2] + b[3]);
  c.center[2] = 0.5 * (b[4] + b[5]);
  c.size = std::max({ b[1] - b[0], b[3] - b[2], b[5] - b[4] });
  c.floor = b[2];
  c.radius = PosedRadius(c);
  return true;
}

/// `count` characters on a square grid on the ground plane y = 0, far enough apart that no two
/// overlap in any pose, each turned about the vertical axis, playing the moving animations in
/// turn, each from its own phase (a golden-ratio sequence over the animation's duration).
Crowd LayOut(const Character& c, int count)
{
  Crowd crowd;
  const int side = static_cast<int>(std::ceil(std::sqrt(static_cast<double>(count))));
  const double spacing = std::max(2.0 * c.radius, 1.6 * c.size);
  crowd.extent = spacing * side;
  for (int i = 0; i < count; ++i)
  {
    const double a = 0.7 * i, cs = std::cos(a), sn = std::sin(a);
    const double x = spacing * (i % side), z = -spacing * (i / side);
    // The box centre goes to (x, ., z), the lowest point to y = 0.
    crowd.places.push_back({ cs, 0, sn, x - (cs * c.center[0] + sn * c.center[2]), 0, 1, 0,
      -c.floor, -sn, 0, cs, z - (-sn * c.center[0] + cs * c.center[2]), 0, 0, 0, 1 });
    const int animation = c.animations[static_cast<size_t>(i) % c.animations.size()];
    crowd.animations.push_back(animation);
    crowd.phases.push_back(
      std::fmod(0.6180339887498949 * i, 1.0) * c.rig.animations[animation].duration);
    tcbench::Sphere s;
    double placed[4];
    vtkMatrix4x4::MultiplyPoint(crowd.places.back().data(), c.center, placed);
    std::copy(placed, placed + 3, s.center);
    s.radius = c.radius;
    crowd.spheres.push_back(s);
    for (int d = 0; d < 3; ++d)
    {
      crowd.bounds[2 * d] =
        std::min(i ? crowd.bounds[2 * d] : VTK_DOUBLE_MAX, s.center[d] - s.radius);
      crowd.bounds[2 * d + 1] =
        std::max(i ? crowd.bounds[2 * d + 1] : -VTK_DOUBLE_MAX, s.center[d] + s.radius);
    }
  }
  return crowd;
}

/// Character i's time in its animation at `frame`, looping.
double SecondsAt(const Character& c, const Crowd& crowd, size_t i, int frame)
{
  const double duration = c.rig.animations[crowd.animations[i]].duration;
  return std::fmod(crowd.phases[i] + frame / kPlaybackRate, duration);
}

/// The peer's palettes at `frame` for the characters whose sphere is in view (what an engine
/// culls by), each character's place folded into its skinning matrices; how many.
int PeerPalettes(const Character& c, const Crowd& crowd, vtkCamera* camera, int frame,
  std::vector<float>& palettes)
{
  palettes.clear();
  int drawn = 0;
  for (size_t i = 0; i < crowd.places.size(); ++i)
  {
    if (!tcbench::InFrustum(camera, double(kWidth) / kHeight, crowd.spheres[i]))
    {
      continue;
    }
    std::vector<tc::Matrix4> matrices =
      tc::poseMatrices(c.rig, crowd.animations[i], SecondsAt(c, crowd, i, frame));
    for (tc::Matrix4& m : matrices)
    {
      m = tc::multiply(crowd.places[i], m);
    }
    tc::appendPaletteRows(matrices, palettes);
    ++drawn;
  }
  return drawn;
}

/// The atlas of `mesh`: read from `atlasFile`, or else built through the filters with their
/// defaults, holes filled and non-manifold points split as `trichart build --fill-holes
/// --split-non-manifold` does (the base complex needs a closed manifold).
vtkSmartPointer<vtkMultiBlockDataSet> Atlas(const std::string& mesh, const std::string& atlasFile)
{
  auto atlas = vtkSmartPointer<vtkMultiBlockDataSet>::New();
  if (!atlasFile.empty())
  {
    vtkNew<tcAtlasReader> reader;
    reader->SetFileName(atlasFile.c_str());
    reader->Update();
    atlas->ShallowCopy(reader->GetOutput());
    return atlas;
  }
  vtkNew<tcMeshReader> reader;
  reader->SetFileName(mesh.c_str());
  reader->BindPoseOn();
  vtkNew<tcMeshPreparation> prep;
  prep->SetInputConnection(reader->GetOutputPort());
  prep->FillHolesOn();
  prep->SplitNonManifoldOn();
  vtkNew<tcCurvature> curvature;
  curvature->SetInputConnection(prep->GetOutputPort());
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
  atlas->ShallowCopy(images->GetOutput());
  return atlas;
}

/// One renderer along the path, in a window of its own: `pose(frame)` runs once the camera is
/// placed, before each render, and `triangles()` after it.
struct Flight
{
  vtkNew<vtkRenderWindow> window;
  vtkNew<vtkRenderer> renderer;
  std::function<void(int)> pose;
  std::function<double()> triangles;
  Run run;

  Flight()
  {
    this->window->SetOffScreenRendering(1);
    this->window->SetSize(kWidth, kHeight);
    this->window->AddRenderer(this->renderer);
  }
};

/// Draws and times one frame of `flight`, or, with `timed` false, draws it only.
void DrawFrame(Flight& flight, int frame, int frames, double extent, double size, bool timed)
{
  const auto start = std::chrono::steady_clock::now();
  tcbench::PlaceCamera(flight.renderer->GetActiveCamera(), frame, frames, extent, size);
  flight.pose(frame);
  flight.window->Render();
  static_cast<vtkOpenGLRenderWindow*>(flight.window.Get())->WaitForCompletion();
  if (timed)
  {
    flight.run.seconds +=
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    flight.run.triangles += flight.triangles() / frames;
  }
}

/// Flies the flights along the path together, frame by frame in turn, each render timed on its
/// own: on a machine shared with other work, a load that comes and goes slows both renderers
/// alike instead of the one that happens to fly then. The first render of each (uploads, shader
/// compilation, tcLODMapper's skinned boxes) is not timed.
void FlyTogether(const std::vector<Flight*>& flights, int frames, double extent, double size)
{
  for (Flight* flight : flights)
  {
    DrawFrame(*flight, 0, frames, extent, size, false);
  }
  for (int f = 0; f < frames; ++f)
  {
    for (Flight* flight : flights)
    {
      DrawFrame(*flight, f, frames, extent, size, true);
    }
  }
}

/// The window's colours after a render, read back.
vtkSmartPointer<vtkUnsignedCharArray> Snapshot(vtkRenderWindow* window)
{
  vtkNew<vtkWindowToImageFilter> grab;
  grab->SetInput(window);
  grab->Update();
  auto pixels = vtkSmartPointer<vtkUnsignedCharArray>::New();
  pixels->DeepCopy(grab->GetOutput()->GetPointData()->GetScalars());
  return pixels;
}

/// Whether a pixel of a flat white silhouette on black is covered.
bool Covered(vtkUnsignedCharArray* image, vtkIdType pixel)
{
  const int n = image->GetNumberOfComponents();
  int sum = 0;
  for (int k = 0; k < std::min(n, 3); ++k)
  {
    sum += image->GetValue(n * pixel + k);
  }
  return sum > 96;
}

/// Pixels covered in `a` and not in `b` or the other way round (`b` nullptr: covered in `a`).
vtkIdType Differing(vtkUnsignedCharArray* a, vtkUnsignedCharArray* b)
{
  vtkIdType count = 0;
  for (vtkIdType p = 0; p < a->GetNumberOfTuples(); ++p)
  {
    count += Covered(a, p) != (b != nullptr && Covered(b, p)) ? 1 : 0;
  }
  return count;
}

/// Silhouettes of one character, in pixels: how many the CPU reference covers at t1, and how
/// many differ between it and each renderer at t1, and between the peer at t1 and at t2.
struct PoseCheck
{
  vtkIdType covered = 0, peer = 0, lod = 0, motion = 0;
  bool lodSkinned = false;

  /// The peer poses as the reference does, and posing moves the silhouette.
  bool PeerPoses() const { return peer <= covered / 100 && motion >= covered / 20; }
  /// tcLODMapper's silhouette is nearer the reference's pose at t1 than the peer's at t2 is.
  bool LodPoses() const { return lodSkinned && 2 * lod < motion; }
};

/// The character's input mesh posed at `seconds` of `animation` on the CPU (tc::skinPoints).
vtkSmartPointer<vtkPolyData> Posed(const Character& c, int animation, double seconds)
{
  const std::vector<double> posed =
    tc::skinPoints(c.bindPoints, c.skin, tc::poseMatrices(c.rig, animation, seconds));
  vtkNew<vtkPoints> points;
  points->SetDataTypeToDouble();
  points->SetNumberOfPoints(c.mesh->GetNumberOfPoints());
  for (vtkIdType p = 0; p < points->GetNumberOfPoints(); ++p)
  {
    points->SetPoint(p, posed.data() + 3 * p);
  }
  auto mesh = vtkSmartPointer<vtkPolyData>::New();
  mesh->ShallowCopy(c.mesh);
  mesh->SetPoints(points);
  return mesh;
}

/// Renders one character, unlit white on black, close up: by the CPU reference, the peer and
/// tcLODMapper at a quarter of its first moving animation, and by the peer at three quarters.
PoseCheck CheckPoses(
  vtkRenderWindow* window, vtkRenderer* renderer, const Character& c, vtkMultiBlockDataSet* atlas)
{
  const int animation = c.animations.front();
  const double t1 = 0.25 * c.rig.animations[animation].duration;
  const double t2 = 0.75 * c.rig.animations[animation].duration;
  vtkCamera* camera = renderer->GetActiveCamera();
  camera->SetFocalPoint(c.center);
  camera->SetPosition(
    c.center[0] + 1.6 * c.radius, c.center[1] + 1.0 * c.radius, c.center[2] + 2.6 * c.radius);
  camera->SetViewUp(0, 1, 0);
  camera->SetViewAngle(40);
  camera->SetClippingRange(0.05 * c.radius, 10.0 * c.radius);
  const auto show = [&](vtkMapper* mapper)
  {
    renderer->RemoveAllViewProps();
    vtkNew<vtkActor> actor;
    actor->SetMapper(mapper);
    actor->GetProperty()->LightingOff();
    renderer->AddActor(actor);
    return Snapshot(window);
  };
  vtkNew<vtkPolyDataMapper> reference;
  reference->SetInputData(Posed(c, animation, t1));
  const auto expected = show(reference);
  vtkNew<tcSkinnedCrowdMapper> peer;
  peer->SetInputData(c.mesh);
  const double b[6] = { c.center[0] - c.radius, c.center[0] + c.radius, c.center[1] - c.radius,
    c.center[1] + c.radius, c.center[2] - c.radius, c.center[2] + c.radius };
  peer->SetCrowdBounds(b);
  const auto peerAt = [&](double seconds)
  {
    std::vector<float> palette;
    tc::appendPaletteRows(tc::poseMatrices(c.rig, animation, seconds), palette);
    peer->SetPalettes(palette, static_cast<int>(c.rig.skeleton.joints.size()));
    return show(peer);
  };
  const auto peer1 = peerAt(t1);
  const auto peer2 = peerAt(t2);
  vtkNew<tcLODMapper> lod;
  lod->SetInputData(atlas);
  lod->SetErrorTarget(kErrorTarget);
  lod->SetAnimation(std::to_string(animation).c_str());
  lod->SetAnimationTime(t1);
  const auto lod1 = show(lod);
  renderer->RemoveAllViewProps();
  PoseCheck check;
  check.covered = Differing(expected, nullptr);
  check.peer = Differing(peer1, expected);
  check.lod = Differing(lod1, expected);
  check.motion = Differing(peer1, peer2);
  check.lodSkinned = lod->GetSkinned();
  return check;
}

/// Frame statistics of tcLODMapper, summed over the timed frames.
struct LodStats
{
  double selection = 0.0, drawList = 0.0, charts = 0.0;
  std::vector<double> atLevel = std::vector<double>(16, 0.0); // charts drawn per level, summed
  vtkIdType chartInstances = 0;
  bool skinned = false;
};

/// tcLODMapper's flight: one actor, every character an instance with its own place, animation
/// and time; `stats` sums its figures over the timed frames.
void SetUpLod(Flight& flight, tcLODMapper* lod, vtkMultiBlockDataSet* atlas, const Character& c,
  const Crowd& crowd, LodStats& stats)
{
  lod->SetInputData(atlas);
  lod->SetErrorTarget(kErrorTarget);
  vtkNew<vtkDoubleArray> matrices;
  matrices->SetNumberOfComponents(16);
  vtkNew<vtkIntArray> animations;
  for (size_t i = 0; i < crowd.places.size(); ++i)
  {
    matrices->InsertNextTuple(crowd.places[i].data());
    animations->InsertNextValue(crowd.animations[i]);
  }
  lod->SetInstanceMatrices(matrices);
  lod->SetInstanceAnimations(animations);
  vtkNew<vtkActor> actor;
  actor->SetMapper(lod);
  flight.renderer->AddActor(actor);
  auto times = vtkSmartPointer<vtkDoubleArray>::New();
  times->SetNumberOfTuples(static_cast<vtkIdType>(crowd.places.size()));
  flight.pose = [lod, times, &c, &crowd](int frame)
  {
    for (size_t i = 0; i < crowd.places.size(); ++i)
    {
      times->SetValue(static_cast<vtkIdType>(i), SecondsAt(c, crowd, i, frame));
    }
    lod->SetInstanceTimes(times);
  };
  flight.triangles = [lod, &stats]()
  {
    stats.selection += lod->GetSelectionSeconds();
    stats.drawList += lod->GetDrawListSeconds();
    stats.charts += static_cast<double>(lod->GetChartsDrawn());
    for (size_t level = 0; level < stats.atLevel.size(); ++level)
    {
      stats.atLevel[level] += static_cast<double>(lod->GetChartsAtLevel(static_cast<int>(level)));
    }
    return static_cast<double>(lod->GetTrianglesDrawn());
  };
}

/// The peer's flight: the characters in view, each frame, in one instanced draw.
void SetUpPeer(Flight& flight, tcSkinnedCrowdMapper* peer, const Character& c, const Crowd& crowd)
{
  peer->SetInputData(c.mesh);
  peer->SetCrowdBounds(crowd.bounds);
  vtkNew<vtkActor> actor;
  actor->SetMapper(peer);
  flight.renderer->AddActor(actor);
  auto drawn = std::make_shared<int>(0);
  vtkRenderer* renderer = flight.renderer;
  flight.pose = [peer, drawn, renderer, &c, &crowd](int frame)
  {
    std::vector<float> palettes;
    *drawn = PeerPalettes(c, crowd, renderer->GetActiveCamera(), frame, palettes);
    peer->SetPalettes(palettes, static_cast<int>(c.rig.skeleton.joints.size()));
  };
  const double triangles = static_cast<double>(c.mesh->GetNumberOfPolys());
  flight.triangles = [drawn, triangles]() { return *drawn * triangles; };
}

/// The figures of one renderer.
void Report(const char* name, const Run& run, int frames)
{
  const double fps = frames / run.seconds;
  std::printf("  %-46s %8.2f fps  %10.0f triangles/frame  %8.2f M triangles/s\n", name, fps,
    run.triangles, 1e-6 * run.triangles * fps);
}

/// The OpenGL renderer's name, from the window's capabilities.
std::string RendererName(vtkRenderWindow* window)
{
  const std::string capabilities = window->ReportCapabilities();
  const size_t at = capabilities.find("OpenGL renderer string:");
  return at == std::string::npos ? "OpenGL renderer: unknown"
                                 : capabilities.substr(at, capabilities.find('\n', at) - at);
}
} // namespace

int main(int argc, char* argv[])
{
  std::setvbuf(stdout, nullptr, _IOLBF, 0); // figures appear as they come, also into a file
  // The filters' reports (tcMeshPreparation's repairs of wuson) are logged as INFO: not figures.
  vtkLogger::SetStderrVerbosity(vtkLogger::VERBOSITY_WARNING);
  const std::string file = argc > 1 && argv[1][0] != 0
    ? argv[1]
    : std::string(TC_SHARED_DATA_DIR) + "/skinned/wuson/wuson.glb";
  const int characters = argc > 2 ? std::max(1, std::atoi(argv[2])) : 400;
  const int frames = argc > 3 ? std::max(2, std::atoi(argv[3])) : 60;
  const std::string atlasFile = argc > 4 ? argv[4] : "";
  Character c;
  if (tcbench::Present({ file }).empty() || !ReadCharacter(file, c))
  {
    return tcbench::Present({ file }).empty() ? 0 : 1;
  }
  std::printf("%s: %lld points, %lld triangles, %zu joints; the crowd plays",
    tcbench::BaseName(file).c_str(), static_cast<long long>(c.mesh->GetNumberOfPoints()),
    static_cast<long long>(c.mesh->GetNumberOfPolys()), c.rig.skeleton.joints.size());
  for (const int a : c.animations)
  {
    std::printf(" '%s' (%.2f s)", c.rig.animations[a].name.c_str(), c.rig.animations[a].duration);
  }
  std::printf("\n");
  const auto started = std::chrono::steady_clock::now();
  const vtkSmartPointer<vtkMultiBlockDataSet> atlas = Atlas(file, atlasFile);
  std::printf("atlas: %s in %.1f s\n", atlasFile.empty() ? "built" : atlasFile.c_str(),
    std::chrono::duration<double>(std::chrono::steady_clock::now() - started).count());
  const Crowd crowd = LayOut(c, characters);

  Flight withLod, plain;
  // Both must pose, or the ratio says nothing.
  const PoseCheck check = CheckPoses(withLod.window, withLod.renderer, c, atlas);
  std::printf("posing check, pixels of one character's silhouette (%lld covered): peer vs the CPU "
              "pose %lld, tcLODMapper vs the CPU pose %lld, peer at t1 vs t2 %lld: peer %s, "
              "tcLODMapper %s\n",
    static_cast<long long>(check.covered), static_cast<long long>(check.peer),
    static_cast<long long>(check.lod), static_cast<long long>(check.motion),
    check.PeerPoses() ? "poses" : "DOES NOT POSE", check.LodPoses() ? "poses" : "DOES NOT POSE");
  if (!check.PeerPoses())
  {
    std::fprintf(stderr, "the peer does not pose its characters: no figures\n");
    return 1;
  }

  LodStats stats;
  vtkNew<tcLODMapper> lod;
  SetUpLod(withLod, lod, atlas, c, crowd, stats);
  vtkNew<tcSkinnedCrowdMapper> peer;
  SetUpPeer(plain, peer, c, crowd);
  FlyTogether({ &withLod, &plain }, frames, crowd.extent, c.size);
  stats.skinned = lod->GetSkinned();
  stats.chartInstances = lod->GetNumberOfCharts() * static_cast<vtkIdType>(crowd.places.size());
  std::printf("crowd: %d characters, each at its own phase, %d frames at %d x %d\n", characters,
    frames, kWidth, kHeight);
  Report(stats.skinned ? "tcLODMapper, skinned atlas, error <= 1 pixel"
                       : "tcLODMapper, NOT skinned, error <= 1 pixel",
    withLod.run, frames);
  Report("tcSkinnedCrowdMapper, skinned input mesh", plain.run, frames);
  const double speedup = plain.run.seconds / withLod.run.seconds;
  // A ratio counts only when tcLODMapper posed its characters and drew them.
  const bool counted = stats.skinned && check.LodPoses() && withLod.run.triangles > 0.0;
  std::printf("  speed-up %.1fx (goal >= %.0fx: %s), at %.1fx fewer triangles per frame; per "
              "frame: LOD selection %.3f ms, draw list %.3f ms, %.0f of %lld chart instances "
              "drawn\n",
    speedup, kSpeedupGoal,
    !counted                    ? "not counted, tcLODMapper did not pose or draw its characters"
      : speedup >= kSpeedupGoal ? "met"
                                : "missed",
    plain.run.triangles / std::max(withLod.run.triangles, 1.0), 1e3 * stats.selection / frames,
    1e3 * stats.drawList / frames, stats.charts / frames,
    static_cast<long long>(stats.chartInstances));
  // Which levels the drawn charts are at (level d: 4^d triangles; 0, one triangle, the coarsest).
  std::printf("  levels of the drawn charts:");
  for (size_t level = 0; level < stats.atLevel.size(); ++level)
  {
    if (stats.atLevel[level] > 0.0)
    {
      std::printf(
        " %zu: %.1f%%", level, 100.0 * stats.atLevel[level] / std::max(stats.charts, 1.0));
    }
  }
  std::printf("\n");
  // A chart is one triangle at its coarsest level: the atlas cannot draw a character in fewer.
  std::printf("  the atlas's floor: %lld charts, so at least %lld triangles per character in view "
              "(the input mesh has %lld)\n",
    static_cast<long long>(stats.chartInstances / characters),
    static_cast<long long>(stats.chartInstances / characters),
    static_cast<long long>(c.mesh->GetNumberOfPolys()));
  const std::string name = RendererName(withLod.window);
  std::printf("  the paper's skinned crowd: %.0f M triangles/s (Table III, Boxing Crowd, GeForce "
              "8800 GTS)%s\n",
    1e-6 * kPaperThroughput,
    name.find("llvmpipe") != std::string::npos
      ? "; Mesa llvmpipe is a CPU rasterizer: its triangles per second are not comparable"
      : "");
  std::printf("%s\n", name.c_str());
  return 0;
}
