// SPDX-License-Identifier: BSD-3-Clause
/// @file skin_fixtures.h
/// What the skinning tests build their rigs from.
#pragma once

#include "tc/skinning/skin.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <string>
#include <utility>
#include <vector>

namespace tctest
{
/// The matrix that moves points by (x, y, z).
inline tc::Matrix4 translation(double x, double y, double z)
{
  tc::Matrix4 m = tc::identityMatrix();
  m[3] = x;
  m[7] = y;
  m[11] = z;
  return m;
}

/// A quaternion (w, x, y, z) turning by `degrees` about unit `axis`.
inline std::array<double, 4> turn(double degrees, const std::array<double, 3>& axis)
{
  const double h = 0.5 * degrees * 3.14159265358979323846 / 180.0;
  return { std::cos(h), std::sin(h) * axis[0], std::sin(h) * axis[1], std::sin(h) * axis[2] };
}

/// A track turning `joint` about `axis` by `degrees` at `times`.
inline tc::JointTrack rotationTrack(int32_t joint, const std::vector<double>& times,
  const std::vector<double>& degrees, const std::array<double, 3>& axis)
{
  tc::JointTrack track;
  track.joint = joint;
  track.rotationTimes = times;
  for (double d : degrees)
  {
    track.rotations.push_back(turn(d, axis));
  }
  return track;
}

/// A chain of 3 joints along x through [x0, x0 + 3 step], and two animations that bend it: "bend"
/// (2 s) about z and "twist" (1.5 s) about y and x.
inline tc::Rig chainRig(double x0, double step)
{
  tc::Rig rig;
  for (int32_t j = 0; j < 3; ++j)
  {
    tc::Joint joint;
    joint.name = "bone " + std::to_string(j);
    joint.parent = j - 1;
    joint.restLocal = j == 0 ? translation(x0, 0, 0) : translation(step, 0, 0);
    joint.inverseBind = tc::inverseAffine(translation(x0 + j * step, 0, 0));
    rig.skeleton.joints.push_back(joint);
  }
  tc::Animation bend;
  bend.name = "bend";
  bend.duration = 2.0;
  bend.tracks = { rotationTrack(1, { 0, 1, 2 }, { 0, 60, -40 }, { 0, 0, 1 }),
    rotationTrack(2, { 0, 1, 2 }, { 0, -50, 70 }, { 0, 0, 1 }) };
  tc::Animation twist;
  twist.name = "twist";
  twist.duration = 1.5;
  twist.tracks = { rotationTrack(1, { 0, 0.75, 1.5 }, { 0, 45, 0 }, { 0, 1, 0 }),
    rotationTrack(2, { 0, 1.5 }, { 0, 90 }, { 1, 0, 0 }) };
  rig.animations = { bend, twist };
  return rig;
}

/// The skin of a point at chain parameter t = (x - x0) / (3 step): Gaussian weights of the 3
/// joints (centres 1/6, 1/2, 5/6, width `width`), normalized, largest first: the 4 joints, then
/// the 4 weights.
inline std::array<float, tc::kSkinValues> chainSkin(double t, double width = 0.1)
{
  std::array<std::pair<float, int>, 3> w{};
  float sum = 0.0f;
  for (int j = 0; j < 3; ++j)
  {
    const double c = (2 * j + 1) / 6.0;
    w[static_cast<size_t>(j)] = { static_cast<float>(std::exp(-std::pow((t - c) / width, 2))), j };
    sum += w[static_cast<size_t>(j)].first;
  }
  std::sort(w.begin(), w.end(), [](const auto& a, const auto& b) { return a.first > b.first; });
  std::array<float, tc::kSkinValues> skin{};
  for (int k = 0; k < 3; ++k)
  {
    skin[static_cast<size_t>(k)] = static_cast<float>(w[static_cast<size_t>(k)].second);
    skin[static_cast<size_t>(tc::kMaxInfluences + k)] = w[static_cast<size_t>(k)].first / sum;
  }
  return skin;
}
} // namespace tctest
