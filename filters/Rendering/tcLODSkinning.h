// SPDX-License-Identifier: BSD-3-Clause
/**
 * @file tcLODSkinning.h
 * @brief What tcLODMapper computes on the CPU to pose a skinned atlas (Feng et al. 2010, 5.2,
 * 6.1): the skin packed for the shader's buffer textures, each instance's skinning matrices per
 * frame, and the instance's posed chart boxes for LOD selection. Private to the Rendering
 * module; no OpenGL here.
 */
#ifndef tcLODSkinning_h
#define tcLODSkinning_h

#include "tc/gim/atlas.h"
#include "tc/gim/lod_selection.h"
#include "tc/skinning/skinned_boxes.h"

#include <array>
#include <cstdint>
#include <string>
#include <vector>

namespace tcvtk::lod
{
/// The Skin attribute's texels in PackTexels' order, 4 floats per texel each: the joints (exact
/// integers as floats) and their weights; texels between charts hold joint 0, weight 0.
struct SkinTexels
{
  std::vector<float> joints;
  std::vector<float> weights;
};
SkinTexels PackSkin(const tc::Atlas& atlas, int skinAttribute);

/// A skinned atlas as the mapper poses it: the rig, its skinned chart boxes, and the frame's
/// skinning matrices of every instance.
struct SkinnedAtlas
{
  bool valid = false;           ///< the atlas has a Skin attribute and a rig
  int32_t joints = 0;           ///< joints of the rig's skeleton
  tc::LodSkinnedBoxes boxes;    ///< per chart, fitted when the atlas arrives
  std::vector<float> palettes;  ///< instances x joints x tc::kPaletteFloats, the frame's
  std::vector<float> posedBox;  ///< instances x #C x 12, the boxes posed by the palettes
  std::vector<float> posedArea; ///< instances x #C
  /// Every chart's finest samples (image 0, each texel once) and their skins: the exact posed
  /// bounds of a few instances (PosedBounds).
  std::vector<double> finestPoints;
  tc::SkinWeights finestSkin;
  /// Each instance's animation and time, as PoseInstances last posed them.
  std::vector<int> animations;
  std::vector<double> times;
};

/// Fits the skinned boxes of `atlas` (tc::fitSkinnedBoxes) when it is skinned; `skinned.valid`
/// says whether it is.
void PrepareSkinnedAtlas(const tc::Atlas& atlas, SkinnedAtlas& skinned);

/// Every instance's skinning matrices (tc::poseMatrices) into skinned.palettes, and its chart
/// boxes posed by them into posedBox and posedArea; in parallel over the instances. Instance i
/// plays animation animations[i] (-1: the bind pose) at times[i] seconds.
void PoseInstances(const tc::Atlas& atlas, const std::vector<int>& animations,
  const std::vector<double>& times, SkinnedAtlas& skinned);

/// Axis-aligned bounds (xmin, xmax, ...) of the posed surface of every instance, each transformed
/// by its row-major 4 x 4 matrix of `instances`. Exact (the finest samples posed on the CPU, as
/// tc::drawnBounds bounds an unposed atlas) while instances x samples stays below
/// kExactBoundsPosings; above, the union of the posed chart boxes, which holds the surface but
/// is larger: posing every sample of a large crowd each frame would cost what skinning on the
/// GPU saves.
constexpr int64_t kExactBoundsPosings = 4000000;
std::array<double, 6> PosedBounds(
  const tc::Atlas& atlas, const SkinnedAtlas& skinned, const std::vector<double>& instances);
} // namespace tcvtk::lod

#endif
