// SPDX-License-Identifier: BSD-3-Clause
/// @file atlas_io.h
/// The atlas file: a tc::Atlas (atlas.h) as one OpenEXR multi-part file, read back bit for bit.
/// A part per attribute and image (coarsest first, a finer image storing only the samples the
/// coarser ones lack), Position and Normal as integer lattice codes predicted from the coarser
/// image (version 4; version 3 when the atlas's values lie on no lattice), other attributes as
/// 32-bit floats, and a zlib-compressed JSON chart table with CRC-32 checksums of the table and
/// of every image. docs/atlas-format.md describes the format (versions 4 and 3, and the versions
/// 1 and 2 it still reads), how the reader validates a file and how the writer replaces one.
/// OpenEXR because it stores float32 and integer images losslessly and any image tool opens
/// them.
#pragma once

#include "tc/common/progress.h"
#include "tc/gim/atlas.h"

#include <string>

namespace tc
{
/// The newest version of the atlas file format, which readAtlas reads with all older ones and
/// writeAtlas writes for a skinned atlas: version 5 plus the rig (skeleton and animations) in
/// the metadata.
constexpr int kAtlasFileVersion = 6;
/// The version writeAtlas writes for an atlas with textures and no rig: version 4 or 3
/// (lattice or not) plus a part per texture.
constexpr int kAtlasTextureVersion = 5;
/// The version writeAtlas writes for an atlas without textures whose every position and normal
/// decodes exactly from its lattice code, as in every atlas the pipeline builds.
constexpr int kAtlasLatticeVersion = 4;
/// The version writeAtlas writes for any other atlas: every attribute as float32.
constexpr int kAtlasFloatVersion = 3;

/// Writes `atlas` to `path` (replaced if it exists). The file is written to a temporary file
/// beside the target and renamed over it only when complete and flushed to disk: on any error or
/// abort the temporary is removed and an existing target is left as it was.
///
/// @param[in] atlas  must pass tc::validateAtlas; its doubles must not be NaN; attribute names
///   must be UTF-8 (source may be anything: bytes that are not UTF-8 are written as U+FFFD)
/// @param[in] path  file to write, named *.exr (any case)
/// @param[in] progress  reports the fraction of texel data written; abort throws tc::Aborted
/// @throws tc::InputError  for an invalid atlas, a path not named .exr, or a path that cannot be
///   written (missing folder, no permission, disk full), naming the path and the cause
void writeAtlas(const Atlas& atlas, const std::string& path, const Progress& progress = {});

/// Whether writeAtlas takes the name `path`: it ends with .exr, in any case.
bool isAtlasFileName(const std::string& path);

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

/// The rig (skeleton and animations) of the atlas file `path`, from its headers alone: what a
/// reader announces (the animation's time steps) before it reads the texels.
/// @throws tc::InputError  as readAtlas for a file that is no atlas or whose metadata is damaged
Rig readAtlasRig(const std::string& path);

/// Whether `path` is an OpenEXR file whose headers carry TriChart atlas metadata (headers only:
/// cheap, never throws; readAtlas still checks everything else).
bool isAtlasFile(const std::string& path);
} // namespace tc
