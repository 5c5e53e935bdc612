// SPDX-License-Identifier: BSD-3-Clause
/// @file soup_io.h
/// Stanford PLY (ASCII and binary, also gzip-compressed) and Wavefront OBJ input through CGAL's
/// readers, with every face checked: VTK's PLY and OBJ readers crash on damaged files.
#pragma once

#include "tc/common/mesh.h"

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

/// Reads the vertices (v) and faces (f, with their first index of each corner: "f 1/4/2 ..."
/// gives 1; negative indices count back from the last vertex) of an OBJ file. Texture
/// coordinates, normals, groups and materials are skipped.
///
/// @param[in] path  file to read
/// @return  #V points and #F polygons in file order
/// @throws tc::InputError  naming the file, for a missing or unreadable file, a file CGAL's
///   reader refuses (with the counts read), a face with fewer than 3 corners or a corner out of
///   range, or a file without faces
PolygonSoup readOBJ(const std::string& path);

/// The inflated bytes of a whole gzip file.
///
/// @throws tc::InputError  naming the file, for a missing file, one without the gzip header, or
///   a stream that does not inflate
std::string readGzip(const std::string& path);
} // namespace tc
