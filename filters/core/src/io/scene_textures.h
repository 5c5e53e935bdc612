// SPDX-License-Identifier: BSD-3-Clause
/// @file scene_textures.h
/// The base-colour texture of a scene Assimp read: embedded in the file or beside it.
#pragma once

#include "tc/io/mesh_file.h"

#include <string>
#include <vector>

struct aiScene;

namespace tc
{
/// The base-colour (else diffuse) texture of the first mesh's material, in the scene's mesh
/// order, that has one (see tc::readScene): an embedded image as its encoded bytes (Assimp's
/// mHeight 0) or as raw texels turned to RGBA with row 0 at the bottom; else the file, relative
/// to `path`'s folder. `leftOut` counts the other materials' distinct textures. An embedded
/// reference the file lacks, or a missing file, adds a warning.
///
/// @param[in] scene  as Assimp read it
/// @param[in] path   the scene file
/// @param[in,out] warnings  the reader's warnings
BaseColorTexture sceneBaseColorTexture(
  const aiScene& scene, const std::string& path, std::vector<std::string>& warnings);
} // namespace tc
