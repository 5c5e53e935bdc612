// SPDX-License-Identifier: BSD-3-Clause
#include "tc/gim/path_tracing.h"

#include "detail/geometry2d.h"
#include "detail/half_edge.h"
#include "detail/star_map.h"
#include "detail/vec3.h"

#include "tc/common/errors.h"
#include "tc/common/parallel.h"

// Tracing by overlay. Feng et al. (section 5.1, Fig. 9) intersect each base edge with the input
// triangles drawn in the plane of its two unfolded base faces. Done literally, base edge by base
// edge and triangle by triangle, one input edge is drawn in different charts for different
// triangles and base edges, and the Steiner points of neighbours disagree (T-junctions, paths
// that cross). Here each input edge is drawn once, and the rest is combinatorial:
//  1. An input edge (u, v) is a straight segment in one chart that holds the images of both
//     ends: their common base face (no crossing), or else the two base faces unfolded about their
//     common edge (the paper's quadrilateral) or the star of a base vertex flattened by z^a
//     (MAPS), possibly with the faces just outside it unfolded onto its link edges; route()
//     says which first. The segment is followed from face to face, must stay inside the chart and
//     pass no base vertex. Its route lists the base edges it crosses, each with its parameter t
//     (a Steiner point) and the base faces before and after, or names the base edge the input
//     edge lies on. Routes run from the lower vertex id to the higher, so both triangles of an
//     edge compute bit-identical Steiner points: no T-junction.
//  2. Round an input triangle its routes give a cyclic word of crossings; a corner on a base edge
//     or at a base vertex spans one or more base faces and adds the crossings between them. No
//     base vertex lies inside a triangle, so the base edges in it are chords, each joining a
//     crossing to the one that undoes it (same base edge, faces swapped): the word reduces like
//     nested brackets. The chords cut the triangle into convex pieces, each in one base face,
//     triangulated by the fan whose smallest triangle is largest. A triangle whose word does not
//     reduce is retried with other charts for its sides (see run()).
//  3. The chords and the input edges on base edges are chained into one path per base edge, from
//     its lower base vertex to its higher one.
// Words that do not reduce, corners that disagree with their routes, chains that do not run from
// end to end: the parameterization is not one-to-one there, and an InputError says so. Feature
// curves: MAPS puts their vertices exactly on their base edge, so their input edges lie on it
// and their paths pass through input vertices only. Round-off: see kSnap.
// Written by hand: no library overlays a mesh with the edges of its own parameter domain (CGAL's
// corefinement and arrangements cut embedded 3D meshes or plane curves, not a MAPS atlas).

#include <algorithm>
#include <array>
#include <atomic>
#include <cmath>
#include <limits>
#include <string>
#include <utility>
#include <vector>

namespace tc
{
namespace
{
using detail::kPi;
/// A barycentric below this (the other two above it) puts the point on the base edge: the path
/// then passes through the point instead of cutting slivers off its triangles (a point 5e-9 off
/// an edge on fandisk left pieces of 1e-14 of their triangle). MAPS places feature vertices
/// exactly (barycentric 0); snapping others moves them by at most 1e-6 of a base triangle, and a
/// point next to a base vertex (two small barycentrics) is not snapped onto either edge, nor a
/// point whose snap would put a whole input triangle on one base edge (a sliver of a scan next to
/// a short base edge: its area in the base domain is itself below kSnap, and snapped it would
/// have none; see Tracer::keepOffEdges).
constexpr double kSnap = 1e-6;
/// Most base edges one input edge may cross (in a star: the valence of its centre).
constexpr int kMaxCrossings = 64;

using detail::nextHe;
using detail::prevHe;
using detail::P2;

using detail::cross;
using detail::dot;
using detail::norm;
using detail::sub;
using detail::V3;

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

class Tracer
{
public:
  Tracer(const TriMesh& mesh, const BaseComplexResult& base)
    : Mesh_(mesh)
    , Base_(base)
  {
  }
  PatchMesh run(const Progress& progress);

private:
  /// An input triangle cut along the paths.
  struct Pieces
  {
    std::vector<int64_t> triangles; ///< x 3, points as in Transition
    std::vector<int32_t> patch;     ///< base face of each
    std::vector<Link> links;        ///< chords
    /// Crossings (lower half-edge, t from the lower vertex id) of the sides whose lower
    /// half-edge is in this triangle, in order along each.
    std::vector<std::pair<int32_t, double>> cuts;
    std::string error;
  };

  void validate(const Progress& progress);
  void buildTopology(const Progress& progress);
  void buildBase();
  /// The image of w, snapped onto a base edge unless keepOffEdges() forbade it.
  Support support(int32_t w) const { return this->image(w, !NoSnap_[w]); }
  Support image(int32_t w, bool snap) const;
  void keepOffEdges();
  int32_t faceOf(int32_t a, int32_t b) const;
  int32_t edgeIndex(int32_t a, int32_t b) const;
  bool faceHas(int32_t g, int32_t v) const
  {
    return Base_.baseTriangles[3 * g] == v || Base_.baseTriangles[3 * g + 1] == v ||
      Base_.baseTriangles[3 * g + 2] == v;
  }
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
  bool direct(const Support& su, const Support& sv, Route& r) const;
  void route(int32_t h, int choice, Route& r) const;
  bool hingeRoute(const Support& su, const Support& sv, int32_t f, int k, Route& r) const;
  bool starRoute(const Support& su, const Support& sv, int32_t s, bool outside, Route& r) const;
  void routeOf(int32_t h, Route& r) const;
  int32_t commonFace(int32_t f) const;
  void split(int32_t f, Pieces& out) const;
  bool repair(int32_t f, int32_t keep, int depth, const std::vector<int32_t>& slot,
    std::vector<int32_t>& changed);
  std::string edgeName(int32_t e) const;
  std::string pointName(int32_t p) const;

  int32_t from(int32_t h) const { return Mesh_.triangles[h]; }
  int32_t to(int32_t h) const { return Mesh_.triangles[nextHe(h)]; }
  V3 pos(int32_t v) const
  {
    return { Mesh_.points[3 * v], Mesh_.points[3 * v + 1], Mesh_.points[3 * v + 2] };
  }

  const TriMesh& Mesh_;
  const BaseComplexResult& Base_;
  int32_t NV_ = 0, NF_ = 0, NB_ = 0, NFB_ = 0;

  std::vector<int32_t> Opp_;       ///< twin of every half-edge 3f + i (corner i to corner i + 1)
  std::vector<int32_t> BaseIndex_; ///< input vertex -> base vertex, -1 if none
  std::vector<uint8_t> NoSnap_;    ///< input vertices that support() never snaps onto an edge

  std::vector<std::pair<int64_t, int32_t>> DirectedBase_; ///< (a << 32 | b) -> base face, sorted
  std::vector<StarChart> Stars_;
  bool StarsReady_ = false;
  std::vector<uint8_t> Choice_;       ///< chart of each input edge (lower half-edge), see route()
  std::vector<int32_t> SteinerStart_; ///< first Steiner id of each input edge (lower half-edge)
  PatchMesh Result_;
};

void Tracer::validate(const Progress& progress)
{
  if (Mesh_.points.size() % 3 != 0 || Mesh_.triangles.size() % 3 != 0)
  {
    throw InputError("tracePaths: points and triangles must be flat #V x 3 and #F x 3 arrays");
  }
  if (Mesh_.triangles.size() >= static_cast<size_t>(std::numeric_limits<int32_t>::max()) ||
    Mesh_.numPoints() >= std::numeric_limits<int32_t>::max() / 2)
  {
    throw InputError("tracePaths: the mesh is too large for 32-bit half-edge ids");
  }
  NV_ = static_cast<int32_t>(Mesh_.numPoints());
  NF_ = static_cast<int32_t>(Mesh_.numTriangles());
  NB_ = static_cast<int32_t>(Base_.baseVertices.size());
  NFB_ = static_cast<int32_t>(Base_.baseTriangles.size() / 3);
  if (NF_ < 4)
  {
    throw InputError("tracePaths: the mesh needs at least 4 triangles (a closed surface)");
  }
  if (Base_.vertexBaseFace.size() != static_cast<size_t>(NV_) ||
    Base_.vertexBarycentric.size() != 3 * static_cast<size_t>(NV_))
  {
    throw InputError("tracePaths: the base complex does not match the mesh (vertexBaseFace and "
                     "vertexBarycentric need one entry per point); pass the mesh that "
                     "buildBaseComplex was given");
  }
  if (NB_ < 4 || NFB_ < 4 || Base_.baseTriangles.size() % 3 != 0 ||
    Base_.baseEdgeIsFeature.size() != Base_.baseTriangles.size())
  {
    throw InputError("tracePaths: the base complex needs at least 4 vertices and 4 triangles, and "
                     "baseEdgeIsFeature one entry per triangle side");
  }
  for (int32_t i = 0; i < NB_; ++i)
  {
    const int32_t v = Base_.baseVertices[i];
    if (v < 0 || v >= NV_ || (i > 0 && v <= Base_.baseVertices[i - 1]))
    {
      throw InputError("tracePaths: baseVertices must be ascending point ids of the mesh");
    }
  }
  for (int32_t x : Base_.baseTriangles)
  {
    if (x < 0 || x >= NB_)
    {
      throw InputError("tracePaths: baseTriangles refers to a base vertex that does not exist");
    }
  }
  for (int32_t x : Mesh_.triangles)
  {
    if (x < 0 || x >= NV_)
    {
      throw InputError("tracePaths: a triangle refers to a point that does not exist");
    }
  }
  BaseIndex_.assign(NV_, -1);
  for (int32_t i = 0; i < NB_; ++i)
  {
    BaseIndex_[Base_.baseVertices[i]] = i;
  }
  NoSnap_.assign(NV_, 0);
  // Every image must be a point of its base face; a vertex other than a base vertex must not
  // land on a base vertex (two input vertices at one point of the base complex cannot be cut
  // apart). The first bad vertex is reported, whatever the thread count.
  std::atomic<int32_t> firstBad{ std::numeric_limits<int32_t>::max() };
  tc::parallel_for(
    NV_,
    [&](int64_t i)
    {
      const int32_t v = static_cast<int32_t>(i);
      const int32_t g = Base_.vertexBaseFace[v];
      const double* w = &Base_.vertexBarycentric[3 * static_cast<size_t>(v)];
      bool ok = g >= 0 && g < NFB_;
      double sum = 0.0;
      for (int k = 0; k < 3; ++k)
      {
        ok &= std::isfinite(w[k]) && w[k] >= -1e-9;
        sum += w[k];
      }
      ok &= std::abs(sum - 1.0) <= 1e-6;
      if (ok)
      {
        const Support s = this->support(v);
        ok = BaseIndex_[v] >= 0 ? (s.n == 1 && s.v[0] == BaseIndex_[v]) : s.n >= 2;
      }
      if (!ok)
      {
        int32_t cur = firstBad.load();
        while (v < cur && !firstBad.compare_exchange_weak(cur, v))
        {
        }
      }
    },
    progress);
  if (firstBad.load() != std::numeric_limits<int32_t>::max())
  {
    const int32_t v = firstBad.load();
    throw InputError("tracePaths: point " + std::to_string(v) +
      " has no valid image in the base complex (base face and barycentrics summing to 1; a base "
      "vertex on its own corner, no other point on a base vertex); rebuild the base complex "
      "from this mesh");
  }
  this->keepOffEdges();
}

void Tracer::buildTopology(const Progress& progress)
{
  // Outgoing half-edges of every vertex (CSR), then each twin is found in the list of the
  // half-edge's end: linear time, no sort, and parallel.
  const int32_t nh = 3 * NF_;
  std::vector<int32_t> offsets(static_cast<size_t>(NV_) + 1, 0);
  for (int32_t h = 0; h < nh; ++h)
  {
    ++offsets[Mesh_.triangles[h] + 1];
  }
  for (int32_t v = 0; v < NV_; ++v)
  {
    offsets[v + 1] += offsets[v];
  }
  std::vector<int32_t> outgoing(nh);
  {
    std::vector<int32_t> fill(offsets.begin(), offsets.end() - 1);
    for (int32_t h = 0; h < nh; ++h)
    {
      outgoing[fill[Mesh_.triangles[h]]++] = h;
    }
  }
  Opp_.assign(nh, -1);
  std::atomic<int32_t> firstBad{ std::numeric_limits<int32_t>::max() };
  auto flag = [&](int32_t h)
  {
    int32_t cur = firstBad.load();
    while (h < cur && !firstBad.compare_exchange_weak(cur, h))
    {
    }
  };
  tc::parallel_for(
    nh,
    [&](int64_t i)
    {
      const int32_t h = static_cast<int32_t>(i);
      const int32_t u = this->from(h), v = this->to(h);
      int found = 0;
      for (int32_t k = offsets[v]; k < offsets[v + 1]; ++k)
      {
        const int32_t g = outgoing[k];
        if (this->to(g) == u)
        {
          Opp_[h] = g;
          ++found;
        }
      }
      // A repeated u -> v shows as two twins of v -> u, a missing twin or a reversed triangle
      // as none.
      if (found != 1 || u == v)
      {
        flag(h);
      }
    },
    progress.sub(0.0, 0.5));
  if (firstBad.load() != std::numeric_limits<int32_t>::max())
  {
    const int32_t h = firstBad.load();
    throw InputError("tracePaths: the mesh is not a closed oriented manifold (edge " +
      std::to_string(this->from(h)) + "-" + std::to_string(this->to(h)) +
      " has no single opposite twin); pass the mesh that buildBaseComplex was given");
  }
  // One fan per vertex: turning around v through the twins visits all its half-edges.
  tc::parallel_for(
    NV_,
    [&](int64_t i)
    {
      const int32_t v = static_cast<int32_t>(i);
      const int32_t count = offsets[v + 1] - offsets[v];
      if (count == 0)
      {
        return;
      }
      const int32_t start = outgoing[offsets[v]];
      int32_t h = start, steps = 0;
      do
      {
        h = Opp_[prevHe(h)];
        ++steps;
      } while (h != start && steps <= count);
      if (steps != count)
      {
        flag(start);
      }
    },
    progress.sub(0.5, 1.0));
  if (firstBad.load() != std::numeric_limits<int32_t>::max())
  {
    throw InputError("tracePaths: the triangles around point " +
      std::to_string(this->from(firstBad.load())) +
      " do not form one fan (non-manifold vertex); pass the mesh that buildBaseComplex was given");
  }
}

int32_t Tracer::faceOf(int32_t a, int32_t b) const
{
  if (StarsReady_)
  {
    // The ring of a is short: faster than the binary search.
    const StarChart& st = Stars_[a];
    const int k = st.index(b);
    return k < 0 ? -1 : st.sector[k];
  }
  const int64_t key = (static_cast<int64_t>(a) << 32) | static_cast<uint32_t>(b);
  const auto it = std::lower_bound(DirectedBase_.begin(), DirectedBase_.end(),
    std::make_pair(key, std::numeric_limits<int32_t>::min()));
  return it != DirectedBase_.end() && it->first == key ? it->second : -1;
}

int32_t Tracer::edgeIndex(int32_t a, int32_t b) const
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

void Tracer::buildBase()
{
  const std::vector<int32_t>& bt = Base_.baseTriangles;
  DirectedBase_.clear();
  DirectedBase_.reserve(bt.size());
  for (int32_t g = 0; g < NFB_; ++g)
  {
    for (int k = 0; k < 3; ++k)
    {
      const int32_t a = bt[3 * g + k], b = bt[3 * g + (k + 1) % 3];
      if (a == b)
      {
        throw InputError("tracePaths: base triangle " + std::to_string(g) + " repeats a vertex");
      }
      DirectedBase_.emplace_back((static_cast<int64_t>(a) << 32) | static_cast<uint32_t>(b), g);
    }
  }
  std::sort(DirectedBase_.begin(), DirectedBase_.end());
  for (size_t i = 0; i < DirectedBase_.size(); ++i)
  {
    const int64_t key = DirectedBase_[i].first;
    const int32_t a = static_cast<int32_t>(key >> 32), b = static_cast<int32_t>(key & 0xffffffff);
    if ((i > 0 && DirectedBase_[i - 1].first == key) || this->faceOf(b, a) < 0)
    {
      throw InputError(
        "tracePaths: the base complex is not a closed oriented manifold (base edge " +
        std::to_string(Base_.baseVertices[a]) + "-" + std::to_string(Base_.baseVertices[b]) +
        "); rebuild it with buildBaseComplex");
    }
  }

  // Base edges, lower index first, in lexicographic order; the base edge of every face side.
  Result_.baseEdges.clear();
  for (const auto& kv : DirectedBase_)
  {
    const int32_t a = static_cast<int32_t>(kv.first >> 32);
    const int32_t b = static_cast<int32_t>(kv.first & 0xffffffff);
    if (a < b)
    {
      Result_.baseEdges.push_back(a);
      Result_.baseEdges.push_back(b);
    }
  }
  Result_.faceEdges.resize(bt.size());
  for (size_t c = 0; c < bt.size(); ++c)
  {
    Result_.faceEdges[c] = this->edgeIndex(bt[c], bt[c - c % 3 + (c % 3 + 1) % 3]);
  }

  // Rings and star charts: the z^a map of MAPS (3D angles at s scaled to sum to 2 pi, radii to
  // the power a) or, where one angle would exceed pi, the ring on the unit circle at equal
  // angles; the same charts as the bijection check of buildBaseComplex. Linear on every base
  // face, so a point's chart position is the barycentric combination of its corners'.
  std::vector<int32_t> facesAt(NB_, 0);
  for (int32_t x : bt)
  {
    ++facesAt[x];
  }
  Stars_.assign(NB_, StarChart());
  std::vector<double> theta, radius; // scratch of flattenStar
  for (int32_t s = 0; s < NB_; ++s)
  {
    StarChart& star = Stars_[s];
    const auto it = std::lower_bound(DirectedBase_.begin(), DirectedBase_.end(),
      std::make_pair(static_cast<int64_t>(s) << 32, std::numeric_limits<int32_t>::min()));
    if (it == DirectedBase_.end() || (it->first >> 32) != s)
    {
      throw InputError("tracePaths: base vertex " + std::to_string(Base_.baseVertices[s]) +
        " is in no base triangle; rebuild the base complex");
    }
    const int32_t first = static_cast<int32_t>(it->first & 0xffffffff);
    int32_t r = first;
    do
    {
      const int32_t f = this->faceOf(s, r);
      star.ring.push_back(r);
      star.sector.push_back(f);
      int32_t next = -1;
      for (int m = 0; m < 3; ++m)
      {
        next = bt[3 * f + m] == r ? bt[3 * f + (m + 1) % 3] : next;
      }
      r = next;
    } while (r != first && static_cast<int32_t>(star.ring.size()) <= facesAt[s]);
    if (static_cast<int32_t>(star.ring.size()) != facesAt[s] || facesAt[s] < 3)
    {
      throw InputError("tracePaths: the base triangles around base vertex " +
        std::to_string(Base_.baseVertices[s]) +
        " do not form one fan of at least 3; rebuild the base complex");
    }
    const size_t n = star.ring.size();
    detail::flattenStar(this->pos(Base_.baseVertices[s]), n,
      [&](size_t i) { return this->pos(Base_.baseVertices[star.ring[i]]); }, theta, radius,
      star.z);
    // The faces across the link, each similar to its 3D triangle, outside the link edge.
    for (size_t i = 0; i < n; ++i)
    {
      const int32_t a = star.ring[(i + 1) % n], b = star.ring[i];
      const int32_t g = this->faceOf(a, b);
      int32_t w = -1;
      for (int m = 0; m < 3; ++m)
      {
        w = bt[3 * g + m] != a && bt[3 * g + m] != b ? bt[3 * g + m] : w;
      }
      const V3 pa = this->pos(Base_.baseVertices[a]);
      const V3 ab = sub(this->pos(Base_.baseVertices[b]), pa);
      const V3 aw = sub(this->pos(Base_.baseVertices[w]), pa);
      const double len2 = dot(ab, ab);
      const double along = dot(aw, ab) / len2, up = norm(cross(ab, aw)) / len2;
      const P2 za = star.z[(i + 1) % n], zb = star.z[i];
      const P2 e{ zb.x - za.x, zb.y - za.y };
      star.outer.push_back(w == s ? -1 : g);
      star.outerApex.push_back(w);
      star.apexAt.push_back({ za.x + along * e.x - up * e.y, za.y + along * e.y + up * e.x });
    }
  }
  StarsReady_ = true;
}

std::string Tracer::edgeName(int32_t e) const
{
  return std::to_string(e) + " (points " +
    std::to_string(Base_.baseVertices[Result_.baseEdges[2 * e]]) + " and " +
    std::to_string(Base_.baseVertices[Result_.baseEdges[2 * e + 1]]) + ")";
}

std::string Tracer::pointName(int32_t p) const
{
  if (p < NV_)
  {
    return "point " + std::to_string(p);
  }
  const int64_t s = p - NV_;
  return "the Steiner point on input edge " + std::to_string(Result_.steinerEdge[2 * s]) + "-" +
    std::to_string(Result_.steinerEdge[2 * s + 1]);
}

Support Tracer::image(int32_t w, bool snap) const
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

/// Forbids the snaps that would flatten or flip an input triangle. For a triangle whose corners'
/// exact images lie in one base face g with positive area, the snapped images must keep a
/// positive area in g; where they do not, its snapped corners keep their exact images. A
/// removed snap can turn another triangle (one corner still snapped) over, so the check runs
/// until nothing changes; snaps are only ever removed, so that ends.
void Tracer::keepOffEdges()
{
  std::vector<uint8_t> snapped(NV_, 0);
  tc::parallel_for(NV_,
    [&](int64_t i)
    {
      const int32_t v = static_cast<int32_t>(i);
      snapped[v] = BaseIndex_[v] < 0 && this->image(v, true).n < this->image(v, false).n ? 1 : 0;
    });
  // The signed area in base face g of the images of the corners of f (0 when g misses one).
  auto area = [&](int32_t g, const Support* s)
  {
    double l[3][3];
    for (int i = 0; i < 3; ++i)
    {
      if (!this->faceHolds(g, s[i]))
      {
        return 0.0;
      }
      for (int k = 0; k < 3; ++k)
      {
        l[i][k] = s[i].weight(Base_.baseTriangles[3 * g + k]);
      }
    }
    return l[0][0] * (l[1][1] * l[2][2] - l[1][2] * l[2][1]) -
      l[0][1] * (l[1][0] * l[2][2] - l[1][2] * l[2][0]) +
      l[0][2] * (l[1][0] * l[2][1] - l[1][1] * l[2][0]);
  };
  std::vector<int32_t> candidates;
  for (int32_t f = 0; f < NF_; ++f)
  {
    const int32_t* c = &Mesh_.triangles[3 * static_cast<size_t>(f)];
    if (snapped[c[0]] || snapped[c[1]] || snapped[c[2]])
    {
      candidates.push_back(f);
    }
  }
  for (bool changed = true; changed;)
  {
    changed = false;
    for (int32_t f : candidates)
    {
      const int32_t* c = &Mesh_.triangles[3 * static_cast<size_t>(f)];
      Support exact[3], now[3];
      for (int i = 0; i < 3; ++i)
      {
        exact[i] = this->image(c[i], false);
        now[i] = this->support(c[i]);
      }
      for (int i = 0; i < 3; ++i)
      {
        const int32_t g = Base_.vertexBaseFace[c[i]];
        if (area(g, exact) > 0.0 && !(area(g, now) > 0.0))
        {
          for (int j = 0; j < 3; ++j)
          {
            changed |= snapped[c[j]] && !NoSnap_[c[j]];
            NoSnap_[c[j]] |= snapped[c[j]];
          }
          break;
        }
      }
    }
  }
}

/// Routes that need no chart: both images in one base face, or on one base edge. False if not.
bool Tracer::direct(const Support& su, const Support& sv, Route& r) const
{
  r.kind = Route::kNoChart;
  r.n = 0;
  r.first = r.last = r.along = -1;
  int32_t all[6];
  int na = 0;
  for (const Support* s : { &su, &sv })
  {
    for (int i = 0; i < s->n; ++i)
    {
      if (std::find(all, all + na, s->v[i]) == all + na)
      {
        all[na++] = s->v[i];
      }
    }
  }
  // Both images on one base edge: the input edge lies on it. The face on its left is fA when
  // it runs from the edge's lower base vertex a towards b, fB when back.
  if (na == 2 && this->faceOf(all[0], all[1]) >= 0)
  {
    const int32_t e = this->edgeIndex(all[0], all[1]);
    const int32_t a = Result_.baseEdges[2 * e], b = Result_.baseEdges[2 * e + 1];
    const double pu = su.weight(b), pv = sv.weight(b);
    if (pu != pv)
    {
      r.kind = Route::kAlong;
      r.along = e;
      r.first = r.last = pv > pu ? this->faceOf(a, b) : this->faceOf(b, a);
    }
    return true; // kNoChart if both are the same point of the edge
  }
  if (na == 3)
  {
    for (const int32_t g : { this->faceOf(all[0], all[1]), this->faceOf(all[1], all[0]) })
    {
      if (g >= 0 && this->faceHas(g, all[2]))
      {
        r.kind = Route::kInFace;
        r.first = r.last = g;
        return true;
      }
    }
  }
  return false;
}

/// Route of the input edge of half-edge h from its lower vertex id u to the higher v (see the
/// top of the file), in the choice-th chart that holds it (0: the first; kNoChart when there are
/// not that many). Charts in order: the star of a base vertex that is the third corner of a
/// triangle of the edge (the triangle's corner and its opposite side then turn round that vertex
/// in the same chart); the two faces about a base edge; the star of a base vertex near an end;
/// the other stars, lowest vertex first; those stars again with the faces outside them.
void Tracer::route(int32_t h, int choice, Route& r) const
{
  const int32_t u = std::min(this->from(h), this->to(h)), v = std::max(this->from(h), this->to(h));
  const Support su = this->support(u), sv = this->support(v);
  if (this->direct(su, sv, r))
  {
    r.kind = choice == 0 ? r.kind : Route::kNoChart; // the only way
    return;
  }
  // Stars that decide on which side the segment passes a base vertex it comes close to: those
  // of a base vertex at the third corner of a triangle of the edge (tried first), then those of
  // a base vertex with weight 1/2 or more at either end, heaviest first (tried after the hinge
  // charts below).
  int32_t first[8];
  int nfirst = 0;
  for (const int32_t s : { BaseIndex_[this->to(nextHe(h))], BaseIndex_[this->to(nextHe(Opp_[h]))] })
  {
    if (s >= 0 && std::find(first, first + nfirst, s) == first + nfirst)
    {
      first[nfirst++] = s;
    }
  }
  std::sort(first, first + nfirst);
  const int napex = nfirst;
  for (const Support* sp : { &su, &sv })
  {
    for (int i = 0; i < sp->n; ++i)
    {
      if (sp->w[i] >= 0.5 && std::find(first, first + nfirst, sp->v[i]) == first + nfirst)
      {
        first[nfirst++] = sp->v[i];
      }
    }
  }
  std::sort(first + napex, first + nfirst,
    [&](int32_t a, int32_t b)
    {
      const double wa = std::max(su.weight(a), sv.weight(a));
      const double wb = std::max(su.weight(b), sv.weight(b));
      return wa > wb || (wa == wb && a < b);
    });
  for (int i = 0; i < napex; ++i)
  {
    for (int outside = 0; outside < 2; ++outside)
    {
      if (this->starRoute(su, sv, first[i], outside == 1, r) && choice-- == 0)
      {
        return;
      }
    }
  }
  // Two faces unfolded about their common edge.
  int32_t faces[64];
  int nf = 0;
  if (su.n == 3)
  {
    faces[nf++] = Base_.vertexBaseFace[u];
  }
  else if (su.n == 2)
  {
    faces[nf++] = this->faceOf(su.v[0], su.v[1]);
    faces[nf++] = this->faceOf(su.v[1], su.v[0]);
  }
  else
  {
    for (int32_t g : Stars_[su.v[0]].sector)
    {
      if (nf < 64)
      {
        faces[nf++] = g;
      }
    }
  }
  for (int i = 0; i < nf; ++i)
  {
    for (int k = 0; k < 3; ++k)
    {
      if (this->hingeRoute(su, sv, faces[i], k, r) && choice-- == 0)
      {
        return;
      }
    }
  }
  // Stars of a base vertex near an end only when no two faces about a base edge hold both ends.
  // A triangle whose corners lie in two such faces is checked in their unfolding by
  // buildBaseComplex (triangleValid), so its sides must be drawn there too. The z^a star of a
  // base vertex with a narrow cone is far from that unfolding (armadillo, no features: a
  // valence-3 base vertex whose ring is stretched 1000:1), and a side drawn straight in it
  // passed the vertex through its third face instead of crossing the edge next to it; the
  // triangle then looked as if it held the vertex and could not be cut.
  for (int i = napex; i < nfirst; ++i)
  {
    for (int outside = 0; outside < 2; ++outside)
    {
      if (this->starRoute(su, sv, first[i], outside == 1, r) && choice-- == 0)
      {
        return;
      }
    }
  }
  // The other stars: one of the images' base vertices or a neighbour of u's.
  int32_t centres[128];
  int nc = 0;
  for (const Support* sp : { &su, &sv })
  {
    for (int i = 0; i < sp->n; ++i)
    {
      centres[nc++] = sp->v[i];
    }
  }
  for (int i = 0; i < su.n; ++i)
  {
    for (int32_t x : Stars_[su.v[i]].ring)
    {
      if (nc < 128)
      {
        centres[nc++] = x;
      }
    }
  }
  std::sort(centres, centres + nc);
  nc = static_cast<int>(std::unique(centres, centres + nc) - centres);
  for (int outside = 0; outside < 2; ++outside)
  {
    for (int i = 0; i < nc; ++i)
    {
      if (std::find(first, first + nfirst, centres[i]) == first + nfirst &&
        this->starRoute(su, sv, centres[i], outside == 1, r) && choice-- == 0)
      {
        return;
      }
    }
  }
  r.kind = Route::kNoChart;
  r.n = 0;
}

/// Route through base face f (holding u) and the face across its side k (holding v), unfolded
/// into the plane (Feng et al. Fig. 9): one crossing, if the segment meets that side.
bool Tracer::hingeRoute(const Support& su, const Support& sv, int32_t f, int k, Route& r) const
{
  const std::vector<int32_t>& bt = Base_.baseTriangles;
  const int32_t x = bt[3 * f + k], y = bt[3 * f + (k + 1) % 3], c = bt[3 * f + (k + 2) % 3];
  const int32_t g = this->faceOf(y, x);
  if (!this->faceHolds(g, sv))
  {
    return false;
  }
  int32_t d = -1;
  for (int m = 0; m < 3; ++m)
  {
    d = bt[3 * g + m] != x && bt[3 * g + m] != y ? bt[3 * g + m] : d;
  }
  // x at 0, y at (L, 0), c above, d below, with the 3D side lengths.
  const V3 px = this->pos(Base_.baseVertices[x]), py = this->pos(Base_.baseVertices[y]);
  const double L = norm(sub(py, px));
  auto apex = [&](int32_t w, double sign)
  {
    const V3 pw = this->pos(Base_.baseVertices[w]);
    const double ax = norm(sub(pw, px)), bx = norm(sub(pw, py));
    const double along = (ax * ax - bx * bx + L * L) / (2 * L);
    return P2{ along, sign * std::sqrt(std::max(0.0, ax * ax - along * along)) };
  };
  const P2 pc = apex(c, 1.0), pd = apex(d, -1.0);
  auto place = [&](const Support& s)
  {
    P2 p{ 0, 0 };
    for (int i = 0; i < s.n; ++i)
    {
      const P2 at = s.v[i] == x ? P2{ 0, 0 } : (s.v[i] == y ? P2{ L, 0 } : (s.v[i] == c ? pc : pd));
      p.x += s.w[i] * at.x;
      p.y += s.w[i] * at.y;
    }
    return p;
  };
  const P2 p = place(su), q = place(sv);
  if (!(p.y > 0 && q.y < 0 && L > 0))
  {
    return false;
  }
  const double t = p.y / (p.y - q.y);
  const double at = p.x + t * (q.x - p.x);
  if (!(at > 0 && at < L && t > 0 && t < 1))
  {
    return false;
  }
  r.kind = Route::kCrossing;
  r.n = 1;
  r.c[0] = { t, this->edgeIndex(x, y), f, g };
  r.first = f;
  r.last = g;
  return true;
}

/// Route through the star of base vertex s flattened by z^a, with the faces across its link
/// unfolded onto it ("placed faces": sector j is (s, ring[j], ring[j + 1]), outer j the face
/// across link edge j). Without `outside`, both ends in the star; with it, at least one outside
/// (tried only when no star holds both ends: the faces outside are unfolded one by one and may
/// overlap, so they are the weaker chart). The segment between the images is followed from placed
/// face to placed face across their common sides; it must not pass through a base vertex nor leave
/// the chart.
bool Tracer::starRoute(
  const Support& su, const Support& sv, int32_t s, bool outside, Route& r) const
{
  const StarChart& st = Stars_[s];
  const int d = static_cast<int>(st.ring.size());
  // Corners and positions of placed face k (0 .. d-1 sectors, d .. 2d-1 outer faces).
  auto corners = [&](int k, int32_t c[3], P2 at[3])
  {
    if (k < d)
    {
      c[0] = s;
      c[1] = st.ring[k];
      c[2] = st.ring[(k + 1) % d];
      at[0] = { 0, 0 };
      at[1] = st.z[k];
      at[2] = st.z[(k + 1) % d];
      return st.sector[k];
    }
    const int j = k - d;
    c[0] = st.ring[(j + 1) % d];
    c[1] = st.ring[j];
    c[2] = st.outerApex[j];
    at[0] = st.z[(j + 1) % d];
    at[1] = st.z[j];
    at[2] = st.apexAt[j];
    return st.outer[j];
  };
  // The placed face across the side opposite corner m of placed face k (-1: outside the chart).
  auto across = [&](int k, int m)
  {
    if (k < d)
    {
      return m == 0 ? (st.outer[k] >= 0 ? d + k : -1) : (m == 1 ? (k + 1) % d : (k - 1 + d) % d);
    }
    return m == 2 ? k - d : -1;
  };
  auto holds = [&](int k, const Support& sp, double b[3], P2& at)
  {
    int32_t c[3];
    P2 pos[3];
    if (corners(k, c, pos) < 0)
    {
      return false;
    }
    b[0] = b[1] = b[2] = 0.0;
    at = { 0, 0 };
    for (int i = 0; i < sp.n; ++i)
    {
      const int m = sp.v[i] == c[0] ? 0 : (sp.v[i] == c[1] ? 1 : (sp.v[i] == c[2] ? 2 : -1));
      if (m < 0)
      {
        return false;
      }
      b[m] = sp.w[i];
      at.x += sp.w[i] * pos[m].x;
      at.y += sp.w[i] * pos[m].y;
    }
    return true;
  };
  auto barycentric = [](const P2& p, const P2 at[3], double b[3])
  {
    const double area =
      (at[1].x - at[0].x) * (at[2].y - at[0].y) - (at[1].y - at[0].y) * (at[2].x - at[0].x);
    for (int m = 0; m < 3; ++m)
    {
      const P2& a = at[(m + 1) % 3];
      const P2& c = at[(m + 2) % 3];
      b[m] = ((c.x - a.x) * (p.y - a.y) - (c.y - a.y) * (p.x - a.x)) / area;
    }
    return area > 0;
  };
  // The placed faces that hold each end (a few: more than one only on a side or a corner).
  int starts[16], ends[16], ns = 0, nd = 0;
  for (int k = 0; k < 2 * d; ++k)
  {
    double b[3];
    P2 at;
    if (ns < 16 && holds(k, su, b, at))
    {
      starts[ns++] = k;
    }
    if (nd < 16 && holds(k, sv, b, at))
    {
      ends[nd++] = k;
    }
  }
  // Ends in the star, or (outside) at least one end in a face outside it.
  for (int pair = 0; pair < ns * nd; ++pair)
  {
    const int start = starts[pair / nd], end = ends[pair % nd];
    double bs[3], be[3];
    P2 p, q;
    if ((start >= d || end >= d) != outside || end == start)
    {
      continue;
    }
    holds(start, su, bs, p);
    holds(end, sv, be, q);
    // Does the segment enter the start face? (exact zeros of the image's barycentrics)
    int32_t c[3];
    P2 at[3];
    corners(start, c, at);
    double bq[3];
    if (!barycentric(q, at, bq))
    {
      continue;
    }
    bool enters = true;
    for (int m = 0; m < 3; ++m)
    {
      enters &= bs[m] > 0 || bq[m] - bs[m] > 0;
    }
    if (!enters)
    {
      continue;
    }
    // Walk.
    int k = start, n = 0, entry = -1;
    double t = 0.0;
    bool ok = false;
    r.first = corners(start, c, at);
    for (int steps = 0; steps <= 2 * d && n < kMaxCrossings; ++steps)
    {
      const int32_t face = corners(k, c, at);
      // Done in the first placed face that holds the end at the same position.
      double bk[3];
      P2 qk;
      if (k == end || (holds(k, sv, bk, qk) && qk.x == q.x && qk.y == q.y))
      {
        ok = true;
        break;
      }
      double bp[3];
      if (!barycentric(p, at, bp) || !barycentric(q, at, bq))
      {
        break;
      }
      int exit = -1;
      double tExit = std::numeric_limits<double>::infinity();
      for (int m = 0; m < 3; ++m)
      {
        const double slope = bq[m] - bp[m];
        if (m == entry || !(slope < 0))
        {
          continue;
        }
        const double tm = bp[m] / (bp[m] - bq[m]);
        if (tm < tExit)
        {
          tExit = tm;
          exit = m;
        }
      }
      const int next = exit >= 0 ? across(k, exit) : -1;
      if (next < 0 || !(tExit > t && tExit < 1))
      {
        break;
      }
      // Through a side, not a corner.
      const double b1 = bp[(exit + 1) % 3] + tExit * (bq[(exit + 1) % 3] - bp[(exit + 1) % 3]);
      const double b2 = bp[(exit + 2) % 3] + tExit * (bq[(exit + 2) % 3] - bp[(exit + 2) % 3]);
      int32_t nc[3];
      P2 nat[3];
      const int32_t nextFace = corners(next, nc, nat);
      if (!(b1 > 0 && b2 > 0) || nextFace < 0)
      {
        break;
      }
      r.c[n++] = { tExit, this->edgeIndex(c[(exit + 1) % 3], c[(exit + 2) % 3]), face, nextFace };
      t = tExit;
      // The side we came in by, as a corner index of the next face.
      entry = -1;
      for (int m = 0; m < 3; ++m)
      {
        entry = nc[m] != c[(exit + 1) % 3] && nc[m] != c[(exit + 2) % 3] ? m : entry;
      }
      k = next;
    }
    if (ok && n > 0)
    {
      r.kind = Route::kCrossing;
      r.n = n;
      r.last = r.c[n - 1].to;
      return true;
    }
  }
  r.n = 0;
  return false;
}

/// Route of half-edge h, from its start to its end, in the chart chosen for its edge.
void Tracer::routeOf(int32_t h, Route& r) const
{
  this->route(h, Choice_[std::min(h, Opp_[h])], r);
  if (this->from(h) < this->to(h))
  {
    return;
  }
  if (r.kind == Route::kAlong)
  {
    const int32_t a = Result_.baseEdges[2 * r.along], b = Result_.baseEdges[2 * r.along + 1];
    const int32_t fA = this->faceOf(a, b);
    r.first = r.last = r.first == fA ? this->faceOf(b, a) : fA;
    return;
  }
  r.reverse();
}

/// The one base face that holds the images of the three corners of input triangle f, -1 if none
/// does, -2 if two do (all three images on one base edge).
int32_t Tracer::commonFace(int32_t f) const
{
  Support s[3];
  int best = 0;
  for (int i = 0; i < 3; ++i)
  {
    s[i] = this->support(Mesh_.triangles[3 * f + i]);
    best = s[i].n > s[best].n ? i : best;
  }
  int32_t candidates[2] = { -1, -1 };
  if (s[best].n == 3)
  {
    candidates[0] = Base_.vertexBaseFace[Mesh_.triangles[3 * f + best]];
  }
  else if (s[best].n == 2)
  {
    candidates[0] = this->faceOf(s[best].v[0], s[best].v[1]);
    candidates[1] = this->faceOf(s[best].v[1], s[best].v[0]);
  }
  else
  {
    candidates[0] = this->faceOf(s[0].v[0], s[1].v[0]);
    candidates[1] = this->faceOf(s[1].v[0], s[0].v[0]);
  }
  int32_t found = -1;
  int count = 0;
  for (int32_t g : candidates)
  {
    if (g >= 0 && this->faceHolds(g, s[0]) && this->faceHolds(g, s[1]) && this->faceHolds(g, s[2]))
    {
      found = g;
      ++count;
    }
  }
  return count == 2 ? -2 : found;
}

/// A Steiner point before the points are numbered: the k-th crossing (from the lower vertex id
/// to the higher) of the input edge whose lower half-edge is `key`.
inline int64_t provisional(int32_t key, int k)
{
  return -1 - (static_cast<int64_t>(key) * kMaxCrossings + k);
}

/// Cuts input triangle f along the base edges that cross it (step 2 at the top of the file).
void Tracer::split(int32_t f, Pieces& out) const
{
  out = Pieces();
  Route routes[3];
  for (int i = 0; i < 3; ++i)
  {
    this->routeOf(3 * f + i, routes[i]);
    if (routes[i].kind == Route::kNoChart)
    {
      out.error = "no chart holds its side " + std::to_string(this->from(3 * f + i)) + "-" +
        std::to_string(this->to(3 * f + i));
      return;
    }
  }
  // The boundary, counter-clockwise: corners and Steiner points (with their positions), the
  // base face of the arc after each, and the transitions between base faces.
  std::vector<int64_t> cycle;
  std::vector<V3> at;
  std::vector<int32_t> arc;
  std::vector<Transition> word;
  for (int i = 0; i < 3; ++i)
  {
    const int32_t c = Mesh_.triangles[3 * f + i];
    const int32_t in = routes[(i + 2) % 3].last, outFace = routes[i].first;
    const Support s = this->support(c);
    if (s.n == 3)
    {
      if (in != Base_.vertexBaseFace[c] || outFace != in)
      {
        out.error = "its sides leave point " + std::to_string(c) + " in other base faces";
        return;
      }
    }
    else if (s.n == 2)
    {
      const int32_t g1 = this->faceOf(s.v[0], s.v[1]), g2 = this->faceOf(s.v[1], s.v[0]);
      if ((in != g1 && in != g2) || (outFace != g1 && outFace != g2))
      {
        out.error = "its sides leave point " + std::to_string(c) + " in other base faces";
        return;
      }
      if (in != outFace)
      {
        word.push_back({ c, this->edgeIndex(s.v[0], s.v[1]), in, outFace });
      }
    }
    else
    {
      // At a base vertex the corner spans the sectors from `in` clockwise to `out`: walking
      // round the boundary, the corner is passed from the incoming side to the outgoing one.
      const StarChart& st = Stars_[s.v[0]];
      const int d = static_cast<int>(st.ring.size());
      const int jin =
        static_cast<int>(std::find(st.sector.begin(), st.sector.end(), in) - st.sector.begin());
      const int jout = static_cast<int>(
        std::find(st.sector.begin(), st.sector.end(), outFace) - st.sector.begin());
      if (jin == d || jout == d)
      {
        out.error = "its sides leave base vertex " + std::to_string(c) + " through other faces";
        return;
      }
      for (int j = jin; j != jout; j = (j - 1 + d) % d)
      {
        word.push_back(
          { c, this->edgeIndex(s.v[0], st.ring[j]), st.sector[j], st.sector[(j - 1 + d) % d] });
      }
    }
    cycle.push_back(c);
    at.push_back(this->pos(c));
    arc.push_back(outFace);
    const Route& r = routes[i];
    const int32_t h = 3 * f + i;
    const int32_t key = std::min(h, Opp_[h]);
    const int32_t lo = std::min(this->from(h), this->to(h)),
                  hi = std::max(this->from(h), this->to(h));
    const bool forward = this->from(h) == lo;
    const V3 plo = this->pos(lo), phi = this->pos(hi);
    for (int k = 0; k < r.n; ++k)
    {
      const int kc = forward ? k : r.n - 1 - k;
      const double t = forward ? r.c[k].t : 1.0 - r.c[k].t;
      if (r.c[k].from != arc.back())
      {
        out.error = "its side " + std::to_string(this->from(h)) + "-" +
          std::to_string(this->to(h)) + " is not one route";
        return;
      }
      if (h == key)
      {
        out.cuts.emplace_back(key, t);
      }
      cycle.push_back(provisional(key, kc));
      // The same expression as the output points, so both triangles of the edge agree.
      at.push_back(
        { plo.x + t * (phi.x - plo.x), plo.y + t * (phi.y - plo.y), plo.z + t * (phi.z - plo.z) });
      arc.push_back(r.c[k].to);
      word.push_back({ provisional(key, kc), r.c[k].edge, r.c[k].from, r.c[k].to });
    }
  }
  // The cuts of an owned side are kept from the lower vertex to the higher.
  for (int i = 0; i < 3; ++i)
  {
    const int32_t h = 3 * f + i;
    if (h < Opp_[h] && this->from(h) > this->to(h))
    {
      auto first = std::find_if(out.cuts.begin(), out.cuts.end(),
        [&](const std::pair<int32_t, double>& c) { return c.first == h; });
      std::reverse(first,
        std::find_if(first, out.cuts.end(),
          [&](const std::pair<int32_t, double>& c) { return c.first != h; }));
    }
  }

  // Pair each transition with the one that undoes it (same base edge, faces swapped), like
  // brackets; the word of a disk without a base vertex inside reduces to nothing.
  auto undoes = [](const Transition& a, const Transition& b)
  { return a.edge == b.edge && a.from == b.to && a.to == b.from && a.point != b.point; };
  std::vector<int> stack;
  std::vector<std::pair<int, int>> pairs;
  for (int j = 0; j < static_cast<int>(word.size()); ++j)
  {
    if (!stack.empty() && undoes(word[stack.back()], word[j]))
    {
      pairs.emplace_back(stack.back(), j);
      stack.pop_back();
    }
    else
    {
      stack.push_back(j);
    }
  }
  size_t lo = 0, hi = stack.size();
  while (hi - lo >= 2 && undoes(word[stack[hi - 1]], word[stack[lo]]))
  {
    pairs.emplace_back(stack[hi - 1], stack[lo]);
    ++lo;
    --hi;
  }
  if (lo != hi)
  {
    out.error = "base edge " + this->edgeName(word[stack[lo]].edge) +
      " enters it and does not leave it (it would hold a base vertex)";
    return;
  }

  // Cut along the chords. A chord from transition P (X -> Y) to Q (Y -> X) has face Y on the
  // side of the boundary from P counter-clockwise to Q, and X on the other side. Polygons hold
  // indices into `cycle`.
  struct Chord
  {
    size_t p, q;
    int32_t left, right; ///< left: face of the piece holding directed p -> q
  };
  std::vector<Chord> chords;
  const size_t m = cycle.size();
  auto indexOf = [&](int64_t point)
  { return static_cast<size_t>(std::find(cycle.begin(), cycle.end(), point) - cycle.begin()); };
  std::vector<std::vector<size_t>> polys(1);
  for (size_t k = 0; k < m; ++k)
  {
    polys[0].push_back(k);
  }
  for (const auto& pq : pairs)
  {
    const Transition& P = word[pq.first];
    const Transition& Q = word[pq.second];
    const size_t ip = indexOf(P.point), iq = indexOf(Q.point);
    chords.push_back({ ip, iq, P.from, P.to });
    out.links.push_back({ P.edge, P.point, Q.point });
    bool done = false;
    for (size_t k = 0; k < polys.size() && !done; ++k)
    {
      std::vector<size_t>& poly = polys[k];
      const auto ia = std::find(poly.begin(), poly.end(), ip);
      const auto ib = std::find(poly.begin(), poly.end(), iq);
      if (ia == poly.end() || ib == poly.end())
      {
        continue;
      }
      const size_t n = poly.size();
      const size_t i = static_cast<size_t>(ia - poly.begin());
      const size_t j = static_cast<size_t>(ib - poly.begin());
      if ((i + 1) % n == j || (j + 1) % n == i)
      {
        out.error = "a path would run along its side";
        return;
      }
      std::vector<size_t> first, second;
      for (size_t x = i;; x = (x + 1) % n)
      {
        first.push_back(poly[x]);
        if (x == j)
        {
          break;
        }
      }
      for (size_t x = j;; x = (x + 1) % n)
      {
        second.push_back(poly[x]);
        if (x == i)
        {
          break;
        }
      }
      poly = std::move(first);
      polys.push_back(std::move(second));
      done = true;
    }
    if (!done)
    {
      out.error = "two paths cross inside it";
      return;
    }
  }

  for (const std::vector<size_t>& poly : polys)
  {
    // The base face of the piece, from every boundary arc and chord side around it.
    int32_t label = -1;
    const size_t n = poly.size();
    for (size_t k = 0; k < n; ++k)
    {
      const size_t x = poly[k], y = poly[(k + 1) % n];
      int32_t l = (x + 1) % m == y ? arc[x] : -1;
      for (const Chord& c : chords)
      {
        l = c.p == x && c.q == y ? c.left : (c.p == y && c.q == x ? c.right : l);
      }
      if (l < 0 || (label >= 0 && l != label))
      {
        out.error = "a piece of it lies in two base faces";
        return;
      }
      label = l;
    }
    // A convex piece: the fan whose smallest triangle is largest.
    size_t apex = 0;
    double bestMin = -1.0;
    for (size_t a = 0; a < n && n > 3; ++a)
    {
      double smallest = std::numeric_limits<double>::infinity();
      for (size_t k = 1; k + 1 < n; ++k)
      {
        const V3& pa = at[poly[a]];
        smallest = std::min(smallest,
          norm(cross(sub(at[poly[(a + k) % n]], pa), sub(at[poly[(a + k + 1) % n]], pa))));
      }
      if (smallest > bestMin)
      {
        bestMin = smallest;
        apex = a;
      }
    }
    for (size_t k = 1; k + 1 < n; ++k)
    {
      out.triangles.push_back(cycle[poly[apex]]);
      out.triangles.push_back(cycle[poly[(apex + k) % n]]);
      out.triangles.push_back(cycle[poly[(apex + k + 1) % n]]);
      out.patch.push_back(label);
    }
  }
}

/// Makes input triangle f cuttable by drawing one of its sides (not the edge `keep`, a lower
/// half-edge) in another chart, where the triangle across that side stays cuttable or, down to
/// `depth` levels, can be made so in turn. A thin triangle at a base vertex can be positive in two
/// charts that pass the vertex on opposite sides (the bijection check of buildBaseComplex draws
/// each triangle in one chart only); the first chart of a side may be the wrong one. Triangles
/// whose sides change are added to `changed`; false (charts restored) if nothing works.
bool Tracer::repair(int32_t f, int32_t keep, int depth, const std::vector<int32_t>& slot,
  std::vector<int32_t>& changed)
{
  auto cuttable = [&](int32_t t)
  {
    Pieces p;
    this->split(t, p);
    return p.error.empty();
  };
  for (int k = 0; k < 3; ++k)
  {
    const int32_t h = 3 * f + k, key = std::min(h, Opp_[h]), g = Opp_[h] / 3;
    if (key == keep || slot[g] < 0)
    {
      continue; // the other triangle is inside one base face: the side has no other chart
    }
    const uint8_t old = Choice_[key];
    for (int c = 0; c < 64; ++c)
    {
      if (c == old)
      {
        continue;
      }
      Route r;
      this->route(h, c, r);
      if (r.kind == Route::kNoChart)
      {
        break;
      }
      Choice_[key] = static_cast<uint8_t>(c);
      const size_t mark = changed.size();
      if (cuttable(f) &&
        (cuttable(g) || (depth > 1 && this->repair(g, key, depth - 1, slot, changed))))
      {
        changed.push_back(f);
        changed.push_back(g);
        return true;
      }
      changed.resize(mark);
    }
    Choice_[key] = old;
  }
  return false;
}

PatchMesh Tracer::run(const Progress& progress)
{
  this->validate(progress.sub(0.0, 0.05));
  this->buildTopology(progress.sub(0.05, 0.2));
  this->buildBase();
  PatchMesh& out = Result_;
  const int32_t ne = static_cast<int32_t>(out.baseEdges.size() / 2);
  const int32_t nh = 3 * NF_;
  if (static_cast<int64_t>(nh) * kMaxCrossings >= std::numeric_limits<int64_t>::max() / 2)
  {
    throw InputError("tracePaths: the mesh is too large");
  }
  const std::string rebuild =
    "; the parameterization is not one-to-one there: rebuild the base complex with "
    "checkBijection on, or with a coarser target (fewer base faces); a scan's slivers (near-flat "
    "triangles) cause this: remove them in the preparation (RemoveSlivers, --remove-slivers)";

  // 1. The input edges that lie on a base edge, and the triangles inside one base face, which
  // keep it; the others are cut.
  Choice_.assign(nh, 0);
  std::vector<int32_t> alongEdge(nh, -1);
  tc::parallel_for(
    nh,
    [&](int64_t i)
    {
      const int32_t h = static_cast<int32_t>(i);
      Route r;
      if (h < Opp_[h] &&
        this->direct(this->support(this->from(h)), this->support(this->to(h)), r) &&
        r.kind == Route::kAlong)
      {
        alongEdge[h] = r.along;
      }
    },
    progress.sub(0.2, 0.3));
  std::vector<int32_t> label(NF_, -1);
  tc::parallel_for(
    NF_,
    [&](int64_t i)
    {
      const int32_t f = static_cast<int32_t>(i);
      const int32_t g = this->commonFace(f);
      bool along = false;
      for (int k = 0; k < 3; ++k)
      {
        along |= alongEdge[std::min(3 * f + k, Opp_[3 * f + k])] >= 0;
      }
      label[f] = g >= 0 && !along ? g : -1;
    },
    progress.sub(0.3, 0.4));
  std::vector<int32_t> slow, slot(NF_, -1);
  for (int32_t f = 0; f < NF_; ++f)
  {
    if (label[f] < 0)
    {
      slot[f] = static_cast<int32_t>(slow.size());
      slow.push_back(f);
    }
  }

  // 2. Cut them; repair() handles the few that cannot be cut.
  std::vector<Pieces> pieces(slow.size());
  tc::parallel_for(
    static_cast<int64_t>(slow.size()), [&](int64_t i) { this->split(slow[i], pieces[i]); },
    progress.sub(0.4, 0.7));
  std::vector<int32_t> changed;
  for (size_t i = 0; i < slow.size(); ++i)
  {
    if (!pieces[i].error.empty())
    {
      // An earlier repair may have fixed it.
      this->split(slow[i], pieces[i]);
      if (!pieces[i].error.empty())
      {
        this->repair(slow[i], -1, 3, slot, changed);
      }
    }
  }
  std::sort(changed.begin(), changed.end());
  changed.erase(std::unique(changed.begin(), changed.end()), changed.end());
  for (int32_t f : changed)
  {
    this->split(f, pieces[slot[f]]);
  }
  for (size_t i = 0; i < slow.size(); ++i)
  {
    if (!pieces[i].error.empty())
    {
      throw UntraceableError("input triangle " + std::to_string(slow[i]) +
          " cannot be cut along the base edges: " + pieces[i].error,
        rebuild);
    }
  }

  // 3. Steiner points, numbered by input edge (its lower half-edge) and along it.
  std::vector<int32_t> count(nh, 0);
  for (const Pieces& p : pieces)
  {
    for (const auto& c : p.cuts)
    {
      ++count[c.first];
    }
  }
  SteinerStart_.assign(nh, 0);
  int64_t ns = 0;
  for (int32_t h = 0; h < nh; ++h)
  {
    SteinerStart_[h] = static_cast<int32_t>(ns);
    ns += count[h];
    if (ns + NV_ >= std::numeric_limits<int32_t>::max())
    {
      throw InputError("tracePaths: too many Steiner points for 32-bit point ids");
    }
  }
  auto global = [&](int64_t p) -> int32_t
  {
    if (p >= 0)
    {
      return static_cast<int32_t>(p);
    }
    const int64_t code = -1 - p;
    return NV_ + SteinerStart_[code / kMaxCrossings] + static_cast<int32_t>(code % kMaxCrossings);
  };
  out.steinerEdge.resize(2 * ns);
  out.steinerParameter.resize(ns);
  out.mesh.points.resize(3 * (static_cast<size_t>(NV_) + ns));
  std::copy(Mesh_.points.begin(), Mesh_.points.end(), out.mesh.points.begin());
  tc::parallel_for(
    static_cast<int64_t>(slow.size()),
    [&](int64_t i)
    {
      const std::vector<std::pair<int32_t, double>>& cuts = pieces[i].cuts;
      for (size_t k = 0; k < cuts.size();)
      {
        const int32_t h = cuts[k].first;
        const int32_t u = std::min(this->from(h), this->to(h));
        const int32_t v = std::max(this->from(h), this->to(h));
        const V3 pu = this->pos(u), pv = this->pos(v);
        for (int32_t j = 0; k < cuts.size() && cuts[k].first == h; ++k, ++j)
        {
          const int64_t s = SteinerStart_[h] + j;
          const double t = cuts[k].second;
          out.steinerEdge[2 * s] = u;
          out.steinerEdge[2 * s + 1] = v;
          out.steinerParameter[s] = t;
          double* p = &out.mesh.points[3 * (NV_ + s)];
          p[0] = pu.x + t * (pv.x - pu.x);
          p[1] = pu.y + t * (pv.y - pu.y);
          p[2] = pu.z + t * (pv.z - pu.z);
        }
      }
    },
    progress.sub(0.7, 0.75));

  // 4. One path per base edge: its chords and the input edges on it, chained from end to end.
  std::vector<Link> links;
  for (const Pieces& p : pieces)
  {
    for (const Link& l : p.links)
    {
      links.push_back({ l.edge, global(l.p), global(l.q) });
    }
  }
  for (int32_t h = 0; h < nh; ++h)
  {
    if (alongEdge[h] >= 0)
    {
      links.push_back({ alongEdge[h], std::min(this->from(h), this->to(h)),
        std::max(this->from(h), this->to(h)) });
    }
  }
  std::sort(links.begin(), links.end(),
    [](const Link& a, const Link& b)
    { return a.edge < b.edge || (a.edge == b.edge && (a.p < b.p || (a.p == b.p && a.q < b.q))); });
  std::vector<int64_t> linkStart(static_cast<size_t>(ne) + 1, 0);
  for (const Link& l : links)
  {
    ++linkStart[l.edge + 1];
  }
  for (int32_t e = 0; e < ne; ++e)
  {
    linkStart[e + 1] += linkStart[e];
  }
  std::vector<std::vector<int32_t>> paths(ne);
  std::vector<std::string> pathError(ne);
  tc::parallel_for(
    ne,
    [&](int64_t ei)
    {
      const int32_t e = static_cast<int32_t>(ei);
      const Link* lb = links.data() + linkStart[e];
      const int64_t nl = linkStart[e + 1] - linkStart[e];
      // Ends of every link, sorted by point: each point of the path has 2 (its ends 1).
      std::vector<std::pair<int64_t, int64_t>> ends;
      for (int64_t k = 0; k < nl; ++k)
      {
        ends.emplace_back(lb[k].p, k);
        ends.emplace_back(lb[k].q, k);
      }
      std::sort(ends.begin(), ends.end());
      auto linksAt = [&](int64_t p)
      {
        return std::equal_range(ends.begin(), ends.end(), std::make_pair(p, int64_t(-1)),
          [](const std::pair<int64_t, int64_t>& x, const std::pair<int64_t, int64_t>& y)
          { return x.first < y.first; });
      };
      const int32_t A = Base_.baseVertices[out.baseEdges[2 * e]];
      const int32_t B = Base_.baseVertices[out.baseEdges[2 * e + 1]];
      std::vector<int32_t>& path = paths[e];
      path.push_back(A);
      int64_t cur = A, came = -1;
      for (int64_t used = 0; cur != B; ++used)
      {
        const auto range = linksAt(cur);
        const int64_t degree = range.second - range.first;
        if (degree != (cur == A ? 1 : 2) || used >= nl)
        {
          pathError[e] = degree == 0
            ? "it stops at " + this->pointName(static_cast<int32_t>(cur))
            : "it branches at " + this->pointName(static_cast<int32_t>(cur));
          return;
        }
        const int64_t k =
          range.first->second != came ? range.first->second : (range.first + 1)->second;
        cur = lb[k].p == cur ? lb[k].q : lb[k].p;
        came = k;
        path.push_back(static_cast<int32_t>(cur));
      }
      const auto range = linksAt(B);
      if (range.second - range.first != 1 || static_cast<int64_t>(path.size()) != nl + 1)
      {
        pathError[e] = "it has pieces that are not on its way from end to end";
      }
    },
    progress.sub(0.75, 0.8));
  for (int32_t e = 0; e < ne; ++e)
  {
    if (!pathError[e].empty())
    {
      throw UntraceableError(
        "the path of base edge " + this->edgeName(e) + " cannot be traced: " + pathError[e],
        rebuild);
    }
  }
  out.pathOffsets.assign(1, 0);
  out.pathPoints.clear();
  for (int32_t e = 0; e < ne; ++e)
  {
    out.pathPoints.insert(out.pathPoints.end(), paths[e].begin(), paths[e].end());
    out.pathOffsets.push_back(static_cast<int64_t>(out.pathPoints.size()));
  }

  // 5. Output triangles in input order: each input triangle, or its pieces.
  std::vector<int64_t> offset(static_cast<size_t>(NF_) + 1, 0);
  for (int32_t f = 0; f < NF_; ++f)
  {
    offset[f + 1] =
      offset[f] + (slot[f] < 0 ? 1 : static_cast<int64_t>(pieces[slot[f]].patch.size()));
  }
  const int64_t nOut = offset[NF_];
  out.mesh.triangles.resize(3 * nOut);
  out.patchId.resize(nOut);
  out.inputTriangle.resize(nOut);
  tc::parallel_for(
    NF_,
    [&](int64_t i)
    {
      const int32_t f = static_cast<int32_t>(i);
      const int64_t o = offset[f];
      if (slot[f] >= 0)
      {
        const Pieces& p = pieces[slot[f]];
        for (size_t k = 0; k < p.triangles.size(); ++k)
        {
          out.mesh.triangles[3 * o + k] = global(p.triangles[k]);
        }
        std::copy(p.patch.begin(), p.patch.end(), out.patchId.begin() + o);
        std::fill(out.inputTriangle.begin() + o,
          out.inputTriangle.begin() + o + static_cast<int64_t>(p.patch.size()), f);
        return;
      }
      std::copy(&Mesh_.triangles[3 * static_cast<size_t>(f)],
        &Mesh_.triangles[3 * static_cast<size_t>(f)] + 3, out.mesh.triangles.begin() + 3 * o);
      out.patchId[o] = label[f];
      out.inputTriangle[o] = f;
    },
    progress.sub(0.8, 1.0));
  out.inputPointId.resize(static_cast<size_t>(NV_) + ns);
  for (int32_t v = 0; v < NV_; ++v)
  {
    out.inputPointId[v] = v;
  }
  std::fill(out.inputPointId.begin() + NV_, out.inputPointId.end(), -1);
  return std::move(out);
}
} // namespace

PatchMesh tracePaths(const TriMesh& mesh, const BaseComplexResult& base, const Progress& progress)
{
  Tracer tracer(mesh, base);
  return tracer.run(progress);
}
} // namespace tc
