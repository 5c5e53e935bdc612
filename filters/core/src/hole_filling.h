// SPDX-License-Identifier: BSD-3-Clause
/// @file hole_filling.h
/// Hole filling for tcMeshPreparation (internal): closes the boundary loops of an oriented
/// manifold triangle mesh with CGAL's triangulate_refine_and_fair_hole.
#pragma once

#include "tc/mesh.h"
#include "tc/progress.h"

#include <cstdint>

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
} // namespace tc
