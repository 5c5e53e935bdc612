// SPDX-License-Identifier: BSD-3-Clause
// The input of the path tracer checked and read. The mesh: the shapes and ids of the arrays, the
// image of every input vertex in the base complex (snapped onto base edges where round-off put
// it beside one), and the twin of every half-edge. The base complex: its directed edges (checked
// to form a closed oriented manifold), its undirected base edges in the order of
// PatchMesh::baseEdges, and the star chart of every base vertex: the z^a map of MAPS (3D angles
// at the vertex scaled to sum to 2 pi, radii to the power a) or, where one angle would exceed pi,
// the ring on the unit circle at equal angles; the same charts as the bijection check of
// buildBaseComplex. A chart is linear on every base face, so a point's chart position is the
// barycentric combination of its corners'.
#include "gim/path_tracer.h"

#include "detail/star_map.h"

#include "tc/common/errors.h"
#include "tc/common/parallel.h"

#include <atomic>
#include <cmath>

namespace tc
{
namespace detail
{
namespace tracing
{
namespace
{
/// No bad item found yet.
constexpr int32_t kNone = std::numeric_limits<int32_t>::max();

/// Lowers `first` to x: the lowest bad item is the one reported, whatever the thread count.
void keepLowest(std::atomic<int32_t>& first, int32_t x)
{
  int32_t cur = first.load();
  while (x < cur && !first.compare_exchange_weak(cur, x))
  {
  }
}
} // namespace

void Tracer::validate(const Progress& progress)
{
  this->checkShapes();
  this->checkIds();
  BaseIndex_.assign(NV_, -1);
  for (int32_t i = 0; i < NB_; ++i)
  {
    BaseIndex_[Base_.baseVertices[i]] = i;
  }
  NoSnap_.assign(NV_, 0);
  this->checkImages(progress);
  this->keepOffEdges();
}

/// Array sizes; sets the counts NV_, NF_, NB_, NFB_.
void Tracer::checkShapes()
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
}

/// Every id in range; base vertices ascending.
void Tracer::checkIds() const
{
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
}

/// Every image must be a point of its base face; a vertex other than a base vertex must not
/// land on a base vertex (two input vertices at one point of the base complex cannot be cut
/// apart).
void Tracer::checkImages(const Progress& progress)
{
  std::atomic<int32_t> firstBad{ kNone };
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
        keepLowest(firstBad, v);
      }
    },
    progress);
  if (firstBad.load() != kNone)
  {
    const int32_t v = firstBad.load();
    throw InputError("tracePaths: point " + std::to_string(v) +
      " has no valid image in the base complex (base face and barycentrics summing to 1; a base "
      "vertex on its own corner, no other point on a base vertex); rebuild the base complex "
      "from this mesh");
  }
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

/// Outgoing half-edges of every vertex (CSR), then each twin is found in the list of the
/// half-edge's end: linear time, no sort, and parallel.
void Tracer::buildTopology(const Progress& progress)
{
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
  this->findTwins(offsets, outgoing, progress.sub(0.0, 0.5));
  this->checkFans(offsets, outgoing, progress.sub(0.5, 1.0));
}

/// Opp_ from the outgoing half-edges of every vertex (offsets into outgoing, CSR).
void Tracer::findTwins(const std::vector<int32_t>& offsets, const std::vector<int32_t>& outgoing,
  const Progress& progress)
{
  const int32_t nh = 3 * NF_;
  Opp_.assign(nh, -1);
  std::atomic<int32_t> firstBad{ kNone };
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
        keepLowest(firstBad, h);
      }
    },
    progress);
  if (firstBad.load() != kNone)
  {
    const int32_t h = firstBad.load();
    throw InputError("tracePaths: the mesh is not a closed oriented manifold (edge " +
      std::to_string(this->from(h)) + "-" + std::to_string(this->to(h)) +
      " has no single opposite twin); pass the mesh that buildBaseComplex was given");
  }
}

/// One fan per vertex: turning around v through the twins visits all its half-edges.
void Tracer::checkFans(const std::vector<int32_t>& offsets, const std::vector<int32_t>& outgoing,
  const Progress& progress) const
{
  std::atomic<int32_t> firstBad{ kNone };
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
        keepLowest(firstBad, start);
      }
    },
    progress);
  if (firstBad.load() != kNone)
  {
    throw InputError("tracePaths: the triangles around point " +
      std::to_string(this->from(firstBad.load())) +
      " do not form one fan (non-manifold vertex); pass the mesh that buildBaseComplex was given");
  }
}

void Tracer::buildBase()
{
  this->sortDirectedBase();
  this->listBaseEdges();
}

/// DirectedBase_: every side of every base face, sorted; each must appear once, its reverse too.
void Tracer::sortDirectedBase()
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
      DirectedBase_.emplace_back(directedKey(a, b), g);
    }
  }
  std::sort(DirectedBase_.begin(), DirectedBase_.end());
  for (size_t i = 0; i < DirectedBase_.size(); ++i)
  {
    const int64_t key = DirectedBase_[i].first;
    const int32_t a = keyFrom(key), b = keyTo(key);
    if ((i > 0 && DirectedBase_[i - 1].first == key) || this->faceOf(b, a) < 0)
    {
      throw InputError(
        "tracePaths: the base complex is not a closed oriented manifold (base edge " +
        std::to_string(Base_.baseVertices[a]) + "-" + std::to_string(Base_.baseVertices[b]) +
        "); rebuild it with buildBaseComplex");
    }
  }
}

/// Base edges, lower index first, in lexicographic order; the base edge of every face side.
void Tracer::listBaseEdges()
{
  const std::vector<int32_t>& bt = Base_.baseTriangles;
  Result_.baseEdges.clear();
  for (const auto& kv : DirectedBase_)
  {
    const int32_t a = keyFrom(kv.first);
    const int32_t b = keyTo(kv.first);
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
}

/// Stars_: the ring and star chart of every base vertex, with the faces across its link.
void Tracer::buildStars()
{
  std::vector<int32_t> facesAt(NB_, 0);
  for (int32_t x : Base_.baseTriangles)
  {
    ++facesAt[x];
  }
  Stars_.assign(NB_, StarChart());
  std::vector<double> theta, radius; // scratch of flattenStar
  for (int32_t s = 0; s < NB_; ++s)
  {
    StarChart& star = Stars_[s];
    this->walkRing(s, facesAt[s], star);
    detail::flattenStar(
      this->basePos(s), star.ring.size(), [&](size_t i) { return this->basePos(star.ring[i]); },
      theta, radius, star.z);
    this->unfoldOuterFaces(s, star);
  }
  StarsReady_ = true;
}

/// The ring of base vertex s (counter-clockwise, from its lowest neighbour) and the base face of
/// each sector; it must close after `faces` (its base faces, at least 3) steps.
void Tracer::walkRing(int32_t s, int32_t faces, StarChart& star) const
{
  const std::vector<int32_t>& bt = Base_.baseTriangles;
  const auto it = std::lower_bound(DirectedBase_.begin(), DirectedBase_.end(),
    std::make_pair(directedKey(s, 0), std::numeric_limits<int32_t>::min()));
  if (it == DirectedBase_.end() || keyFrom(it->first) != s)
  {
    throw InputError("tracePaths: base vertex " + std::to_string(Base_.baseVertices[s]) +
      " is in no base triangle; rebuild the base complex");
  }
  const int32_t first = keyTo(it->first);
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
  } while (r != first && static_cast<int32_t>(star.ring.size()) <= faces);
  if (static_cast<int32_t>(star.ring.size()) != faces || faces < 3)
  {
    throw InputError("tracePaths: the base triangles around base vertex " +
      std::to_string(Base_.baseVertices[s]) +
      " do not form one fan of at least 3; rebuild the base complex");
  }
}

/// The faces across the link of s, each similar to its 3D triangle, outside the link edge.
void Tracer::unfoldOuterFaces(int32_t s, StarChart& star) const
{
  const size_t n = star.ring.size();
  for (size_t i = 0; i < n; ++i)
  {
    const int32_t a = star.ring[(i + 1) % n], b = star.ring[i];
    const int32_t g = this->faceOf(a, b);
    const int32_t w = this->thirdCorner(g, a, b);
    const V3 pa = this->basePos(a);
    const V3 ab = sub(this->basePos(b), pa);
    const V3 aw = sub(this->basePos(w), pa);
    const double len2 = dot(ab, ab);
    const double along = dot(aw, ab) / len2, up = norm(cross(ab, aw)) / len2;
    const P2 za = star.z[(i + 1) % n], zb = star.z[i];
    const P2 e{ zb.x - za.x, zb.y - za.y };
    star.outer.push_back(w == s ? -1 : g);
    star.outerApex.push_back(w);
    star.apexAt.push_back({ za.x + along * e.x - up * e.y, za.y + along * e.y + up * e.x });
  }
}
} // namespace tracing
} // namespace detail
} // namespace tc
