// SPDX-License-Identifier: BSD-3-Clause
#include "tc/skinning/skinned_boxes.h"

#include "skinning/weight_fit.h"

#include "tc/common/errors.h"

#include <Eigen/Dense>

#include <algorithm>
#include <cmath>
#include <map>
#include <numeric>

namespace tc
{
namespace
{
using Vec3 = std::array<double, 3>;

// A chart's finest-level samples: bind positions and skins.
struct ChartSamples
{
  std::vector<Vec3> points;
  std::vector<PointSkin> skins;
};

// An orthonormal box: centre, axes (rows) and half extents.
struct Obb
{
  Eigen::Vector3d center = Eigen::Vector3d::Zero();
  Eigen::Matrix3d axes = Eigen::Matrix3d::Identity();
  Eigen::Vector3d half = Eigen::Vector3d::Zero();
};

Eigen::Vector3d toEigen(const Vec3& p)
{
  return Eigen::Vector3d(p[0], p[1], p[2]);
}

ChartSamples chartSamples(const Atlas& atlas, int32_t chart, int32_t skinAttribute)
{
  ChartSamples s;
  const int32_t d = atlas.charts[static_cast<size_t>(chart)].maxLevel;
  const int32_t n = 1 << d;
  for (int32_t j = 0; j <= n; ++j)
  {
    for (int32_t i = 0; i + j <= n; ++i)
    {
      const float* p = atlasSample(atlas, chart, 0, d, i, j);
      const float* k = atlasSample(atlas, chart, skinAttribute, d, i, j);
      s.points.push_back({ p[0], p[1], p[2] });
      PointSkin skin;
      for (int m = 0; m < kMaxInfluences; ++m)
      {
        skin.joints[static_cast<size_t>(m)] = static_cast<int32_t>(k[m]);
        skin.weights[static_cast<size_t>(m)] = k[kMaxInfluences + m];
      }
      s.skins.push_back(skin);
    }
  }
  return s;
}

Vec3 skinPoint(const Vec3& p, const PointSkin& skin, const std::vector<Matrix4>& matrices)
{
  Vec3 q{ 0.0, 0.0, 0.0 };
  for (int m = 0; m < kMaxInfluences; ++m)
  {
    const double w = skin.weights[static_cast<size_t>(m)];
    if (w == 0.0)
    {
      continue;
    }
    const Matrix4& t = matrices[static_cast<size_t>(skin.joints[static_cast<size_t>(m)])];
    for (int r = 0; r < 3; ++r)
    {
      q[r] += w * (t[4 * r] * p[0] + t[4 * r + 1] * p[1] + t[4 * r + 2] * p[2] + t[4 * r + 3]);
    }
  }
  return q;
}

std::vector<Vec3> poseSamples(const ChartSamples& s, const std::vector<Matrix4>& matrices)
{
  std::vector<Vec3> posed(s.points.size());
  for (size_t v = 0; v < posed.size(); ++v)
  {
    posed[v] = skinPoint(s.points[v], s.skins[v], matrices);
  }
  return posed;
}

// The PCA box of `points`: axes the eigenvectors of their covariance, every half extent at
// least minHalf.
Obb pcaBox(const std::vector<Vec3>& points, double minHalf)
{
  Obb box;
  for (const Vec3& p : points)
  {
    box.center += toEigen(p);
  }
  box.center /= static_cast<double>(points.size());
  Eigen::Matrix3d cov = Eigen::Matrix3d::Zero();
  for (const Vec3& p : points)
  {
    const Eigen::Vector3d x = toEigen(p) - box.center;
    cov += x * x.transpose();
  }
  box.axes = Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d>(cov).eigenvectors().transpose();
  Eigen::Vector3d lo = Eigen::Vector3d::Constant(INFINITY), hi = -lo;
  for (const Vec3& p : points)
  {
    const Eigen::Vector3d u = box.axes * (toEigen(p) - box.center);
    lo = lo.cwiseMin(u);
    hi = hi.cwiseMax(u);
  }
  box.center += box.axes.transpose() * (0.5 * (lo + hi));
  box.half = (0.5 * (hi - lo)).cwiseMax(minHalf);
  return box;
}

double obbVolume(const Obb& box)
{
  return 8.0 * box.half.prod();
}

// Padding of a bind box per side, in bind lengths: (below, above) along axis 0, 1, 2.
using SidePads = std::array<double, 6>;

// AtlasChart::box layout of `box` grown by `pads`.
std::array<double, 12> boxCorners(const Obb& box, const SidePads& pads)
{
  Eigen::Vector3d half, center = box.center;
  for (int axis = 0; axis < 3; ++axis)
  {
    const double below = pads[static_cast<size_t>(2 * axis)];
    const double above = pads[static_cast<size_t>(2 * axis + 1)];
    half(axis) = box.half(axis) + 0.5 * (below + above);
    center += 0.5 * (above - below) * box.axes.row(axis).transpose();
  }
  const Eigen::Vector3d c0 = center - box.axes.transpose() * half;
  std::array<double, 12> corners{};
  for (int r = 0; r < 3; ++r)
  {
    corners[static_cast<size_t>(r)] = c0(r);
    for (int axis = 0; axis < 3; ++axis)
    {
      corners[static_cast<size_t>(3 * (axis + 1) + r)] =
        c0(r) + 2.0 * half(axis) * box.axes(axis, r);
    }
  }
  return corners;
}

// Corner m (bit order) of AtlasChart::box-style corners.
Vec3 boxCorner(const std::array<double, 12>& corners, int m)
{
  Vec3 p{ corners[0], corners[1], corners[2] };
  for (int axis = 0; axis < 3; ++axis)
  {
    if (m >> axis & 1)
    {
      for (int r = 0; r < 3; ++r)
      {
        p[r] += corners[static_cast<size_t>(3 * (axis + 1) + r)] - corners[static_cast<size_t>(r)];
      }
    }
  }
  return p;
}

// The chart's dominant joints: the (at most 4) largest total weights over its samples,
// largest first.
std::vector<int32_t> dominantJoints(const ChartSamples& s)
{
  std::map<int32_t, double> total;
  for (const PointSkin& skin : s.skins)
  {
    for (int m = 0; m < kMaxInfluences; ++m)
    {
      if (skin.weights[static_cast<size_t>(m)] > 0.0f)
      {
        total[skin.joints[static_cast<size_t>(m)]] += skin.weights[static_cast<size_t>(m)];
      }
    }
  }
  std::vector<std::pair<int32_t, double>> order(total.begin(), total.end());
  std::stable_sort(order.begin(), order.end(),
    [](const std::pair<int32_t, double>& a, const std::pair<int32_t, double>& b)
    { return a.second > b.second; });
  std::vector<int32_t> joints;
  for (size_t k = 0; k < order.size() && k < static_cast<size_t>(kMaxInfluences); ++k)
  {
    joints.push_back(order[k].first);
  }
  if (joints.empty())
  {
    joints.push_back(0);
  }
  return joints;
}

Eigen::Matrix3d linearPart(const Matrix4& t)
{
  Eigen::Matrix3d l;
  for (int r = 0; r < 3; ++r)
  {
    for (int c = 0; c < 3; ++c)
    {
      l(r, c) = t[static_cast<size_t>(4 * r + c)];
    }
  }
  return l;
}

// The affine motion (L, t: y = L x + t) that carries the bind samples to their posed positions
// best in least squares, with a faint pull of L towards `prior` (the dominant joint's linear
// part), which only decides the directions the samples do not span (a flat chart's normal).
std::pair<Eigen::Matrix3d, Eigen::Vector3d> chartMotion(
  const std::vector<Vec3>& bind, const std::vector<Vec3>& posed, const Eigen::Matrix3d& prior)
{
  Eigen::Vector3d mx = Eigen::Vector3d::Zero(), my = Eigen::Vector3d::Zero();
  for (size_t v = 0; v < bind.size(); ++v)
  {
    mx += toEigen(bind[v]);
    my += toEigen(posed[v]);
  }
  mx /= static_cast<double>(bind.size());
  my /= static_cast<double>(bind.size());
  Eigen::Matrix3d xx = Eigen::Matrix3d::Zero(), yx = Eigen::Matrix3d::Zero();
  for (size_t v = 0; v < bind.size(); ++v)
  {
    const Eigen::Vector3d x = toEigen(bind[v]) - mx;
    xx += x * x.transpose();
    yx += (toEigen(posed[v]) - my) * x.transpose();
  }
  const double lambda = 1e-6 * xx.trace() + 1e-300;
  const Eigen::Matrix3d l = (xx + lambda * Eigen::Matrix3d::Identity())
                              .ldlt()
                              .solve((yx + lambda * prior).transpose())
                              .transpose();
  return { l, my - l * mx };
}

// Step 2: the weights of `joints` (>= 0, sum 1) whose blend carries `corner` closest to the
// targets over all frames (simplexLeastSquares of the 3 #K residuals).
PointSkin fitCornerSkin(const std::vector<Vec3>& corners, const std::vector<int32_t>& joints,
  const std::vector<std::vector<Matrix4>>& frames,
  const std::vector<std::vector<Eigen::Vector3d>>& targets)
{
  const int m = static_cast<int>(joints.size());
  Eigen::MatrixXd g = Eigen::MatrixXd::Zero(m, m);
  Eigen::VectorXd h = Eigen::VectorXd::Zero(m);
  for (size_t k = 0; k < frames.size(); ++k)
  {
    for (size_t c = 0; c < corners.size(); ++c)
    {
      Eigen::MatrixXd p(3, m);
      for (int b = 0; b < m; ++b)
      {
        PointSkin one;
        one.joints[0] = joints[static_cast<size_t>(b)];
        one.weights[0] = 1.0f;
        p.col(b) = toEigen(skinPoint(corners[c], one, frames[k]));
      }
      g += p.transpose() * p;
      h += p.transpose() * targets[k][c];
    }
  }
  g += (1e-9 * g.trace() + 1e-300) * Eigen::MatrixXd::Identity(m, m);
  const Eigen::VectorXd w = detail::proxy::simplexLeastSquares(g, h, 0);
  PointSkin skin;
  for (int b = 0; b < m; ++b)
  {
    skin.joints[static_cast<size_t>(b)] = joints[static_cast<size_t>(b)];
    skin.weights[static_cast<size_t>(b)] = static_cast<float>(std::max(0.0, w(b)));
  }
  const float sum = std::accumulate(skin.weights.begin(), skin.weights.end(), 0.0f);
  for (float& x : skin.weights)
  {
    x /= sum;
  }
  return skin;
}

// The fitted frames' times of one animation: framesPerAnimation even ones, plus the key times
// when there are fewer of those.
std::vector<double> frameTimes(const Animation& animation, int count, bool withKeys)
{
  std::vector<double> times;
  for (int k = 0; k < count; ++k)
  {
    times.push_back(count == 1 ? 0.0 : animation.duration * k / (count - 1));
  }
  const std::vector<double> keys = animationKeyTimes(animation);
  if (withKeys && keys.size() < static_cast<size_t>(count))
  {
    times.insert(times.end(), keys.begin(), keys.end());
  }
  std::sort(times.begin(), times.end());
  times.erase(std::unique(times.begin(), times.end()), times.end());
  return times;
}

// Skinning matrices of every frame of every animation (the rest pose when there is none).
std::vector<std::vector<Matrix4>> frameMatrices(const Rig& rig, int count, bool withKeys)
{
  std::vector<std::vector<Matrix4>> frames;
  if (rig.animations.empty())
  {
    frames.push_back(skinningMatrices(rig.skeleton, jointGlobals(rig.skeleton, nullptr, 0.0)));
  }
  for (const Animation& animation : rig.animations)
  {
    for (double t : frameTimes(animation, count, withKeys))
    {
      frames.push_back(skinningMatrices(rig.skeleton, jointGlobals(rig.skeleton, &animation, t)));
    }
  }
  return frames;
}

// Whether every posed sample of every frame lies in the posed box (boxContains, no tolerance).
bool holdsAll(const SkinnedBox& box, const std::vector<std::vector<Matrix4>>& frames,
  const std::vector<std::vector<Vec3>>& posed)
{
  for (size_t k = 0; k < frames.size(); ++k)
  {
    const BoxFrame frame = posedBoxFrame(poseBox(box, frames[k]));
    for (const Vec3& p : posed[k])
    {
      if (!boxContains(frame, p))
      {
        return false;
      }
    }
  }
  return true;
}

// Step 3: the smallest padding (to 1/4096 of the diagonal, by doubling then bisection) of every
// side of the bind box for which the posed box holds every posed sample of every frame. One
// padding for all sides: growing sides on their own (by how far samples stick out of each) does
// not converge, since every grown corner moves the posed axes too.
double requiredPadding(SkinnedBox& box, const Obb& bind, double diagonal,
  const std::vector<std::vector<Matrix4>>& frames, const std::vector<std::vector<Vec3>>& posed)
{
  const auto holds = [&](double pad)
  {
    box.corners = boxCorners(bind, SidePads{ pad, pad, pad, pad, pad, pad });
    return holdsAll(box, frames, posed);
  };
  if (holds(0.0))
  {
    return 0.0;
  }
  double lo = 0.0, hi = diagonal / 256.0;
  while (!holds(hi))
  {
    lo = hi;
    hi *= 2.0;
    if (hi > 64.0 * diagonal)
    {
      throw InputError("fitSkinnedBoxes: a chart's skinned box cannot hold its samples (its "
                       "corners' skins do not follow the chart; check the Skin attribute)");
    }
  }
  while (hi - lo > diagonal / 4096.0)
  {
    const double mid = 0.5 * (lo + hi);
    (holds(mid) ? hi : lo) = mid;
  }
  return hi;
}

// One chart: (1) bind box by PCA of the bind samples, (2) per corner the weights of the chart's
// dominant joints that follow the chart's best affine motion, (3) growth until it holds every
// sample of the fitted and checked frames, plus the margin on every side; then its volume
// ratios at the fitted frames.
SkinnedBox fitChart(const ChartSamples& s, const std::vector<std::vector<Matrix4>>& fit,
  const std::vector<std::vector<Matrix4>>& check, const SkinnedBoxOptions& options,
  std::vector<double>& ratios)
{
  Obb bind = pcaBox(s.points, 0.0);
  const double diagonal = std::max(2.0 * bind.half.norm(), 1e-300);
  bind.half = bind.half.cwiseMax(0.5 * options.minExtent * diagonal);
  const std::vector<int32_t> joints = dominantJoints(s);
  std::vector<std::vector<Vec3>> posed;
  for (const std::vector<Matrix4>& matrices : fit)
  {
    posed.push_back(poseSamples(s, matrices));
  }
  SkinnedBox box;
  box.corners = boxCorners(bind, SidePads{});
  std::vector<std::pair<Eigen::Matrix3d, Eigen::Vector3d>> motions;
  for (size_t k = 0; k < fit.size(); ++k)
  {
    motions.push_back(chartMotion(s.points, posed[k], linearPart(fit[k][joints[0]])));
  }
  for (int m = 0; m < 8; m += 2)
  {
    // Corners m and m + 1 lie across the thinnest axis (PCA's first): one skin for both, so
    // that the posed thin edge is the blend of rotations of the bind one, never a difference of
    // two blends much longer than the chart is thick.
    const std::vector<Vec3> pair = { boxCorner(box.corners, m), boxCorner(box.corners, m + 1) };
    std::vector<std::vector<Eigen::Vector3d>> targets(fit.size());
    for (size_t k = 0; k < fit.size(); ++k)
    {
      for (const Vec3& corner : pair)
      {
        targets[k].push_back(motions[k].first * toEigen(corner) + motions[k].second);
      }
    }
    box.skin[static_cast<size_t>(m)] = fitCornerSkin(pair, joints, fit, targets);
    box.skin[static_cast<size_t>(m + 1)] = box.skin[static_cast<size_t>(m)];
  }
  std::vector<std::vector<Matrix4>> all = fit;
  all.insert(all.end(), check.begin(), check.end());
  for (const std::vector<Matrix4>& matrices : check)
  {
    posed.push_back(poseSamples(s, matrices));
  }
  const double pad = (1.0 + options.padding) * requiredPadding(box, bind, diagonal, all, posed);
  const SidePads pads{ pad, pad, pad, pad, pad, pad };
  box.corners = boxCorners(bind, pads);
  for (size_t k = 0; k < fit.size(); ++k)
  {
    const double tight = obbVolume(pcaBox(posed[k], 0.5 * options.minExtent * diagonal));
    ratios.push_back(posedBoxFrame(poseBox(box, fit[k])).volume / tight);
  }
  return box;
}
} // namespace

std::array<std::array<double, 3>, 8> poseBox(
  const SkinnedBox& box, const std::vector<Matrix4>& matrices)
{
  std::array<Vec3, 8> posed{};
  for (int m = 0; m < 8; ++m)
  {
    posed[static_cast<size_t>(m)] =
      skinPoint(boxCorner(box.corners, m), box.skin[static_cast<size_t>(m)], matrices);
  }
  return posed;
}

BoxFrame posedBoxFrame(const std::array<std::array<double, 3>, 8>& corners)
{
  BoxFrame frame;
  frame.pivot = corners[0];
  Eigen::Matrix3d axes;
  axes.col(0) = toEigen(corners[1]) - toEigen(corners[0]);
  axes.col(1) = toEigen(corners[2]) - toEigen(corners[0]);
  axes.col(2) = toEigen(corners[4]) - toEigen(corners[0]);
  const Eigen::Matrix3d inverse = axes.inverse();
  Eigen::Vector3d lo = Eigen::Vector3d::Constant(INFINITY), hi = -lo;
  for (const Vec3& q : corners)
  {
    const Eigen::Vector3d u = inverse * (toEigen(q) - toEigen(corners[0]));
    lo = lo.cwiseMin(u);
    hi = hi.cwiseMax(u);
  }
  for (int r = 0; r < 3; ++r)
  {
    frame.lo[static_cast<size_t>(r)] = lo(r);
    frame.hi[static_cast<size_t>(r)] = hi(r);
    for (int c = 0; c < 3; ++c)
    {
      frame.inverseAxes[static_cast<size_t>(3 * r + c)] = inverse(r, c);
    }
  }
  frame.volume = std::abs(axes.determinant()) * (hi - lo).prod();
  return frame;
}

bool boxContains(const BoxFrame& frame, const std::array<double, 3>& point, double tolerance)
{
  const Vec3 x{ point[0] - frame.pivot[0], point[1] - frame.pivot[1], point[2] - frame.pivot[2] };
  for (size_t r = 0; r < 3; ++r)
  {
    const double u = frame.inverseAxes[3 * r] * x[0] + frame.inverseAxes[3 * r + 1] * x[1] +
      frame.inverseAxes[3 * r + 2] * x[2];
    const double slack = tolerance * (frame.hi[r] - frame.lo[r]);
    if (!(u >= frame.lo[r] - slack && u <= frame.hi[r] + slack))
    {
      return false;
    }
  }
  return true;
}

SkinnedBoxesResult fitSkinnedBoxes(
  const Atlas& atlas, const SkinnedBoxOptions& options, const Progress& progress)
{
  const int32_t skin = findAttribute(atlas, kAtlasSkin);
  if (skin < 0 || atlas.rig.empty())
  {
    throw InputError("fitSkinnedBoxes: the atlas is not skinned (it needs a Skin attribute and a "
                     "rig; build it from a skinned input)");
  }
  const std::vector<std::vector<Matrix4>> fit =
    frameMatrices(atlas.rig, std::max(1, options.framesPerAnimation), true);
  const std::vector<std::vector<Matrix4>> check =
    frameMatrices(atlas.rig, std::max(0, options.checkFramesPerAnimation), false);
  SkinnedBoxesResult result;
  result.frames = static_cast<int64_t>(fit.size());
  std::vector<double> ratios;
  for (size_t c = 0; c < atlas.charts.size(); ++c)
  {
    progress.report(static_cast<double>(c) / static_cast<double>(atlas.charts.size()));
    const ChartSamples s = chartSamples(atlas, static_cast<int32_t>(c), skin);
    result.boxes.push_back(fitChart(s, fit, check, options, ratios));
  }
  for (double r : ratios)
  {
    result.meanVolumeRatio += r / static_cast<double>(ratios.size());
    result.largestVolumeRatio = std::max(result.largestVolumeRatio, r);
  }
  if (!ratios.empty())
  {
    std::nth_element(ratios.begin(), ratios.begin() + ratios.size() / 2, ratios.end());
    result.medianVolumeRatio = ratios[ratios.size() / 2];
  }
  progress.report(1.0);
  return result;
}
} // namespace tc
