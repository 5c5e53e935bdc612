// SPDX-License-Identifier: BSD-3-Clause
/// @file crest_lines.h
/// Crest lines (ridges and valleys) of a triangle mesh: the curves where the dominant principal
/// curvature is extremal along its own direction. Section 4.2 of Feng et al. 2010 obtains
/// "fragmented crest line segments by finding local extrema of curvatures [Stylianou and Farin
/// 2004]" and lowers the spectral-clustering similarity of faces separated by one (beta = 0.1
/// in Eq. (3)). The tracing follows Ohtake et al. 2004 (Ridge-valley lines on meshes via
/// implicit surface fitting): zero crossings of the extremality coefficient e = grad(k) . d on
/// mesh edges, joined inside triangles, chained into polylines and filtered by their strength.
#pragma once

#include "tc/features/curvature.h"
#include "tc/common/mesh.h"
#include "tc/common/progress.h"

#include <cstdint>
#include <vector>

namespace tc
{
struct CrestLineOptions
{
  /// Trace ridges: maxima of k1 along d1 where k1 > 0 dominates (k1 > |k2|), convex crests.
  bool ridges = true;
  /// Trace valleys: minima of k2 along d2 where k2 < 0 dominates (-k2 > |k1|), concave crests.
  bool valleys = true;
  /// Salience: a crest point counts only where its |k| is at least this many times the mesh's
  /// typical curvature (area-weighted mean of max(|k1|, |k2|) over all vertices). Extrema of a
  /// curvature that is the same everywhere (a sphere, a cylinder) are estimation noise, not
  /// features; 1.5 keeps crests that stand out from the rest of the surface.
  double minRelativeCurvature = 1.5;
  /// And at least this value of |k| times the bounding-box diagonal (k * diagonal = 2 sqrt(3)
  /// for a sphere): removes the rounding-noise crests of flat regions, whose typical curvature
  /// is itself noise.
  double minCurvatureTimesSize = 1.0;
  /// Lines whose strength (integral of |k| along the line, dimensionless) is below this are
  /// dropped. A line as long as its radius of curvature has strength 1.
  double minStrength = 1.0;
  /// Lines made of fewer segments (triangles crossed) than this are dropped.
  int minSegments = 3;
};

/// Crest lines as polylines over their own points.
struct CrestLines
{
  std::vector<double> points;        ///< #P x 3 positions, on mesh edges
  std::vector<int64_t> offsets{ 0 }; ///< #L + 1 offsets into connectivity
  std::vector<int64_t> connectivity; ///< point ids of every line; a closed line repeats its first
  std::vector<double> strength;      ///< #L integral of |k| along the line (scale invariant)
  std::vector<int8_t> type;          ///< #L 0 = ridge (max of k1, convex), 1 = valley (min of k2)
  /// #P id of the mesh edge (tc::buildEdgeTable order) that holds each point; where a crest
  /// passes exactly through a mesh vertex, its point is that end of the edge.
  std::vector<int32_t> pointEdge;

  int64_t numLines() const { return static_cast<int64_t>(offsets.size()) - 1; }
};

/// Ridge and valley lines from a curvature estimate of the same mesh.
///
/// Per vertex, the extremality coefficient e = grad(k1) . d1 (ridges; grad(k2) . d2 for
/// valleys), with the gradient fitted over the one-ring in the tangent plane. A crest point
/// lies on every edge where e changes sign once both ends' directions are oriented alike
/// (linear interpolation); the two crossings of a triangle whose directions can be oriented
/// consistently form a segment when e decreases along d (a maximum: ridge) or increases (a
/// minimum: valley). Segments sharing a crossing (same mesh edge) are chained into polylines,
/// broken at branchings. Output order is deterministic.
///
/// @param[in] mesh       #V x 3 points, #F x 3 triangles
/// @param[in] curvature  computeCurvature() of `mesh` (k1, k2, d1, d2, normals of #V entries)
/// @param[in] options    which crests and how salient
/// @param[in] progress   progress and abort
/// @throws InputError when the curvature does not belong to the mesh
CrestLines extractCrestLines(const TriMesh& mesh, const CurvatureResult& curvature,
  const CrestLineOptions& options = {}, const Progress& progress = {});

/// Crest lines snapped to mesh vertices: each crest point marks the nearer end of the edge it
/// lies on. Mesh edges whose two ends are marked run along a crest; eq. 3 and 4 of Feng et al.
/// lower the similarity of the two faces of such an edge.
/// @return #V flags, 1 at a vertex next to a crest line
std::vector<uint8_t> crestVertices(const TriMesh& mesh, const CrestLines& lines);
} // namespace tc
