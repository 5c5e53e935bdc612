// SPDX-License-Identifier: BSD-3-Clause
/// @file off_io.h
/// Object File Format (OFF) input and output. VTK has no OFF reader, so the VTK layer and the
/// command-line tools read CGAL / Princeton meshes through these two functions.
#pragma once

#include "tc/common/mesh.h"

#include <string>

namespace tc
{
/// Reads an ASCII OFF file and its common variants into a polygon soup.
///
/// Accepted: the keyword [ST][C][N][4][n]OFF (OFF, COFF, NOFF, CNOFF, STOFF, 4OFF, nOFF with its
/// dimension), '#' comments anywhere, blank lines, CR-LF line ends, the counts "V F [E]" on the
/// keyword line or on a line of their own, one vertex per line (its first 3 numbers are the
/// position; for 4OFF x y z w gives x/w y/w z/w; further columns such as normals, colours or
/// texture coordinates are ignored), one face per line "n i0 .. i(n-1) [colour]". Anything after
/// the last face (an edge list) is ignored. NaN and Inf coordinates are read as such:
/// tc::prepareMesh reports them.
///
/// @param[in] path  file to read
/// @return  #V points and #F polygons in file order, point ids 0-based as in the file
/// @throws tc::InputError  "path:line: what is wrong" for a missing or unreadable file, a file
///   that is not ASCII OFF (binary OFF included), bad counts, a non-numeric token, a vertex with
///   fewer than 3 coordinates, a face whose corner index is out of range, or a truncated file.
PolygonSoup readOFF(const std::string& path);

/// Writes a triangle mesh as ASCII OFF. Coordinates are written in the shortest form that reads
/// back to the same double, so writeOFF then readOFF is bit-exact. The text goes to a temporary
/// file beside the target, which is renamed over it at the end: a failed write never leaves a
/// half-written file behind.
///
/// @param[in] path  file to write (replaced if it exists)
/// @param[in] mesh  #V points, #F x 3 triangles with ids in [0, #V)
/// @throws tc::InputError  when a triangle refers to a missing point, or on any I/O failure
///   (missing folder, no permission, disk full)
void writeOFF(const std::string& path, const TriMesh& mesh);
} // namespace tc
