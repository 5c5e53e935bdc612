// SPDX-License-Identifier: BSD-3-Clause
/// @file kmeans.h
/// k-means with k-means++ seeding (Arthur and Vassilvitskii 2007) over the rows of the spectral
/// embedding, the grouping step of Feng et al. 2010, section 4.1. Deterministic for a seed,
/// whatever the number of threads.
#pragma once

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
/// Labels in [0, k) for the n x dim rows of x (row-major). Restarts (kmeansRestarts) run on a
/// seeded sample of at most kmeansSampleSize rows (and at least 50 per cluster; all rows when
/// fewer), in parallel, each with its own generator; the best inertia wins (the lowest restart
/// on ties), and its centers are refined on all rows. A cluster can be left empty only when x
/// has fewer distinct rows than k.
std::vector<int32_t> kmeans(const std::vector<double>& x, int64_t n, int dim, int k,
  const SpectralClusteringOptions& options, uint64_t seed, const Progress& progress);
} // namespace spectral
} // namespace detail
} // namespace tc
