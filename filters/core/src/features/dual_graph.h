// SPDX-License-Identifier: BSD-3-Clause
/// @file dual_graph.h
/// The weighted dual graph of spectral clustering (Feng et al. 2010, section 4.2): faces joined
/// across shared edges and, below a radius, to the faces within that dual-path length, each edge
/// with its length dist(f_i, f_j) and whether a crest line separates the two faces (beta of
/// eq. 3). Also its connected pieces.
#pragma once

#include "tc/common/mesh.h"
#include "tc/common/progress.h"

#include <cstdint>
#include <vector>

namespace tc
{
namespace detail
{
namespace spectral
{
/// Symmetric graph over faces in CSR form: the neighbours of f are ids[offsets[f] ..
/// offsets[f + 1]), with the dual-path length and whether a crest separates the two.
struct DualGraph
{
  std::vector<int64_t> offsets; ///< #F + 1
  std::vector<int32_t> ids;
  std::vector<double> dist;
  std::vector<uint8_t> crest;
};

/// Faces sharing a mesh edge (every pair of the fan of a non-manifold edge), rows sorted by
/// neighbour id. The length is |c_i - m_e| + |m_e - c_j| through the midpoint m_e of the shared
/// edge, so that sums along dual paths are geodesic lengths on the surface (section 4.2,
/// dist(f_i, f_j)). A crest separates the two faces when both ends of the shared edge are crest
/// vertices. A pair that shares two edges keeps the shorter length, crest if either edge is.
/// @param[in] centroids    #F x 3 face centroids
/// @param[in] crestVertex  #V flags, may be empty
DualGraph buildAdjacentDual(const TriMesh& mesh, const std::vector<double>& centroids,
  const std::vector<uint8_t>& crestVertex, const Progress& progress);

/// Section 4.2: "we add an additional dual edge between f_i, f_j if dist(f_i, f_j) < 2 dist-bar"
/// for non-adjacent faces, dist the dual-path (geodesic) length: every pair of faces, one of
/// them marked in `active`, whose shortest path over `adj` is below `radius`. The crest flag of
/// such an edge is that of the shortest path (set when it crosses a crest). Rows: the adjacent
/// row, then the extra edges.
/// @param[in] active  #F flags
DualGraph addExtraEdges(const DualGraph& adj, const std::vector<uint8_t>& active, double radius,
  const Progress& progress);

/// The graph of the components that are clustered exactly, and eq. 3's sigma_d on it.
struct ExactGraph
{
  DualGraph graph;        ///< the adjacent graph with the extra edges of section 4.2
  double invSigmaD = 0.0; ///< 1 / sigma_d; 0 when all distances are equal (constant factor)
};

/// Extra edges (addExtraEdges) below extraEdgeFactor times the mean adjacent distance over the
/// faces `exact` marks; sigma_d is the standard deviation of dist over that graph's edges.
/// @param[in] exact  #F flags, or empty when no face is clustered exactly (empty result)
ExactGraph buildExactGraph(const DualGraph& adjacent, const std::vector<uint8_t>& exact,
  double extraEdgeFactor, const Progress& progress);

/// Connected pieces of a graph, numbered in the order of their first (lowest) face.
struct Pieces
{
  std::vector<int32_t> of;    ///< #F piece of each face
  std::vector<int64_t> size;  ///< #pieces face counts
  std::vector<int32_t> first; ///< #pieces lowest face of each piece
};

/// Pieces of `g`; with `label`, of the subgraph of its edges between faces of the same label.
/// @param[in] label  #F labels or nullptr
Pieces findPieces(const DualGraph& g, const std::vector<int32_t>* label);

/// Sum, sum of squares and number of the distances of the edges (each counted once) of a graph
/// that leave the faces a mask marks.
struct DistanceMoments
{
  double sum = 0.0;
  double squares = 0.0;
  double count = 0.0;
};

/// @param[in] use  #F flags
DistanceMoments distanceMoments(const DualGraph& graph, const std::vector<uint8_t>& use);
} // namespace spectral
} // namespace detail
} // namespace tc
