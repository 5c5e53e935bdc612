// SPDX-License-Identifier: BSD-3-Clause
// Per-frame level-of-detail selection (Feng et al. 2010, section 6.1, eqs. (6) and (7)) and the
// draw list, through the core alone (no VTK): tc::selectLevels on 100K synthetic charts (random
// boxes in a unit cube, seen by a perspective camera from inside the cube's range so that some
// are culled and some straddle the eye plane), in area and error mode, with and without
// culling, on one thread and on all; then 400 instances of a 518-chart model (selection per
// instance and tc::buildDrawList); then 100K synthetic skinned boxes (4 random joints of 64 per
// box, random weights per corner) posed by tc::poseLodBoxes and selected. Prints the median of 50
// calls and the goal of the task next to it.
//
//   tc_bench_lod_selection
#include "tc/gim/lod_selection.h"
#include "tc/skinning/skin.h"
#include "tc/skinning/skinned_boxes.h"

#include "view_matrices.h"

#include <tbb/info.h>
#include <tbb/task_arena.h>

#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <cstdint>
#include <functional>
#include <iomanip>
#include <iostream>
#include <limits>
#include <random>
#include <sstream>
#include <string>
#include <vector>

namespace
{
constexpr double kMaxMilliseconds = 1.0;        // goal: <= 1 ms per call for 100K charts
constexpr double kMaxSkinnedMilliseconds = 2.0; // goal: <= 2 ms to pose and select 100K charts
constexpr int32_t kJoints = 64;
constexpr int32_t kCharts = 100000;
constexpr int32_t kInstances = 400;
constexpr int32_t kModelCharts = 518;
constexpr int kCalls = 50;
constexpr double kWidth = 1920.0, kHeight = 1080.0;

const char* mark(bool ok)
{
  return ok ? "ok" : "MISSED";
}

std::string fixed(double value, int digits)
{
  std::ostringstream s;
  s << std::fixed << std::setprecision(digits) << value;
  return s.str();
}

/// Median wall-clock milliseconds of kCalls calls of `work`, after one call to warm up.
double medianMilliseconds(const std::function<void()>& work)
{
  work();
  std::vector<double> ms(kCalls);
  for (double& t : ms)
  {
    const auto start = std::chrono::steady_clock::now();
    work();
    t = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
  }
  std::nth_element(ms.begin(), ms.begin() + kCalls / 2, ms.end());
  return ms[kCalls / 2];
}

using tctest::Matrix;
using tctest::multiply;

/// OpenGL perspective times look-at, row-major (as gluPerspective * gluLookAt).
Matrix camera(const std::array<double, 3>& eye, const std::array<double, 3>& target,
  double fovyDegrees, double aspect, double zNear, double zFar)
{
  return multiply(
    tctest::perspective(fovyDegrees, aspect, zNear, zFar), tctest::lookAt(eye, target));
}

/// A uniformly random orthonormal frame (rows): Gram-Schmidt on two Gaussian vectors of `normal`.
std::array<std::array<double, 3>, 3> randomFrame(
  std::mt19937& rng, std::normal_distribution<double>& normal)
{
  std::array<std::array<double, 3>, 3> e{};
  const auto normalize = [](std::array<double, 3>& v)
  {
    const double l = std::sqrt(v[0] * v[0] + v[1] * v[1] + v[2] * v[2]);
    for (double& x : v)
    {
      x /= l;
    }
  };
  for (int k = 0; k < 2; ++k)
  {
    for (double& v : e[k])
    {
      v = normal(rng);
    }
  }
  normalize(e[0]);
  const double d = e[0][0] * e[1][0] + e[0][1] * e[1][1] + e[0][2] * e[1][2];
  for (int i = 0; i < 3; ++i)
  {
    e[1][i] -= d * e[0][i];
  }
  normalize(e[1]);
  e[2] = { e[0][1] * e[1][2] - e[0][2] * e[1][1], e[0][2] * e[1][0] - e[0][0] * e[1][2],
    e[0][0] * e[1][1] - e[0][1] * e[1][0] };
  return e;
}

/// `count` charts with random boxes in the unit cube: c0 uniform, three orthogonal axes of
/// lengths `minSize` .. `maxSize` in a random orientation, maxLevel 3 .. 7, measured errors
/// halving per level, neighbours c + 1, c + 2, c + 3 (mod count).
tc::LodCharts syntheticCharts(int32_t count, double minSize, double maxSize, uint32_t seed)
{
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  std::normal_distribution<double> normal(0.0, 1.0);
  std::uniform_int_distribution<int32_t> level(3, 7);
  tc::LodCharts charts;
  charts.stride = 8;
  charts.box.resize(12 * static_cast<size_t>(count));
  charts.worldArea.resize(static_cast<size_t>(count));
  charts.maxLevel.resize(static_cast<size_t>(count));
  charts.levelError.assign(static_cast<size_t>(count) * static_cast<size_t>(charts.stride),
    std::numeric_limits<float>::infinity());
  charts.neighbor.resize(3 * static_cast<size_t>(count));
  for (int32_t c = 0; c < count; ++c)
  {
    const std::array<std::array<double, 3>, 3> e = randomFrame(rng, normal);
    std::array<double, 3> length{};
    float* b = charts.box.data() + 12 * static_cast<size_t>(c);
    for (int i = 0; i < 3; ++i)
    {
      b[i] = static_cast<float>(unit(rng));
    }
    for (int k = 0; k < 3; ++k)
    {
      length[static_cast<size_t>(k)] = minSize + (maxSize - minSize) * unit(rng);
      for (int i = 0; i < 3; ++i)
      {
        b[3 + 3 * k + i] = static_cast<float>(length[static_cast<size_t>(k)] * e[k][i]);
      }
    }
    // Eq. (6) before projection for orthogonal axes: the three face areas.
    charts.worldArea[static_cast<size_t>(c)] =
      static_cast<float>(length[0] * length[1] + length[0] * length[2] + length[1] * length[2]);
    const int32_t maxLevel = level(rng);
    charts.maxLevel[static_cast<size_t>(c)] = maxLevel;
    for (int32_t l = 0; l <= maxLevel; ++l)
    {
      charts.levelError[static_cast<size_t>(c) * 8 + static_cast<size_t>(l)] =
        static_cast<float>(0.1 * length[0] * std::ldexp(1.0, -l));
    }
    for (int k = 0; k < 3; ++k)
    {
      charts.neighbor[3 * static_cast<size_t>(c) + static_cast<size_t>(k)] = (c + k + 1) % count;
    }
  }
  return charts;
}

/// `count` skinned boxes shaped as syntheticCharts' (c0 in the unit cube, orthogonal axes of
/// 0.002 .. 0.02), each moved by 4 distinct random joints of kJoints with random weights per
/// corner (the worst case of the layout: every joint slot used).
std::vector<tc::SkinnedBox> syntheticSkinnedBoxes(int32_t count, uint32_t seed)
{
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  std::normal_distribution<double> normal(0.0, 1.0);
  std::vector<tc::SkinnedBox> boxes(static_cast<size_t>(count));
  for (tc::SkinnedBox& box : boxes)
  {
    const auto e = randomFrame(rng, normal);
    for (size_t i = 0; i < 3; ++i)
    {
      box.corners[i] = unit(rng);
    }
    for (size_t k = 0; k < 3; ++k)
    {
      const double length = 0.002 + 0.018 * unit(rng);
      for (size_t i = 0; i < 3; ++i)
      {
        box.corners[3 * (k + 1) + i] = box.corners[i] + length * e[k][i];
      }
    }
    std::array<int32_t, 4> joints{};
    for (size_t m = 0; m < 4; ++m)
    {
      do
      {
        joints[m] = static_cast<int32_t>(rng() % kJoints);
      } while (std::find(joints.begin(), joints.begin() + static_cast<std::ptrdiff_t>(m),
                 joints[m]) != joints.begin() + static_cast<std::ptrdiff_t>(m));
    }
    for (tc::PointSkin& skin : box.skin)
    {
      double sum = 0.0;
      std::array<double, 4> w{};
      for (double& x : w)
      {
        x = 0.05 + unit(rng);
        sum += x;
      }
      for (size_t m = 0; m < 4; ++m)
      {
        skin.joints[m] = joints[m];
        skin.weights[m] = static_cast<float>(w[m] / sum);
      }
    }
  }
  return boxes;
}

/// Skinning matrices of kJoints joints: each a rotation by up to 20 degrees about a random axis
/// through a random point of the unit cube, so that the posed boxes stay about the cube.
std::vector<tc::Matrix4> syntheticPose(uint32_t seed)
{
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  std::normal_distribution<double> normal(0.0, 1.0);
  std::vector<tc::Matrix4> matrices;
  for (int32_t j = 0; j < kJoints; ++j)
  {
    const auto e = randomFrame(rng, normal);
    const double angle = 20.0 * unit(rng) * 3.14159265358979323846 / 180.0;
    const double c = std::cos(angle), s = std::sin(angle);
    // Rotation about e[0]: R = e0 e0^T + c (I - e0 e0^T) + s [e0]x.
    const std::array<double, 3>& a = e[0];
    const double cross[3][3] = { { 0, -a[2], a[1] }, { a[2], 0, -a[0] }, { -a[1], a[0], 0 } };
    tc::Matrix4 m = tc::identityMatrix();
    const std::array<double, 3> pivot{ unit(rng), unit(rng), unit(rng) };
    for (size_t r = 0; r < 3; ++r)
    {
      double shift = pivot[r];
      for (size_t k = 0; k < 3; ++k)
      {
        const double value = a[r] * a[k] * (1.0 - c) + (r == k ? c : 0.0) + s * cross[r][k];
        m[4 * r + k] = value;
        shift -= value * pivot[k];
      }
      m[4 * r + 3] = shift;
    }
    matrices.push_back(m);
  }
  return matrices;
}

/// Drawn charts per level, e.g. "0:12 1:40 ...", and the culled ones.
std::string histogram(const std::vector<int32_t>& levels, int32_t stride)
{
  std::vector<int64_t> count(static_cast<size_t>(stride) + 1, 0);
  for (const int32_t l : levels)
  {
    ++count[static_cast<size_t>(l + 1)];
  }
  std::ostringstream s;
  s << "culled " << count[0];
  for (int32_t d = 0; d < stride; ++d)
  {
    s << ", " << d << ": " << count[static_cast<size_t>(d) + 1];
  }
  return s.str();
}

/// Posing 100K skinned boxes by one instance's palette (tc::poseLodBoxes) and selecting their
/// levels (default options: error mode, culling) on the posed boxes, as the renderer does per
/// skinned instance and frame.
void benchSkinnedBoxes(
  const tc::LodCharts& charts, const tc::LodView& view, tbb::task_arena& single, int threads)
{
  const tc::LodSkinnedBoxes boxes =
    tc::LodSkinnedBoxes::fromBoxes(syntheticSkinnedBoxes(kCharts, 3));
  std::vector<float> palette;
  tc::appendPaletteRows(syntheticPose(4), palette);
  tc::LodCharts posed = charts;
  std::vector<int32_t> levels(static_cast<size_t>(kCharts));
  const tc::LodOptions options;
  const auto pose = [&]
  { tc::poseLodBoxes(boxes, palette.data(), kJoints, posed.box.data(), posed.worldArea.data()); };
  const auto poseSelect = [&]
  {
    pose();
    tc::selectLevels(posed, view, options, levels.data());
  };
  poseSelect();
  std::cout << "\n== skinned boxes: pose (tc::poseLodBoxes) + select, " << kCharts
            << " synthetic charts, 4 of " << kJoints << " joints per box\n";
  std::cout << "levels (error 1 px, culling): " << histogram(levels, posed.stride) << "\n";
  std::cout << "ms per frame (median of " << kCalls << ")  1 thread   " << threads << " threads\n";
  const double poseOne = medianMilliseconds([&] { single.execute(pose); });
  const double poseAll = medianMilliseconds(pose);
  const auto select = [&] { tc::selectLevels(posed, view, options, levels.data()); };
  const double selectOne = medianMilliseconds([&] { single.execute(select); });
  const double selectAll = medianMilliseconds(select);
  const double one = medianMilliseconds([&] { single.execute(poseSelect); });
  const double all = medianMilliseconds(poseSelect);
  std::cout << "  " << std::left << std::setw(26) << "pose" << std::right << std::setw(8)
            << fixed(poseOne, 3) << std::setw(11) << fixed(poseAll, 3) << "\n";
  std::cout << "  " << std::left << std::setw(26) << "select (posed boxes)" << std::right
            << std::setw(8) << fixed(selectOne, 3) << std::setw(11) << fixed(selectAll, 3) << "\n";
  std::cout << "  " << std::left << std::setw(26) << "pose + select" << std::right << std::setw(8)
            << fixed(one, 3) << std::setw(11) << fixed(all, 3) << "\n";
  std::cout << "goal <= 2 ms to pose and select 100K charts: "
            << mark(all <= kMaxSkinnedMilliseconds) << " (" << fixed(all, 3) << " ms on " << threads
            << " threads, " << fixed(one, 3)
            << " ms on 1 thread: " << mark(one <= kMaxSkinnedMilliseconds) << ")\n";
}
} // namespace

int main()
{
  const int threads = tbb::info::default_concurrency();
  tbb::task_arena single(1);

  // 100K charts in the unit cube, the eye inside the cube's range (some boxes behind it, some
  // around it, some outside the side planes).
  const tc::LodCharts charts = syntheticCharts(kCharts, 0.002, 0.02, 1);
  tc::LodView view;
  view.worldToClip =
    camera({ 0.5, 0.55, 0.9 }, { 0.5, 0.5, 0.0 }, 60.0, kWidth / kHeight, 0.01, 10.0);
  view.width = kWidth;
  view.height = kHeight;
  std::vector<int32_t> levels(static_cast<size_t>(kCharts));

  std::cout << "\n== LOD selection (eqs. 6, 7): " << kCharts << " synthetic charts, " << kWidth
            << " x " << kHeight << ", perspective camera\n";
  struct Mode
  {
    const char* name;
    tc::LodOptions options;
  };
  tc::LodOptions area;
  tc::LodOptions areaNoCull;
  areaNoCull.cull = false;
  tc::LodOptions error;
  error.errorPixels = 0.5;
  tc::LodOptions errorNoCull = error;
  errorNoCull.cull = false;
  const std::vector<Mode> modes{ { "area, culling", area }, { "area, no culling", areaNoCull },
    { "error 0.5 px, culling", error }, { "error 0.5 px, no culling", errorNoCull } };

  for (const Mode& mode : modes)
  {
    tc::selectLevels(charts, view, mode.options, levels.data());
    std::cout << "levels (" << mode.name << "): " << histogram(levels, charts.stride) << "\n";
  }
  std::cout << "ms per call (median of " << kCalls << ")  1 thread   " << threads << " threads\n";
  double worstSingle = 0.0, worstParallel = 0.0;
  for (const Mode& mode : modes)
  {
    const auto call = [&] { tc::selectLevels(charts, view, mode.options, levels.data()); };
    const double one = medianMilliseconds([&] { single.execute(call); });
    const double all = medianMilliseconds(call);
    worstSingle = std::max(worstSingle, one);
    worstParallel = std::max(worstParallel, all);
    std::cout << "  " << std::left << std::setw(26) << mode.name << std::right << std::setw(8)
              << fixed(one, 3) << std::setw(11) << fixed(all, 3) << "\n";
  }
  std::cout << "goal <= 1 ms for 100K charts: " << mark(worstParallel <= kMaxMilliseconds)
            << " (worst " << fixed(worstParallel, 3) << " ms on " << threads << " threads, "
            << fixed(worstSingle, 3) << " ms on 1 thread: " << mark(worstSingle <= kMaxMilliseconds)
            << ")\n";

  // 400 instances of one 518-chart model (boxes of 0.1 .. 0.4 in a unit cube) on a 20 x 20
  // grid 1.5 apart, seen at a slant from beyond one edge: near instances fine, far ones coarse.
  // The model matrix of each instance is a translation, so its world-to-clip matrix is VP * T.
  const tc::LodCharts model = syntheticCharts(kModelCharts, 0.1, 0.4, 2);
  const Matrix viewProjection =
    camera({ 15.0, 2.0, 30.5 }, { 15.0, 0.0, 20.0 }, 60.0, kWidth / kHeight, 0.1, 100.0);
  std::vector<tc::LodView> instanceViews(static_cast<size_t>(kInstances));
  for (int32_t r = 0; r < kInstances; ++r)
  {
    const double tx = 1.5 * (r % 20), tz = 1.5 * (r / 20);
    const Matrix translation{ 1, 0, 0, tx, 0, 1, 0, 0, 0, 0, 1, tz, 0, 0, 0, 1 };
    tc::LodView& v = instanceViews[static_cast<size_t>(r)];
    v.worldToClip = multiply(viewProjection, translation);
    v.width = kWidth;
    v.height = kHeight;
  }
  std::vector<int32_t> instanceLevels(static_cast<size_t>(kInstances) * kModelCharts);
  const auto selectAll = [&]
  {
    for (int32_t r = 0; r < kInstances; ++r)
    {
      tc::selectLevels(model, instanceViews[static_cast<size_t>(r)], area,
        instanceLevels.data() + static_cast<size_t>(r) * kModelCharts);
    }
  };
  tc::LodDrawList list;
  const double selectMs = medianMilliseconds(selectAll);
  const double listMs =
    medianMilliseconds([&] { tc::buildDrawList(model, instanceLevels.data(), kInstances, list); });
  std::cout << "\n== draw list: " << kInstances << " instances x " << kModelCharts << " charts\n";
  std::cout << "ms per frame (median of " << kCalls << ")\n";
  std::cout << "  " << std::left << std::setw(26) << "selectLevels x 400" << std::right
            << fixed(selectMs, 3) << "\n";
  std::cout << "  " << std::left << std::setw(26) << "buildDrawList" << std::right
            << fixed(listMs, 3) << "\n";
  std::cout << "entries: " << list.entries.size() / 4 << " of "
            << int64_t(kInstances) * kModelCharts << ", grid triangles: " << list.triangles
            << ", per level:";
  for (size_t d = 0; d < list.chartsPerLevel.size(); ++d)
  {
    std::cout << " " << d << ": " << list.chartsPerLevel[d];
  }
  std::cout << "\n";
  benchSkinnedBoxes(charts, view, single, threads);
  return 0;
}
