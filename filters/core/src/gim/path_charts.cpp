// SPDX-License-Identifier: BSD-3-Clause
// The base complex as the path tracer reads it: its directed edges (checked to form a closed
// oriented manifold), its undirected base edges in the order of PatchMesh::baseEdges, and the
// star chart of every base vertex: the z^a map of MAPS (3D angles at the vertex scaled to sum to
// 2 pi, radii to the power a) or, where one angle would exceed pi, the ring on the unit circle at
// equal angles; the same charts as the bijection check of buildBaseComplex. A chart is linear on
// every base face, so a point's chart position is the barycentric combination of its corners'.
#include "gim/path_tracer.h"

#include "detail/star_map.h"

#include "tc/common/errors.h"

namespace tc
{
namespace detail
{
namespace tracing
{
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
