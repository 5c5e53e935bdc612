// SPDX-License-Identifier: BSD-3-Clause
/// @file geometry_image_mesh.h
/// The mesh an atlas of triangular geometry images draws at a chosen level per chart, stitched
/// without cracks by eq. (8) of Feng et al. 2010 (section 6.3): the CPU reference the GPU vertex
/// shader must match vertex for vertex.
///
/// The vertex rule (what a shader computes for every grid vertex, from four integers per chart:
/// its level n and the levels m_k of the charts across its sides k = 0, 1, 2):
///   Chart c at level n (N = 2^n) draws grid vertices (i, j), i, j >= 0, i + j <= N, and the N^2
///   triangles (i, j), (i+1, j), (i, j+1) and (i+1, j), (i+1, j+1), (i, j+1), counter-clockwise.
///   - A corner ((0, 0), (N, 0), (0, N)) never moves.
///   - A vertex on exactly one side k (j == 0: k = 0, t = i; i + j == N: k = 1, t = j; i == 0:
///     k = 2, t = N - j; the parameter t of atlas.h) whose neighbour is coarser, m_k < n, moves to
///     parameter t' = t - (t mod 2^(n - m_k)) of the same side (stitchedGridPoint). Every t' is a
///     multiple of 2^(n - m_k), i.e. a sample the coarser neighbour also draws.
///   - Every other vertex stays.
///   The vertex then takes every attribute from sample (i', j') of chart c at level n, i.e. from
///   texel atlasTexel(chart, n, i', j') of image maxLevel - n (tc::atlasSample). By the atlas
///   invariants its position is bit-identical to what the neighbour draws for the same point.
///
/// rebuildMesh applies the rule to every chart and welds the result: vertices that are the same
/// atlas point become one output point, so the mesh is closed wherever the base complex is.
/// Grid triangles whose corners collapse onto fewer than three distinct points are dropped: each
/// moved vertex collapses one edge of its side and takes exactly one triangle with it, so
/// #F = sum_c (4^n_c - sum over sides with m_k < n_c of (2^n_c - 2^m_k)). Triangles come chart by
/// chart, each chart's in grid order (row j, then i; the triangle (i, j), (i+1, j), (i, j+1)
/// before (i+1, j), (i+1, j+1), (i, j+1)), with the corners in the order above.
///
/// Attributes other than Position: the atlas may keep one-sided values along a feature side
/// (validateAtlas compares positions only, so normals may differ there). A welded point carries
/// the value of its source sample (below); the value a chart's shader reads for its own copy is
/// atlasSample(atlas, c, a, n, stitchedGridPoint(...)), the same everywhere else. Where a chart's
/// own values of an attribute after Position and Normal differ from its welded point's (beyond
/// float noise: 1e-5 of the value, or of 1), as on a texture seam whose sides the atlas samples
/// per chart, the point splits: that chart's vertex goes to a copy of the point carrying the
/// chart's own values (one copy per distinct value, shared by the charts that agree), appended
/// after the points below as 4. seam copies, in chart order. The mesh is then closed in its
/// positions, not its point ids, along such seams.
///
/// Output points, in this order (each identified topologically, never by comparing positions):
///   1. base vertices: one per distinct AtlasChart::cornerVertex, ascending by that id;
///   2. base-edge samples: per base edge (the unordered pair of chart sides; edges ordered by the
///      smaller (chart, side) of the pair, called the owner), the 2^m - 1 samples strictly inside
///      the edge at m = the lower of its two charts' levels, in the direction of the owner side's
///      parameter t;
///   3. interior samples: per chart, the (N - 1)(N - 2) / 2 samples with i, j >= 1, i + j < N,
///      row by row (j, then i).
/// Each point is read from one sample (pointSource): a base vertex from the lowest chart that
/// has it as a corner, an edge sample from the owner chart, an interior sample from its chart.
///
/// Cost: O(C + sum_c 4^{n_c}) time and memory for C charts at levels n_c (one pass over every
/// chart's grid, in parallel over charts, then one read per output point, in parallel); no hash
/// table and no sort of samples, since every point's index follows from the counts above.
#pragma once

#include "tc/common/mesh.h"
#include "tc/common/progress.h"
#include "tc/gim/atlas.h"

#include <array>
#include <cstdint>
#include <vector>

namespace tc
{
// gridVertexCount and gridVertexIndex (tc/gim/atlas.h) count and order a chart's grid vertices.

/// The vertex rule above: the grid point (i', j') whose sample grid vertex (i, j) of a chart at
/// `level` draws, given the levels (>= 0, clamped like the chart's) of the charts across its
/// sides 0, 1, 2.
inline std::array<int32_t, 2> stitchedGridPoint(
  int32_t level, const std::array<int32_t, 3>& neighborLevels, int32_t i, int32_t j)
{
  const int32_t big = int32_t(1) << level;
  const std::array<int32_t, 2> st = gridSide(i, j, big);
  const int32_t side = st[0], t = st[1];
  // Corners (t = 0 or N) never move.
  if (side < 0 || t == 0 || t == big || neighborLevels[side] >= level)
  {
    return { i, j };
  }
  // Eq. (8) of Feng et al.: snap to the coarser neighbour's samples. The paper rounds the texture
  // coordinates u and v down separately; on side 1 (i + j = N) that would leave the side, so the
  // side's own parameter t is rounded instead. On side 0 that is the paper's rounding of u; on
  // side 2 it rounds j up rather than down, which keeps one rule for the three sides (the grid is
  // symmetric under turning the chart) and lands on the coarse samples all the same.
  const int32_t step = int32_t(1) << (level - neighborLevels[side]);
  return sidePoint(side, t - t % step, big);
}

struct RebuiltMesh
{
  /// #V points (attribute 0, Position, widened to double) and #F triangles, counter-clockwise
  /// like the charts.
  TriMesh mesh;
  /// Per atlas attribute a >= 1 (Normal, then user arrays), attributes[a - 1]: #V x components
  /// of that attribute, read from the same sample as the point.
  std::vector<std::vector<float>> attributes;
  std::vector<int32_t> chartId; ///< #F chart each triangle belongs to
  std::vector<int32_t> level;   ///< #F level of that chart
  /// #C: the level each chart was drawn at (the requested one, clamped to [0, maxLevel]).
  std::vector<int32_t> chartLevel;
  /// #V x 3: (chart, i, j) of the sample each point was read from, at chartLevel[chart].
  std::vector<int32_t> pointSource;
  /// Grid vertex v = gridVertexIndex(n, i, j) of chart c at its level n is output point
  /// chartVertexPoint[chartVertexOffsets[c] + v]: what the shader must draw for it.
  std::vector<int64_t> chartVertexOffsets; ///< #C + 1
  std::vector<int32_t> chartVertexPoint;   ///< sum over charts of gridVertexCount(n)
  int64_t droppedTriangles = 0;            ///< grid triangles that stitching collapsed
};

/// Rebuilds the mesh with chart c at levels[c] (clamped to [0, charts[c].maxLevel]).
/// The atlas's sample invariants (bit-identical shared sides and corners, dyadic samples shared
/// across levels) are trusted, not checked: validateAtlas checks them. What this function needs to
/// read safely and to weld is checked in O(C): image sizes, every texel of every level inside its
/// image, neighbours that name each other with matching corners, three distinct corners per chart.
/// @param[in] levels  #C levels, >= 0
/// @throws InputError for a levels array of the wrong size or a negative level, and for an atlas
///         that fails the checks above (the message names the chart and what to fix)
RebuiltMesh rebuildMesh(
  const Atlas& atlas, const std::vector<int32_t>& levels, const Progress& progress = {});

/// The same with one level for every chart (each clamped to its chart's maxLevel).
RebuiltMesh rebuildMesh(const Atlas& atlas, int32_t level, const Progress& progress = {});
} // namespace tc
