// SPDX-License-Identifier: BSD-3-Clause
/// @file vec3.h
/// A plain 3-vector for the core's hot loops (base complex, path tracing): an aggregate of three
/// doubles, so arrays of it stay flat and cost nothing to build.
#pragma once

#include <cmath>

namespace tc
{
namespace detail
{
struct V3
{
  double x, y, z;
};
inline V3 sub(const V3& a, const V3& b)
{
  return { a.x - b.x, a.y - b.y, a.z - b.z };
}
inline V3 cross(const V3& a, const V3& b)
{
  return { a.y * b.z - a.z * b.y, a.z * b.x - a.x * b.z, a.x * b.y - a.y * b.x };
}
inline double dot(const V3& a, const V3& b)
{
  return a.x * b.x + a.y * b.y + a.z * b.z;
}
inline double norm(const V3& a)
{
  return std::sqrt(dot(a, a));
}
} // namespace detail
} // namespace tc
