// SPDX-License-Identifier: BSD-3-Clause
/// @file weight_fit.h
/// The skin weights of proxy bones (James and Twigg 2005, as Feng et al. 2010, 4.3 uses them):
/// each point's own bone and candidate bones, and the non-negative weights summing to 1 that
/// reproduce its positions over all frames best, given the bone transforms.
#pragma once

#include "skinning/bone_transforms.h"

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
/// Per point, the bone of the cluster holding the largest area of the faces around it (ties to
/// the lower bone); a point no face uses takes the bone whose rigid motion follows it best over
/// the frames.
/// @param[in] clusterId  #F bone of each face
/// @param[in] rigid      #K x #B rigidTransforms()
/// @return #V
std::vector<int32_t> pointBones(const std::vector<int32_t>& triangles,
  const std::vector<int32_t>& clusterId, const std::vector<std::vector<float>>& frames,
  const std::vector<std::vector<Matrix4>>& rigid);

/// Candidate bones per point (CSR, own bone first, the others ascending): the point's own bone,
/// the bones of the faces around it, and every bone whose cluster shares a mesh vertex with one
/// of those (the clusters next to the point's).
struct Candidates
{
  std::vector<int64_t> offsets; ///< #V + 1
  std::vector<int32_t> bones;
};

/// @param[in] pointBone  #V pointBones()
Candidates candidateBones(const std::vector<int32_t>& triangles,
  const std::vector<int32_t>& clusterId, const std::vector<int32_t>& pointBone, int32_t numBones);

/// argmin_w 1/2 w^T G w - h^T w subject to w >= 0 and sum w = 1, by a primal active-set method
/// started at the vertex e_start of the simplex: free weights solve the equality-constrained
/// problem exactly (its KKT system); a step that would make one negative stops at the bound and
/// drops it; a weight at 0 is freed while its Lagrange multiplier is negative. Finite (each step
/// lowers the objective), exact up to rounding.
/// @param[in] g  m x m symmetric positive (semi-)definite; make it definite for a unique answer
/// @param[in] h  m
Eigen::VectorXd simplexLeastSquares(const Eigen::MatrixXd& g, const Eigen::VectorXd& h, int start);

/// Per point, the weights of its candidate bones that minimize sum_{k >= 1} |sum_b w_b M_b^k p -
/// p^k|^2 over w >= 0, sum w = 1 (simplexLeastSquares, with a negligible pull towards the own
/// bone that decides between bones moving the point alike), then the maxInfluences largest
/// solved again on their own.
/// @param[in] matrices  #K x #B bone transforms
Influences fitWeights(const std::vector<std::vector<float>>& frames,
  const std::vector<std::vector<Matrix4>>& matrices, const Candidates& candidates,
  int maxInfluences, const Progress& progress);
} // namespace proxy
} // namespace detail
} // namespace tc
