// SPDX-License-Identifier: BSD-3-Clause
/// @file obj_materials.h
/// The base-colour texture of an OBJ file: its material libraries (.mtl) and their map_Kd.
#pragma once

#include "tc/io/mesh_file.h"

#include <string>
#include <vector>

namespace tc
{
/// The map_Kd of the first material, in the order the faces use them (`used`, from usemtl), that
/// has one, read from its file (tc::readTextureFile); with no usemtl, the first material of the
/// libraries that has one. `leftOut` counts the other materials' distinct map_Kd names. A library
/// that is missing adds a warning; a file with no texture gives an empty name.
///
/// @param[in] objPath    the OBJ file (libraries and textures are relative to its folder)
/// @param[in] libraries  the mtllib names, in file order
/// @param[in] used       the usemtl names, in the order faces first use them
/// @param[in,out] warnings  the reader's warnings
BaseColorTexture objBaseColorTexture(const std::string& objPath,
  const std::vector<std::string>& libraries, const std::vector<std::string>& used,
  std::vector<std::string>& warnings);
} // namespace tc
