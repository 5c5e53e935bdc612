// SPDX-License-Identifier: BSD-3-Clause
#include "tc/features/feature_refinement.h"

#include "detail/geometry2d.h"

#include "tc/common/errors.h"
#include "tc/common/mesh_topology.h"
#include "tc/common/parallel.h"

#include <boost/graph/boykov_kolmogorov_max_flow.hpp>
#include <boost/graph/compressed_sparse_row_graph.hpp>
#include <boost/property_map/property_map.hpp>

#include <algorithm>
#include <array>
#include <cmath>
#include <functional>
#include <limits>
#include <numeric>
#include <queue>
#include <string>
#include <utility>

namespace tc
{
namespace
{
constexpr double kInf = std::numeric_limits<double>::infinity();
using detail::kPi;

double distance(const TriMesh& mesh, int64_t a, int64_t b)
{
  const double dx = mesh.points[3 * a] - mesh.points[3 * b];
  const double dy = mesh.points[3 * a + 1] - mesh.points[3 * b + 1];
  const double dz = mesh.points[3 * a + 2] - mesh.points[3 * b + 2];
  return std::sqrt(dx * dx + dy * dy + dz * dz);
}

void validate(const TriMesh& mesh, const std::vector<int32_t>& clusterId,
  const std::vector<double>& meanCurvature, const std::vector<double>& faceMeanCurvature,
  const std::vector<uint8_t>& crestVertex)
{
  const size_t nv = static_cast<size_t>(mesh.numPoints());
  const size_t nf = static_cast<size_t>(mesh.numTriangles());
  auto mismatch = [](const char* what, size_t got, size_t want, const char* of)
  {
    throw InputError(std::string("refineFeatures: ") + what + " has " + std::to_string(got) +
      " entries but the mesh has " + std::to_string(want) + " " + of +
      "; pass arrays computed on this mesh");
  };
  if (mesh.points.size() % 3 != 0 || mesh.triangles.size() % 3 != 0)
  {
    throw InputError("refineFeatures: points and triangles must hold 3 values per element");
  }
  if (clusterId.size() != nf)
  {
    mismatch("clusterId", clusterId.size(), nf, "triangles");
  }
  if (faceMeanCurvature.size() != nf)
  {
    mismatch("faceMeanCurvature", faceMeanCurvature.size(), nf, "triangles");
  }
  if (meanCurvature.size() != nv)
  {
    mismatch("meanCurvature", meanCurvature.size(), nv, "vertices");
  }
  if (!crestVertex.empty() && crestVertex.size() != nv)
  {
    mismatch("crestVertex", crestVertex.size(), nv, "vertices (or none)");
  }
  for (size_t i = 0; i < mesh.triangles.size(); ++i)
  {
    const int32_t v = mesh.triangles[i];
    if (v < 0 || static_cast<size_t>(v) >= nv)
    {
      throw InputError("refineFeatures: triangle " + std::to_string(i / 3) + " references vertex " +
        std::to_string(v) + " of a mesh with " + std::to_string(nv) +
        " vertices; fix the connectivity");
    }
    if (v == mesh.triangles[3 * (i / 3) + (i + 1) % 3])
    {
      throw InputError("refineFeatures: triangle " + std::to_string(i / 3) +
        " repeats a vertex; clean the mesh with prepareMesh() first");
    }
  }
  for (size_t f = 0; f < nf; ++f)
  {
    if (clusterId[f] < 0)
    {
      throw InputError("refineFeatures: triangle " + std::to_string(f) + " has cluster id " +
        std::to_string(clusterId[f]) + "; every triangle needs a cluster (ids >= 0)");
    }
    if (!std::isfinite(faceMeanCurvature[f]))
    {
      throw InputError(
        "refineFeatures: faceMeanCurvature of triangle " + std::to_string(f) + " is not finite");
    }
  }
  for (size_t v = 0; v < nv; ++v)
  {
    if (!std::isfinite(meanCurvature[v]))
    {
      throw InputError(
        "refineFeatures: meanCurvature of vertex " + std::to_string(v) + " is not finite");
    }
  }
}

/// Faces joined across shared mesh edges (every pair of faces of a non-manifold edge), CSR.
struct DualGraph
{
  std::vector<int64_t> offsets; ///< #F + 1
  std::vector<int32_t> faces;   ///< neighbour face of each entry
  std::vector<int32_t> edges;   ///< mesh edge shared with that neighbour
};

DualGraph buildDualGraph(const EdgeTable& edges, int64_t nf)
{
  DualGraph dual;
  dual.offsets.assign(nf + 1, 0);
  const int64_t ne = edges.numEdges();
  for (int64_t e = 0; e < ne; ++e)
  {
    const int64_t k = edges.valence(e);
    for (int64_t i = edges.faceOffsets[e]; i < edges.faceOffsets[e + 1]; ++i)
    {
      dual.offsets[edges.edgeFaces[i] + 1] += k - 1;
    }
  }
  std::partial_sum(dual.offsets.begin(), dual.offsets.end(), dual.offsets.begin());
  dual.faces.resize(dual.offsets[nf]);
  dual.edges.resize(dual.offsets[nf]);
  std::vector<int64_t> fill(dual.offsets.begin(), dual.offsets.end() - 1);
  for (int64_t e = 0; e < ne; ++e)
  {
    for (int64_t i = edges.faceOffsets[e]; i < edges.faceOffsets[e + 1]; ++i)
    {
      for (int64_t j = edges.faceOffsets[e]; j < edges.faceOffsets[e + 1]; ++j)
      {
        if (i != j)
        {
          const int32_t f = edges.edgeFaces[i];
          dual.faces[fill[f]] = edges.edgeFaces[j];
          dual.edges[fill[f]++] = static_cast<int32_t>(e);
        }
      }
    }
  }
  return dual;
}

/// Edges where the labels of their faces differ (mesh-boundary edges never are).
std::vector<uint8_t> boundaryEdges(const EdgeTable& edges, const std::vector<int32_t>& label)
{
  const int64_t ne = edges.numEdges();
  std::vector<uint8_t> out(ne, 0);
  for (int64_t e = 0; e < ne; ++e)
  {
    const int32_t first = label[edges.edgeFaces[edges.faceOffsets[e]]];
    for (int64_t i = edges.faceOffsets[e] + 1; i < edges.faceOffsets[e + 1]; ++i)
    {
      out[e] |= label[edges.edgeFaces[i]] != first ? 1 : 0;
    }
  }
  return out;
}

/// The band of section 4.2 with, for each band face, the pair of clusters (index into the
/// sorted pair keys) whose boundary is nearest to it.
struct Band
{
  std::vector<int32_t> pair;     ///< #F nearest boundary pair of a band face, -1 outside the band
  std::vector<int64_t> pairKeys; ///< #P sorted keys a * #clusters + b of adjacent clusters a < b
  int64_t size = 0;
};

Band buildBand(const TriMesh& mesh, const EdgeTable& edges, const DualGraph& dual,
  const std::vector<int32_t>& label, int64_t numClusters, const std::vector<uint8_t>& isBoundary,
  double bandFraction, int bandRings, const Band* within, const Progress& progress)
{
  auto eligible = [&](int64_t f) { return within == nullptr || within->pair[f] >= 0; };
  const int64_t nf = mesh.numTriangles();
  const int64_t ne = edges.numEdges();
  Band band;
  band.pair.assign(nf, -1);

  // Each boundary edge separates the smallest and the largest label of its faces (two faces
  // on a manifold edge).
  std::vector<int64_t> edgeKey(ne, -1);
  for (int64_t e = 0; e < ne; ++e)
  {
    if (isBoundary[e])
    {
      int32_t lo = std::numeric_limits<int32_t>::max(), hi = -1;
      for (int64_t i = edges.faceOffsets[e]; i < edges.faceOffsets[e + 1]; ++i)
      {
        lo = std::min(lo, label[edges.edgeFaces[i]]);
        hi = std::max(hi, label[edges.edgeFaces[i]]);
      }
      edgeKey[e] = static_cast<int64_t>(lo) * numClusters + hi;
      band.pairKeys.push_back(edgeKey[e]);
    }
  }
  std::sort(band.pairKeys.begin(), band.pairKeys.end());
  band.pairKeys.erase(std::unique(band.pairKeys.begin(), band.pairKeys.end()), band.pairKeys.end());
  if (band.pairKeys.empty())
  {
    progress.report(1.0);
    return band;
  }

  // Multi-source Dijkstra over the dual graph (dual edges as long as the distance of the face
  // centroids) from the faces that touch a boundary; a face at a junction takes the smallest
  // pair among its boundary edges. The band is the first ceil(bandFraction #F) faces settled,
  // and always every face that touches a boundary (else the cut could not move it).
  std::vector<double> centroid(3 * nf);
  for (int64_t f = 0; f < nf; ++f)
  {
    for (int c = 0; c < 3; ++c)
    {
      centroid[3 * f + c] = (mesh.points[3 * mesh.triangles[3 * f] + c] +
                              mesh.points[3 * mesh.triangles[3 * f + 1] + c] +
                              mesh.points[3 * mesh.triangles[3 * f + 2] + c]) /
        3.0;
    }
  }
  std::vector<double> dist(nf, kInf);
  std::vector<int32_t> nearest(nf, -1);
  using Item = std::pair<double, int32_t>;
  std::priority_queue<Item, std::vector<Item>, std::greater<Item>> queue;
  for (int64_t f = 0; f < nf; ++f)
  {
    for (int c = 0; c < 3 && eligible(f); ++c)
    {
      const int32_t e = edges.faceEdges[3 * f + c];
      if (isBoundary[e])
      {
        const int32_t p = static_cast<int32_t>(
          std::lower_bound(band.pairKeys.begin(), band.pairKeys.end(), edgeKey[e]) -
          band.pairKeys.begin());
        nearest[f] = nearest[f] < 0 ? p : std::min(nearest[f], p);
        dist[f] = 0.0;
      }
    }
    if (dist[f] == 0.0)
    {
      queue.emplace(0.0, static_cast<int32_t>(f));
    }
  }
  // Faces within bandRings dual steps of a seed belong to the band whatever its size.
  std::vector<uint8_t> required(nf, 0);
  int64_t requiredLeft = 0;
  {
    std::vector<int32_t> front, next;
    for (int64_t f = 0; f < nf; ++f)
    {
      if (dist[f] == 0.0)
      {
        required[f] = 1;
        front.push_back(static_cast<int32_t>(f));
      }
    }
    requiredLeft = static_cast<int64_t>(front.size());
    for (int r = 0; r < bandRings && !front.empty(); ++r)
    {
      next.clear();
      for (int32_t f : front)
      {
        for (int64_t j = dual.offsets[f]; j < dual.offsets[f + 1]; ++j)
        {
          if (!required[dual.faces[j]])
          {
            required[dual.faces[j]] = 1;
            next.push_back(dual.faces[j]);
          }
        }
      }
      requiredLeft += static_cast<int64_t>(next.size());
      front.swap(next);
    }
  }
  const int64_t target = within != nullptr
    ? nf
    : static_cast<int64_t>(std::ceil(std::clamp(bandFraction, 0.0, 1.0) * static_cast<double>(nf)));
  const int64_t reportEvery = std::max<int64_t>(1, nf / 16);
  while (!queue.empty() && (band.size < target || requiredLeft > 0))
  {
    const auto [d, f] = queue.top();
    queue.pop();
    if (d > dist[f] || band.pair[f] >= 0 || (band.size >= target && !required[f]))
    {
      continue;
    }
    band.pair[f] = nearest[f];
    requiredLeft -= required[f];
    if (++band.size % reportEvery == 0)
    {
      progress.report(std::min(1.0, static_cast<double>(band.size) / std::max<int64_t>(1, target)));
    }
    for (int64_t j = dual.offsets[f]; j < dual.offsets[f + 1]; ++j)
    {
      const int32_t g = dual.faces[j];
      if (!eligible(g))
      {
        continue;
      }
      const double dx = centroid[3 * f] - centroid[3 * g];
      const double dy = centroid[3 * f + 1] - centroid[3 * g + 1];
      const double dz = centroid[3 * f + 2] - centroid[3 * g + 2];
      const double nd = d + std::sqrt(dx * dx + dy * dy + dz * dz);
      if (nd < dist[g])
      {
        dist[g] = nd;
        nearest[g] = nearest[f];
        queue.emplace(nd, g);
      }
    }
  }
  progress.report(1.0);
  return band;
}

using DualCapacity = std::vector<double>;

/// The angle between the normals of the two faces of every manifold edge, in radians (0 on
/// other edges).
std::vector<double> edgeDihedrals(const TriMesh& mesh, const EdgeTable& edges)
{
  const int64_t nf = mesh.numTriangles();
  std::vector<double> normal(3 * nf);
  parallel_for(nf,
    [&](int64_t f)
    {
      const int32_t* t = &mesh.triangles[3 * f];
      double u[3], v[3];
      for (int c = 0; c < 3; ++c)
      {
        u[c] = mesh.points[3 * t[1] + c] - mesh.points[3 * t[0] + c];
        v[c] = mesh.points[3 * t[2] + c] - mesh.points[3 * t[0] + c];
      }
      const double n[3] = { u[1] * v[2] - u[2] * v[1], u[2] * v[0] - u[0] * v[2],
        u[0] * v[1] - u[1] * v[0] };
      const double l = std::sqrt(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]);
      for (int c = 0; c < 3; ++c)
      {
        normal[3 * f + c] = l > 0.0 ? n[c] / l : 0.0;
      }
    });
  const int64_t ne = edges.numEdges();
  std::vector<double> dihedral(ne, 0.0);
  parallel_for(ne,
    [&](int64_t e)
    {
      if (edges.valence(e) == 2)
      {
        const double* n0 = &normal[3 * edges.edgeFaces[edges.faceOffsets[e]]];
        const double* n1 = &normal[3 * edges.edgeFaces[edges.faceOffsets[e] + 1]];
        dihedral[e] =
          std::acos(std::clamp(n0[0] * n1[0] + n0[1] * n1[1] + n0[2] * n1[2], -1.0, 1.0));
      }
    });
  return dihedral;
}

/// Eq. 4 for every entry of the dual graph (see FeatureRefinementOptions::dihedralWeight);
/// `dihedral` is edgeDihedrals' result, needed only when dihedralWeight > 0.
DualCapacity dualCapacity(const TriMesh& mesh, const EdgeTable& edges, const DualGraph& dual,
  const std::vector<double>& faceMeanCurvature, const std::vector<uint8_t>& crestVertex,
  const std::vector<double>& dihedral, const FeatureRefinementOptions& options,
  const Progress& progress)
{
  const int64_t nf = mesh.numTriangles();
  // sigma_k of eq. 3/4: the standard deviation of |kappa| over all faces.
  double mean = 0.0, meanSq = 0.0;
  for (int64_t f = 0; f < nf; ++f)
  {
    const double k = std::abs(faceMeanCurvature[f]);
    mean += k;
    meanSq += k * k;
  }
  mean /= static_cast<double>(nf);
  const double sigma = std::sqrt(std::max(0.0, meanSq / static_cast<double>(nf) - mean * mean));
  const double inverseSigma = sigma > 0.0 ? 1.0 / sigma : 0.0;
  // The dihedral angle theta_e between the normals of the two faces of each manifold edge, and
  // its standard deviation sigma_theta over those edges (see dihedralWeight).
  double inverseSigmaTheta = 0.0;
  if (options.dihedralWeight > 0.0)
  {
    const int64_t ne = edges.numEdges();
    double sum = 0.0, sumSq = 0.0;
    int64_t count = 0;
    for (int64_t e = 0; e < ne; ++e)
    {
      if (edges.valence(e) == 2)
      {
        sum += dihedral[e];
        sumSq += dihedral[e] * dihedral[e];
        ++count;
      }
    }
    if (count > 0)
    {
      const double m = sum / static_cast<double>(count);
      const double sd = std::sqrt(std::max(0.0, sumSq / static_cast<double>(count) - m * m));
      inverseSigmaTheta = sd > 0.0 ? options.dihedralWeight / sd : 0.0;
    }
  }
  // Eq. 4: g(i, j) = beta |e_ij| exp(-(|k_i| + |k_j|) / sigma_k), beta = crestBeta where a crest
  // line runs along the shared edge (both its ends next to a crest), times
  // exp(-dihedralWeight theta_ij / sigma_theta).
  auto capacity = [&](int32_t f, int32_t g, int32_t e)
  {
    const int32_t a = edges.vertices[2 * e], b = edges.vertices[2 * e + 1];
    const double beta =
      !crestVertex.empty() && crestVertex[a] && crestVertex[b] ? options.crestBeta : 1.0;
    const double theta = options.dihedralWeight > 0.0 ? dihedral[e] * inverseSigmaTheta : 0.0;
    return beta * distance(mesh, a, b) *
      std::exp(
        -(std::abs(faceMeanCurvature[f]) + std::abs(faceMeanCurvature[g])) * inverseSigma - theta);
  };
  DualCapacity out(dual.faces.size());
  parallel_for(
    nf,
    [&](int64_t f)
    {
      for (int64_t j = dual.offsets[f]; j < dual.offsets[f + 1]; ++j)
      {
        out[j] = capacity(static_cast<int32_t>(f), dual.faces[j], dual.edges[j]);
      }
    },
    progress);
  return out;
}

/// Straightens one-face zig-zags of the refined boundaries (see
/// FeatureRefinementOptions::straightenLines): a face whose two sides at vertex u are boundary
/// edges to one other cluster, whose third side (v, w) is not, and where u is on no other
/// boundary edge, goes to that other cluster, so the boundary runs v - w instead of v - u - w.
/// Each change removes one boundary edge, so this ends; faces are visited in id order, pass
/// after pass, so the result does not depend on the thread count.
/// @return the number of faces relabelled; `label` is updated in place
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
      // Side k runs from corner k to corner k + 1: the two boundary sides meet at the corner
      // they share.
      int k = -1;
      for (int i = 0; i < 3; ++i)
      {
        if (!boundary[side[i]] && boundary[side[(i + 1) % 3]] && boundary[side[(i + 2) % 3]])
        {
          k = i;
        }
      }
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

/// Minimum s-t cuts of section 4.2 (Katz and Tal 2003) for every pair of adjacent clusters at
/// once. The band faces nearest to the boundary of clusters (a, b) that belong to a or b are
/// the free nodes of that pair; their neighbours outside (faces of a just beyond the band or in
/// the band of another pair) are contracted into the source, those of b into the sink, faces of
/// other clusters are left out. The regions of different pairs share no free node and no
/// n-link, so one max-flow over their disjoint union solves every pair's cut.
/// @return the number of faces relabelled; `label` is updated in place
int64_t cutBand(const TriMesh& mesh, const DualGraph& dual, const std::vector<double>& capacity,
  const Band& band, int64_t numClusters, std::vector<int32_t>& label, const Progress& progress)
{
  const int64_t nf = mesh.numTriangles();
  const int64_t numPairs = static_cast<int64_t>(band.pairKeys.size());
  if (numPairs == 0)
  {
    progress.report(1.0);
    return 0;
  }
  auto pairA = [&](int32_t p) { return static_cast<int32_t>(band.pairKeys[p] / numClusters); };
  auto pairB = [&](int32_t p) { return static_cast<int32_t>(band.pairKeys[p] % numClusters); };

  // Free nodes: band faces labelled with one of the clusters of their nearest pair.
  std::vector<int32_t> region(nf, -1);
  for (int64_t f = 0; f < nf; ++f)
  {
    const int32_t p = band.pair[f];
    if (p >= 0 && (label[f] == pairA(p) || label[f] == pairB(p)))
    {
      region[f] = p;
    }
  }
  // A pair without faces of a or of b around its free nodes has nothing to cut against.
  std::vector<uint8_t> hasSource(numPairs, 0), hasSink(numPairs, 0);
  for (int64_t f = 0; f < nf; ++f)
  {
    const int32_t p = region[f];
    if (p < 0)
    {
      continue;
    }
    for (int64_t j = dual.offsets[f]; j < dual.offsets[f + 1]; ++j)
    {
      const int32_t g = dual.faces[j];
      if (region[g] != p)
      {
        hasSource[p] |= label[g] == pairA(p) ? 1 : 0;
        hasSink[p] |= label[g] == pairB(p) ? 1 : 0;
      }
    }
  }
  std::vector<int32_t> node(nf, -1);
  std::vector<int32_t> nodeFace;
  for (int64_t f = 0; f < nf; ++f)
  {
    if (region[f] >= 0 && !(hasSource[region[f]] && hasSink[region[f]]))
    {
      region[f] = -1;
    }
    if (region[f] >= 0)
    {
      node[f] = static_cast<int32_t>(nodeFace.size());
      nodeFace.push_back(static_cast<int32_t>(f));
    }
  }
  const int64_t n = static_cast<int64_t>(nodeFace.size());
  if (n == 0)
  {
    progress.report(1.0);
    return 0;
  }
  const int32_t source = static_cast<int32_t>(n), sink = static_cast<int32_t>(n + 1);

  // Arcs: an undirected n-link is two arcs, each the other's reverse, both with the capacity;
  // a t-link is an arc with the capacity and a reverse arc with none.
  struct Arc
  {
    int32_t from, to;
    double capacity;
  };
  std::vector<Arc> arcs;
  std::vector<double> sourceCap(n, 0.0), sinkCap(n, 0.0);
  for (int64_t i = 0; i < n; ++i)
  {
    const int32_t f = nodeFace[i];
    const int32_t p = region[f];
    for (int64_t j = dual.offsets[f]; j < dual.offsets[f + 1]; ++j)
    {
      const int32_t g = dual.faces[j];
      if (region[g] == p)
      {
        if (f < g)
        {
          const double c = capacity[j];
          arcs.push_back({ static_cast<int32_t>(i), node[g], c });
          arcs.push_back({ node[g], static_cast<int32_t>(i), c });
        }
      }
      else if (label[g] == pairA(p))
      {
        sourceCap[i] += capacity[j];
      }
      else if (label[g] == pairB(p))
      {
        sinkCap[i] += capacity[j];
      }
    }
  }
  for (int64_t i = 0; i < n; ++i)
  {
    if (sourceCap[i] > 0.0)
    {
      arcs.push_back({ source, static_cast<int32_t>(i), sourceCap[i] });
      arcs.push_back({ static_cast<int32_t>(i), source, 0.0 });
    }
    if (sinkCap[i] > 0.0)
    {
      arcs.push_back({ static_cast<int32_t>(i), sink, sinkCap[i] });
      arcs.push_back({ sink, static_cast<int32_t>(i), 0.0 });
    }
  }
  progress.report(0.3);

  // Compressed sparse row graph: arcs sorted by tail (stable, so the order is deterministic);
  // arcs 2k and 2k + 1 were pushed as reverses of each other.
  const int64_t na = static_cast<int64_t>(arcs.size());
  std::vector<int64_t> position(na);
  {
    std::vector<int64_t> start(n + 3, 0);
    for (const Arc& a : arcs)
    {
      ++start[a.from + 1];
    }
    std::partial_sum(start.begin(), start.end(), start.begin());
    for (int64_t k = 0; k < na; ++k)
    {
      position[k] = start[arcs[k].from]++;
    }
  }
  std::vector<std::pair<int32_t, int32_t>> sortedArcs(na);
  std::vector<double> cap(na), residual(na);
  for (int64_t k = 0; k < na; ++k)
  {
    sortedArcs[position[k]] = { arcs[k].from, arcs[k].to };
    cap[position[k]] = arcs[k].capacity;
  }
  using Graph = boost::compressed_sparse_row_graph<boost::directedS, boost::no_property,
    boost::no_property, boost::no_property, int32_t, int64_t>;
  using EdgeDesc = boost::graph_traits<Graph>::edge_descriptor;
  Graph graph(
    boost::edges_are_sorted, sortedArcs.begin(), sortedArcs.end(), static_cast<int32_t>(n + 2));
  // Arc k of the sorted list has edge index k (edges_are_sorted keeps the order).
  std::vector<EdgeDesc> reverse(na);
  for (int64_t k = 0; k < na; ++k)
  {
    const int64_t r = position[k ^ 1];
    reverse[position[k]] = EdgeDesc(sortedArcs[r].first, r);
  }
  std::vector<EdgeDesc> predecessor(n + 2);
  std::vector<boost::default_color_type> color(n + 2);
  std::vector<int64_t> distanceToTerminal(n + 2);
  const auto edgeIndex = boost::get(boost::edge_index, graph);
  const auto vertexIndex = boost::get(boost::vertex_index, graph);
  progress.report(0.4);
  boost::boykov_kolmogorov_max_flow(graph,
    boost::make_iterator_property_map(cap.begin(), edgeIndex),
    boost::make_iterator_property_map(residual.begin(), edgeIndex),
    boost::make_iterator_property_map(reverse.begin(), edgeIndex),
    boost::make_iterator_property_map(predecessor.begin(), vertexIndex),
    boost::make_iterator_property_map(color.begin(), vertexIndex),
    boost::make_iterator_property_map(distanceToTerminal.begin(), vertexIndex), vertexIndex, source,
    sink);
  progress.report(0.9);

  // The source tree (black) is a, the sink tree (white) b; a free node in neither tree has no
  // unsaturated path to a terminal and keeps its label.
  std::vector<int32_t> before(n);
  for (int64_t i = 0; i < n; ++i)
  {
    const int32_t f = nodeFace[i];
    before[i] = label[f];
    if (color[i] == boost::black_color)
    {
      label[f] = pairA(region[f]);
    }
    else if (color[i] == boost::white_color)
    {
      label[f] = pairB(region[f]);
    }
  }
  // Every cluster stays non-empty: undo the cuts of the pairs of a cluster that lost all its
  // faces (undoing restores that cluster's faces and can only empty another one through its
  // own pairs, so this ends).
  std::vector<int64_t> count(numClusters, 0);
  for (int64_t f = 0; f < nf; ++f)
  {
    ++count[label[f]];
  }
  std::vector<uint8_t> undone(numPairs, 0);
  for (bool again = true; again;)
  {
    again = false;
    for (int32_t c = 0; c < numClusters; ++c)
    {
      if (count[c] > 0)
      {
        continue;
      }
      for (int32_t p = 0; p < numPairs; ++p)
      {
        if (!undone[p] && (pairA(p) == c || pairB(p) == c))
        {
          undone[p] = 1;
          again = true;
        }
      }
      for (int64_t i = 0; i < n; ++i)
      {
        const int32_t f = nodeFace[i];
        if (undone[region[f]] && label[f] != before[i])
        {
          --count[label[f]];
          ++count[before[i]];
          label[f] = before[i];
        }
      }
    }
  }
  int64_t changed = 0;
  for (int64_t i = 0; i < n; ++i)
  {
    changed += label[nodeFace[i]] != before[i] ? 1 : 0;
  }
  progress.report(1.0);
  return changed;
}

/// Non-branching segments of the boundary graph (section 4.2): paths between vertices whose
/// boundary degree is not 2 (junctions of 3+ boundaries, ends on the mesh border or at
/// non-manifold spots), then closed loops without such vertices, each started at its smallest
/// edge. Paths go out of each end vertex in edge-table order, so the output is deterministic.
void traceSegments(const EdgeTable& edges, const std::vector<uint8_t>& isBoundary, int64_t nv,
  std::vector<int64_t>& offsets, std::vector<int32_t>& vertices)
{
  const int64_t ne = edges.numEdges();
  std::vector<int64_t> start(nv + 1, 0);
  for (int64_t e = 0; e < ne; ++e)
  {
    if (isBoundary[e])
    {
      ++start[edges.vertices[2 * e] + 1];
      ++start[edges.vertices[2 * e + 1] + 1];
    }
  }
  std::partial_sum(start.begin(), start.end(), start.begin());
  std::vector<int32_t> incident(start[nv]);
  {
    std::vector<int64_t> fill(start.begin(), start.end() - 1);
    for (int64_t e = 0; e < ne; ++e)
    {
      if (isBoundary[e])
      {
        incident[fill[edges.vertices[2 * e]]++] = static_cast<int32_t>(e);
        incident[fill[edges.vertices[2 * e + 1]]++] = static_cast<int32_t>(e);
      }
    }
  }
  auto degree = [&](int64_t v) { return start[v + 1] - start[v]; };
  std::vector<uint8_t> used(ne, 0);
  offsets.assign(1, 0);
  vertices.clear();
  auto walk = [&](int32_t v, int32_t e)
  {
    vertices.push_back(v);
    const int32_t first = v;
    for (;;)
    {
      used[e] = 1;
      v = edges.vertices[2 * e] == v ? edges.vertices[2 * e + 1] : edges.vertices[2 * e];
      vertices.push_back(v);
      if (degree(v) != 2 || v == first)
      {
        break;
      }
      const int32_t e0 = incident[start[v]], e1 = incident[start[v] + 1];
      e = used[e0] ? e1 : e0;
      if (used[e])
      {
        break;
      }
    }
    offsets.push_back(static_cast<int64_t>(vertices.size()));
  };
  for (int64_t v = 0; v < nv; ++v)
  {
    if (degree(v) != 2)
    {
      for (int64_t i = start[v]; i < start[v + 1]; ++i)
      {
        if (!used[incident[i]])
        {
          walk(static_cast<int32_t>(v), incident[i]);
        }
      }
    }
  }
  for (int64_t e = 0; e < ne; ++e)
  {
    if (isBoundary[e] && !used[e])
    {
      walk(edges.vertices[2 * e], static_cast<int32_t>(e));
    }
  }
}
} // namespace

FeatureRefinementResult refineFeatures(const TriMesh& mesh, const std::vector<int32_t>& clusterId,
  const std::vector<double>& meanCurvature, const std::vector<double>& faceMeanCurvature,
  const std::vector<uint8_t>& crestVertex, const FeatureRefinementOptions& options,
  const Progress& progress)
{
  validate(mesh, clusterId, meanCurvature, faceMeanCurvature, crestVertex);
  const int64_t nv = mesh.numPoints();
  const int64_t nf = mesh.numTriangles();
  FeatureRefinementResult result;
  result.clusterId = clusterId;
  result.featureVertex.assign(nv, 0);
  result.cornerVertex.assign(nv, 0);
  if (nf == 0)
  {
    progress.report(1.0);
    return result;
  }

  // 1. Topology, and cluster ids made compact (0 .. #clusters - 1) for flat per-cluster arrays.
  const EdgeTable edges = buildEdgeTable(mesh.triangles);
  const DualGraph dual = buildDualGraph(edges, nf);
  std::vector<int32_t> ids = clusterId;
  std::sort(ids.begin(), ids.end());
  ids.erase(std::unique(ids.begin(), ids.end()), ids.end());
  const int64_t numClusters = static_cast<int64_t>(ids.size());
  std::vector<int32_t> label(nf);
  for (int64_t f = 0; f < nf; ++f)
  {
    label[f] =
      static_cast<int32_t>(std::lower_bound(ids.begin(), ids.end(), clusterId[f]) - ids.begin());
  }
  progress.report(0.05);

  // 2. The band and its minimum cuts (eq. 4), repeated on the new boundaries while they move
  //    (see cutPasses).
  const std::vector<int32_t> inputLabel = label;
  // Edge dihedral angles, for eq. 4's crease factor and for straightening.
  const std::vector<double> dihedral = options.dihedralWeight > 0.0 || options.straightenLines
    ? edgeDihedrals(mesh, edges)
    : std::vector<double>();
  const DualCapacity capacity = dualCapacity(
    mesh, edges, dual, faceMeanCurvature, crestVertex, dihedral, options, progress.sub(0.05, 0.1));
  const int passes = std::max(1, options.cutPasses);
  Band first;
  for (int pass = 0; pass < passes; ++pass)
  {
    const Progress step = progress.sub(0.1 + 0.5 * pass / passes, 0.1 + 0.5 * (pass + 1) / passes);
    Band band = buildBand(mesh, edges, dual, label, numClusters, boundaryEdges(edges, label),
      options.bandFraction, pass == 0 ? options.bandRings : 0, pass == 0 ? nullptr : &first,
      step.sub(0.0, 0.3));
    const int64_t changed =
      cutBand(mesh, dual, capacity, band, numClusters, label, step.sub(0.3, 1.0));
    if (pass == 0)
    {
      result.bandFaces = band.size;
      first = std::move(band);
    }
    if (changed == 0)
    {
      break;
    }
  }
  if (options.straightenLines)
  {
    result.straightenedFaces = straightenBoundaries(
      mesh, edges, dihedral, options.creaseAngle * kPi / 180.0, numClusters, label);
  }
  for (int64_t f = 0; f < nf; ++f)
  {
    result.relabeledFaces += label[f] != inputLabel[f] ? 1 : 0;
  }
  for (int64_t f = 0; f < nf; ++f)
  {
    result.clusterId[f] = ids[label[f]];
  }

  // 3. The threshold: the mean of the top curvatureTopFraction of |H| over the vertices that
  //    triangles use, scaled, and at least the noise floor. Vertices ranked by |H| descending,
  //    ties by id, also order the corner maxima below.
  std::vector<uint8_t> used(nv, 0);
  for (int32_t v : mesh.triangles)
  {
    used[v] = 1;
  }
  std::vector<int32_t> byCurvature;
  byCurvature.reserve(nv);
  for (int64_t v = 0; v < nv; ++v)
  {
    if (used[v])
    {
      byCurvature.push_back(static_cast<int32_t>(v));
    }
  }
  std::sort(byCurvature.begin(), byCurvature.end(),
    [&](int32_t a, int32_t b)
    {
      const double ha = std::abs(meanCurvature[a]), hb = std::abs(meanCurvature[b]);
      return ha > hb || (ha == hb && a < b);
    });
  const int64_t numUsed = static_cast<int64_t>(byCurvature.size());
  const int64_t numTop = std::clamp<int64_t>(
    static_cast<int64_t>(std::ceil(options.curvatureTopFraction * static_cast<double>(numUsed))), 1,
    numUsed);
  double topSum = 0.0;
  for (int64_t i = 0; i < numTop; ++i)
  {
    topSum += std::abs(meanCurvature[byCurvature[i]]);
  }
  double lo[3] = { kInf, kInf, kInf }, hi[3] = { -kInf, -kInf, -kInf };
  for (int32_t v : byCurvature)
  {
    for (int c = 0; c < 3; ++c)
    {
      lo[c] = std::min(lo[c], mesh.points[3 * v + c]);
      hi[c] = std::max(hi[c], mesh.points[3 * v + c]);
    }
  }
  const double diagonal = std::sqrt((hi[0] - lo[0]) * (hi[0] - lo[0]) +
    (hi[1] - lo[1]) * (hi[1] - lo[1]) + (hi[2] - lo[2]) * (hi[2] - lo[2]));
  const double floor = diagonal > 0.0 ? options.minCurvatureTimesSize / diagonal : 0.0;
  result.curvatureThreshold =
    std::max(options.curvatureThresholdScale * topSum / static_cast<double>(numTop), floor);
  progress.report(0.65);

  // 4. Segments of the refined boundaries; a segment is kept where the mean |H| along it
  //    (length-weighted: each edge contributes its length times the mean |H| of its ends, so
  //    the density of vertices does not matter) reaches the threshold.
  {
    std::vector<int64_t> segOffsets;
    std::vector<int32_t> segVertices;
    traceSegments(edges, boundaryEdges(edges, label), nv, segOffsets, segVertices);
    result.candidateSegments = static_cast<int64_t>(segOffsets.size()) - 1;
    auto meanAlong = [&](int64_t begin, int64_t end)
    {
      double weighted = 0.0, length = 0.0;
      for (int64_t i = begin; i + 1 < end; ++i)
      {
        const int32_t a = segVertices[i], b = segVertices[i + 1];
        const double l = distance(mesh, a, b);
        weighted += l * 0.5 * (std::abs(meanCurvature[a]) + std::abs(meanCurvature[b]));
        length += l;
      }
      return length > 0.0 ? weighted / length : 0.0;
    };
    for (int64_t s = 0; s < result.candidateSegments; ++s)
    {
      const int64_t begin = segOffsets[s], end = segOffsets[s + 1];
      if (!(meanAlong(begin, end) >= result.curvatureThreshold))
      {
        continue;
      }
      for (int64_t i = begin; i < end; ++i)
      {
        result.lineVertices.push_back(segVertices[i]);
        result.featureVertex[segVertices[i]] = 1;
      }
      result.lineOffsets.push_back(static_cast<int64_t>(result.lineVertices.size()));
      result.lineCurvature.push_back(meanAlong(begin, end));
    }
  }
  progress.report(0.75);

  // 5. Corners: vertices of the highest rank within cornerRings rings (rank = position in
  //    byCurvature, so ties go to the smaller id), found by cornerRings min-dilations of the
  //    rank over the one-ring; the top cornerFraction of them that reach the threshold.
  {
    const VertexRing ring = buildVertexRing(edges, nv);
    std::vector<int32_t> rank(nv, std::numeric_limits<int32_t>::max());
    for (int64_t i = 0; i < numUsed; ++i)
    {
      rank[byCurvature[i]] = static_cast<int32_t>(i);
    }
    std::vector<int32_t> dilated = rank, next(nv);
    const int rings = std::max(0, options.cornerRings);
    for (int r = 0; r < rings; ++r)
    {
      parallel_for(
        nv,
        [&](int64_t v)
        {
          int32_t m = dilated[v];
          for (int64_t j = ring.offsets[v]; j < ring.offsets[v + 1]; ++j)
          {
            m = std::min(m, dilated[ring.ids[j]]);
          }
          next[v] = m;
        },
        progress.sub(0.75 + 0.2 * r / rings, 0.75 + 0.2 * (r + 1) / rings), 4);
      dilated.swap(next);
    }
    std::vector<int32_t> maxima;
    for (int32_t v : byCurvature)
    {
      if (dilated[v] == rank[v])
      {
        maxima.push_back(v);
      }
    }
    const int64_t keep = std::min<int64_t>(static_cast<int64_t>(maxima.size()),
      static_cast<int64_t>(std::ceil(
        std::clamp(options.cornerFraction, 0.0, 1.0) * static_cast<double>(maxima.size()))));
    for (int64_t i = 0; i < keep; ++i)
    {
      if (std::abs(meanCurvature[maxima[i]]) >= result.curvatureThreshold)
      {
        result.cornerVertex[maxima[i]] = 1;
      }
    }
    if (options.junctionCorners)
    {
      // Count feature-line edges at each vertex (a closed line's first vertex is repeated).
      std::vector<int32_t> lineDegree(nv, 0);
      for (int64_t l = 0; l < result.numLines(); ++l)
      {
        for (int64_t i = result.lineOffsets[l]; i + 1 < result.lineOffsets[l + 1]; ++i)
        {
          ++lineDegree[result.lineVertices[i]];
          ++lineDegree[result.lineVertices[i + 1]];
        }
      }
      for (int64_t v = 0; v < nv; ++v)
      {
        result.cornerVertex[v] |= lineDegree[v] >= 3 ? 1 : 0;
      }
    }
    for (int64_t v = 0; v < nv; ++v)
    {
      if (result.cornerVertex[v])
      {
        result.corners.push_back(static_cast<int32_t>(v));
      }
    }
  }
  progress.report(1.0);
  return result;
}
} // namespace tc
