// SPDX-License-Identifier: BSD-3-Clause
#include "features/crease_lines.h"

#include "detail/geometry2d.h"
#include "features/feature_lines.h"
#include "features/polyline_chains.h"

#include <algorithm>
#include <unordered_set>

namespace tc
{
namespace detail
{
namespace refinement
{
namespace
{
uint64_t pairKey(int64_t a, int64_t b)
{
  return (static_cast<uint64_t>(std::min(a, b)) << 32) | static_cast<uint64_t>(std::max(a, b));
}

// The edges `keep` accepts that no kept line holds, as segment node pairs in edge-table order.
template <class Keep>
std::vector<int64_t> freeSegments(
  const EdgeTable& edges, const FeatureRefinementResult& result, Keep&& keep)
{
  std::unordered_set<uint64_t> onLine;
  for (int64_t l = 0; l < result.numLines(); ++l)
  {
    for (int64_t i = result.lineOffsets[l]; i + 1 < result.lineOffsets[l + 1]; ++i)
    {
      onLine.insert(pairKey(result.lineVertices[i], result.lineVertices[i + 1]));
    }
  }
  std::vector<int64_t> segments;
  for (int64_t e = 0; e < edges.numEdges(); ++e)
  {
    const int64_t a = edges.vertices[2 * e], b = edges.vertices[2 * e + 1];
    if (edges.valence(e) == 2 && keep(e) && !onLine.count(pairKey(a, b)))
    {
      segments.push_back(a);
      segments.push_back(b);
    }
  }
  return segments;
}

// The chains cut at every inner node that `stop` marks; a closed chain through such a node is
// first turned to start there, so that it becomes an open path from and to it.
Polylines splitAt(const Polylines& chains, const std::vector<uint8_t>& stop)
{
  Polylines out;
  for (size_t c = 0; c + 1 < chains.offsets.size(); ++c)
  {
    std::vector<int64_t> path(
      chains.nodes.begin() + chains.offsets[c], chains.nodes.begin() + chains.offsets[c + 1]);
    if (path.size() > 2 && path.front() == path.back())
    {
      const auto at = std::find_if(
        path.begin(), path.end() - 1, [&](int64_t v) { return stop[static_cast<size_t>(v)]; });
      std::rotate(path.begin(), at, path.end() - 1);
      path.back() = path.front();
    }
    out.nodes.push_back(path.front());
    for (size_t i = 1; i < path.size(); ++i)
    {
      out.nodes.push_back(path[i]);
      if (i + 1 < path.size() && stop[static_cast<size_t>(path[i])])
      {
        out.offsets.push_back(static_cast<int64_t>(out.nodes.size()));
        out.nodes.push_back(path[i]);
      }
    }
    out.offsets.push_back(static_cast<int64_t>(out.nodes.size()));
  }
  return out;
}
// The chains of `segments`, cut at the vertices of the kept lines, appended to the lines when
// they have at least minEdges edges.
void appendChains(const TriMesh& mesh, const std::vector<int64_t>& segments,
  const std::vector<double>& meanCurvature, int minEdges, FeatureRefinementResult& result)
{
  const Polylines chains = splitAt(chainSegments(segments, mesh.numPoints()), result.featureVertex);
  for (size_t c = 0; c + 1 < chains.offsets.size(); ++c)
  {
    const int64_t begin = chains.offsets[c], end = chains.offsets[c + 1];
    if (end - begin - 1 >= minEdges)
    {
      appendLine(mesh, chains, begin, end, meanCurvature, result);
    }
  }
}
} // namespace

void addCreaseLines(const TriMesh& mesh, const EdgeTable& edges,
  const std::vector<double>& dihedral, const std::vector<double>& meanCurvature,
  const FeatureRefinementOptions& options, FeatureRefinementResult& result)
{
  if (!(options.creaseLineAngle > 0.0))
  {
    return;
  }
  const double angle = options.creaseLineAngle * kPi / 180.0;
  const std::vector<int64_t> segments =
    freeSegments(edges, result, [&](int64_t e) { return dihedral[e] >= angle; });
  appendChains(mesh, segments, meanCurvature, std::max(1, options.creaseLineEdges), result);
}

void addSeamLines(const TriMesh& mesh, const EdgeTable& edges,
  const std::vector<double>& meanCurvature, const FeatureRefinementOptions& options,
  FeatureRefinementResult& result)
{
  if (options.seamSides.empty())
  {
    return;
  }
  std::vector<uint8_t> seamEdge(static_cast<size_t>(edges.numEdges()), 0);
  for (size_t f = 0; f < options.seamSides.size(); ++f)
  {
    for (size_t k = 0; k < 3; ++k)
    {
      if (options.seamSides[f] & (1u << k))
      {
        seamEdge[static_cast<size_t>(edges.faceEdges[3 * f + k])] = 1;
      }
    }
  }
  const std::vector<int64_t> segments =
    freeSegments(edges, result, [&](int64_t e) { return seamEdge[static_cast<size_t>(e)] != 0; });
  appendChains(mesh, segments, meanCurvature, 1, result);
}

void addSkinLines(const TriMesh& mesh, const EdgeTable& edges,
  const std::vector<double>& meanCurvature, const FeatureRefinementOptions& options,
  FeatureRefinementResult& result)
{
  const std::vector<int32_t>& region = options.skinRegions;
  if (region.empty())
  {
    return;
  }
  const std::vector<int64_t> segments = freeSegments(edges, result,
    [&](int64_t e)
    {
      const int32_t* f = edges.edgeFaces.data() + edges.faceOffsets[e];
      return region[static_cast<size_t>(f[0])] != region[static_cast<size_t>(f[1])];
    });
  appendChains(mesh, segments, meanCurvature, 1, result);
}
} // namespace refinement
} // namespace detail
} // namespace tc
