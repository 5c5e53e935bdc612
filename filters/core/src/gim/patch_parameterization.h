// SPDX-License-Identifier: BSD-3-Clause
/// @file patch_parameterization.h
/// Private to buildGeometryImages: one patch mapped onto the right triangle (Feng et al. 2010,
/// section 5.2) by Floater's mean-value coordinates with its boundary fixed by arc length along
/// its three paths, then reweighted to lower its L2 stretch (Yoshizawa, Belyaev and Seidel 2004).
#pragma once

#include "detail/geometry2d.h"
#include "gim/geometry_images_input.h"

#include <cstdint>

namespace tc::detail::geometry_images
{
/// Twice the signed uv area of triangle t of p: positive when counter-clockwise.
inline double uvArea2(const PatchParameterization& p, int64_t t)
{
  const double* a = &p.uv[2 * p.triangles[3 * t]];
  const double* b = &p.uv[2 * p.triangles[3 * t + 1]];
  const double* q = &p.uv[2 * p.triangles[3 * t + 2]];
  return orient({ a[0], a[1] }, { b[0], b[1] }, { q[0], q[1] });
}

/// The parameterization of patch c (tc::parameterizePatch) with stretchIterations passes.
/// @throws InputError naming the patch when it is not a disk bounded by its three paths or its
///         system cannot be solved
PatchParameterization parameterize(const PatchMesh& pm, const BaseComplexResult& base,
  const Layout& L, int32_t c, int32_t stretchIterations);

/// A_c of chart c (its input to the area rule of level_rule.h): the sum over its triangles of area
/// * (1 + curvatureWeight * |H| * diagonal), |H| the mean of |meanCurvature| at the corners (0 when
/// meanCurvature is empty).
double curvatureWeightedArea(const TriMesh& mesh, const Layout& L, int32_t c,
  const std::vector<double>& meanCurvature, double curvatureWeight, double diagonal);
} // namespace tc::detail::geometry_images
