// SPDX-License-Identifier: BSD-3-Clause
/// @file splitmix.h
/// SplitMix64 (Steele, Lea and Flood 2014). Its finalizer spreads 64 bits into a hash (the hash
/// tables of the mesh preparation); its generator gives one reproducible stream per key in two
/// words of state (the sample positions of the surface distance, independent of the thread).
#pragma once

#include <cstdint>

namespace tc
{
namespace detail
{
/// The finalizer of SplitMix64: mixes the 64 bits of h into a well-spread hash.
inline uint64_t mix64(uint64_t h)
{
  h ^= h >> 30;
  h *= 0xBF58476D1CE4E5B9ull;
  h ^= h >> 27;
  h *= 0x94D049BB133111EBull;
  return h ^ (h >> 31);
}

/// The next number of the SplitMix64 stream whose state is `state` (advanced).
inline uint64_t splitMix(uint64_t& state)
{
  return mix64(state += 0x9E3779B97F4A7C15ull);
}
} // namespace detail
} // namespace tc
