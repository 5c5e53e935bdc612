// SPDX-License-Identifier: BSD-3-Clause
#include "tc/common/mesh_topology.h"

#include <algorithm>
#include <numeric>

namespace tc
{
VertexFaces buildVertexFaces(const std::vector<int32_t>& triangles, int64_t numPoints)
{
  VertexFaces vf;
  vf.offsets.assign(numPoints + 1, 0);
  for (int32_t v : triangles)
  {
    ++vf.offsets[v + 1];
  }
  std::partial_sum(vf.offsets.begin(), vf.offsets.end(), vf.offsets.begin());
  vf.faceIds.resize(triangles.size());
  std::vector<int64_t> fill(vf.offsets.begin(), vf.offsets.end() - 1);
  const int64_t nf = static_cast<int64_t>(triangles.size() / 3);
  for (int64_t f = 0; f < nf; ++f)
  {
    for (int i = 0; i < 3; ++i)
    {
      vf.faceIds[fill[triangles[3 * f + i]]++] = static_cast<int32_t>(f);
    }
  }
  return vf;
}

EdgeTable buildEdgeTable(const std::vector<int32_t>& triangles)
{
  // Sort (min, max, half-edge) keys once; equal keys are one undirected edge.
  const int64_t nh = static_cast<int64_t>(triangles.size());
  std::vector<uint64_t> keys(nh);
  for (int64_t h = 0; h < nh; ++h)
  {
    const int64_t f = h / 3;
    const uint32_t a = static_cast<uint32_t>(triangles[h]);
    const uint32_t b = static_cast<uint32_t>(triangles[3 * f + (h % 3 + 1) % 3]);
    keys[h] = (static_cast<uint64_t>(std::min(a, b)) << 32) | std::max(a, b);
  }
  std::vector<int64_t> order(nh);
  std::iota(order.begin(), order.end(), 0);
  std::sort(order.begin(), order.end(),
    [&](int64_t x, int64_t y) { return keys[x] < keys[y] || (keys[x] == keys[y] && x < y); });

  EdgeTable et;
  et.faceEdges.resize(nh);
  et.edgeFaces.resize(nh);
  et.faceOffsets.reserve(nh / 2 + 2);
  et.vertices.reserve(nh);
  for (int64_t i = 0; i < nh; ++i)
  {
    const int64_t h = order[i];
    if (i == 0 || keys[h] != keys[order[i - 1]])
    {
      et.faceOffsets.push_back(i);
      et.vertices.push_back(static_cast<int32_t>(keys[h] >> 32));
      et.vertices.push_back(static_cast<int32_t>(keys[h] & 0xffffffffu));
    }
    et.faceEdges[h] = static_cast<int32_t>(et.faceOffsets.size() - 1);
    et.edgeFaces[i] = static_cast<int32_t>(h / 3);
  }
  et.faceOffsets.push_back(nh);
  return et;
}

VertexRing buildVertexRing(const EdgeTable& edges, int64_t numPoints)
{
  VertexRing ring;
  ring.offsets.assign(numPoints + 1, 0);
  const int64_t ne = edges.numEdges();
  for (int64_t e = 0; e < ne; ++e)
  {
    ++ring.offsets[edges.vertices[2 * e] + 1];
    ++ring.offsets[edges.vertices[2 * e + 1] + 1];
  }
  std::partial_sum(ring.offsets.begin(), ring.offsets.end(), ring.offsets.begin());
  ring.ids.resize(2 * ne);
  std::vector<int64_t> fill(ring.offsets.begin(), ring.offsets.end() - 1);
  for (int64_t e = 0; e < ne; ++e)
  {
    const int32_t a = edges.vertices[2 * e];
    const int32_t b = edges.vertices[2 * e + 1];
    ring.ids[fill[a]++] = b;
    ring.ids[fill[b]++] = a;
  }
  for (int64_t v = 0; v < numPoints; ++v)
  {
    std::sort(ring.ids.begin() + ring.offsets[v], ring.ids.begin() + ring.offsets[v + 1]);
  }
  return ring;
}
std::vector<int32_t> labelBoundaryEdges(
  const EdgeTable& edges, const std::vector<int32_t>& faceLabels)
{
  std::vector<int32_t> pairs;
  const int64_t ne = edges.numEdges();
  for (int64_t e = 0; e < ne; ++e)
  {
    const int32_t first = faceLabels[edges.edgeFaces[edges.faceOffsets[e]]];
    for (int64_t k = edges.faceOffsets[e] + 1; k < edges.faceOffsets[e + 1]; ++k)
    {
      if (faceLabels[edges.edgeFaces[k]] != first)
      {
        pairs.push_back(edges.vertices[2 * e]);
        pairs.push_back(edges.vertices[2 * e + 1]);
        break;
      }
    }
  }
  return pairs;
}
} // namespace tc
