// SPDX-License-Identifier: BSD-3-Clause
/// @file file_names.h
/// File-name rules that the writers share: a writer picks its format by the extension and
/// refuses one it does not write.
#pragma once

#include <string>

namespace tc
{
/// Whether `path` ends with `extension` (".glb", ".ply.gz"), ignoring ASCII case.
bool hasExtension(const std::string& path, const std::string& extension);

/// Whether `path` is a name (not the extension alone) ending with one of `extensions`, given
/// space-separated without dots ("glb gltf fbx"), ignoring ASCII case.
bool hasOneOfExtensions(const std::string& path, const char* extensions);
} // namespace tc
