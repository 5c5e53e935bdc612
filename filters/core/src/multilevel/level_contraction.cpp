// SPDX-License-Identifier: BSD-3-Clause
// QSlim on one level of the multilevel mesh (Kircher and Garland 2005, section 3; Garland and
// Heckbert 1997): the level's vertices and edges as a graph, contracted cheapest edge first.
//
// Written here rather than with CGAL's Surface_mesh_simplification (or meshoptimizer): those
// need a manifold halfedge mesh at every step, while above M1 a level is the non-manifold graph
// of M0's clusters, and every contraction must sum M0's quadrics and record which vertices
// merged; one contraction loop over flat edge lists does both for every level.
#include "multilevel/multilevel_internal.h"

#include <algorithm>
#include <numeric>
#include <queue>

namespace tc
{
namespace detail
{
namespace multilevel
{
namespace
{
struct HeapEntry
{
  double cost;
  int32_t lo, hi; ///< the edge's ends when it was pushed, lo < hi
  int32_t edge;
  int32_t stamp;
};
/// Cheapest first; equal costs by the ends' ids, so the order never depends on the heap.
struct HeapOrder
{
  bool operator()(const HeapEntry& x, const HeapEntry& y) const
  {
    if (x.cost != y.cost)
    {
      return x.cost > y.cost;
    }
    return x.lo != y.lo ? x.lo > y.lo : x.hi > y.hi;
  }
};

/// The contraction state. Edge e has slots 2e and 2e + 1, one per end: End_[s] is the vertex
/// at slot s, the other end is End_[s ^ 1], and the slots of a vertex form a singly linked list
/// (Head_, Next_), which a contraction splices instead of reallocating.
class Contraction
{
public:
  Contraction(const ClusterGraph& graph, LiveFaces* faces)
    : Q_(graph.quadrics)
    , Sum_(graph.positionSums)
    , Count_(graph.counts)
    , End_(graph.edges)
    , Faces_(faces)
  {
    const int32_t n = graph.size();
    Into_.resize(n);
    std::iota(Into_.begin(), Into_.end(), 0);
    Head_.assign(n, -1);
    Mark_.assign(n, -1);
    Next_.assign(End_.size(), -1);
    EdgeAlive_.assign(End_.size() / 2, 1);
    Stamp_.assign(End_.size() / 2, 0);
    for (int32_t s = static_cast<int32_t>(End_.size()) - 1; s >= 0; --s)
    {
      Next_[s] = Head_[End_[s]];
      Head_[End_[s]] = s;
    }
  }

  void run(int32_t target, const Progress& progress);
  std::vector<int32_t> parents(int32_t* count);

private:
  double cost(int32_t a, int32_t b) const;
  void push(int32_t e);
  void pushAll();
  bool popValid(HeapEntry& top);
  void merge(int32_t a, int32_t b);
  void spliceEdges(int32_t a, int32_t b);
  int32_t root(int32_t v);

  std::vector<Quadric> Q_;
  std::vector<V3> Sum_;
  std::vector<int32_t> Count_;
  std::vector<int32_t> End_, Next_, Head_;
  std::vector<uint8_t> EdgeAlive_;
  std::vector<int32_t> Stamp_;
  std::vector<int32_t> Into_; ///< the vertex each merged into (itself while it lives)
  std::vector<int32_t> Mark_;
  LiveFaces* Faces_;
  std::priority_queue<HeapEntry, std::vector<HeapEntry>, HeapOrder> Heap_;
};

double Contraction::cost(int32_t a, int32_t b) const
{
  Quadric q = Q_[a];
  q.add(Q_[b]);
  const double n = Count_[a] + Count_[b];
  const V3 mean{ (Sum_[a].x + Sum_[b].x) / n, (Sum_[a].y + Sum_[b].y) / n,
    (Sum_[a].z + Sum_[b].z) / n };
  return placeVertex(q, mean).error;
}

void Contraction::push(int32_t e)
{
  const int32_t a = End_[2 * e], b = End_[2 * e + 1];
  Heap_.push({ this->cost(a, b), std::min(a, b), std::max(a, b), e, ++Stamp_[e] });
}

void Contraction::pushAll()
{
  for (int32_t e = 0; e < static_cast<int32_t>(EdgeAlive_.size()); ++e)
  {
    if (EdgeAlive_[e])
    {
      this->push(e);
    }
  }
}

/// Pops entries until one is current (its edge alive, not recosted since it was pushed).
bool Contraction::popValid(HeapEntry& top)
{
  while (!Heap_.empty())
  {
    top = Heap_.top();
    Heap_.pop();
    if (EdgeAlive_[top.edge] && Stamp_[top.edge] == top.stamp)
    {
      return true;
    }
  }
  return false;
}

/// Moves b's edges to a: the edge ab and edges to a vertex a is already joined to die (so the
/// graph keeps one edge per pair), the others are relabelled and spliced into a's list.
void Contraction::spliceEdges(int32_t a, int32_t b)
{
  for (int32_t* link = &Head_[a]; *link >= 0;)
  {
    const int32_t s = *link;
    if (!EdgeAlive_[s / 2])
    {
      *link = Next_[s];
      continue;
    }
    Mark_[End_[s ^ 1]] = a;
    link = &Next_[s];
  }
  for (int32_t s = Head_[b]; s >= 0;)
  {
    const int32_t next = Next_[s];
    const int32_t other = End_[s ^ 1];
    if (EdgeAlive_[s / 2] && (other == a || Mark_[other] == a))
    {
      EdgeAlive_[s / 2] = 0;
    }
    else if (EdgeAlive_[s / 2])
    {
      Mark_[other] = a;
      End_[s] = a;
      Next_[s] = Head_[a];
      Head_[a] = s;
    }
    s = next;
  }
  Head_[b] = -1;
}

/// b merges into a: quadrics, position sums and counts add up (section 3: Q_a is the sum over
/// the cluster), and a's edges are recosted.
void Contraction::merge(int32_t a, int32_t b)
{
  Q_[a].add(Q_[b]);
  Sum_[a] = { Sum_[a].x + Sum_[b].x, Sum_[a].y + Sum_[b].y, Sum_[a].z + Sum_[b].z };
  Count_[a] += Count_[b];
  Into_[b] = a;
  if (Faces_)
  {
    Faces_->contract(a, b);
  }
  this->spliceEdges(a, b);
  for (int32_t s = Head_[a]; s >= 0; s = Next_[s])
  {
    if (EdgeAlive_[s / 2])
    {
      this->push(s / 2);
    }
  }
}

/// Contracts until `target` vertices remain. An edge the link condition refuses is dropped
/// until a contraction at one of its ends recosts it; when the queue runs dry with such edges
/// left, every live edge is queued again, as long as the last round contracted something.
void Contraction::run(int32_t target, const Progress& progress)
{
  const int32_t n = static_cast<int32_t>(Count_.size());
  const int32_t wanted = std::max(1, n - target);
  const int32_t every = std::max(1, wanted / 64);
  int32_t remaining = n, refused = 0, sinceQueued = 0;
  this->pushAll();
  HeapEntry top{};
  while (remaining > target)
  {
    if (!this->popValid(top))
    {
      if (refused == 0 || sinceQueued == 0)
      {
        break;
      }
      refused = sinceQueued = 0;
      this->pushAll();
      continue;
    }
    const int32_t a = End_[2 * top.edge], b = End_[2 * top.edge + 1];
    if (Faces_ && !Faces_->linkConditionHolds(std::min(a, b), std::max(a, b)))
    {
      ++refused;
      continue;
    }
    this->merge(std::min(a, b), std::max(a, b));
    --remaining;
    ++sinceQueued;
    if ((n - remaining) % every == 0)
    {
      progress.report(std::min(1.0, static_cast<double>(n - remaining) / wanted));
    }
  }
  progress.report(1.0);
}

int32_t Contraction::root(int32_t v)
{
  while (Into_[v] != v)
  {
    Into_[v] = Into_[Into_[v]];
    v = Into_[v];
  }
  return v;
}

/// The survivor of a merge is the lower id, so a cluster's root is its lowest member, and
/// parents numbered in the order of their roots are numbered by lowest member.
std::vector<int32_t> Contraction::parents(int32_t* count)
{
  const int32_t n = static_cast<int32_t>(Into_.size());
  std::vector<int32_t> id(n, -1), parent(n);
  *count = 0;
  for (int32_t v = 0; v < n; ++v)
  {
    const int32_t r = this->root(v);
    if (id[r] < 0)
    {
      id[r] = (*count)++;
    }
    parent[v] = id[r];
  }
  return parent;
}
} // namespace

std::vector<int32_t> contractLevel(const ClusterGraph& graph, int32_t target, LiveFaces* faces,
  const Progress& progress, int32_t* parents)
{
  Contraction contraction(graph, faces);
  contraction.run(target, progress);
  return contraction.parents(parents);
}
} // namespace multilevel
} // namespace detail
} // namespace tc
