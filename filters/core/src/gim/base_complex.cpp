// SPDX-License-Identifier: BSD-3-Clause
#include "tc/gim/base_complex.h"

#include "detail/geometry2d.h"
#include "detail/half_edge.h"
#include "detail/quadric.h"
#include "detail/star_map.h"
#include "detail/vec3.h"

#include "tc/common/errors.h"

// How this file works, in the order run() calls it:
//  1. validateAndLink: corner table of the input (twins found through per-vertex lists, no
//     sort), closed-manifold checks, feature flags. A vertex is pinned (never removed) at a
//     corner, or where a number of feature edges other than 2 meet (junctions, curve ends).
//     Internally vertices and faces are renumbered in a spatially coherent order (reorder());
//     ties and "lowest-numbered" rules still compare input ids, so the result is the same.
//  2. Quadrics (Garland-Heckbert, area-weighted, plus feature-edge planes) and a lazy priority
//     queue of half-edge collapses u -> v, cheapest first, ties by vertex id (deterministic).
//  3. prepare(): the rules of Feng et al. section 5.1 (no feature / non-feature collapse; a
//     feature vertex only moves along its own curve), the link condition, normals and shapes of
//     the new triangles, and the MAPS flattening of u's ring by z^a, in which the fan from v
//     must be a valid triangulation. At a feature vertex each side of the curve is flattened
//     onto a half plane, so the curve is straight in both.
//  4. apply(): MAPS reassignment. Every removed vertex stored in u's faces (and u) is placed in
//     the flat ring and located in the new fan; points on the curve through u go onto the new
//     curve edge by arc length (one barycentric exactly 0); a point outside every new triangle
//     by round-off is snapped into the nearest one. Then the corner table is updated.
//  5. movedTrianglesValid(): every input triangle at a moved point or at a base vertex whose
//     star changed must keep its orientation in the chart of its corners' images (one base face,
//     two faces unfolded about an edge, or a base vertex's star flattened by z^a); otherwise the
//     collapse is undone and rejected, so the map stays a bijection.
//  6. repairFlips(): a last check of every input triangle, with parameter-domain smoothing of
//     the rare leftovers, then output().

#include <algorithm>
#include <cmath>
#include <deque>
#include <limits>
#include <queue>
#include <string>
#include <utility>

namespace tc
{
namespace
{
using detail::kPi;
/// BaseComplexOptions::maxError stops the simplification only once the base complex has at most
/// one face per this many input points (64 input triangles each on average): under the geometry
/// images' default budget of one sample per point, a chart then averages 32 samples (level 3
/// has 45), where smaller charts would be left with a few samples each.
constexpr int64_t kPointsPerBoundedFace = 32;

/// Barycentric slack below which a point still counts as inside a flat triangle (round-off of
/// the z^a map and of the 2x2 solves); beyond it the point is snapped (MAPS flip repair).
constexpr double kInsideSlack = 1e-12;

using detail::nextHe;
using detail::prevHe;

using detail::cross;
using detail::dot;
using detail::norm;
using detail::sub;
using detail::V3;

using detail::barycentric;
using detail::orient;
using detail::P2;

/// Closest point of triangle (a, b, c) to p, as barycentrics, and its squared distance.
double closestBarycentric(const P2& p, const P2& a, const P2& b, const P2& c, double w[3])
{
  double inside[3];
  if (barycentric(p, a, b, c, inside) && inside[0] >= 0 && inside[1] >= 0 && inside[2] >= 0)
  {
    std::copy(inside, inside + 3, w);
    return 0.0;
  }
  const P2 corner[3] = { a, b, c };
  double best = std::numeric_limits<double>::infinity();
  for (int i = 0; i < 3; ++i)
  {
    const P2& s = corner[i];
    const P2& t = corner[(i + 1) % 3];
    const double ex = t.x - s.x, ey = t.y - s.y;
    const double len2 = ex * ex + ey * ey;
    double u = len2 > 0 ? ((p.x - s.x) * ex + (p.y - s.y) * ey) / len2 : 0.0;
    u = std::min(1.0, std::max(0.0, u));
    const double dx = s.x + u * ex - p.x, dy = s.y + u * ey - p.y;
    const double d2 = dx * dx + dy * dy;
    if (d2 < best)
    {
      best = d2;
      w[i] = 1.0 - u;
      w[(i + 1) % 3] = u;
      w[(i + 2) % 3] = 0.0;
    }
  }
  return best;
}

using detail::evalSum;
using detail::Quadric;

/// Triangle shape 4 sqrt(3) area / (sum of squared sides): 1 equilateral, 0 degenerate.
inline double shapeQuality(const V3& a, const V3& b, const V3& c, const V3& n)
{
  const V3 ab = sub(b, a), bc = sub(c, b), ca = sub(a, c);
  const double s = dot(ab, ab) + dot(bc, bc) + dot(ca, ca);
  return s > 0 ? 2.0 * std::sqrt(3.0) * norm(n) / s : 0.0;
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

struct Candidate
{
  double cost;
  int32_t target;
  int32_t halfEdge;
  int32_t rank; ///< input id of target
};

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
  Simplifier(const TriMesh& mesh, const std::vector<uint8_t>& featureVertex,
    const std::vector<uint8_t>& cornerVertex, const std::vector<int32_t>& featureEdges,
    const BaseComplexOptions& options)
    : Mesh_(mesh)
    , Options_(options)
  {
    this->validateAndLink(featureVertex, cornerVertex, featureEdges);
  }

  BaseComplexResult run(const Progress& progress);

private:
  void validateAndLink(const std::vector<uint8_t>& featureVertex,
    const std::vector<uint8_t>& cornerVertex, const std::vector<int32_t>& featureEdges);
  void reorder();
  void initQuadrics();
  bool legal(int32_t u, int32_t h) const;
  void gatherCandidates(int32_t u);
  void push(int32_t u, double cost);
  void requeueAfter(int32_t v);
  bool prepare(int32_t u, int32_t h0);
  bool flattenChain(int begin, int end, double span, bool conformal, std::vector<P2>& z) const;
  void apply(int32_t u);
  void undo();
  bool movedTrianglesValid();
  bool checkTriangle(int32_t t);
  void commitStarUsers();
  void relocate(int32_t p, int j);
  void placeOnFeature(int32_t p, double t);
  void locateFlat(int32_t p, const P2& P, int side, int guess);
  void store(int32_t p, int j, double bv, double bj, double bj1);
  BaseComplexResult output() const;

  // Charts of the base domain, for the bijection check (see triangleValid).
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
  Support supportOf(int32_t p) const;
  const StarChart& star(int32_t s, bool chart) const;
  bool inStar(int32_t s, const Support& sup, P2* at) const;
  bool inStar(int32_t s, const Support sup[3], P2 at[3]) const;
  bool triangleValid(int64_t t, int32_t* starCentre = nullptr) const;
  int countInvalidAround(int32_t p) const;
  bool smooth(int32_t p);
  int64_t repairFlips(const Progress& progress);

  V3 pos(int32_t v) const { return { Points3_[3 * v], Points3_[3 * v + 1], Points3_[3 * v + 2] }; }

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

void Simplifier::validateAndLink(const std::vector<uint8_t>& featureVertex,
  const std::vector<uint8_t>& cornerVertex, const std::vector<int32_t>& featureEdges)
{
  if (Mesh_.points.size() % 3 != 0 || Mesh_.triangles.size() % 3 != 0)
  {
    throw InputError(
      "buildBaseComplex: points and triangles must be flat #V x 3 and #F x 3 arrays");
  }
  if (Mesh_.numPoints() >= std::numeric_limits<int32_t>::max() / 2 ||
    Mesh_.triangles.size() >= static_cast<size_t>(std::numeric_limits<int32_t>::max()))
  {
    throw InputError("buildBaseComplex: the mesh is too large for 32-bit half-edge ids");
  }
  NumVertices_ = static_cast<int32_t>(Mesh_.numPoints());
  NumFaces_ = static_cast<int32_t>(Mesh_.numTriangles());
  if (NumFaces_ < 4)
  {
    throw InputError("buildBaseComplex: the mesh needs at least 4 triangles (a closed surface)");
  }
  if (!featureVertex.empty() && featureVertex.size() != static_cast<size_t>(NumVertices_))
  {
    throw InputError("buildBaseComplex: featureVertex must be empty or have one entry per point");
  }
  if (!cornerVertex.empty() && cornerVertex.size() != static_cast<size_t>(NumVertices_))
  {
    throw InputError("buildBaseComplex: cornerVertex must be empty or have one entry per point");
  }
  if (featureEdges.size() % 2 != 0)
  {
    throw InputError("buildBaseComplex: featureEdges must be a flat #E x 2 array");
  }
  const int32_t nh = 3 * NumFaces_;
  for (int32_t f = 0; f < NumFaces_; ++f)
  {
    const int32_t a = Mesh_.triangles[3 * f], b = Mesh_.triangles[3 * f + 1],
                  c = Mesh_.triangles[3 * f + 2];
    if (a < 0 || b < 0 || c < 0 || a >= NumVertices_ || b >= NumVertices_ || c >= NumVertices_)
    {
      throw InputError(
        "buildBaseComplex: triangle " + std::to_string(f) + " refers to a missing point");
    }
    if (a == b || b == c || c == a)
    {
      throw InputError("buildBaseComplex: triangle " + std::to_string(f) +
        " repeats a corner; run tcMeshPreparation to drop degenerate triangles");
    }
  }

  this->reorder();
  F_ = Tri_;
  // Half-edge h of internal face FaceOf_[f], corner i, in input order (3 f + i): every loop whose
  // order can show (lists, sums, error messages) runs in this order.
  auto inputHe = [&](int32_t h) { return 3 * FaceOf_[h / 3] + h % 3; };

  // Outgoing half-edges of every vertex in CSR form, then twins by scanning the (short) list of
  // the other end: O(#F * valence), no sort.
  std::vector<int32_t>& offsets = InOffsets_;
  offsets.assign(NumVertices_ + 1, 0);
  for (int32_t h = 0; h < nh; ++h)
  {
    ++offsets[F_[h] + 1];
  }
  for (int32_t input = 0; input < NumVertices_; ++input)
  {
    if (offsets[VertexOf_[input] + 1] == 0)
    {
      throw InputError("buildBaseComplex: point " + std::to_string(input) +
        " is in no triangle; run tcMeshPreparation to drop unused points");
    }
  }
  for (int32_t v = 0; v < NumVertices_; ++v)
  {
    offsets[v + 1] += offsets[v];
  }
  std::vector<int32_t>& outHe = InHe_;
  outHe.resize(nh);
  std::vector<int32_t> outTarget(nh);
  {
    std::vector<int32_t> fill(offsets.begin(), offsets.end() - 1);
    for (int32_t i = 0; i < nh; ++i)
    {
      const int32_t h = inputHe(i);
      const int32_t slot = fill[F_[h]]++;
      outHe[slot] = h;
      outTarget[slot] = F_[nextHe(h)];
    }
  }
  auto findHe = [&](int32_t a, int32_t b, int* count)
  {
    int32_t found = -1;
    *count = 0;
    for (int32_t s = offsets[a]; s < offsets[a + 1]; ++s)
    {
      if (outTarget[s] == b)
      {
        found = outHe[s];
        ++*count;
      }
    }
    return found;
  };
  Opp_.assign(nh, -1);
  for (int32_t i = 0; i < nh; ++i)
  {
    const int32_t h = inputHe(i);
    const int32_t a = F_[h], b = F_[nextHe(h)];
    int same = 0, twin = 0;
    findHe(a, b, &same);
    const int32_t o = findHe(b, a, &twin);
    auto edge = [&]
    { return "(" + std::to_string(VertexRank_[a]) + ", " + std::to_string(VertexRank_[b]) + ")"; };
    if (same != 1 || twin > 1)
    {
      throw InputError("buildBaseComplex: edge " + edge() +
        " has more than 2 triangles or inconsistent orientation (split non-manifold edges and "
        "orient the mesh in the preparation: SplitNonManifold and Orient, trichart build "
        "--split-non-manifold)");
    }
    if (twin == 0)
    {
      throw InputError("buildBaseComplex: edge " + edge() +
        " is on a boundary; the base complex needs a closed surface (close the holes in the "
        "preparation: FillHoles, trichart build --fill-holes)");
    }
    Opp_[h] = o;
  }
  Out_.resize(NumVertices_);
  Valence_.resize(NumVertices_);
  for (int32_t input = 0; input < NumVertices_; ++input)
  {
    const int32_t v = VertexOf_[input];
    const int32_t start = outHe[offsets[v]];
    const int32_t valence = offsets[v + 1] - offsets[v];
    int32_t h = start, steps = 0;
    do
    {
      h = Opp_[prevHe(h)];
      ++steps;
    } while (h != start && steps <= valence);
    if (steps != valence)
    {
      throw InputError("buildBaseComplex: the triangles around point " + std::to_string(input) +
        " form more than one fan (split non-manifold vertices in the preparation: "
        "SplitNonManifold, trichart build --split-non-manifold)");
    }
    Out_[v] = start;
    Valence_[v] = valence;
  }

  // Feature flags. A vertex is on a feature when flagged or when a feature edge ends there; it
  // is pinned (treated like a corner) unless exactly 2 feature edges meet there, i.e. at
  // corners, junctions of 3+ curves and open curve ends.
  FeatureHe_.assign(nh, 0);
  std::vector<int32_t> featureCount(NumVertices_, 0);
  for (size_t i = 0; i < featureEdges.size(); i += 2)
  {
    const int32_t ia = featureEdges[i], ib = featureEdges[i + 1];
    if (ia < 0 || ib < 0 || ia >= NumVertices_ || ib >= NumVertices_)
    {
      throw InputError(
        "buildBaseComplex: feature edge " + std::to_string(i / 2) + " refers to a missing point");
    }
    const int32_t a = VertexOf_[ia], b = VertexOf_[ib];
    int count = 0;
    const int32_t h = findHe(a, b, &count);
    if (h < 0)
    {
      throw InputError("buildBaseComplex: feature edge (" + std::to_string(ia) + ", " +
        std::to_string(ib) + ") is not an edge of the mesh");
    }
    if (!FeatureHe_[h])
    {
      FeatureHe_[h] = FeatureHe_[Opp_[h]] = 1;
      ++featureCount[a];
      ++featureCount[b];
    }
  }
  Feature_.assign(NumVertices_, 0);
  Pinned_.assign(NumVertices_, 0);
  for (int32_t v = 0; v < NumVertices_; ++v)
  {
    const int32_t input = VertexRank_[v];
    Feature_[v] = (!featureVertex.empty() && featureVertex[input]) || featureCount[v] > 0;
    Pinned_[v] =
      (!cornerVertex.empty() && cornerVertex[input]) || (Feature_[v] && featureCount[v] != 2);
  }
}

/// Vertices sorted along a Morton (Z-order) curve of their positions, faces by their lowest
/// internal vertex (a stable counting sort), ties by input id.
void Simplifier::reorder()
{
  const int32_t nv = NumVertices_, nf = NumFaces_;
  const std::vector<double>& P = Mesh_.points;
  double lo[3] = { 0, 0, 0 }, hi[3] = { 0, 0, 0 };
  for (int c = 0; c < 3; ++c)
  {
    lo[c] = hi[c] = P[c];
  }
  for (int32_t v = 1; v < nv; ++v)
  {
    for (int c = 0; c < 3; ++c)
    {
      lo[c] = std::min(lo[c], P[3 * v + c]);
      hi[c] = std::max(hi[c], P[3 * v + c]);
    }
  }
  std::vector<std::pair<uint64_t, int32_t>> key(nv);
  for (int32_t v = 0; v < nv; ++v)
  {
    uint32_t q[3];
    for (int c = 0; c < 3; ++c)
    {
      const double t = hi[c] > lo[c] ? (P[3 * v + c] - lo[c]) / (hi[c] - lo[c]) : 0.0;
      q[c] = t > 0 ? static_cast<uint32_t>(std::min(t, 1.0) * 2097151.0) : 0u;
    }
    uint64_t code = 0;
    for (int b = 20; b >= 0; --b)
    {
      for (int c = 0; c < 3; ++c)
      {
        code = (code << 1) | ((q[c] >> b) & 1u);
      }
    }
    key[v] = { code, v };
  }
  std::sort(key.begin(), key.end());
  VertexRank_.resize(nv);
  VertexOf_.resize(nv);
  Points3_.resize(3 * static_cast<size_t>(nv));
  for (int32_t v = 0; v < nv; ++v)
  {
    const int32_t input = key[v].second;
    VertexRank_[v] = input;
    VertexOf_[input] = v;
    std::copy(&P[3 * input], &P[3 * input] + 3, &Points3_[3 * v]);
  }
  std::vector<int32_t> first(nv + 1, 0);
  std::vector<int32_t> lowest(nf);
  for (int32_t f = 0; f < nf; ++f)
  {
    const int32_t* t = &Mesh_.triangles[3 * f];
    lowest[f] = std::min(VertexOf_[t[0]], std::min(VertexOf_[t[1]], VertexOf_[t[2]]));
    ++first[lowest[f] + 1];
  }
  for (int32_t v = 0; v < nv; ++v)
  {
    first[v + 1] += first[v];
  }
  FaceOf_.resize(nf);
  Tri_.resize(3 * static_cast<size_t>(nf));
  for (int32_t input = 0; input < nf; ++input)
  {
    const int32_t f = first[lowest[input]]++;
    FaceOf_[input] = f;
    for (int c = 0; c < 3; ++c)
    {
      Tri_[3 * f + c] = VertexOf_[Mesh_.triangles[3 * input + c]];
    }
  }
}

void Simplifier::initQuadrics()
{
  Quadric_.assign(NumVertices_, Quadric());
  Area_.assign(NumVertices_, 0.0);
  V3 lo = pos(0), hi = pos(0);
  for (int32_t v = 1; v < NumVertices_; ++v)
  {
    const V3 p = pos(v);
    lo = { std::min(lo.x, p.x), std::min(lo.y, p.y), std::min(lo.z, p.z) };
    hi = { std::max(hi.x, p.x), std::max(hi.y, p.y), std::max(hi.z, p.z) };
  }
  Diag2_ = std::max(dot(sub(hi, lo), sub(hi, lo)), std::numeric_limits<double>::min());

  // Area-weighted plane quadrics (Garland and Heckbert 1997, section 5): the sum then measures
  // squared distance integrated over the merged surface, so small regions go first and the
  // base triangles come out of similar size.
  for (int32_t input = 0; input < NumFaces_; ++input)
  {
    const int32_t f = FaceOf_[input];
    const V3 a = pos(F_[3 * f]), b = pos(F_[3 * f + 1]), c = pos(F_[3 * f + 2]);
    V3 n = cross(sub(b, a), sub(c, a));
    const double len = norm(n);
    if (!(len > 0))
    {
      continue;
    }
    n = { n.x / len, n.y / len, n.z / len };
    const double area = 0.5 * len;
    Quadric plane;
    plane.addPlane(n, -dot(n, a), area);
    for (int i = 0; i < 3; ++i)
    {
      Quadric_[F_[3 * f + i]].add(plane);
      Area_[F_[3 * f + i]] += area;
    }
  }
  // Feature curves: a plane through each feature edge perpendicular to each of its faces
  // (Garland and Heckbert's boundary constraint), weighted like the area it stands for, so a
  // curve simplifies first where it is straight.
  const double weight = Options_.featureWeight;
  for (int32_t i = 0; i < 3 * NumFaces_ && weight > 0; ++i)
  {
    const int32_t h = 3 * FaceOf_[i / 3] + i % 3;
    if (!FeatureHe_[h])
    {
      continue;
    }
    const V3 a = pos(F_[h]), b = pos(F_[nextHe(h)]);
    const V3 c = pos(F_[nextHe(nextHe(h))]);
    const V3 e = sub(b, a);
    const V3 nf = cross(e, sub(c, a));
    V3 m = cross(e, nf);
    const double len = norm(m);
    if (!(len > 0))
    {
      continue;
    }
    m = { m.x / len, m.y / len, m.z / len };
    Quadric plane;
    plane.addPlane(m, -dot(m, a), weight * dot(e, e));
    Quadric_[F_[h]].add(plane);
    Quadric_[F_[nextHe(h)]].add(plane);
  }
}

/// The rules of Feng et al. section 5.1 that do not depend on geometry: never remove a pinned
/// vertex; never collapse an edge joining a feature and a non-feature vertex; a feature vertex
/// only moves along its own curve (the edge collapsed is one of its 2 feature edges).
bool Simplifier::legal(int32_t u, int32_t h) const
{
  if (Pinned_[u])
  {
    return false;
  }
  const int32_t v = F_[nextHe(h)];
  return Feature_[u] ? FeatureHe_[h] != 0 : !Feature_[v];
}

void Simplifier::gatherCandidates(int32_t u)
{
  Candidates_.clear();
  const int32_t start = Out_[u];
  int32_t h = start;
  do
  {
    if (this->legal(u, h))
    {
      const int32_t v = F_[nextHe(h)];
      Candidates_.push_back(
        { evalSum(Quadric_[u], Quadric_[v], this->pos(v)), v, h, VertexRank_[v] });
    }
    h = Opp_[prevHe(h)];
  } while (h != start);
  // Insertion sort: a handful of candidates, all with distinct ranks.
  for (size_t i = 1; i < Candidates_.size(); ++i)
  {
    const Candidate c = Candidates_[i];
    size_t j = i;
    for (; j > 0 &&
         (c.cost < Candidates_[j - 1].cost ||
           (c.cost == Candidates_[j - 1].cost && c.rank < Candidates_[j - 1].rank));
         --j)
    {
      Candidates_[j] = Candidates_[j - 1];
    }
    Candidates_[j] = c;
  }
}

/// Lazy priority queue: a vertex has at most one live entry (its key in Key_), and a key may be
/// lower than the vertex's current cheapest collapse; the entry is re-evaluated when it is popped.
void Simplifier::push(int32_t u, double cost)
{
  if (cost < Key_[u])
  {
    Key_[u] = cost;
    Heap_.push({ cost, u, VertexRank_[u] });
  }
}

/// After a collapse into v: v has new edges (full re-evaluation); each neighbour x only gained
/// or changed its edge to v, so its key drops to that edge's cost if cheaper. A neighbour with no
/// entry (every collapse was rejected) is re-evaluated in full: its ring has changed, so rejected
/// collapses may have become valid.
void Simplifier::requeueAfter(int32_t v)
{
  this->gatherCandidates(v);
  if (!Candidates_.empty())
  {
    this->push(v, Candidates_.front().cost);
  }
  const int32_t start = Out_[v];
  int32_t g = start;
  do
  {
    const int32_t x = F_[nextHe(g)];
    if (!Pinned_[x])
    {
      if (Key_[x] == std::numeric_limits<double>::infinity())
      {
        this->gatherCandidates(x);
        if (!Candidates_.empty())
        {
          this->push(x, Candidates_.front().cost);
        }
      }
      else
      {
        const int32_t back = Opp_[g];
        if (this->legal(x, back))
        {
          this->push(x, evalSum(Quadric_[x], Quadric_[v], this->pos(v)));
        }
      }
    }
    g = Opp_[prevHe(g)];
  } while (g != start);
}

/// Maps ring vertices x_begin..x_end (faces begin..end-1) into the plane with the conformal map
/// z^a of Lee et al. (MAPS, section 3.2): polar angles are scaled by a = span / (their total
/// 3D angle) and radii raised to the power a. span = 2 pi closes the full ring. At a feature
/// vertex each side of the curve is mapped onto the upper half plane (span = pi, the curve on
/// the real axis) with radii kept (power 1): both sides then put a curve point at the same
/// place, the arc-length position that placeOnFeature gives it, so curve points and the points
/// beside the curve move together. Returns false when a face would fold over (its scaled angle
/// reaches pi).
bool Simplifier::flattenChain(
  int begin, int end, double span, bool conformal, std::vector<P2>& z) const
{
  double total = 0.0, meanRadius = 0.0;
  for (int j = begin; j < end; ++j)
  {
    total += Theta_[j];
  }
  for (int j = begin; j <= end; ++j)
  {
    meanRadius += Radius_[j % K_];
  }
  meanRadius /= (end - begin + 1);
  if (!(total > 0) || !(meanRadius > 0))
  {
    return false;
  }
  const double a = span / total;
  double phi = 0.0;
  for (int j = begin; j <= end; ++j)
  {
    if (j < end && !(a * Theta_[j] < kPi * (1.0 - 1e-9)))
    {
      return false;
    }
    const double rho =
      conformal ? std::pow(Radius_[j % K_] / meanRadius, a) : Radius_[j % K_] / meanRadius;
    const double angle = j == end ? span : a * phi;
    z[j] = { rho * std::cos(angle), rho * std::sin(angle) };
    if (j < end)
    {
      phi += Theta_[j];
    }
  }
  return true;
}

/// Gathers the ring of u for the collapse along h0 = u -> v and tests every rule that depends
/// on the current mesh: link condition, valences, feature sides, normals and shapes of the new
/// triangles, and that the new fan from v is a valid triangulation of the flattened ring (the
/// flat polygon is star-shaped from v), which is what makes the MAPS reassignment a bijection.
bool Simplifier::prepare(int32_t u, int32_t h0)
{
  const int32_t v = F_[nextHe(h0)];
  U_ = u;
  V_ = v;
  RingHe_.clear();
  RingV_.clear();
  RingF_.clear();
  int32_t h = h0;
  do
  {
    RingHe_.push_back(h);
    RingV_.push_back(F_[nextHe(h)]);
    RingF_.push_back(h / 3);
    h = Opp_[prevHe(h)];
  } while (h != h0);
  const int k = static_cast<int>(RingV_.size());
  K_ = k;
  if (k < 3 || FaceCount_ <= 4)
  {
    return false;
  }
  const int32_t x1 = RingV_[1], xl = RingV_[k - 1];
  // Every vertex keeps valence >= 3 (no tetrahedron collapses into a flat pair of triangles).
  if (Valence_[v] + k - 4 < 3 || Valence_[x1] - 1 < 3 || Valence_[xl] - 1 < 3)
  {
    return false;
  }
  // Link condition (Dey et al. 1999): u and v share exactly the neighbours x_1 and x_{k-1}.
  ++MarkCounter_;
  {
    const int32_t start = Out_[v];
    int32_t g = start;
    do
    {
      Mark_[F_[nextHe(g)]] = MarkCounter_;
      g = Opp_[prevHe(g)];
    } while (g != start);
  }
  for (int j = 2; j <= k - 2; ++j)
  {
    if (Mark_[RingV_[j]] == MarkCounter_)
    {
      return false;
    }
  }

  M_ = k;
  if (Feature_[u])
  {
    for (int j = 1; j < k; ++j)
    {
      if (FeatureHe_[RingHe_[j]])
      {
        M_ = j;
        break;
      }
    }
    // Each side of the curve needs two faces (the collapse deletes one on each side); a single
    // face between the two curve edges would be flattened onto the new curve edge.
    if (M_ < 2 || M_ > k - 2)
    {
      return false;
    }
  }

  // 3D: no normal flip, no degenerate triangle. The shape bound is relative: a new triangle may
  // not be worse than minTriangleQuality nor than the worst triangle it replaces.
  const V3 pu = this->pos(u), pv = this->pos(v);
  Theta_.resize(k);
  Radius_.resize(k);
  double worstOld = 1.0;
  for (int j = 0; j < k; ++j)
  {
    const V3 a = sub(this->pos(RingV_[j]), pu);
    const V3 b = sub(this->pos(RingV_[(j + 1) % k]), pu);
    const V3 n = cross(a, b);
    Theta_[j] = std::atan2(norm(n), dot(a, b));
    Radius_[j] = norm(a);
    worstOld =
      std::min(worstOld, shapeQuality(pu, this->pos(RingV_[j]), this->pos(RingV_[(j + 1) % k]), n));
  }
  const double minQuality = std::min(Options_.minTriangleQuality, worstOld);
  const double minCos = std::cos(Options_.maxNormalChange * kPi / 180.0);
  for (int j = 1; j <= k - 2; ++j)
  {
    const V3 pa = this->pos(RingV_[j]), pb = this->pos(RingV_[j + 1]);
    const V3 nOld = cross(sub(pa, pu), sub(pb, pu));
    const V3 nNew = cross(sub(pa, pv), sub(pb, pv));
    const double lo = norm(nOld), ln = norm(nNew);
    if (!(dot(nOld, nNew) > minCos * lo * ln) || !(ln > 0))
    {
      return false;
    }
    if (shapeQuality(pv, pa, pb, nNew) < minQuality)
    {
      return false;
    }
  }

  // Flat domain.
  ZA_.resize(k + 1);
  ZB_.resize(k + 1);
  if (M_ == k)
  {
    if (!this->flattenChain(0, k, 2.0 * kPi, true, ZA_))
    {
      return false;
    }
    ZA_[k] = ZA_[0];
  }
  else
  {
    if (!this->flattenChain(0, M_, kPi, false, ZA_) || !this->flattenChain(M_, k, kPi, false, ZB_))
    {
      return false;
    }
    L1_ = Radius_[0];
    L2_ = Radius_[M_];
  }
  // The fan from v must tile the flat polygon: every new flat triangle counter-clockwise, with a
  // margin so that later barycentric solves stay well conditioned.
  const double minSine = 1e-6;
  for (int j = 1; j <= k - 2; ++j)
  {
    const bool sideB = j >= M_;
    const std::vector<P2>& z = sideB ? ZB_ : ZA_;
    const P2 zv = sideB ? ZB_[k] : ZA_[0];
    const P2& za = z[j];
    const P2& zb = z[j + 1];
    const double la = std::hypot(za.x - zv.x, za.y - zv.y);
    const double lb = std::hypot(zb.x - zv.x, zb.y - zv.y);
    if (!(orient(zv, za, zb) > minSine * la * lb))
    {
      return false;
    }
  }
  return true;
}

/// Stores point p in new face j = (v, x_j, x_{j+1}) with these barycentrics (corner order of the
/// face follows the old one: u's corner now holds v).
void Simplifier::store(int32_t p, int j, double bv, double bj, double bj1)
{
  const int32_t f = RingF_[j];
  const int c = RingHe_[j] % 3;
  double* b = &PointBary_[3 * p];
  const double sum = bv + bj + bj1;
  b[c] = bv / sum;
  b[(c + 1) % 3] = bj / sum;
  b[(c + 2) % 3] = bj1 / sum;
  PointFace_[p] = f;
  Next_[p] = Head_[f];
  Head_[f] = p;
}

/// A point of the feature curve through u goes onto the new curve edge (v, w), at arc-length
/// parameter t from v (MAPS's 1-D parameterization of feature curves): exactly on the base edge.
void Simplifier::placeOnFeature(int32_t p, double t)
{
  t = std::min(1.0, std::max(0.0, t));
  // Side A's last new face (v, x_{m-1}, w) carries the edge v -> ... -> w.
  this->store(p, M_ - 1, 1.0 - t, 0.0, t);
}

/// Locates a flat point among the new faces of one side (fan from v) and stores it there. A point
/// outside all of them (round-off in the z^a map or in earlier steps) is snapped to the nearest
/// new triangle and nudged a hair inside: the flip repair of MAPS.
void Simplifier::locateFlat(int32_t p, const P2& P, int side, int guess)
{
  const int k = K_;
  const int lo = side == 0 ? 1 : M_;
  const int hi = side == 0 ? std::min(M_, k - 1) - 1 : k - 2;
  const std::vector<P2>& z = side == 0 ? ZA_ : ZB_;
  const P2 zv = side == 0 ? ZA_[0] : ZB_[k];
  guess = std::min(hi, std::max(lo, guess));
  double w[3];
  double bestMin = -std::numeric_limits<double>::infinity();
  int best = -1;
  double bestW[3] = { 1, 0, 0 };
  for (int n = 0; n <= hi - lo; ++n)
  {
    const int i = n == 0 ? guess : (lo + n - 1 < guess ? lo + n - 1 : lo + n);
    if (!barycentric(P, zv, z[i], z[i + 1], w))
    {
      continue;
    }
    const double m = std::min(w[0], std::min(w[1], w[2]));
    if (m > bestMin)
    {
      bestMin = m;
      best = i;
      std::copy(w, w + 3, bestW);
      if (m >= 0.0)
      {
        break;
      }
    }
  }
  if (best >= 0 && bestMin >= -kInsideSlack)
  {
    this->store(p, best, std::max(0.0, bestW[0]), std::max(0.0, bestW[1]), std::max(0.0, bestW[2]));
    return;
  }
  ++Snapped_;
  double bestD = std::numeric_limits<double>::infinity();
  for (int i = lo; i <= hi; ++i)
  {
    const double d = closestBarycentric(P, zv, z[i], z[i + 1], w);
    if (d < bestD)
    {
      bestD = d;
      best = i;
      std::copy(w, w + 3, bestW);
    }
  }
  const double nudge = 1e-9;
  this->store(p, best, (1 - nudge) * bestW[0] + nudge / 3, (1 - nudge) * bestW[1] + nudge / 3,
    (1 - nudge) * bestW[2] + nudge / 3);
}

/// New (face, barycentric) of point p, which lay in old face j of the ring (j = -1: p is u).
void Simplifier::relocate(int32_t p, int j)
{
  const int k = K_;
  const bool featureCollapse = M_ < k;
  const double t0 = L1_ / (L1_ + L2_);
  if (j < 0)
  {
    if (featureCollapse)
    {
      this->placeOnFeature(p, t0);
    }
    else
    {
      this->locateFlat(p, P2{ 0.0, 0.0 }, 0, 1);
    }
    return;
  }
  const int c = RingHe_[j] % 3;
  const double* b = &PointBary_[3 * p];
  const double bu = b[c], bj = b[(c + 1) % 3], bj1 = b[(c + 2) % 3];
  if (bu == 0.0)
  {
    // On the link edge (x_j, x_{j+1}), which survives: keep its 1-D coordinate exactly.
    if (j == 0)
    {
      this->store(p, 1, bj, bj1, 0.0);
    }
    else if (j == k - 1)
    {
      this->store(p, k - 2, bj1, 0.0, bj);
    }
    else
    {
      this->store(p, j, 0.0, bj, bj1);
    }
    return;
  }
  if (featureCollapse && Feature_[p] && (bj == 0.0 || bj1 == 0.0))
  {
    // On curve edge (u, x): x = v sits at ring index 0 (= k), w at index m.
    const int xi = bj == 0.0 ? j + 1 : j;
    const double bx = bj == 0.0 ? bj1 : bj;
    if (xi % k == 0)
    {
      this->placeOnFeature(p, bu * t0);
      return;
    }
    if (xi == M_)
    {
      this->placeOnFeature(p, t0 + bx * (1.0 - t0));
      return;
    }
  }
  const int side = featureCollapse && j >= M_ ? 1 : 0;
  const std::vector<P2>& z = side == 0 ? ZA_ : ZB_;
  const P2 P{ bj * z[j].x + bj1 * z[j + 1].x, bj * z[j].y + bj1 * z[j + 1].y };
  this->locateFlat(p, P, side, j);
}

/// Performs the collapse prepared for u: MAPS reassignment of every point in the ring's faces (and
/// of u), then the corner-table update. Everything it changes can be restored by undo().
void Simplifier::apply(int32_t u)
{
  const int k = K_;
  const int32_t v = V_;

  // MAPS: take every point out of the ring's faces, then put it (and u) into the new faces.
  Points_.clear();
  OldBary_.clear();
  for (int j = 0; j < k; ++j)
  {
    const int32_t f = RingF_[j];
    for (int32_t p = Head_[f]; p >= 0; p = Next_[p])
    {
      Points_.emplace_back(p, j);
      OldBary_.push_back(PointBary_[3 * p]);
      OldBary_.push_back(PointBary_[3 * p + 1]);
      OldBary_.push_back(PointBary_[3 * p + 2]);
    }
    Head_[f] = -1;
  }
  Points_.emplace_back(u, -1);
  for (const auto& pj : Points_)
  {
    this->relocate(pj.first, pj.second);
  }
  Removed_[u] = 1;

  // Corner table: drop faces 0 and k-1, glue their outer twins, rename u to v.
  const int32_t h0 = RingHe_[0];
  const int32_t h1 = Opp_[h0];
  const int32_t A = Opp_[nextHe(h0)], B = Opp_[prevHe(h0)];
  const int32_t C = Opp_[nextHe(h1)], D = Opp_[prevHe(h1)];
  UndoFeature_[0] = FeatureHe_[A];
  UndoFeature_[1] = FeatureHe_[B];
  UndoFeature_[2] = FeatureHe_[C];
  UndoFeature_[3] = FeatureHe_[D];
  UndoOpp_[0] = A;
  UndoOpp_[1] = B;
  UndoOpp_[2] = C;
  UndoOpp_[3] = D;
  Opp_[A] = B;
  Opp_[B] = A;
  Opp_[C] = D;
  Opp_[D] = C;
  FeatureHe_[A] = FeatureHe_[B] = FeatureHe_[A] | FeatureHe_[B];
  FeatureHe_[C] = FeatureHe_[D] = FeatureHe_[C] | FeatureHe_[D];
  for (int j = 1; j <= k - 2; ++j)
  {
    F_[RingHe_[j]] = v;
  }
  FaceAlive_[RingF_[0]] = 0;
  FaceAlive_[RingF_[k - 1]] = 0;
  FaceCount_ -= 2;
  const int32_t x1 = RingV_[1], xl = RingV_[k - 1];
  UndoOut_[0] = Out_[v];
  UndoOut_[1] = Out_[x1];
  UndoOut_[2] = Out_[xl];
  Out_[v] = B;
  Out_[x1] = A;
  Out_[xl] = C;
  Valence_[v] += k - 4;
  --Valence_[x1];
  --Valence_[xl];
  Valence_[u] = 0;
  StarValid_[u] = 0;
  for (int j = 0; j < k; ++j)
  {
    StarValid_[RingV_[j]] = 0;
  }
}

void Simplifier::undo()
{
  const int k = K_;
  const int32_t u = U_, v = V_;
  const int32_t h0 = RingHe_[0];
  const int32_t h1 = Opp_[h0];
  const int32_t A = UndoOpp_[0], B = UndoOpp_[1], C = UndoOpp_[2], D = UndoOpp_[3];
  Opp_[A] = nextHe(h0);
  Opp_[B] = prevHe(h0);
  Opp_[C] = nextHe(h1);
  Opp_[D] = prevHe(h1);
  FeatureHe_[A] = UndoFeature_[0];
  FeatureHe_[B] = UndoFeature_[1];
  FeatureHe_[C] = UndoFeature_[2];
  FeatureHe_[D] = UndoFeature_[3];
  for (int j = 1; j <= k - 2; ++j)
  {
    F_[RingHe_[j]] = u;
  }
  FaceAlive_[RingF_[0]] = 1;
  FaceAlive_[RingF_[k - 1]] = 1;
  FaceCount_ += 2;
  const int32_t x1 = RingV_[1], xl = RingV_[k - 1];
  Out_[v] = UndoOut_[0];
  Out_[x1] = UndoOut_[1];
  Out_[xl] = UndoOut_[2];
  Valence_[v] -= k - 4;
  ++Valence_[x1];
  ++Valence_[xl];
  Valence_[u] = k;
  Removed_[u] = 0;
  StarValid_[u] = 0;
  for (int j = 0; j < k; ++j)
  {
    StarValid_[RingV_[j]] = 0;
    Head_[RingF_[j]] = -1;
  }
  for (size_t i = 0; i + 1 < Points_.size(); ++i)
  {
    const int32_t p = Points_[i].first;
    const int32_t f = RingF_[Points_[i].second];
    PointFace_[p] = f;
    std::copy(&OldBary_[3 * i], &OldBary_[3 * i] + 3, &PointBary_[3 * p]);
    Next_[p] = Head_[f];
    Head_[f] = p;
  }
  PointFace_[u] = -1;
}

/// Whether every input triangle at a point the collapse moved, or at a base vertex whose star it
/// changed, is still valid (triangleValid): a collapse that would fold or stretch one is
/// rejected, so the map stays a bijection at every level instead of being untangled at the end.
bool Simplifier::checkTriangle(int32_t t)
{
  int32_t centre = -1;
  const bool valid = this->triangleValid(t, &centre);
  if (centre != TriStar_[t])
  {
    PendingStar_.emplace_back(t, centre);
  }
  return valid;
}

/// Files the triangles checked by an accepted collapse under the star they were drawn in.
void Simplifier::commitStarUsers()
{
  for (const auto& tc : PendingStar_)
  {
    const int32_t t = tc.first;
    const int32_t old = TriStar_[t];
    if (old >= 0)
    {
      const int32_t prev = TriStarPrev_[t], next = TriStarNext_[t];
      (prev >= 0 ? TriStarNext_[prev] : StarHead_[old]) = next;
      if (next >= 0)
      {
        TriStarPrev_[next] = prev;
      }
    }
    TriStar_[t] = tc.second;
    if (tc.second >= 0)
    {
      TriStarPrev_[t] = -1;
      TriStarNext_[t] = StarHead_[tc.second];
      if (StarHead_[tc.second] >= 0)
      {
        TriStarPrev_[StarHead_[tc.second]] = t;
      }
      StarHead_[tc.second] = t;
    }
  }
  PendingStar_.clear();
}

bool Simplifier::movedTrianglesValid()
{
  ++TriCounter_;
  PendingStar_.clear();
  auto once = [&](int32_t t)
  { return TriMark_[t] == TriCounter_ || (TriMark_[t] = TriCounter_, false); };
  for (const auto& pj : Points_)
  {
    const int32_t p = pj.first;
    for (int32_t s = InOffsets_[p]; s < InOffsets_[p + 1]; ++s)
    {
      const int32_t t = InHe_[s] / 3;
      if (!once(t) && !this->checkTriangle(t))
      {
        return false;
      }
    }
  }
  // The star charts of u, v and the ring changed: the triangles drawn in them, and those at
  // these base vertices (a star that now holds them may come first), are drawn anew, unless
  // their other corners did not move and lie in one face with the vertex (that face's
  // barycentric plane did not change).
  auto inFaceWith = [&](int32_t p, int32_t x)
  {
    if (!Removed_[p])
    {
      return p == x;
    }
    const int32_t f = PointFace_[p];
    return F_[3 * f] == x || F_[3 * f + 1] == x || F_[3 * f + 2] == x;
  };
  for (int j = -1; j < K_; ++j)
  {
    const int32_t x = j < 0 ? U_ : RingV_[j];
    for (int32_t t = StarHead_[x]; t >= 0; t = TriStarNext_[t])
    {
      if (!once(t) && !this->checkTriangle(t))
      {
        return false;
      }
    }
    if (j < 0)
    {
      continue;
    }
    for (int32_t s = InOffsets_[x]; s < InOffsets_[x + 1]; ++s)
    {
      const int32_t h = InHe_[s];
      const int32_t t = h / 3;
      if (once(t))
      {
        continue;
      }
      const int32_t p = Tri_[nextHe(h)], q = Tri_[prevHe(h)];
      if (Removed_[p] && Removed_[q] && PointFace_[p] == PointFace_[q] && inFaceWith(p, x))
      {
        continue;
      }
      if (!this->checkTriangle(t))
      {
        return false;
      }
    }
  }
  return true;
}

BaseComplexResult Simplifier::run(const Progress& progress)
{
  const Progress setup = progress.sub(0.0, 0.1);
  const Progress simplify = progress.sub(0.1, 0.9);
  const Progress repair = progress.sub(0.9, 1.0);
  this->initQuadrics();
  FaceAlive_.assign(NumFaces_, 1);
  FaceCount_ = NumFaces_;
  Removed_.assign(NumVertices_, 0);
  Key_.assign(NumVertices_, std::numeric_limits<double>::infinity());
  Mark_.assign(NumVertices_, 0);
  Head_.assign(NumFaces_, -1);
  Next_.assign(NumVertices_, -1);
  PointFace_.assign(NumVertices_, -1);
  PointBary_.assign(3 * static_cast<size_t>(NumVertices_), 0.0);
  TriMark_.assign(NumFaces_, 0);
  StarHead_.assign(NumVertices_, -1);
  TriStar_.assign(NumFaces_, -1);
  TriStarPrev_.assign(NumFaces_, -1);
  TriStarNext_.assign(NumFaces_, -1);
  StarSlot_.assign(NumVertices_, -1);
  StarValid_.assign(NumVertices_, 0);
  {
    std::vector<HeapEntry> entries;
    entries.reserve(NumVertices_);
    for (int32_t u = 0; u < NumVertices_; ++u)
    {
      if (Pinned_[u])
      {
        continue;
      }
      this->gatherCandidates(u);
      if (!Candidates_.empty())
      {
        Key_[u] = Candidates_.front().cost;
        entries.push_back({ Key_[u], u, VertexRank_[u] });
      }
    }
    Heap_ = decltype(Heap_)(HeapOrder(), std::move(entries));
  }
  setup.report(1.0);

  BaseComplexResult result;
  const int64_t target = std::max<int64_t>(4, Options_.targetFaces);
  // The error bound never leaves more than one face per kPointsPerBoundedFace input points: on a
  // coarse input it would leave charts of a few samples each. Vertices whose collapses it
  // refused wait in `deferred`; should the simplification end above that count, the bound is
  // lifted until the count is reached, and they are queued again.
  const int64_t boundedFaces = NumVertices_ / kPointsPerBoundedFace;
  bool bounded = Options_.maxError > 0;
  std::vector<int32_t> deferred;
  const double toRemove = std::max<double>(1.0, static_cast<double>(NumFaces_ - target));
  int64_t pops = 0;
  while (FaceCount_ > target)
  {
    if (Heap_.empty())
    {
      if (!bounded || FaceCount_ <= boundedFaces || deferred.empty())
      {
        break;
      }
      bounded = false;
      // A vertex is deferred again each time it is popped and refused: queue it once.
      std::sort(deferred.begin(), deferred.end());
      deferred.erase(std::unique(deferred.begin(), deferred.end()), deferred.end());
      for (int32_t v : deferred)
      {
        if (!Removed_[v] && !Pinned_[v])
        {
          this->gatherCandidates(v);
          if (!Candidates_.empty())
          {
            this->push(v, Candidates_.front().cost);
          }
        }
      }
      deferred.clear();
      continue;
    }
    if (!bounded && Options_.maxError > 0 && FaceCount_ <= boundedFaces)
    {
      bounded = true; // the count is reached: the bound stops the rest
    }
    if ((++pops & 4095) == 0)
    {
      simplify.report(std::min(1.0, (NumFaces_ - FaceCount_) / toRemove));
    }
    const HeapEntry top = Heap_.top();
    Heap_.pop();
    const int32_t u = top.vertex;
    if (Removed_[u] || top.cost != Key_[u])
    {
      continue;
    }
    Key_[u] = std::numeric_limits<double>::infinity();
    this->gatherCandidates(u);
    bool done = false;
    for (size_t c = 0; c < Candidates_.size() && !done; ++c)
    {
      const Candidate cand = Candidates_[c];
      if (cand.cost > top.cost)
      {
        // The key was a lower bound, or cheaper collapses of u were rejected: wait for the turn
        // of this one.
        this->push(u, cand.cost);
        break;
      }
      const double error = cand.cost /
        std::max(Area_[u] + Area_[cand.target], std::numeric_limits<double>::min()) / Diag2_;
      if (bounded && error > Options_.maxError)
      {
        deferred.push_back(u);
        continue;
      }
      if (!this->prepare(u, cand.halfEdge))
      {
        continue;
      }
      this->apply(u);
      if (Options_.checkBijection && !this->movedTrianglesValid())
      {
        this->undo();
        continue;
      }
      this->commitStarUsers();
      Quadric_[V_].add(Quadric_[u]);
      Area_[V_] += Area_[u];
      ++result.collapses;
      result.maxCollapseError = std::max(result.maxCollapseError, error);
      done = true;
    }
    if (done)
    {
      this->requeueAfter(V_);
    }
  }
  simplify.report(1.0);
  const int64_t invalid = this->repairFlips(repair);
  BaseComplexResult out = this->output();
  out.collapses = result.collapses;
  out.maxCollapseError = result.maxCollapseError;
  out.reachedTarget = FaceCount_ <= Options_.targetFaces;
  out.snappedPoints = Snapped_;
  out.invalidTriangles = invalid;
  progress.report(1.0);
  return out;
}

Simplifier::Support Simplifier::supportOf(int32_t p) const
{
  Support s;
  if (!Removed_[p])
  {
    s.n = 1;
    s.face = Out_[p] / 3;
    s.v[0] = p;
    s.w[0] = 1.0;
    return s;
  }
  s.face = PointFace_[p];
  for (int i = 0; i < 3; ++i)
  {
    if (PointBary_[3 * p + i] != 0.0)
    {
      s.v[s.n] = F_[3 * s.face + i];
      s.w[s.n] = PointBary_[3 * p + i];
      ++s.n;
    }
  }
  return s;
}

/// The chart of the star of base vertex s: its ring flattened by z^a (3D angles at s scaled to
/// sum to 2 pi, radii to the power a), or, where one angle is more than half the total and a
/// face would fold, the ring on the unit circle at equal angles. Cached until the star changes;
/// the ring alone (chart = false) is cheap, the flat positions are computed when first needed.
const Simplifier::StarChart& Simplifier::star(int32_t s, bool chart) const
{
  if (StarSlot_[s] < 0)
  {
    StarSlot_[s] = static_cast<int32_t>(Stars_.size());
    Stars_.emplace_back();
  }
  StarChart& star = Stars_[StarSlot_[s]];
  if (StarValid_[s] == 0)
  {
    StarValid_[s] = 1;
    star.he.clear();
    star.ring.clear();
    const int32_t start = Out_[s];
    int32_t h = start;
    do
    {
      star.he.push_back(h);
      star.ring.push_back(F_[nextHe(h)]);
      h = Opp_[prevHe(h)];
    } while (h != start);
  }
  if (!chart || StarValid_[s] == 2)
  {
    return star;
  }
  StarValid_[s] = 2;
  star.z.clear();
  detail::flattenStar(this->pos(s), star.ring.size(),
    [&](size_t i) { return this->pos(star.ring[i]); }, StarTheta_, StarRadius_, star.z);
  return star;
}

/// Position of a point with this support in the chart of the star of s, or false when the point
/// is outside the closed star of s.
bool Simplifier::inStar(int32_t s, const Support& sup, P2* at) const
{
  const StarChart& star = this->star(s, at != nullptr);
  const int d = static_cast<int>(star.ring.size());
  int index[3], n = 0;
  P2 p{ 0.0, 0.0 };
  for (int i = 0; i < sup.n; ++i)
  {
    if (sup.v[i] == s)
    {
      continue;
    }
    const auto it = std::find(star.ring.begin(), star.ring.end(), sup.v[i]);
    if (it == star.ring.end())
    {
      return false;
    }
    index[n] = static_cast<int>(it - star.ring.begin());
    if (at)
    {
      p.x += sup.w[i] * star.z[index[n]].x;
      p.y += sup.w[i] * star.z[index[n]].y;
    }
    ++n;
  }
  // A point inside a face must be in a face of the star (s is a corner); one on an edge that
  // misses s must be on the far side of a face of the star.
  if (n == 3 ||
    (n == 2 && (index[1] - index[0] + d) % d != 1 && (index[0] - index[1] + d) % d != 1))
  {
    return false;
  }
  if (at)
  {
    *at = p;
  }
  return true;
}

/// inStar for the three corners of a triangle at once: the ring is looked up once per support
/// vertex, and the chart is only computed when all three are in the closed star.
bool Simplifier::inStar(int32_t s, const Support sup[3], P2 at[3]) const
{
  const StarChart& ring = this->star(s, false);
  const int32_t* ids = ring.ring.data();
  const int d = static_cast<int>(ring.ring.size());
  int index[3][3];
  for (int j = 0; j < 3; ++j)
  {
    int n = 0, found[3];
    for (int i = 0; i < sup[j].n; ++i)
    {
      index[j][i] = -1;
      if (sup[j].v[i] == s)
      {
        continue;
      }
      int r = 0;
      while (r < d && ids[r] != sup[j].v[i])
      {
        ++r;
      }
      if (r == d)
      {
        return false;
      }
      index[j][i] = found[n++] = r;
    }
    if (n == 3 ||
      (n == 2 && (found[1] - found[0] + d) % d != 1 && (found[0] - found[1] + d) % d != 1))
    {
      return false;
    }
  }
  const StarChart& star = this->star(s, true);
  for (int j = 0; j < 3; ++j)
  {
    at[j] = { 0.0, 0.0 };
    for (int i = 0; i < sup[j].n; ++i)
    {
      if (index[j][i] >= 0)
      {
        at[j].x += sup[j].w[i] * star.z[index[j][i]].x;
        at[j].y += sup[j].w[i] * star.z[index[j][i]].y;
      }
    }
  }
  return true;
}

/// Whether input triangle t keeps its orientation in the base domain, drawn with straight sides
/// in the chart the later stages use for it (Feng et al. section 5.1: base triangles unfolded
/// into the plane): corners in one closed base face (a corner's face, or the face their
/// supports span) -> that face's barycentric plane; each in one of two faces about a base edge
/// -> the two 3D triangles unfolded about the edge; otherwise the star
/// chart of the lowest-numbered base vertex whose closed star holds all three. A triangle no
/// chart holds straddles the base complex and is invalid too. The area must clear a relative
/// margin so that any evaluation of these charts agrees on its sign.
bool Simplifier::triangleValid(int64_t t, int32_t* starCentre) const
{
  if (starCentre)
  {
    *starCentre = -1;
  }
  constexpr double kMargin = 1e-12;
  auto area = [&](const P2 p[3])
  {
    const double a = orient(p[0], p[1], p[2]);
    const double s = (p[1].x - p[0].x) * (p[1].x - p[0].x) + (p[1].y - p[0].y) * (p[1].y - p[0].y) +
      (p[2].x - p[1].x) * (p[2].x - p[1].x) + (p[2].y - p[1].y) * (p[2].y - p[1].y) +
      (p[0].x - p[2].x) * (p[0].x - p[2].x) + (p[0].y - p[2].y) * (p[0].y - p[2].y);
    return a > kMargin * s;
  };
  // Fast paths. Three base vertices that still make face t, as in the input (a fine base
  // complex): the rule below would find t and draw it as its own barycentric triangle, area 1/2.
  // Three removed vertices stored in the same face, by far the most common case on a coarse base
  // complex: the rule below would pick that face's barycentric plane too.
  {
    const int32_t a = Tri_[3 * t], b = Tri_[3 * t + 1], c = Tri_[3 * t + 2];
    if (!Removed_[a] && !Removed_[b] && !Removed_[c] && FaceAlive_[t] && F_[3 * t] == a &&
      F_[3 * t + 1] == b && F_[3 * t + 2] == c)
    {
      return true;
    }
    if (Removed_[a] && Removed_[b] && Removed_[c] && PointFace_[a] == PointFace_[b] &&
      PointFace_[a] == PointFace_[c])
    {
      const P2 p[3] = { { PointBary_[3 * a + 1], PointBary_[3 * a + 2] },
        { PointBary_[3 * b + 1], PointBary_[3 * b + 2] },
        { PointBary_[3 * c + 1], PointBary_[3 * c + 2] } };
      return area(p);
    }
  }
  Support sup[3];
  int32_t all[9];
  int na = 0;
  for (int i = 0; i < 3; ++i)
  {
    sup[i] = this->supportOf(Tri_[3 * t + i]);
    for (int j = 0; j < sup[i].n; ++j)
    {
      all[na++] = sup[i].v[j];
    }
  }
  // Sorted by input id, without repeats (insertion sort: at most 9 ids).
  {
    // Swapped down one step at a time: a shifting loop would become a call to memmove.
    int32_t rank[9];
    int n = 0;
    for (int i = 0; i < na; ++i)
    {
      const int32_t x = all[i], r = VertexRank_[x];
      bool repeat = false;
      for (int m = 0; m < n; ++m)
      {
        repeat |= rank[m] == r;
      }
      if (repeat)
      {
        continue;
      }
      all[n] = x;
      rank[n] = r;
      for (int j = n; j > 0 && rank[j - 1] > rank[j]; --j)
      {
        std::swap(all[j - 1], all[j]);
        std::swap(rank[j - 1], rank[j]);
      }
      ++n;
    }
    na = n;
  }
  auto faceHas = [&](int32_t f, int32_t v)
  { return F_[3 * f] == v || F_[3 * f + 1] == v || F_[3 * f + 2] == v; };
  // Whether face f holds every image: na <= 3 distinct vertices, all among its corners.
  auto holdsAll = [&](int32_t f)
  {
    if (na > 3)
    {
      return false;
    }
    const int32_t c0 = F_[3 * f], c1 = F_[3 * f + 1], c2 = F_[3 * f + 2];
    for (int i = 0; i < na; ++i)
    {
      if (all[i] != c0 && all[i] != c1 && all[i] != c2)
      {
        return false;
      }
    }
    return true;
  };

  // The face that holds every image: a corner's face, or the base face spanned by the union,
  // looked for only when no corner's face holds them. Then no support spans a face; one on an
  // edge leaves only the face across that edge, else the faces around all[0] are searched.
  int32_t faces[4] = { sup[0].face, sup[1].face, sup[2].face, -1 };
  int edgeSupport = -1;
  for (int i = 0; i < 3; ++i)
  {
    edgeSupport = sup[i].n == 2 ? i : edgeSupport;
  }
  for (int i = 0; i < 4; ++i)
  {
    if (i == 3 && na == 3 && edgeSupport >= 0)
    {
      const Support& q = sup[edgeSupport];
      for (int e = 0; e < 3; ++e)
      {
        const int32_t a = F_[3 * q.face + e], b = F_[3 * q.face + (e + 1) % 3];
        if ((a == q.v[0] && b == q.v[1]) || (a == q.v[1] && b == q.v[0]))
        {
          faces[3] = Opp_[3 * q.face + e] / 3;
        }
      }
    }
    else if (i == 3 && na == 3)
    {
      const int32_t start = Out_[all[0]];
      int32_t h = start;
      do
      {
        if (faceHas(h / 3, all[1]) && faceHas(h / 3, all[2]))
        {
          faces[3] = h / 3;
        }
        h = Opp_[prevHe(h)];
      } while (h != start);
    }
    const int32_t f = faces[i];
    if (f < 0 || !holdsAll(f))
    {
      continue;
    }
    // Barycentric plane of f, drawn as the right triangle (0,0) (1,0) (0,1).
    P2 p[3];
    for (int j = 0; j < 3; ++j)
    {
      p[j] = { 0.0, 0.0 };
      for (int m = 0; m < sup[j].n; ++m)
      {
        p[j].x += sup[j].v[m] == F_[3 * f + 1] ? sup[j].w[m] : 0.0;
        p[j].y += sup[j].v[m] == F_[3 * f + 2] ? sup[j].w[m] : 0.0;
      }
    }
    return area(p);
  }
  for (int i = 0; i < 3 && na <= 4; ++i)
  {
    const int32_t f = sup[i].face;
    for (int e = 0; e < 3; ++e)
    {
      const int32_t h = Opp_[3 * f + e];
      const int32_t a = F_[3 * f + e], b = F_[3 * f + (e + 1) % 3], c = F_[3 * f + (e + 2) % 3];
      const int32_t d = F_[prevHe(h)];
      // Each image must lie in the closed face f = (a, b, c) or g = (b, a, d): four shared
      // vertices are not enough when another pair of faces spans them too.
      auto inHinge = [&](const Support& q)
      {
        bool inF = true, inG = true;
        for (int m = 0; m < q.n; ++m)
        {
          inF &= q.v[m] == a || q.v[m] == b || q.v[m] == c;
          inG &= q.v[m] == a || q.v[m] == b || q.v[m] == d;
        }
        return inF || inG;
      };
      if (!inHinge(sup[0]) || !inHinge(sup[1]) || !inHinge(sup[2]))
      {
        continue;
      }
      const V3 pa = this->pos(a), pb = this->pos(b);
      const double L = norm(sub(pb, pa));
      auto apex = [&](int32_t x, double sign)
      {
        const double ax = norm(sub(this->pos(x), pa)), bx = norm(sub(this->pos(x), pb));
        const double px = (ax * ax - bx * bx + L * L) / (2 * L);
        return P2{ px, sign * std::sqrt(std::max(0.0, ax * ax - px * px)) };
      };
      const int32_t ids[4] = { a, b, c, d };
      const P2 at[4] = { { 0.0, 0.0 }, { L, 0.0 }, apex(c, 1.0), apex(d, -1.0) };
      // A corner at an end of the hinge edge where the two faces together turn by pi or more:
      // a triangle there can be positive in the unfolding and yet lie outside it (its angle at
      // that end is the reflex rest of the plane), so the hinge does not hold it. tracePaths
      // draws the side opposite such a corner in the corner's star (bunny_glmark2 with features:
      // a saddle base vertex whose two faces span 181.7 degrees in 3D but 174.9 in its z^a star,
      // where the triangle is inverted); the star chart below decides, as it does there.
      bool reflexCorner = false;
      for (int j = 0; j < 3; ++j)
      {
        if (sup[j].n == 1 && (sup[j].v[0] == a || sup[j].v[0] == b))
        {
          // Convex at a when d, a, c turn left; at b when c, b, d do.
          reflexCorner |= sup[j].v[0] == a ? !(orient(at[0], at[3], at[2]) > 0.0)
                                           : !(orient(at[1], at[2], at[3]) > 0.0);
        }
      }
      if (reflexCorner)
      {
        continue;
      }
      P2 p[3];
      for (int j = 0; j < 3; ++j)
      {
        p[j] = { 0.0, 0.0 };
        for (int m = 0; m < sup[j].n; ++m)
        {
          const int k = static_cast<int>(std::find(ids, ids + 4, sup[j].v[m]) - ids);
          p[j].x += sup[j].w[m] * at[k].x;
          p[j].y += sup[j].w[m] * at[k].y;
        }
      }
      return area(p);
    }
  }
  for (int i = 0; i < na; ++i)
  {
    // A corner inside a face is only in the stars of that face's vertices: no ring needed.
    const int32_t c = all[i];
    auto corner = [&](const Support& q)
    { return q.n < 3 || q.v[0] == c || q.v[1] == c || q.v[2] == c; };
    if (!corner(sup[0]) || !corner(sup[1]) || !corner(sup[2]))
    {
      continue;
    }
    P2 p[3];
    if (this->inStar(c, sup, p))
    {
      if (starCentre)
      {
        *starCentre = all[i];
      }
      return area(p);
    }
  }
  return false;
}

int Simplifier::countInvalidAround(int32_t p) const
{
  int bad = 0;
  for (int32_t s = InOffsets_[p]; s < InOffsets_[p + 1]; ++s)
  {
    bad += !this->triangleValid(InHe_[s] / 3);
  }
  return bad;
}

/// One step of parameter-domain smoothing (the untangling half of MAPS's flip repair): moves p
/// to the mean of its mesh neighbours in the star chart that holds them (Tutte's barycentric
/// embedding, locally), and keeps the move only if fewer triangles around p are invalid.
bool Simplifier::smooth(int32_t p)
{
  const int before = this->countInvalidAround(p);
  if (before == 0)
  {
    return false;
  }
  // Chart: the lowest-numbered base vertex whose closed star holds the most neighbours.
  int32_t candidates[64];
  int nc = 0;
  for (int32_t s = InOffsets_[p]; s < InOffsets_[p + 1] && nc < 61; ++s)
  {
    const Support q = this->supportOf(Tri_[nextHe(InHe_[s])]);
    for (int j = 0; j < q.n; ++j)
    {
      candidates[nc++] = q.v[j];
    }
  }
  std::sort(candidates, candidates + nc,
    [&](int32_t a, int32_t b) { return VertexRank_[a] < VertexRank_[b]; });
  nc = static_cast<int>(std::unique(candidates, candidates + nc) - candidates);
  int32_t bestS = -1;
  int bestCount = 0;
  P2 bestMean{ 0, 0 };
  for (int c = 0; c < nc; ++c)
  {
    int count = 0;
    P2 mean{ 0, 0 };
    for (int32_t s = InOffsets_[p]; s < InOffsets_[p + 1]; ++s)
    {
      P2 at;
      if (this->inStar(candidates[c], this->supportOf(Tri_[nextHe(InHe_[s])]), &at))
      {
        ++count;
        mean.x += at.x;
        mean.y += at.y;
      }
    }
    if (count > bestCount)
    {
      bestCount = count;
      bestS = candidates[c];
      bestMean = { mean.x / count, mean.y / count };
    }
  }
  if (bestS < 0)
  {
    return false;
  }
  const StarChart& star = this->star(bestS, true);
  const int d = static_cast<int>(star.ring.size());
  for (int i = 0; i < d; ++i)
  {
    double w[3];
    if (!barycentric(bestMean, P2{ 0, 0 }, star.z[i], star.z[(i + 1) % d], w) ||
      std::min(w[0], std::min(w[1], w[2])) < -kInsideSlack)
    {
      continue;
    }
    const int32_t oldFace = PointFace_[p];
    const double oldBary[3] = { PointBary_[3 * p], PointBary_[3 * p + 1], PointBary_[3 * p + 2] };
    const int32_t h = star.he[i];
    const int c = h % 3;
    const double sum = std::max(0.0, w[0]) + std::max(0.0, w[1]) + std::max(0.0, w[2]);
    PointFace_[p] = h / 3;
    PointBary_[3 * p + c] = std::max(0.0, w[0]) / sum;
    PointBary_[3 * p + (c + 1) % 3] = std::max(0.0, w[1]) / sum;
    PointBary_[3 * p + (c + 2) % 3] = std::max(0.0, w[2]) / sum;
    if (this->countInvalidAround(p) < before)
    {
      return true;
    }
    PointFace_[p] = oldFace;
    std::copy(oldBary, oldBary + 3, &PointBary_[3 * p]);
    return false;
  }
  return false;
}

/// Flip repair (Lee et al. 1998; Feng et al. section 5.1 "we detect and fix any triangle flips
/// in the parametric domain"). The z^a maps of successive collapses bend straight lines, so a
/// thin input triangle can come out folded, or, where the base complex is still about as fine
/// as the input, stretched over more than one star. Every invalid triangle is found, and the
/// non-feature vertices of invalid triangles are smoothed in the parameter domain, sweep after
/// sweep, widening to their neighbours when a sweep makes no progress. Returns how many
/// triangles are still invalid.
int64_t Simplifier::repairFlips(const Progress& progress)
{
  std::vector<uint8_t> invalid(NumFaces_, 0);
  std::vector<int32_t> badList;
  for (int32_t t = 0; t < NumFaces_; ++t)
  {
    if (!this->triangleValid(t))
    {
      invalid[t] = 1;
      badList.push_back(t);
    }
  }
  progress.report(0.5);
  std::vector<int32_t> movable;
  std::vector<uint8_t> inSet(NumVertices_, 0);
  int ring = 0;
  const int kSweeps = 40;
  for (int sweep = 0; sweep < kSweeps && !badList.empty(); ++sweep)
  {
    movable.clear();
    for (int32_t t : badList)
    {
      for (int i = 0; i < 3; ++i)
      {
        const int32_t p = Tri_[3 * t + i];
        if (Removed_[p] && !Feature_[p] && !inSet[p])
        {
          inSet[p] = 1;
          movable.push_back(p);
        }
      }
    }
    // Widen: neighbours of the movable set, as many rings as sweeps without progress.
    for (int r = 0; r < ring; ++r)
    {
      const size_t n = movable.size();
      for (size_t i = 0; i < n; ++i)
      {
        for (int32_t s = InOffsets_[movable[i]]; s < InOffsets_[movable[i] + 1]; ++s)
        {
          const int32_t q = Tri_[nextHe(InHe_[s])];
          if (Removed_[q] && !Feature_[q] && !inSet[q])
          {
            inSet[q] = 1;
            movable.push_back(q);
          }
        }
      }
    }
    std::sort(movable.begin(), movable.end(),
      [&](int32_t a, int32_t b) { return VertexRank_[a] < VertexRank_[b]; });
    bool moved = false;
    for (int32_t p : movable)
    {
      moved |= this->smooth(p);
      inSet[p] = 0;
    }
    // Re-evaluate the triangles around the movable set.
    const size_t before = badList.size();
    for (int32_t p : movable)
    {
      for (int32_t s = InOffsets_[p]; s < InOffsets_[p + 1]; ++s)
      {
        const int32_t t = InHe_[s] / 3;
        const uint8_t now = !this->triangleValid(t);
        if (now && !invalid[t])
        {
          badList.push_back(t);
        }
        invalid[t] = now;
      }
    }
    badList.erase(
      std::remove_if(badList.begin(), badList.end(), [&](int32_t t) { return !invalid[t]; }),
      badList.end());
    std::sort(badList.begin(), badList.end());
    badList.erase(std::unique(badList.begin(), badList.end()), badList.end());
    ring = (moved && badList.size() < before) ? 0 : std::min(ring + 1, 4);
  }
  progress.report(1.0);
  return static_cast<int64_t>(badList.size());
}

BaseComplexResult Simplifier::output() const
{
  // Everything in input order and input ids.
  BaseComplexResult r;
  std::vector<int32_t> baseIndex(NumVertices_, -1);
  for (int32_t input = 0; input < NumVertices_; ++input)
  {
    const int32_t v = VertexOf_[input];
    if (!Removed_[v])
    {
      baseIndex[v] = static_cast<int32_t>(r.baseVertices.size());
      r.baseVertices.push_back(input);
    }
  }
  std::vector<int32_t> faceIndex(NumFaces_, -1);
  for (int32_t input = 0; input < NumFaces_; ++input)
  {
    const int32_t f = FaceOf_[input];
    if (!FaceAlive_[f])
    {
      continue;
    }
    faceIndex[f] = static_cast<int32_t>(r.baseTriangles.size() / 3);
    for (int i = 0; i < 3; ++i)
    {
      r.baseTriangles.push_back(baseIndex[F_[3 * f + i]]);
      r.baseEdgeIsFeature.push_back(FeatureHe_[3 * f + i]);
    }
  }
  r.vertexBaseFace.resize(NumVertices_);
  r.vertexBarycentric.assign(3 * static_cast<size_t>(NumVertices_), 0.0);
  for (int32_t input = 0; input < NumVertices_; ++input)
  {
    const int32_t v = VertexOf_[input];
    if (Removed_[v])
    {
      r.vertexBaseFace[input] = faceIndex[PointFace_[v]];
      std::copy(&PointBary_[3 * v], &PointBary_[3 * v] + 3, &r.vertexBarycentric[3 * input]);
    }
    else
    {
      const int32_t h = Out_[v];
      r.vertexBaseFace[input] = faceIndex[h / 3];
      r.vertexBarycentric[3 * input + h % 3] = 1.0;
    }
  }
  return r;
}
} // namespace

BaseComplexResult buildBaseComplex(const TriMesh& mesh, const std::vector<uint8_t>& featureVertex,
  const std::vector<uint8_t>& cornerVertex, const std::vector<int32_t>& featureEdges,
  const BaseComplexOptions& options, const Progress& progress)
{
  Simplifier simplifier(mesh, featureVertex, cornerVertex, featureEdges, options);
  return simplifier.run(progress);
}
} // namespace tc
