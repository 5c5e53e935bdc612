// SPDX-License-Identifier: BSD-3-Clause
#include "features/feature_lines.h"

#include "features/face_geometry.h"

#include <cmath>

namespace tc
{
namespace detail
{
namespace refinement
{
Polylines boundarySegments(
  const EdgeTable& edges, const std::vector<uint8_t>& isBoundary, int64_t nv)
{
  std::vector<int64_t> segmentNodes;
  const int64_t ne = edges.numEdges();
  for (int64_t e = 0; e < ne; ++e)
  {
    if (isBoundary[e])
    {
      segmentNodes.push_back(edges.vertices[2 * e]);
      segmentNodes.push_back(edges.vertices[2 * e + 1]);
    }
  }
  return chainSegments(segmentNodes, nv);
}

void keepFeatureSegments(const TriMesh& mesh, const Polylines& segments,
  const std::vector<double>& meanCurvature, FeatureRefinementResult& result)
{
  auto meanAlong = [&](int64_t begin, int64_t end)
  {
    double weighted = 0.0, length = 0.0;
    for (int64_t i = begin; i + 1 < end; ++i)
    {
      const int64_t a = segments.nodes[i], b = segments.nodes[i + 1];
      const double l = vertexDistance(mesh, a, b);
      weighted += l * 0.5 * (std::abs(meanCurvature[a]) + std::abs(meanCurvature[b]));
      length += l;
    }
    return length > 0.0 ? weighted / length : 0.0;
  };
  const int64_t numSegments = static_cast<int64_t>(segments.offsets.size()) - 1;
  for (int64_t s = 0; s < numSegments; ++s)
  {
    const int64_t begin = segments.offsets[s], end = segments.offsets[s + 1];
    if (!(meanAlong(begin, end) >= result.curvatureThreshold))
    {
      continue;
    }
    for (int64_t i = begin; i < end; ++i)
    {
      const int32_t v = static_cast<int32_t>(segments.nodes[i]);
      result.lineVertices.push_back(v);
      result.featureVertex[v] = 1;
    }
    result.lineOffsets.push_back(static_cast<int64_t>(result.lineVertices.size()));
    result.lineCurvature.push_back(meanAlong(begin, end));
  }
}
} // namespace refinement
} // namespace detail
} // namespace tc
