// SPDX-License-Identifier: BSD-3-Clause
/// @file cluster_cleanup.h
/// The clusters after k-means (Feng et al. 2010, section 4.1): one connected region each and
/// numbered without gaps. k-means in the embedding does not see connectivity, and a stray piece
/// would give the boundary stage (section 4.2) a closed curve around nothing.
#pragma once

#include "features/dual_graph.h"

#include <cstdint>
#include <vector>

namespace tc
{
namespace detail
{
namespace spectral
{
/// Every cluster keeps its largest edge-connected piece (the lowest-numbered one on ties); the
/// faces of its other pieces join the clusters around them, grown breadth-first from the kept
/// pieces (a face takes the cluster of the neighbour that reaches it first, in face order). Each
/// cluster is then one connected region and no cluster disappears.
/// @param[in]     adj          the adjacent dual graph
/// @param[in,out] label        #F cluster ids in [0, numClusters)
void keepLargestPieces(const DualGraph& adj, int32_t numClusters, std::vector<int32_t>& label);

/// Cluster ids in the order of the lowest face of each cluster, with no gap.
/// @param[in,out] label  #F cluster ids >= 0
/// @return the number of clusters
int32_t renumberByFirstFace(std::vector<int32_t>& label);
} // namespace spectral
} // namespace detail
} // namespace tc
