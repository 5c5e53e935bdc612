// SPDX-License-Identifier: BSD-3-Clause
/// @file components.h
/// The edge-connected components of a mesh and their shares of the clusters: spectral
/// clustering (Feng et al. 2010, section 4.1) treats each component on its own, because no
/// cluster may span two of them.
#pragma once

#include "features/dual_graph.h"
#include "features/spectrum.h"

#include "tc/common/progress.h"
#include "tc/features/spectral_clustering.h"

#include <cstdint>
#include <functional>
#include <vector>

namespace tc
{
namespace detail
{
namespace spectral
{
struct Components
{
  std::vector<std::vector<int32_t>> faces; ///< #C faces of each component, ascending
  std::vector<int64_t> sizes;              ///< #C face counts
  std::vector<int> clusters;               ///< #C clusters of each component (allocateClusters)
  int64_t largest = 0;                     ///< the first component of the most faces
  int64_t count() const { return static_cast<int64_t>(sizes.size()); }
};

/// Components of the adjacent dual graph, numbered in the order of their first face, with
/// their shares of numClusters.
Components findComponents(const DualGraph& adjacent, int numClusters);

/// Clusters per component, in proportion to its face count (largest remainder). A component
/// whose share rounds to zero still gets one cluster (clusters never span components); those
/// extra clusters are taken back from components that got a rounding bonus (share rounded up),
/// so every component keeps at least floor(its share) and the total is numClusters whenever the
/// rounding leaves room. Never more clusters than faces.
/// @param[in] sizes  #C face counts
/// @return #C cluster counts
std::vector<int> allocateClusters(const std::vector<int64_t>& sizes, int numClusters);

/// The spectrum of component `component` (its faces ascending) with `ne` eigenpairs wanted: what
/// clusterComponents() embeds. Eq. 3's exact or Nystrom spectrum for spectralClustering(), eq. 5's
/// for tc::clusterDeformation.
using ComponentSpectrum = std::function<Spectrum(
  int64_t component, const std::vector<int32_t>& faces, int ne, const Progress& progress)>;

/// Clusters the faces of every component into result.clusterId (#F, preset by the caller),
/// numbered per component in the order of their first face (clusters left empty take no id), and
/// the eigenvalues of the largest component into result.eigenvalues (section 4.1): a component
/// of one cluster, or of no more faces than clusters, needs no spectrum; the others are embedded
/// (options.embedding, numEigenvectors) from spectrumOf and grouped by k-means (kmeans.h).
/// result.usedNystrom is set for a component above options.nystromThreshold.
/// @return the number of cluster ids used
int32_t clusterComponents(const ComponentSpectrum& spectrumOf, const Components& components,
  const SpectralClusteringOptions& options, SpectralClusteringResult& result,
  const Progress& progress);
} // namespace spectral
} // namespace detail
} // namespace tc
