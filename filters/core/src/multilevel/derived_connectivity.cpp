// SPDX-License-Identifier: BSD-3-Clause
// The connectivity of a level of the multilevel mesh, derived from M0 and the clusters
// (Kircher and Garland 2005, section 3): a face of M0 maps to its corners' parents and exists
// at the level unless it degenerates; so does an edge.
#include "multilevel/multilevel_internal.h"

#include <algorithm>
#include <array>
#include <utility>

namespace tc
{
namespace detail
{
namespace multilevel
{
void uniqueEdges(const TriMesh& mesh, std::vector<int32_t>& edges, std::vector<int32_t>& faceCount,
  std::vector<int32_t>& firstFace)
{
  // (a, b, face) per side, sorted: runs of one pair are one edge, its lowest face first.
  std::vector<std::array<int32_t, 3>> sides;
  sides.reserve(mesh.triangles.size());
  for (int32_t f = 0; f < static_cast<int32_t>(mesh.numTriangles()); ++f)
  {
    for (int i = 0; i < 3; ++i)
    {
      const int32_t a = mesh.triangles[3 * f + i], b = mesh.triangles[3 * f + (i + 1) % 3];
      sides.push_back({ std::min(a, b), std::max(a, b), f });
    }
  }
  std::sort(sides.begin(), sides.end());
  edges.clear();
  faceCount.clear();
  firstFace.clear();
  for (size_t i = 0; i < sides.size(); ++i)
  {
    if (i > 0 && sides[i][0] == sides[i - 1][0] && sides[i][1] == sides[i - 1][1])
    {
      ++faceCount.back();
      continue;
    }
    edges.push_back(sides[i][0]);
    edges.push_back(sides[i][1]);
    faceCount.push_back(1);
    firstFace.push_back(sides[i][2]);
  }
}

namespace
{
/// The faces of M0 that survive the map, once per vertex triple, in the orientation of the
/// lowest M0 face of the triple (a triple's faces may disagree where the level folds).
void deriveFaces(const TriMesh& mesh, const std::vector<int32_t>& clusterOf, MultilevelLevel& level)
{
  std::vector<std::pair<std::array<int32_t, 3>, int32_t>> keyed;
  for (int32_t f = 0; f < static_cast<int32_t>(mesh.numTriangles()); ++f)
  {
    std::array<int32_t, 3> t;
    for (int i = 0; i < 3; ++i)
    {
      t[i] = clusterOf[mesh.triangles[3 * f + i]];
    }
    if (t[0] == t[1] || t[1] == t[2] || t[0] == t[2])
    {
      continue;
    }
    std::sort(t.begin(), t.end());
    keyed.push_back({ t, f });
  }
  std::sort(keyed.begin(), keyed.end());
  level.triangles.clear();
  level.sourceFaces.clear();
  for (size_t i = 0; i < keyed.size(); ++i)
  {
    if (i > 0 && keyed[i].first == keyed[i - 1].first)
    {
      continue;
    }
    level.sourceFaces.push_back(keyed[i].second);
  }
  // In M0's face order, so that a level's faces follow the input's.
  std::sort(level.sourceFaces.begin(), level.sourceFaces.end());
  for (const int32_t f : level.sourceFaces)
  {
    for (int i = 0; i < 3; ++i)
    {
      level.triangles.push_back(clusterOf[mesh.triangles[3 * f + i]]);
    }
  }
}
} // namespace

void deriveConnectivity(const TriMesh& mesh, const std::vector<int32_t>& edges0,
  const std::vector<int32_t>& clusterOf, MultilevelLevel& level)
{
  deriveFaces(mesh, clusterOf, level);
  std::vector<std::pair<int32_t, int32_t>> pairs;
  pairs.reserve(edges0.size() / 2);
  for (size_t e = 0; 2 * e < edges0.size(); ++e)
  {
    const int32_t a = clusterOf[edges0[2 * e]], b = clusterOf[edges0[2 * e + 1]];
    if (a != b)
    {
      pairs.push_back({ std::min(a, b), std::max(a, b) });
    }
  }
  std::sort(pairs.begin(), pairs.end());
  pairs.erase(std::unique(pairs.begin(), pairs.end()), pairs.end());
  level.edges.clear();
  for (const auto& [a, b] : pairs)
  {
    level.edges.push_back(a);
    level.edges.push_back(b);
  }
}
} // namespace multilevel
} // namespace detail
} // namespace tc
