// SPDX-License-Identifier: BSD-3-Clause
#include "features/refinement_band.h"

#include "features/face_geometry.h"

#include <algorithm>
#include <cmath>
#include <functional>
#include <limits>
#include <queue>
#include <utility>

namespace tc
{
namespace detail
{
namespace refinement
{
namespace
{
constexpr double kInf = std::numeric_limits<double>::infinity();

// Each boundary edge separates the smallest and the largest label of its faces (two faces on
// a manifold edge).
// @return #E the pair key of every boundary edge, -1 on other edges
std::vector<int64_t> boundaryKeys(const EdgeTable& edges, const std::vector<int32_t>& label,
  const ClusterPairs& pairs, const std::vector<uint8_t>& isBoundary)
{
  const int64_t ne = edges.numEdges();
  std::vector<int64_t> edgeKey(ne, -1);
  for (int64_t e = 0; e < ne; ++e)
  {
    if (isBoundary[e])
    {
      int32_t lo = std::numeric_limits<int32_t>::max(), hi = -1;
      for (int64_t i = edges.faceOffsets[e]; i < edges.faceOffsets[e + 1]; ++i)
      {
        lo = std::min(lo, label[edges.edgeFaces[i]]);
        hi = std::max(hi, label[edges.edgeFaces[i]]);
      }
      edgeKey[e] = pairs.key(lo, hi);
    }
  }
  return edgeKey;
}

// The distinct keys, ascending.
std::vector<int64_t> distinctKeys(const std::vector<int64_t>& edgeKey)
{
  std::vector<int64_t> keys;
  for (int64_t key : edgeKey)
  {
    if (key >= 0)
    {
      keys.push_back(key);
    }
  }
  std::sort(keys.begin(), keys.end());
  keys.erase(std::unique(keys.begin(), keys.end()), keys.end());
  return keys;
}

// The search fronts of the multi-source Dijkstra: distance to the nearest boundary and the
// pair of that boundary, per face.
struct Fronts
{
  std::vector<double> dist;
  std::vector<int32_t> nearest;
};

// The sources: eligible faces that touch a boundary, at distance 0, with the smallest pair
// among their boundary edges.
template <typename Eligible>
Fronts seedFronts(const EdgeTable& edges, const std::vector<uint8_t>& isBoundary,
  const std::vector<int64_t>& edgeKey, const std::vector<int64_t>& pairKeys,
  const Eligible& eligible, int64_t nf)
{
  Fronts fronts{ std::vector<double>(nf, kInf), std::vector<int32_t>(nf, -1) };
  for (int64_t f = 0; f < nf; ++f)
  {
    for (int c = 0; c < 3 && eligible(f); ++c)
    {
      const int32_t e = edges.faceEdges[3 * f + c];
      if (isBoundary[e])
      {
        const int32_t p = static_cast<int32_t>(
          std::lower_bound(pairKeys.begin(), pairKeys.end(), edgeKey[e]) - pairKeys.begin());
        int32_t& nearest = fronts.nearest[f];
        nearest = nearest < 0 ? p : std::min(nearest, p);
        fronts.dist[f] = 0.0;
      }
    }
  }
  return fronts;
}

// Faces within `rings` dual steps of a source, which belong to the band whatever its size.
// @param[out] count  how many
std::vector<uint8_t> requiredFaces(
  const FaceAdjacency& dual, const std::vector<double>& dist, int rings, int64_t& count)
{
  const int64_t nf = static_cast<int64_t>(dist.size());
  std::vector<uint8_t> required(nf, 0);
  std::vector<int32_t> front, next;
  for (int64_t f = 0; f < nf; ++f)
  {
    if (dist[f] == 0.0)
    {
      required[f] = 1;
      front.push_back(static_cast<int32_t>(f));
    }
  }
  count = static_cast<int64_t>(front.size());
  for (int r = 0; r < rings && !front.empty(); ++r)
  {
    next.clear();
    for (int32_t f : front)
    {
      for (int64_t j = dual.offsets[f]; j < dual.offsets[f + 1]; ++j)
      {
        if (!required[dual.faces[j]])
        {
          required[dual.faces[j]] = 1;
          next.push_back(dual.faces[j]);
        }
      }
    }
    count += static_cast<int64_t>(next.size());
    front.swap(next);
  }
  return required;
}

// The multi-source Dijkstra over the dual graph (dual edges as long as the distance of the
// face centroids): the band is the first `target` faces settled, and every required face.
template <typename Eligible>
void growBand(const FaceAdjacency& dual, const std::vector<double>& centroids,
  const Eligible& eligible, Fronts& fronts, const std::vector<uint8_t>& required,
  int64_t requiredLeft, int64_t target, Band& band, const Progress& progress)
{
  const int64_t nf = static_cast<int64_t>(fronts.dist.size());
  std::vector<double>& dist = fronts.dist;
  using Item = std::pair<double, int32_t>;
  std::priority_queue<Item, std::vector<Item>, std::greater<Item>> queue;
  for (int64_t f = 0; f < nf; ++f)
  {
    if (dist[f] == 0.0)
    {
      queue.emplace(0.0, static_cast<int32_t>(f));
    }
  }
  const int64_t reportEvery = std::max<int64_t>(1, nf / 16);
  while (!queue.empty() && (band.size < target || requiredLeft > 0))
  {
    const auto [d, f] = queue.top();
    queue.pop();
    if (d > dist[f] || band.pair[f] >= 0 || (band.size >= target && !required[f]))
    {
      continue;
    }
    band.pair[f] = fronts.nearest[f];
    requiredLeft -= required[f];
    if (++band.size % reportEvery == 0)
    {
      progress.report(std::min(1.0, static_cast<double>(band.size) / std::max<int64_t>(1, target)));
    }
    for (int64_t j = dual.offsets[f]; j < dual.offsets[f + 1]; ++j)
    {
      const int32_t g = dual.faces[j];
      if (!eligible(g))
      {
        continue;
      }
      const double nd = d + distance3(&centroids[3 * f], &centroids[3 * g]);
      if (nd < dist[g])
      {
        dist[g] = nd;
        fronts.nearest[g] = fronts.nearest[f];
        queue.emplace(nd, g);
      }
    }
  }
}
} // namespace

std::vector<uint8_t> boundaryEdges(const EdgeTable& edges, const std::vector<int32_t>& label)
{
  const int64_t ne = edges.numEdges();
  std::vector<uint8_t> out(ne, 0);
  for (int64_t e = 0; e < ne; ++e)
  {
    const int32_t first = label[edges.edgeFaces[edges.faceOffsets[e]]];
    for (int64_t i = edges.faceOffsets[e] + 1; i < edges.faceOffsets[e + 1]; ++i)
    {
      out[e] |= label[edges.edgeFaces[i]] != first ? 1 : 0;
    }
  }
  return out;
}

Band buildBand(const EdgeTable& edges, const FaceAdjacency& dual,
  const std::vector<double>& centroids, const std::vector<int32_t>& label,
  const ClusterPairs& pairs, const std::vector<uint8_t>& isBoundary, const BandExtent& extent,
  const Progress& progress)
{
  const int64_t nf = static_cast<int64_t>(label.size());
  const Band* within = extent.within;
  auto eligible = [within](int64_t f) { return within == nullptr || within->pair[f] >= 0; };
  Band band;
  band.pair.assign(nf, -1);

  // 1. The pairs of clusters that meet, one key per boundary edge.
  const std::vector<int64_t> edgeKey = boundaryKeys(edges, label, pairs, isBoundary);
  band.pairKeys = distinctKeys(edgeKey);
  if (band.pairKeys.empty())
  {
    progress.report(1.0);
    return band;
  }

  // 2. The sources, and the faces near them that the band always holds (else the cut could not
  //    move a boundary).
  Fronts fronts = seedFronts(edges, isBoundary, edgeKey, band.pairKeys, eligible, nf);
  int64_t requiredCount = 0;
  const std::vector<uint8_t> required =
    requiredFaces(dual, fronts.dist, extent.rings, requiredCount);

  // 3. The nearest faces, up to the target size.
  const int64_t target = within != nullptr
    ? nf
    : static_cast<int64_t>(
        std::ceil(std::clamp(extent.fraction, 0.0, 1.0) * static_cast<double>(nf)));
  growBand(dual, centroids, eligible, fronts, required, requiredCount, target, band, progress);
  progress.report(1.0);
  return band;
}
} // namespace refinement
} // namespace detail
} // namespace tc
