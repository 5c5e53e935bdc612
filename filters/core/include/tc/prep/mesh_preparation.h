// SPDX-License-Identifier: BSD-3-Clause
/// @file mesh_preparation.h
/// The tcMeshPreparation stage: turns a polygon soup as read from a file into a clean, oriented
/// triangle mesh that the later stages can trust, and reports every change it made and every
/// defect it found (per element and in total).
#pragma once

#include "tc/common/mesh.h"
#include "tc/common/progress.h"

#include <cstdint>
#include <string>
#include <vector>

namespace tc
{
struct PreparationOptions
{
  /// Points closer than this fraction of the bounding-box diagonal (of the points that polygons
  /// use) are merged into the lowest-id point of the group; 0 merges exact duplicates only.
  double mergeTolerance = 0.0;
  /// Duplicate vertices (and so cut edges) until every edge has at most 2 triangles and the
  /// triangles around every vertex form one fan.
  bool splitNonManifold = false;
  /// Orient each component consistently; closed components face outward (positive volume).
  bool orient = true;
  /// Close the holes of the oriented mesh (boundary loops, e.g. where a scanner saw nothing)
  /// with a minimum-area triangulation refined to the density around the hole and faired
  /// (CGAL's triangulate_refine_and_fair_hole). Needs a manifold mesh (splitNonManifold).
  bool fillHoles = false;
  /// With fillHoles: loops of more boundary edges than this stay open (0: any size). The long
  /// loops are usually a surface's outer border (a terrain, a scan of one side), which a lid
  /// would not repair.
  int64_t maxHoleEdges = 1000;
  /// Remove slivers, last (after hole filling): collapse the shortest edge of each needle
  /// (longest side over shortest above sliverEdgeRatio) into the endpoint that changes the volume
  /// least, flip the longest edge of each cap (an angle above sliverAngle), wherever that keeps
  /// the topology and folds no triangle (CGAL's remove_almost_degenerate_faces). Why: the base
  /// complex keeps slivers (a collapse may make triangles as thin as the ones it removes), and
  /// the paths cannot be traced through their near-flat stars. No point moves; collapsed points
  /// are dropped. Needs a manifold mesh (splitNonManifold).
  bool removeSlivers = false;
  double sliverAngle = 170.0;    ///< degrees, 120 .. 180: a larger angle makes a cap
  double sliverEdgeRatio = 10.0; ///< >= 3: a larger ratio of longest to shortest side, a needle

  // Dropping components (edge-connected, across every shared edge), after orientation and
  // before hole filling, so that no hole of a dropped part is filled and every count is of the
  // input's triangles. Off by default: a user's mesh is never cut silently. A component is
  // counted under the first rule that drops it, in this order.

  /// Drop the components that cannot be oriented (Moebius-like), which no later repair
  /// accepts; what is left may then be filled and cleaned.
  bool dropNonOrientable = false;
  /// Drop the components of fewer triangles than this (0: off): a scan's stray islands. An
  /// absolute count rather than a fraction of the largest component: what a component needs in
  /// the later stages (a base complex of a few faces, charts with samples) is a number of
  /// triangles, whatever the size of its neighbours, and the case a fraction would serve (one
  /// body and debris) is keepLargestComponent's.
  int64_t minComponentTriangles = 0;
  /// Keep only the component of the most triangles (the first of equal ones): a scanned object
  /// and the debris around it.
  bool keepLargestComponent = false;
};

/// Smallest sliverAngle and sliverEdgeRatio: below them ordinary triangles count as slivers.
constexpr double kMinSliverAngle = 120.0;
constexpr double kMinSliverEdgeRatio = 3.0;

/// What tcMeshPreparation found and changed. Counts of removed things refer to the stage in
/// which they were removed: inputPoints = mergedPoints + unusedPoints + (outputPoints -
/// splitVertices - holePoints + sliverPoints + droppedComponentPoints).
struct PreparationReport
{
  int64_t inputPoints = 0;
  int64_t inputPolygons = 0;
  int64_t polygonsTriangulated = 0; ///< input polygons with more than 3 corners
  int64_t mergedPoints = 0;         ///< used points merged into another (lower-id) point
  int64_t degenerateFaces = 0;      ///< triangles (or polygons of < 3 corners) dropped: repeated
                                    ///< corner or area below 1e-12 diagonal^2
  int64_t duplicateFaces = 0;       ///< triangles dropped: same 3 points as an earlier one
  int64_t flippedFaces = 0;         ///< output triangles whose corner order was reversed
  int64_t unusedPoints = 0;         ///< input points no kept triangle uses (merged ones excluded)
  int64_t nonManifoldEdges = 0;     ///< edges with more than 2 triangles (before splitting)
  int64_t nonManifoldVertices = 0;  ///< vertices whose triangles form > 1 fan (before splitting)
  int64_t splitVertices = 0;        ///< vertex copies added by splitNonManifold
  int64_t filledHoles = 0;          ///< boundary loops closed by fillHoles
  int64_t holeTriangles = 0;        ///< triangles added to close them
  int64_t holePoints = 0;           ///< points added inside the patches (refinement)
  int64_t unfairedHoles = 0;        ///< filled holes whose patch could not be faired
  int64_t openHoles = 0;            ///< loops fillHoles left open (too long, or no manifold
                                    ///< triangulation, or a non-manifold mesh)
  int64_t droppedFragments = 0;     ///< with fillHoles: components of fewer than 4 triangles
                                    ///< dropped (no closed surface; a filled lone triangle
                                    ///< would be a flat two-sided pair)
  int64_t slivers = 0;              ///< with removeSlivers: caps and needles found
  int64_t sliverPoints = 0;         ///< points collapsed away to remove needles
  int64_t reshapedTriangles = 0;    ///< output triangles with new corners (cap flips)
  int64_t remainingSlivers = 0;     ///< slivers no valid collapse or flip removed
  int64_t boundaryEdges = 0;        ///< output edges with exactly 1 triangle
  int64_t components = 0;           ///< edge-connected components of the output
  int64_t nonOrientableComponents = 0; ///< components left unoriented (Moebius-like)
  int64_t closedComponents = 0;        ///< components without boundary or non-manifold edge
  int64_t outputPoints = 0;
  int64_t outputTriangles = 0;

  // Components dropped by the options, each under the first rule that dropped it.
  int64_t droppedNonOrientable = 0; ///< with dropNonOrientable: components
  int64_t droppedNonOrientableTriangles = 0;
  int64_t droppedSmallComponents = 0; ///< with minComponentTriangles: components
  int64_t droppedSmallTriangles = 0;
  int64_t droppedMinorComponents = 0; ///< with keepLargestComponent: the other components
  int64_t droppedMinorTriangles = 0;
  int64_t droppedComponentPoints = 0; ///< points only these (and droppedFragments) used

  int64_t nonOrientableTriangles = 0; ///< triangles of the nonOrientableComponents
  /// The output's largest component (the first of equal ones): its triangles, and whether it
  /// is closed (no boundary or non-manifold edge) and oriented, so that keepLargestComponent
  /// would leave a closed, oriented mesh (but for non-manifold vertices).
  int64_t largestComponentTriangles = 0;
  bool largestComponentClosed = false;

  /// True if the output geometry or connectivity differs from the input: polygons
  /// triangulated, points merged or dropped, faces or components dropped or flipped, or
  /// vertices split.
  bool changed() const;
  /// Multi-line summary, one line per non-zero item, e.g. "merged 12 duplicate points".
  std::string text() const;
};

struct PreparationResult
{
  TriMesh mesh;                           ///< #Vout points, #Fout triangles
  std::vector<int64_t> inputPointId;      ///< #Vout: input point it came from (lowest of a
                                          ///< merged group); -1 for a hole-filling point
  std::vector<int64_t> inputCellId;       ///< #Fout: input polygon it came from; -1 for a
                                          ///< hole-filling triangle
  std::vector<uint8_t> nonManifoldEdge;   ///< #Fout: 1 if a side is shared by > 2 triangles
                                          ///< (before splitting)
  std::vector<uint8_t> nonManifoldVertex; ///< #Vout: 1 if the triangles around it formed more
                                          ///< than one fan (before splitting; copies too)
  std::vector<uint8_t> boundaryVertex;    ///< #Vout: 1 on an open boundary of the output
  std::vector<int32_t> componentId;       ///< #Fout: edge-connected component, numbered in the
                                          ///< order of their first triangle
  PreparationReport report;
};

/// True if a prepared mesh is what the base complex and the stages after it need: every
/// component closed, manifold (nothing left unsplit) and consistently oriented (false with
/// orient off, which leaves the orientation unchecked).
bool closedManifold(const PreparationReport& report, const PreparationOptions& options);

/// What keeps a prepared mesh from being a closed, oriented manifold, each defect with its count
/// and the option that repairs it (property and `trichart build` flag), joined by "; ", e.g.
/// "3 boundary edges (close the holes: FillHoles, trichart build --fill-holes)"; "" when
/// closedManifold() holds. Every face (CLI, Python, viewer) shows this text.
std::string closedManifoldRepairs(
  const PreparationReport& report, const PreparationOptions& options);

/// Cleans a polygon soup into a triangle mesh, in this order: (1) validate; (2) merge duplicate
/// points; (3) triangulate polygons (ear clipping in the plane of the Newell normal) and drop
/// degenerate triangles; (4) drop duplicate triangles; (5) drop unused points; (6) find
/// non-manifold edges and vertices and (7) split them if asked; (8) orient; (9) drop
/// components (non-orientable, small, all but the largest: if asked); (10) fill holes (if
/// asked) and orient again; (11) remove slivers (if asked); (12) count boundary edges and
/// components. Output points keep the input order (split copies, then hole-filling points are
/// appended); output triangles keep the polygon order (hole-filling triangles appended;
/// dropping components and removing slivers only drop points and triangles). Deterministic.
///
/// @param[in] soup      #V points, #P polygons with ids in [0, #V)
/// @param[in] options   see PreparationOptions
/// @param[in] progress  reported a few times; may abort (tc::Aborted)
/// @throws tc::InputError  no points, no polygons, malformed offsets, a polygon id out of range,
///   NaN/Inf coordinates (names the first such point and the count), zero total area, no
///   triangle with non-zero area left after cleaning, or no component left after dropping
///   components (says which rule dropped how many); more than 2^31 - 1 output points or
///   triangles
PreparationResult prepareMesh(
  const PolygonSoup& soup, const PreparationOptions& options = {}, const Progress& progress = {});
} // namespace tc
