// SPDX-License-Identifier: BSD-3-Clause
/// @file spectral_clustering.h
/// Spectral clustering of the dual graph of a triangle mesh (Feng et al. 2010, section 4.1 and
/// eq. 1-3): faces are graph nodes, joined across shared edges and to nearby non-adjacent faces;
/// the similarity of eq. 3 is low across high curvature and across crest lines, so cluster
/// boundaries follow features. Eigenvectors of D^-1/2 W D^-1/2 (Spectra) embed the faces; k-means
/// groups them. Meshes above a face-count threshold use the Nystrom approximation (Fowlkes et al.
/// 2004) so that time and memory stay bounded.
#pragma once

#include "tc/common/mesh.h"
#include "tc/common/progress.h"

#include <cstdint>
#include <vector>

namespace tc
{
/// How the eigenvectors e_i of D^-1/2 W D^-1/2 (eigenvalues lambda_i) become the coordinates
/// that k-means groups. Section 4.1 embeds face i as row i of M_e = [e_1/sqrt(lambda_1) ..].
enum class SpectralEmbedding
{
  /// Row i of D^-1/2 M_e: the eigenvectors of the random walk D^-1 W (Shi and Malik 2000,
  /// which section 4.1 builds on). They are constant over a well separated cluster whatever
  /// the degrees, so faces of high curvature (small degree under eq. 3) stay with their region.
  RandomWalk,
  /// Row i of M_e as printed. Its coordinates scale with sqrt(degree), so the faces of high
  /// curvature gather near the origin and k-means tends to make one scattered cluster of them.
  Paper,
  /// Row i of M_e scaled to unit length (Ng, Jordan and Weiss 2002).
  RowNormalized,
};

struct SpectralClusteringOptions
{
  /// Number of clusters k over the whole mesh. Clusters never span connected components: each
  /// component gets a share in proportion to its face count (see spectralClustering()).
  int numClusters = 16;
  /// Number of eigenvectors Ne of the embedding; 0 means the component's cluster count (k for
  /// a mesh in one piece).
  int numEigenvectors = 0;
  /// Coordinates of the faces for k-means (see SpectralEmbedding).
  SpectralEmbedding embedding = SpectralEmbedding::RandomWalk;
  /// Eq. 3's beta where a crest line separates two faces (1 elsewhere).
  double crestBeta = 0.1;
  /// Extra dual edges join faces whose dual-path distance is below this factor times the mean
  /// distance between adjacent faces (the paper uses 2); 0 keeps adjacent faces only.
  double extraEdgeFactor = 2.0;
  /// Exact graph: eq. 3 is multiplied by exp(-(1 - n_i . n_j) / exactNormalSigma), n the unit
  /// normals of the two faces (the Nystrom kernel's normal term, see nystromNormalSigma); 0
  /// gives the paper's eq. 3. It cuts the graph across sharp creases that carry no crest line
  /// (small values such as 0.05 put the cluster boundaries of CAD meshes on their sharp edges).
  /// Off by default: where creases are split over several edges of moderate angle it helps no
  /// more than a change of seed, and on noisy scans its effect is unknown.
  double exactNormalSigma = 0.0;
  /// Components with more faces than this use the Nystrom method; the others the exact sparse
  /// graph of eq. 3, whose time and memory grow faster than linearly with the face count
  /// (sparse Cholesky factorization).
  int64_t nystromThreshold = 100000;
  /// Nystrom: number of sampled faces m (uniformly among the component's faces). Keep it well
  /// above numClusters (tens of samples per cluster); time grows with m.
  int nystromSamples = 500;
  /// Nystrom: rank of the approximation (largest eigenpairs of the sample-to-sample kernel
  /// kept, at least Ne); time and memory grow linearly with it (#F x rank floats).
  int nystromRank = 64;
  /// Nystrom: width sigma_d of the kernel, in mean distances from a sample face to its nearest
  /// other sample (the kernel needs to reach a few samples from every face).
  double nystromKernelScale = 6.0;
  /// Nystrom: the kernel also decays with the angle between face normals, by
  /// exp(-(1 - n_i . n_j) / nystromNormalSigma), in place of the crest term beta; 0 turns
  /// this off (eq. 3 with beta = 1).
  double nystromNormalSigma = 1.0;
  /// k-means: k-means++ seeding, this many restarts, the best (lowest inertia) is kept.
  int kmeansRestarts = 8;
  /// k-means: at most this many Lloyd iterations per run (a run stops earlier once fewer than
  /// 1 face in 2000 changes cluster).
  int kmeansIterations = 100;
  /// k-means: on a component with more faces than this (and than 50 per cluster), the
  /// restarts run on a seeded sample of that many faces and the best one is refined on all
  /// faces (0: always all faces).
  int64_t kmeansSampleSize = 10000;
  /// Each cluster keeps only its largest edge-connected piece; its other pieces join the
  /// clusters around them. k-means in the embedding does not see connectivity, and a stray
  /// piece would give the boundary stage a closed curve around nothing.
  bool connectedClusters = true;
  /// Seed of every random choice: equal seeds give identical results, whatever the number of
  /// threads.
  uint64_t seed = 1;
};

struct SpectralClusteringResult
{
  std::vector<int32_t> clusterId;  ///< #F cluster of each face, in [0, numClusters), numbered
                                   ///< in the order of the first face of each cluster
  std::vector<double> eigenvalues; ///< the Ne largest eigenvalues of D^-1/2 W D^-1/2 of the
                                   ///< largest component, descending (empty if it has a single
                                   ///< cluster; Nystrom's are approximations)
  int32_t numClusters = 0;         ///< clusters actually produced (summed over components)
  bool usedNystrom = false;        ///< whether any component used the Nystrom method
};

/// Clusters the faces of a mesh so that cluster boundaries follow high curvature and crest
/// lines (section 4.1-4.2 of Feng et al. 2010).
///
/// The dual graph joins faces that share an edge (dist = centroid to edge midpoint to centroid)
/// and faces whose dual-path distance is below extraEdgeFactor times the mean adjacent one
/// (dist = that path length). Weights follow eq. 3; beta = crestBeta where both ends of the
/// shared edge are crest vertices, or, for an extra edge, where its shortest dual path crosses
/// such an edge. sigma_k is the standard deviation of |faceMeanCurvature| over all faces,
/// sigma_d that of dist over the graph's edges; a zero sigma drops its (then constant) factor.
///
/// Each edge-connected component is clustered on its own. Its share of numClusters is
/// proportional to its face count (largest remainder); a component whose share rounds to zero
/// still gets one cluster, taken back from a component whose share was rounded up when there
/// is one, so the total is numClusters unless many small components have no share at all
/// (then result.numClusters is larger). A component never gets more clusters than faces.
///
/// The embedding (see SpectralEmbedding) comes from the Ne largest eigenpairs of
/// D^-1/2 W D^-1/2: shift-invert Lanczos (Spectra) on the normalized Laplacian for the exact
/// graph, the orthogonalized Nystrom extension (Fowlkes et al. 2004) above nystromThreshold.
/// k-means (k-means++ seeding, restarts) groups the rows. Deterministic for a given seed.
///
/// @param[in] mesh               #V x 3 points, #F x 3 triangles (manifold or not)
/// @param[in] faceMeanCurvature  #F mean curvature per face (tcCurvature's FaceMeanCurvature)
/// @param[in] crestVertex        #V 1 where a crest line passes (crestVertices()), may be empty
/// @param[in] options            see SpectralClusteringOptions
/// @param[in] progress           progress and abort (tc::Aborted)
/// @throws InputError if the mesh has fewer faces than numClusters, an option is out of range,
///   a triangle references a missing vertex, a point is not finite, or the arrays do not match
///   the mesh (or hold a non-finite curvature)
SpectralClusteringResult spectralClustering(const TriMesh& mesh,
  const std::vector<double>& faceMeanCurvature, const std::vector<uint8_t>& crestVertex,
  const SpectralClusteringOptions& options = {}, const Progress& progress = {});
} // namespace tc
