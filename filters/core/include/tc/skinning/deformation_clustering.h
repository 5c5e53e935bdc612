// SPDX-License-Identifier: BSD-3-Clause
/// @file deformation_clustering.h
/// Deformation discontinuities of a deforming sequence (Feng et al. 2010, section 4.3, eq. 5):
/// faces are clustered spectrally, as in section 4.1, by how alike their deformation gradients
/// (Sumner and Popovic 2004, Sumner et al. 2005) are over all frames, so that cluster boundaries
/// run across bending joints; the boundaries become feature lines, and each cluster can carry a
/// proxy bone (proxy_bones.h). Also the same lines from a skin: the boundaries between the faces
/// that different joints dominate.
#pragma once

#include "tc/common/mesh.h"
#include "tc/common/progress.h"
#include "tc/skinning/skin.h"

#include <cstdint>
#include <vector>

namespace tc
{
/// The polygons of `soup` as triangles over the same point ids: a polygon of n >= 3 corners is
/// the fan of its first corner (n - 2 triangles, in polygon order). The point ids, and so the
/// rows of a sequence's frames or of a skin, are unchanged.
/// @return #F x 3 point ids
/// @throws InputError  for a polygon of fewer than 3 corners or a point id out of range
std::vector<int32_t> fanTriangles(const PolygonSoup& soup);

/// The deformation gradient of every face from `rest` to `deformed` (Sumner et al. 2005): the
/// 3 x 3 matrix Gamma with Gamma [e1 e2 e3] = [e1' e2' e3'], e1 = v2 - v1, e2 = v3 - v1 and
/// e3 = n / sqrt(|n|), n = e1 x e2 (the fourth vertex v4 = v1 + e3), primes in the deformed
/// frame. A rigid motion gives its rotation; a face degenerate in the rest frame (|n| below
/// 1e-6 times its longest squared edge: float positions resolve no thinner one) gets all zeros
/// and its flag set.
/// @param[in] triangles  #F x 3 point ids
/// @param[in] rest       #V x 3 rest positions (xyz interleaved)
/// @param[in] deformed   #V x 3 deformed positions
/// @param[out] degenerate  #F 1 where the rest face has no gradient (may be nullptr)
/// @return #F x 9, each Gamma row-major
/// @throws InputError  as clusterDeformation() for the two frames
std::vector<double> deformationGradients(const std::vector<int32_t>& triangles,
  const std::vector<float>& rest, const std::vector<float>& deformed,
  std::vector<uint8_t>* degenerate = nullptr);

struct DeformationClusteringOptions
{
  /// Number of clusters k over the whole sequence; 0 (the default) picks
  /// defaultDeformationClusters(#F). Clusters never span edge-connected components; each gets
  /// at least one, and a share by how much it deforms (see clusterDeformation(), step 2).
  int numClusters = 0;
  /// Extra dual edges join faces whose dual-path distance is below this factor times the mean
  /// distance between adjacent faces (section 4.2; the static clustering's default).
  double extraEdgeFactor = 2.0;
  /// Multiplies sigma_Gamma of eq. 5 (1 = the paper's rule): smaller values make the clusters
  /// follow the deformation more and the distance less.
  double gradientSigmaScale = 1.0;
  /// k-means restarts (k-means++ seeding), the best inertia is kept.
  int kmeansRestarts = 8;
  /// Seed of every random choice: equal seeds give identical results.
  uint64_t seed = 1;
};

/// The number of clusters the default (numClusters = 0) picks for a mesh of `numFaces` faces:
/// round(sqrt(numFaces) / 2), clamped to [2, 64] and to the face count. Proxy bones need a
/// cluster per part that moves rigidly, and a finer mesh, which resolves more parts and
/// smaller ones (fingers, facial features), gets more, but a skeleton's joint count grows far
/// more slowly than the face count; the square root follows that, and the bounds keep a coarse
/// mesh from a single bone and a dense one from more bones than a GPU skinning palette takes.
int defaultDeformationClusters(int64_t numFaces);

struct DeformationClusteringResult
{
  std::vector<int32_t> clusterId;        ///< #F cluster of each face, numbered in the order of the
                                         ///< first face of each cluster (boneDominanceClusters: the
                                         ///< dominant joint)
  int32_t numClusters = 0;               ///< clusters produced (ids in [0, numClusters))
  std::vector<uint8_t> featureVertex;    ///< #V 1 on a cluster boundary
  std::vector<int64_t> lineOffsets{ 0 }; ///< #L + 1 offsets into lineVertices
  std::vector<int32_t> lineVertices; ///< the cluster boundaries as paths over mesh edges (vertex
                                     ///< ids), broken at junctions of 3 or more clusters and at
                                     ///< the mesh border, as tc::refineFeatures returns its
                                     ///< lines; a closed line repeats its first vertex. Every
                                     ///< boundary edge is on a line (section 4.3 keeps them all)
  std::vector<double> eigenvalues;   ///< the largest eigenvalues of D^-1/2 W_b D^-1/2 of the
                                     ///< largest component, descending (empty for a dominance
                                     ///< clustering or a single cluster)
  double sigmaGamma = 0.0;           ///< sigma_Gamma of eq. 5 (0: no face deforms differently)
  double sigmaD = 0.0;               ///< sigma_d of eq. 5, in mesh units

  int64_t numLines() const { return static_cast<int64_t>(lineOffsets.size()) - 1; }
};

/// Clusters the faces of a deforming sequence by their deformation (Feng et al. 2010, 4.3).
///
/// 1. Gamma_i^k, the deformation gradient of face i from frame 0 (the rest) to frame k
///    (deformationGradients()), for every frame k >= 1.
/// 2. The dual graph of tc::spectralClustering: faces joined across shared edges and to the
///    faces within extraEdgeFactor mean adjacent distances along the surface; dist(f_i, f_j) the
///    dual-path length, sigma_d its standard deviation over the graph's edges. Each
///    edge-connected component is clustered on its own, with a share of k proportional to
///    (n_c r_c^2)^(1/3), n_c its face count and r_c the RMS residual of the one rigid motion per
///    frame that fits it best (at least 1 each, face-count shares when nothing deforms): where m
///    bones cut a part's error to about r_c / m, these shares minimize the total squared error,
///    so a rigid accessory gets one bone and a long bending part several.
/// 3. Eq. 5 on every dual edge: w_b(i, j) = exp(-sum_k ||Gamma_i^k - Gamma_j^k||_F / (n_a
///    sigma_Gamma)) exp(-dist(f_i, f_j) / sigma_d), n_a the number of frames after the rest
///    and sigma_Gamma (times gradientSigmaScale) the standard deviation of the gradients over
///    all faces and frames: the gradients Gamma_i^k of every non-degenerate face i and every
///    frame k >= 1 taken as 9-vectors, sigma_Gamma = sqrt(mean_{i,k} ||Gamma_i^k - G||_F^2), G
///    their mean (population; the root of the trace of their covariance). A face degenerate in
///    the rest frame keeps the distance term alone; with a single frame, or when no gradient
///    varies, the deformation term is 1.
/// 4. Per edge-connected component: the eigenvectors of D^-1/2 W_b D^-1/2, the random-walk
///    embedding and k-means of tc::spectralClustering (the same solver, embedding and k-means);
///    each cluster keeps its largest connected piece.
/// 5. The boundaries between clusters as feature lines.
///
/// @param[in] triangles  #F x 3 point ids (fanTriangles() of a sequence's soup)
/// @param[in] frames     #K x (#V x 3) positions per frame; frame 0 is the rest
/// @param[in] options    see DeformationClusteringOptions
/// @param[in] progress   reported about 10 times; may abort (tc::Aborted)
/// @throws InputError  for no frame, frames of different sizes or not a multiple of 3, a
///   non-finite coordinate (naming the frame and the point), no triangle, a point id out of
///   range, numClusters < 0 or above the face count, or an option out of range
DeformationClusteringResult clusterDeformation(const std::vector<int32_t>& triangles,
  const std::vector<std::vector<float>>& frames, const DeformationClusteringOptions& options = {},
  const Progress& progress = {});

/// Clusters the faces of a skinned mesh by the joint that dominates them: per face, the joint
/// with the largest weight summed over its 3 corners (ties to the lower joint index). Cluster
/// ids are joint indices (so the ids are not compact; numClusters = the largest used + 1); the
/// boundaries between the regions of different joints become feature lines as in
/// clusterDeformation(). Its sigmas are 0.
/// @param[in] triangles  #F x 3 point ids into the skin's points
/// @param[in] skin       #V x 4 joints and weights (tc::Scene::skin)
/// @throws InputError  for an empty skin, no triangle or a point id outside the skin
DeformationClusteringResult boneDominanceClusters(
  const std::vector<int32_t>& triangles, const SkinWeights& skin);
} // namespace tc
