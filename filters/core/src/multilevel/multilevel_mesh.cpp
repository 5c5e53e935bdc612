// SPDX-License-Identifier: BSD-3-Clause
// buildMultilevelMesh (Kircher and Garland 2005, section 3): the input checked, M0's quadrics,
// then each level contracted from the one below, its quadrics summed over its clusters, its
// vertices placed and its connectivity derived from M0.
#include "multilevel/multilevel_internal.h"

#include "tc/common/errors.h"
#include "tc/common/mesh_topology.h"

#include <algorithm>
#include <cmath>
#include <memory>
#include <string>

namespace tc
{
namespace detail
{
namespace multilevel
{
namespace
{
void checkOptions(const MultilevelOptions& options)
{
  if (options.branchingFactor < 2)
  {
    throw InputError("buildMultilevelMesh: the branching factor must be at least 2 (each level "
                     "has 1 / branching factor of the vertices below; the paper uses 8), not " +
      std::to_string(options.branchingFactor));
  }
  if (options.maxLevels < 0 || options.coarsestVertices < 1)
  {
    throw InputError("buildMultilevelMesh: the number of levels must be 0 (no limit) or more "
                     "and the coarsest vertex count at least 1, not " +
      std::to_string(options.maxLevels) + " and " + std::to_string(options.coarsestVertices));
  }
}

void checkMesh(const TriMesh& mesh)
{
  if (mesh.numTriangles() == 0 || mesh.numPoints() == 0)
  {
    throw InputError("buildMultilevelMesh: the mesh has no triangles; give it a triangle mesh");
  }
  for (int64_t i = 0; i < static_cast<int64_t>(mesh.points.size()); ++i)
  {
    if (!std::isfinite(mesh.points[i]))
    {
      throw InputError("buildMultilevelMesh: point " + std::to_string(i / 3) +
        " has a coordinate that is not a finite number; remove or repair it first");
    }
  }
  for (int64_t f = 0; f < mesh.numTriangles(); ++f)
  {
    const int32_t* t = &mesh.triangles[3 * f];
    for (int i = 0; i < 3; ++i)
    {
      if (t[i] < 0 || t[i] >= mesh.numPoints())
      {
        throw InputError("buildMultilevelMesh: triangle " + std::to_string(f) + " names point " +
          std::to_string(t[i]) + ", which the mesh does not have");
      }
    }
    if (t[0] == t[1] || t[1] == t[2] || t[0] == t[2])
    {
      throw InputError("buildMultilevelMesh: triangle " + std::to_string(f) +
        " repeats a corner; remove degenerate triangles first (TriChart Mesh Preparation)");
    }
  }
}

/// Whether the faces around v form one fan: its link (the opposite sides of its faces) is
/// connected. `local` and `parent` are scratch.
bool oneFan(const TriMesh& mesh, const VertexFaces& vf, int32_t v, std::vector<int32_t>& local,
  std::vector<int32_t>& parent)
{
  local.clear();
  for (int64_t k = vf.offsets[v]; k < vf.offsets[v + 1]; ++k)
  {
    for (int i = 0; i < 3; ++i)
    {
      local.push_back(mesh.triangles[3 * vf.faceIds[k] + i]);
    }
  }
  std::sort(local.begin(), local.end());
  local.erase(std::unique(local.begin(), local.end()), local.end());
  parent.resize(local.size());
  for (size_t i = 0; i < parent.size(); ++i)
  {
    parent[i] = static_cast<int32_t>(i);
  }
  auto find = [&](int32_t x)
  {
    while (parent[x] != x)
    {
      x = parent[x] = parent[parent[x]];
    }
    return x;
  };
  auto index = [&](int32_t x)
  { return static_cast<int32_t>(std::lower_bound(local.begin(), local.end(), x) - local.begin()); };
  int32_t components = static_cast<int32_t>(local.size()) - 1; // v itself is not in its link
  for (int64_t k = vf.offsets[v]; k < vf.offsets[v + 1]; ++k)
  {
    const int32_t* t = &mesh.triangles[3 * vf.faceIds[k]];
    const int i = t[0] == v ? 0 : t[1] == v ? 1 : 2;
    const int32_t x = find(index(t[(i + 1) % 3])), y = find(index(t[(i + 2) % 3]));
    if (x != y)
    {
      parent[std::max(x, y)] = std::min(x, y);
      --components;
    }
  }
  return components == 1;
}

/// The link condition assumes a manifold M0 (Kircher and Garland, section 4.2).
void checkManifold(
  const TriMesh& mesh, const std::vector<int32_t>& edges, const std::vector<int32_t>& edgeFaceCount)
{
  for (size_t e = 0; e < edgeFaceCount.size(); ++e)
  {
    if (edgeFaceCount[e] > 2)
    {
      throw InputError("buildMultilevelMesh: edge " + std::to_string(edges[2 * e]) + "-" +
        std::to_string(edges[2 * e + 1]) + " has " + std::to_string(edgeFaceCount[e]) +
        " faces; the link condition needs a manifold mesh: split non-manifold edges first "
        "(TriChart Mesh Preparation) or turn the link condition off");
    }
  }
  const VertexFaces vf = buildVertexFaces(mesh.triangles, mesh.numPoints());
  std::vector<int32_t> local, parent;
  for (int32_t v = 0; v < static_cast<int32_t>(mesh.numPoints()); ++v)
  {
    if (vf.offsets[v + 1] > vf.offsets[v] && !oneFan(mesh, vf, v, local, parent))
    {
      throw InputError("buildMultilevelMesh: the faces around vertex " + std::to_string(v) +
        " are not one fan; the link condition needs a manifold mesh: split non-manifold "
        "vertices first (TriChart Mesh Preparation) or turn the link condition off");
    }
  }
}

/// What the levels are built from: M0 and its quadrics, and per vertex of the current level its
/// sum of M0 positions (the mean a singular quadric falls back to).
struct Builder
{
  const TriMesh& mesh;
  std::vector<int32_t> edges0, edgeFaceCount, edgeFace;
  std::vector<Quadric> quadrics0;
  std::vector<int32_t> clusterOf; ///< M0 vertex -> vertex of the current level
  std::vector<V3> positionSums;   ///< per vertex of the current level
};

void storeQuadric(const Quadric& q, int32_t v, MultilevelLevel& level)
{
  std::copy_n(q.q, 10, &level.quadrics[10 * static_cast<size_t>(v)]);
}

Quadric loadQuadric(const MultilevelLevel& level, int32_t v)
{
  Quadric q;
  std::copy_n(&level.quadrics[10 * static_cast<size_t>(v)], 10, q.q);
  return q;
}

MultilevelLevel inputLevel(Builder& b)
{
  const int32_t n = static_cast<int32_t>(b.mesh.numPoints());
  MultilevelLevel level;
  level.points = b.mesh.points;
  level.clusterSizes.assign(n, 1);
  level.quadrics.resize(10 * static_cast<size_t>(n));
  level.errors.resize(n);
  level.placements.assign(n, Placement::Input);
  b.clusterOf.resize(n);
  b.positionSums.resize(n);
  for (int32_t v = 0; v < n; ++v)
  {
    b.clusterOf[v] = v;
    b.positionSums[v] = { b.mesh.points[3 * v], b.mesh.points[3 * v + 1],
      b.mesh.points[3 * v + 2] };
    storeQuadric(b.quadrics0[v], v, level);
    level.errors[v] = evaluate(b.quadrics0[v], b.positionSums[v]);
  }
  deriveConnectivity(b.mesh, b.edges0, b.clusterOf, level);
  return level;
}

ClusterGraph clusterGraph(const Builder& b, const MultilevelLevel& level)
{
  ClusterGraph graph;
  const int32_t n = static_cast<int32_t>(level.clusterSizes.size());
  graph.quadrics.resize(n);
  for (int32_t v = 0; v < n; ++v)
  {
    graph.quadrics[v] = loadQuadric(level, v);
  }
  graph.positionSums = b.positionSums;
  graph.counts = level.clusterSizes;
  graph.edges = level.edges;
  return graph;
}

/// Places every vertex of `level` (placeVertex at its cluster's mean), then, where the quadric
/// was singular, takes the cluster's M0 vertex of lowest error if that is lower still
/// (Garland and Heckbert's fallback to the contracted vertices).
void placeLevel(const Builder& b, MultilevelLevel& level)
{
  const int32_t n = static_cast<int32_t>(level.clusterSizes.size());
  level.points.resize(3 * static_cast<size_t>(n));
  level.errors.resize(n);
  level.placements.resize(n);
  std::vector<Quadric> q(n);
  for (int32_t a = 0; a < n; ++a)
  {
    q[a] = loadQuadric(level, a);
    const double count = level.clusterSizes[a];
    const V3& s = b.positionSums[a];
    const Placed placed = placeVertex(q[a], { s.x / count, s.y / count, s.z / count });
    level.points[3 * a] = placed.p.x;
    level.points[3 * a + 1] = placed.p.y;
    level.points[3 * a + 2] = placed.p.z;
    level.errors[a] = placed.error;
    level.placements[a] = placed.how;
  }
  for (int32_t v = 0; v < static_cast<int32_t>(b.mesh.numPoints()); ++v)
  {
    const int32_t a = b.clusterOf[v];
    const V3 p{ b.mesh.points[3 * v], b.mesh.points[3 * v + 1], b.mesh.points[3 * v + 2] };
    const double e = evaluate(q[a], p);
    if (level.placements[a] != Placement::Optimal && e < level.errors[a])
    {
      std::copy_n(&b.mesh.points[3 * v], 3, &level.points[3 * a]);
      level.errors[a] = e;
      level.placements[a] = Placement::ClusterVertex;
    }
  }
}

/// Level k + 1 from level k and the parents of k's vertices: clusters, their quadrics (sums of
/// the children's, hence of M0's over the cluster), positions and derived connectivity.
MultilevelLevel coarserLevel(Builder& b, const MultilevelLevel& below, int32_t count)
{
  MultilevelLevel level;
  level.clusterSizes.assign(count, 0);
  level.quadrics.assign(10 * static_cast<size_t>(count), 0.0);
  std::vector<V3> sums(count, V3{ 0, 0, 0 });
  for (int32_t v = 0; v < static_cast<int32_t>(below.parents.size()); ++v)
  {
    const int32_t a = below.parents[v];
    level.clusterSizes[a] += below.clusterSizes[v];
    for (int i = 0; i < 10; ++i)
    {
      level.quadrics[10 * static_cast<size_t>(a) + i] +=
        below.quadrics[10 * static_cast<size_t>(v) + i];
    }
    sums[a] = { sums[a].x + b.positionSums[v].x, sums[a].y + b.positionSums[v].y,
      sums[a].z + b.positionSums[v].z };
  }
  b.positionSums = std::move(sums);
  for (int32_t& c : b.clusterOf)
  {
    c = below.parents[c];
  }
  placeLevel(b, level);
  deriveConnectivity(b.mesh, b.edges0, b.clusterOf, level);
  return level;
}

/// Progress of the contraction of level k into k + 1: each level has 1 / branching of the work
/// of the one below, so level k gets the share r^k (1 - r) of what follows M0's quadrics.
Progress levelProgress(const Progress& progress, int k, int branching)
{
  const double r = 1.0 / branching;
  return progress.sub(
    0.05 + 0.95 * (1.0 - std::pow(r, k)), 0.05 + 0.95 * (1.0 - std::pow(r, k + 1)));
}
} // namespace
} // namespace multilevel
} // namespace detail

MultilevelMesh buildMultilevelMesh(
  const TriMesh& mesh, const MultilevelOptions& options, const Progress& progress)
{
  using namespace detail::multilevel;
  // 1. The input and the options.
  checkOptions(options);
  checkMesh(mesh);
  Builder b{ mesh, {}, {}, {}, {}, {}, {} };
  uniqueEdges(mesh, b.edges0, b.edgeFaceCount, b.edgeFace);
  if (options.linkCondition)
  {
    checkManifold(mesh, b.edges0, b.edgeFaceCount);
  }

  // 2. M0: the input with its vertex quadrics.
  b.quadrics0 = vertexQuadrics(mesh, b.edges0, b.edgeFaceCount, b.edgeFace);
  MultilevelMesh result;
  result.levels.push_back(inputLevel(b));
  progress.report(0.05);

  // 3. Each level by QSlim on the one below, with the link condition from M0 to M1.
  for (int k = 0; options.maxLevels == 0 || k < options.maxLevels; ++k)
  {
    MultilevelLevel& below = result.levels.back();
    const int64_t n = below.numVertices();
    const int64_t target = std::llround(static_cast<double>(n) / options.branchingFactor);
    if (target < options.coarsestVertices)
    {
      break;
    }
    std::unique_ptr<LiveFaces> faces;
    if (k == 0 && options.linkCondition)
    {
      faces = std::make_unique<LiveFaces>(mesh);
    }
    int32_t count = 0;
    below.parents = contractLevel(clusterGraph(b, below), static_cast<int32_t>(target), faces.get(),
      levelProgress(progress, k, options.branchingFactor), &count);
    if (count == n)
    {
      below.parents.clear(); // nothing could be contracted: this is the coarsest level
      break;
    }
    result.levels.push_back(coarserLevel(b, below, count));
  }

  // 4. The coarsest level has no parents.
  result.levels.back().parents.assign(result.levels.back().clusterSizes.size(), -1);
  progress.report(1.0);
  return result;
}

std::vector<int32_t> MultilevelMesh::clusterOf(int level) const
{
  std::vector<int32_t> cluster(levels.empty() ? 0 : levels[0].clusterSizes.size());
  for (size_t v = 0; v < cluster.size(); ++v)
  {
    cluster[v] = static_cast<int32_t>(v);
  }
  for (int k = 0; k < level; ++k)
  {
    for (int32_t& c : cluster)
    {
      c = levels[k].parents[c];
    }
  }
  return cluster;
}
} // namespace tc
