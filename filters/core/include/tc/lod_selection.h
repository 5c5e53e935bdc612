// SPDX-License-Identifier: BSD-3-Clause
/// @file lod_selection.h
/// Per-frame level-of-detail selection for an atlas of triangular geometry images (Feng et al.
/// 2010, section 6.1), and the draw list that groups the drawn charts by level for one instanced
/// draw call per level (section 6.2).
///
/// Area rule (eq. 6 and 7). The oriented box of a chart is c0 and three axes a_k (atlas.h). Its
/// corners c0 and c0 + a_k, projected to pixels (x / w * width / 2, y / w * height / 2), give the
/// projected area A = sum over the three pairs (i, k) of |cross(ĉ_i - ĉ_0, ĉ_k - ĉ_0)|, the
/// three visible faces of the box. With A_0 = width * height (the window), eq. 7 reads
/// d = min(log4(alpha A), d_max) with alpha A_0 = 4^d_max (the paper prints max; min is meant),
/// i.e. d = d_max + log4(A / A_0): a chart that fills the window gets its finest level, and each
/// quartering of its screen area one level less, which keeps triangles per pixel about constant.
/// The level drawn is floor(d + bias + 1/2), clamped to [0, d_max].
///
/// Error rule (errorPixels > 0, charts with measured LevelError). s = sqrt(A / A_world) pixels
/// per model unit, with A_world the same sum on the unprojected axes; the level drawn is the
/// coarsest d whose levelError[d] * s <= errorPixels (d_max when none is), plus round(bias),
/// clamped.
///
/// Near and culled charts. Projection is linear in homogeneous coordinates, so any linear
/// function of the eight corners is smallest at c0 plus the negative parts of its values on the
/// axes. A box with a corner at w <= 1e-6 (it straddles or lies behind the eye plane) is drawn
/// at d_max; with culling, a box whose eight corners all lie outside one clip plane
/// (-w <= x, y, z <= w) gets level -1 and is not drawn.
///
/// Cost: O(C) per instance, about 80 floating-point operations per chart, no allocation.
#pragma once

#include "tc/atlas.h"

#include <array>
#include <cstdint>
#include <vector>

namespace tc
{
/// What LOD selection reads per chart, as flat float arrays.
struct LodCharts
{
  std::vector<float> box;        ///< #C x 12: c0 xyz, then the axes a1, a2, a3 xyz
  std::vector<float> worldArea;  ///< #C: |a1 x a2| + |a1 x a3| + |a2 x a3|
  std::vector<int32_t> maxLevel; ///< #C
  /// #C x stride: levelError[d] for d <= maxLevel, +inf beyond; every entry +inf when the chart's
  /// errors were not measured.
  std::vector<float> levelError;
  int32_t stride = 0;            ///< largest maxLevel + 1
  std::vector<int32_t> neighbor; ///< #C x 3: the chart across side k (-1: none)

  static LodCharts fromAtlas(const Atlas& atlas);
};

struct LodView
{
  std::array<double, 16> worldToClip{}; ///< row-major; clip = M * (x, y, z, 1)
  double width = 0.0;                   ///< viewport, pixels
  double height = 0.0;
};

struct LodOptions
{
  double bias = 0.0;        ///< levels added to the chosen level (positive: finer)
  double errorPixels = 0.0; ///< > 0: the error rule
  bool cull = true;         ///< level -1 for boxes wholly outside the view frustum
};

/// levels[c] for every chart of one instance: in [0, maxLevel[c]], or -1 when culled.
void selectLevels(
  const LodCharts& charts, const LodView& view, const LodOptions& options, int32_t* levels);

/// One entry per drawn (instance, chart), grouped by level.
struct LodDrawList
{
  /// 4 ints per entry: chart, instance, packed levels n | m0 << 4 | m1 << 8 | m2 << 12 (n the
  /// chart's level, m_k the level of the chart across side k in the same instance, n itself when
  /// that chart is absent or not drawn), 0.
  std::vector<int32_t> entries;
  std::vector<int64_t> levelStart;     ///< stride + 1: level d is [levelStart[d], levelStart[d+1])
  std::vector<int64_t> chartsPerLevel; ///< stride
  int64_t triangles = 0;               ///< sum over entries of 4^level
};

/// levels: instances x #C, a row per instance (selectLevels' output). O(instances * C); the
/// list's storage is reused between calls.
/// @throws InputError for a level above 15 (4 bits per level in the packing)
void buildDrawList(
  const LodCharts& charts, const int32_t* levels, int32_t instances, LodDrawList& list);
} // namespace tc
