// SPDX-License-Identifier: BSD-3-Clause
/// @file md2_frames.h
/// Every vertex keyframe of a Quake II MD2 model, for tc::readSequence.
#pragma once

#include "tc/common/progress.h"
#include "tc/io/sequence_io.h"

#include <string>

namespace tc
{
/// Reads every frame of the MD2 file `path` as tc::readSequence documents it (source "md2").
/// The whole header is checked against the file's size before anything else is read or
/// allocated.
///
/// @param[in] path      the .md2 file
/// @param[in] progress  reported once per frame; may abort (tc::Aborted)
/// @throws tc::InputError  "cannot read 'path' as MD2: ..." for a missing file, a header that is
///   no MD2 one, counts or offsets the file does not hold, a triangle whose vertex or texture
///   coordinate index is out of range, or a frame whose scale or translation is not finite
DeformingSequence readMD2Sequence(const std::string& path, const Progress& progress);
} // namespace tc
