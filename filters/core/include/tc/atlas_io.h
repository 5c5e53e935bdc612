// SPDX-License-Identifier: BSD-3-Clause
/// @file atlas_io.h
/// The atlas file: a tc::Atlas (atlas.h) as one OpenEXR multi-part file, read back bit for bit.
///
/// Layout (format "TriChart atlas", version 2):
/// - one scan-line part per attribute a and image k, named "<attribute name>.<k>" (e.g.
///   "Position.0", "Normal.2"), in the order image 0 (all attributes), image 1, ...; its data
///   window is (0, 0) .. (width - 1, height - 1) of image k and EXR scan line y is atlas row y
///   (no flip: texel (x, y) of atlas.h is pixel (x, y) of the part); every part shares the
///   display window of the largest image, as OpenEXR requires of multi-part files;
/// - one FLOAT channel per component, lossless ZIP compression; channel names by component
///   count: 3 -> X, Y, Z; 1, 2, 4 -> R; R, G; R, G, B, A; any other count n -> C0 .. C(n-1);
/// - the metadata is UTF-8 JSON with "format": "TriChart atlas", "version": 2, "source",
///   "inputPoints", "inputTriangles", "inputDiagonal", "attributes": [{"name", "components"}],
///   "images": [{"width", "height", "crc32": [one per attribute]}] and "charts": [{every
///   AtlasChart field under its C++ name}]. The first part's header holds it as three
///   attributes: the string attribute "trichartAtlasZ", the JSON text compressed by zlib
///   (RFC 1950 stream, best compression; the string holds these raw bytes, NULs included), the
///   int attribute "trichartAtlasLength", the byte length of the JSON text, and the int
///   attribute "trichartAtlasCrc32", the CRC-32 of the JSON text.
///
/// Version 1, which readAtlas still reads, differs only in the metadata: "version": 1 and the
/// plain JSON text in the string attribute "trichartAtlas" (with "trichartAtlasCrc32"; no
/// length attribute).
///
/// Doubles are JSON numbers that read back to the same bits (-0.0 included); +-infinity, which
/// JSON cannot hold, is written as the string "inf" / "-inf". The CRC-32 (zlib) of each part's
/// float data (little-endian bytes, atlas order) and of the JSON catch damage that OpenEXR
/// cannot see (chunks that ZIP left uncompressed, digits in the metadata).
#pragma once

#include "tc/atlas.h"
#include "tc/progress.h"

#include <string>

namespace tc
{
/// Version of the atlas file format that writeAtlas writes; readAtlas reads it and older ones.
constexpr int kAtlasFileVersion = 2;

/// Writes `atlas` to `path` (replaced if it exists). The file is written to a temporary file
/// beside the target and renamed over it only when complete and flushed to disk: on any error or
/// abort the temporary is removed and an existing target is left as it was.
///
/// @param[in] atlas  must pass tc::validateAtlas; its doubles must not be NaN; attribute names
///   must be UTF-8 (source may be anything: bytes that are not UTF-8 are written as U+FFFD)
/// @param[in] path  file to write, conventionally *.exr
/// @param[in] progress  reports the fraction of texel data written; abort throws tc::Aborted
/// @throws tc::InputError  for an invalid atlas, or a path that cannot be written (missing
///   folder, no permission, disk full), naming the path and the cause
void writeAtlas(const Atlas& atlas, const std::string& path, const Progress& progress = {});

/// Reads an atlas written by writeAtlas. Every float texel and every double is bit-identical to
/// what was written.
///
/// @param[in] path  file to read
/// @param[in] progress  reports the fraction of texel data read; abort throws tc::Aborted
/// @return  an atlas that passes tc::validateAtlas
/// @throws tc::InputError  naming the file and what is wrong: missing or unreadable, not
///   OpenEXR, not a TriChart atlas (no or invalid metadata, another format, a newer version),
///   truncated or corrupt (OpenEXR errors, compressed metadata that does not inflate to its
///   declared length, checksum mismatches), parts missing or with wrong sizes or channels, or an
///   atlas that fails tc::validateAtlas
Atlas readAtlas(const std::string& path, const Progress& progress = {});

/// Whether `path` is an OpenEXR file whose headers carry TriChart atlas metadata (headers only:
/// cheap, never throws; readAtlas still checks everything else).
bool isAtlasFile(const std::string& path);
} // namespace tc
