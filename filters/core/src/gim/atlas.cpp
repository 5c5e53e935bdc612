// SPDX-License-Identifier: BSD-3-Clause
#include "tc/gim/atlas.h"

#include "tc/common/errors.h"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <string>
#include <unordered_map>

namespace tc
{
namespace
{
[[noreturn]] void fail(const std::string& what)
{
  throw InputError("invalid atlas: " + what);
}

std::string chartName(size_t c)
{
  return "chart " + std::to_string(c);
}

bool samePosition(const float* a, const float* b)
{
  return std::memcmp(a, b, 3 * sizeof(float)) == 0;
}
/// Position and Normal first, then any others, each named once with 1 to 64 components.
void checkAttributes(const Atlas& atlas)
{
  if (atlas.attributes.size() < 2 || atlas.attributes[0].name != kAtlasPosition ||
    atlas.attributes[0].components != 3 || atlas.attributes[1].name != kAtlasNormal ||
    atlas.attributes[1].components != 3)
  {
    fail("the first two attributes must be Position and Normal with 3 components each");
  }
  for (size_t a = 0; a < atlas.attributes.size(); ++a)
  {
    const AtlasAttribute& attribute = atlas.attributes[a];
    if (attribute.name.empty() || attribute.components < 1 || attribute.components > 64)
    {
      fail("attribute " + std::to_string(a) + " needs a name and 1 to 64 components");
    }
    for (size_t b = 0; b < a; ++b)
    {
      if (atlas.attributes[b].name == attribute.name)
      {
        fail("attribute '" + attribute.name + "' appears twice");
      }
    }
  }
}

/// Textures named once each, of a size a GPU texture can have, and the coordinates to look them
/// up.
void checkTextures(const Atlas& atlas)
{
  if (atlas.textures.empty())
  {
    return;
  }
  const int32_t uv = findAttribute(atlas, kAtlasTextureCoordinates);
  if (uv < 0 || atlas.attributes[static_cast<size_t>(uv)].components != 2)
  {
    fail(std::string("it has textures but no attribute ") + kAtlasTextureCoordinates +
      " with 2 components to look them up");
  }
  for (size_t t = 0; t < atlas.textures.size(); ++t)
  {
    const AtlasTexture& texture = atlas.textures[t];
    const std::string what = "texture " + std::to_string(t) + " ('" + texture.name + "')";
    if (texture.name.empty())
    {
      fail("texture " + std::to_string(t) + " has no name");
    }
    if (texture.width < 1 || texture.height < 1 || texture.width > (1 << 16) ||
      texture.height > (1 << 16))
    {
      fail(what + " has size " + std::to_string(texture.width) + " x " +
        std::to_string(texture.height) + "; 1 to 65536 texels a side");
    }
    for (size_t u = 0; u < t; ++u)
    {
      if (atlas.textures[u].name == texture.name)
      {
        fail(what + " has the name of texture " + std::to_string(u));
      }
    }
  }
}

/// A Skin attribute of kSkinValues components exactly when the rig has joints.
void checkSkinLayout(const Atlas& atlas)
{
  const int32_t skin = findAttribute(atlas, kAtlasSkin);
  if ((skin >= 0) != !atlas.rig.empty())
  {
    fail(skin >= 0 ? std::string("it has a ") + kAtlasSkin + " attribute but no skeleton"
                   : std::string("it has a skeleton but no ") + kAtlasSkin + " attribute");
  }
  if (skin >= 0 && atlas.attributes[static_cast<size_t>(skin)].components != kSkinValues)
  {
    fail(std::string("its ") + kAtlasSkin + " attribute needs " + std::to_string(kSkinValues) +
      " components (4 joints, 4 weights)");
  }
}

/// Every chart texel's skin: 4 integer joints of the skeleton, 4 finite weights >= 0.
void checkSkinData(const Atlas& atlas)
{
  const int32_t skin = findAttribute(atlas, kAtlasSkin);
  const double joints = static_cast<double>(atlas.rig.skeleton.joints.size());
  for (size_t k = 0; skin >= 0 && k < atlas.images.size(); ++k)
  {
    const float* values = atlas.images[k].data[static_cast<size_t>(skin)].data();
    forEachImageSample(atlas, k,
      [&](int32_t c, int32_t, int32_t, int32_t, size_t texel)
      {
        const float* v = values + kSkinValues * texel;
        for (int r = 0; r < kMaxInfluences; ++r)
        {
          if (!(v[r] >= 0 && v[r] < joints && std::floor(v[r]) == v[r]) ||
            !(v[kMaxInfluences + r] >= 0 && std::isfinite(v[kMaxInfluences + r])))
          {
            fail(chartName(static_cast<size_t>(c)) + " has a skin sample whose joint is no " +
              "joint of the skeleton or whose weight is negative or not finite");
          }
        }
      });
  }
}

/// One image per mip step of the finest chart, each of a size a GPU texture can have.
void checkImageSizes(const Atlas& atlas)
{
  const int32_t maxLevel = atlas.maxLevel();
  if (maxLevel < 0 || maxLevel > 20)
  {
    fail("levels must lie in [0, 20], found " + std::to_string(maxLevel));
  }
  if (atlas.images.size() != static_cast<size_t>(maxLevel) + 1)
  {
    fail("it needs " + std::to_string(maxLevel + 1) + " images (one per level of its finest " +
      "chart), found " + std::to_string(atlas.images.size()));
  }
  for (size_t k = 0; k < atlas.images.size(); ++k)
  {
    const AtlasImage& image = atlas.images[k];
    if (image.width < 1 || image.height < 1 || image.width > (1 << 16) || image.height > (1 << 16))
    {
      fail("image " + std::to_string(k) + " has size " + std::to_string(image.width) + " x " +
        std::to_string(image.height));
    }
  }
}

/// Neighbours across the three sides of chart c that exist, name it back and run the shared
/// side between the same base vertices the other way.
void checkNeighbours(const Atlas& atlas, size_t c)
{
  const size_t nc = atlas.charts.size();
  const AtlasChart& chart = atlas.charts[c];
  for (int k = 0; k < 3; ++k)
  {
    const int32_t nb = chart.neighborChart[k];
    const int32_t ns = chart.neighborSide[k];
    if (chart.cornerVertex[k] < 0)
    {
      fail(chartName(c) + " has no base vertex at corner " + std::to_string(k));
    }
    if (nb < 0 || static_cast<size_t>(nb) >= nc || static_cast<size_t>(nb) == c || ns < 0 || ns > 2)
    {
      fail(chartName(c) + " side " + std::to_string(k) + " has no valid neighbour (the " +
        "base complex must be closed)");
    }
    const AtlasChart& other = atlas.charts[static_cast<size_t>(nb)];
    if (other.neighborChart[ns] != static_cast<int32_t>(c) || other.neighborSide[ns] != k)
    {
      fail(chartName(c) + " side " + std::to_string(k) + " and " + chartName(nb) + " side " +
        std::to_string(ns) + " do not name each other as neighbours");
    }
    if (other.cornerVertex[ns] != chart.cornerVertex[(k + 1) % 3] ||
      other.cornerVertex[(ns + 1) % 3] != chart.cornerVertex[k])
    {
      fail(chartName(c) + " side " + std::to_string(k) + " and " + chartName(nb) + " side " +
        std::to_string(ns) + " do not run between the same base vertices the other way");
    }
  }
}

/// Chart c: levels and origins, neighbours and partner that agree, every level inside its image.
void checkChartLayout(const Atlas& atlas, size_t c)
{
  const size_t nc = atlas.charts.size();
  const AtlasChart& chart = atlas.charts[c];
  if (chart.maxLevel < 0 || chart.origin.size() != static_cast<size_t>(chart.maxLevel) + 1)
  {
    fail(chartName(c) + " needs one origin per level 0 .. maxLevel");
  }
  if (!chart.levelError.empty() &&
    chart.levelError.size() != static_cast<size_t>(chart.maxLevel) + 1)
  {
    fail(chartName(c) + " has " + std::to_string(chart.levelError.size()) +
      " level errors, expected none or " + std::to_string(chart.maxLevel + 1));
  }
  checkNeighbours(atlas, c);
  if (chart.partner >= 0)
  {
    if (static_cast<size_t>(chart.partner) >= nc || static_cast<size_t>(chart.partner) == c ||
      atlas.charts[static_cast<size_t>(chart.partner)].partner != static_cast<int32_t>(c) ||
      atlas.charts[static_cast<size_t>(chart.partner)].rotated == chart.rotated)
    {
      fail(chartName(c) + " and its partner do not share a rectangle as a pair (one of the " +
        "two rotated)");
    }
  }
  for (int32_t d = 0; d <= chart.maxLevel; ++d)
  {
    const AtlasImage& image = atlas.images[static_cast<size_t>(chart.maxLevel - d)];
    const int32_t n = 1 << d;
    // The grid is the convex hull of its corners: corners inside means every sample inside.
    for (const auto& ij : { std::array<int32_t, 2>{ 0, 0 }, std::array<int32_t, 2>{ n, 0 },
           std::array<int32_t, 2>{ 0, n } })
    {
      const std::array<int32_t, 2> xy = atlasTexel(chart, d, ij[0], ij[1]);
      if (xy[0] < 0 || xy[1] < 0 || xy[0] >= image.width || xy[1] >= image.height)
      {
        fail(chartName(c) + " level " + std::to_string(d) + " lies outside image " +
          std::to_string(chart.maxLevel - d));
      }
    }
  }
}

/// No texel belongs to two charts.
void checkTexelOwners(const Atlas& atlas)
{
  for (size_t k = 0; k < atlas.images.size(); ++k)
  {
    const AtlasImage& image = atlas.images[k];
    std::vector<int32_t> owner(
      static_cast<size_t>(image.width) * static_cast<size_t>(image.height), -1);
    forEachImageSample(atlas, k,
      [&](int32_t c, int32_t, int32_t, int32_t, size_t texel)
      {
        int32_t& o = owner[texel];
        if (o >= 0)
        {
          fail(chartName(static_cast<size_t>(c)) + " and " + chartName(static_cast<size_t>(o)) +
            " share texel (" + std::to_string(texel % static_cast<size_t>(image.width)) + ", " +
            std::to_string(texel / static_cast<size_t>(image.width)) + ") of image " +
            std::to_string(k));
        }
        o = c;
      });
  }
}

/// Every attribute of every image the right size, every position finite.
void checkImageData(const Atlas& atlas)
{
  for (size_t k = 0; k < atlas.images.size(); ++k)
  {
    const AtlasImage& image = atlas.images[k];
    if (image.data.size() != atlas.attributes.size())
    {
      fail("image " + std::to_string(k) + " does not hold every attribute");
    }
    for (size_t a = 0; a < atlas.attributes.size(); ++a)
    {
      const size_t expected = static_cast<size_t>(image.width) * static_cast<size_t>(image.height) *
        static_cast<size_t>(atlas.attributes[a].components);
      if (image.data[a].size() != expected)
      {
        fail("attribute '" + atlas.attributes[a].name + "' of image " + std::to_string(k) +
          " has " + std::to_string(image.data[a].size()) + " values, expected " +
          std::to_string(expected));
      }
    }
  }
  for (size_t k = 0; k < atlas.images.size(); ++k)
  {
    const float* position = atlas.images[k].data[0].data();
    forEachImageSample(atlas, k,
      [&](int32_t c, int32_t, int32_t, int32_t, size_t texel)
      {
        const float* p = position + 3 * texel;
        if (!std::isfinite(p[0]) || !std::isfinite(p[1]) || !std::isfinite(p[2]))
        {
          fail(chartName(static_cast<size_t>(c)) + " has a position that is not a finite number");
        }
      });
  }
}

/// Side k of chart c: sample t equals sample N - t of the neighbour's side at every common
/// level, and sample 2t of the next finer level of the same chart (the dyadic subset property
/// stitching relies on). Positions, and the skin so that both charts pose a side alike; not the
/// normals: a side along a feature may keep one-sided normals.
void checkSharedSide(const Atlas& atlas, size_t c, int k)
{
  const AtlasChart& chart = atlas.charts[c];
  const int32_t skin = findAttribute(atlas, kAtlasSkin);
  const int32_t ci = static_cast<int32_t>(c);
  const int32_t nb = chart.neighborChart[k];
  const int32_t ns = chart.neighborSide[k];
  const int32_t common = std::min(chart.maxLevel, atlas.charts[static_cast<size_t>(nb)].maxLevel);
  for (int32_t d = 0; d <= chart.maxLevel; ++d)
  {
    const int32_t n = 1 << d;
    for (int32_t t = 0; t <= n; ++t)
    {
      const std::array<int32_t, 2> ij = sidePoint(k, t, n);
      const float* p = atlasSample(atlas, ci, 0, d, ij[0], ij[1]);
      if (d <= common)
      {
        const std::array<int32_t, 2> nij = sidePoint(ns, n - t, n);
        if (!samePosition(p, atlasSample(atlas, nb, 0, d, nij[0], nij[1])) ||
          (skin >= 0 &&
            std::memcmp(atlasSample(atlas, ci, skin, d, ij[0], ij[1]),
              atlasSample(atlas, nb, skin, d, nij[0], nij[1]), kSkinValues * sizeof(float)) != 0))
        {
          fail(chartName(c) + " side " + std::to_string(k) + " level " + std::to_string(d) +
            " sample " + std::to_string(t) + " differs from " + chartName(nb) + "'s copy of it");
        }
      }
      if (d < chart.maxLevel)
      {
        const std::array<int32_t, 2> fij = sidePoint(k, 2 * t, 2 * n);
        if (!samePosition(p, atlasSample(atlas, ci, 0, d + 1, fij[0], fij[1])))
        {
          fail(chartName(c) + " side " + std::to_string(k) + " level " + std::to_string(d) +
            " sample " + std::to_string(t) + " is not sample " + std::to_string(2 * t) +
            " of level " + std::to_string(d + 1));
        }
      }
    }
  }
}
} // namespace

int32_t findAttribute(const Atlas& atlas, const std::string& name)
{
  for (size_t a = 0; a < atlas.attributes.size(); ++a)
  {
    if (atlas.attributes[a].name == name)
    {
      return static_cast<int32_t>(a);
    }
  }
  return -1;
}

void validateAtlasLayout(const Atlas& atlas)
{
  checkAttributes(atlas);
  checkTextures(atlas);
  checkSkinLayout(atlas);
  if (atlas.charts.empty())
  {
    fail("it has no chart");
  }
  checkImageSizes(atlas);
  for (size_t c = 0; c < atlas.charts.size(); ++c)
  {
    checkChartLayout(atlas, c);
  }
  checkTexelOwners(atlas);
}

void validateAtlas(const Atlas& atlas)
{
  validateAtlasLayout(atlas);
  checkImageData(atlas);
  checkSkinData(atlas);
  for (size_t t = 0; t < atlas.textures.size(); ++t)
  {
    const AtlasTexture& texture = atlas.textures[t];
    const size_t bytes =
      static_cast<size_t>(texture.width) * static_cast<size_t>(texture.height) * 4;
    if (texture.rgba.size() != bytes)
    {
      fail("texture " + std::to_string(t) + " ('" + texture.name + "') holds " +
        std::to_string(texture.rgba.size()) + " bytes, not the " + std::to_string(bytes) +
        " of its size");
    }
  }
  // Shared sides, and corner k of every chart: the base vertex's position, the same in every
  // chart around it.
  std::unordered_map<int32_t, const float*> cornerPosition;
  for (size_t c = 0; c < atlas.charts.size(); ++c)
  {
    const AtlasChart& chart = atlas.charts[c];
    for (int k = 0; k < 3; ++k)
    {
      checkSharedSide(atlas, c, k);
      const std::array<int32_t, 2> corner = sidePoint(k, 0, 1 << chart.maxLevel);
      const float* p =
        atlasSample(atlas, static_cast<int32_t>(c), 0, chart.maxLevel, corner[0], corner[1]);
      auto [it, inserted] = cornerPosition.emplace(chart.cornerVertex[k], p);
      if (!inserted && !samePosition(it->second, p))
      {
        fail(chartName(c) + " corner " + std::to_string(k) + " (base vertex " +
          std::to_string(chart.cornerVertex[k]) + ") differs from another chart's copy of it");
      }
    }
  }
}
} // namespace tc
