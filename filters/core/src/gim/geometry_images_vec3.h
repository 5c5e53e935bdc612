// SPDX-License-Identifier: BSD-3-Clause
/// @file geometry_images_vec3.h
/// Private to buildGeometryImages: the Eigen 3-vector its geometric steps compute with, and the
/// small rules on points they share. Only Eigen's Core and Geometry (cheap to compile); the
/// sparse solvers stay in patch_parameterization.cpp and sample_fit.cpp.
#pragma once

#include "tc/common/mesh.h"

#include <Eigen/Core>
#include <Eigen/Geometry>

#include <cstdint>
#include <vector>

namespace tc::detail::geometry_images
{
using Vec3 = Eigen::Vector3d;

inline Vec3 pointOf(const TriMesh& mesh, int64_t v)
{
  return Vec3(mesh.points[3 * v], mesh.points[3 * v + 1], mesh.points[3 * v + 2]);
}

/// Row v of a #V x 3 array.
inline Vec3 rowOf(const std::vector<double>& values, int64_t v)
{
  return Vec3(values[3 * v], values[3 * v + 1], values[3 * v + 2]);
}

/// n divided by its length; the zero vector stays zero.
inline Vec3 normalizedOrZero(const Vec3& n)
{
  return n.norm() > 0.0 ? Vec3(n.normalized()) : n;
}

/// Arc length from the first point of `path` (count points of `mesh`) to each of its points.
inline std::vector<double> arcLengths(const TriMesh& mesh, const int32_t* path, int64_t count)
{
  std::vector<double> arc(count, 0.0);
  for (int64_t i = 1; i < count; ++i)
  {
    arc[i] = arc[i - 1] + (pointOf(mesh, path[i]) - pointOf(mesh, path[i - 1])).norm();
  }
  return arc;
}
} // namespace tc::detail::geometry_images
