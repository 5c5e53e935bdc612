// SPDX-License-Identifier: BSD-3-Clause
/// @file level_error.h
/// Private to buildGeometryImages: AtlasChart::levelError, the distance from a patch to the
/// surface a level of its chart's grid draws (the error rule's measure and the renderer's
/// screen-space error, Feng et al. 2010, section 6.1).
#pragma once

#include "gim/chart_grid.h"

#include <array>
#include <cstdint>
#include <vector>

namespace tc::detail::geometry_images
{
/// Inner edges of a patch as pairs of its local points.
using Creases = std::vector<std::array<int32_t, 2>>;

/// Inner edges of a patch whose two triangles meet at more than 45 degrees: creases that no
/// feature line follows, inside a chart.
Creases patchCreases(const TriMesh& mesh, const PatchParameterization& p);

/// levelError[d] of a chart for d = 0 .. upTo: the largest distance from a patch point to the
/// level-d grid surface at the same (u, v), the piecewise-linear reconstruction in parameter
/// space; level d is grid g at stride g.n / 2^d. Also measured where a crease edge of the patch
/// crosses a grid line (u, v or u + v a multiple of 2^-d): there grid edges cut across the fold,
/// and the deviation is largest between the crease's points.
std::vector<double> chartLevelErrors(const TriMesh& mesh, const PatchParameterization& p,
  const ChartGrid& g, const Creases& creases, int32_t upTo);
} // namespace tc::detail::geometry_images
