// SPDX-License-Identifier: BSD-3-Clause
/// @file atlas_layout.h
/// Where the atlas file puts the texels (internal to atlas_io.cpp): the part of each attribute
/// and image, its channels, and the compact parts of version 3, which hold only the texels no
/// coarser image holds. docs/atlas-format.md describes the layout.
#pragma once

#include "tc/gim/atlas.h"

#include <cstdint>
#include <string>
#include <vector>

namespace tc
{
namespace detail
{
/// Name of the part of `attribute` in image k: "<attribute>.<k>", e.g. "Position.0".
std::string partName(const std::string& attribute, size_t image);

/// Channel names of an attribute with `components` components: 3 -> X, Y, Z; 1, 2, 4 -> R;
/// R, G; R, G, B, A; any other n -> C0 .. C(n-1).
std::vector<std::string> channelNames(int32_t components);

/// Floats of one attribute of a whole image: width x height x components.
size_t floatCount(const AtlasImage& image, const AtlasAttribute& attribute);

/// Floats in a part of `rows` rows of an image `width` texels wide.
uint64_t partFloats(int32_t width, int32_t rows, const AtlasAttribute& attribute);

/// What a texel of an image holds, for the compact layout.
enum TexelRole : uint8_t
{
  kEmptyTexel = 0,     ///< no chart: 0 in every attribute
  kNewTexel = 1,       ///< a sample that no coarser image holds: stored in the part
  kInheritedTexel = 2, ///< sample (i, j), both even, of level d >= 1: (i/2, j/2) of image k + 1
};

/// How the parts of one image are stored.
struct ImageLayout
{
  bool compact = false;       ///< only its new texels (else the whole image)
  std::vector<uint8_t> roles; ///< compact: the TexelRole of every texel (width x height)
  int32_t partHeight = 0;     ///< rows of each of its parts (of the image's width)
};

/// The layout of image k of `atlas` (whose chart layout is valid), compact or whole.
ImageLayout imageLayout(const Atlas& atlas, size_t k, bool compact);

/// The layout the writer picks for image k: compact whenever its texels allow it, i.e. every
/// inherited texel is bit-identical to its coarser copy and every empty texel all zero bits, in
/// every attribute. The pipeline's point-sampled pyramid always is; an atlas made otherwise is
/// stored whole, so every atlas reads back exactly.
ImageLayout chooseLayout(const Atlas& atlas, size_t k);

/// The new texels of `data` (`comps` floats each) in texel order, as `rows` rows of the image's
/// width: the last row ends in zeros.
std::vector<float> compactTexels(const std::vector<float>& data, const std::vector<uint8_t>& roles,
  int32_t width, int32_t rows, int32_t comps);

/// The inverse of compactTexels for the new texels: puts them back into `data`.
void expandTexels(const std::vector<float>& compact, const std::vector<uint8_t>& roles,
  int32_t comps, std::vector<float>& data);

/// Copies the inherited texels of attribute a of image k from image k + 1 into `data`.
void copyInherited(const Atlas& atlas, size_t k, size_t a, std::vector<float>& data);
} // namespace detail
} // namespace tc
