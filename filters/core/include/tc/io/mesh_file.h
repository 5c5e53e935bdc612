// SPDX-License-Identifier: BSD-3-Clause
/// @file mesh_file.h
/// What a mesh file holds besides its polygons: per-point texture coordinates and colours, and the
/// base-colour texture of its first textured material. The core decodes no image: it returns the
/// encoded bytes (PNG, JPEG, ...) or raw texels, and the VTK layer decodes them (tcMeshReader).
#pragma once

#include "tc/common/mesh.h"

#include <cstdint>
#include <string>
#include <vector>

namespace tc
{
/// Per-point values of a mesh file, each empty when the file does not give it for every point.
struct PointAttributes
{
  /// #V x 2 (u, v) in OpenGL / VTK convention: v = 0 at the bottom row of the image.
  std::vector<float> textureCoordinates;
  /// #V x 4 RGBA bytes; alpha 255 where the file gives RGB only.
  std::vector<uint8_t> colors;
};

/// The base-colour texture (glTF baseColorTexture, a diffuse map, OBJ map_Kd) of the first
/// material that has one, as the file stores it. `encoded` or `rgba` holds the image; neither
/// does when the material names a file that is missing (a warning of the reader says so).
struct BaseColorTexture
{
  std::string name;    ///< as the material names it, or "embedded:<k>" for the file's k-th image
  std::string path;    ///< where an external file was looked for ("" when embedded)
  std::string encoded; ///< the image file's bytes (PNG, JPEG, ...), to be decoded
  int width = 0;       ///< of raw texels (`rgba`); 0 for an encoded image
  int height = 0;
  std::vector<uint8_t> rgba; ///< raw texels: width x height x 4, row 0 = the image's bottom
  int64_t leftOut = 0;       ///< distinct base-colour textures of other materials, not kept

  bool hasImage() const { return !encoded.empty() || !rgba.empty(); }
};

/// A mesh file as read: the polygons, the per-point values, the texture, and what the reader
/// left out or doubted, one sentence each ("3 faces have no texture coordinates: ...").
struct MeshFile
{
  PolygonSoup soup;
  PointAttributes attributes;
  BaseColorTexture texture;
  std::vector<std::string> warnings;
};

/// Texture `name`, as a material of the mesh file `meshPath` names it, read from its file: a
/// relative name is taken from the mesh's folder ('\\' read as '/'). A file that is missing or
/// unreadable leaves `encoded` empty and appends a warning to `warnings`.
///
/// @param[in] meshPath  the mesh file
/// @param[in] name      the texture's file name as the material gives it
/// @param[in,out] warnings  the reader's warnings
BaseColorTexture readTextureFile(
  const std::string& meshPath, const std::string& name, std::vector<std::string>& warnings);
} // namespace tc
