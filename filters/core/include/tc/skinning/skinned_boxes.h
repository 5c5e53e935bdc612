// SPDX-License-Identifier: BSD-3-Clause
/// @file skinned_boxes.h
/// Skinned oriented bounding boxes of a skinned atlas's charts (Feng et al. 2010, 6.1 and
/// Fig. 14): corners of a chart's box carry bone influence weights of their own, fitted so that
/// the box follows the chart through the animations, and the box's range is fitted so that it
/// holds every sample of the chart at every sampled frame. The renderer skins the corners with
/// the frame's skinning matrices (poseLodBoxes) and projects the box for LOD selection (eq. 6).
///
/// The posed box. As in the paper ("only four of the eight corners of the OBB are transformed
/// to form three new major axes"), a few corners are skinned: c0, c2 and c3, each by linear
/// blend skinning with its own skin, to q_0, q_2, q_3. They give the posed frame: pivot q_0 and
/// the orthogonal axes A_3 = q_3 - q_0, A_1 along A_2' x A_3 (A_2' = q_2 - q_0) and A_2 along
/// A_3 x A_1 with |A_2| = |A_2'|, |A_1| = |a1| (the bind thin edge: a bend moves the chart
/// across its thickness, which the range holds; scaling it with the posed edges would shrink it
/// where the chart folds and the edges shorten, and widen the range by as much). The posed box is
/// the parallelepiped of coordinates lo <= u <= hi in that frame, q_0 + sum_k u_k A_k, its range
/// [lo, hi] fitted per box once (the range of the chart's samples over all sampled frames, plus a
/// margin): a box again, which LOD selection projects (eq. 6) and culls as it is. Why not the
/// parallelepiped of the posed corners themselves: where the chart bends, corners skinned apart
/// skew it (a thin edge can fold into the chart's plane) and a skewed frame magnifies the chart's
/// bulge in its coordinates; and growing the bind box until the posed one holds the samples need
/// not converge, since far corners with different skins skew the posed box more the farther they
/// move. The range makes containment exact at the sampled frames. poseBox gives the posed box's
/// pivot and its three neighbours, posedBoxFrame its frame, boxContains the containment every
/// fitted box guarantees at the fitted and checked frames (and, by the margin, between them where
/// the motion is smooth).
#pragma once

#include "tc/common/progress.h"
#include "tc/gim/atlas.h"
#include "tc/skinning/skin.h"

#include <array>
#include <cstdint>
#include <vector>

namespace tc
{
/// One chart's skinned box.
struct SkinnedBox
{
  /// Bind pose, as AtlasChart::box: c0, then its neighbours c0 + a1, c0 + a2, c0 + a3 (xyz each);
  /// a1 is the thin edge (across the chart), orthogonal to a2 and a3.
  std::array<double, 12> corners{};
  /// The skins of c0, c2 and c3 (file comment): joints (at most 4 distinct ones over the three)
  /// and weights (>= 0, sum 1).
  std::array<PointSkin, 3> skin{};
  /// The posed box's range of coordinates u in the posed frame (file comment): [0, 1]^3 is the
  /// bind box carried by the frame.
  std::array<double, 3> lo{ 0.0, 0.0, 0.0 };
  std::array<double, 3> hi{ 1.0, 1.0, 1.0 };
};

struct SkinnedBoxOptions
{
  /// Poses sampled evenly over [0, duration] of every animation (both ends included), plus the
  /// animation's key times when it has fewer keys than this. The weights are fitted over these
  /// frames, and the range holds their samples.
  int framesPerAnimation = 16;
  /// Extra frames (evenly over every animation) whose samples the range holds too; the largest
  /// change of each side of the range between two consecutive ones is added to that side, a
  /// margin for the poses between them where the motion is smooth.
  int checkFramesPerAnimation = 64;
  /// How far the samples of the fitted and checked frames reach beyond the bind box carried by
  /// the posed frame (coordinates outside [0, 1]) is enlarged by this fraction on every side.
  double padding = 0.1;
  /// Thinnest extent of a bind box and of a tight box, as a fraction of the chart's bind-box
  /// diagonal (keeps flat charts' boxes invertible and their volume ratios finite).
  double minExtent = 1e-3;
};

struct SkinnedBoxesResult
{
  std::vector<SkinnedBox> boxes; ///< per chart
  /// Mean over charts and fitted frames of the posed box's volume over the tight box's: the
  /// chart's posed samples' oriented box by PCA (eigenvectors of their covariance), every
  /// extent floored at minExtent.
  double meanVolumeRatio = 0.0;
  double medianVolumeRatio = 0.0;  ///< over the same ratios
  double largestVolumeRatio = 0.0; ///< over the same ratios
  /// The posed boxes' volumes summed over charts and fitted frames over the tight boxes' sum:
  /// the ratio of the volume the boxes enclose, which a thin chart does not dominate.
  double summedVolumeRatio = 0.0;
  int64_t frames = 0; ///< fitted frames over all animations
};

/// Fits every chart's skinned box over the frames of all of the atlas rig's animations (the rest
/// pose when it has none).
/// @throws InputError  for an atlas without a Skin attribute or rig
SkinnedBoxesResult fitSkinnedBoxes(
  const Atlas& atlas, const SkinnedBoxOptions& options = {}, const Progress& progress = {});

/// The posed box of `box` at `matrices` (skinningMatrices of a frame), in double: its pivot
/// q_0 + sum_k lo_k A_k and the pivot's three neighbours (the pivot plus (hi_k - lo_k) A_k), with
/// the posed frame of the file comment.
std::array<std::array<double, 3>, 4> poseBox(
  const SkinnedBox& box, const std::vector<Matrix4>& matrices);

/// The parallelepiped of a pivot p_0 and its neighbours p_1 .. p_3 (poseBox's): the pivot, the
/// inverse of the axes [p_1 - p_0, p_2 - p_0, p_3 - p_0] (row-major 3 x 3; NaN when they are
/// degenerate, so that it holds nothing) and its volume.
struct BoxFrame
{
  std::array<double, 3> pivot{};
  std::array<double, 9> inverseAxes{};
  double volume = 0.0;
};

/// The frame of the parallelepiped of `corners` (poseBox's).
BoxFrame posedBoxFrame(const std::array<std::array<double, 3>, 4>& corners);

/// Whether `point` lies in the posed box `frame`: its coordinates u within [-tolerance,
/// 1 + tolerance].
bool boxContains(const BoxFrame& frame, const std::array<double, 3>& point, double tolerance = 0.0);

/// Skinned boxes laid out for posing every frame: structure of arrays in float, a chart's skinned
/// corners side by side as 4 lanes (c0, c2, c3 and an idle one) so that one vector operation
/// poses them together.
struct LodSkinnedBoxes
{
  /// #C x 12: the skinned bind corners by coordinate: x of the 4 lanes, then y, then z
  std::vector<float> corners;
  /// #C x 4: the joints that move the box (the union of its corners' joints), unused slots 0
  std::vector<int32_t> joints;
  /// #C x 16: the weight of joint slot s at lane i at [16 c + 4 s + i] (0 where unused)
  std::vector<float> weights;
  /// #C: |a1|, the length of the posed thin axis
  std::vector<float> thickness;
  /// #C x 6: the posed box's range, lo (3), then hi - lo (3)
  std::vector<float> range;
  std::vector<int32_t> jointCount; ///< #C: joint slots used (0 .. 4)
  int32_t paletteJoints = 0;       ///< largest joint + 1: the palette poseLodBoxes needs

  /// Number of charts #C.
  int32_t size() const { return static_cast<int32_t>(jointCount.size()); }

  /// The arrays of `boxes` (corners and weights rounded to float).
  /// @throws InputError for a box whose skins use more than 4 distinct joints, a negative
  ///         joint or a negative or non-finite weight
  static LodSkinnedBoxes fromBoxes(const std::vector<SkinnedBox>& boxes);
};

/// Poses every box by `palette` and writes it in LodCharts' layout, so that tc::selectLevels can
/// run on the posed boxes (write them into LodCharts::box and LodCharts::worldArea): the box
/// poseBox gives in double, posed in float, as its pivot and the axes to the pivot's neighbours,
/// and worldArea = eq. 6 on those axes. Allocates the palette's 4 broadcast copies once per call
/// and nothing per chart; runs in parallel over blocks of charts when #C is large.
/// @param[in] palette  joints x kPaletteFloats: the first three rows of every joint's skinning
///                     matrix, row-major (tc::appendPaletteRows)
/// @param[out] box  #C x 12: the pivot, then the three axes (xyz each)
/// @param[out] worldArea  #C: |a1 x a2| + |a1 x a3| + |a2 x a3| of the posed axes
/// @throws InputError when `boxes`' arrays disagree in size or `joints` < boxes.paletteJoints
void poseLodBoxes(
  const LodSkinnedBoxes& boxes, const float* palette, int32_t joints, float* box, float* worldArea);
} // namespace tc
