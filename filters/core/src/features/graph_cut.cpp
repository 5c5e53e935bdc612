// SPDX-License-Identifier: BSD-3-Clause
#include "features/graph_cut.h"

#include "features/face_geometry.h"
#include "features/statistics.h"

#include "tc/common/parallel.h"

#include <boost/graph/boykov_kolmogorov_max_flow.hpp>
#include <boost/graph/compressed_sparse_row_graph.hpp>
#include <boost/property_map/property_map.hpp>

#include <algorithm>
#include <cmath>
#include <numeric>
#include <utility>

namespace tc
{
namespace detail
{
namespace refinement
{
namespace
{
// 1 / sigma_theta times dihedralWeight, sigma_theta the standard deviation of the dihedral
// angle over the manifold edges (0: no crease factor).
double creaseScale(
  const EdgeTable& edges, const std::vector<double>& dihedral, double dihedralWeight)
{
  if (!(dihedralWeight > 0.0))
  {
    return 0.0;
  }
  const int64_t ne = edges.numEdges();
  double sum = 0.0, sumSq = 0.0;
  int64_t count = 0;
  for (int64_t e = 0; e < ne; ++e)
  {
    if (edges.valence(e) == 2)
    {
      sum += dihedral[e];
      sumSq += dihedral[e] * dihedral[e];
      ++count;
    }
  }
  const double sd = standardDeviation(sum, sumSq, static_cast<double>(count));
  return sd > 0.0 ? dihedralWeight / sd : 0.0;
}

// The free nodes of the cuts: band faces labelled with one of the clusters of their nearest
// pair, of pairs that have faces of both clusters around their free nodes (else there is
// nothing to cut against).
struct CutNodes
{
  std::vector<int32_t> region;   // #F pair of a free node's face, -1 elsewhere
  std::vector<int32_t> node;     // #F node id of a free face, -1 elsewhere
  std::vector<int32_t> nodeFace; // #N face of each node
};

CutNodes freeNodes(const FaceAdjacency& dual, const Band& band, const ClusterPairs& pairs,
  const std::vector<int32_t>& label)
{
  const int64_t nf = static_cast<int64_t>(label.size());
  const int64_t numPairs = static_cast<int64_t>(band.pairKeys.size());
  auto pairA = [&](int32_t p) { return pairs.first(band.pairKeys[p]); };
  auto pairB = [&](int32_t p) { return pairs.second(band.pairKeys[p]); };
  CutNodes nodes;
  nodes.region.assign(nf, -1);
  std::vector<int32_t>& region = nodes.region;
  for (int64_t f = 0; f < nf; ++f)
  {
    const int32_t p = band.pair[f];
    if (p >= 0 && (label[f] == pairA(p) || label[f] == pairB(p)))
    {
      region[f] = p;
    }
  }
  std::vector<uint8_t> hasSource(numPairs, 0), hasSink(numPairs, 0);
  for (int64_t f = 0; f < nf; ++f)
  {
    const int32_t p = region[f];
    if (p < 0)
    {
      continue;
    }
    for (int64_t j = dual.offsets[f]; j < dual.offsets[f + 1]; ++j)
    {
      const int32_t g = dual.faces[j];
      if (region[g] != p)
      {
        hasSource[p] |= label[g] == pairA(p) ? 1 : 0;
        hasSink[p] |= label[g] == pairB(p) ? 1 : 0;
      }
    }
  }
  nodes.node.assign(nf, -1);
  for (int64_t f = 0; f < nf; ++f)
  {
    if (region[f] >= 0 && !(hasSource[region[f]] && hasSink[region[f]]))
    {
      region[f] = -1;
    }
    if (region[f] >= 0)
    {
      nodes.node[f] = static_cast<int32_t>(nodes.nodeFace.size());
      nodes.nodeFace.push_back(static_cast<int32_t>(f));
    }
  }
  return nodes;
}

struct Arc
{
  int32_t from, to;
  double capacity;
};

// The arcs over the free nodes 0 .. n-1, the source n and the sink n + 1: an undirected n-link
// is two arcs, each the other's reverse, both with the capacity; a t-link is an arc with the
// capacity and a reverse arc with none. Arcs 2k and 2k + 1 are reverses of each other.
std::vector<Arc> cutArcs(const FaceAdjacency& dual, const std::vector<double>& capacity,
  const CutNodes& nodes, const Band& band, const ClusterPairs& pairs,
  const std::vector<int32_t>& label)
{
  const int64_t n = static_cast<int64_t>(nodes.nodeFace.size());
  const int32_t source = static_cast<int32_t>(n), sink = static_cast<int32_t>(n + 1);
  std::vector<Arc> arcs;
  std::vector<double> sourceCap(n, 0.0), sinkCap(n, 0.0);
  for (int64_t i = 0; i < n; ++i)
  {
    const int32_t f = nodes.nodeFace[i];
    const int32_t p = nodes.region[f];
    for (int64_t j = dual.offsets[f]; j < dual.offsets[f + 1]; ++j)
    {
      const int32_t g = dual.faces[j];
      if (nodes.region[g] == p)
      {
        if (f < g)
        {
          const double c = capacity[j];
          arcs.push_back({ static_cast<int32_t>(i), nodes.node[g], c });
          arcs.push_back({ nodes.node[g], static_cast<int32_t>(i), c });
        }
      }
      else if (label[g] == pairs.first(band.pairKeys[p]))
      {
        sourceCap[i] += capacity[j];
      }
      else if (label[g] == pairs.second(band.pairKeys[p]))
      {
        sinkCap[i] += capacity[j];
      }
    }
  }
  for (int64_t i = 0; i < n; ++i)
  {
    if (sourceCap[i] > 0.0)
    {
      arcs.push_back({ source, static_cast<int32_t>(i), sourceCap[i] });
      arcs.push_back({ static_cast<int32_t>(i), source, 0.0 });
    }
    if (sinkCap[i] > 0.0)
    {
      arcs.push_back({ static_cast<int32_t>(i), sink, sinkCap[i] });
      arcs.push_back({ sink, static_cast<int32_t>(i), 0.0 });
    }
  }
  return arcs;
}

// Boykov-Kolmogorov max-flow over the arcs (nodes n = source, n + 1 = sink).
// @return #N +1 for a node in the source tree, -1 in the sink tree, 0 in neither
std::vector<int8_t> maxFlowSides(const std::vector<Arc>& arcs, int64_t n, const Progress& progress)
{
  const int32_t source = static_cast<int32_t>(n), sink = static_cast<int32_t>(n + 1);
  // Compressed sparse row graph: arcs sorted by tail (stable, so the order is deterministic).
  const int64_t na = static_cast<int64_t>(arcs.size());
  std::vector<int64_t> position(na);
  {
    std::vector<int64_t> start(n + 3, 0);
    for (const Arc& a : arcs)
    {
      ++start[a.from + 1];
    }
    std::partial_sum(start.begin(), start.end(), start.begin());
    for (int64_t k = 0; k < na; ++k)
    {
      position[k] = start[arcs[k].from]++;
    }
  }
  std::vector<std::pair<int32_t, int32_t>> sortedArcs(na);
  std::vector<double> cap(na), residual(na);
  for (int64_t k = 0; k < na; ++k)
  {
    sortedArcs[position[k]] = { arcs[k].from, arcs[k].to };
    cap[position[k]] = arcs[k].capacity;
  }
  using Graph = boost::compressed_sparse_row_graph<boost::directedS, boost::no_property,
    boost::no_property, boost::no_property, int32_t, int64_t>;
  using EdgeDesc = boost::graph_traits<Graph>::edge_descriptor;
  Graph graph(
    boost::edges_are_sorted, sortedArcs.begin(), sortedArcs.end(), static_cast<int32_t>(n + 2));
  // Arc k of the sorted list has edge index k (edges_are_sorted keeps the order).
  std::vector<EdgeDesc> reverse(na);
  for (int64_t k = 0; k < na; ++k)
  {
    const int64_t r = position[k ^ 1];
    reverse[position[k]] = EdgeDesc(sortedArcs[r].first, r);
  }
  std::vector<EdgeDesc> predecessor(n + 2);
  std::vector<boost::default_color_type> color(n + 2);
  std::vector<int64_t> distanceToTerminal(n + 2);
  const auto edgeIndex = boost::get(boost::edge_index, graph);
  const auto vertexIndex = boost::get(boost::vertex_index, graph);
  progress.report(0.4);
  boost::boykov_kolmogorov_max_flow(graph,
    boost::make_iterator_property_map(cap.begin(), edgeIndex),
    boost::make_iterator_property_map(residual.begin(), edgeIndex),
    boost::make_iterator_property_map(reverse.begin(), edgeIndex),
    boost::make_iterator_property_map(predecessor.begin(), vertexIndex),
    boost::make_iterator_property_map(color.begin(), vertexIndex),
    boost::make_iterator_property_map(distanceToTerminal.begin(), vertexIndex), vertexIndex, source,
    sink);
  // The source tree is black, the sink tree white.
  std::vector<int8_t> side(n, 0);
  for (int64_t i = 0; i < n; ++i)
  {
    side[i] = color[i] == boost::black_color ? 1 : (color[i] == boost::white_color ? -1 : 0);
  }
  return side;
}

// Every cluster stays non-empty: undo the cuts of the pairs of a cluster that lost all its
// faces (undoing restores that cluster's faces and can only empty another one through its own
// pairs, so this ends).
// @param[in] before  #N label of each node's face before the cut
void keepClustersNonEmpty(const CutNodes& nodes, const std::vector<int32_t>& before,
  const Band& band, const ClusterPairs& pairs, std::vector<int32_t>& label)
{
  const int64_t n = static_cast<int64_t>(before.size());
  const int32_t numPairs = static_cast<int32_t>(band.pairKeys.size());
  std::vector<int64_t> count(pairs.numClusters, 0);
  for (int32_t l : label)
  {
    ++count[l];
  }
  std::vector<uint8_t> undone(numPairs, 0);
  for (bool again = true; again;)
  {
    again = false;
    for (int32_t c = 0; c < pairs.numClusters; ++c)
    {
      if (count[c] > 0)
      {
        continue;
      }
      for (int32_t p = 0; p < numPairs; ++p)
      {
        const int64_t key = band.pairKeys[p];
        if (!undone[p] && (pairs.first(key) == c || pairs.second(key) == c))
        {
          undone[p] = 1;
          again = true;
        }
      }
      for (int64_t i = 0; i < n; ++i)
      {
        const int32_t f = nodes.nodeFace[i];
        if (undone[nodes.region[f]] && label[f] != before[i])
        {
          --count[label[f]];
          ++count[before[i]];
          label[f] = before[i];
        }
      }
    }
  }
}
} // namespace

std::vector<double> dualCapacity(const TriMesh& mesh, const EdgeTable& edges,
  const FaceAdjacency& dual, const std::vector<double>& faceMeanCurvature,
  const std::vector<uint8_t>& crestVertex, const std::vector<double>& dihedral,
  const FeatureRefinementOptions& options, const Progress& progress)
{
  const int64_t nf = mesh.numTriangles();
  const double sigma = curvatureSpread(faceMeanCurvature);
  const double inverseSigma = sigma > 0.0 ? 1.0 / sigma : 0.0;
  const double inverseSigmaTheta = creaseScale(edges, dihedral, options.dihedralWeight);
  auto capacity = [&](int32_t f, int32_t g, int32_t e)
  {
    const int32_t a = edges.vertices[2 * e], b = edges.vertices[2 * e + 1];
    const double beta = crestAlong(crestVertex, a, b) ? options.crestBeta : 1.0;
    const double theta = options.dihedralWeight > 0.0 ? dihedral[e] * inverseSigmaTheta : 0.0;
    return beta * vertexDistance(mesh, a, b) *
      std::exp(
        -(std::abs(faceMeanCurvature[f]) + std::abs(faceMeanCurvature[g])) * inverseSigma - theta);
  };
  std::vector<double> out(dual.faces.size());
  parallel_for(
    nf,
    [&](int64_t f)
    {
      for (int64_t j = dual.offsets[f]; j < dual.offsets[f + 1]; ++j)
      {
        out[j] = capacity(static_cast<int32_t>(f), dual.faces[j], dual.edges[j]);
      }
    },
    progress);
  return out;
}

int64_t cutBand(const FaceAdjacency& dual, const std::vector<double>& capacity, const Band& band,
  const ClusterPairs& pairs, std::vector<int32_t>& label, const Progress& progress)
{
  if (band.pairKeys.empty())
  {
    progress.report(1.0);
    return 0;
  }
  // 1. The free nodes and the arcs between them and to the terminals.
  const CutNodes nodes = freeNodes(dual, band, pairs, label);
  const int64_t n = static_cast<int64_t>(nodes.nodeFace.size());
  if (n == 0)
  {
    progress.report(1.0);
    return 0;
  }
  const std::vector<Arc> arcs = cutArcs(dual, capacity, nodes, band, pairs, label);
  progress.report(0.3);

  // 2. The max-flow.
  const std::vector<int8_t> side = maxFlowSides(arcs, n, progress);
  progress.report(0.9);

  // 3. The source tree is a, the sink tree b; a free node in neither tree has no unsaturated
  //    path to a terminal and keeps its label.
  std::vector<int32_t> before(n);
  for (int64_t i = 0; i < n; ++i)
  {
    const int32_t f = nodes.nodeFace[i];
    const int64_t key = band.pairKeys[nodes.region[f]];
    before[i] = label[f];
    if (side[i] > 0)
    {
      label[f] = pairs.first(key);
    }
    else if (side[i] < 0)
    {
      label[f] = pairs.second(key);
    }
  }
  keepClustersNonEmpty(nodes, before, band, pairs, label);
  int64_t changed = 0;
  for (int64_t i = 0; i < n; ++i)
  {
    changed += label[nodes.nodeFace[i]] != before[i] ? 1 : 0;
  }
  progress.report(1.0);
  return changed;
}
} // namespace refinement
} // namespace detail
} // namespace tc
