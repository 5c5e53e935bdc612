// SPDX-License-Identifier: BSD-3-Clause
/// @file sample_fit.h
/// Private to buildGeometryImages: GeometryImageOptions::fitSamples. Interpolated samples lie on
/// the surface, so on a curved surface every grid triangle is a chord that lies to one side of
/// it; once d_max is chosen, the samples are moved to fit the surface by least squares instead:
/// each path's samples at the lower d_max of its two charts (eq. 8 never draws a side finer),
/// then each chart's interior samples at its d_max with its sides fixed.
#pragma once

#include "gim/resampling.h"

#include <cstdint>
#include <vector>

namespace tc::detail::geometry_images
{
/// Fits the side samples of path e, which follows no feature curve (a feature curve stays
/// sampled on the curve, so the crease stays in place). A side is fitted at the lower level[] of
/// its two charts, the finest level at which it is ever drawn, and written into both charts'
/// grids; the finer chart's samples between those (drawn by no level: stitching moves them onto
/// the coarser ones) are put on the straight line between them, so its interior is fitted
/// against the side it is drawn with and its levelError measures that side.
void fitSide(const SamplingInput& in, int32_t e, const std::vector<int32_t>& level,
  const std::vector<PathSamples>& paths, std::vector<ChartGrid>& grids);

/// Moves the interior samples of level d of a chart (grid g at stride g.n / 2^d) off the
/// surface to fit it in the least-squares sense; side and corner samples stay. No sample moves
/// farther than `maxOffset` (its offset is shortened to it; 0: no bound): a sample that few
/// data constrain, next to a crease side, can be pulled farther from the surface than the
/// interpolated grid ever was, which lowers the RMS and raises the largest error. Writes back
/// the positions only.
/// @param[in] maxOffset  the chart's interpolated levelError at d, in input units
void fitInterior(
  const TriMesh& mesh, const PatchParameterization& p, ChartGrid& g, int32_t d, double maxOffset);
} // namespace tc::detail::geometry_images
