// SPDX-License-Identifier: BSD-3-Clause
/// @file path_tracer.h
/// The path tracer behind tracePaths (tc/gim/path_tracing.h), private to the core: the class
/// Tracer and the small types its steps share. Its steps live in their own files:
///   path_tracing.cpp  tracePaths and Tracer::run, the steps in order; which triangles are cut
///   path_input.cpp    the input checked and read: the images of the mesh's vertices, its
///                     half-edge twins, the base edges and the star charts of the base vertices
///   path_route.cpp    the route of an input edge over the base complex (step 1 below)
///   path_split.cpp    an input triangle cut along the base edges (step 2)
///   path_output.cpp   Steiner points, paths chained (step 3), output triangles
///
/// Tracing by overlay. Feng et al. (section 5.1, Fig. 9) intersect each base edge with the input
/// triangles drawn in the plane of its two unfolded base faces. Done literally, base edge by base
/// edge and triangle by triangle, one input edge is drawn in different charts for different
/// triangles and base edges, and the Steiner points of neighbours disagree (T-junctions, paths
/// that cross). Here each input edge is drawn once, and the rest is combinatorial:
///  1. An input edge (u, v) is a straight segment in one chart that holds the images of both
///     ends: their common base face (no crossing), or else the two base faces unfolded about their
///     common edge (the paper's quadrilateral) or the star of a base vertex flattened by z^a
///     (MAPS), possibly with the faces just outside it unfolded onto its link edges; route()
///     says which first. The segment is followed from face to face, must stay inside the chart and
///     pass no base vertex. Its route lists the base edges it crosses, each with its parameter t
///     (a Steiner point) and the base faces before and after, or names the base edge the input
///     edge lies on. Routes run from the lower vertex id to the higher, so both triangles of an
///     edge compute bit-identical Steiner points: no T-junction.
///  2. Round an input triangle its routes give a cyclic word of crossings; a corner on a base edge
///     or at a base vertex spans one or more base faces and adds the crossings between them. No
///     base vertex lies inside a triangle, so the base edges in it are chords, each joining a
///     crossing to the one that undoes it (same base edge, faces swapped): the word reduces like
///     nested brackets. The chords cut the triangle into convex pieces, each in one base face,
///     triangulated by the fan whose smallest triangle is largest. A triangle whose word does not
///     reduce is retried with other charts for its sides (repair()).
///  3. The chords and the input edges on base edges are chained into one path per base edge, from
///     its lower base vertex to its higher one.
/// Words that do not reduce, corners that disagree with their routes, chains that do not run from
/// end to end: the parameterization is not one-to-one there, and an UntraceableError says so.
/// Feature curves: MAPS puts their vertices exactly on their base edge, so their input edges lie
/// on it and their paths pass through input vertices only. Round-off: see kSnap.
/// Written by hand: no library overlays a mesh with the edges of its own parameter domain (CGAL's
/// corefinement and arrangements cut embedded 3D meshes or plane curves, not a MAPS atlas).
#pragma once

#include "tc/gim/path_tracing.h"

#include "detail/geometry2d.h"
#include "detail/half_edge.h"
#include "detail/vec3.h"

#include <algorithm>
#include <array>
#include <cstdint>
#include <limits>
#include <string>
#include <utility>
#include <vector>

namespace tc
{
namespace detail
{
namespace tracing
{
/// A barycentric below this (the other two above it) puts the point on the base edge. A point
/// that round-off has moved off the edge it belongs on would otherwise have the path pass just
/// beside it and cut slivers off its triangles: pieces with a vanishing fraction of their area.
/// MAPS places feature vertices exactly (barycentric 0); snapping others moves them by at most
/// kSnap of a base triangle. Not snapped: a point next to a base vertex (two small barycentrics),
/// which is on neither edge, nor a point whose snap would put a whole input triangle on one base
/// edge (a sliver next to a short base edge has an area in the base domain below kSnap itself,
/// and snapped it would have none; see Tracer::keepOffEdges).
constexpr double kSnap = 1e-6;
/// Most base edges one input edge may cross (in a star: the valence of its centre).
constexpr int kMaxCrossings = 64;

/// The end of the message of every UntraceableError of the tracer: why, and what to change.
inline constexpr char kNotOneToOne[] =
  "; the parameterization is not one-to-one there: rebuild the base complex with "
  "checkBijection on, or with a coarser target (fewer base faces); a scan's slivers (near-flat "
  "triangles) cause this: remove them in the preparation (RemoveSlivers, --remove-slivers)";

/// The image of an input vertex: its base vertices with non-zero barycentrics (1: a base vertex,
/// 2: a point of a base edge, 3: inside a base face).
struct Support
{
  int n = 0;
  int32_t v[3] = { -1, -1, -1 };
  double w[3] = { 0, 0, 0 };
  double weight(int32_t x) const
  {
    return v[0] == x ? w[0] : (v[1] == x ? w[1] : (v[2] == x ? w[2] : 0.0));
  }
};

/// A base vertex's ring (counter-clockwise) and its star flattened by z^a, the vertex at 0.
/// Sector j is the base face (s, ring[j], ring[j + 1]).
struct StarChart
{
  std::vector<int32_t> ring;
  std::vector<P2> z;
  std::vector<int32_t> sector; ///< base face of sector j
  /// The base face across link edge j (ring[j], ring[j + 1]) and the position of its third
  /// vertex, the face unfolded onto the chart (its 3D shape, scaled onto the link edge); -1
  /// where that face is in the star itself.
  std::vector<int32_t> outer;
  std::vector<int32_t> outerApex;
  std::vector<P2> apexAt;
  int index(int32_t v) const
  {
    for (size_t i = 0; i < ring.size(); ++i)
    {
      if (ring[i] == v)
      {
        return static_cast<int>(i);
      }
    }
    return -1;
  }
};

/// One crossing of an input edge with a base edge.
struct Crossing
{
  double t;     ///< along the route's input edge
  int32_t edge; ///< base edge
  int32_t from; ///< base face before the crossing
  int32_t to;   ///< base face after it
};

/// An input edge drawn over the base complex.
struct Route
{
  enum Kind : int8_t
  {
    kNoChart,  ///< no chart holds a straight segment between the images of its ends
    kInFace,   ///< inside one base face (its ends may be on its sides or corners)
    kAlong,    ///< on base edge `along`
    kCrossing, ///< crosses n base edges
  };
  Kind kind = kNoChart;
  int32_t first = -1; ///< base face just after the start (kAlong: the face on the left)
  int32_t last = -1;  ///< base face just before the end (kAlong: the face on the left)
  int32_t along = -1;
  int n = 0;
  std::array<Crossing, kMaxCrossings> c;

  void reverse()
  {
    std::swap(first, last);
    std::reverse(c.begin(), c.begin() + n);
    for (int i = 0; i < n; ++i)
    {
      c[i].t = 1.0 - c[i].t;
      std::swap(c[i].from, c[i].to);
    }
  }
};

/// A transition on the boundary of an input triangle: at `point` the boundary crosses base edge
/// `edge` from base face `from` to base face `to`.
struct Transition
{
  int64_t point; ///< input vertex, or a Steiner point as numbered by provisional()
  int32_t edge;
  int32_t from, to;
};

/// A piece of a path: a chord through an input triangle, or an input edge on a base edge.
struct Link
{
  int32_t edge;
  int64_t p, q; ///< points as in Transition
};

/// An input triangle cut along the paths.
struct Pieces
{
  std::vector<int64_t> triangles; ///< x 3, points as in Transition
  std::vector<int32_t> patch;     ///< base face of each
  std::vector<Link> links;        ///< chords
  /// Crossings (lower half-edge, t from the lower vertex id) of the sides whose lower
  /// half-edge is in this triangle, in order along each.
  std::vector<std::pair<int32_t, double>> cuts;
  std::string error; ///< why it cannot be cut; empty if it can
};

/// A Steiner point before the points are numbered: the k-th crossing (from the lower vertex id
/// to the higher) of the input edge whose lower half-edge is `key`.
inline int64_t provisional(int32_t key, int k)
{
  return -1 - (static_cast<int64_t>(key) * kMaxCrossings + k);
}

/// The point at t on the segment from a to b. The one expression of a Steiner point's position,
/// so that both triangles of an input edge and the output agree to the bit.
inline V3 pointAt(const V3& a, const V3& b, double t)
{
  return { a.x + t * (b.x - a.x), a.y + t * (b.y - a.y), a.z + t * (b.z - a.z) };
}

/// Key of the directed base edge a -> b in the sorted list of directed base edges.
inline int64_t directedKey(int32_t a, int32_t b)
{
  return (static_cast<int64_t>(a) << 32) | static_cast<uint32_t>(b);
}
inline int32_t keyFrom(int64_t key)
{
  return static_cast<int32_t>(key >> 32);
}
inline int32_t keyTo(int64_t key)
{
  return static_cast<int32_t>(key & 0xffffffff);
}

/// Traces the paths of one base complex over one mesh (see the top of this file). Used once:
/// construct, run().
class Tracer
{
public:
  Tracer(const TriMesh& mesh, const BaseComplexResult& base)
    : Mesh_(mesh)
    , Base_(base)
  {
  }
  /// The steps of the top of this file, in order (path_tracing.cpp).
  PatchMesh run(const Progress& progress);

private:
  struct PlacedFaces; ///< a star chart with the faces across its link (path_route.cpp)
  struct Boundary;    ///< the boundary word of an input triangle (path_split.cpp)

  // The input (path_input.cpp).
  void validate(const Progress& progress);
  void checkShapes();
  void checkIds() const;
  void checkImages(const Progress& progress);
  void keepOffEdges();
  void buildTopology(const Progress& progress);
  void findTwins(const std::vector<int32_t>& offsets, const std::vector<int32_t>& outgoing,
    const Progress& progress);
  void checkFans(const std::vector<int32_t>& offsets, const std::vector<int32_t>& outgoing,
    const Progress& progress) const;

  // The base complex (path_input.cpp).
  void buildBase();
  void sortDirectedBase();
  void listBaseEdges();
  void buildStars();
  void walkRing(int32_t s, int32_t faces, StarChart& star) const;
  void unfoldOuterFaces(int32_t s, StarChart& star) const;

  // Routes (path_route.cpp). The helpers of route() and split() marked inline are defined and
  // called in one file only: inline lets the compiler inline them there (a plain member of this
  // library, built as position-independent code with every symbol exported, could be interposed
  // at load time, so the compiler never inlines it).
  bool direct(const Support& su, const Support& sv, Route& r) const;
  void route(int32_t h, int choice, Route& r) const;
  inline int nearStars(
    int32_t h, const Support& su, const Support& sv, int32_t stars[8], int& napex) const;
  inline bool tryStars(
    const Support& su, const Support& sv, const int32_t* stars, int n, int& choice, Route& r) const;
  inline bool tryHinges(
    int32_t u, const Support& su, const Support& sv, int& choice, Route& r) const;
  inline bool tryOtherStars(const Support& su, const Support& sv, const int32_t* tried, int ntried,
    int& choice, Route& r) const;
  inline bool hingeRoute(const Support& su, const Support& sv, int32_t f, int k, Route& r) const;
  bool starRoute(const Support& su, const Support& sv, int32_t s, bool outside, Route& r) const;
  inline bool walkStar(const PlacedFaces& chart, int start, int end, const Support& sv, const P2& p,
    const P2& q, Route& r) const;
  void routeOf(int32_t h, Route& r) const;

  // Cutting triangles (path_tracing.cpp, path_split.cpp).
  void findEdgesOnBase(const Progress& progress);
  void findWholeTriangles(const Progress& progress);
  void cutTriangles(const Progress& progress);
  int32_t commonFace(int32_t f) const;
  void split(int32_t f, Pieces& out) const;
  inline bool traceBoundary(int32_t f, const Route routes[3], Boundary& b, Pieces& out) const;
  inline bool addCorner(int32_t c, int32_t in, int32_t outFace, Boundary& b, Pieces& out) const;
  inline bool addSide(int32_t h, const Route& r, Boundary& b, Pieces& out) const;
  inline void orderCuts(int32_t f, Pieces& out) const;
  bool repair(int32_t f, int32_t keep, int depth, std::vector<int32_t>& changed);

  // The output (path_output.cpp).
  int64_t numberSteinerPoints();
  void placeSteinerPoints(int64_t ns, const Progress& progress);
  void chainPaths(const Progress& progress);
  std::vector<Link> pathLinks() const;
  std::string chainPath(int32_t e, const Link* links, int64_t nl, std::vector<int32_t>& path) const;
  void writeTriangles(int64_t ns, const Progress& progress);
  std::string edgeName(int32_t e) const;
  std::string pointName(int32_t p) const;

  /// The image of w, snapped onto a base edge unless keepOffEdges() forbade it.
  Support support(int32_t w) const { return this->image(w, !NoSnap_[w]); }
  Support image(int32_t w, bool snap) const;
  int32_t faceOf(int32_t a, int32_t b) const;
  int32_t edgeIndex(int32_t a, int32_t b) const;
  /// Whether base vertex v is a corner of base face g.
  bool faceHas(int32_t g, int32_t v) const
  {
    return Base_.baseTriangles[3 * g] == v || Base_.baseTriangles[3 * g + 1] == v ||
      Base_.baseTriangles[3 * g + 2] == v;
  }
  /// Whether base face g holds the image s (its base vertices are corners of g).
  bool faceHolds(int32_t g, const Support& s) const
  {
    for (int i = 0; i < s.n; ++i)
    {
      if (!this->faceHas(g, s.v[i]))
      {
        return false;
      }
    }
    return true;
  }
  /// The corner of base face g that is neither a nor b.
  int32_t thirdCorner(int32_t g, int32_t a, int32_t b) const
  {
    const std::vector<int32_t>& bt = Base_.baseTriangles;
    int32_t w = -1;
    for (int m = 0; m < 3; ++m)
    {
      w = bt[3 * g + m] != a && bt[3 * g + m] != b ? bt[3 * g + m] : w;
    }
    return w;
  }
  /// Output point id of a point as in Transition (once numberSteinerPoints() has run).
  int32_t pointId(int64_t p) const
  {
    if (p >= 0)
    {
      return static_cast<int32_t>(p);
    }
    const int64_t code = -1 - p;
    return NV_ + SteinerStart_[code / kMaxCrossings] + static_cast<int32_t>(code % kMaxCrossings);
  }

  int32_t from(int32_t h) const { return Mesh_.triangles[h]; }
  int32_t to(int32_t h) const { return Mesh_.triangles[nextHe(h)]; }
  /// The ends of the input edge of h, lower and higher vertex id.
  int32_t lower(int32_t h) const { return std::min(this->from(h), this->to(h)); }
  int32_t upper(int32_t h) const { return std::max(this->from(h), this->to(h)); }
  /// The half-edge of h's input edge that stands for it (the lower of h and its twin).
  int32_t lowerHalfEdge(int32_t h) const { return std::min(h, Opp_[h]); }
  V3 pos(int32_t v) const
  {
    return { Mesh_.points[3 * v], Mesh_.points[3 * v + 1], Mesh_.points[3 * v + 2] };
  }
  V3 basePos(int32_t b) const { return this->pos(Base_.baseVertices[b]); }

  const TriMesh& Mesh_;
  const BaseComplexResult& Base_;
  int32_t NV_ = 0, NF_ = 0, NB_ = 0, NFB_ = 0;

  std::vector<int32_t> Opp_;       ///< twin of every half-edge 3f + i (corner i to corner i + 1)
  std::vector<int32_t> BaseIndex_; ///< input vertex -> base vertex, -1 if none
  std::vector<uint8_t> NoSnap_;    ///< input vertices that support() never snaps onto an edge

  std::vector<std::pair<int64_t, int32_t>>
    DirectedBase_; ///< directedKey(a, b) -> base face, sorted
  std::vector<StarChart> Stars_;
  bool StarsReady_ = false;
  std::vector<uint8_t> Choice_; ///< chart of each input edge (lower half-edge), see route()

  std::vector<int32_t> AlongEdge_; ///< base edge an input edge lies on (lower half-edge), or -1
  std::vector<int32_t> Label_;     ///< base face of an input triangle kept whole, or -1
  std::vector<int32_t> Cut_;       ///< the input triangles that are cut, ascending
  std::vector<int32_t> Slot_;      ///< index in Cut_ (and Pieces_) of an input triangle, or -1
  std::vector<Pieces> Pieces_;     ///< the pieces of each triangle of Cut_

  std::vector<int32_t> SteinerStart_; ///< first Steiner id of each input edge (lower half-edge)
  PatchMesh Result_;
};

inline Support Tracer::image(int32_t w, bool snap) const
{
  Support s;
  if (BaseIndex_[w] >= 0)
  {
    s.n = 1;
    s.v[0] = BaseIndex_[w];
    s.w[0] = 1.0;
    return s;
  }
  const int32_t g = Base_.vertexBaseFace[w];
  double l[3];
  double sum = 0.0;
  for (int k = 0; k < 3; ++k)
  {
    l[k] = std::max(0.0, Base_.vertexBarycentric[3 * static_cast<size_t>(w) + k]);
    sum += l[k];
  }
  int small = 0, which = -1;
  for (int k = 0; k < 3; ++k)
  {
    l[k] /= sum;
    if (l[k] > 0.0 && l[k] < kSnap)
    {
      ++small;
      which = k;
    }
  }
  // Round-off of a point on a base edge: put it on the edge. Not when two are small: that is a
  // point next to a base vertex, which is on neither edge.
  if (snap && small == 1 && l[(which + 1) % 3] >= kSnap && l[(which + 2) % 3] >= kSnap)
  {
    const double rest = 1.0 - l[which];
    l[which] = 0.0;
    l[(which + 1) % 3] /= rest;
    l[(which + 2) % 3] /= rest;
  }
  for (int k = 0; k < 3; ++k)
  {
    if (l[k] > 0.0)
    {
      s.v[s.n] = Base_.baseTriangles[3 * g + k];
      s.w[s.n] = l[k];
      ++s.n;
    }
  }
  return s;
}

/// The base face of the directed base edge a -> b (on its left), -1 if there is none.
inline int32_t Tracer::faceOf(int32_t a, int32_t b) const
{
  if (StarsReady_)
  {
    // The ring of a is short: faster than the binary search.
    const StarChart& st = Stars_[a];
    const int k = st.index(b);
    return k < 0 ? -1 : st.sector[k];
  }
  const int64_t key = directedKey(a, b);
  const auto it = std::lower_bound(DirectedBase_.begin(), DirectedBase_.end(),
    std::make_pair(key, std::numeric_limits<int32_t>::min()));
  return it != DirectedBase_.end() && it->first == key ? it->second : -1;
}

/// Index in PatchMesh::baseEdges of the base edge {a, b} (binary search).
inline int32_t Tracer::edgeIndex(int32_t a, int32_t b) const
{
  const std::pair<int32_t, int32_t> key(std::min(a, b), std::max(a, b));
  int32_t lo = 0, hi = static_cast<int32_t>(Result_.baseEdges.size() / 2);
  while (lo < hi)
  {
    const int32_t mid = (lo + hi) / 2;
    const std::pair<int32_t, int32_t> m(Result_.baseEdges[2 * mid], Result_.baseEdges[2 * mid + 1]);
    if (m < key)
    {
      lo = mid + 1;
    }
    else
    {
      hi = mid;
    }
  }
  return lo;
}
} // namespace tracing
} // namespace detail
} // namespace tc
