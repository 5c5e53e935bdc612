// SPDX-License-Identifier: BSD-3-Clause
/// @file union_find.h
/// Union-find (internal): the mesh preparation's corners into fans (non-manifold detection and
/// splitting), faces into components and orientation patches; the multilevel mesh's clusters
/// into their connected parts. The root of a set is its lowest
/// element, so results do not depend on the order of the unions.
#pragma once

#include <algorithm>
#include <cstdint>
#include <numeric>
#include <utility>
#include <vector>

namespace tc
{
namespace detail
{
/// Union-find over 0 .. n-1 (corners, faces).
class DisjointSets
{
public:
  explicit DisjointSets(int64_t n)
    : Parent(n)
  {
    std::iota(Parent.begin(), Parent.end(), 0);
  }

  int32_t find(int32_t x)
  {
    while (Parent[x] != x)
    {
      Parent[x] = Parent[Parent[x]];
      x = Parent[x];
    }
    return x;
  }

  void unite(int32_t a, int32_t b)
  {
    a = find(a);
    b = find(b);
    if (a < b)
    {
      Parent[b] = a;
    }
    else if (b < a)
    {
      Parent[a] = b;
    }
  }

private:
  std::vector<int32_t> Parent;
};

/// Union-find that also keeps whether each element is flipped relative to its root (the
/// lowest element of its set): the orientation of faces within a patch.
class ParitySets
{
public:
  explicit ParitySets(int64_t n)
    : Parent(n)
    , Parity(n, 0)
  {
    std::iota(Parent.begin(), Parent.end(), 0);
  }

  /// Root of x and the parity of x relative to it.
  std::pair<int32_t, uint8_t> find(int32_t x)
  {
    int32_t root = x;
    uint8_t parity = 0;
    while (Parent[root] != root)
    {
      parity ^= Parity[root];
      root = Parent[root];
    }
    for (uint8_t p = parity; Parent[x] != x;)
    {
      const int32_t next = Parent[x];
      const uint8_t step = Parity[x];
      Parent[x] = root;
      Parity[x] = p;
      p ^= step;
      x = next;
    }
    return { root, parity };
  }

  /// Records that a and b differ by `parity`; false if that contradicts what is known.
  bool unite(int32_t a, int32_t b, uint8_t parity)
  {
    const auto [ra, pa] = find(a);
    const auto [rb, pb] = find(b);
    if (ra == rb)
    {
      return (pa ^ pb) == parity;
    }
    const int32_t low = std::min(ra, rb);
    const int32_t high = std::max(ra, rb);
    Parent[high] = low;
    Parity[high] = static_cast<uint8_t>(pa ^ pb ^ parity);
    return true;
  }

private:
  std::vector<int32_t> Parent;
  std::vector<uint8_t> Parity;
};
} // namespace detail
} // namespace tc
