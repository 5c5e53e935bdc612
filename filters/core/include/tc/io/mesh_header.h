// SPDX-License-Identifier: BSD-3-Clause
/// @file mesh_header.h
/// The size a mesh file declares, read without reading the mesh, so that a face can estimate the
/// memory of a request (tc/gim/build_memory.h) and refuse it before the reader allocates.
#pragma once

#include <cstdint>
#include <string>

namespace tc
{
/// Counts a mesh file declares; -1 where the format does not say (or the file cannot be read:
/// the reader then says why).
struct MeshFileCounts
{
  int64_t points = -1;
  int64_t triangles = -1; ///< faces as declared: a polygon counts once (a lower bound)
};

/// The counts of `path` by its extension: PLY and gzip-compressed PLY (the header's vertex and
/// face elements), OFF (its count line), binary STL (the facet count, when the file's size
/// matches it; points taken as half the facets, as on a closed mesh), OBJ (its v and f lines,
/// counted in one pass over the file without keeping it). Other formats, ASCII STL and damaged
/// headers give -1. Reads at most the first 64 KiB, except of an OBJ file.
MeshFileCounts readMeshFileCounts(const std::string& path);
} // namespace tc
