// SPDX-License-Identifier: BSD-3-Clause
/// @file geometry2d.h
/// Plane points and the predicates of the flattened charts of the base domain (MAPS stars,
/// unfolded base faces): orientation, cross product, barycentric coordinates.
#pragma once

namespace tc
{
namespace detail
{
constexpr double kPi = 3.14159265358979323846;

/// A point of a flattened chart.
struct P2
{
  double x, y;
};

/// Twice the signed area of (a, b, c): positive when counter-clockwise.
inline double orient(const P2& a, const P2& b, const P2& c)
{
  return (b.x - a.x) * (c.y - a.y) - (b.y - a.y) * (c.x - a.x);
}

/// z component of a x b.
inline double cross(const P2& a, const P2& b)
{
  return a.x * b.y - a.y * b.x;
}

/// Barycentrics of p in triangle (a, b, c), w[0] = 1 - w[1] - w[2]; false for a degenerate or
/// clockwise triangle.
inline bool barycentric(const P2& p, const P2& a, const P2& b, const P2& c, double w[3])
{
  const double d = orient(a, b, c);
  if (!(d > 0.0))
  {
    return false;
  }
  w[1] = orient(a, p, c) / d;
  w[2] = orient(a, b, p) / d;
  w[0] = 1.0 - w[1] - w[2];
  return true;
}
} // namespace detail
} // namespace tc
