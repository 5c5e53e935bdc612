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

double meanCurvatureAlong(const TriMesh& mesh, const Polylines& lines, int64_t begin, int64_t end,
  const std::vector<double>& meanCurvature)
{
  double weighted = 0.0, length = 0.0;
  for (int64_t i = begin; i + 1 < end; ++i)
  {
    const int64_t a = lines.nodes[i], b = lines.nodes[i + 1];
    const double l = vertexDistance(mesh, a, b);
    weighted += l * 0.5 * (std::abs(meanCurvature[a]) + std::abs(meanCurvature[b]));
    length += l;
  }
  return length > 0.0 ? weighted / length : 0.0;
}

void appendLine(const TriMesh& mesh, const Polylines& lines, int64_t begin, int64_t end,
  const std::vector<double>& meanCurvature, FeatureRefinementResult& result)
{
  for (int64_t i = begin; i < end; ++i)
  {
    const int32_t v = static_cast<int32_t>(lines.nodes[i]);
    result.lineVertices.push_back(v);
    result.featureVertex[v] = 1;
  }
  result.lineOffsets.push_back(static_cast<int64_t>(result.lineVertices.size()));
  result.lineCurvature.push_back(meanCurvatureAlong(mesh, lines, begin, end, meanCurvature));
}

void keepFeatureSegments(const TriMesh& mesh, const Polylines& segments,
  const std::vector<double>& meanCurvature, FeatureRefinementResult& result)
{
  const int64_t numSegments = static_cast<int64_t>(segments.offsets.size()) - 1;
  for (int64_t s = 0; s < numSegments; ++s)
  {
    const int64_t begin = segments.offsets[s], end = segments.offsets[s + 1];
    if (meanCurvatureAlong(mesh, segments, begin, end, meanCurvature) >= result.curvatureThreshold)
    {
      appendLine(mesh, segments, begin, end, meanCurvature, result);
    }
  }
}
} // namespace refinement
} // namespace detail
} // namespace tc
