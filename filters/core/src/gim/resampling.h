// SPDX-License-Identifier: BSD-3-Clause
/// @file resampling.h
/// Private to buildGeometryImages: the float samples of the charts' grids (Feng et al. 2010,
/// section 5.2). Each path is sampled once, by arc length, and both its charts copy the same
/// floats; corners are the base vertex's own values; interior samples interpolate the patch at
/// the grid point's (u, v). Normals are shared (two-sided) except along feature curves, where a
/// chart takes the one-sided normal of its own triangles so that the crease stays sharp.
#pragma once

#include "gim/chart_grid.h"
#include "gim/geometry_images_input.h"

#include <cstdint>
#include <vector>

namespace tc::detail::geometry_images
{
/// What the samplers read.
struct SamplingInput
{
  const PatchMesh& patches;
  const BaseComplexResult& base;
  const Layout& L;
  const SampleLayout& S;
  const std::vector<GeometryImageAttribute>& extra;
  const std::vector<double>& shared;         ///< #V' x 3 shared unit normals
  const std::vector<uint8_t>& featureVertex; ///< per base vertex (featureVertices)
};

/// Shared (two-sided) unit normals of every point: `normals` (#V' x 3, may be empty: angle-
/// weighted vertex normals of the patch mesh), normalized.
std::vector<double> sharedNormals(
  const TriMesh& mesh, const Layout& L, const std::vector<double>& normals);

/// Path e sampled at 2^level + 1 dyadic arc-length fractions, from its lower base vertex to its
/// higher one (level: the finer sampled level of its two charts).
PathSamples samplePath(const SamplingInput& in, int32_t e, int32_t level);

/// The grid of chart c (table entry `chart`, parameterization p) at `level`: side samples copied
/// from `paths` (one-sided normals along a feature side), interior samples interpolated.
ChartGrid sampleChartGrid(const SamplingInput& in, const PatchParameterization& p,
  const AtlasChart& chart, int32_t c, int32_t level, const std::vector<PathSamples>& paths);
} // namespace tc::detail::geometry_images
