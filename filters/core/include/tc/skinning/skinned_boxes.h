// SPDX-License-Identifier: BSD-3-Clause
/// @file skinned_boxes.h
/// Skinned oriented bounding boxes of a skinned atlas's charts (Feng et al. 2010, 6.1 and
/// Fig. 14): every corner of a chart's box carries bone influence weights of its own, fitted so
/// that the box follows the chart through the animations, and the box is grown until it holds
/// every sample of the chart at every sampled frame. The renderer skins the corners with the
/// frame's skinning matrices and projects the box for LOD selection (eq. 6).
///
/// The posed box. A box's 8 corners, indexed by bits (corner m = c0 + (m & 1) a + (m >> 1 & 1) b
/// + (m >> 2 & 1) c, with a, b, c its edge vectors), are posed each by linear blend skinning with
/// its own skin. The posed corners q_0 .. q_7 form no parallelepiped in general, so the posed
/// box is defined as the parallelepiped spanned from q_0 by the posed axes a' = q_1 - q_0,
/// b' = q_2 - q_0, c' = q_4 - q_0 (eq. 6's pivot and major axes) and widened to the range of
/// all 8 posed corners in the coordinates of that frame: {q_0 + [a' b' c'] u : lo <= u <= hi},
/// lo and hi the smallest and largest coordinates of the q_m. It holds all 8 posed corners and
/// eq. 6's parallelepiped of the 4 posed corners c0 .. c3 (u in [0, 1]^3). posedBoxFrame gives
/// it; boxContains is the containment every fitted box guarantees.
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
  /// Bind pose, as AtlasChart::box: c0, then its neighbours c0 + a, c0 + b, c0 + c (xyz each).
  std::array<double, 12> corners{};
  /// Per corner m = 0 .. 7 in bit order (see the file comment): 0 c0, 1 c0 + a, 2 c0 + b,
  /// 3 c0 + a + b, 4 c0 + c, 5 c0 + a + c, 6 c0 + b + c, 7 c0 + a + b + c. Weights >= 0, sum 1.
  std::array<PointSkin, 8> skin{};
};

struct SkinnedBoxOptions
{
  /// Poses sampled evenly over [0, duration] of every animation (both ends included), plus the
  /// animation's key times when it has fewer keys than this. The weights are fitted and the
  /// boxes grown over these frames.
  int framesPerAnimation = 16;
  /// Extra frames (evenly over every animation) the growth checks too, so that containment also
  /// holds between the fitted frames where the motion is smooth.
  int checkFramesPerAnimation = 64;
  /// The growth that makes the box hold every sample of the fitted and checked frames is
  /// enlarged by this fraction (a safety margin for poses between the checked frames).
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
  int64_t frames = 0;              ///< fitted frames over all animations
};

/// Fits every chart's skinned box over the frames of all of the atlas rig's animations (the rest
/// pose when it has none).
/// @throws InputError  for an atlas without a Skin attribute or rig
SkinnedBoxesResult fitSkinnedBoxes(
  const Atlas& atlas, const SkinnedBoxOptions& options = {}, const Progress& progress = {});

/// The 8 corners of `box` (bit order) posed by `matrices` (skinningMatrices of a frame): each
/// corner by linear blend skinning with its PointSkin.
std::array<std::array<double, 3>, 8> poseBox(
  const SkinnedBox& box, const std::vector<Matrix4>& matrices);

/// The posed box of 8 posed corners in its own frame: the pivot q_0, the inverse of the axes
/// [a' b' c'] (row-major 3 x 3), the coordinate ranges lo, hi, and its volume.
struct BoxFrame
{
  std::array<double, 3> pivot{};
  std::array<double, 9> inverseAxes{};
  std::array<double, 3> lo{};
  std::array<double, 3> hi{};
  double volume = 0.0;
};

/// The frame of the posed box of `corners` (poseBox's).
BoxFrame posedBoxFrame(const std::array<std::array<double, 3>, 8>& corners);

/// Whether `point` lies in the posed box `frame` (its coordinates within [lo, hi], each widened
/// by `tolerance` times its range).
bool boxContains(const BoxFrame& frame, const std::array<double, 3>& point, double tolerance = 0.0);
} // namespace tc
