// SPDX-License-Identifier: BSD-3-Clause
/// @file base_complex.h
/// The feature-constrained base complex and its MAPS parameterization (Feng et al. 2010,
/// section 5.1; Lee et al. 1998, MAPS). Quadric-error half-edge collapses, each keeping one
/// endpoint (so base vertices are original vertices), simplify the mesh to a few dozen or
/// hundred triangles; feature curves become base edges and no base triangle straddles a
/// feature. As each vertex is removed, its one-ring is flattened with the conformal z^a map and
/// the vertex, with every vertex already parameterized over that ring, is located in the
/// retriangulated flat domain, so that every original vertex ends with a base face and
/// barycentric coordinates, and the map from the mesh to the base complex is a bijection.
#pragma once

#include "tc/common/mesh.h"
#include "tc/common/progress.h"

#include <cstdint>
#include <vector>

namespace tc
{
struct BaseComplexOptions
{
  /// Stop when the base complex has at most this many triangles.
  int64_t targetFaces = 100;
  /// Also stop before a collapse whose quadric error exceeds this fraction of the squared
  /// bounding-box diagonal (0: no error bound, only targetFaces). The error of a collapse is the
  /// mean squared distance of the kept vertex to the planes of the surface merged into it (the
  /// Garland-Heckbert quadric over the area it covers); collapses above the bound are never made,
  /// so the default, 1e-4, keeps every base triangle within about 1% of the diagonal (RMS) of
  /// its surface. Why a bound: where feature curves block collapses (their vertices cannot leave
  /// the curve), the count target alone is met by collapsing the smooth regions into huge
  /// triangles that deviate far from their surface, and every level of the geometry images is
  /// worse for it. The bound stops nothing while the base complex has more than one face per 32
  /// input points, so that a coarse input still gets charts large enough to sample.
  double maxError = 1e-4;
  /// Shape bound on the triangles a collapse creates, as 4 sqrt(3) area / (sum of squared
  /// sides) (1 equilateral, 0 degenerate; 0.1 is a smallest angle of about 5 degrees). Relative
  /// to the neighbours: a collapse may still create a triangle as good as the worst one it
  /// replaces, so a mesh that already has slivers can be simplified.
  double minTriangleQuality = 0.1;
  /// Largest angle in degrees between the normal of a triangle before and after the collapse
  /// moves one of its corners; 90 only forbids flips.
  double maxNormalChange = 90.0;
  /// Weight of the feature-curve quadrics (planes through a feature edge, perpendicular to its
  /// faces, weighted by squared edge length) against the area-weighted face quadrics.
  double featureWeight = 1.0;
  /// Check every collapse for input triangles it would fold or stretch across the base complex
  /// (see BaseComplexResult::invalidTriangles) and reject it if so. This keeps the map a
  /// bijection at every level; turned off, simplification is several times faster and folds are
  /// only repaired at the end, where some may remain.
  bool checkBijection = true;
};

struct BaseComplexResult
{
  std::vector<int32_t> baseVertices;     ///< #Vb original vertex id of each base vertex, ascending
  std::vector<int32_t> baseTriangles;    ///< #Fb x 3 indices into baseVertices, outward (CCW)
  std::vector<int32_t> vertexBaseFace;   ///< #V base face of every original vertex
  std::vector<double> vertexBarycentric; ///< #V x 3 barycentrics in that face (sum 1)
  std::vector<int32_t>
    baseEdgeIsFeature;   ///< #Fb x 3: 1 if side (i, i+1) of a base face carries a feature curve
  int64_t collapses = 0; ///< half-edge collapses performed
  double maxCollapseError = 0.0; ///< largest quadric error accepted (fraction of diag^2)
  /// False when the simplification stopped above targetFaces because every remaining collapse
  /// would break a rule (feature, topology, normal, shape or a valid flat retriangulation) or
  /// exceed maxError; the result is still a valid base complex, only finer than asked.
  bool reachedTarget = false;
  /// Points of the MAPS parameterization that fell outside every new triangle of a collapse by
  /// round-off and were snapped into the nearest one (Lee et al.'s flip repair).
  int64_t snappedPoints = 0;
  /// Input triangles left folded or stretched across the base complex after the flip repair
  /// (0 when the parameterization is a bijection). Each triangle is drawn with straight sides
  /// in the chart of its corners' images: one base face (barycentric plane), two base faces
  /// unfolded about their shared edge, or the star of a base vertex flattened by z^a.
  int64_t invalidTriangles = 0;
};

/// Simplifies `mesh` into its base complex and parameterizes every input vertex over it
/// (section 5.1). Deterministic: ties are broken by input ids, so equal inputs give equal bits.
/// @param[in] mesh           #V x 3 points, #F x 3 triangles: closed, manifold, oriented
/// @param[in] featureVertex  #V 1 on a feature curve (may be empty: no features)
/// @param[in] cornerVertex   #V 1 at a corner (never removed; may be empty)
/// @param[in] featureEdges   #E x 2 vertex ids of the mesh edges that make the feature curves
/// @param[in] options        when to stop and which collapses to refuse (BaseComplexOptions)
/// @param[in] progress       fraction done (set-up, collapses, flip repair); abort throws
///                           tc::Aborted
/// @return the base complex in input vertex ids and the parameterization (BaseComplexResult)
/// @throws InputError for a mesh that is not a closed oriented manifold, or arrays that do not
///         match it; the message says what to fix (e.g. split non-manifold vertices in
///         tcMeshPreparation)
BaseComplexResult buildBaseComplex(const TriMesh& mesh, const std::vector<uint8_t>& featureVertex,
  const std::vector<uint8_t>& cornerVertex, const std::vector<int32_t>& featureEdges,
  const BaseComplexOptions& options = {}, const Progress& progress = {});
} // namespace tc
