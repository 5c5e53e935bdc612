// SPDX-License-Identifier: BSD-3-Clause
/// @file path_tracing.h
/// Triangle patches (Feng et al. 2010, section 5.1, Fig. 9): every base edge of the base complex
/// is traced onto the input mesh as a path, and the input is split along all paths into one patch
/// per base face, a topological disk bounded by the three paths of its sides.
///
/// A path is the base edge drawn straight in the base domain of the MAPS parameterization, over
/// the input triangles drawn there by the images of their corners (two base faces unfolded about
/// their common edge, as in the paper, or the star of a base vertex flattened by z^a); a Steiner
/// point is inserted where it crosses an input edge. Each input edge is drawn in one chart only,
/// so the two triangles of an edge share its Steiner points to the bit: no T-junctions, no paths
/// that cross. The result does not depend on the thread count.
#pragma once

#include "tc/common/mesh.h"
#include "tc/common/progress.h"
#include "tc/gim/base_complex.h"

#include <cstdint>
#include <vector>

namespace tc
{
/// The input split along the traced paths.
struct PatchMesh
{
  /// The input split along the paths. Points 0 .. #V-1 are the input points in order; Steiner
  /// points follow. Triangles are counter-clockwise like the input, in input order: the pieces of
  /// an input triangle take its place.
  TriMesh mesh;
  std::vector<int32_t> inputPointId; ///< #V' input point id, -1 for a Steiner point
  /// #S x 2: the input points (lower id first) of the input edge each Steiner point lies on.
  std::vector<int32_t> steinerEdge;
  /// #S: t in (0, 1) from steinerEdge[2s] to steinerEdge[2s + 1]; the point is p0 + t (p1 - p0).
  std::vector<double> steinerParameter;
  std::vector<int32_t> patchId;       ///< #F' base face (= patch, = chart) of each triangle
  std::vector<int32_t> inputTriangle; ///< #F' input triangle each piece came from

  /// Base edges: #Eb x 2 indices into BaseComplexResult::baseVertices, lower index first, in
  /// lexicographic order.
  std::vector<int32_t> baseEdges;
  /// #Fb x 3: base edge of side k (corner k to corner k + 1) of base face f.
  std::vector<int32_t> faceEdges;
  /// Path of base edge e: points pathPoints[pathOffsets[e] .. pathOffsets[e + 1]) of `mesh`,
  /// from the point of baseEdges[2e] to the point of baseEdges[2e + 1], consecutive points joined
  /// by an edge of `mesh`. A path on a feature curve passes through input points only.
  std::vector<int64_t> pathOffsets{ 0 };
  std::vector<int32_t> pathPoints;
};

/// Traces every base edge of `base` onto `mesh` and splits the mesh along the paths.
/// @param[in] mesh      the mesh buildBaseComplex was given (closed, manifold, oriented)
/// @param[in] base      its base complex and MAPS parameterization (invalidTriangles should be 0;
///                      a triangle the parameterization folds may make a path impossible to
///                      trace)
/// @param[in] progress  reported between blocks of work; may abort (tc::Aborted)
/// @return the split mesh, its patches and the paths
/// @throws InputError when the arrays do not match the mesh or each other, the mesh or the base
///         complex is not a closed oriented manifold, a point has no valid image in the base
///         complex, or the ids would not fit in 32 bits (the message says what to pass instead)
/// @throws UntraceableError when a path cannot be traced or an input triangle cannot be cut
///         along the paths (the message names the base edge or triangle and what to change)
PatchMesh tracePaths(
  const TriMesh& mesh, const BaseComplexResult& base, const Progress& progress = {});

/// Values given per triangle corner of the traced mesh (texture coordinates across a seam,
/// tc/prep/corner_attributes.h) at the corners of its pieces: each corner of a piece is a
/// corner of its input triangle or a Steiner point on one of its sides, so the value is that
/// corner's, or interpolated along that side, from the input triangle's own corners.
/// @param[in] patches     tracePaths' result for `mesh`
/// @param[in] mesh        the mesh given to tracePaths
/// @param[in] values      #F x 3 x components over mesh's triangles
/// @return #F' x 3 x components over patches.mesh's triangles
/// @throws InputError when the sizes do not match
std::vector<double> pieceCornerValues(const PatchMesh& patches, const TriMesh& mesh,
  const std::vector<double>& values, int32_t components);
} // namespace tc
