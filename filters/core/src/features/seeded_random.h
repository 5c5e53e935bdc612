// SPDX-License-Identifier: BSD-3-Clause
/// @file seeded_random.h
/// The random choices of spectral clustering (Nystrom samples, k-means samples and seeds), all
/// derived from SpectralClusteringOptions::seed so that equal seeds give identical results with
/// every standard library and any number of threads.
#pragma once

#include <algorithm>
#include <cstdint>
#include <numeric>
#include <random>
#include <utility>
#include <vector>

namespace tc
{
namespace detail
{
namespace spectral
{
/// SplitMix64 finalizer: independent seeds for every (component, purpose, restart).
inline uint64_t mixSeed(uint64_t seed, uint64_t a, uint64_t b = 0)
{
  uint64_t z = seed + 0x9E3779B97F4A7C15ull * (a + 1) + 0xBF58476D1CE4E5B9ull * (b + 1);
  z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ull;
  z = (z ^ (z >> 27)) * 0x94D049BB133111EBull;
  return z ^ (z >> 31);
}

/// Uniform in [0, 1) from the top 53 bits: the same numbers with every standard library
/// (std::uniform_real_distribution is implementation-defined).
inline double uniform01(std::mt19937_64& rng)
{
  return static_cast<double>(rng() >> 11) * (1.0 / 9007199254740992.0);
}

/// Uniform in [0, n).
inline int64_t uniformIndex(std::mt19937_64& rng, int64_t n)
{
  return std::min<int64_t>(n - 1, static_cast<int64_t>(uniform01(rng) * static_cast<double>(n)));
}

/// m distinct indices of [0, n), ascending (partial Fisher-Yates).
inline std::vector<int64_t> sampleIndices(int64_t n, int64_t m, uint64_t seed)
{
  std::vector<int64_t> all(n);
  std::iota(all.begin(), all.end(), 0);
  std::mt19937_64 rng(seed);
  for (int64_t i = 0; i < m; ++i)
  {
    std::swap(all[i], all[i + uniformIndex(rng, n - i)]);
  }
  all.resize(m);
  std::sort(all.begin(), all.end());
  return all;
}
} // namespace spectral
} // namespace detail
} // namespace tc
