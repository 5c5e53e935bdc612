// SPDX-License-Identifier: BSD-3-Clause
/// @file simplifier.h
/// The simplifier behind buildBaseComplex (tc/gim/base_complex.h; Feng et al. 2010 section 5.1,
/// MAPS of Lee et al. 1998): quadric half-edge collapses over a corner table, the MAPS
/// parameterization of every removed vertex, and the bijection check of every collapse. Private
/// to the base complex. One concept a file, in the order of run()'s steps:
///   corner_table.cpp        1. input checks, spatial reorder, twins, fans, feature flags
///   collapse_queue.cpp      2. quadrics, legal collapses, the lazy priority queue
///   half_edge_collapse.cpp  3-4. rules and flat ring of one collapse, MAPS reassignment, undo
///   bijection_check.cpp     5. charts of the base domain, validity of input triangles
///   flip_repair.cpp         6. last check of every triangle, parameter-domain smoothing
///   base_complex.cpp        the entry point, run() and its collapse loop, output
#pragma once

#include "tc/gim/base_complex.h"

#include "detail/geometry2d.h"
#include "detail/half_edge.h"
#include "detail/quadric.h"
#include "detail/vec3.h"

#include <algorithm>
#include <cstdint>
#include <deque>
#include <queue>
#include <utility>
#include <vector>

namespace tc
{
namespace detail
{
namespace base_complex
{
/// Barycentric slack below which a point still counts as inside a flat triangle (round-off of
/// the z^a map and of the 2x2 solves); beyond it the point is snapped (MAPS flip repair).
constexpr double kInsideSlack = 1e-12;

/// Bounding box of n points stored #n x 3 in `points`.
inline void boundingBox(const double* points, int32_t n, double lo[3], double hi[3])
{
  for (int c = 0; c < 3; ++c)
  {
    lo[c] = hi[c] = points[c];
  }
  for (int32_t v = 1; v < n; ++v)
  {
    for (int c = 0; c < 3; ++c)
    {
      lo[c] = std::min(lo[c], points[3 * v + c]);
      hi[c] = std::max(hi[c], points[3 * v + c]);
    }
  }
}

struct HeapEntry
{
  double cost;
  int32_t vertex;
  int32_t rank; ///< input id of vertex
};
/// Smallest cost first; equal costs by input vertex id, so the order never depends on heap
/// internals.
struct HeapOrder
{
  bool operator()(const HeapEntry& a, const HeapEntry& b) const
  {
    return a.cost > b.cost || (a.cost == b.cost && a.rank > b.rank);
  }
};

/// A legal collapse u -> target along halfEdge, with its quadric cost.
struct Candidate
{
  double cost;
  int32_t target;
  int32_t halfEdge;
  int32_t rank; ///< input id of target
};

// Hidden: private to TriChartCore, and not interposable, so that under -fPIC the compiler may
// still inline the calls between the members defined in one file.
#pragma GCC visibility push(hidden)

/// Quadric-error half-edge collapses with the MAPS parameterization, over flat arrays.
///
/// A dedicated corner table (triangle corners + opposite half-edges, Rossignac-style) instead of
/// CGAL's Surface_mesh_simplification: MAPS needs, at every collapse, the ordered one-ring, the
/// faces that survive (so parameterized points can move into them by index) and the feature
/// flags of every half-edge, the undo of a collapse that the bijection check rejects, and a
/// flat-array structure gives all of that with no per-collapse allocation (scratch vectors are
/// reused) and no property-map or handle indirection in the inner loops.
///
/// Half-edge h = 3f + i runs from corner i to corner i + 1 of face f; opp[h] is its twin.
/// Turning around a vertex: the half-edge after h (outgoing from the same vertex, next in
/// counter-clockwise order) is opp[prev(h)].
class Simplifier
{
public:
  /// Checks and links the input (step 1); throws InputError as buildBaseComplex documents.
  Simplifier(const TriMesh& mesh, const std::vector<uint8_t>& featureVertex,
    const std::vector<uint8_t>& cornerVertex, const std::vector<int32_t>& featureEdges,
    const BaseComplexOptions& options)
    : Mesh_(mesh)
    , Options_(options)
  {
    this->validateAndLink(featureVertex, cornerVertex, featureEdges);
  }

  /// Steps 2 to 6 and the output, in input ids.
  BaseComplexResult run(const Progress& progress);

private:
  // Charts of the base domain, for the bijection check (see triangleValid).
  /// Where a point of the parameterization lies: the n base vertices with a nonzero
  /// barycentric (w) in base face `face`; a base vertex is its own support (n = 1).
  struct Support
  {
    int n = 0;
    int32_t face = -1;
    int32_t v[3] = { -1, -1, -1 };
    double w[3] = { 0, 0, 0 };
  };
  struct StarChart
  {
    std::vector<int32_t> ring; ///< ring vertices counter-clockwise
    /// he[i]: half-edge s -> ring[i]; its face is (s, ring[i], ring[i+1])
    std::vector<int32_t> he;
    std::vector<P2> z; ///< flat position of ring[i]; s at the origin
  };
  /// The images of an input triangle's corners: their supports, and every base vertex they
  /// name (all[0 .. na)), sorted by input id without repeats.
  struct TriangleImages
  {
    Support sup[3];
    int32_t all[9];
    int na = 0;
  };

  // 1. corner_table.cpp: the input checked, renumbered and linked.
  void validateAndLink(const std::vector<uint8_t>& featureVertex,
    const std::vector<uint8_t>& cornerVertex, const std::vector<int32_t>& featureEdges);
  void checkSizes(const std::vector<uint8_t>& featureVertex,
    const std::vector<uint8_t>& cornerVertex, const std::vector<int32_t>& featureEdges);
  void checkTriangles() const;
  void reorder();
  void linkOutgoing(std::vector<int32_t>& outTarget);
  int32_t findHe(int32_t a, int32_t b, const std::vector<int32_t>& outTarget, int* count) const;
  void linkTwins(const std::vector<int32_t>& outTarget);
  void linkFans();
  void flagFeatures(const std::vector<uint8_t>& featureVertex,
    const std::vector<uint8_t>& cornerVertex, const std::vector<int32_t>& featureEdges,
    const std::vector<int32_t>& outTarget);

  // 2. collapse_queue.cpp: quadrics and the lazy priority queue.
  void initQuadrics();
  void addFaceQuadrics();
  void addFeatureQuadrics();
  bool legal(int32_t u, int32_t h) const;
  void gatherCandidates(int32_t u);
  void push(int32_t u, double cost);
  void queueCheapest(int32_t u);
  void buildQueue();
  void requeueAfter(int32_t v);

  // base_complex.cpp: the state of the collapses and the loop that makes them.
  void initState();
  void collapseLoop(const Progress& progress, BaseComplexResult& result);
  bool collapseCheapest(
    int32_t u, double key, bool bounded, std::vector<int32_t>& deferred, BaseComplexResult& result);
  bool tryCollapse(int32_t u, int32_t h);
  void requeueDeferred(std::vector<int32_t>& deferred);
  BaseComplexResult output() const;

  // 3-4. half_edge_collapse.cpp: one collapse u -> v, its MAPS reassignment and its undo.
  bool prepare(int32_t u, int32_t h0);
  void gatherRing(int32_t u, int32_t h0);
  bool linkConditionHolds();
  bool findCurveSides();
  double measureRing();
  bool newTrianglesAllowed(double worstOld) const;
  bool flattenRing();
  bool flattenChain(int begin, int end, double span, bool conformal, std::vector<P2>& z) const;
  bool fanTilesRing() const;
  void apply(int32_t u);
  void reassignPoints(int32_t u);
  void removeFaces();
  void undo();
  void restoreFaces();
  void restorePoints();
  void relocate(int32_t p, int j);
  void placeOnFeature(int32_t p, double t);
  void locateFlat(int32_t p, const P2& P, int side, int guess);
  void store(int32_t p, int j, double bv, double bj, double bj1);

  // 5. bijection_check.cpp: input triangles drawn in the charts of the base domain.
  bool movedTrianglesValid();
  bool movedPointsValid();
  bool changedStarsValid();
  bool checkTriangle(int32_t t);
  void commitStarUsers();
  Support supportOf(int32_t p) const;
  const StarChart& star(int32_t s, bool chart) const;
  bool inStar(int32_t s, const Support& sup, P2* at) const;
  bool inStar(int32_t s, const Support sup[3], P2 at[3]) const;
  bool triangleValid(int64_t t, int32_t* starCentre = nullptr) const;
  // The steps of triangleValid, the hottest code of the simplification: inline, and defined in
  // bijection_check.cpp, the only file that may call them, so that they fold back into it.
  inline void gatherImages(int64_t t, TriangleImages& im) const;
  inline int32_t spannedFace(const TriangleImages& im) const;
  inline bool drawnInFace(const TriangleImages& im, bool* valid) const;
  inline bool drawnInHinge(const TriangleImages& im, bool* valid) const;
  inline bool unfoldHinge(
    const Support sup[3], int32_t a, int32_t b, int32_t c, int32_t d, P2 p[3]) const;
  inline bool drawnInStar(const TriangleImages& im, int32_t* starCentre) const;

  // 6. flip_repair.cpp: the last check and the parameter-domain smoothing.
  int64_t repairFlips(const Progress& progress);
  void gatherMovable(const std::vector<int32_t>& badList, int ring, std::vector<uint8_t>& inSet,
    std::vector<int32_t>& movable) const;
  void reevaluate(const std::vector<int32_t>& movable, std::vector<uint8_t>& invalid,
    std::vector<int32_t>& badList) const;
  int countInvalidAround(int32_t p) const;
  bool smooth(int32_t p);
  bool smoothingChart(int32_t p, int32_t* centre, P2* mean) const;

  V3 pos(int32_t v) const { return { Points3_[3 * v], Points3_[3 * v + 1], Points3_[3 * v + 2] }; }
  /// Half-edge i of the input (3 f + c in input face ids) in internal ids: every loop whose
  /// order can show (lists, sums, error messages) runs in this order.
  int32_t inputHe(int32_t i) const { return 3 * FaceOf_[i / 3] + i % 3; }
  /// The half-edge after h out of the same vertex, counter-clockwise.
  int32_t nextOutgoing(int32_t h) const { return Opp_[prevHe(h)]; }
  bool faceHas(int32_t f, int32_t v) const
  {
    return F_[3 * f] == v || F_[3 * f + 1] == v || F_[3 * f + 2] == v;
  }
  /// Puts point p in face h / 3 with barycentrics w0 at the corner where h starts, w1 and w2 at
  /// the next ones, scaled to sum 1 (the face's list of points is not touched).
  void setPoint(int32_t p, int32_t h, double w0, double w1, double w2)
  {
    const int c = h % 3;
    double* b = &PointBary_[3 * p];
    const double sum = w0 + w1 + w2;
    b[c] = w0 / sum;
    b[(c + 1) % 3] = w1 / sum;
    b[(c + 2) % 3] = w2 / sum;
    PointFace_[p] = h / 3;
  }
  /// Whether the check of the current collapse has seen triangle t already (and marks it).
  bool seen(int32_t t) { return TriMark_[t] == TriCounter_ || (TriMark_[t] = TriCounter_, false); }

  const TriMesh& Mesh_;
  const BaseComplexOptions& Options_;

  // The input in a spatially coherent order (vertices along a Morton curve, faces by their
  // lowest vertex), so that the random access of the collapses and checks stays in cache.
  // Every tie and every "lowest-numbered" rule compares input ids (VertexRank_), and every
  // accumulation runs in input order, so the result does not depend on this order.
  std::vector<double> Points3_;     ///< #V x 3 positions, internal order
  std::vector<int32_t> Tri_;        ///< #F x 3 input triangles, internal ids
  std::vector<int32_t> VertexRank_; ///< internal vertex -> input vertex id
  std::vector<int32_t> VertexOf_;   ///< input vertex id -> internal vertex
  std::vector<int32_t> FaceOf_;     ///< input face id -> internal face
  int32_t NumVertices_ = 0;
  int32_t NumFaces_ = 0;
  int64_t FaceCount_ = 0;

  // Mesh: corners, twins, one outgoing half-edge and the valence of every vertex.
  std::vector<int32_t> F_;
  std::vector<int32_t> Opp_;
  std::vector<int32_t> Out_;
  std::vector<int32_t> Valence_;
  std::vector<uint8_t> FaceAlive_;
  std::vector<uint8_t> FeatureHe_; ///< half-edge lies on a feature curve (both twins set)

  // Input adjacency: half-edges out of vertex v are InHe_[InOffsets_[v] .. InOffsets_[v+1]).
  std::vector<int32_t> InOffsets_;
  std::vector<int32_t> InHe_;

  // Vertices.
  std::vector<uint8_t> Feature_; ///< on a feature curve
  std::vector<uint8_t> Pinned_;  ///< corner, junction or curve end: never removed
  std::vector<uint8_t> Removed_;
  std::vector<Quadric> Quadric_;
  std::vector<double> Area_; ///< area behind each quadric (for the reported mean error)
  std::vector<double> Key_;  ///< key of the live heap entry of each vertex (+inf: none)
  std::vector<int32_t> Mark_;
  int32_t MarkCounter_ = 0;
  double Diag2_ = 1.0;

  // MAPS: every removed vertex lies in one live face, in a singly linked list per face.
  std::vector<int32_t> Head_;
  std::vector<int32_t> Next_;
  std::vector<int32_t> PointFace_;
  std::vector<double> PointBary_;

  std::priority_queue<HeapEntry, std::vector<HeapEntry>, HeapOrder> Heap_;

  // Scratch of one collapse u -> v = x_0: ring x_0..x_{k-1} counter-clockwise, face j is
  // (u, x_j, x_{j+1}) and ringHe[j] is its half-edge u -> x_j. Reused: no allocation per step.
  std::vector<Candidate> Candidates_;
  std::vector<int32_t> RingHe_, RingV_, RingF_;
  std::vector<double> Theta_, Radius_;
  std::vector<P2> ZA_, ZB_;
  std::vector<std::pair<int32_t, int32_t>> Points_;
  std::vector<double> OldBary_;
  int32_t UndoOpp_[4] = { 0, 0, 0, 0 };
  uint8_t UndoFeature_[4] = { 0, 0, 0, 0 };
  int32_t UndoOut_[3] = { 0, 0, 0 };
  std::vector<int32_t> TriMark_;
  int32_t TriCounter_ = 0;
  // Input triangles drawn in the star chart of a base vertex x, in a doubly linked list per x,
  // so that they are drawn again when that star changes; updates wait for the collapse to be
  // accepted (PendingStar_).
  std::vector<int32_t> StarHead_, TriStar_, TriStarPrev_, TriStarNext_;
  std::vector<std::pair<int32_t, int32_t>> PendingStar_;
  int K_ = 0;
  int M_ = 0; ///< feature collapse: index of the other curve neighbour w = x_m; else K_
  int32_t U_ = -1, V_ = -1;
  double L1_ = 0, L2_ = 0; ///< feature collapse: |u - v| and |u - w|
  int64_t Snapped_ = 0;

  // Star charts, computed when first asked for and recomputed after the star changes.
  mutable std::vector<int32_t> StarSlot_;
  mutable std::vector<uint8_t> StarValid_; ///< 0 stale, 1 ring and he valid, 2 z too
  mutable std::deque<StarChart> Stars_;    ///< deque: references stay valid as it grows
  mutable std::vector<double> StarTheta_, StarRadius_;
};

#pragma GCC visibility pop
} // namespace base_complex
} // namespace detail
} // namespace tc
