// SPDX-License-Identifier: BSD-3-Clause
/// @file proxy_bones.h
/// Proxy bones of a deforming sequence without a skeleton (Feng et al. 2010, section 4.3: "once
/// we represent each cluster using one proxy bone, we can further compute bone transformations
/// and bone influence weights ... that solve least-squares problems [James and Twigg 2005]"):
/// one bone per deformation cluster, and a linear blend skin of at most 4 bones per point fitted
/// to every frame, so that tc::skinPoints poses the rest frame into each frame.
#pragma once

#include "tc/common/progress.h"
#include "tc/io/sequence_io.h"
#include "tc/skinning/deformation_clustering.h"
#include "tc/skinning/skin.h"

#include <cstdint>
#include <string>
#include <vector>

namespace tc
{
struct ProxyBonesOptions
{
  /// How the faces are clustered into bones (numClusters = the number of bones).
  DeformationClusteringOptions clustering;
  /// Influences per point, in [1, kMaxInfluences].
  int maxInfluences = kMaxInfluences;
  /// Rounds of (weights given the bone transforms, then the transforms given the weights) after
  /// the first weights fitted to the rigid transforms; at least 1.
  int iterations = 3;
  /// The affine bone fit is regularized towards the bone's rigid transform of the frame (over
  /// its interior points, see fitProxyBones()) by this weight relative to the mean diagonal of
  /// its block of the normal equations: it keeps a bone whose weighted points are (nearly)
  /// coplanar or few well posed and is far too small to move a well posed one.
  double affineRegularization = 1e-6;
};

/// Distances between fitted and input points, per frame.
struct FitError
{
  std::vector<double> rms; ///< #K root mean square point distance per frame, mesh units
  std::vector<double> max; ///< #K largest point distance per frame, mesh units
  double totalRms = 0.0;   ///< RMS over every point of frames 1 .. #K - 1 (of frame 0 when it
                           ///< is the only one): frame 0, the rest, is exact by construction
  double totalMax = 0.0;   ///< the largest distance over all frames
  double diagonal = 0.0;   ///< the rest frame's bounding-box diagonal

  /// `distance` as a fraction of the diagonal (0 when the diagonal is 0).
  double relative(double distance) const { return diagonal > 0.0 ? distance / diagonal : 0.0; }
};

struct ProxyBonesResult
{
  DeformationClusteringResult clusters; ///< the clusters, one proxy bone each, and their lines
  /// One root joint per cluster: names "proxy 0", "proxy 1", .., parent -1, restLocal and
  /// inverseBind the identity (the rest frame is the bind pose).
  Skeleton skeleton;
  /// #V x 4: non-negative weights, at most maxInfluences non-zero, summing to 1 (in float).
  SkinWeights skin;
  /// #K x #B skinning matrices (row-major affine): tc::skinPoints(frames[0], skin,
  /// frameMatrices[k]) is the fitted frame k. frameMatrices[0] is the identity.
  std::vector<std::vector<Matrix4>> frameMatrices;
  /// #K x #B the rigid transforms (rotation and translation) of each cluster, rest to frame k,
  /// by least squares over the cluster's points (Kabsch): the rigid baseline.
  std::vector<std::vector<Matrix4>> rigidMatrices;
  /// #V the cluster (bone) each point belongs to: the one holding the largest area of the
  /// faces around it (ties to the lower id); a point no face uses takes the bone whose rigid
  /// motion follows it best.
  std::vector<int32_t> pointBone;
  FitError lbs;   ///< of the fitted skin
  FitError rigid; ///< of the rigid baseline: each point moved by its pointBone's rigid transform
};

/// Fits proxy bones and a linear blend skin to a deforming sequence.
///
/// 1. Clusters (clusterDeformation(), one bone each) and each point's own bone (pointBone).
/// 2. Rigid transforms: per bone and frame, the rotation and translation that carry the bone's
///    rest points (those of its faces) closest to their frame-k positions (Kabsch; a reflection
///    is turned into the nearest rotation): rigidMatrices, the baseline. The skin starts from
///    the same fit over the cluster's interior points only (those whose faces all belong to
///    it; all of them below 3): the points of a boundary also follow the next cluster, and
///    fitting a bone to them spreads the joint's bend into the bone.
/// 3. Candidate bones of a point: its own bone, the bones of the faces around it, and the bones
///    of the clusters adjacent to those (sharing a mesh edge).
/// 4. Weights per point, fitted to all frames given the bone transforms: the least-squares
///    error sum_k |sum_b w_b M_b^k p - p^k|^2 over the candidates, with w >= 0 and sum w = 1 (an
///    exact primal active-set method on the simplex); the maxInfluences largest are kept and
///    solved again.
/// 5. Transforms given the weights (James and Twigg 2005): per frame, the 3 x 4 affine matrices
///    of all bones together by linear least squares over all points (one normal matrix for
///    every frame and coordinate), lightly regularized towards the interior rigid transforms
///    (affineRegularization).
/// 6. Steps 4 and 5 alternate `iterations` times; the last transforms are fitted to the float
///    weights that the skin stores, and frame 0 keeps the identity.
///
/// @param[in] triangles  #F x 3 point ids (fanTriangles() of a sequence's soup)
/// @param[in] frames     #K x (#V x 3) positions; frame 0 is the rest (bind) pose
/// @param[in] options    see ProxyBonesOptions
/// @param[in] progress   reported about 20 times; may abort (tc::Aborted)
/// @throws InputError  as clusterDeformation(), and for options out of range
ProxyBonesResult fitProxyBones(const std::vector<int32_t>& triangles,
  const std::vector<std::vector<float>>& frames, const ProxyBonesOptions& options = {},
  const Progress& progress = {});

/// fitProxyBones() over the fan triangles of the sequence's soup and its frames.
/// @throws InputError  as fanTriangles() and fitProxyBones()
ProxyBonesResult fitProxyBones(const DeformingSequence& sequence,
  const ProxyBonesOptions& options = {}, const Progress& progress = {});

/// The fit as a rig: its proxy skeleton and one animation named `name` whose sampled poses are
/// the fitted frames at `times` (seconds, one per frame), so that a sequence travels through the
/// pipeline and into the atlas as a skinned mesh does.
/// @throws InputError  when `times` has not one time per fitted frame or is not ascending
Rig proxyRig(
  const ProxyBonesResult& fit, const std::vector<double>& times, const std::string& name);

/// The name of proxy bone `bone`: "proxy <bone>".
std::string proxyJointName(int32_t bone);

/// True if `rig`'s skeleton is one fitProxyBones() made (root joints named by proxyJointName()):
/// fitted to frames, not a skeleton the file had.
bool isProxyRig(const Rig& rig);

/// The distances between `fitted` frames and the input `frames`, per frame.
/// @param[in] fitted  #K x (#V x 3)
/// @param[in] frames  #K x (#V x 3), frame 0 the rest (its bounding box gives the diagonal)
/// @throws InputError  when the frame counts or sizes differ
FitError measureFit(
  const std::vector<std::vector<double>>& fitted, const std::vector<std::vector<float>>& frames);
} // namespace tc
