// SPDX-License-Identifier: BSD-3-Clause
#include "features/components.h"

#include <algorithm>
#include <cmath>
#include <numeric>

namespace tc
{
namespace detail
{
namespace spectral
{
Components findComponents(const DualGraph& adjacent, int numClusters)
{
  const Pieces pieces = findPieces(adjacent, nullptr);
  const int64_t nf = static_cast<int64_t>(pieces.of.size());
  Components c;
  c.sizes = pieces.size;
  c.faces.resize(c.sizes.size());
  for (size_t i = 0; i < c.sizes.size(); ++i)
  {
    c.faces[i].reserve(c.sizes[i]);
  }
  for (int64_t f = 0; f < nf; ++f)
  {
    c.faces[pieces.of[f]].push_back(static_cast<int32_t>(f));
  }
  c.clusters = allocateClusters(c.sizes, numClusters);
  for (int64_t i = 1; i < c.count(); ++i)
  {
    if (c.sizes[i] > c.sizes[c.largest])
    {
      c.largest = i;
    }
  }
  return c;
}

std::vector<int> allocateClusters(const std::vector<int64_t>& sizes, int numClusters)
{
  const size_t nc = sizes.size();
  const double total = static_cast<double>(std::accumulate(sizes.begin(), sizes.end(), int64_t(0)));
  std::vector<double> quota(nc);
  std::vector<int> alloc(nc);
  int assigned = 0;
  for (size_t c = 0; c < nc; ++c)
  {
    quota[c] = numClusters * static_cast<double>(sizes[c]) / total;
    alloc[c] = static_cast<int>(std::floor(quota[c]));
    assigned += alloc[c];
  }
  std::vector<size_t> order(nc);
  std::iota(order.begin(), order.end(), 0);
  auto fraction = [&](size_t c) { return quota[c] - std::floor(quota[c]); };
  std::stable_sort(
    order.begin(), order.end(), [&](size_t a, size_t b) { return fraction(a) > fraction(b); });
  for (size_t i = 0; assigned < numClusters && i < nc; ++i, ++assigned)
  {
    ++alloc[order[i]];
  }
  int excess = 0;
  for (size_t c = 0; c < nc; ++c)
  {
    if (alloc[c] == 0)
    {
      alloc[c] = 1;
      ++excess;
    }
  }
  // Take back from the smallest rounding bonuses first.
  for (auto it = order.rbegin(); excess > 0 && it != order.rend(); ++it)
  {
    const size_t c = *it;
    if (alloc[c] > std::max(1, static_cast<int>(std::floor(quota[c]))))
    {
      --alloc[c];
      --excess;
    }
  }
  for (size_t c = 0; c < nc; ++c)
  {
    alloc[c] = static_cast<int>(std::min<int64_t>(alloc[c], sizes[c]));
  }
  return alloc;
}
} // namespace spectral
} // namespace detail
} // namespace tc
