// SPDX-License-Identifier: BSD-3-Clause
/// @file spectrum.h
/// The largest eigenpairs of the normalized similarity N = D^-1/2 W D^-1/2 (Feng et al. 2010,
/// section 4.1, eq. 2 and 3) of one mesh component: from the exact sparse matrix over the dual
/// graph (Spectra), or from the Nystrom approximation (Fowlkes et al. 2004) above a face-count
/// threshold. Every Eigen and Spectra solve of spectral clustering is behind this header, so
/// that one translation unit compiles them.
#pragma once

#include "features/dual_graph.h"

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
/// Eigenpairs of D^-1/2 W D^-1/2 of one component and the degrees D.
struct Spectrum
{
  std::vector<double> values;  ///< Ne, descending
  std::vector<double> vectors; ///< n x Ne row-major, local face order
  std::vector<double> degree;  ///< n
};

/// The exact spectrum of one component: eq. 3 on every edge of the exact graph that leaves
/// the component's faces (with exactNormalSigma > 0 also times exp(-(1 - n_i . n_j) /
/// exactNormalSigma)), normalized to N (eq. 2), and its ne largest eigenpairs (at most the
/// face count): a dense solve for small components, else shift-invert Lanczos on the
/// normalized Laplacian I - N (sparse LDLT), with Lanczos on N itself as the fallback.
/// @param[in] faces    global ids of the component's faces, ascending
/// @param[in] localId  #F index of each face of the component in `faces`
/// @param[in] curvExp  #F curvatureExponents()
/// @param[in] normals  #F x 3 unit face normals
/// @throws std::runtime_error when no eigensolver converges
Spectrum exactSpectrum(const std::vector<int32_t>& faces, const ExactGraph& exact,
  const std::vector<int32_t>& localId, const std::vector<double>& curvExp,
  const std::vector<double>& normals, int ne, const SpectralClusteringOptions& options,
  const Progress& progress);

/// The exact spectrum of one component for similarities given on the graph's entries (the
/// deformation similarity of eq. 5, tc::clusterDeformation): W over the component's faces,
/// normalized to N (eq. 2), and its ne largest eigenpairs, solved as exactSpectrum() does.
/// @param[in] faces    global ids of the component's faces, ascending
/// @param[in] graph    symmetric dual graph whose rows of `faces` stay inside the component
/// @param[in] weights  one positive similarity per entry of graph.ids, equal in both directions
/// @param[in] localId  #F index of each face of the component in `faces`
/// @throws std::runtime_error when no eigensolver converges
Spectrum weightedSpectrum(const std::vector<int32_t>& faces, const DualGraph& graph,
  const std::vector<double>& weights, const std::vector<int32_t>& localId, int ne,
  const Progress& progress);

/// The Nystrom approximation of the spectrum of one component: eq. 3 with the Euclidean
/// distance of centroids and a normal term in place of beta (nystromNormalSigma), sampled on
/// nystromSamples faces, extended to all faces in rank nystromRank (Fowlkes et al., section 3;
/// the details beside the definition).
/// @param[in] faces  global ids of the component's faces, ascending
/// @param[in] cen    #F x 3 centroids
/// @param[in] nrm    #F x 3 unit normals
/// @param[in] ce     #F |kappa| / sigma_k
/// @param[in] seed   of the sample choice
Spectrum nystromSpectrum(const std::vector<int32_t>& faces, const std::vector<double>& cen,
  const std::vector<double>& nrm, const std::vector<double>& ce, int ne,
  const SpectralClusteringOptions& options, uint64_t seed, const Progress& progress);
} // namespace spectral
} // namespace detail
} // namespace tc
