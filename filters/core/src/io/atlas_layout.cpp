// SPDX-License-Identifier: BSD-3-Clause
#include "io/atlas_layout.h"

#include <algorithm>
#include <cstring>

namespace tc
{
namespace detail
{
namespace
{
/// Calls f(texel of image k, texel of image k + 1) for every inherited texel of image k.
template <class F>
void forEachInherited(const Atlas& atlas, size_t k, F&& f)
{
  const size_t coarseWidth =
    k + 1 < atlas.images.size() ? static_cast<size_t>(atlas.images[k + 1].width) : 0;
  forEachImageSample(atlas, k,
    [&](int32_t c, int32_t d, int32_t i, int32_t j, size_t texel)
    {
      if (d >= 1 && i % 2 == 0 && j % 2 == 0)
      {
        const std::array<int32_t, 2> xy =
          atlasTexel(atlas.charts[static_cast<size_t>(c)], d - 1, i / 2, j / 2);
        f(texel, static_cast<size_t>(xy[1]) * coarseWidth + static_cast<size_t>(xy[0]));
      }
    });
}

/// The role of every texel of image k, rows of the image's width.
std::vector<uint8_t> texelRoles(const Atlas& atlas, size_t k)
{
  const AtlasImage& image = atlas.images[k];
  std::vector<uint8_t> roles(
    static_cast<size_t>(image.width) * static_cast<size_t>(image.height), kEmptyTexel);
  forEachImageSample(atlas, k,
    [&roles](int32_t, int32_t, int32_t, int32_t, size_t texel) { roles[texel] = kNewTexel; });
  forEachInherited(atlas, k, [&roles](size_t texel, size_t) { roles[texel] = kInheritedTexel; });
  return roles;
}

/// Height of a compact part of an image `width` texels wide: rows enough for its new texels
/// (at least 1).
int32_t compactHeight(const std::vector<uint8_t>& roles, int32_t width)
{
  const size_t fresh = static_cast<size_t>(std::count(roles.begin(), roles.end(), kNewTexel));
  const size_t w = static_cast<size_t>(width);
  return static_cast<int32_t>(std::max<size_t>(1, (fresh + w - 1) / w));
}

/// Whether every empty texel of `data` (`comps` floats each) is all zero bits.
bool emptyTexelsZero(const float* data, const std::vector<uint8_t>& roles, size_t comps)
{
  for (size_t t = 0; t < roles.size(); ++t)
  {
    if (roles[t] != kEmptyTexel)
    {
      continue;
    }
    for (size_t c = 0; c < comps; ++c)
    {
      uint32_t bits = 0;
      std::memcpy(&bits, data + t * comps + c, sizeof(bits));
      if (bits != 0)
      {
        return false;
      }
    }
  }
  return true;
}

/// Whether image k can be stored compactly (see chooseLayout).
bool compactable(const Atlas& atlas, size_t k, const std::vector<uint8_t>& roles)
{
  for (size_t a = 0; a < atlas.attributes.size(); ++a)
  {
    const size_t comps = static_cast<size_t>(atlas.attributes[a].components);
    const float* fine = atlas.images[k].data[a].data();
    if (!emptyTexelsZero(fine, roles, comps))
    {
      return false;
    }
    if (k + 1 == atlas.images.size())
    {
      continue;
    }
    const float* coarse = atlas.images[k + 1].data[a].data();
    bool same = true;
    forEachInherited(atlas, k,
      [&](size_t texel, size_t from)
      {
        same = same &&
          std::memcmp(fine + texel * comps, coarse + from * comps, comps * sizeof(float)) == 0;
      });
    if (!same)
    {
      return false;
    }
  }
  return true;
}
} // namespace

std::string partName(const std::string& attribute, size_t image)
{
  return attribute + "." + std::to_string(image);
}

std::vector<std::string> channelNames(int32_t components)
{
  switch (components)
  {
    case 1:
      return { "R" };
    case 2:
      return { "R", "G" };
    case 3:
      return { "X", "Y", "Z" };
    case 4:
      return { "R", "G", "B", "A" };
    default:
    {
      std::vector<std::string> names;
      for (int32_t c = 0; c < components; ++c)
      {
        names.push_back("C" + std::to_string(c));
      }
      return names;
    }
  }
}

size_t floatCount(const AtlasImage& image, const AtlasAttribute& attribute)
{
  return static_cast<size_t>(image.width) * static_cast<size_t>(image.height) *
    static_cast<size_t>(attribute.components);
}

uint64_t partFloats(int32_t width, int32_t rows, const AtlasAttribute& attribute)
{
  return static_cast<uint64_t>(width) * static_cast<uint64_t>(rows) *
    static_cast<uint64_t>(attribute.components);
}

ImageLayout imageLayout(const Atlas& atlas, size_t k, bool compact)
{
  const AtlasImage& image = atlas.images[k];
  ImageLayout layout;
  layout.compact = compact;
  layout.partHeight = image.height;
  if (compact)
  {
    layout.roles = texelRoles(atlas, k);
    layout.partHeight = compactHeight(layout.roles, image.width);
  }
  return layout;
}

ImageLayout chooseLayout(const Atlas& atlas, size_t k)
{
  const AtlasImage& image = atlas.images[k];
  ImageLayout layout;
  layout.roles = texelRoles(atlas, k);
  layout.compact = compactable(atlas, k, layout.roles);
  layout.partHeight = layout.compact ? compactHeight(layout.roles, image.width) : image.height;
  if (!layout.compact)
  {
    layout.roles.clear();
  }
  return layout;
}

std::vector<float> compactTexels(const std::vector<float>& data, const std::vector<uint8_t>& roles,
  int32_t width, int32_t rows, int32_t comps)
{
  const size_t nc = static_cast<size_t>(comps);
  std::vector<float> out(static_cast<size_t>(width) * static_cast<size_t>(rows) * nc, 0.0f);
  auto to = out.begin();
  for (size_t t = 0; t < roles.size(); ++t)
  {
    if (roles[t] == kNewTexel)
    {
      to = std::copy(data.begin() + static_cast<std::ptrdiff_t>(t * nc),
        data.begin() + static_cast<std::ptrdiff_t>((t + 1) * nc), to);
    }
  }
  return out;
}

void expandTexels(const std::vector<float>& compact, const std::vector<uint8_t>& roles,
  int32_t comps, std::vector<float>& data)
{
  const size_t nc = static_cast<size_t>(comps);
  auto from = compact.begin();
  for (size_t t = 0; t < roles.size(); ++t)
  {
    if (roles[t] == kNewTexel)
    {
      std::copy(from, from + static_cast<std::ptrdiff_t>(nc),
        data.begin() + static_cast<std::ptrdiff_t>(t * nc));
      from += static_cast<std::ptrdiff_t>(nc);
    }
  }
}

void copyInherited(const Atlas& atlas, size_t k, size_t a, std::vector<float>& data)
{
  const size_t comps = static_cast<size_t>(atlas.attributes[a].components);
  const float* coarse = k + 1 < atlas.images.size() ? atlas.images[k + 1].data[a].data() : nullptr;
  forEachInherited(atlas, k,
    [&](size_t texel, size_t from) {
      std::copy(coarse + from * comps, coarse + (from + 1) * comps, data.begin() + texel * comps);
    });
}
} // namespace detail
} // namespace tc
