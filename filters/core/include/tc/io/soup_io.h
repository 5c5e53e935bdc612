// SPDX-License-Identifier: BSD-3-Clause
/// @file soup_io.h
/// Stanford PLY (ASCII and binary, also gzip-compressed, through CGAL's reader) and Wavefront OBJ
/// input (parsed here), with every face checked: VTK's PLY and OBJ readers crash on damaged
/// files. The ...File functions also give texture coordinates, colours and the texture.
#pragma once

#include "tc/common/mesh.h"
#include "tc/io/mesh_file.h"

#include <string>

namespace tc
{
/// Reads the vertex positions (x, y, z) and the faces (the vertex_indices or vertex_index list)
/// of a PLY file, ASCII or binary of either byte order, or of a gzip-compressed one when `path`
/// ends in ".gz". Other properties and elements are skipped.
///
/// @param[in] path  file to read
/// @return  #V points and #F polygons in file order
/// @throws tc::InputError  naming the file, for a missing or unreadable file, a gzip stream
///   that does not inflate, a header or body that is no PLY (with the counts the header
///   declares and how many were read), a face with fewer than 3 corners or a corner out of
///   range, or a file without faces
PolygonSoup readPLY(const std::string& path);

/// readPLY, with the vertices' texture coordinates (properties u v, s t, texture_u texture_v or
/// texture_s texture_t, v = 0 at the image's bottom), colours (red green blue [alpha] or
/// r g b [a]) and the texture a "comment TextureFile <name>" line names (MeshLab's), read
/// relative to the file's folder; a missing texture file is a warning.
///
/// @throws tc::InputError  as readPLY
MeshFile readPLYFile(const std::string& path);

/// Reads an OBJ file: its vertices ("v x y z", or "v x y z r g b" with colours in [0, 1]),
/// texture coordinates ("vt u [v]", v = 0 at the image's bottom as OBJ has it) and faces ("f"
/// with corners v, v/vt, v//vn or v/vt/vn; negative indices count back from the last one read),
/// and the map_Kd of its materials (mtllib, usemtl) as the texture (see tc::MeshFile).
/// Normals, groups, lines and other statements are skipped.
///
/// Points: one per v line, in file order; with texture coordinates, one more for each further
/// distinct (v, vt) pair of a vertex (a UV seam), appended, as vtkOBJReader does; vertices no face
/// uses get (0, 0). Texture coordinates are kept only when every corner has one: a file where
/// some corners have none (the format allows it) is read without them, with a warning naming the
/// line of the first such corner. Colours likewise only when every v line has r g b. A missing
/// .mtl or texture file is a warning.
///
/// @param[in] path  file to read
/// @throws tc::InputError  "cannot read 'path' as OBJ: line N: ..." for a v line without 3
///   numbers, a vt line without a number, a token that is no number or index, a face with fewer
///   than 3 corners, a corner index 0 or out of range (vertex or texture coordinate); or for a
///   missing file or one without faces
MeshFile readOBJFile(const std::string& path);

/// The polygons of readOBJFile: #V points and #F polygons in file order.
PolygonSoup readOBJ(const std::string& path);

/// The inflated bytes of a whole gzip file.
///
/// @throws tc::InputError  naming the file, for a missing file, one without the gzip header, or
///   a stream that does not inflate
std::string readGzip(const std::string& path);
} // namespace tc
