// SPDX-License-Identifier: BSD-3-Clause
/// @file face_sides.h
/// The sides of the faces on an edge of an EdgeTable (internal to the mesh preparation): side i
/// of face f runs from corner i to corner i + 1, and is edge faceEdges[3 f + i].
#pragma once

#include "tc/common/mesh_topology.h"

#include <cstdint>
#include <vector>

namespace tc
{
namespace detail
{
/// Side (0, 1, 2) of face f that lies on edge e.
inline int sideOf(const EdgeTable& edges, int64_t f, int32_t e)
{
  return edges.faceEdges[3 * f] == e ? 0 : (edges.faceEdges[3 * f + 1] == e ? 1 : 2);
}

/// True if f and g run along their common edge e in opposite directions (consistent).
inline bool consistentAcross(
  const std::vector<int32_t>& triangles, const EdgeTable& edges, int32_t e, int32_t f, int32_t g)
{
  const int i = sideOf(edges, f, e);
  const int j = sideOf(edges, g, e);
  return triangles[3 * f + i] != triangles[3 * g + j];
}
} // namespace detail
} // namespace tc
