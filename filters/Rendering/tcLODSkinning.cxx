// SPDX-License-Identifier: BSD-3-Clause
#include "tcLODSkinning.h"

#include "tc/common/errors.h"
#include "tc/common/parallel.h"
#include "tc/skinning/skin.h"

#include <algorithm>
#include <cmath>

namespace tcvtk::lod
{
SkinTexels PackSkin(const tc::Atlas& atlas, int skinAttribute)
{
  SkinTexels texels;
  for (const tc::AtlasImage& image : atlas.images)
  {
    const std::vector<float>& skin = image.data[static_cast<size_t>(skinAttribute)];
    const size_t size = skin.size() / tc::kSkinValues;
    for (size_t t = 0; t < size; ++t)
    {
      const float* s = skin.data() + tc::kSkinValues * t;
      texels.joints.insert(texels.joints.end(), s, s + tc::kMaxInfluences);
      texels.weights.insert(texels.weights.end(), s + tc::kMaxInfluences, s + tc::kSkinValues);
    }
  }
  return texels;
}

void PrepareSkinnedAtlas(const tc::Atlas& atlas, SkinnedAtlas& skinned)
{
  skinned = SkinnedAtlas();
  if (atlas.rig.empty() || tc::findAttribute(atlas, tc::kAtlasSkin) < 0)
  {
    return;
  }
  skinned.boxes = tc::LodSkinnedBoxes::fromBoxes(tc::fitSkinnedBoxes(atlas).boxes);
  skinned.joints = static_cast<int32_t>(atlas.rig.skeleton.joints.size());
  const int skin = tc::findAttribute(atlas, tc::kAtlasSkin);
  const tc::AtlasImage& finest = atlas.images[0];
  std::vector<uint8_t> seen(finest.data[0].size() / 3, 0);
  tc::forEachImageSample(atlas, 0,
    [&](int32_t, int32_t, int32_t, int32_t, size_t t)
    {
      if (seen[t]++ == 0)
      {
        skinned.finestPoints.insert(skinned.finestPoints.end(), finest.data[0].begin() + 3 * t,
          finest.data[0].begin() + 3 * t + 3);
        const float* s = finest.data[static_cast<size_t>(skin)].data() + tc::kSkinValues * t;
        skinned.finestSkin.joints.insert(
          skinned.finestSkin.joints.end(), s, s + tc::kMaxInfluences);
        skinned.finestSkin.weights.insert(
          skinned.finestSkin.weights.end(), s + tc::kMaxInfluences, s + tc::kSkinValues);
      }
    });
  skinned.valid = true;
}

void PoseInstances(const tc::Atlas& atlas, const std::vector<int>& animations,
  const std::vector<double>& times, SkinnedAtlas& skinned)
{
  const size_t instances = times.size();
  skinned.animations = animations;
  skinned.times = times;
  const size_t nc = static_cast<size_t>(skinned.boxes.size());
  const size_t perPalette = static_cast<size_t>(skinned.joints) * tc::kPaletteFloats;
  skinned.palettes.resize(instances * perPalette);
  skinned.posedBox.resize(instances * nc * 12);
  skinned.posedArea.resize(instances * nc);
  tc::parallel_for(
    static_cast<int64_t>(instances),
    [&](int64_t i)
    {
      const size_t k = static_cast<size_t>(i);
      std::vector<float> palette;
      tc::appendPaletteRows(tc::poseMatrices(atlas.rig, animations[k], times[k]), palette);
      std::copy(palette.begin(), palette.end(), skinned.palettes.begin() + k * perPalette);
      tc::poseLodBoxes(skinned.boxes, palette.data(), skinned.joints,
        skinned.posedBox.data() + k * nc * 12, skinned.posedArea.data() + k * nc);
    },
    tc::Progress(), 1);
}

namespace
{
/// Widens `bounds` by the point `p` of model coordinates carried by the row-major 4 x 4 `m`.
void Widen(std::array<double, 6>& bounds, const double* m, const double p[3])
{
  for (int r = 0; r < 3; ++r)
  {
    const double v = m[4 * r] * p[0] + m[4 * r + 1] * p[1] + m[4 * r + 2] * p[2] + m[4 * r + 3];
    bounds[static_cast<size_t>(2 * r)] = std::min(bounds[static_cast<size_t>(2 * r)], v);
    bounds[static_cast<size_t>(2 * r + 1)] = std::max(bounds[static_cast<size_t>(2 * r + 1)], v);
  }
}

/// Widens `bounds` by the 8 corners of every posed box of instance `i`.
void WidenByBoxes(
  std::array<double, 6>& bounds, const SkinnedAtlas& skinned, size_t i, const double* m)
{
  const size_t nc = static_cast<size_t>(skinned.boxes.size());
  for (size_t c = 0; c < nc; ++c)
  {
    const float* b = skinned.posedBox.data() + 12 * (i * nc + c);
    for (int corner = 0; corner < 8; ++corner)
    {
      double p[3];
      for (int x = 0; x < 3; ++x)
      {
        p[x] = b[x];
        for (int k = 0; k < 3; ++k)
        {
          p[x] += ((corner >> k) & 1) ? b[3 + 3 * k + x] : 0.0f;
        }
      }
      Widen(bounds, m, p);
    }
  }
}
} // namespace

std::array<double, 6> PosedBounds(
  const tc::Atlas& atlas, const SkinnedAtlas& skinned, const std::vector<double>& instances)
{
  std::array<double, 6> bounds{ INFINITY, -INFINITY, INFINITY, -INFINITY, INFINITY, -INFINITY };
  const size_t count = std::min(instances.size() / 16, skinned.times.size());
  const bool exact =
    static_cast<int64_t>(count * skinned.finestPoints.size() / 3) <= kExactBoundsPosings;
  for (size_t i = 0; i < count; ++i)
  {
    const double* m = instances.data() + 16 * i;
    if (!exact)
    {
      WidenByBoxes(bounds, skinned, i, m);
      continue;
    }
    const std::vector<double> posed = tc::skinPoints(skinned.finestPoints, skinned.finestSkin,
      tc::poseMatrices(atlas.rig, skinned.animations[i], skinned.times[i]));
    for (size_t p = 0; p + 2 < posed.size(); p += 3)
    {
      Widen(bounds, m, posed.data() + p);
    }
  }
  if (exact && count > 0)
  {
    // The GPU blends the matrices in float: its vertices may pass the double posing's extremes
    // by a few float steps of the scale of the scene.
    const double pad =
      1e-6 * std::hypot(bounds[1] - bounds[0], bounds[3] - bounds[2], bounds[5] - bounds[4]);
    for (size_t k = 0; k < 6; ++k)
    {
      bounds[k] += k % 2 ? pad : -pad;
    }
  }
  return bounds;
}
} // namespace tcvtk::lod
