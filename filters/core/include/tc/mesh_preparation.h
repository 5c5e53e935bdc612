// SPDX-License-Identifier: BSD-3-Clause
/// @file mesh_preparation.h
/// The tcMeshPreparation stage: turns a polygon soup as read from a file into a clean, oriented
/// triangle mesh that the later stages can trust, and reports every change it made and every
/// defect it found (per element and in total).
#pragma once

#include "tc/mesh.h"
#include "tc/progress.h"

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
};

/// What tcMeshPreparation found and changed. Counts of removed things refer to the stage in
/// which they were removed: inputPoints = mergedPoints + unusedPoints + (outputPoints -
/// splitVertices).
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
  int64_t boundaryEdges = 0;        ///< output edges with exactly 1 triangle
  int64_t components = 0;           ///< edge-connected components of the output
  int64_t nonOrientableComponents = 0; ///< components left unoriented (Moebius-like)
  int64_t closedComponents = 0;        ///< components without boundary or non-manifold edge
  int64_t outputPoints = 0;
  int64_t outputTriangles = 0;

  /// True if the output geometry or connectivity differs from the input: polygons
  /// triangulated, points merged or dropped, faces dropped or flipped, or vertices split.
  bool changed() const;
  /// Multi-line summary, one line per non-zero item, e.g. "merged 12 duplicate points".
  std::string text() const;
};

struct PreparationResult
{
  TriMesh mesh;                           ///< #Vout points, #Fout triangles
  std::vector<int64_t> inputPointId;      ///< #Vout: input point it came from (lowest of a
                                          ///< merged group)
  std::vector<int64_t> inputCellId;       ///< #Fout: input polygon it came from
  std::vector<uint8_t> nonManifoldEdge;   ///< #Fout: 1 if a side is shared by > 2 triangles
                                          ///< (before splitting)
  std::vector<uint8_t> nonManifoldVertex; ///< #Vout: 1 if the triangles around it formed more
                                          ///< than one fan (before splitting; copies too)
  std::vector<uint8_t> boundaryVertex;    ///< #Vout: 1 on an open boundary of the output
  std::vector<int32_t> componentId;       ///< #Fout: edge-connected component, numbered in the
                                          ///< order of their first triangle
  PreparationReport report;
};

/// Cleans a polygon soup into a triangle mesh, in this order: validate; merge duplicate points;
/// triangulate polygons (ear clipping in the plane of the Newell normal); drop degenerate and
/// duplicate triangles; find non-manifold edges and vertices (and split them if asked); orient;
/// drop unused points; count boundary edges and components. Output points keep the input
/// order (split copies are appended); output triangles keep the polygon order. Deterministic.
///
/// @param[in] soup      #V points, #P polygons with ids in [0, #V)
/// @param[in] options   see PreparationOptions
/// @param[in] progress  reported a few times; may abort (tc::Aborted)
/// @throws tc::InputError  no points, no polygons, malformed offsets, a polygon id out of range,
///   NaN/Inf coordinates (names the first such point and the count), zero total area, or no
///   triangle with non-zero area left after cleaning; more than 2^31 - 1 output points or
///   triangles
PreparationResult prepareMesh(
  const PolygonSoup& soup, const PreparationOptions& options = {}, const Progress& progress = {});
} // namespace tc
