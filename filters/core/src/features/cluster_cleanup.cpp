// SPDX-License-Identifier: BSD-3-Clause
#include "features/cluster_cleanup.h"

#include <algorithm>

namespace tc
{
namespace detail
{
namespace spectral
{
namespace
{
// The largest piece of every cluster, the lowest-numbered one on ties.
std::vector<int32_t> mainPieces(
  const Pieces& pieces, const std::vector<int32_t>& label, int32_t numClusters)
{
  std::vector<int32_t> main(numClusters, -1);
  for (int32_t p = 0; p < static_cast<int32_t>(pieces.size.size()); ++p)
  {
    int32_t& best = main[label[pieces.first[p]]];
    if (best < 0 || pieces.size[p] > pieces.size[best])
    {
      best = p;
    }
  }
  return main;
}

// Faces labelled -1 take the label of the neighbour that reaches them first, breadth-first
// from the labelled faces that border them (in face order).
void growIntoUnlabelled(const DualGraph& adj, std::vector<int32_t>& label)
{
  const int64_t nf = static_cast<int64_t>(label.size());
  std::vector<int32_t> queue;
  for (int64_t f = 0; f < nf; ++f)
  {
    if (label[f] < 0)
    {
      continue;
    }
    for (int64_t k = adj.offsets[f]; k < adj.offsets[f + 1]; ++k)
    {
      if (label[adj.ids[k]] < 0)
      {
        queue.push_back(static_cast<int32_t>(f));
        break;
      }
    }
  }
  for (size_t head = 0; head < queue.size(); ++head)
  {
    const int32_t f = queue[head];
    for (int64_t k = adj.offsets[f]; k < adj.offsets[f + 1]; ++k)
    {
      const int32_t g = adj.ids[k];
      if (label[g] < 0)
      {
        label[g] = label[f];
        queue.push_back(g);
      }
    }
  }
}
} // namespace

void keepLargestPieces(const DualGraph& adj, int32_t numClusters, std::vector<int32_t>& label)
{
  const Pieces pieces = findPieces(adj, &label);
  const std::vector<int32_t> main = mainPieces(pieces, label, numClusters);
  if (pieces.size.size() == static_cast<size_t>(numClusters))
  {
    return; // every cluster is one piece already
  }
  const int64_t nf = static_cast<int64_t>(label.size());
  for (int64_t f = 0; f < nf; ++f)
  {
    if (main[label[f]] != pieces.of[f])
    {
      label[f] = -1;
    }
  }
  growIntoUnlabelled(adj, label);
}

int32_t renumberByFirstFace(std::vector<int32_t>& label)
{
  int32_t maxLabel = -1;
  for (int32_t l : label)
  {
    maxLabel = std::max(maxLabel, l);
  }
  std::vector<int32_t> renumber(maxLabel + 1, -1);
  int32_t next = 0;
  for (int32_t& l : label)
  {
    int32_t& id = renumber[l];
    if (id < 0)
    {
      id = next++;
    }
    l = id;
  }
  return next;
}
} // namespace spectral
} // namespace detail
} // namespace tc
