// SPDX-License-Identifier: BSD-3-Clause
/// @file atlas_metadata.h
/// The metadata of the atlas file (internal to atlas_io.cpp): the JSON chart table with the
/// atlas's sizes and checksums, its zlib compression, and its checks when read.
/// docs/atlas-format.md lists every field.
#pragma once

#include "io/atlas_codes.h"
#include "tc/gim/atlas.h"

#include <cstddef>
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

namespace tc
{
namespace detail
{
constexpr const char* kFormatName = "TriChart atlas";
constexpr const char* kMetadataAttribute = "trichartAtlas";            ///< version 1: the JSON text
constexpr const char* kCompressedMetadataAttribute = "trichartAtlasZ"; ///< from version 2: deflated
constexpr const char* kMetadataLengthAttribute = "trichartAtlasLength";
constexpr const char* kMetadataCrcAttribute = "trichartAtlasCrc32";

/// CRC-32 (zlib's) of `bytes` bytes at `data`, and of a text.
uint32_t crc32Of(const void* data, size_t bytes);
uint32_t crc32Of(const std::string& text);

/// Per image, per attribute: the CRC-32 of its float data.
using AtlasChecksums = std::vector<std::vector<uint32_t>>;

/// The name of the part that holds texture `name`: "<name>.texture" (an attribute's parts end in
/// ".<image>", digits, so no texture's part name is an attribute's).
std::string texturePartName(const std::string& name);

/// Refuses what the metadata cannot hold exactly: NaN doubles and attribute and texture names
/// that are not UTF-8 (validateAtlas has checked the layout).
/// @throws InputError  "cannot write atlas <path>: ..."
void checkWritable(const Atlas& atlas, const std::string& path);

/// The metadata JSON text of `atlas` (everything but the texels), bytes of `source` that are
/// not UTF-8 written as U+FFFD: version 5 when the atlas has textures, else version 4 with
/// `lattice`, else version 3.
/// @param[in] crcs     per image, per attribute
/// @param[in] textureCrcs  per texture, of its bytes
/// @param[in] compact  per image: 1 if its parts hold only its new texels
/// @param[in] lattice  the lattice Position and Normal are coded on, or null (floats)
std::string metadataJson(const Atlas& atlas, const AtlasChecksums& crcs,
  const std::vector<uint32_t>& textureCrcs, const std::vector<uint8_t>& compact,
  const AtlasLattice* lattice);

/// The metadata JSON text deflated for "trichartAtlasZ" (zlib stream, best compression).
/// @throws InputError  when the text or its compressed form exceed what an OpenEXR attribute
///   holds (2^31 - 1 bytes), or zlib fails
std::string compressMetadata(const std::string& text, const std::string& path);

/// The JSON text deflated in `packed`, which the file says inflates to `declared` bytes. Memory
/// grows with the bytes actually inflated (never more than declared + 1), so a damaged length
/// or stream cannot make the reader allocate more than the metadata's real size.
/// @throws InputError  for a length deflate cannot give, a stream that is cut short, corrupt,
///   longer or shorter than declared, or followed by stray bytes
std::string inflateMetadata(const std::string& path, const std::string& packed, int64_t declared);

/// The metadata as the first part of a file stores it.
struct StoredMetadata
{
  std::string text;            ///< the JSON text (inflated when compressed)
  bool compressed = false;     ///< it was deflated ("trichartAtlasZ"), not plain ("trichartAtlas")
  std::optional<uint32_t> crc; ///< the "trichartAtlasCrc32" attribute, when present
};

/// Checks that the metadata names the format and a version this reader reads, is stored as that
/// version stores it, and matches its checksum.
/// @throws InputError  naming the file and what is wrong
void checkMetadata(const std::string& path, const StoredMetadata& stored);

/// The atlas without texels, the checksums and the storage of every image, from checked
/// metadata.
struct AtlasMetadata
{
  Atlas atlas;                         ///< images with width and height only, no data
  AtlasChecksums crcs;                 ///< per image, per attribute
  std::vector<uint32_t> textureCrcs;   ///< per texture (its bytes empty until read)
  std::vector<uint8_t> compact;        ///< per image: 1 if its parts hold only its new texels
  std::optional<AtlasLattice> lattice; ///< version 4: Position and Normal are coded on it
};

/// checkMetadata, then every field parsed; counts and sizes within validateAtlas's limits
/// before anything is allocated from them.
/// @throws InputError  naming the file and the first field that is missing or wrong
AtlasMetadata parseMetadata(const std::string& path, const StoredMetadata& stored);
} // namespace detail
} // namespace tc
