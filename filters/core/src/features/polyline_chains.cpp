// SPDX-License-Identifier: BSD-3-Clause
#include "features/polyline_chains.h"

#include <cstddef>

namespace tc
{
namespace detail
{
namespace
{
// Segments at every node, CSR, in segment order.
struct NodeSegments
{
  std::vector<int64_t> offsets; // #nodes + 1
  std::vector<int64_t> segments;
  int64_t degree(int64_t node) const { return offsets[node + 1] - offsets[node]; }
};

NodeSegments nodeSegments(const std::vector<int64_t>& segmentNodes, int64_t numNodes)
{
  NodeSegments ns;
  ns.offsets.assign(numNodes + 1, 0);
  for (int64_t node : segmentNodes)
  {
    ++ns.offsets[node + 1];
  }
  for (int64_t k = 0; k < numNodes; ++k)
  {
    ns.offsets[k + 1] += ns.offsets[k];
  }
  ns.segments.resize(segmentNodes.size());
  std::vector<int64_t> fill(ns.offsets.begin(), ns.offsets.end() - 1);
  for (std::size_t s = 0; s < segmentNodes.size(); ++s)
  {
    ns.segments[fill[segmentNodes[s]]++] = static_cast<int64_t>(s / 2);
  }
  return ns;
}
} // namespace

Polylines chainSegments(const std::vector<int64_t>& segmentNodes, int64_t numNodes)
{
  const int64_t numSegments = static_cast<int64_t>(segmentNodes.size() / 2);
  const NodeSegments at = nodeSegments(segmentNodes, numNodes);
  std::vector<char> used(numSegments, 0);
  Polylines out;
  // From `start` along `seg` until a node that is not a plain link (or the start again).
  const auto walk = [&](int64_t start, int64_t seg)
  {
    int64_t node = start;
    out.nodes.push_back(start);
    while (true)
    {
      used[seg] = 1;
      node = segmentNodes[2 * seg] == node ? segmentNodes[2 * seg + 1] : segmentNodes[2 * seg];
      out.nodes.push_back(node);
      if (at.degree(node) != 2)
      {
        break;
      }
      int64_t next = -1;
      for (int64_t j = at.offsets[node]; j < at.offsets[node + 1]; ++j)
      {
        if (!used[at.segments[j]])
        {
          next = at.segments[j];
        }
      }
      if (next < 0)
      {
        break; // back at the start of a closed line
      }
      seg = next;
    }
    out.offsets.push_back(static_cast<int64_t>(out.nodes.size()));
  };
  // Open lines run from ends and branchings; what remains are closed loops.
  for (int64_t node = 0; node < numNodes; ++node)
  {
    if (at.degree(node) == 0 || at.degree(node) == 2)
    {
      continue;
    }
    for (int64_t j = at.offsets[node]; j < at.offsets[node + 1]; ++j)
    {
      if (!used[at.segments[j]])
      {
        walk(node, at.segments[j]);
      }
    }
  }
  for (int64_t s = 0; s < numSegments; ++s)
  {
    if (!used[s])
    {
      walk(segmentNodes[2 * s], s);
    }
  }
  return out;
}
} // namespace detail
} // namespace tc
