// SPDX-License-Identifier: BSD-3-Clause
/// @file deformation_gradients.h
/// Deformation gradients of the faces of a sequence (Sumner et al. 2005) and the terms of eq. 5
/// of Feng et al. 2010 built from them: per dual edge, how much the gradients of its two faces
/// differ over the frames, and sigma_Gamma.
#pragma once

#include "features/dual_graph.h"

#include "tc/common/progress.h"

#include <cstdint>
#include <vector>

namespace tc
{
namespace detail
{
namespace deformation
{
/// Per face, the inverse of the rest edge matrix V = [e1 e2 e3] (columns; see
/// tc::deformationGradients), so that Gamma = V' V^-1 costs one product per frame.
struct RestInverses
{
  std::vector<double> inverse;     ///< #F x 9 row-major, zeros for a degenerate face
  std::vector<uint8_t> degenerate; ///< #F 1 where V is not invertible
};

/// @param[in] triangles  #F x 3 point ids
/// @param[in] rest       #V x 3 rest positions
RestInverses restInverses(const std::vector<int32_t>& triangles, const std::vector<float>& rest);

/// Gamma = V' V^-1 of every face in `deformed` (zeros for a degenerate rest face).
/// @param[out] gamma  #F x 9 row-major
void frameGradients(const std::vector<int32_t>& triangles, const RestInverses& rest,
  const std::vector<float>& deformed, std::vector<double>& gamma);

/// Eq. 5's deformation term on every entry of a dual graph.
struct GradientDifferences
{
  /// Per CSR entry (f, g) of the graph: (1 / n_a) sum_{k >= 1} ||Gamma_f^k - Gamma_g^k||_F,
  /// n_a the number of frames after the rest; 0 where f or g is degenerate (no gradient).
  std::vector<double> meanDifference;
  /// sigma_Gamma: the population standard deviation of the gradients as 9-vectors over every
  /// non-degenerate face and every frame k >= 1, i.e. sqrt(mean_{i,k} ||Gamma_i^k -
  /// mean(Gamma)||_F^2), the root of the trace of their covariance; 0 with a single frame.
  double sigma = 0.0;
};

/// @param[in] triangles  #F x 3 point ids
/// @param[in] frames     #K x (#V x 3), frame 0 the rest
/// @param[in] graph      the dual graph (may be empty: no entry)
/// @param[in] progress   reported once per frame; may abort
GradientDifferences gradientDifferences(const std::vector<int32_t>& triangles,
  const std::vector<std::vector<float>>& frames, const spectral::DualGraph& graph,
  const Progress& progress);
} // namespace deformation
} // namespace detail
} // namespace tc
