// SPDX-License-Identifier: BSD-3-Clause
#include "features/boundary_straightening.h"

#include "features/refinement_band.h"

#include <algorithm>

namespace tc
{
namespace detail
{
namespace refinement
{
namespace
{
// The side k of a face that is not a boundary edge while its other two sides are (-1: none).
// Side k runs from corner k to corner k + 1: the two boundary sides meet at corner k + 2.
int zigZagSide(const int32_t* side, const std::vector<uint8_t>& boundary)
{
  int k = -1;
  for (int i = 0; i < 3; ++i)
  {
    if (!boundary[side[i]] && boundary[side[(i + 1) % 3]] && boundary[side[(i + 2) % 3]])
    {
      k = i;
    }
  }
  return k;
}
} // namespace

int64_t straightenBoundaries(const TriMesh& mesh, const EdgeTable& edges,
  const std::vector<double>& dihedral, double creaseAngle, int64_t numClusters,
  std::vector<int32_t>& label)
{
  const int64_t nf = mesh.numTriangles();
  const int64_t ne = edges.numEdges();
  std::vector<uint8_t> boundary = boundaryEdges(edges, label);
  std::vector<int32_t> degree(mesh.numPoints(), 0);
  for (int64_t e = 0; e < ne; ++e)
  {
    if (boundary[e])
    {
      ++degree[edges.vertices[2 * e]];
      ++degree[edges.vertices[2 * e + 1]];
    }
  }
  std::vector<int64_t> size(numClusters, 0);
  for (int32_t l : label)
  {
    ++size[l];
  }
  auto across = [&](int64_t e, int64_t f)
  {
    const int32_t a = edges.edgeFaces[edges.faceOffsets[e]];
    return a == f ? edges.edgeFaces[edges.faceOffsets[e] + 1] : a;
  };
  auto crease = [&](int64_t e) { return dihedral[e] >= creaseAngle; };
  int64_t changed = 0;
  for (bool again = true; again;)
  {
    again = false;
    for (int64_t f = 0; f < nf; ++f)
    {
      const int32_t* side = &edges.faceEdges[3 * f];
      if (edges.valence(side[0]) != 2 || edges.valence(side[1]) != 2 || edges.valence(side[2]) != 2)
      {
        continue;
      }
      const int k = zigZagSide(side, boundary);
      if (k < 0)
      {
        continue;
      }
      const int64_t vw = side[k], a = side[(k + 1) % 3], b = side[(k + 2) % 3];
      const int32_t u = mesh.triangles[3 * f + (k + 2) % 3];
      const int32_t other = label[across(a, f)];
      if (label[across(b, f)] != other || degree[u] != 2 || size[label[f]] == 1 ||
        ((crease(a) || crease(b)) && dihedral[vw] < std::max(dihedral[a], dihedral[b])))
      {
        continue;
      }
      --size[label[f]];
      ++size[other];
      label[f] = other;
      boundary[a] = boundary[b] = 0;
      boundary[vw] = 1;
      degree[u] = 0;
      ++changed;
      again = true;
    }
  }
  return changed;
}
} // namespace refinement
} // namespace detail
} // namespace tc
