// SPDX-License-Identifier: BSD-3-Clause
/// @file chart_box.h
/// Private to buildGeometryImages: AtlasChart::box, the oriented box that feeds the renderer's
/// projected-area estimate (Feng et al. 2010, eq. 6), and the rounding of the chart table's
/// doubles for storage.
#pragma once

#include "gim/chart_grid.h"

#include <array>
#include <cstdint>

namespace tc::detail::geometry_images
{
/// The bounding-box diagonal of the patch mesh's input points (inputPointId >= 0), 0 without
/// any: the scale of the curvature weight and of the level rules' tolerance.
double inputDiagonal(const PatchMesh& patches);

/// `x` to 8 significant decimal digits: the chart table's doubles (box corners, level errors)
/// feed estimates that the renderer evaluates in float (7.2 digits), and as the shortest decimal
/// text that reads back to the same double they take half the atlas file's metadata bytes of
/// full-precision values.
double storageRounded(double x);

/// The box along the principal axes of the patch's points (as AtlasChart::box: c0 and its three
/// neighbours), holding them and, with `fitted`, the samples of level `level` of that grid
/// (fitted samples leave the surface; they do not set the axes); grown and rounded so that the
/// stored box still holds them.
std::array<double, 12> chartBox(
  const TriMesh& mesh, const PatchParameterization& p, const ChartGrid* fitted, int32_t level);
} // namespace tc::detail::geometry_images
