// SPDX-License-Identifier: BSD-3-Clause
/// @file atlas_codes.h
/// The integer texels of version 4 of the atlas file (internal to atlas_io.cpp): Position and
/// Normal as lattice codes (gim/atlas_quantization.h), each new texel stored as the zigzag
/// residual against a prediction from the coarser image. docs/atlas-format.md, section 2.
#pragma once

#include "gim/atlas_quantization.h"
#include "io/atlas_layout.h"
#include "tc/gim/atlas.h"

#include <cstdint>
#include <optional>
#include <string>
#include <vector>

namespace tc::detail
{
/// What a version-4 file stores of its lattice.
struct AtlasLattice
{
  PositionFrame frame;
  int32_t normalBits = kNormalBits;
};

/// The attributes version 4 stores as codes: Position (3 codes) and Normal (2).
constexpr size_t kCodedAttributes = 2;
/// Codes per texel of coded attribute a: 3 for Position, 2 for Normal.
int32_t codeComponents(size_t a);
/// Their channel names: X, Y, Z and U, V, 32-bit unsigned integers.
std::vector<std::string> codeChannelNames(size_t a);

/// The lattice that stores every chart sample's position and normal of `atlas` exactly: every
/// one decodes bit for bit from its nearest code. None when one does not (an atlas not snapped
/// by the pipeline), or when an image is not stored compactly (`layouts`).
std::optional<AtlasLattice> exactLattice(
  const Atlas& atlas, const std::vector<ImageLayout>& layouts);

/// Rows of a coded part per block of its byte planes: OpenEXR's ZIP compresses 16 scan lines at
/// a time.
constexpr int32_t kPlaneBlockRows = 16;

/// The values a coded part stores for `residuals` (rows of `width` texels, `comps` values each,
/// as CodeWriter::residuals gives them): per block of kPlaneBlockRows rows, their bytes as
/// planes (channel by channel, byte 0 of every value, then byte 1, ...), passed through the
/// inverse of the byte interleave and difference predictor that OpenEXR's ZIP applies to a
/// block before deflate, so that deflate sees the planes: small residuals make planes of
/// zeros. A bijection on each block (docs/atlas-format.md, section 2).
std::vector<uint32_t> planeValues(std::vector<uint32_t> residuals, int32_t width, size_t comps);

/// The inverse of planeValues: the residuals of a coded part's values.
std::vector<uint32_t> planeResiduals(std::vector<uint32_t> values, int32_t width, size_t comps);

/// Writes coded attributes image by image, finest last: the residuals of image k are taken
/// against the codes of image k + 1, so call it for k = K - 1 down to 0.
class CodeWriter
{
public:
  CodeWriter(const Atlas& atlas, const AtlasLattice& lattice);

  /// The zigzag residual of every new texel of attribute a (< kCodedAttributes) of image k, in
  /// the order of a coded part (chart by chart, each level's new samples row by row; a position
  /// whose twin across a shared side came before is left out), as rows of the image's width
  /// (partHeight of them, ending in zeros), codeComponents(a) per texel. Images must come
  /// coarsest first, each attribute once.
  std::vector<uint32_t> residuals(size_t k, size_t a, const ImageLayout& layout);

private:
  const Atlas& Source;
  AtlasLattice Lattice;
  /// Per coded attribute, per image: the codes of the images written so far (of Normal, the
  /// last one only).
  std::vector<std::vector<std::vector<int32_t>>> Codes;
};

/// Reads coded attributes image by image, coarsest first (the inverse of CodeWriter).
class CodeReader
{
public:
  CodeReader(const Atlas& atlas, const AtlasLattice& lattice);

  /// The floats of attribute a of image k (width x height x 3, 0 off the charts) from the
  /// residuals of its part; `data` of the image's size. Inherited texels come from image k + 1,
  /// read before.
  /// @throws InputError  "cannot read atlas <path>: ..." when a residual decodes to a code
  ///   outside the lattice (damage the checksums would also see, caught before any float is made)
  void decode(size_t k, size_t a, const ImageLayout& layout, const std::vector<uint32_t>& residuals,
    const std::string& path, const std::string& part, std::vector<float>& data);

private:
  const Atlas& Source;
  AtlasLattice Lattice;
  std::vector<std::vector<std::vector<int32_t>>> Codes; ///< as CodeWriter's, of those read
};
} // namespace tc::detail
