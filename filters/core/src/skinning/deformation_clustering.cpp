// SPDX-License-Identifier: BSD-3-Clause
#include "tc/skinning/deformation_clustering.h"

#include "features/cluster_cleanup.h"
#include "features/components.h"
#include "features/dual_graph.h"
#include "features/face_geometry.h"
#include "features/feature_lines.h"
#include "features/refinement_band.h"
#include "features/spectrum.h"
#include "skinning/cluster_allocation.h"
#include "skinning/deformation_gradients.h"
#include "skinning/sequence_checks.h"

#include "tc/common/errors.h"
#include "tc/common/mesh_topology.h"
#include "tc/features/spectral_clustering.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <string>

namespace tc
{
namespace
{
using namespace detail::spectral;

// exp() of anything below this is still a normal double, as in the static clustering: a face
// unlike all its neighbours keeps a tiny similarity instead of becoming an isolated node.
constexpr double kMinExponent = -600.0;

void validateOptions(const DeformationClusteringOptions& o, int64_t nf)
{
  const std::string where = "clusterDeformation: ";
  if (o.numClusters < 0 || o.numClusters > nf)
  {
    throw InputError(where + "numClusters is " + std::to_string(o.numClusters) + " for a mesh of " +
      std::to_string(nf) + " faces; ask for 0 (automatic) to " + std::to_string(nf) + " clusters");
  }
  if (!(o.extraEdgeFactor >= 0.0) || !(o.gradientSigmaScale > 0.0) || o.kmeansRestarts < 1)
  {
    throw InputError(where +
      "invalid options: need extraEdgeFactor >= 0, gradientSigmaScale > 0, kmeansRestarts >= 1");
  }
}

// The rest frame as a mesh (double points) for the dual graph.
TriMesh restMesh(const std::vector<int32_t>& triangles, const std::vector<float>& rest)
{
  TriMesh mesh;
  mesh.points.assign(rest.begin(), rest.end());
  mesh.triangles = triangles;
  return mesh;
}

// Faces of the components that get two clusters or more (the others need no graph).
std::vector<uint8_t> clusteredFaces(const Components& components, int64_t nf)
{
  std::vector<uint8_t> use;
  for (int64_t c = 0; c < components.count(); ++c)
  {
    if (components.clusters[c] >= 2)
    {
      use.resize(nf, 0);
      for (int32_t f : components.faces[c])
      {
        use[f] = 1;
      }
    }
  }
  return use;
}

// Eq. 5 on every entry of the graph. A zero sigma drops its (then constant) factor.
std::vector<double> similarities(const ExactGraph& exact,
  const detail::deformation::GradientDifferences& gradients, double sigmaScale)
{
  const double invSigmaGamma = gradients.sigma > 0.0 ? 1.0 / (sigmaScale * gradients.sigma) : 0.0;
  std::vector<double> w(exact.graph.ids.size());
  for (size_t e = 0; e < w.size(); ++e)
  {
    w[e] = std::exp(std::max(kMinExponent,
      -gradients.meanDifference[e] * invSigmaGamma - exact.graph.dist[e] * exact.invSigmaD));
  }
  return w;
}

// The options of the shared component clustering: the exact graph everywhere (eq. 5 needs
// the dual edges; there is no Nystrom kernel for it) and the static clustering's embedding.
SpectralClusteringOptions componentOptions(const DeformationClusteringOptions& o, int k)
{
  SpectralClusteringOptions s;
  s.numClusters = k;
  s.nystromThreshold = std::numeric_limits<int64_t>::max();
  s.kmeansRestarts = o.kmeansRestarts;
  s.seed = o.seed;
  return s;
}

// The cluster boundaries as lines (what tc::refineFeatures does with its kept segments, here
// with every segment kept).
void addBoundaryLines(
  const std::vector<int32_t>& triangles, int64_t nv, DeformationClusteringResult& result)
{
  const EdgeTable edges = buildEdgeTable(triangles);
  const detail::Polylines lines = detail::refinement::boundarySegments(
    edges, detail::refinement::boundaryEdges(edges, result.clusterId), nv);
  result.featureVertex.assign(nv, 0);
  result.lineOffsets = lines.offsets;
  result.lineVertices.assign(lines.nodes.begin(), lines.nodes.end());
  for (int32_t v : result.lineVertices)
  {
    result.featureVertex[v] = 1;
  }
}

// The joint with the largest weight summed over the corners of face f (ties to the lower
// joint); `sums` is scratch.
int32_t dominantJoint(const std::vector<int32_t>& triangles, const SkinWeights& skin, int64_t f,
  std::vector<std::pair<int32_t, double>>& sums)
{
  sums.clear();
  for (int c = 0; c < 3; ++c)
  {
    const int64_t v = triangles[3 * f + c];
    for (int i = 0; i < kMaxInfluences; ++i)
    {
      const int32_t joint = skin.joints[kMaxInfluences * v + i];
      const double w = skin.weights[kMaxInfluences * v + i];
      auto it =
        std::find_if(sums.begin(), sums.end(), [joint](const auto& s) { return s.first == joint; });
      if (it == sums.end())
      {
        sums.emplace_back(joint, w);
      }
      else
      {
        it->second += w;
      }
    }
  }
  int32_t best = sums.front().first;
  double most = sums.front().second;
  for (const auto& [joint, w] : sums)
  {
    if (w > most || (w == most && joint < best))
    {
      best = joint;
      most = w;
    }
  }
  return best;
}
} // namespace

std::vector<int32_t> fanTriangles(const PolygonSoup& soup)
{
  const int64_t nv = soup.numPoints();
  std::vector<int32_t> triangles;
  for (int64_t p = 0; p < soup.numPolygons(); ++p)
  {
    const int64_t begin = soup.offsets[p];
    const int64_t n = soup.offsets[p + 1] - begin;
    if (n < 3)
    {
      throw InputError("fanTriangles: polygon " + std::to_string(p) + " has " + std::to_string(n) +
        " corners; a face needs at least 3");
    }
    for (int64_t i = 0; i < n; ++i)
    {
      const int64_t id = soup.connectivity[begin + i];
      if (id < 0 || id >= nv)
      {
        throw InputError("fanTriangles: polygon " + std::to_string(p) + " references point " +
          std::to_string(id) + " of " + std::to_string(nv) + "; fix the connectivity");
      }
    }
    for (int64_t i = 1; i + 1 < n; ++i)
    {
      for (int64_t c : { begin, begin + i, begin + i + 1 })
      {
        triangles.push_back(static_cast<int32_t>(soup.connectivity[c]));
      }
    }
  }
  return triangles;
}

std::vector<double> deformationGradients(const std::vector<int32_t>& triangles,
  const std::vector<float>& rest, const std::vector<float>& deformed,
  std::vector<uint8_t>* degenerate)
{
  detail::requireSequence("deformationGradients: ", triangles, { rest, deformed });
  const detail::deformation::RestInverses inverses =
    detail::deformation::restInverses(triangles, rest);
  std::vector<double> gamma;
  detail::deformation::frameGradients(triangles, inverses, deformed, gamma);
  if (degenerate != nullptr)
  {
    *degenerate = inverses.degenerate;
  }
  return gamma;
}

int defaultDeformationClusters(int64_t numFaces)
{
  const int64_t k =
    std::llround(std::sqrt(static_cast<double>(std::max<int64_t>(numFaces, 0))) / 2);
  return static_cast<int>(
    std::min<int64_t>(std::clamp<int64_t>(k, 2, 64), std::max<int64_t>(numFaces, 1)));
}

DeformationClusteringResult clusterDeformation(const std::vector<int32_t>& triangles,
  const std::vector<std::vector<float>>& frames, const DeformationClusteringOptions& options,
  const Progress& progress)
{
  detail::requireSequence("clusterDeformation: ", triangles, frames);
  const int64_t nf = static_cast<int64_t>(triangles.size() / 3);
  const int64_t nv = static_cast<int64_t>(frames[0].size() / 3);
  validateOptions(options, nf);
  const int k = options.numClusters > 0 ? options.numClusters : defaultDeformationClusters(nf);

  // 1. The dual graph of section 4.2 over the rest frame, its components with their shares of
  // the clusters, and sigma_d.
  const TriMesh rest = restMesh(triangles, frames[0]);
  const DualGraph adjacent =
    buildAdjacentDual(rest, detail::faceCentroids(rest), {}, progress.sub(0.0, 0.05));
  Components components = findComponents(adjacent, k);
  detail::proxy::allocateByRigidResidual(triangles, frames, k, components, progress.sub(0.05, 0.1));
  const ExactGraph exact = buildExactGraph(
    adjacent, clusteredFaces(components, nf), options.extraEdgeFactor, progress.sub(0.1, 0.15));

  // 2. Eq. 5: the deformation gradients' differences over the frames, and the distances.
  const detail::deformation::GradientDifferences gradients =
    detail::deformation::gradientDifferences(
      triangles, frames, exact.graph, progress.sub(0.15, 0.4));
  const std::vector<double> weights = similarities(exact, gradients, options.gradientSigmaScale);

  // 3. Per component: the spectrum of W_b, embedding and k-means (section 4.1's machinery).
  SpectralClusteringResult clusters;
  clusters.clusterId.assign(nf, -1);
  std::vector<int32_t> localId(nf, 0);
  const ComponentSpectrum spectrumOf =
    [&](int64_t, const std::vector<int32_t>& faces, int ne, const Progress& part)
  {
    for (size_t i = 0; i < faces.size(); ++i)
    {
      localId[faces[i]] = static_cast<int32_t>(i);
    }
    return weightedSpectrum(faces, exact.graph, weights, localId, ne, part);
  };
  const int32_t numIds = clusterComponents(
    spectrumOf, components, componentOptions(options, k), clusters, progress.sub(0.4, 0.95));

  // 4. One connected region per cluster (proxy bones need closed regions, section 4.3).
  keepLargestPieces(adjacent, numIds, clusters.clusterId);
  DeformationClusteringResult result;
  result.numClusters = renumberByFirstFace(clusters.clusterId);
  result.clusterId = std::move(clusters.clusterId);
  result.eigenvalues = std::move(clusters.eigenvalues);
  result.sigmaGamma = gradients.sigma * options.gradientSigmaScale;
  result.sigmaD = exact.invSigmaD > 0.0 ? 1.0 / exact.invSigmaD : 0.0;

  // 5. The boundaries as feature lines.
  addBoundaryLines(triangles, nv, result);
  progress.report(1.0);
  return result;
}

DeformationClusteringResult boneDominanceClusters(
  const std::vector<int32_t>& triangles, const SkinWeights& skin)
{
  const std::string where = "boneDominanceClusters: ";
  if (skin.empty() || skin.joints.size() % kMaxInfluences != 0 ||
    skin.weights.size() != skin.joints.size())
  {
    throw InputError(where + "the skin has no points (or joints and weights of different " +
      "sizes); pass the skin of a skinned scene");
  }
  const int64_t nv = static_cast<int64_t>(skin.joints.size() / kMaxInfluences);
  detail::requireTriangles(where, triangles, nv);
  const int64_t nf = static_cast<int64_t>(triangles.size() / 3);
  DeformationClusteringResult result;
  result.clusterId.assign(nf, 0);
  std::vector<std::pair<int32_t, double>> sums;
  for (int64_t f = 0; f < nf; ++f)
  {
    result.clusterId[f] = dominantJoint(triangles, skin, f, sums);
    result.numClusters = std::max(result.numClusters, result.clusterId[f] + 1);
  }
  addBoundaryLines(triangles, nv, result);
  return result;
}
} // namespace tc
