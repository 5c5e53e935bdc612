// SPDX-License-Identifier: BSD-3-Clause
#include "tc/features/spectral_clustering.h"

#include "features/cluster_cleanup.h"
#include "features/components.h"
#include "features/dual_graph.h"
#include "features/face_geometry.h"
#include "features/input_checks.h"
#include "features/kmeans.h"
#include "features/seeded_random.h"
#include "features/spectrum.h"
#include "features/statistics.h"

#include "tc/common/errors.h"

#include <algorithm>
#include <cmath>
#include <string>

namespace tc
{
namespace
{
using namespace detail::spectral;

void validate(const TriMesh& mesh, const std::vector<double>& faceMeanCurvature,
  const std::vector<uint8_t>& crestVertex, const SpectralClusteringOptions& o)
{
  const int64_t nv = mesh.numPoints();
  const int64_t nf = mesh.numTriangles();
  const std::string where = "spectralClustering: ";
  if (mesh.triangles.size() % 3 != 0 || mesh.points.size() % 3 != 0)
  {
    throw InputError(where + "points and triangles must hold 3 numbers each");
  }
  if (o.numClusters < 1)
  {
    throw InputError(
      where + "numClusters is " + std::to_string(o.numClusters) + "; ask for at least 1 cluster");
  }
  if (nf < o.numClusters)
  {
    throw InputError(where + "the mesh has " + std::to_string(nf) + " faces, fewer than the " +
      std::to_string(o.numClusters) + " clusters asked for; lower numClusters to at most " +
      std::to_string(nf));
  }
  detail::requireVertexIds(mesh, where);
  for (int64_t v = 0; v < nv; ++v)
  {
    if (!std::isfinite(mesh.points[3 * v]) || !std::isfinite(mesh.points[3 * v + 1]) ||
      !std::isfinite(mesh.points[3 * v + 2]))
    {
      throw InputError(where + "point " + std::to_string(v) +
        " has a non-finite coordinate; clean the mesh with tcMeshPreparation first");
    }
  }
  if (static_cast<int64_t>(faceMeanCurvature.size()) != nf)
  {
    throw InputError(where + "faceMeanCurvature has " + std::to_string(faceMeanCurvature.size()) +
      " values but the mesh " + std::to_string(nf) +
      " faces; pass computeCurvature()'s faceMean of the same mesh");
  }
  for (int64_t f = 0; f < nf; ++f)
  {
    if (!std::isfinite(faceMeanCurvature[f]))
    {
      throw InputError(where + "faceMeanCurvature of face " + std::to_string(f) +
        " is not finite; recompute the curvature of a mesh without degenerate faces");
    }
  }
  if (!crestVertex.empty() && static_cast<int64_t>(crestVertex.size()) != nv)
  {
    throw InputError(where + "crestVertex has " + std::to_string(crestVertex.size()) +
      " values but the mesh " + std::to_string(nv) + " vertices; pass crestVertices() of the " +
      "same mesh or an empty array");
  }
  if (o.numEigenvectors < 0 || !(o.crestBeta > 0.0) || !(o.extraEdgeFactor >= 0.0) ||
    !(o.exactNormalSigma >= 0.0) || o.nystromSamples < 2 || o.nystromRank < 1 ||
    !(o.nystromKernelScale > 0.0) || o.kmeansRestarts < 1 || o.kmeansIterations < 1 ||
    o.kmeansSampleSize < 0)
  {
    throw InputError(where +
      "invalid options: need numEigenvectors >= 0, crestBeta > 0, "
      "extraEdgeFactor >= 0, exactNormalSigma >= 0, nystromSamples >= 2, nystromRank >= 1, "
      "nystromKernelScale > 0, kmeansRestarts >= 1, kmeansIterations >= 1, "
      "kmeansSampleSize >= 0");
  }
}

// Section 4.1: row i of M_e, columns e_j / sqrt(lambda_j), embeds face i (then scaled per
// SpectralEmbedding). Columns with lambda <= 0 are left out: M_e M_e^T approximates the
// similarity only through positive eigenvalues.
// @return n x dim row-major
std::vector<double> embed(const Spectrum& s, SpectralEmbedding mode, int& dim)
{
  const int ne = static_cast<int>(s.values.size());
  const int64_t n = static_cast<int64_t>(s.degree.size());
  std::vector<int> keep;
  for (int j = 0; j < ne; ++j)
  {
    if (s.values[j] > 1e-12)
    {
      keep.push_back(j);
    }
  }
  dim = std::max(1, static_cast<int>(keep.size()));
  std::vector<double> x(static_cast<size_t>(n) * dim, 0.0);
  for (int64_t i = 0; i < n; ++i)
  {
    double* row = x.data() + i * dim;
    double norm2 = 0.0;
    for (size_t j = 0; j < keep.size(); ++j)
    {
      row[j] = s.vectors[i * ne + keep[j]] / std::sqrt(s.values[keep[j]]);
      norm2 += row[j] * row[j];
    }
    double scale = 1.0;
    if (mode == SpectralEmbedding::RandomWalk)
    {
      scale = 1.0 / std::sqrt(s.degree[i]);
    }
    else if (mode == SpectralEmbedding::RowNormalized && norm2 > 0.0)
    {
      scale = 1.0 / std::sqrt(norm2);
    }
    for (int j = 0; j < dim; ++j)
    {
      row[j] *= scale;
    }
  }
  return x;
}

// The faces of the components clustered exactly (at least 2 clusters, at most
// nystromThreshold faces), or empty when there are none.
std::vector<uint8_t> exactFaces(const Components& components, int64_t nf, int64_t nystromThreshold)
{
  std::vector<uint8_t> exact;
  for (int64_t c = 0; c < components.count(); ++c)
  {
    if (components.clusters[c] >= 2 && components.sizes[c] <= nystromThreshold)
    {
      exact.resize(nf, 0);
      for (int32_t f : components.faces[c])
      {
        exact[f] = 1;
      }
    }
  }
  return exact;
}

// What every component's clustering reads: the exact graph of eq. 3 and the per-face terms.
struct SpectralInputs
{
  const ExactGraph& exact;
  const std::vector<double>& centroids; // #F x 3
  const std::vector<double>& normals;   // #F x 3 unit
  const std::vector<double>& curvExp;   // #F |kappa| / sigma_k
  const SpectralClusteringOptions& options;
};

// The spectrum of component c (Ne wanted): the exact graph of eq. 3 up to nystromThreshold
// faces, the Nystrom approximation above.
Spectrum componentSpectrum(const SpectralInputs& in, const std::vector<int32_t>& faces, int64_t c,
  int ne, std::vector<int32_t>& localId, const Progress& progress)
{
  const int64_t n = static_cast<int64_t>(faces.size());
  if (n > in.options.nystromThreshold)
  {
    return nystromSpectrum(faces, in.centroids, in.normals, in.curvExp, ne, in.options,
      mixSeed(in.options.seed, 100, static_cast<uint64_t>(c)), progress);
  }
  for (int64_t i = 0; i < n; ++i)
  {
    localId[faces[i]] = static_cast<int32_t>(i);
  }
  return exactSpectrum(faces, in.exact, localId, in.curvExp, in.normals, ne, in.options, progress);
}

} // namespace

namespace detail
{
namespace spectral
{
int32_t clusterComponents(const ComponentSpectrum& spectrumOf, const Components& components,
  const SpectralClusteringOptions& options, SpectralClusteringResult& result,
  const Progress& progress)
{
  const int64_t nf = static_cast<int64_t>(result.clusterId.size());
  int64_t done = 0;
  int32_t nextCluster = 0;
  for (int64_t c = 0; c < components.count(); ++c)
  {
    const std::vector<int32_t>& faces = components.faces[c];
    const int64_t n = components.sizes[c];
    const Progress part =
      progress.sub(static_cast<double>(done) / nf, static_cast<double>(done + n) / nf);
    done += n;
    const int k = components.clusters[c];
    if (k <= 1)
    {
      for (int32_t f : faces)
      {
        result.clusterId[f] = nextCluster;
      }
      ++nextCluster;
      part.report(1.0);
      continue;
    }
    if (k >= n)
    {
      // As many clusters as faces: nothing to embed (and a 2-face graph has eigenvalues 1
      // and -1, whose embedding could not tell the faces apart).
      for (int32_t f : faces)
      {
        result.clusterId[f] = nextCluster++;
      }
      part.report(1.0);
      continue;
    }
    result.usedNystrom |= n > options.nystromThreshold;
    const int neWanted = options.numEigenvectors > 0 ? options.numEigenvectors : k;
    const Spectrum spectrum = spectrumOf(c, faces, neWanted, part.sub(0.0, 0.8));
    if (c == components.largest)
    {
      result.eigenvalues = spectrum.values;
    }
    int dim = 0;
    const std::vector<double> embedding = embed(spectrum, options.embedding, dim);
    const std::vector<int32_t> labels = kmeans(embedding, n, dim, k, options,
      mixSeed(options.seed, 200, static_cast<uint64_t>(c)), part.sub(0.8, 1.0));
    // Renumber by first face: cluster ids follow the order of the lowest face of each cluster,
    // and clusters left empty (fewer distinct rows than k) take no id.
    std::vector<int32_t> renumber(k, -1);
    for (int64_t i = 0; i < n; ++i)
    {
      int32_t& id = renumber[labels[i]];
      if (id < 0)
      {
        id = nextCluster++;
      }
      result.clusterId[faces[i]] = id;
    }
  }
  return nextCluster;
}
} // namespace spectral
} // namespace detail

SpectralClusteringResult spectralClustering(const TriMesh& mesh,
  const std::vector<double>& faceMeanCurvature, const std::vector<uint8_t>& crestVertex,
  const SpectralClusteringOptions& options, const Progress& progress)
{
  validate(mesh, faceMeanCurvature, crestVertex, options);

  // 1. The dual graph of adjacent faces (section 4.2), over face centroids.
  const std::vector<double> centroids = detail::faceCentroids(mesh);
  const std::vector<double> normals = detail::faceUnitNormals(mesh);
  const DualGraph adjacent =
    buildAdjacentDual(mesh, centroids, crestVertex, progress.sub(0.0, 0.05));

  // 2. Components, their faces and their shares of the clusters.
  const Components components = findComponents(adjacent, options.numClusters);

  // 3. Eq. 3's terms: |kappa| / sigma_k, and the exact graph (extra edges) with sigma_d.
  const std::vector<double> curvExp = detail::curvatureExponents(faceMeanCurvature);
  const ExactGraph exact =
    buildExactGraph(adjacent, exactFaces(components, mesh.numTriangles(), options.nystromThreshold),
      options.extraEdgeFactor, progress.sub(0.05, 0.2));

  // 4. Per component: eigenvectors, embedding (section 4.1) and k-means.
  SpectralClusteringResult result;
  result.clusterId.assign(mesh.numTriangles(), -1);
  const SpectralInputs inputs{ exact, centroids, normals, curvExp, options };
  std::vector<int32_t> localId(mesh.numTriangles(), 0);
  const ComponentSpectrum spectrumOf =
    [&](int64_t c, const std::vector<int32_t>& faces, int ne, const Progress& part)
  { return componentSpectrum(inputs, faces, c, ne, localId, part); };
  const int32_t numIds =
    clusterComponents(spectrumOf, components, options, result, progress.sub(0.2, 1.0));

  // 5. One connected region per cluster, numbered by first face.
  if (options.connectedClusters)
  {
    keepLargestPieces(adjacent, numIds, result.clusterId);
  }
  result.numClusters = renumberByFirstFace(result.clusterId);
  progress.report(1.0);
  return result;
}
} // namespace tc
