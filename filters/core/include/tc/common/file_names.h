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
} // namespace tc
