// SPDX-License-Identifier: BSD-3-Clause
/// @file uv_locator.h
/// Private to buildGeometryImages: 2-D point location in a parameterized patch, a uniform
/// bucket grid over the unit square (CGAL 5.5 has no 2-D AABB traits, and the parameter domain
/// is a fixed square).
#pragma once

#include "tc/gim/geometry_images.h"

#include <cstdint>
#include <vector>

namespace tc::detail::geometry_images
{
/// Point location in the parameterized patch: a uniform bucket grid over the unit square, about
/// one cell per triangle (at most 1024 x 1024). Holds a reference to the parameterization.
class UvLocator
{
public:
  struct Hit
  {
    int32_t triangle = -1; ///< of the patch, -1 if it has no triangle of non-zero uv area
    double w[3] = { 0.0, 0.0, 0.0 };
  };

  explicit UvLocator(const PatchParameterization& p);

  /// The triangle that contains (u, v) best (largest smallest barycentric), searched in growing
  /// rings of cells until one contains it; barycentrics clamped to the triangle.
  Hit locate(double u, double v) const;

private:
  int32_t cell(double x) const;
  void barycentric(int32_t t, double u, double v, double (&w)[3]) const;

  const PatchParameterization& P_;
  int32_t G_ = 1;
  std::vector<int64_t> Offsets_;
  std::vector<int32_t> Ids_;
};
} // namespace tc::detail::geometry_images
