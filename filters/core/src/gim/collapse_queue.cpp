// SPDX-License-Identifier: BSD-3-Clause
// Step 2 of the base complex (simplifier.h): Garland-Heckbert quadrics, area-weighted plus
// feature-edge planes, and a lazy priority queue of half-edge collapses u -> v, cheapest first,
// ties by input vertex id (deterministic), under the rules of Feng et al. section 5.1.
#include "gim/simplifier.h"

#include <algorithm>
#include <limits>
#include <utility>

namespace tc
{
namespace detail
{
namespace base_complex
{
void Simplifier::initQuadrics()
{
  Quadric_.assign(NumVertices_, Quadric());
  Area_.assign(NumVertices_, 0.0);
  double lo[3], hi[3];
  boundingBox(Points3_.data(), NumVertices_, lo, hi);
  const V3 diagonal = sub(V3{ hi[0], hi[1], hi[2] }, V3{ lo[0], lo[1], lo[2] });
  Diag2_ = std::max(dot(diagonal, diagonal), std::numeric_limits<double>::min());
  this->addFaceQuadrics();
  this->addFeatureQuadrics();
}

/// Area-weighted plane quadrics (Garland and Heckbert 1997, section 5): the sum then measures
/// squared distance integrated over the merged surface, so small regions go first and the base
/// triangles come out of similar size.
void Simplifier::addFaceQuadrics()
{
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
}

/// Feature curves: a plane through each feature edge perpendicular to each of its faces
/// (Garland and Heckbert's boundary constraint), weighted like the area it stands for, so a curve
/// simplifies first where it is straight.
void Simplifier::addFeatureQuadrics()
{
  const double weight = Options_.featureWeight;
  for (int32_t i = 0; i < 3 * NumFaces_ && weight > 0; ++i)
  {
    const int32_t h = this->inputHe(i);
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

/// Candidates_: the legal collapses of u, cheapest first, ties by input id of the target.
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
    h = this->nextOutgoing(h);
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

/// Queues u at the cost of its cheapest legal collapse, if it has one.
void Simplifier::queueCheapest(int32_t u)
{
  this->gatherCandidates(u);
  if (!Candidates_.empty())
  {
    this->push(u, Candidates_.front().cost);
  }
}

/// The first queue: every vertex that may be removed, at its cheapest collapse, heapified at once.
void Simplifier::buildQueue()
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

/// After a collapse into v: v has new edges (full re-evaluation); each neighbour x only gained
/// or changed its edge to v, so its key drops to that edge's cost if cheaper. A neighbour with no
/// entry (every collapse was rejected) is re-evaluated in full: its ring has changed, so rejected
/// collapses may have become valid.
void Simplifier::requeueAfter(int32_t v)
{
  this->queueCheapest(v);
  const int32_t start = Out_[v];
  int32_t g = start;
  do
  {
    const int32_t x = F_[nextHe(g)];
    if (!Pinned_[x])
    {
      if (Key_[x] == std::numeric_limits<double>::infinity())
      {
        this->queueCheapest(x);
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
    g = this->nextOutgoing(g);
  } while (g != start);
}
} // namespace base_complex
} // namespace detail
} // namespace tc
