// SPDX-License-Identifier: BSD-3-Clause
/// @file atlas_quantization.h
/// The lattice an atlas's positions and normals lie on (private to the core: the last step of
/// buildGeometryImages snaps to it, the atlas file stores the integer codes, docs/atlas-format.md
/// section 4). One frame for all charts, so that a sample two charts share stays bit-identical in
/// both, and one decode rule for the snap and the reader, so that the atlas in memory (what the
/// renderer uploads) equals what the file reads back bit for bit.
///
/// - Positions: coordinate a of code q is float(double(origin[a] + q) * step), step = 2^e the
///   largest power of two <= inputDiagonal * 2^-16, origin[a] in steps. The snap moves a point
///   by at most step * sqrt(3) / 2 <= 1.33e-5 of the diagonal (1/75 of the 0.1 %).
/// - Normals: octahedral codes (u, v), |u|, |v| <= L = 2^(kNormalBits - 1) - 1 (Cigolle et al.
///   2014, "A survey of efficient representations for independent unit vectors"), decoded in
///   double and rounded to float; the closest of the four codes around a normal's projection
///   moves it by at most about 0.041 degrees at 12 bits (0.02 at 13, which costs a bit more per
///   component).
#pragma once

#include "tc/gim/atlas.h"

#include <array>
#include <cstdint>
#include <optional>

namespace tc::detail
{
/// Positions: the step is 2^e <= inputDiagonal * 2^-kPositionStepBits.
constexpr int32_t kPositionStepBits = 16;
/// Position codes run 0 .. extent with extent at most this (2^24: the frame is then a few
/// hundred diagonals wide, far beyond any atlas whose samples lie near its input).
constexpr int64_t kMaxPositionExtent = int64_t(1) << 24;
/// Normals: bits per octahedral component.
constexpr int32_t kNormalBits = 12;

/// The position lattice: coordinate a of code q (0 <= q <= extent[a]) is
/// float(double(origin[a] + q) * 2^stepExponent).
struct PositionFrame
{
  int32_t stepExponent = 0;
  std::array<int64_t, 3> origin{}; ///< in steps
  std::array<int64_t, 3> extent{}; ///< the largest code per axis
};

/// The frame of `atlas`: the step from inputDiagonal, origin and extent from the bounding box of
/// every chart sample's position (the layout must be valid). None when inputDiagonal is not
/// positive and finite, a position is not finite, or the box spans more than
/// kMaxPositionExtent steps (an atlas whose diagonal does not fit its samples).
std::optional<PositionFrame> positionFrame(const Atlas& atlas);

/// Coordinate `axis` of code q: the one decode rule.
float decodeCoordinate(const PositionFrame& frame, int axis, int64_t q);

/// The nearest codes of `p`; false when one lies outside 0 .. extent (then `q` is unset).
bool encodePosition(const PositionFrame& frame, const float* p, std::array<int64_t, 3>& q);

/// The largest octahedral code, L = 2^(bits - 1) - 1.
constexpr int32_t normalLimit(int32_t bits)
{
  return (int32_t(1) << (bits - 1)) - 1;
}

/// The unit normal of octahedral code (u, v), |u|, |v| <= normalLimit(bits), into `n`: the one
/// decode rule. -0.0 never comes out, so that the encode of a decoded normal is unambiguous.
void decodeNormal(int32_t bits, int32_t u, int32_t v, float* n);

/// The octahedral code whose normal is closest to `n` of the four around its projection; false
/// when `n` is zero or not finite.
bool encodeNormal(int32_t bits, const float* n, std::array<int32_t, 2>& uv);

/// Every chart sample's Position and Normal (attributes 0 and 1) replaced by the decode of its
/// code, in every image (a shared or inherited sample, bit-identical before, stays so); every
/// chart's box grown and its level errors raised by the farthest the snap moved one of its
/// samples, so that the box still holds them and the errors still bound them. An atlas without
/// a frame keeps its positions; a zero or non-finite normal stays as it is. The layout must be
/// valid.
void snapToLattice(Atlas& atlas);
} // namespace tc::detail
