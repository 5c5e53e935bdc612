// SPDX-License-Identifier: BSD-3-Clause
/// @file ply_io.h
/// Stanford PLY input (ASCII and binary, also gzip-compressed), through CGAL's PLY reader, with
/// every face checked: VTK's PLY reader crashes on truncated or damaged files.
#pragma once

#include "tc/mesh.h"

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
} // namespace tc
