// SPDX-License-Identifier: BSD-3-Clause
/// @file geometry_images.h
/// Triangular geometry images (Feng et al. 2010, section 5.2): every patch of a PatchMesh is
/// parameterized onto the right triangle (0,0), (1,0), (0,1) with Floater's mean-value
/// coordinates, its boundary fixed by arc length along the three paths, then reweighted to lower
/// its L2 stretch (see GeometryImageOptions::stretchIterations); the parameterization is
/// resampled on a (2^d + 1)-per-side triangular grid for every level d <= d_max; charts are
/// packed in pairs into (2^dh + 2) x (2^dh + 1) rectangles of one image per mip step. The result
/// is a tc::Atlas (tc/gim/atlas.h) that keeps every invariant listed there.
///
/// How the samples are made:
/// - The area rule (the paper's): 4^d_max of chart c proportional to its curvature-weighted
///   area A_c = sum over its triangles of area * (1 + curvatureWeight * |H| * diagonal), |H| the
///   mean of |meanCurvature| at the triangle's corners and `diagonal` the input's bounding-box
///   diagonal (so the weight is dimensionless: 1 where the radius of curvature equals the
///   diagonal). The constant of proportionality is the largest one whose total of samples at
///   every chart's finest level fits sampleBudget; d_max is clamped to [minLevel, maxLevel].
/// - The error rule (LevelRule::Error, the default): every chart is sampled up to
///   min(area-rule d_max + kErrorRuleLevelsAbove, maxLevel) and its levelError measured at each
///   of those levels; then, from minLevel everywhere, the chart with the largest error at its
///   current level rises by one level while that rise, gridVertexCount(d + 1) -
///   gridVertexCount(d), fits sampleBudget. Errors within 1e-6 of (diagonal + largest |coordinate|)
///   of the largest tie and rise together or not at all, so congruent charts keep one d_max and
///   flat charts (errors of float rounding only) share the budget evenly. A chart at its cap, or a
///   tie whose rise does not fit, leaves the competition and the next largest is tried. The same
///   budget thus goes where the measured error is (creases inside a chart, whose error falls
///   slowly with the level, get the samples that flat charts do not need). The result does not
///   depend on the thread count. Levels are point samples of the finest grid, so the grids
///   sampled at the cap hold every lower level bit for bit: nothing is sampled twice and the atlas
///   equals one sampled directly at the chosen d_max (then fitted).
/// - With an errorTarget (the default), the error rule stops on the error instead of the
///   budget: charts are
///   sampled first at the area rule's d_max, and every chart whose levelError there is above
///   errorTarget * diagonal is sampled again one level finer (with its paths, and the charts
///   across them, which copy their sides), round after round, until none is above the target
///   below maxLevel or the grids would hold more than 4^kErrorRuleLevelsAbove times the area
///   rule's budget (largest errors first). The charts then rise as above, each only while its
///   error is above the target (and the rise fits sampleBudget when one is given): every chart
///   ends at the first level below the target, or at its cap.
/// - Interior grid samples: the grid point is located in the parameterized patch and position,
///   normal (renormalized) and every extra attribute are interpolated barycentrically.
/// - Side samples are never located in 2-D: each path is sampled once, by arc length, from its
///   lower base vertex to its higher one, at the dyadic fractions of the finer of its two charts,
///   and both charts copy the same float values (a coarser level takes every other one).
///   Corner samples are the base vertex's own values, the same in every chart.
/// - Normals: the given ones (or angle-weighted vertex normals), except near feature curves
///   (BaseComplexResult::baseEdgeIsFeature), where a shared vertex normal averages across the
///   crease. Along a side that follows a feature curve each chart uses the normals of its own
///   triangles only (one-sided), so the crease stays sharp (positions stay identical); inside a
///   chart, points on such a side and corners on a feature curve use the one-sided normal; a
///   side that is not a feature but ends at a corner on one takes, at that end, the normal of
///   its two charts' triangles (shared by both). Corner samples keep the shared normal, the
///   same in every chart.
/// - Fitted samples (GeometryImageOptions::fitSamples, the default): interpolated samples lie
///   on the surface, so on a curved surface every grid triangle is a chord that lies to one
///   side of it. Once d_max is chosen, each path's samples at the lower d_max of its two charts
///   (eq. 8 never draws a side finer) are fitted to the path, the finer chart's samples between
///   them put on the straight lines it is drawn with, then each chart's interior samples at its
///   d_max to its patch, by least squares (data: the points and the triangles' centroids at
///   their (u, v), weighted by area; a weak membrane on the offsets keeps them smooth where a
///   sample has little data; no interior sample moves farther than the chart's interpolated
///   levelError at d_max). Paths along feature curves stay on the curve; corners stay on
///   their base vertex; both charts of a side still copy the same floats at every level both
///   have. levelError and the box are measured on the fitted samples. Normals and extra
///   attributes stay interpolated.
/// - Level d is sample (2^(d_max-d) i, 2^(d_max-d) j) of the finest grid: a point-sampled
///   pyramid, so every level's sides are a subset of the finer ones (what eq. 8 needs).
/// - Packing: charts sorted by d_max and paired in that order (closest d_max together); the
///   higher one lower-left (rotated 0), the other upper-right turned by 180 degrees (rotated 1).
///   Each image is shelf-packed, tallest rectangle first; its width is the multiple of 4 (from
///   the widest rectangle up to twice sqrt(total area)) that gives the smallest image.
/// - AtlasChart::box: the box along the principal axes of the patch's points, holding them and
///   the fitted samples.
///
/// Cost: one sparse LU per patch, O(samples) for the grids, one sparse LDLT per chart and per
/// path for the fit. Patches, paths and charts run in parallel. The error rule samples up to
/// 16x the budget to measure (two levels above the area rule).
#pragma once

#include "tc/common/progress.h"
#include "tc/gim/atlas.h"
#include "tc/gim/base_complex.h"
#include "tc/gim/path_tracing.h"

#include <cstdint>
#include <string>
#include <vector>

namespace tc
{
/// How GeometryImageOptions chooses each chart's d_max (see the file comment).
enum class LevelRule : int32_t
{
  Area = 0,  ///< 4^d_max proportional to the curvature-weighted area (paper section 5.2)
  Error = 1, ///< the budget spent greedily on the largest measured levelError
};

/// Levels above the area rule's d_max up to which the error rule measures a chart.
constexpr int32_t kErrorRuleLevelsAbove = 2;

/// The default GeometryImageOptions::errorTarget. The target bounds each chart's levelError
/// (grid against the chart's own triangles); the stitched sides of a coarser neighbour and the
/// two-sided Hausdorff add to it, so the target sits below the 0.1% of the diagonal meant for the
/// finest level (a pixel in a 1,000-pixel view of the whole mesh).
constexpr double kDefaultErrorTarget = 7e-4;

struct GeometryImageOptions
{
  /// The error rule's goal, as a fraction of the input's bounding-box diagonal: a chart rises
  /// while its levelError at its current level is above errorTarget * diagonal (and it is
  /// below maxLevel and the budget allows), and no further. 0: no goal, the budget alone.
  double errorTarget = kDefaultErrorTarget;
  /// Total samples over all charts at their finest level, (2^d + 1)(2^d + 2) / 2 per chart.
  /// 0: with an errorTarget, as many as the target needs (up to what the measuring may hold,
  /// 4^kErrorRuleLevelsAbove times the input's points); without one, as many as the input has
  /// points. A budget below #charts samples at minLevel is an error; with 0 the charts simply
  /// stay at minLevel then.
  int64_t sampleBudget = 0;
  int32_t minLevel = 2; ///< smallest d_max of a chart (0 .. maxLevel)
  int32_t maxLevel = 8; ///< largest d_max of a chart (at most 12: 4097 samples per side)
  /// Weight of |mean curvature| * diagonal in the curvature-weighted area (0: area only); it
  /// also sets the error rule's caps, through the area rule's levels.
  double curvatureWeight = 1.0;
  LevelRule levelRule = LevelRule::Error; ///< how d_max is chosen under the budget
  /// Stretch-reducing passes over each chart's mean-value map (Yoshizawa, Belyaev and Seidel
  /// 2004), 0 .. 100; 0 keeps Floater's map alone. Each pass divides the weight of every
  /// neighbour j by the L2 stretch (Sander et al. 2001) around j and solves again; passes stop
  /// when the chart's L2 stretch no longer falls, and the lowest map is kept. Weights stay
  /// positive, so every map is a convex combination (no flip). A protrusion that the mean-value
  /// map shrinks to a speck of the triangle gets grid samples in proportion to its area instead.
  int32_t stretchIterations = 10;
  /// Fit the interior samples of every chart's finest level to the patch by least squares
  /// instead of interpolating the surface at them (see the file comment); side and corner
  /// samples, shared with the neighbours, stay on the paths.
  bool fitSamples = true;
};

/// A point array to resample into the atlas besides Position and Normal.
struct GeometryImageAttribute
{
  std::string name;           ///< not empty, not "Position" or "Normal", unique
  int32_t components = 1;     ///< 1 .. 64
  std::vector<double> values; ///< #V' x components over the points of PatchMesh::mesh
  /// #F' x 3 x components over the triangles of PatchMesh::mesh (tc::pieceCornerValues), or
  /// empty: where given, a sample takes the values of the triangles of its own chart, so that
  /// the two charts of a side along a texture seam each keep their own texture coordinates.
  std::vector<double> cornerValues;
  /// Skin influences (tc::kSkinValues components: 4 joint ids, then their 4 weights;
  /// tc::PointSkin): a sample between points takes tc::blendInfluences of theirs (the union of
  /// their joints, weights interpolated, the 4 largest kept) instead of a linear blend, which
  /// would blend joint ids. No corner values.
  bool influences = false;
};

/// The parameterization of one patch onto the right triangle.
struct PatchParameterization
{
  std::vector<int32_t> points;        ///< #Vp points of PatchMesh::mesh in the patch, ascending
  std::vector<double> uv;             ///< #Vp x 2 parameter of each point in the right triangle
  std::vector<int32_t> triangles;     ///< #Fp x 3 indices into `points`, counter-clockwise
  std::vector<int32_t> meshTriangles; ///< #Fp triangle of PatchMesh::mesh of each
  int64_t boundaryPoints = 0;         ///< points on the three paths (fixed by arc length)
  int64_t flippedTriangles = 0;       ///< triangles with negative signed uv area
  /// Triangles with zero uv area: all three corners on one side of the triangle, which happens
  /// when a patch triangle has all its corners on one path (Floater's theorem needs no such
  /// triangle for a strict embedding; these are flattened onto the side, never flipped).
  int64_t degenerateTriangles = 0;
  double meanValueStretch = 0.0; ///< L2 stretch of Floater's mean-value map
  double stretch = 0.0;          ///< L2 stretch of the map kept
  int32_t stretchIterations = 0; ///< stretch-reducing passes that lowered it
};

/// Parameterizes patch `patch` (= base face) alone: corner k of the base face at (0,0), (1,0),
/// (0,1) for k = 0, 1, 2, each path fixed on its side by arc length, the interior by Floater's
/// mean-value coordinates (one sparse LU solve), then options.stretchIterations stretch-reducing
/// passes (the other options are only checked).
/// @throws InputError when the arrays do not match, or the patch is not a disk bounded by the
///         three paths of its sides (the message names the patch)
PatchParameterization parameterizePatch(const PatchMesh& patches, const BaseComplexResult& base,
  int32_t patch, const GeometryImageOptions& options = {});

/// Builds the atlas of triangular geometry images.
/// @param[in] patches        the input split into patches along the traced paths
/// @param[in] base           baseVertices, baseTriangles and baseEdgeIsFeature (may be empty: no
///                           feature) of the base complex the paths were traced from
/// @param[in] normals        #V' x 3 unit normals over the points of patches.mesh, or empty:
///                           angle-weighted vertex normals of patches.mesh
/// @param[in] meanCurvature  #V' mean curvature, or empty: d_max from the area alone
/// @param[in] extra          further point arrays to resample (attributes 2, 3, ... in order)
/// @return attributes Position, Normal, then `extra`; one chart per base face; inputPoints =
///         points with inputPointId >= 0, inputTriangles = largest inputTriangle + 1,
///         inputDiagonal = bounding-box diagonal of those points; `source` left empty.
///         levelError[d] of a chart is the largest distance between a patch point and the point
///         of the level-d grid at the same (u, v) (the grid triangle containing its parameter,
///         interpolated linearly), also taken where a crease edge inside the patch (its
///         triangles at more than 45 degrees) crosses a grid line: an upper bound of the
///         distance from the patch's points and creases to the level-d surface.
/// @throws InputError for arrays that do not match, a patch that is not a disk bounded by its
///         paths, bad options or a sampleBudget too small for minLevel
Atlas buildGeometryImages(const PatchMesh& patches, const BaseComplexResult& base,
  const std::vector<double>& normals, const std::vector<double>& meanCurvature,
  const std::vector<GeometryImageAttribute>& extra, const GeometryImageOptions& options = {},
  const Progress& progress = {});
} // namespace tc
