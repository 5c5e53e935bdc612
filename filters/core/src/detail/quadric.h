// SPDX-License-Identifier: BSD-3-Clause
/// @file quadric.h
/// The error quadric of Garland and Heckbert (1997), for quadric-driven simplification (the
/// base complex's collapses, and the QSlim levels of the multilevel mesh).
#pragma once

#include "detail/vec3.h"

#include <algorithm>

namespace tc
{
namespace detail
{
/// Symmetric 4x4 quadric, upper triangle: a00 a01 a02 a11 a12 a22 b0 b1 b2 c, so that
/// Q(p) = p^T A p + 2 b.p + c.
struct Quadric
{
  double q[10] = { 0, 0, 0, 0, 0, 0, 0, 0, 0, 0 };

  /// Adds w times the squared distance to the plane n.p + d = 0 (n of unit length).
  void addPlane(const V3& n, double d, double w)
  {
    q[0] += w * n.x * n.x;
    q[1] += w * n.x * n.y;
    q[2] += w * n.x * n.z;
    q[3] += w * n.y * n.y;
    q[4] += w * n.y * n.z;
    q[5] += w * n.z * n.z;
    q[6] += w * d * n.x;
    q[7] += w * d * n.y;
    q[8] += w * d * n.z;
    q[9] += w * d * d;
  }
  void add(const Quadric& o)
  {
    for (int i = 0; i < 10; ++i)
    {
      q[i] += o.q[i];
    }
  }
};

/// (Qa + Qb)(p) without forming the sum, clamped at 0 against round-off.
inline double evalSum(const Quadric& a, const Quadric& b, const V3& p)
{
  double s[10];
  for (int i = 0; i < 10; ++i)
  {
    s[i] = a.q[i] + b.q[i];
  }
  const double e = s[0] * p.x * p.x + 2 * s[1] * p.x * p.y + 2 * s[2] * p.x * p.z +
    s[3] * p.y * p.y + 2 * s[4] * p.y * p.z + s[5] * p.z * p.z +
    2 * (s[6] * p.x + s[7] * p.y + s[8] * p.z) + s[9];
  return std::max(0.0, e);
}
} // namespace detail
} // namespace tc
