// SPDX-License-Identifier: BSD-3-Clause
/// @file path_tracing.h
/// Triangle patches (Feng et al. 2010, section 5.1, Fig. 9): every base edge of the base complex
/// is traced onto the input mesh as a path. The two base triangles of the edge are unfolded into
/// the plane, the input triangles parameterized there (MAPS) are drawn in the same plane, the
/// straight base edge is intersected with them, and Steiner vertices are inserted where it
/// crosses an input edge. Splitting the input along all paths cuts it into one patch per base
/// face: a topological disk bounded by the three paths of its sides.
#pragma once

#include "tc/gim/base_complex.h"
#include "tc/common/mesh.h"
#include "tc/common/progress.h"

#include <cstdint>
#include <vector>

namespace tc
{
struct PatchMesh
{
  /// The input split along the paths. Points 0 .. #V-1 are the input points in order; Steiner
  /// points follow. Triangles are counter-clockwise like the input.
  TriMesh mesh;
  std::vector<int32_t> inputPointId;    ///< #V' input point id, -1 for a Steiner point
  std::vector<int32_t> steinerEdge;     ///< #S x 2: input points of the input edge a Steiner point lies on
  std::vector<double> steinerParameter; ///< #S: t in (0, 1) from steinerEdge[2s] to steinerEdge[2s + 1]
  std::vector<int32_t> patchId;         ///< #F' base face (= patch, = chart) of each triangle
  std::vector<int32_t> inputTriangle;   ///< #F' input triangle each piece came from

  /// Base edges: #Eb x 2 indices into BaseComplexResult::baseVertices, lower index first.
  std::vector<int32_t> baseEdges;
  /// #Fb x 3: base edge of side k (corner k to corner k + 1) of base face f.
  std::vector<int32_t> faceEdges;
  /// Path of base edge e: points pathPoints[pathOffsets[e] .. pathOffsets[e + 1]) of `mesh`,
  /// from the point of baseEdges[2e] to the point of baseEdges[2e + 1].
  std::vector<int64_t> pathOffsets{ 0 };
  std::vector<int32_t> pathPoints;
};

/// @param[in] mesh  the mesh buildBaseComplex was given (closed, manifold, oriented)
/// @param[in] base  its base complex and MAPS parameterization (invalidTriangles should be 0; a
///                  triangle the parameterization folds may make a path impossible to trace)
/// @throws InputError when the arrays do not match the mesh
/// @throws UntraceableError when a path cannot be traced or an input triangle cannot be cut
///         along the paths (the message names the base edge or triangle and what to change)
PatchMesh tracePaths(
  const TriMesh& mesh, const BaseComplexResult& base, const Progress& progress = {});
} // namespace tc
