// SPDX-License-Identifier: BSD-3-Clause
#include "tc/skinning/skinned_boxes.h"

#include "skinning/weight_fit.h"

#include "tc/common/errors.h"
#include "tc/common/parallel.h"

#include <Eigen/Dense>

#include <algorithm>
#include <cmath>
#include <limits>
#include <map>
#include <numeric>
#include <string>

namespace tc
{
namespace
{
using Vec3 = std::array<double, 3>;
using Corners = std::array<Vec3, 4>;

// A chart's finest-level samples: bind positions and skins.
struct ChartSamples
{
  std::vector<Vec3> points;
  std::vector<PointSkin> skins;
};

// An orthonormal box: centre, axes (rows, the thinnest first) and half extents.
struct Obb
{
  Eigen::Vector3d center = Eigen::Vector3d::Zero();
  Eigen::Matrix3d axes = Eigen::Matrix3d::Identity();
  Eigen::Vector3d half = Eigen::Vector3d::Zero();
};

// An affine motion y = linear x + shift.
struct Motion
{
  Eigen::Matrix3d linear = Eigen::Matrix3d::Identity();
  Eigen::Vector3d shift = Eigen::Vector3d::Zero();
};

// The frames a box is fitted and checked at: their skinning matrices and the chart's samples
// posed by each.
struct Frames
{
  std::vector<std::vector<Matrix4>> matrices;
  /// Per frame, its animation when the frames of that animation follow each other in time order
  /// (the check frames), else -1.
  std::vector<int32_t> sequence;
  std::vector<std::vector<Vec3>> posed;
};

Eigen::Vector3d toEigen(const Vec3& p)
{
  return Eigen::Vector3d(p[0], p[1], p[2]);
}

Vec3 fromEigen(const Eigen::Vector3d& p)
{
  return { p(0), p(1), p(2) };
}

// The corners that carry a skin (SkinnedBox::skin): c0, c2, c3.
constexpr std::array<size_t, 3> kSkinnedCorners{ 0, 2, 3 };

Eigen::Vector3d bindCorner(const SkinnedBox& box, size_t i)
{
  return Eigen::Vector3d(box.corners[3 * i], box.corners[3 * i + 1], box.corners[3 * i + 2]);
}

// The length of the bind thin edge a1, the posed thin axis's (header).
double bindThickness(const SkinnedBox& box)
{
  return (bindCorner(box, 1) - bindCorner(box, 0)).norm();
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

// The PCA box of `points`: axes the eigenvectors of their covariance (ascending eigenvalues, so
// the thinnest first), every half extent at least minHalf.
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
  // Right-handed, so that the thin axis is the other two's cross product (frameCorners).
  if (box.axes.determinant() < 0.0)
  {
    box.axes.row(0) *= -1.0;
  }
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

// The corners c0 .. c3 of `box`: c0 the low corner, c_k the next one along axis k - 1.
Corners boxCorners(const Obb& box)
{
  const Eigen::Vector3d c0 = box.center - box.axes.transpose() * box.half;
  Corners corners{};
  corners[0] = fromEigen(c0);
  for (int axis = 0; axis < 3; ++axis)
  {
    corners[static_cast<size_t>(axis + 1)] =
      fromEigen(c0 + 2.0 * box.half(axis) * box.axes.row(axis).transpose());
  }
  return corners;
}

void setCorners(SkinnedBox& box, const Corners& corners)
{
  for (size_t i = 0; i < 4; ++i)
  {
    for (size_t r = 0; r < 3; ++r)
    {
      box.corners[3 * i + r] = corners[i][r];
    }
  }
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

// The affine motion that carries the bind samples to their posed positions best in least
// squares, with a faint pull of its linear part towards `prior` (the dominant joint's), which
// only decides the directions the samples do not span (a flat chart's normal).
Motion chartMotion(
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
  Motion motion;
  motion.linear = (xx + lambda * Eigen::Matrix3d::Identity())
                    .ldlt()
                    .solve((yx + lambda * prior).transpose())
                    .transpose();
  motion.shift = my - motion.linear * mx;
  return motion;
}

// The weights of `joints` (>= 0, sum 1) whose blend carries the bind `corner` closest to its
// targets over all frames (simplexLeastSquares of the 3 #K residuals).
PointSkin fitCornerSkin(const Vec3& corner, const std::vector<int32_t>& joints,
  const std::vector<std::vector<Matrix4>>& frames, const std::vector<Vec3>& targets)
{
  const int m = static_cast<int>(joints.size());
  Eigen::MatrixXd g = Eigen::MatrixXd::Zero(m, m);
  Eigen::VectorXd h = Eigen::VectorXd::Zero(m);
  for (size_t k = 0; k < frames.size(); ++k)
  {
    Eigen::MatrixXd p(3, m);
    for (int b = 0; b < m; ++b)
    {
      PointSkin one;
      one.joints[0] = joints[static_cast<size_t>(b)];
      one.weights[0] = 1.0f;
      p.col(b) = toEigen(skinPoint(corner, one, frames[k]));
    }
    g += p.transpose() * p;
    h += p.transpose() * toEigen(targets[k]);
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

// Skinning matrices of every frame of every animation (the rest pose when there is none), in
// time order within an animation, and each frame's animation (-1 for the rest pose).
struct FrameSet
{
  std::vector<std::vector<Matrix4>> matrices;
  std::vector<int32_t> animation;
};

FrameSet frameMatrices(const Rig& rig, int count, bool withKeys)
{
  FrameSet frames;
  if (rig.animations.empty())
  {
    frames.matrices.push_back(poseMatrices(rig, -1, 0.0));
    frames.animation.push_back(-1);
  }
  for (size_t a = 0; a < rig.animations.size(); ++a)
  {
    for (double t : frameTimes(rig.animations[a], count, withKeys))
    {
      frames.matrices.push_back(poseMatrices(rig, static_cast<int>(a), t));
      frames.animation.push_back(static_cast<int32_t>(a));
    }
  }
  return frames;
}

// The posed frame of `box` at `matrices` (header): the pivot q_0 and q_0 + A_k for its axes.
Corners frameCorners(const SkinnedBox& box, const std::vector<Matrix4>& matrices)
{
  std::array<Eigen::Vector3d, 3> q;
  for (size_t j = 0; j < 3; ++j)
  {
    const size_t i = kSkinnedCorners[j];
    const Vec3 corner{ box.corners[3 * i], box.corners[3 * i + 1], box.corners[3 * i + 2] };
    q[j] = toEigen(skinPoint(corner, box.skin[j], matrices));
  }
  const Eigen::Vector3d a2 = q[1] - q[0], a3 = q[2] - q[0];
  const Eigen::Vector3d normal = a2.cross(a3);
  const Eigen::Vector3d e1 = normal.normalized(), e3 = a3.normalized();
  Corners out{};
  out[0] = fromEigen(q[0]);
  out[1] = fromEigen(q[0] + bindThickness(box) * e1);
  out[2] = fromEigen(q[0] + a2.norm() * e3.cross(e1));
  out[3] = fromEigen(q[2]);
  return out;
}

// Step 3: the range of the posed samples' coordinates in the posed frame over every frame, each
// side then moved out by `padding` times how far it reaches beyond [0, 1], and by the largest
// change of that side between consecutive frames of a sequence: between two frames the chart
// moves less than that where the motion is smooth. Exact at the frames, whatever the corners'
// skins do. False (the box unchanged) when the frame collapses at some frame.
bool fitRange(SkinnedBox& box, const Frames& frames, double padding)
{
  Eigen::Vector3d lo = Eigen::Vector3d::Constant(INFINITY), hi = -lo;
  Eigen::Vector3d stepLo = Eigen::Vector3d::Zero(), stepHi = stepLo, lastLo = stepLo,
                  lastHi = stepLo;
  for (size_t k = 0; k < frames.matrices.size(); ++k)
  {
    const BoxFrame frame = posedBoxFrame(frameCorners(box, frames.matrices[k]));
    if (!(frame.volume > 0.0))
    {
      return false;
    }
    const Eigen::Map<const Eigen::Matrix<double, 3, 3, Eigen::RowMajor>> inverse(
      frame.inverseAxes.data());
    Eigen::Vector3d frameLo = Eigen::Vector3d::Constant(INFINITY), frameHi = -frameLo;
    for (const Vec3& p : frames.posed[k])
    {
      const Eigen::Vector3d u = inverse * (toEigen(p) - toEigen(frame.pivot));
      frameLo = frameLo.cwiseMin(u);
      frameHi = frameHi.cwiseMax(u);
    }
    if (k > 0 && frames.sequence[k] >= 0 && frames.sequence[k] == frames.sequence[k - 1])
    {
      stepLo = stepLo.cwiseMax((frameLo - lastLo).cwiseAbs());
      stepHi = stepHi.cwiseMax((frameHi - lastHi).cwiseAbs());
    }
    lastLo = frameLo;
    lastHi = frameHi;
    lo = lo.cwiseMin(frameLo);
    hi = hi.cwiseMax(frameHi);
  }
  for (size_t k = 0; k < 3; ++k)
  {
    const Eigen::Index e = static_cast<Eigen::Index>(k);
    box.lo[k] = lo(e) - padding * std::max(0.0, -lo(e)) - stepLo(e);
    box.hi[k] = hi(e) + padding * std::max(0.0, hi(e) - 1.0) + stepHi(e);
  }
  return true;
}

// Volume figures of the fitted frames: per chart and frame the posed box's volume and the
// tight box's.
struct VolumeFigures
{
  std::vector<double> posed;
  std::vector<double> tight;
};

// Step 2: the skins of the corners c0, c2, c3 that carry the frame (frameCorners), each fitted
// to where the chart's best affine motion of every fitted frame carries that corner.
void fitCornerSkins(SkinnedBox& box, const ChartSamples& s, const Obb& bind,
  const std::vector<int32_t>& joints, const Frames& fit)
{
  const Corners corners = boxCorners(bind);
  std::array<std::vector<Vec3>, 3> targets;
  for (size_t k = 0; k < fit.matrices.size(); ++k)
  {
    const Motion motion =
      chartMotion(s.points, fit.posed[k], linearPart(fit.matrices[k][joints[0]]));
    for (size_t j = 0; j < 3; ++j)
    {
      const Vec3& corner = corners[kSkinnedCorners[j]];
      targets[j].push_back(fromEigen(motion.linear * toEigen(corner) + motion.shift));
    }
  }
  for (size_t j = 0; j < 3; ++j)
  {
    box.skin[j] = fitCornerSkin(corners[kSkinnedCorners[j]], joints, fit.matrices, targets[j]);
  }
}

// One chart: (1) bind box by PCA of the bind samples, (2) the weights of the chart's dominant
// joints at c0, c2, c3 that follow the chart's motion, (3) the range that holds every sample of
// the fitted and checked frames in the posed frame, plus the margin; then its volumes at the
// fitted frames.
SkinnedBox fitChart(const ChartSamples& s, const FrameSet& fit, const FrameSet& check,
  const SkinnedBoxOptions& options, VolumeFigures& figures)
{
  Obb bind = pcaBox(s.points, 0.0);
  const double diagonal = std::max(2.0 * bind.half.norm(), 1e-300);
  bind.half = bind.half.cwiseMax(0.5 * options.minExtent * diagonal);
  Frames frames;
  for (const std::vector<Matrix4>& matrices : fit.matrices)
  {
    frames.matrices.push_back(matrices);
    frames.sequence.push_back(-1);
    frames.posed.push_back(poseSamples(s, matrices));
  }
  SkinnedBox box;
  fitCornerSkins(box, s, bind, dominantJoints(s), frames);
  for (size_t k = 0; k < check.matrices.size(); ++k)
  {
    frames.matrices.push_back(check.matrices[k]);
    frames.sequence.push_back(check.animation[k]);
    frames.posed.push_back(poseSamples(s, check.matrices[k]));
  }
  setCorners(box, boxCorners(bind));
  if (!fitRange(box, frames, options.padding))
  {
    // The chords c0-c2 and c0-c3 fall parallel in some pose (a chart folded flat across a
    // joint): the frame then follows c0's skin alone, a blend of rotations, which keeps its
    // edges apart.
    box.skin[1] = box.skin[2] = box.skin[0];
    if (!fitRange(box, frames, options.padding))
    {
      throw InputError("fitSkinnedBoxes: a chart's box collapses in a pose (its skin maps it "
                       "flat; check the Skin attribute and the skinning matrices)");
    }
  }
  for (size_t k = 0; k < fit.matrices.size(); ++k)
  {
    figures.posed.push_back(posedBoxFrame(poseBox(box, fit.matrices[k])).volume);
    figures.tight.push_back(obbVolume(pcaBox(frames.posed[k], 0.5 * options.minExtent * diagonal)));
  }
  return box;
}

void summarize(const VolumeFigures& figures, SkinnedBoxesResult& result)
{
  std::vector<double> ratios;
  double posed = 0.0, tight = 0.0;
  for (size_t k = 0; k < figures.posed.size(); ++k)
  {
    ratios.push_back(figures.posed[k] / figures.tight[k]);
    result.meanVolumeRatio += ratios.back() / static_cast<double>(figures.posed.size());
    result.largestVolumeRatio = std::max(result.largestVolumeRatio, ratios.back());
    posed += figures.posed[k];
    tight += figures.tight[k];
  }
  result.summedVolumeRatio = tight > 0.0 ? posed / tight : 0.0;
  if (!ratios.empty())
  {
    std::nth_element(ratios.begin(), ratios.begin() + ratios.size() / 2, ratios.end());
    result.medianVolumeRatio = ratios[ratios.size() / 2];
  }
}
} // namespace

std::array<std::array<double, 3>, 4> poseBox(
  const SkinnedBox& box, const std::vector<Matrix4>& matrices)
{
  const Corners q = frameCorners(box, matrices);
  Corners out{};
  for (size_t r = 0; r < 3; ++r)
  {
    double pivot = q[0][r];
    for (size_t k = 0; k < 3; ++k)
    {
      pivot += box.lo[k] * (q[k + 1][r] - q[0][r]);
    }
    out[0][r] = pivot;
    for (size_t k = 0; k < 3; ++k)
    {
      out[k + 1][r] = pivot + (box.hi[k] - box.lo[k]) * (q[k + 1][r] - q[0][r]);
    }
  }
  return out;
}

BoxFrame posedBoxFrame(const std::array<std::array<double, 3>, 4>& corners)
{
  BoxFrame frame;
  frame.pivot = corners[0];
  Eigen::Matrix3d axes;
  for (int k = 0; k < 3; ++k)
  {
    axes.col(k) = toEigen(corners[static_cast<size_t>(k + 1)]) - toEigen(corners[0]);
  }
  frame.volume = std::abs(axes.determinant());
  const Eigen::Matrix3d inverse = frame.volume > 0.0
    ? Eigen::Matrix3d(axes.inverse())
    : Eigen::Matrix3d::Constant(std::numeric_limits<double>::quiet_NaN());
  for (int r = 0; r < 3; ++r)
  {
    for (int c = 0; c < 3; ++c)
    {
      frame.inverseAxes[static_cast<size_t>(3 * r + c)] = inverse(r, c);
    }
  }
  return frame;
}

bool boxContains(const BoxFrame& frame, const std::array<double, 3>& point, double tolerance)
{
  const Vec3 x{ point[0] - frame.pivot[0], point[1] - frame.pivot[1], point[2] - frame.pivot[2] };
  for (size_t r = 0; r < 3; ++r)
  {
    const double u = frame.inverseAxes[3 * r] * x[0] + frame.inverseAxes[3 * r + 1] * x[1] +
      frame.inverseAxes[3 * r + 2] * x[2];
    if (!(u >= -tolerance && u <= 1.0 + tolerance))
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
  const FrameSet fit = frameMatrices(atlas.rig, std::max(1, options.framesPerAnimation), true);
  const FrameSet check =
    frameMatrices(atlas.rig, std::max(0, options.checkFramesPerAnimation), false);
  SkinnedBoxesResult result;
  result.frames = static_cast<int64_t>(fit.matrices.size());
  const size_t n = atlas.charts.size();
  result.boxes.resize(n);
  // Charts in parallel, each with its own figures, joined in chart order.
  std::vector<VolumeFigures> perChart(n);
  parallel_for(
    static_cast<int64_t>(n),
    [&](int64_t c)
    {
      const ChartSamples s = chartSamples(atlas, static_cast<int32_t>(c), skin);
      result.boxes[static_cast<size_t>(c)] =
        fitChart(s, fit, check, options, perChart[static_cast<size_t>(c)]);
    },
    progress);
  VolumeFigures figures;
  for (const VolumeFigures& f : perChart)
  {
    figures.posed.insert(figures.posed.end(), f.posed.begin(), f.posed.end());
    figures.tight.insert(figures.tight.end(), f.tight.begin(), f.tight.end());
  }
  summarize(figures, result);
  return result;
}
} // namespace tc

namespace tc
{
namespace
{
/// Charts per block of poseLodBoxes: the unit of parallel scheduling, whose posed corners and
/// frames wait on the stack between the two stages.
constexpr int32_t kPoseBlock = 256;
/// From this many charts on, blocks run in parallel (as in selectLevels).
constexpr int32_t kParallelPoseCharts = 16384;
/// Floats of a broadcast palette entry: every one of a joint's 12 values 4 times, once per corner
/// lane, so that one vector load multiplies it into the 4 corners.
constexpr int kBroadcastFloats = 4 * kPaletteFloats;

/// The joint slot of `joint` in a box's `slots`, added when new.
/// @throws InputError when the box already has 4 other joints
int32_t jointSlot(std::array<int32_t, 4>& slots, int32_t& used, int32_t joint, size_t box)
{
  for (int32_t s = 0; s < used; ++s)
  {
    if (slots[static_cast<size_t>(s)] == joint)
    {
      return s;
    }
  }
  if (used == 4)
  {
    throw InputError("LodSkinnedBoxes: box " + std::to_string(box) +
      " has skins with more than 4 distinct joints; a box is posed by at most 4 (fit it with "
      "tc::fitSkinnedBoxes)");
  }
  slots[static_cast<size_t>(used)] = joint;
  return used++;
}

/// A block's charts as lanes: one value per chart of the block.
using Lanes = Eigen::Array<float, Eigen::Dynamic, 1, 0, kPoseBlock, 1>;
using LaneMap = Eigen::Map<Lanes>;
/// Posed corners of a block's charts, coordinate r of corner i at [4 r + i][chart].
using BlockCorners = float[12][kPoseBlock];

/// Stage 1 of a block: the skinned corners of every chart posed by linear blend skinning. Its 4
/// lanes (c0, c2, c3, idle) are the inner loops, which the compiler turns into vector operations:
/// per joint slot, 12 broadcast palette loads and 24 multiply-adds pose all 4.
void poseCorners(const LodSkinnedBoxes& boxes, const float* broadcast, int32_t begin, int32_t count,
  BlockCorners& out)
{
  for (int32_t l = 0; l < count; ++l)
  {
    const size_t c = static_cast<size_t>(begin + l);
    const float* x = boxes.corners.data() + 12 * c;
    float q[3][4] = {};
    for (int32_t s = 0; s < boxes.jointCount[c]; ++s)
    {
      const float* m = broadcast + kBroadcastFloats * static_cast<size_t>(boxes.joints[4 * c + s]);
      const float* w = boxes.weights.data() + 16 * c + 4 * static_cast<size_t>(s);
      for (int r = 0; r < 3; ++r)
      {
        const float* row = m + 16 * r;
        for (int i = 0; i < 4; ++i)
        {
          q[r][i] +=
            w[i] * (row[i] * x[i] + row[4 + i] * x[4 + i] + row[8 + i] * x[8 + i] + row[12 + i]);
        }
      }
    }
    for (int r = 0; r < 3; ++r)
    {
      for (int i = 0; i < 4; ++i)
      {
        out[4 * r + i][l] = q[r][i];
      }
    }
  }
}

/// Stage 2 of a block: the posed frame as frameCorners builds it, the charts as lanes (Eigen
/// arrays, whose square root is a vector instruction where std::sqrt stays scalar to set errno);
/// then per chart the box of its range, in LodCharts' layout, and eq. (6) on its axes, which for
/// orthogonal axes is the sum of the products of their lengths.
void frameBlock(const LodSkinnedBoxes& boxes, BlockCorners& q, int32_t begin, int32_t count,
  float* box, float* worldArea)
{
  const auto at = [&](int r, int lane) { return LaneMap(q[4 * r + lane], count); };
  const auto norm = [](const Lanes* v)
  { return (v[0].square() + v[1].square() + v[2].square()).sqrt(); };
  const auto cross = [](const Lanes* a, const Lanes* b, Lanes* out)
  {
    for (int r = 0; r < 3; ++r)
    {
      const int u = (r + 1) % 3, v = (r + 2) % 3;
      out[r] = a[u] * b[v] - a[v] * b[u];
    }
  };
  // e[k]: the unit axes e1 = unit(A_2' x A_3), e2 = e3 x e1, e3 = unit(A_3); length[k]: |A_k|.
  Lanes a2[3], e[3][3], length[3];
  for (int r = 0; r < 3; ++r)
  {
    a2[r] = at(r, 1) - at(r, 0);
    e[2][r] = at(r, 2) - at(r, 0);
  }
  cross(a2, e[2], e[0]);
  const float tiny = std::numeric_limits<float>::min();
  length[0] = Eigen::Map<const Lanes>(boxes.thickness.data() + begin, count);
  length[1] = norm(a2);
  length[2] = norm(e[2]);
  const Lanes inverse0 = norm(e[0]).max(tiny).inverse(), inverse2 = length[2].max(tiny).inverse();
  for (int r = 0; r < 3; ++r)
  {
    e[0][r] *= inverse0;
    e[2][r] *= inverse2;
  }
  cross(e[2], e[0], e[1]);
  for (int32_t l = 0; l < count; ++l)
  {
    const size_t c = static_cast<size_t>(begin + l);
    const float* range = boxes.range.data() + 6 * c;
    float* o = box + 12 * c;
    float extent[3];
    for (int k = 0; k < 3; ++k)
    {
      extent[k] = range[3 + k] * length[k](l);
    }
    for (int r = 0; r < 3; ++r)
    {
      float pivot = q[4 * r][l];
      for (int k = 0; k < 3; ++k)
      {
        pivot += range[k] * length[k](l) * e[k][r](l);
        o[3 + 3 * k + r] = extent[k] * e[k][r](l);
      }
      o[r] = pivot;
    }
    worldArea[c] = extent[0] * extent[1] + extent[0] * extent[2] + extent[1] * extent[2];
  }
}

/// Box `c`'s skins into `out`'s joint slots and weights (lane j: SkinnedBox::skin[j]).
void addSkins(const SkinnedBox& box, size_t c, LodSkinnedBoxes& out)
{
  std::array<int32_t, 4> slots{};
  int32_t used = 0;
  for (size_t lane = 0; lane < 3; ++lane)
  {
    const PointSkin& skin = box.skin[lane];
    for (size_t m = 0; m < static_cast<size_t>(kMaxInfluences); ++m)
    {
      const float w = skin.weights[m];
      if (!(w >= 0.0f) || !std::isfinite(w) || skin.joints[m] < 0)
      {
        throw InputError("LodSkinnedBoxes: box " + std::to_string(c) + " skin " +
          std::to_string(lane) + " has joint " + std::to_string(skin.joints[m]) + " with weight " +
          std::to_string(w) + "; want joints >= 0 and finite weights >= 0");
      }
      if (w > 0.0f)
      {
        const int32_t s = jointSlot(slots, used, skin.joints[m], c);
        out.weights[16 * c + 4 * static_cast<size_t>(s) + lane] += w;
        out.paletteJoints = std::max(out.paletteJoints, skin.joints[m] + 1);
      }
    }
  }
  std::copy(slots.begin(), slots.end(), out.joints.begin() + static_cast<std::ptrdiff_t>(4 * c));
  out.jointCount[c] = used;
}
} // namespace

LodSkinnedBoxes LodSkinnedBoxes::fromBoxes(const std::vector<SkinnedBox>& boxes)
{
  const size_t n = boxes.size();
  LodSkinnedBoxes out;
  out.corners.resize(12 * n);
  out.joints.assign(4 * n, 0);
  out.weights.assign(16 * n, 0.0f);
  out.thickness.resize(n);
  out.jointCount.assign(n, 0);
  out.range.resize(6 * n);
  for (size_t c = 0; c < n; ++c)
  {
    const SkinnedBox& box = boxes[c];
    for (size_t k = 0; k < 3; ++k)
    {
      out.range[6 * c + k] = static_cast<float>(box.lo[k]);
      out.range[6 * c + 3 + k] = static_cast<float>(box.hi[k] - box.lo[k]);
    }
    out.thickness[c] = static_cast<float>(bindThickness(box));
    // The idle lane 3 poses c0 again, with no weight.
    for (size_t lane = 0; lane < 4; ++lane)
    {
      const size_t i = lane < 3 ? kSkinnedCorners[lane] : 0;
      for (size_t r = 0; r < 3; ++r)
      {
        out.corners[12 * c + 4 * r + lane] = static_cast<float>(box.corners[3 * i + r]);
      }
    }
    addSkins(box, c, out);
  }
  return out;
}

void poseLodBoxes(
  const LodSkinnedBoxes& boxes, const float* palette, int32_t joints, float* box, float* worldArea)
{
  const size_t n = boxes.jointCount.size();
  if (boxes.corners.size() != 12 * n || boxes.joints.size() != 4 * n ||
    boxes.weights.size() != 16 * n || boxes.range.size() != 6 * n || boxes.thickness.size() != n)
  {
    throw InputError("poseLodBoxes: the box arrays disagree (want corners #C x 12, joints #C x 4, "
                     "weights #C x 16, range #C x 6, thickness #C for #C = jointCount.size() = " +
      std::to_string(n) + "); build them with LodSkinnedBoxes::fromBoxes");
  }
  if (joints < boxes.paletteJoints)
  {
    throw InputError("poseLodBoxes: the palette has " + std::to_string(joints) +
      " joints, the boxes use " + std::to_string(boxes.paletteJoints) +
      "; pass the skinning matrices of the rig the boxes were fitted to");
  }
  // Row r, column k of joint j at [48 j + 16 r + 4 k + lane].
  std::vector<float> broadcast(static_cast<size_t>(kBroadcastFloats) * static_cast<size_t>(joints));
  for (size_t e = 0; e < broadcast.size(); ++e)
  {
    broadcast[e] = palette[e / 4];
  }
  const int32_t count = boxes.size();
  const int32_t blocks = (count + kPoseBlock - 1) / kPoseBlock;
  const auto block = [&](int64_t b)
  {
    const int32_t begin = static_cast<int32_t>(b) * kPoseBlock;
    const int32_t size = std::min(count, begin + kPoseBlock) - begin;
    BlockCorners corners;
    poseCorners(boxes, broadcast.data(), begin, size, corners);
    frameBlock(boxes, corners, begin, size, box, worldArea);
  };
  if (count >= kParallelPoseCharts)
  {
    parallel_for(blocks, block, Progress(), 1);
  }
  else
  {
    for (int32_t b = 0; b < blocks; ++b)
    {
      block(b);
    }
  }
}
} // namespace tc
