// SPDX-License-Identifier: BSD-3-Clause
/// @file multilevel_internal.h
/// The steps of buildMultilevelMesh (tc/multilevel/multilevel_mesh.h), one concept a file:
///   vertex_quadrics.cpp      M0's quadrics, and the placement of a vertex from its quadric
///   live_faces.cpp           M0's faces as contraction goes, and the link condition on them
///   level_contraction.cpp    QSlim on one level's cluster graph: the cheapest edge first
///   derived_connectivity.cpp a level's faces and edges from M0 and its clusters
///   multilevel_mesh.cpp      the entry point: input checks, the levels one after another
///   multilevel_check.cpp     checkMultilevelMesh
#pragma once

#include "tc/multilevel/multilevel_mesh.h"

#include "detail/quadric.h"
#include "detail/vec3.h"

#include <cstdint>
#include <vector>

namespace tc
{
namespace detail
{
namespace multilevel
{
/// M0's vertex quadrics: each face's plane weighted by its area at its three corners, and
/// through each boundary edge (an edge of one face) the plane perpendicular to that face,
/// weighted by the edge's length squared (Garland and Heckbert's boundary constraint, which
/// keeps an open boundary from shrinking).
/// @param[in] edges  #E x 2 unique edges; edgeFaceCount[e] the faces of edge e
std::vector<Quadric> vertexQuadrics(const TriMesh& mesh, const std::vector<int32_t>& edges,
  const std::vector<int32_t>& edgeFaceCount, const std::vector<int32_t>& edgeFace);

/// Where a vertex with quadric `q` goes (see tc::Placement): the minimizer of q, or where q is
/// singular the minimizer nearest `mean` (the mean of its cluster's M0 positions).
struct Placed
{
  V3 p;
  double error; ///< q(p), >= 0
  Placement how;
};
Placed placeVertex(const Quadric& q, const V3& mean);

/// q(p) clamped at 0 against round-off.
double evaluate(const Quadric& q, const V3& p);

/// A level's vertices as the contraction sees them: summed quadrics, sums of M0 positions and
/// M0 counts (so that a merged vertex's mean is the sum over the merge), and its edges.
struct ClusterGraph
{
  std::vector<Quadric> quadrics;
  std::vector<V3> positionSums;
  std::vector<int32_t> counts;
  std::vector<int32_t> edges; ///< #E x 2 unique pairs a < b

  int32_t size() const { return static_cast<int32_t>(counts.size()); }
};

/// M0's faces under the contractions of M0 into M1: which faces are still triangles, in which
/// current vertices; it answers the link condition (Dey et al. 1998) of an edge before it is
/// contracted. Faces of a vertex sit in a singly linked list per vertex (FaceNext_ per
/// corner), so a contraction relinks them without allocating.
class LiveFaces
{
public:
  explicit LiveFaces(const TriMesh& mesh);

  /// Whether contracting a and b keeps the surface homeomorphic: Lk(a) n Lk(b) = Lk(ab), with a
  /// boundary coned off to a virtual vertex.
  bool linkConditionHolds(int32_t a, int32_t b);

  /// Records that b merged into a: faces of both die, the others of b now name a.
  void contract(int32_t a, int32_t b);

private:
  /// Gathers the live faces of v into Faces_ (dropping dead ones from its list).
  void gather(int32_t v);
  /// Neighbours of v into `ring`, marked with Stamp_ in `mark`, with in `use` how many live
  /// faces share the edge to each.
  void gatherRing(
    int32_t v, std::vector<int32_t>& mark, std::vector<int32_t>& use, std::vector<int32_t>& ring);
  bool hasFace(int32_t a, int32_t x, int32_t y);
  /// Whether the vertex of this ring has a boundary edge (an edge of one face).
  static bool oneSidedEdge(const std::vector<int32_t>& ring, const std::vector<int32_t>& use);

  std::vector<int32_t> Tri_;           ///< #F x 3 current corners
  std::vector<uint8_t> Alive_;         ///< #F
  std::vector<int32_t> Head_;          ///< #V: first corner (3 f + i) of v's list, -1 none
  std::vector<int32_t> Next_;          ///< 3 #F: next corner of the same vertex's list
  std::vector<int32_t> Faces_;         ///< scratch: live faces of the last vertex gathered
  std::vector<int32_t> RingA_, RingB_; ///< scratch: the rings of a and b
  std::vector<int32_t> MarkA_, MarkB_; ///< #V: stamp of the last check that saw it in a ring
  std::vector<int32_t> UseA_, UseB_;   ///< #V: faces on the edge from a (b) to it
  int32_t Stamp_ = 0;
};

/// QSlim on one level: contracts the cheapest edge of `graph` (the merged quadric at its
/// placement; ties by vertex ids) until `target` vertices remain or no edge is left that may
/// be contracted. With `faces`, only edges whose link condition holds are contracted.
/// @return #V: the parent of each vertex, in 0 .. parents - 1, numbered by lowest member
std::vector<int32_t> contractLevel(const ClusterGraph& graph, int32_t target, LiveFaces* faces,
  const Progress& progress, int32_t* parents);

/// Level k's faces, source faces and edges (MultilevelLevel) derived from M0 through
/// `clusterOf` (M0 vertex -> level-k vertex).
/// @param[in] edges0  M0's unique edges, #E x 2
void deriveConnectivity(const TriMesh& mesh, const std::vector<int32_t>& edges0,
  const std::vector<int32_t>& clusterOf, MultilevelLevel& level);

/// M0's unique edges (#E x 2, a < b, sorted) with the face count and first face of each.
void uniqueEdges(const TriMesh& mesh, std::vector<int32_t>& edges, std::vector<int32_t>& faceCount,
  std::vector<int32_t>& firstFace);
} // namespace multilevel
} // namespace detail
} // namespace tc
