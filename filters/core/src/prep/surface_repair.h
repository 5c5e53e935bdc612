// SPDX-License-Identifier: BSD-3-Clause
/// @file surface_repair.h
/// Repairs of an oriented manifold triangle mesh for tcMeshPreparation (internal): hole filling
/// (CGAL's triangulate_refine_and_fair_hole) and sliver removal (CGAL's
/// remove_almost_degenerate_faces).
#pragma once

#include "tc/common/mesh.h"
#include "tc/common/progress.h"

#include <cstdint>
#include <vector>

namespace tc
{
struct HoleFilling
{
  int64_t filledHoles = 0; ///< boundary loops closed
  int64_t addedTriangles = 0;
  int64_t addedPoints = 0;   ///< refinement points inside the patches
  int64_t unfairedHoles = 0; ///< filled, but fairing failed: the refined patch is kept as it is
  int64_t skippedHoles = 0;  ///< loops longer than maxEdges, left open
  bool nonManifold = false;  ///< the mesh is not manifold there: nothing was filled
};

/// Closes every boundary loop of `mesh` with at most `maxEdges` edges (0: any) by a minimum-area
/// triangulation, refined to the density around the hole and faired (CGAL,
/// Polygon_mesh_processing::triangulate_refine_and_fair_hole; Liepa 2003). New points and
/// triangles are appended after the existing ones, which keep their ids; new triangles follow
/// the orientation of the triangles around the hole.
///
/// @param[in,out] mesh  an oriented triangle mesh; when a vertex or edge is not manifold the
///   mesh is left unchanged and HoleFilling::nonManifold is set
/// @param[in] progress  reported per hole; may abort (tc::Aborted)
HoleFilling fillHoles(TriMesh& mesh, int64_t maxEdges, const Progress& progress = {});

struct SliverRemoval
{
  /// #V' old index of every point kept, ascending (collapses remove points; none move); empty
  /// when the mesh had no sliver and was left as it is
  std::vector<int32_t> keptPoints;
  /// #F' old index of every triangle kept, ascending (a flipped pair keeps its two indices);
  /// empty when the mesh had no sliver
  std::vector<int32_t> keptTriangles;
  int64_t collapsedPoints = 0;   ///< needles removed by collapsing their shortest edge
  int64_t reshapedTriangles = 0; ///< kept triangles whose corners changed (cap edge flips)
  int64_t slivers = 0;           ///< triangles beyond the thresholds before
  int64_t remainingSlivers = 0;  ///< and after (no valid collapse or flip removes them)
  bool nonManifold = false;      ///< the mesh is not manifold: nothing was changed
};

/// Removes the slivers of `mesh` (CGAL, Polygon_mesh_processing::experimental::
/// remove_almost_degenerate_faces): a needle loses its shortest edge by a half-edge collapse
/// that keeps the endpoint changing the volume least (no point moves), a cap's longest edge is
/// flipped; a change that would break the topology or fold a triangle is not made. Points and
/// triangles keep their order.
///
/// @param[in,out] mesh  an oriented triangle mesh; when a vertex or edge is not manifold the mesh
///   is left unchanged and SliverRemoval::nonManifold is set
/// @param[in] maxAngleDegrees  caps: largest angle above this (PreparationOptions::sliverAngle)
/// @param[in] maxEdgeRatio     needles: longest side over shortest above this
SliverRemoval removeSlivers(
  TriMesh& mesh, double maxAngleDegrees, double maxEdgeRatio, const Progress& progress = {});
} // namespace tc
