// SPDX-License-Identifier: BSD-3-Clause
/// @file ply_layout.h
/// The layout a PLY header declares, as tc::readPLY checks it (soup_io.cpp), and the vertex
/// properties CGAL's reader skips: texture coordinates and colours with alpha.
#pragma once

#include "tc/io/mesh_file.h"

#include <map>
#include <string>
#include <utility>
#include <vector>

namespace tc
{
/// One element of a PLY header: its name and the type of each property ("list <type>" for a
/// list), the first of a repeated name only, as CGAL's reader looks names up.
struct PlyElement
{
  std::string name;
  long long count = 0;
  std::map<std::string, std::string> types;
  /// Every property in file order: its list's size type ("" for a scalar), its value type.
  std::vector<std::pair<std::string, std::string>> layout;
  std::vector<std::string> names; ///< every property's name, in file order
};

/// What checkHeader found: where the end_header line starts and the data after it, the format.
struct PlyHeader
{
  size_t end = 0;
  size_t body = 0;
  std::string format;
  std::vector<PlyElement> elements;
  std::string textureFile; ///< of a "comment TextureFile <name>" line (MeshLab's), or ""
};

/// Bytes of a binary PLY scalar type.
inline size_t plySize(const std::string& type)
{
  if (type == "char" || type == "uchar" || type == "int8" || type == "uint8")
  {
    return 1;
  }
  if (type == "short" || type == "ushort" || type == "int16" || type == "uint16")
  {
    return 2;
  }
  return type == "double" || type == "float64" ? 8 : 4;
}

/// The texture coordinates (vertex properties u v, s t, texture_u texture_v or texture_s
/// texture_t, taken as they are: v = 0 at the image's bottom, as MeshLab writes them) and colours
/// (red green blue [alpha] or r g b [a]; bytes as they are, floats scaled from [0, 1]) of the
/// vertex element of a file whose header `header` checked. Empty where the file has none, or
/// when its data ends early (CGAL's reader then reports the file).
PointAttributes readPlyVertexAttributes(const std::string& bytes, const PlyHeader& header);
} // namespace tc
