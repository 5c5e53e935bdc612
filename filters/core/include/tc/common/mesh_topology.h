// SPDX-License-Identifier: BSD-3-Clause
/// @file mesh_topology.h
/// Adjacency of a triangle mesh in compressed (CSR) form: the faces around each vertex, the
/// unique undirected edges with their faces, and the one-ring of each vertex. Built once per
/// stage in O(#F log #F); no per-element heap allocation.
#pragma once

#include "tc/common/mesh.h"

#include <cstdint>
#include <vector>

namespace tc
{
/// Faces around every vertex: faces of vertex v are faceIds[offsets[v] .. offsets[v+1]).
struct VertexFaces
{
  std::vector<int64_t> offsets; ///< #V + 1
  std::vector<int32_t> faceIds; ///< 3 #F
};

/// Unique undirected edges. Edge e joins vertices[2e] < vertices[2e+1]; its faces are
/// edgeFaces[faceOffsets[e] .. faceOffsets[e+1]) (1 on a boundary, 2 inside, > 2 non-manifold).
/// faceEdges[3f + i] is the edge from corner i to corner (i+1)%3 of face f.
struct EdgeTable
{
  std::vector<int32_t> vertices;    ///< #E x 2, sorted pair
  std::vector<int64_t> faceOffsets; ///< #E + 1
  std::vector<int32_t> edgeFaces;   ///< 3 #F
  std::vector<int32_t> faceEdges;   ///< #F x 3: edge of side (i, i+1) of each face

  int64_t numEdges() const { return static_cast<int64_t>(vertices.size() / 2); }
  int64_t valence(int64_t e) const { return faceOffsets[e + 1] - faceOffsets[e]; }
};

/// Vertex neighbours (one-ring), sorted: neighbours of v are ids[offsets[v] .. offsets[v+1]).
struct VertexRing
{
  std::vector<int64_t> offsets; ///< #V + 1
  std::vector<int32_t> ids;
};

/// @param[in] triangles  #F x 3 vertex ids, all in [0, numPoints)
VertexFaces buildVertexFaces(const std::vector<int32_t>& triangles, int64_t numPoints);

/// @param[in] triangles  #F x 3 vertex ids; degenerate sides (equal ends) are not allowed
EdgeTable buildEdgeTable(const std::vector<int32_t>& triangles);

/// One-ring from the edge table.
VertexRing buildVertexRing(const EdgeTable& edges, int64_t numPoints);

/// Edges where a face label changes: every edge whose faces do not all have the same label.
/// @param[in] faceLabels  #F labels (e.g. cluster ids)
/// @return #B x 2 vertex ids, in edge-table order
std::vector<int32_t> labelBoundaryEdges(
  const EdgeTable& edges, const std::vector<int32_t>& faceLabels);
} // namespace tc
