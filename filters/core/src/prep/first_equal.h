// SPDX-License-Identifier: BSD-3-Clause
/// @file first_equal.h
/// Finding repeated items in linear time (internal to the mesh preparation): duplicate points
/// and duplicate triangles.
#pragma once

#include <cstdint>
#include <vector>

namespace tc
{
namespace detail
{
/// For items 0 .. n-1 in order, the first item equal to each (itself if none before it), with
/// an open-addressing hash table: linear time, where sorting would cost n log n.
/// @param hash   hash(i): 64 well-spread bits of item i (equal items, equal hashes)
/// @param equal  equal(i, j): whether items i and j are the same
template <typename HashFn, typename EqualFn>
std::vector<int32_t> firstEqual(int64_t n, const HashFn& hash, const EqualFn& equal)
{
  uint64_t capacity = 16;
  while (capacity < 2 * static_cast<uint64_t>(n))
  {
    capacity *= 2;
  }
  const uint64_t mask = capacity - 1;
  std::vector<int32_t> table(capacity, -1);
  std::vector<int32_t> first(n);
  for (int32_t i = 0; i < n; ++i)
  {
    for (uint64_t slot = hash(i) & mask;; slot = (slot + 1) & mask)
    {
      const int32_t j = table[slot];
      if (j < 0)
      {
        table[slot] = i;
        first[i] = i;
        break;
      }
      if (equal(i, j))
      {
        first[i] = j;
        break;
      }
    }
  }
  return first;
}
} // namespace detail
} // namespace tc
