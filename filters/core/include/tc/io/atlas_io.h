// SPDX-License-Identifier: BSD-3-Clause
/// @file atlas_io.h
/// The atlas file: a tc::Atlas (atlas.h) as one OpenEXR multi-part file, read back bit for bit.
///
/// Layout (format "TriChart atlas", version 3):
/// - one scan-line part per attribute a and image k, named "<attribute name>.<k>" (e.g.
///   "Position.0", "Normal.2"), the coarsest image first (image K - 1 (all attributes), then
///   K - 2, ... 0), so that a file read front to back refines; every part shares the display
///   window of the largest image, as OpenEXR requires of multi-part files;
/// - one FLOAT channel per component, lossless ZIP compression; channel names by component
///   count: 3 -> X, Y, Z; 1, 2, 4 -> R; R, G; R, G, B, A; any other count n -> C0 .. C(n-1);
/// - an image whose metadata says "texels": "new" is stored compactly. Its texels are of three
///   kinds: sample (i, j), both even, of a chart at level d >= 1 repeats sample (i/2, j/2) of
///   level d - 1 in image k + 1 (the point-sampled pyramid, "every other sample"), and is not
///   stored; a texel no chart covers is 0 and is not stored; every other chart sample is new.
///   The part holds the new texels in texel order (row y = 0, 1, ..., x = 0, 1, ... within a
///   row), filling rows of the image's width one after the other, the last row completed with
///   zeros: its data window is (0, 0) .. (width - 1, ceil(new texels / width) - 1), at least one
///   row. A reader rebuilds the images coarsest first. The writer stores an image this way
///   whenever its texels allow it, which the pipeline's atlases always do; the coarser images
///   then cost no bytes, a quarter of the texels of the finer ones;
/// - an image whose metadata says "texels": "all" is stored whole: the part's data window is
///   (0, 0) .. (width - 1, height - 1) of image k and EXR scan line y is atlas row y (no flip:
///   texel (x, y) of atlas.h is pixel (x, y) of the part);
/// - the metadata is UTF-8 JSON with "format": "TriChart atlas", "version": 3, "source",
///   "inputPoints", "inputTriangles", "inputDiagonal", "attributes": [{"name", "components"}],
///   "images": [{"width", "height", "texels", "crc32": [one per attribute]}] and "charts":
///   [{every AtlasChart field under its C++ name}]. The first part's header holds it as three
///   attributes: the string attribute "trichartAtlasZ", the JSON text compressed by zlib
///   (RFC 1950 stream, best compression; the string holds these raw bytes, NULs included), the
///   int attribute "trichartAtlasLength", the byte length of the JSON text, and the int
///   attribute "trichartAtlasCrc32", the CRC-32 of the JSON text.
///
/// Versions 1 and 2, which readAtlas still reads, store every image whole (no "texels" entry,
/// parts in the order image 0, 1, ...). Version 2 differs from version 3 in nothing else;
/// version 1 has "version": 1 and the plain JSON text in the string attribute "trichartAtlas"
/// (with "trichartAtlasCrc32"; no length attribute).
///
/// Doubles are JSON numbers that read back to the same bits (-0.0 included); +-infinity, which
/// JSON cannot hold, is written as the string "inf" / "-inf". The CRC-32 (zlib) of every image's
/// float data per attribute (all its texels as atlas.h lays them out, little-endian bytes,
/// whether its part is compact or whole) and of the JSON catch damage that OpenEXR cannot see
/// (chunks that ZIP left uncompressed, digits in the metadata).
#pragma once

#include "tc/gim/atlas.h"
#include "tc/common/progress.h"

#include <string>

namespace tc
{
/// Version of the atlas file format that writeAtlas writes; readAtlas reads it and older ones.
constexpr int kAtlasFileVersion = 3;

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
