// SPDX-License-Identifier: BSD-3-Clause
// tcLODMapper posing a skinned atlas in its vertex shader (Feng et al. 2010, 5.2, 6.2): the
// bundled bunny skinned to a 3-joint chain along x (tests/core/support/skin_fixtures.h) through
// the whole pipeline, drawn as three instances, each at its own time of its own animation.
// 1. Exactness: for several times and random per-chart levels, every vertex the GPU draws
//    (transform feedback) equals CPU skinning (tc::skinPoints) of the vertex tcGeometryImageMesh
//    builds for it (tc::rebuildMesh), then the instance's transform, within 1e-6 of the diagonal.
// 2. No crack in any pose: the drawn triangles of every instance form a closed surface (every
//    edge between distinct drawn vertices, compared bit for bit, borders two triangles), and
//    without stitching they do not.
// 3. Bounds and selection: the mapper's bounds hold every drawn vertex; the instances pose apart.
// Then an image of the posed crowd against its baseline.
#include "tcAtlasConversion.h"
#include "tcGeometryImages.h"
#include "tcLODMapper.h"
#include "tcMeshConversion.h"
#include "tcTestUtilities.h"

#include "skin_fixtures.h"

#include "tc/common/array_names.h"
#include "tc/gim/atlas.h"
#include "tc/gim/geometry_image_mesh.h"
#include "tc/skinning/skin.h"

#include <vtkActor.h>
#include <vtkCamera.h>
#include <vtkDoubleArray.h>
#include <vtkFloatArray.h>
#include <vtkIntArray.h>
#include <vtkMinimalStandardRandomSequence.h>
#include <vtkMultiBlockDataSet.h>
#include <vtkNew.h>
#include <vtkPointData.h>
#include <vtkPolyData.h>
#include <vtkProperty.h>
#include <vtkRegressionTestImage.h>
#include <vtkRenderWindow.h>
#include <vtkRenderer.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <map>
#include <vector>

namespace
{
/// `mesh` skinned to tctest::chainRig over its x range: SkinIndices, SkinWeights and the Rig.
void SkinToChain(vtkPolyData* mesh)
{
  double b[6];
  mesh->GetBounds(b);
  vtkNew<vtkIntArray> joints;
  joints->SetName(tc::kSkinIndices);
  joints->SetNumberOfComponents(tc::kMaxInfluences);
  vtkNew<vtkFloatArray> weights;
  weights->SetName(tc::kSkinWeights);
  weights->SetNumberOfComponents(tc::kMaxInfluences);
  for (vtkIdType p = 0; p < mesh->GetNumberOfPoints(); ++p)
  {
    // A wider blend than the core tests' so that many samples mix three joints.
    const auto s = tctest::chainSkin((mesh->GetPoint(p)[0] - b[0]) / (b[1] - b[0]), 0.25);
    int j[tc::kMaxInfluences];
    for (int k = 0; k < tc::kMaxInfluences; ++k)
    {
      j[k] = static_cast<int>(s[static_cast<size_t>(k)]);
    }
    joints->InsertNextTypedTuple(j);
    weights->InsertNextTypedTuple(s.data() + tc::kMaxInfluences);
  }
  mesh->GetPointData()->AddArray(joints);
  mesh->GetPointData()->AddArray(weights);
  tcvtk::SetTextField(
    mesh->GetFieldData(), tc::kRig, tc::encodeRig(tctest::chainRig(b[0], (b[1] - b[0]) / 3.0)));
}

/// Three instances side by side, 1.2 widths apart.
vtkNew<vtkDoubleArray> Row(double width)
{
  vtkNew<vtkDoubleArray> matrices;
  matrices->SetNumberOfComponents(16);
  for (int i = 0; i < 3; ++i)
  {
    double m[16] = { 1, 0, 0, 1.2 * width * i, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1 };
    matrices->InsertNextTuple(m);
  }
  return matrices;
}

/// What a pose of the three instances is: each instance's animation and time.
struct Pose
{
  std::array<int, 3> animation;
  std::array<double, 3> time;
};

/// The CPU's posed point `point` of `rebuilt` in instance `instance` (translated by `shift`).
std::array<double, 3> CpuPoint(const tc::Atlas& atlas, const tc::RebuiltMesh& rebuilt,
  int32_t point, const Pose& pose, int instance, double shift)
{
  const int skin = tc::findAttribute(atlas, tc::kAtlasSkin);
  const float* s = rebuilt.attributes[static_cast<size_t>(skin - 1)].data() +
    tc::kSkinValues * static_cast<size_t>(point);
  tc::SkinWeights weights;
  for (int k = 0; k < tc::kMaxInfluences; ++k)
  {
    weights.joints.push_back(static_cast<int32_t>(s[k]));
    weights.weights.push_back(s[tc::kMaxInfluences + k]);
  }
  const std::array<double, 3> p = rebuilt.mesh.point(point);
  const std::vector<double> posed = tc::skinPoints({ p[0], p[1], p[2] }, weights,
    // -1 is the mapper's Animation, the first by default.
    tc::poseMatrices(atlas.rig, std::max(0, pose.animation[static_cast<size_t>(instance)]),
      pose.time[static_cast<size_t>(instance)]));
  return { posed[0] + shift * instance, posed[1], posed[2] };
}

/// Edges between distinct captured vertices (bit patterns of instance and position) that do not
/// border exactly two drawn triangles.
long long OpenEdges(vtkFloatArray* captured)
{
  using Key = std::array<uint32_t, 4>;
  std::map<std::pair<Key, Key>, int> edges;
  const auto key = [&](vtkIdType v)
  {
    const float* r = captured->GetPointer(8 * v);
    Key k{};
    std::memcpy(k.data(), r, 3 * sizeof(float));
    std::memcpy(&k[3], r + 7, sizeof(float));
    return k;
  };
  for (vtkIdType t = 0; 3 * t + 2 < captured->GetNumberOfTuples(); ++t)
  {
    if (captured->GetPointer(8 * 3 * t)[3] == -1.0f)
    {
      continue; // a padding copy, collapsed
    }
    const Key k[3] = { key(3 * t), key(3 * t + 1), key(3 * t + 2) };
    for (int e = 0; e < 3; ++e)
    {
      const Key& a = k[e];
      const Key& b = k[(e + 1) % 3];
      if (a != b && k[(e + 2) % 3] != a && k[(e + 2) % 3] != b)
      {
        ++edges[std::minmax(a, b)];
      }
    }
  }
  return std::count_if(edges.begin(), edges.end(), [](const auto& e) { return e.second != 2; });
}
} // namespace

int TestLODMapperSkinning(int argc, char* argv[])
{
  tctest::Checker check;
  const std::string data = tctest::Arg(argc, argv, "-D");
  vtkSmartPointer<vtkPolyData> mesh = tctest::ReadPrepared(data + "/meshes/bunny_npm.off");
  if (!TC_CHECK(check, mesh != nullptr))
  {
    return 1;
  }
  SkinToChain(mesh);
  vtkSmartPointer<tcGeometryImages> images =
    tctest::AtlasStages(mesh, 4 * mesh->GetNumberOfPoints());
  tc::Atlas atlas;
  std::string error;
  if (!TC_CHECK(check, tcvtk::ToAtlas(images->GetOutput(), atlas, error)) ||
    !TC_CHECK(check, tc::findAttribute(atlas, tc::kAtlasSkin) >= 0 && !atlas.rig.empty()))
  {
    std::printf("%s\n", error.c_str());
    return 1;
  }
  const vtkIdType nc = static_cast<vtkIdType>(atlas.charts.size());
  const double diagonal = atlas.inputDiagonal;
  double bounds[6];
  mesh->GetBounds(bounds);
  const double shift = 1.2 * (bounds[1] - bounds[0]);

  vtkNew<tcLODMapper> mapper;
  mapper->SetInputConnection(images->GetOutputPort());
  mapper->SetInstanceMatrices(Row(bounds[1] - bounds[0]));
  vtkNew<vtkActor> actor;
  actor->SetMapper(mapper);
  vtkNew<vtkRenderer> renderer;
  renderer->AddActor(actor);
  renderer->SetBackground(1.0, 1.0, 1.0);
  vtkNew<vtkRenderWindow> window;
  window->SetOffScreenRendering(1);
  window->SetSize(600, 300);
  window->AddRenderer(renderer);

  const std::vector<Pose> poses = { { { 0, 0, 1 }, { 0.0, 1.0, 0.75 } },
    { { 0, 1, 0 }, { 0.5, 1.5, 2.0 } }, { { 1, 0, -1 }, { 0.3, 1.7, 0.0 } } };
  vtkNew<vtkMinimalStandardRandomSequence> random;
  random->SetSeed(5);
  mapper->CaptureVerticesOn();
  for (size_t trial = 0; trial < poses.size(); ++trial)
  {
    const Pose& pose = poses[trial];
    vtkNew<vtkDoubleArray> times;
    vtkNew<vtkIntArray> animations;
    for (int i = 0; i < 3; ++i)
    {
      times->InsertNextValue(pose.time[static_cast<size_t>(i)]);
      animations->InsertNextValue(pose.animation[static_cast<size_t>(i)]);
    }
    mapper->SetInstanceTimes(times);
    mapper->SetInstanceAnimations(animations);
    std::vector<int32_t> chosen;
    vtkNew<vtkIntArray> levels;
    for (vtkIdType c = 0; c < nc; ++c)
    {
      random->Next();
      const int finest = atlas.charts[static_cast<size_t>(c)].maxLevel;
      chosen.push_back(trial == 0 ? finest : static_cast<int>(random->GetValue() * (finest + 1)));
      levels->InsertNextValue(chosen.back());
    }
    mapper->SetChartLevels(levels);
    mapper->StitchingOn();
    renderer->ResetCamera();
    window->Render();
    TC_CHECK(check, mapper->GetSkinned());
    const tc::RebuiltMesh rebuilt = tc::rebuildMesh(atlas, chosen);
    vtkFloatArray* captured = mapper->GetCapturedVertices();
    double worst = 0.0, moved = 0.0;
    long long drawn = 0, outside = 0;
    const double* b = mapper->GetBounds();
    for (vtkIdType v = 0; v < captured->GetNumberOfTuples(); ++v)
    {
      const float* r = captured->GetPointer(8 * v);
      if (r[3] == -1.0f)
      {
        continue;
      }
      ++drawn;
      const int c = static_cast<int>(r[3]), i = static_cast<int>(r[4]), j = static_cast<int>(r[5]);
      const int n = static_cast<int>(r[6]), instance = static_cast<int>(r[7]);
      const int32_t point = rebuilt.chartVertexPoint[static_cast<size_t>(
        rebuilt.chartVertexOffsets[static_cast<size_t>(c)] + tc::gridVertexIndex(n, i, j))];
      const std::array<double, 3> p = CpuPoint(atlas, rebuilt, point, pose, instance, shift);
      worst = std::max(worst, std::hypot(p[0] - r[0], p[1] - r[1], p[2] - r[2]) / diagonal);
      const std::array<double, 3> rest = rebuilt.mesh.point(point);
      moved = std::max(moved,
        std::hypot(p[0] - shift * instance - rest[0], p[1] - rest[1], p[2] - rest[2]) / diagonal);
      outside +=
        r[0] < b[0] || r[0] > b[1] || r[1] < b[2] || r[1] > b[3] || r[2] < b[4] || r[2] > b[5];
    }
    const long long open = OpenEdges(captured);
    mapper->StitchingOff();
    window->Render();
    const long long openUnstitched = OpenEdges(mapper->GetCapturedVertices());
    std::printf("pose %zu: %lld vertices drawn, largest distance to CPU skinning %.3g of the "
                "diagonal (posing moved them up to %.3g), %lld outside the bounds, open edges "
                "%lld stitched, %lld unstitched\n",
      trial, drawn, worst, moved, outside, open, openUnstitched);
    TC_CHECK(check, drawn > 0 && worst <= 1e-6 && outside == 0 && open == 0 && moved > 0.05);
    TC_CHECK(check, trial == 0 || openUnstitched > 0);
  }
  mapper->CaptureVerticesOff();
  mapper->StitchingOn();
  mapper->SetChartLevels(nullptr);

  // The posed crowd as the view chooses its levels, against the baseline.
  actor->GetProperty()->SetColor(0.85, 0.75, 0.55);
  renderer->ResetCamera();
  window->Render();
  std::printf("view-dependent: %lld triangles, %lld charts drawn of %lld\n",
    static_cast<long long>(mapper->GetTrianglesDrawn()),
    static_cast<long long>(mapper->GetChartsDrawn()), static_cast<long long>(3 * nc));
  TC_CHECK(check, mapper->GetChartsDrawn() == 3 * nc);
  const int image = vtkRegressionTestImage(window);
  TC_CHECK(check, image != vtkRegressionTester::FAILED);
  return check.failures == 0 ? 0 : 1;
}
