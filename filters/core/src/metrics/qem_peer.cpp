// SPDX-License-Identifier: BSD-3-Clause
#include "tc/metrics/qem_peer.h"

#include "tc/common/errors.h"

#include <meshoptimizer.h>

#include <limits>
#include <string>
#include <vector>

namespace tc
{
TriMesh simplifyQem(const TriMesh& mesh, int64_t targetTriangles)
{
  if (targetTriangles < 0 || mesh.triangles.size() > std::numeric_limits<unsigned int>::max())
  {
    throw InputError("simplifyQem: the target must be >= 0 and the mesh below 2^32 indices "
                     "(target " +
      std::to_string(targetTriangles) + ")");
  }
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
  TriMesh out;
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
} // namespace tc
