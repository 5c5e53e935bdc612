// SPDX-License-Identifier: BSD-3-Clause
/// @file points.h
/// Points of the flat xyz arrays of the mesh preparation (internal) as detail::V3.
#pragma once

#include "detail/vec3.h"

#include <cstdint>

namespace tc
{
namespace detail
{
/// Point v of `points` (#V x 3, xyz interleaved).
inline V3 pointOf(const double* points, int64_t v)
{
  return { points[3 * v], points[3 * v + 1], points[3 * v + 2] };
}

/// Twice the area of triangle (a, b, c) of `points`.
inline double doubleArea(const double* points, int64_t a, int64_t b, int64_t c)
{
  const V3 pa = pointOf(points, a);
  return norm(cross(sub(pointOf(points, b), pa), sub(pointOf(points, c), pa)));
}
} // namespace detail
} // namespace tc
