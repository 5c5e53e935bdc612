// SPDX-License-Identifier: BSD-3-Clause
/// @file atlas_packing.h
/// Private to buildGeometryImages: packing (Feng et al. 2010, section 5.2). Charts sorted by
/// d_max are paired in that order (closest d_max together), the higher one lower-left (rotated
/// 0), the other upper-right turned by 180 degrees (rotated 1), in (2^dh + 2) x (2^dh + 1)
/// rectangles; each image of the mip chain is shelf-packed, tallest rectangle first. Written by
/// hand: no library packs triangle pairs.
#pragma once

#include "gim/chart_grid.h"

#include <cstdint>
#include <vector>

namespace tc::detail::geometry_images
{
/// Pairs the charts (AtlasChart::partner, rotated), then sizes every image k = 0 .. max level
/// and places every chart's level maxLevel - k in it (AtlasChart::origin); the images' data are
/// allocated, zero. Every chart's maxLevel must be set (= level[c]).
void packAtlas(const std::vector<int32_t>& level, const SampleLayout& S, Atlas& atlas);

/// Copies every level d of chart c (grid g at stride 2^(grid level - d)) into its texels; charts
/// own disjoint texels, so charts can be written in parallel.
void writeChartImages(const ChartGrid& g, const SampleLayout& S, int32_t c, Atlas& atlas);
} // namespace tc::detail::geometry_images
