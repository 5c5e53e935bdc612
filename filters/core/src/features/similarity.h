// SPDX-License-Identifier: BSD-3-Clause
/// @file similarity.h
/// The similarity of eq. 3 of Feng et al. 2010 on the dual graph,
/// w_ij = beta exp(-(|k_i| + |k_j|) / sigma_k) exp(-dist(f_i, f_j) / sigma_d), normalized to
/// N = D^-1/2 W D^-1/2 (eq. 2): its parameters over the whole mesh, and its matrix over one
/// component.
#pragma once

#include "features/components.h"
#include "features/dual_graph.h"
#include "features/spectrum.h"

#include "tc/common/progress.h"
#include "tc/features/spectral_clustering.h"

#include <cstdint>
#include <vector>

namespace tc
{
namespace detail
{
namespace spectral
{
/// |k_f| / sigma_k per face, sigma_k the standard deviation of |faceMeanCurvature| over all
/// faces. All 0 when sigma_k = 0 (a plane, a sphere): the factor is then the same for every
/// pair and cancels in D^-1/2 W D^-1/2 (no 0/0).
/// @return #F
std::vector<double> curvatureExponents(const std::vector<double>& faceMeanCurvature);

/// The graph of the components clustered exactly (at least 2 clusters, at most
/// nystromThreshold faces) and eq. 3's sigma_d on it.
struct ExactGraph
{
  DualGraph graph;        ///< the adjacent graph with the extra edges of section 4.2
  double invSigmaD = 0.0; ///< 1 / sigma_d; 0 when all distances are equal (constant factor)
};

/// Extra edges below extraEdgeFactor times the mean adjacent distance over the faces of the
/// exact components; sigma_d is the standard deviation of dist over that graph's edges.
ExactGraph buildExactGraph(const DualGraph& adjacent, const Components& components,
  const SpectralClusteringOptions& options, const Progress& progress);

/// Eq. 3 on every edge of `graph` that leaves one component, normalized (eq. 2). With
/// exactNormalSigma > 0 each weight is also multiplied by exp(-(1 - n_i . n_j) /
/// exactNormalSigma).
/// @param[in]  faces    global ids of the component's faces
/// @param[in]  localId  #F index of each face of the component in `faces`
/// @param[in]  curvExp  #F curvatureExponents()
/// @param[in]  normals  #F x 3 unit face normals
/// @param[out] degree   #faces D, the weight sums of the rows (at least 1e-300)
/// @return N over local ids
LocalMatrix normalizedSimilarity(const std::vector<int32_t>& faces, const ExactGraph& exact,
  const std::vector<int32_t>& localId, const std::vector<double>& curvExp,
  const std::vector<double>& normals, const SpectralClusteringOptions& options,
  std::vector<double>& degree);
} // namespace spectral
} // namespace detail
} // namespace tc
