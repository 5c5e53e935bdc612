// SPDX-License-Identifier: BSD-3-Clause
/// @file bone_transforms.h
/// The bone transforms of a proxy-bone skin (Feng et al. 2010, 4.3; James and Twigg 2005): the
/// rigid motion of each cluster per frame (Kabsch), and the affine matrices of all bones that
/// best reproduce a frame given the skin weights (linear least squares).
#pragma once

#include "tc/common/progress.h"
#include "tc/skinning/skin.h"

#include <Eigen/Core>

#include <cstdint>
#include <vector>

namespace tc
{
namespace detail
{
namespace proxy
{
/// Point v of a frame (#V x 3 floats), in double.
inline Eigen::Vector3d pointOf(const std::vector<float>& frame, int64_t v)
{
  return { frame[3 * v], frame[3 * v + 1], frame[3 * v + 2] };
}

/// Per bone, the points of its cluster's faces, ascending (CSR).
struct BonePoints
{
  std::vector<int64_t> offsets; ///< #B + 1
  std::vector<int32_t> points;
  int64_t numBones() const { return static_cast<int64_t>(offsets.size()) - 1; }
};

/// @param[in] triangles  #F x 3 point ids
/// @param[in] clusterId  #F bone of each face, in [0, numBones)
BonePoints bonePoints(
  const std::vector<int32_t>& triangles, const std::vector<int32_t>& clusterId, int32_t numBones);

/// Per bone, the interior points of its cluster: those whose faces all belong to it. The points
/// on a boundary move with the cluster on the other side as well, and the joint region between
/// two parts is where the motion is least rigid, so these fit a bone's own motion better. A
/// bone with fewer than 3 interior points keeps all of its points.
/// @param[in] nv  number of points
BonePoints interiorBonePoints(const std::vector<int32_t>& triangles,
  const std::vector<int32_t>& clusterId, int32_t numBones, int64_t nv);

/// Per frame and bone, the rotation and translation that carry the bone's rest points closest
/// to their positions in the frame (least squares: Kabsch's SVD, a reflection turned into the
/// nearest rotation). Frame 0 is the identity.
/// @param[in] frames  #K x (#V x 3), frame 0 the rest
/// @return #K x #B
std::vector<std::vector<Matrix4>> rigidTransforms(
  const std::vector<std::vector<float>>& frames, const BonePoints& bones, const Progress& progress);

/// Per bone, the RMS distance between its points moved by its rigid transforms and their
/// positions, over frames 1 .. #K - 1 (0 with a single frame or no point).
/// @param[in] rigid  #K x #B rigidTransforms()
/// @return #B
std::vector<double> rigidResiduals(const std::vector<std::vector<float>>& frames,
  const BonePoints& bones, const std::vector<std::vector<Matrix4>>& rigid);

/// Skin weights during the fit: `slots` (bone, weight) pairs per point, unused slots weight 0.
struct Influences
{
  int slots = 0;
  std::vector<int32_t> bones;  ///< #V x slots
  std::vector<double> weights; ///< #V x slots, non-negative, summing to 1 per point
};

/// Per frame k >= 1, the 3 x 4 affine matrices of all bones together that minimize
/// sum_v |sum_b w_vb M_b p_v - p_v^k|^2 (James and Twigg 2005), plus `regularization` times the
/// mean diagonal of each bone's block of the normal equations times |M_b - rigid_b^k|^2, which
/// keeps a bone whose weighted points do not span 3-D well posed. The points are centred and
/// scaled for the solve; one factorization serves every frame. Frame 0 is the identity.
/// @param[in] rigid  #K x #B rigidTransforms()
/// @return #K x #B
std::vector<std::vector<Matrix4>> affineTransforms(const std::vector<std::vector<float>>& frames,
  const Influences& influences, const std::vector<std::vector<Matrix4>>& rigid,
  double regularization, const Progress& progress);
} // namespace proxy
} // namespace detail
} // namespace tc
