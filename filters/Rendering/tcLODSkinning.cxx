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
  skinned.valid = true;
}

void PoseInstances(const tc::Atlas& atlas, const std::vector<int>& animations,
  const std::vector<double>& times, SkinnedAtlas& skinned)
{
  const size_t instances = times.size();
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

int ChooseAnimation(const tc::Atlas& atlas, const std::string& choice, std::string& error)
{
  try
  {
    return tc::findAnimation(atlas.rig.animations, choice);
  }
  catch (const tc::InputError& e)
  {
    error = e.what();
    return -1;
  }
}

std::array<double, 6> PosedBounds(const SkinnedAtlas& skinned, const std::vector<double>& instances)
{
  std::array<double, 6> bounds{ INFINITY, -INFINITY, INFINITY, -INFINITY, INFINITY, -INFINITY };
  const size_t nc = static_cast<size_t>(skinned.boxes.size());
  for (size_t i = 0; i < instances.size() / 16 && (i + 1) * nc * 12 <= skinned.posedBox.size(); ++i)
  {
    const double* m = instances.data() + 16 * i;
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
        for (int r = 0; r < 3; ++r)
        {
          const double v =
            m[4 * r] * p[0] + m[4 * r + 1] * p[1] + m[4 * r + 2] * p[2] + m[4 * r + 3];
          bounds[static_cast<size_t>(2 * r)] = std::min(bounds[static_cast<size_t>(2 * r)], v);
          bounds[static_cast<size_t>(2 * r + 1)] =
            std::max(bounds[static_cast<size_t>(2 * r + 1)], v);
        }
      }
    }
  }
  return bounds;
}
} // namespace tcvtk::lod
