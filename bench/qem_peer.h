// SPDX-License-Identifier: BSD-3-Clause
// The QEM peer of the benchmarks: meshoptimizer's meshopt_simplify, the simplifier a game
// engine's LOD chain (gltfpack) is made with.
#pragma once

#include "tc/common/mesh.h"

#include <meshoptimizer.h>

#include <cstdint>
#include <vector>

namespace tcbench
{
/// meshoptimizer's quadric simplification of `mesh` to at most `targetTriangles` triangles,
/// returned as a mesh of the vertices it still uses; `mesh` itself for a target at or above
/// its count (meshopt_simplify requires a target no larger than its input).
inline tc::TriMesh SimplifyQem(const tc::TriMesh& mesh, int64_t targetTriangles)
{
  if (targetTriangles >= mesh.numTriangles())
  {
    return mesh;
  }
  std::vector<float> positions(mesh.points.begin(), mesh.points.end());
  std::vector<unsigned int> indices(mesh.triangles.begin(), mesh.triangles.end());
  std::vector<unsigned int> kept(indices.size());
  // target_error 1.0 (relative to the mesh extent): only the triangle count stops it.
  const size_t count = meshopt_simplify(kept.data(), indices.data(), indices.size(),
    positions.data(), static_cast<size_t>(mesh.numPoints()), 3 * sizeof(float),
    3 * static_cast<size_t>(targetTriangles), 1.0f);
  kept.resize(count);
  std::vector<int32_t> newId(static_cast<size_t>(mesh.numPoints()), -1);
  tc::TriMesh out;
  for (const unsigned int v : kept)
  {
    if (newId[v] < 0)
    {
      newId[v] = static_cast<int32_t>(out.numPoints());
      out.points.insert(out.points.end(), &mesh.points[3 * static_cast<size_t>(v)],
        &mesh.points[3 * static_cast<size_t>(v)] + 3);
    }
    out.triangles.push_back(newId[v]);
  }
  return out;
}
} // namespace tcbench
