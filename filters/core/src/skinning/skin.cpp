// SPDX-License-Identifier: BSD-3-Clause
#include "tc/skinning/skin.h"

#include "tc/common/errors.h"

#include <Eigen/Geometry>

#include <algorithm>
#include <array>
#include <cctype>
#include <cmath>
#include <set>

namespace tc
{
namespace
{
/// Influences (joint, weight), largest weight first; ties by joint, so that the order does not
/// depend on the file's.
constexpr auto heavierFirst = [](const auto& a, const auto& b)
{ return a.second != b.second ? a.second > b.second : a.first < b.first; };

using RowMatrix = Eigen::Matrix<double, 4, 4, Eigen::RowMajor>;

Eigen::Map<const RowMatrix> view(const Matrix4& m)
{
  return Eigen::Map<const RowMatrix>(m.data());
}

Matrix4 toMatrix(const RowMatrix& m)
{
  Matrix4 out;
  Eigen::Map<RowMatrix>(out.data()) = m;
  return out;
}

/// The key interval of `times` around `t` and the fraction into it, held at the ends.
std::pair<size_t, double> keyInterval(const std::vector<double>& times, double t)
{
  if (times.size() < 2 || t <= times.front())
  {
    return { 0, 0.0 };
  }
  if (t >= times.back())
  {
    return { times.size() - 1, 0.0 };
  }
  const size_t i =
    static_cast<size_t>(std::upper_bound(times.begin(), times.end(), t) - times.begin()) - 1;
  const double span = times[i + 1] - times[i];
  return { i, span > 0 ? (t - times[i]) / span : 0.0 };
}

Eigen::Vector3d lerpKeys(
  const std::vector<double>& times, const std::vector<std::array<double, 3>>& values, double t)
{
  const auto [i, a] = keyInterval(times, t);
  const Eigen::Vector3d p(values[i].data());
  return a > 0 ? Eigen::Vector3d((1 - a) * p + a * Eigen::Vector3d(values[i + 1].data())) : p;
}

Eigen::Quaterniond slerpKeys(
  const std::vector<double>& times, const std::vector<std::array<double, 4>>& values, double t)
{
  const auto [i, a] = keyInterval(times, t);
  const auto quaternion = [&](size_t k)
  { return Eigen::Quaterniond(values[k][0], values[k][1], values[k][2], values[k][3]); };
  const Eigen::Quaterniond q = quaternion(i);
  return (a > 0 ? q.slerp(a, quaternion(i + 1)) : q).normalized();
}

/// The joint's local transform at `t`: T R S from the track's keys, each component without
/// keys taken from the rest transform's decomposition.
Matrix4 animatedLocal(const Joint& joint, const JointTrack& track, double t)
{
  const Eigen::Affine3d rest(view(joint.restLocal));
  Eigen::Matrix3d rotation, scaling;
  rest.computeRotationScaling(&rotation, &scaling);
  const Eigen::Vector3d p = track.positions.empty()
    ? rest.translation()
    : lerpKeys(track.positionTimes, track.positions, t);
  const Eigen::Quaterniond q = track.rotations.empty()
    ? Eigen::Quaterniond(rotation)
    : slerpKeys(track.rotationTimes, track.rotations, t);
  const Eigen::Vector3d s = track.scales.empty() ? Eigen::Vector3d(scaling.diagonal())
                                                 : lerpKeys(track.scaleTimes, track.scales, t);
  Eigen::Affine3d local = Eigen::Translation3d(p) * q * Eigen::Scaling(s);
  return toMatrix(local.matrix());
}
} // namespace

Matrix4 identityMatrix()
{
  return toMatrix(RowMatrix::Identity());
}

Matrix4 multiply(const Matrix4& a, const Matrix4& b)
{
  return toMatrix(view(a) * view(b));
}

Matrix4 inverseAffine(const Matrix4& m)
{
  return toMatrix(Eigen::Affine3d(view(m)).inverse(Eigen::Affine).matrix());
}

std::vector<double> animationKeyTimes(const Animation& animation)
{
  std::set<double> times{ 0.0, animation.duration };
  for (const double t : animation.frameTimes)
  {
    times.insert(t);
  }
  for (const JointTrack& track : animation.tracks)
  {
    for (const auto* keys : { &track.positionTimes, &track.rotationTimes, &track.scaleTimes })
    {
      for (const double t : *keys)
      {
        if (t >= 0.0 && t <= animation.duration)
        {
          times.insert(t);
        }
      }
    }
  }
  return { times.begin(), times.end() };
}

void addSkinPoint(
  std::vector<std::pair<int32_t, float>> influences, int32_t fallbackJoint, SkinWeights& skin)
{
  influences.erase(
    std::remove_if(influences.begin(), influences.end(),
      [](const auto& jw) { return !(jw.second > 0.0f && std::isfinite(jw.second)); }),
    influences.end());
  std::sort(influences.begin(), influences.end(), heavierFirst);
  const bool cut = influences.size() > static_cast<size_t>(kMaxInfluences);
  if (cut)
  {
    ++skin.pointsOverLimit;
    skin.largestDropped = std::max(skin.largestDropped, double(influences[kMaxInfluences].second));
    influences.resize(kMaxInfluences);
  }
  if (influences.empty())
  {
    influences.emplace_back(fallbackJoint, 1.0f);
  }
  double total = 0.0;
  for (const auto& jw : influences)
  {
    total += jw.second;
  }
  if (!cut && std::abs(total - 1.0) > 1e-3)
  {
    skin.smallestSum = skin.pointsOffUnitSum > 0 ? std::min(skin.smallestSum, total) : total;
    skin.largestSum = skin.pointsOffUnitSum > 0 ? std::max(skin.largestSum, total) : total;
    ++skin.pointsOffUnitSum;
  }
  total = cut ? total : 1.0;
  for (int k = 0; k < kMaxInfluences; ++k)
  {
    const bool used = k < static_cast<int>(influences.size());
    skin.joints.push_back(used ? influences[k].first : 0);
    skin.weights.push_back(used ? static_cast<float>(influences[k].second / total) : 0.0f);
  }
}

int findAnimation(const std::vector<Animation>& animations, const std::string& choice)
{
  const int n = static_cast<int>(animations.size());
  if (n == 0)
  {
    return -1;
  }
  if (choice.empty())
  {
    return 0;
  }
  for (int a = 0; a < n; ++a)
  {
    if (animations[a].name == choice)
    {
      return a;
    }
  }
  if (choice.size() < 9 &&
    std::all_of(choice.begin(), choice.end(), [](unsigned char c) { return std::isdigit(c); }) &&
    std::stoi(choice) < n)
  {
    return std::stoi(choice);
  }
  std::string names;
  for (int a = 0; a < n; ++a)
  {
    names += (a ? ", '" : "'") + animations[a].name + "' (" + std::to_string(a) + ")";
  }
  throw InputError("there is no animation '" + choice + "'; the animations are " + names);
}

int findAnimation(
  const std::vector<Animation>& animations, const std::string& choice, std::string& error)
{
  try
  {
    return findAnimation(animations, choice);
  }
  catch (const InputError& e)
  {
    error = e.what();
    return -1;
  }
}

PointSkin blendInfluences(int count, const PointSkin* skins, const double* blend)
{
  std::array<std::pair<int32_t, double>, 3 * kMaxInfluences> merged{};
  int n = 0;
  double total = 0.0;
  for (int p = 0; p < count; ++p)
  {
    for (int k = 0; k < kMaxInfluences; ++k)
    {
      const double w = blend[p] * skins[p].weights[k];
      if (!(w > 0.0))
      {
        continue;
      }
      total += w;
      int slot = 0;
      while (slot < n && merged[slot].first != skins[p].joints[k])
      {
        ++slot;
      }
      merged[slot].first = skins[p].joints[k];
      merged[slot].second += w;
      n = std::max(n, slot + 1);
    }
  }
  std::sort(merged.begin(), merged.begin() + n, heavierFirst);
  double kept = 0.0;
  for (int k = 0; k < std::min(n, kMaxInfluences); ++k)
  {
    kept += merged[k].second;
  }
  PointSkin out;
  for (int k = 0; k < std::min(n, kMaxInfluences); ++k)
  {
    out.joints[k] = merged[k].first;
    out.weights[k] = static_cast<float>(merged[k].second * (total / kept));
  }
  return out;
}

namespace
{
/// The sampled poses of `animation` at `seconds`: the frames around it blended linearly, the
/// first or last outside them.
std::vector<Matrix4> sampledGlobals(
  const Skeleton& skeleton, const Animation& animation, double seconds)
{
  const auto [k, a] = keyInterval(animation.frameTimes, seconds);
  const size_t next = std::min(k + 1, animation.frameTimes.size() - 1);
  for (const size_t f : { k, next })
  {
    if (animation.frameGlobals.size() != animation.frameTimes.size() ||
      animation.frameGlobals[f].size() != skeleton.joints.size())
    {
      throw InputError("animation '" + animation.name + "' has " +
        std::to_string(animation.frameGlobals.size()) + " sampled poses for " +
        std::to_string(animation.frameTimes.size()) + " frame times, or a pose of another " +
        "joint count than the skeleton's " + std::to_string(skeleton.joints.size()));
    }
  }
  std::vector<Matrix4> out(skeleton.joints.size());
  for (size_t j = 0; j < out.size(); ++j)
  {
    out[j] = toMatrix(
      (1.0 - a) * view(animation.frameGlobals[k][j]) + a * view(animation.frameGlobals[next][j]));
  }
  return out;
}
} // namespace

std::vector<Matrix4> jointGlobals(
  const Skeleton& skeleton, const Animation* animation, double seconds)
{
  if (animation && !animation->frameTimes.empty())
  {
    return sampledGlobals(skeleton, *animation, seconds);
  }
  std::vector<Matrix4> local(skeleton.joints.size());
  for (size_t j = 0; j < local.size(); ++j)
  {
    local[j] = skeleton.joints[j].restLocal;
  }
  if (animation)
  {
    for (const JointTrack& track : animation->tracks)
    {
      if (track.joint >= 0 && static_cast<size_t>(track.joint) < local.size())
      {
        local[track.joint] = animatedLocal(skeleton.joints[track.joint], track, seconds);
      }
    }
  }
  std::vector<Matrix4> global(local.size());
  for (size_t j = 0; j < local.size(); ++j)
  {
    const Joint& joint = skeleton.joints[j];
    // A second joint of one node moves with that node's (already animated) first joint.
    const Matrix4& own = joint.sameNodeAs >= 0 ? local[joint.sameNodeAs] : local[j];
    global[j] = joint.parent >= 0 ? multiply(global[joint.parent], own) : own;
  }
  return global;
}

std::vector<Matrix4> skinningMatrices(const Skeleton& skeleton, const std::vector<Matrix4>& globals)
{
  std::vector<Matrix4> matrices(globals.size());
  for (size_t j = 0; j < globals.size(); ++j)
  {
    matrices[j] = multiply(globals[j], skeleton.joints[j].inverseBind);
  }
  return matrices;
}

std::vector<Matrix4> poseMatrices(const Rig& rig, int animation, double seconds)
{
  const bool animated = animation >= 0 && animation < static_cast<int>(rig.animations.size());
  return skinningMatrices(rig.skeleton,
    jointGlobals(
      rig.skeleton, animated ? &rig.animations[static_cast<size_t>(animation)] : nullptr, seconds));
}

void appendPaletteRows(const std::vector<Matrix4>& matrices, std::vector<float>& palette)
{
  for (const Matrix4& m : matrices)
  {
    for (int k = 0; k < kPaletteFloats; ++k)
    {
      palette.push_back(static_cast<float>(m[static_cast<size_t>(k)]));
    }
  }
}

std::vector<double> skinPoints(const std::vector<double>& bindPoints, const SkinWeights& skin,
  const std::vector<Matrix4>& matrices)
{
  const size_t n = bindPoints.size() / 3;
  if (skin.joints.size() != kMaxInfluences * n || skin.weights.size() != kMaxInfluences * n)
  {
    throw InputError("the skin has weights for " + std::to_string(skin.joints.size() / 4) +
      " points, the mesh has " + std::to_string(n));
  }
  std::vector<double> posed(3 * n, 0.0);
  for (size_t v = 0; v < n; ++v)
  {
    const Eigen::Vector4d p(bindPoints[3 * v], bindPoints[3 * v + 1], bindPoints[3 * v + 2], 1.0);
    Eigen::Vector4d sum = Eigen::Vector4d::Zero();
    for (size_t k = 0; k < kMaxInfluences; ++k)
    {
      const float w = skin.weights[kMaxInfluences * v + k];
      const int32_t j = skin.joints[kMaxInfluences * v + k];
      if (w == 0.0f)
      {
        continue;
      }
      if (j < 0 || static_cast<size_t>(j) >= matrices.size())
      {
        throw InputError("point " + std::to_string(v) + " is weighted to joint " +
          std::to_string(j) + " of " + std::to_string(matrices.size()));
      }
      sum += double(w) * (view(matrices[j]) * p);
    }
    posed[3 * v] = sum.x();
    posed[3 * v + 1] = sum.y();
    posed[3 * v + 2] = sum.z();
  }
  return posed;
}
} // namespace tc
