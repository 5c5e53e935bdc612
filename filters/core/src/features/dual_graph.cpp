// SPDX-License-Identifier: BSD-3-Clause
#include "features/dual_graph.h"

#include "features/face_adjacency.h"
#include "features/face_geometry.h"
#include "features/statistics.h"

#include "tc/common/mesh_topology.h"
#include "tc/common/parallel.h"

#include <tbb/enumerable_thread_specific.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <numeric>
#include <utility>

namespace tc
{
namespace detail
{
namespace spectral
{
namespace
{
constexpr double kInf = std::numeric_limits<double>::infinity();
// Sources per task of the extra-edge search.
constexpr int64_t kSearchChunk = 2048;

// ---------------------------------------------------------------------------------------------
// Adjacent faces

// Every ordered pair of faces across a shared mesh edge, in FaceAdjacency order, with its
// length through the edge midpoint and its crest flag. A degenerate edge (equal ends) joins no
// faces.
DualGraph adjacentPairs(const TriMesh& mesh, const EdgeTable& edges, const FaceAdjacency& fa,
  const std::vector<double>& centroids, const std::vector<uint8_t>& crestVertex)
{
  const int64_t nf = mesh.numTriangles();
  auto joins = [&](int32_t e) { return edges.vertices[2 * e] != edges.vertices[2 * e + 1]; };
  DualGraph g;
  g.offsets.assign(nf + 1, 0);
  for (int64_t f = 0; f < nf; ++f)
  {
    for (int64_t j = fa.offsets[f]; j < fa.offsets[f + 1]; ++j)
    {
      g.offsets[f + 1] += joins(fa.edges[j]) ? 1 : 0;
    }
  }
  std::partial_sum(g.offsets.begin(), g.offsets.end(), g.offsets.begin());
  const int64_t total = g.offsets[nf];
  g.ids.resize(total);
  g.dist.resize(total);
  g.crest.resize(total);
  parallel_for(nf,
    [&](int64_t f)
    {
      int64_t slot = g.offsets[f];
      for (int64_t j = fa.offsets[f]; j < fa.offsets[f + 1]; ++j)
      {
        const int32_t e = fa.edges[j];
        if (!joins(e))
        {
          continue;
        }
        const int32_t a = edges.vertices[2 * e];
        const int32_t b = edges.vertices[2 * e + 1];
        double mid[3];
        for (int c = 0; c < 3; ++c)
        {
          mid[c] = 0.5 * (mesh.points[3 * a + c] + mesh.points[3 * b + c]);
        }
        const int32_t other = fa.faces[j];
        g.ids[slot] = other;
        g.dist[slot] = distance3(&centroids[3 * f], mid) + distance3(&centroids[3 * other], mid);
        g.crest[slot] = crestAlong(crestVertex, a, b) ? 1 : 0;
        ++slot;
      }
    });
  return g;
}

// Sorts every row; a pair of faces that shares two edges (a fold) or appears twice in a fan
// keeps one dual edge: the shorter length, crest if either shared edge is one. A face paired
// with itself (a degenerate triangle with two equal sides) is dropped.
// @return #F the entries kept at the front of each row
std::vector<int64_t> mergeRepeatedNeighbours(DualGraph& g)
{
  const int64_t nf = static_cast<int64_t>(g.offsets.size()) - 1;
  std::vector<int64_t> kept(nf, 0);
  parallel_for(nf,
    [&](int64_t f)
    {
      const int64_t begin = g.offsets[f];
      const int64_t end = g.offsets[f + 1];
      // Rows are short (3 for a manifold mesh): insertion sort without allocation.
      for (int64_t i = begin + 1; i < end; ++i)
      {
        for (int64_t j = i; j > begin && g.ids[j] < g.ids[j - 1]; --j)
        {
          std::swap(g.ids[j], g.ids[j - 1]);
          std::swap(g.dist[j], g.dist[j - 1]);
          std::swap(g.crest[j], g.crest[j - 1]);
        }
      }
      int64_t out = begin;
      for (int64_t i = begin; i < end; ++i)
      {
        if (g.ids[i] == static_cast<int32_t>(f))
        {
          continue;
        }
        if (out > begin && g.ids[out - 1] == g.ids[i])
        {
          g.dist[out - 1] = std::min(g.dist[out - 1], g.dist[i]);
          g.crest[out - 1] = g.crest[out - 1] | g.crest[i];
          continue;
        }
        g.ids[out] = g.ids[i];
        g.dist[out] = g.dist[i];
        g.crest[out] = g.crest[i];
        ++out;
      }
      kept[f] = out - begin;
    });
  return kept;
}

// Moves the first kept[f] entries of every row together and frees the rest.
void compactRows(DualGraph& g, const std::vector<int64_t>& kept)
{
  const int64_t nf = static_cast<int64_t>(kept.size());
  int64_t write = 0;
  for (int64_t f = 0; f < nf; ++f)
  {
    const int64_t begin = g.offsets[f];
    g.offsets[f] = write;
    for (int64_t i = begin; i < begin + kept[f]; ++i, ++write)
    {
      g.ids[write] = g.ids[i];
      g.dist[write] = g.dist[i];
      g.crest[write] = g.crest[i];
    }
  }
  g.offsets[nf] = write;
  g.ids.resize(write);
  g.dist.resize(write);
  g.crest.resize(write);
  g.ids.shrink_to_fit();
  g.dist.shrink_to_fit();
  g.crest.shrink_to_fit();
}

// ---------------------------------------------------------------------------------------------
// Extra edges

struct DijkstraScratch
{
  std::vector<double> best;
  std::vector<uint8_t> crest;
  std::vector<int32_t> touched;
  std::vector<std::pair<double, int32_t>> heap;
};

struct ExtraEdges
{
  std::vector<int32_t> source;
  std::vector<int32_t> target;
  std::vector<double> dist;
  std::vector<uint8_t> crest;
};

// Min-heap order of (distance, face): ties by face id, so the search order is deterministic.
bool laterInHeap(const std::pair<double, int32_t>& a, const std::pair<double, int32_t>& b)
{
  return a.first > b.first || (a.first == b.first && a.second > b.second);
}

// A Dijkstra from src bounded by radius. Each pair is recorded once, from its lower face id,
// so the graph is symmetric whatever the tie-breaking.
void searchExtraEdges(
  const DualGraph& adj, int64_t src, double radius, DijkstraScratch& s, ExtraEdges& out)
{
  const int32_t* adjBegin = adj.ids.data() + adj.offsets[src];
  const int32_t* adjEnd = adj.ids.data() + adj.offsets[src + 1];
  s.best[src] = 0.0;
  s.crest[src] = 0;
  s.touched.push_back(static_cast<int32_t>(src));
  s.heap.emplace_back(0.0, static_cast<int32_t>(src));
  while (!s.heap.empty())
  {
    std::pop_heap(s.heap.begin(), s.heap.end(), laterInHeap);
    const auto [d, u] = s.heap.back();
    s.heap.pop_back();
    if (d > s.best[u])
    {
      continue;
    }
    if (u > src && !std::binary_search(adjBegin, adjEnd, u))
    {
      out.source.push_back(static_cast<int32_t>(src));
      out.target.push_back(u);
      out.dist.push_back(d);
      out.crest.push_back(s.crest[u]);
    }
    for (int64_t k = adj.offsets[u]; k < adj.offsets[u + 1]; ++k)
    {
      const int32_t v = adj.ids[k];
      const double nd = d + adj.dist[k];
      if (nd < radius && nd < s.best[v])
      {
        if (s.best[v] == kInf)
        {
          s.touched.push_back(v);
        }
        s.best[v] = nd;
        s.crest[v] = s.crest[u] | adj.crest[k];
        s.heap.emplace_back(nd, v);
        std::push_heap(s.heap.begin(), s.heap.end(), laterInHeap);
      }
    }
  }
  for (int32_t t : s.touched)
  {
    s.best[t] = kInf;
  }
  s.touched.clear();
}

// The adjacency rows followed by the extra edges in both directions (freed as they are copied).
DualGraph mergeExtraEdges(const DualGraph& adj, std::vector<ExtraEdges>& found)
{
  const int64_t nf = static_cast<int64_t>(adj.offsets.size()) - 1;
  DualGraph g;
  g.offsets.assign(nf + 1, 0);
  for (int64_t f = 0; f < nf; ++f)
  {
    g.offsets[f + 1] = adj.offsets[f + 1] - adj.offsets[f];
  }
  for (const ExtraEdges& e : found)
  {
    for (size_t i = 0; i < e.source.size(); ++i)
    {
      ++g.offsets[e.source[i] + 1];
      ++g.offsets[e.target[i] + 1];
    }
  }
  std::partial_sum(g.offsets.begin(), g.offsets.end(), g.offsets.begin());
  const int64_t total = g.offsets[nf];
  g.ids.resize(total);
  g.dist.resize(total);
  g.crest.resize(total);
  std::vector<int64_t> fill(g.offsets.begin(), g.offsets.end() - 1);
  for (int64_t f = 0; f < nf; ++f)
  {
    for (int64_t k = adj.offsets[f]; k < adj.offsets[f + 1]; ++k)
    {
      const int64_t slot = fill[f]++;
      g.ids[slot] = adj.ids[k];
      g.dist[slot] = adj.dist[k];
      g.crest[slot] = adj.crest[k];
    }
  }
  for (ExtraEdges& e : found)
  {
    for (size_t i = 0; i < e.source.size(); ++i)
    {
      for (int side = 0; side < 2; ++side)
      {
        const int32_t a = side == 0 ? e.source[i] : e.target[i];
        const int32_t b = side == 0 ? e.target[i] : e.source[i];
        const int64_t slot = fill[a]++;
        g.ids[slot] = b;
        g.dist[slot] = e.dist[i];
        g.crest[slot] = e.crest[i];
      }
    }
    e = ExtraEdges();
  }
  return g;
}
} // namespace

DualGraph buildAdjacentDual(const TriMesh& mesh, const std::vector<double>& centroids,
  const std::vector<uint8_t>& crestVertex, const Progress& progress)
{
  const EdgeTable edges = buildEdgeTable(mesh.triangles);
  progress.report(0.4);
  DualGraph g = adjacentPairs(
    mesh, edges, buildFaceAdjacency(edges, mesh.numTriangles()), centroids, crestVertex);
  progress.report(0.7);
  compactRows(g, mergeRepeatedNeighbours(g));
  progress.report(1.0);
  return g;
}

DualGraph addExtraEdges(
  const DualGraph& adj, const std::vector<uint8_t>& active, double radius, const Progress& progress)
{
  const int64_t nf = static_cast<int64_t>(adj.offsets.size()) - 1;
  const int64_t numChunks = (nf + kSearchChunk - 1) / kSearchChunk;
  std::vector<ExtraEdges> found(numChunks);
  tbb::enumerable_thread_specific<DijkstraScratch> scratch(
    [nf]()
    {
      DijkstraScratch s;
      s.best.assign(nf, kInf);
      s.crest.assign(nf, 0);
      return s;
    });
  parallel_for(
    numChunks,
    [&](int64_t c)
    {
      DijkstraScratch& s = scratch.local();
      const int64_t stop = std::min(nf, (c + 1) * kSearchChunk);
      for (int64_t src = c * kSearchChunk; src < stop; ++src)
      {
        if (active[src])
        {
          searchExtraEdges(adj, src, radius, s, found[c]);
        }
      }
    },
    progress.sub(0.0, 0.8));
  DualGraph g = mergeExtraEdges(adj, found);
  progress.report(1.0);
  return g;
}

ExactGraph buildExactGraph(const DualGraph& adjacent, const std::vector<uint8_t>& exact,
  double extraEdgeFactor, const Progress& progress)
{
  ExactGraph out;
  if (exact.empty())
  {
    return out;
  }
  const DistanceMoments near = distanceMoments(adjacent, exact);
  const double radius = extraEdgeFactor * (near.count > 0 ? near.sum / near.count : 0.0);
  out.graph = radius > 0.0 ? addExtraEdges(adjacent, exact, radius, progress) : adjacent;
  const DistanceMoments used = distanceMoments(out.graph, exact);
  const double sigmaD = standardDeviation(used.sum, used.squares, used.count);
  out.invSigmaD = sigmaD > 0.0 ? 1.0 / sigmaD : 0.0;
  return out;
}

Pieces findPieces(const DualGraph& g, const std::vector<int32_t>* label)
{
  const int64_t nf = static_cast<int64_t>(g.offsets.size()) - 1;
  Pieces p;
  p.of.assign(nf, -1);
  std::vector<int32_t> stack;
  for (int64_t seed = 0; seed < nf; ++seed)
  {
    if (p.of[seed] >= 0)
    {
      continue;
    }
    const int32_t id = static_cast<int32_t>(p.size.size());
    int64_t size = 0;
    p.of[seed] = id;
    stack.push_back(static_cast<int32_t>(seed));
    while (!stack.empty())
    {
      const int32_t f = stack.back();
      stack.pop_back();
      ++size;
      for (int64_t k = g.offsets[f]; k < g.offsets[f + 1]; ++k)
      {
        const int32_t n = g.ids[k];
        if (p.of[n] < 0 && (label == nullptr || (*label)[n] == (*label)[f]))
        {
          p.of[n] = id;
          stack.push_back(n);
        }
      }
    }
    p.size.push_back(size);
    p.first.push_back(static_cast<int32_t>(seed));
  }
  return p;
}

DistanceMoments distanceMoments(const DualGraph& graph, const std::vector<uint8_t>& use)
{
  DistanceMoments m;
  const int64_t nf = static_cast<int64_t>(use.size());
  for (int64_t f = 0; f < nf; ++f)
  {
    if (!use[f])
    {
      continue;
    }
    for (int64_t k = graph.offsets[f]; k < graph.offsets[f + 1]; ++k)
    {
      if (graph.ids[k] > f)
      {
        m.sum += graph.dist[k];
        m.squares += graph.dist[k] * graph.dist[k];
        m.count += 1.0;
      }
    }
  }
  return m;
}
} // namespace spectral
} // namespace detail
} // namespace tc
