// SPDX-License-Identifier: BSD-3-Clause
/// @file face_adjacency.h
/// The dual graph of a triangle mesh as section 4.2 of Feng et al. 2010 uses it: faces joined
/// across shared mesh edges, every ordered pair of faces of a non-manifold edge's fan. The one
/// definition under the spectral graph (eq. 3) and the graph cut (eq. 4).
#pragma once

#include "tc/common/mesh_topology.h"

#include <cstdint>
#include <vector>

namespace tc
{
namespace detail
{
/// CSR: the neighbours of face f are faces[offsets[f] .. offsets[f + 1]), in edge-table order of
/// the shared edge and, along one edge, in the order of its fan. A face that holds an edge
/// twice (a degenerate triangle) is its own neighbour there.
struct FaceAdjacency
{
  std::vector<int64_t> offsets; ///< #F + 1
  std::vector<int32_t> faces;   ///< neighbour face of each entry
  std::vector<int32_t> edges;   ///< mesh edge shared with that neighbour
};

/// Whether a crest line runs along the mesh edge (a, b), so that beta of eq. 3 and 4 applies to
/// the two faces it separates: both ends are crest vertices (crestVertices()).
/// @param[in] crestVertex  #V flags, or empty (no crest anywhere)
inline bool crestAlong(const std::vector<uint8_t>& crestVertex, int32_t a, int32_t b)
{
  return !crestVertex.empty() && crestVertex[a] && crestVertex[b];
}

/// @param[in] edges  buildEdgeTable() of the mesh
/// @param[in] nf     number of faces
FaceAdjacency buildFaceAdjacency(const EdgeTable& edges, int64_t nf);
} // namespace detail
} // namespace tc
