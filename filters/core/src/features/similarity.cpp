// SPDX-License-Identifier: BSD-3-Clause
#include "features/similarity.h"

#include "features/statistics.h"

#include "tc/common/parallel.h"

#include <algorithm>
#include <cmath>

namespace tc
{
namespace detail
{
namespace spectral
{
std::vector<double> curvatureExponents(const std::vector<double>& faceMeanCurvature)
{
  const double sigmaK = curvatureSpread(faceMeanCurvature);
  std::vector<double> curvExp(faceMeanCurvature.size(), 0.0);
  if (sigmaK > 0.0)
  {
    for (size_t f = 0; f < faceMeanCurvature.size(); ++f)
    {
      curvExp[f] = std::abs(faceMeanCurvature[f]) / sigmaK;
    }
  }
  return curvExp;
}

ExactGraph buildExactGraph(const DualGraph& adjacent, const Components& components,
  const SpectralClusteringOptions& options, const Progress& progress)
{
  std::vector<uint8_t> exactFace(adjacent.offsets.size() - 1, 0);
  bool anyExact = false;
  for (int64_t c = 0; c < components.count(); ++c)
  {
    if (components.clusters[c] >= 2 && components.sizes[c] <= options.nystromThreshold)
    {
      anyExact = true;
      for (int32_t f : components.faces[c])
      {
        exactFace[f] = 1;
      }
    }
  }
  ExactGraph exact;
  if (!anyExact)
  {
    return exact;
  }
  const DistanceMoments near = distanceMoments(adjacent, exactFace);
  const double radius = options.extraEdgeFactor * (near.count > 0 ? near.sum / near.count : 0.0);
  exact.graph = radius > 0.0 ? addExtraEdges(adjacent, exactFace, radius, progress) : adjacent;
  const DistanceMoments used = distanceMoments(exact.graph, exactFace);
  const double sigmaD = standardDeviation(used.sum, used.squares, used.count);
  exact.invSigmaD = sigmaD > 0.0 ? 1.0 / sigmaD : 0.0;
  return exact;
}

LocalMatrix normalizedSimilarity(const std::vector<int32_t>& faces, const ExactGraph& exact,
  const std::vector<int32_t>& localId, const std::vector<double>& curvExp,
  const std::vector<double>& normals, const SpectralClusteringOptions& options,
  std::vector<double>& degree)
{
  const DualGraph& graph = exact.graph;
  const double invNormalSigma =
    options.exactNormalSigma > 0.0 ? 1.0 / options.exactNormalSigma : 0.0;
  const int64_t n = static_cast<int64_t>(faces.size());
  LocalMatrix N;
  N.offsets.resize(n + 1);
  N.offsets[0] = 0;
  for (int64_t i = 0; i < n; ++i)
  {
    const int32_t f = faces[i];
    N.offsets[i + 1] = N.offsets[i] + (graph.offsets[f + 1] - graph.offsets[f]);
  }
  N.ids.resize(N.offsets[n]);
  N.values.resize(N.offsets[n]);
  degree.assign(n, 0.0);
  parallel_for(n,
    [&](int64_t i)
    {
      const int32_t f = faces[i];
      int64_t slot = N.offsets[i];
      double sum = 0.0;
      for (int64_t k = graph.offsets[f]; k < graph.offsets[f + 1]; ++k, ++slot)
      {
        const int32_t g = graph.ids[k];
        // Eq. 3: w = beta exp(-(|k_i| + |k_j|) / sigma_k) exp(-dist / sigma_d).
        // With exactNormalSigma, times exp(-(1 - n_i . n_j) / exactNormalSigma).
        const double beta = graph.crest[k] ? options.crestBeta : 1.0;
        const double bend = invNormalSigma > 0.0
          ? (1.0 - normals[3 * f] * normals[3 * g] - normals[3 * f + 1] * normals[3 * g + 1] -
              normals[3 * f + 2] * normals[3 * g + 2]) *
            invNormalSigma
          : 0.0;
        const double w = beta *
          std::exp(std::max(
            kMinExponent, -(curvExp[f] + curvExp[g]) - graph.dist[k] * exact.invSigmaD - bend));
        N.ids[slot] = localId[g];
        N.values[slot] = w;
        sum += w;
      }
      degree[i] = std::max(sum, 1e-300);
    });
  parallel_for(n,
    [&](int64_t i)
    {
      for (int64_t k = N.offsets[i]; k < N.offsets[i + 1]; ++k)
      {
        N.values[k] /= std::sqrt(degree[i] * degree[N.ids[k]]);
      }
    });
  return N;
}
} // namespace spectral
} // namespace detail
} // namespace tc
