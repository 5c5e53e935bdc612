// SPDX-License-Identifier: BSD-3-Clause
#include "features/corners.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace tc
{
namespace detail
{
namespace refinement
{
namespace
{
// The best (lowest) rank within `rings` rings of every vertex, one min-dilation over the
// one-ring per ring (sequential: a few operations per vertex and ring; abort is honoured
// between rings).
std::vector<int32_t> dilateRanks(
  const VertexRing& ring, const std::vector<int32_t>& rank, int rings, const Progress& progress)
{
  const int64_t nv = static_cast<int64_t>(rank.size());
  std::vector<int32_t> dilated = rank, next(nv);
  for (int r = 0; r < rings; ++r)
  {
    for (int64_t v = 0; v < nv; ++v)
    {
      int32_t m = dilated[v];
      for (int64_t j = ring.offsets[v]; j < ring.offsets[v + 1]; ++j)
      {
        m = std::min(m, dilated[ring.ids[j]]);
      }
      next[v] = m;
    }
    dilated.swap(next);
    progress.report(static_cast<double>(r + 1) / rings);
  }
  return dilated;
}

// 1 at every vertex where 3 or more feature-line edges meet (a closed line's first vertex is
// repeated at its end, so it counts twice as it should).
std::vector<uint8_t> lineJunctions(const FeatureRefinementResult& result, int64_t nv)
{
  std::vector<int32_t> lineDegree(nv, 0);
  for (int64_t l = 0; l < result.numLines(); ++l)
  {
    for (int64_t i = result.lineOffsets[l]; i + 1 < result.lineOffsets[l + 1]; ++i)
    {
      ++lineDegree[result.lineVertices[i]];
      ++lineDegree[result.lineVertices[i + 1]];
    }
  }
  std::vector<uint8_t> junction(nv, 0);
  for (int64_t v = 0; v < nv; ++v)
  {
    junction[v] = lineDegree[v] >= 3 ? 1 : 0;
  }
  return junction;
}
} // namespace

void findCorners(const EdgeTable& edges, const std::vector<int32_t>& byCurvature,
  const std::vector<double>& meanCurvature, const FeatureRefinementOptions& options,
  FeatureRefinementResult& result, const Progress& progress)
{
  const int64_t nv = static_cast<int64_t>(meanCurvature.size());
  // 1. The N-ring maxima of the rank.
  std::vector<int32_t> rank(nv, std::numeric_limits<int32_t>::max());
  for (size_t i = 0; i < byCurvature.size(); ++i)
  {
    rank[byCurvature[i]] = static_cast<int32_t>(i);
  }
  const std::vector<int32_t> dilated =
    dilateRanks(buildVertexRing(edges, nv), rank, std::max(0, options.cornerRings), progress);
  std::vector<int32_t> maxima;
  for (int32_t v : byCurvature)
  {
    if (dilated[v] == rank[v])
    {
      maxima.push_back(v);
    }
  }
  // 2. The top cornerFraction of them (maxima are in rank order) that reach the threshold.
  const int64_t keep = std::min<int64_t>(static_cast<int64_t>(maxima.size()),
    static_cast<int64_t>(std::ceil(
      std::clamp(options.cornerFraction, 0.0, 1.0) * static_cast<double>(maxima.size()))));
  for (int64_t i = 0; i < keep; ++i)
  {
    if (std::abs(meanCurvature[maxima[i]]) >= result.curvatureThreshold)
    {
      result.cornerVertex[maxima[i]] = 1;
    }
  }
  // 3. Junctions of feature lines.
  if (options.junctionCorners)
  {
    const std::vector<uint8_t> junction = lineJunctions(result, nv);
    for (int64_t v = 0; v < nv; ++v)
    {
      result.cornerVertex[v] |= junction[v];
    }
  }
  for (int64_t v = 0; v < nv; ++v)
  {
    if (result.cornerVertex[v])
    {
      result.corners.push_back(static_cast<int32_t>(v));
    }
  }
}
} // namespace refinement
} // namespace detail
} // namespace tc
