// SPDX-License-Identifier: BSD-3-Clause
// checkMultilevelMesh: the structure of a multilevel mesh against its M0 (Kircher and Garland
// 2005): parents in range, clusters connected in M0 (the validity of section 4.2), derived
// faces, and the topology of each level.
#include "multilevel/multilevel_internal.h"

#include "detail/union_find.h"

#include <algorithm>
#include <array>
#include <string>
#include <utility>

namespace tc
{
namespace
{
using detail::DisjointSets;

/// Counts parents out of range; the coarsest level must have -1 everywhere.
int64_t invalidParents(const MultilevelMesh& m, size_t k)
{
  const MultilevelLevel& level = m.levels[k];
  const bool coarsest = k + 1 == m.levels.size();
  const int64_t above = coarsest ? 0 : m.levels[k + 1].numVertices();
  int64_t bad = std::abs(static_cast<int64_t>(level.parents.size()) - level.numVertices());
  for (const int32_t p : level.parents)
  {
    bad += coarsest ? (p != -1) : (p < 0 || p >= above);
  }
  return bad;
}

/// Empty and disconnected clusters of the level-k vertices under `cluster` (M0 -> level k):
/// M0's vertices joined along the M0 edges inside one cluster, then one root per cluster.
void clusterCounts(const TriMesh& mesh, const std::vector<int32_t>& edges0,
  const std::vector<int32_t>& cluster, MultilevelLevelCheck& check)
{
  DisjointSets sets(mesh.numPoints());
  for (size_t e = 0; 2 * e < edges0.size(); ++e)
  {
    if (cluster[edges0[2 * e]] == cluster[edges0[2 * e + 1]])
    {
      sets.unite(edges0[2 * e], edges0[2 * e + 1]);
    }
  }
  std::vector<int32_t> root(check.vertices, -1);
  std::vector<uint8_t> split(check.vertices, 0);
  for (int32_t v = 0; v < static_cast<int32_t>(mesh.numPoints()); ++v)
  {
    const int32_t a = cluster[v], r = sets.find(v);
    split[a] |= (root[a] >= 0 && root[a] != r);
    root[a] = r;
  }
  for (int64_t a = 0; a < check.vertices; ++a)
  {
    check.emptyClusters += root[a] < 0;
    check.disconnectedClusters += split[a];
  }
}

/// Euler characteristic, boundary and non-manifold edges, and the genus where the level is
/// edge-manifold: (2 components - chi - boundary loops) / 2.
void topology(const MultilevelLevel& level, MultilevelLevelCheck& check)
{
  std::vector<std::array<int32_t, 2>> sides;
  for (size_t i = 0; i < level.triangles.size(); ++i)
  {
    const int32_t a = level.triangles[i], b = level.triangles[i - i % 3 + (i + 1) % 3];
    sides.push_back({ std::min(a, b), std::max(a, b) });
  }
  std::sort(sides.begin(), sides.end());
  DisjointSets surface(level.numVertices()), boundary(level.numVertices());
  std::vector<uint8_t> used(level.numVertices(), 0), onBoundary(level.numVertices(), 0);
  for (size_t i = 0, j = 0; i < sides.size(); i = j)
  {
    j = i + 1;
    while (j < sides.size() && sides[j] == sides[i])
    {
      ++j;
    }
    const auto [a, b] = sides[i];
    ++check.edges;
    used[a] = used[b] = 1;
    surface.unite(a, b);
    check.nonManifoldEdges += j - i > 2;
    if (j - i == 1)
    {
      ++check.boundaryEdges;
      boundary.unite(a, b);
      onBoundary[a] = onBoundary[b] = 1;
    }
  }
  int64_t usedVertices = 0, components = 0, loops = 0;
  for (int32_t v = 0; v < static_cast<int32_t>(level.numVertices()); ++v)
  {
    usedVertices += used[v];
    components += used[v] && surface.find(v) == v;
    loops += onBoundary[v] && boundary.find(v) == v;
  }
  check.eulerCharacteristic = usedVertices - check.edges + check.triangles;
  if (check.nonManifoldEdges == 0)
  {
    check.genus = (2 * components - check.eulerCharacteristic - loops) / 2;
  }
}

void note(MultilevelCheck& result, size_t k, int64_t count, const char* what)
{
  if (count > 0 && result.firstProblem.empty())
  {
    result.firstProblem =
      "level " + std::to_string(k) + " has " + std::to_string(count) + " " + what;
  }
}
} // namespace

MultilevelCheck checkMultilevelMesh(const TriMesh& mesh, const MultilevelMesh& multilevel)
{
  MultilevelCheck result;
  if (multilevel.levels.empty() || multilevel.levels[0].numVertices() != mesh.numPoints())
  {
    result.firstProblem = "level 0 does not have the mesh's " + std::to_string(mesh.numPoints()) +
      " vertices: the multilevel mesh was built from another mesh";
    return result;
  }
  std::vector<int32_t> edges0, faceCount, firstFace;
  detail::multilevel::uniqueEdges(mesh, edges0, faceCount, firstFace);
  std::vector<int32_t> cluster(mesh.numPoints());
  for (int32_t v = 0; v < static_cast<int32_t>(cluster.size()); ++v)
  {
    cluster[v] = v;
  }
  for (size_t k = 0; k < multilevel.levels.size(); ++k)
  {
    const MultilevelLevel& level = multilevel.levels[k];
    MultilevelLevelCheck check;
    check.vertices = level.numVertices();
    check.triangles = level.numTriangles();
    check.invalidParents = invalidParents(multilevel, k);
    clusterCounts(mesh, edges0, cluster, check);
    MultilevelLevel derived;
    detail::multilevel::deriveConnectivity(mesh, edges0, cluster, derived);
    check.mismatchedFaces = derived.triangles == level.triangles
      ? 0
      : std::max<int64_t>(1, std::abs(derived.numTriangles() - level.numTriangles()));
    topology(level, check);
    note(result, k, check.invalidParents, "parents out of range");
    note(result, k, check.emptyClusters, "vertices without an M0 vertex under them");
    note(result, k, check.disconnectedClusters, "clusters that are not connected in M0");
    note(result, k, check.mismatchedFaces, "triangles other than those derived from M0");
    result.levels.push_back(check);
    if (check.invalidParents > 0)
    {
      break; // the clusters of the levels above cannot be followed
    }
    if (k + 1 < multilevel.levels.size())
    {
      for (int32_t& c : cluster)
      {
        c = level.parents[c];
      }
    }
  }
  return result;
}
} // namespace tc
