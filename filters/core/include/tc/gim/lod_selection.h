// SPDX-License-Identifier: BSD-3-Clause
/// @file lod_selection.h
/// Per-frame level-of-detail selection for an atlas of triangular geometry images (Feng et al.
/// 2010, section 6.1), and the draw list that groups the chosen (instance, chart) pairs by level
/// for the renderer. Plain arrays in, plain arrays out: no VTK, no GPU.
///
/// Every chart carries an oriented bounding box: pivot c0 and the axes a_k = c_k - c0 (k = 1, 2,
/// 3) to its three adjacent corners; the box's corners are c0 + s1 a1 + s2 a2 + s3 a3, s_k in
/// {0, 1}. Given the view (a 4 x 4 world-to-clip matrix M and the viewport in pixels), a chart's
/// level is chosen as follows, the first rule that applies winning:
///
/// 1. Culling (LodOptions::cull): the box lies wholly outside one of the six clip planes
///    -w <= x <= w, -w <= y <= w, -w <= z <= w (i.e. w + x < 0 at all 8 corners, or w - x < 0,
///    ...). A linear function g of the homogeneous corner takes its largest value over the box at
///    g(M c0) + sum_k max(0, g(M a_k)) (M a_k: the linear part, w row included), so 6 sums decide
///    it instead of 48 tests. Level -1. Conservative: a box beyond a corner of the frustum that
///    is not wholly outside any one plane is kept.
/// 2. Near the eye: some corner has w <= kLodNearEpsilon * (|w(c0)| + sum_k |w(a_k)|), i.e.
///    w(c0) + sum_k min(0, w(a_k)) is at most that. The box touches or straddles the eye plane,
///    where its projection is unbounded (or meaningless behind the eye): level maxLevel. The
///    threshold is relative to the box's own extent in w so that it does not depend on the
///    scene's units. With culling off, a box wholly behind the eye also lands here.
/// 3. Degenerate box (worldArea == 0, e.g. a chart without a box): level 0.
/// 4. Eq. (6): the projected area of the box in pixels^2,
///      A = sum_{i > k} |(ĉ_i - ĉ_0) x (ĉ_k - ĉ_0)|,
///    with ĉ_i = (x / w * width / 2, y / w * height / 2) of M c_i (x 2D cross product). The
///    three terms are the areas of the parallelograms of three adjacent faces, the faces a viewer
///    can see at once. Projection is linear in homogeneous coordinates, so M c_k = M c0 + M a_k,
///    and ĉ_k - ĉ_0 = (x_a w_0 - x_0 w_a) / (w_0 w_k) (per screen axis), which avoids
///    subtracting two nearby projected points.
///    - Area mode, eq. (7) with min for the paper's max (the level can only be limited by
///      maxLevel from above): alpha A_0 = 4^maxLevel with A_0 = width * height, so
///        d = floor(maxLevel + log4(A / (width * height)) + bias + 0.5), clamped to [0, maxLevel]:
///      a box that fills the viewport gets maxLevel, each quarter of that area one level less, so
///      that the ratio of triangles to covered pixels stays about constant.
///    - Error mode (LodOptions::errorPixels > 0, for charts whose levelError is measured):
///      s = sqrt(A / worldArea) pixels per world unit (worldArea is eq. (6) on the unprojected
///      axes, so s is the box's average magnification), and d = the smallest level with
///      levelError[d] * s <= errorPixels (maxLevel when none), then d + round(bias) (half away
///      from zero), clamped to [0, maxLevel]. Charts whose levelError is not measured use the
///      area mode.
///
/// Precision: everything is evaluated in float; the level agrees with an evaluation in double
/// except where the continuous level (or levelError[d] * s against errorPixels, or a corner
/// against a clip plane) is within about 1e-4 of a boundary.
///
/// Cost: O(#C) per call with a few dozen float operations per chart, branch-free, in blocks
/// that the compiler vectorizes and that run in parallel (tc::parallel_for) for large #C.
#pragma once

#include "tc/gim/atlas.h"

#include <array>
#include <cstdint>
#include <vector>

namespace tc
{
/// Relative threshold of the near-eye rule (rule 2 above).
constexpr float kLodNearEpsilon = 1e-5f;

/// Largest level the draw list's packed levels can hold (4 bits each).
constexpr int32_t kLodMaxLevel = 15;

/// What LOD selection reads per chart, structure of arrays in float for speed.
struct LodCharts
{
  std::vector<float> box; ///< #C x 12: c0 xyz, then axes a1, a2, a3 (corner_k - c0) xyz
  /// #C: eq. 6 on the unprojected axes: |a1 x a2| + |a1 x a3| + |a2 x a3|
  std::vector<float> worldArea;
  std::vector<int32_t> maxLevel; ///< #C
  /// #C x stride: chart's levelError[d] for d <= maxLevel, else +inf; all +inf when not measured
  std::vector<float> levelError;
  int32_t stride = 0;            ///< max maxLevel + 1
  std::vector<int32_t> neighbor; ///< #C x 3: neighborChart (-1 none)

  /// Number of charts #C.
  int32_t size() const { return static_cast<int32_t>(maxLevel.size()); }

  /// The arrays of an atlas's charts: the box's corners become c0 and the axes c_k - c0 (taken
  /// in double, then rounded), worldArea is computed in double.
  /// @throws InputError for a chart whose maxLevel is outside [0, kLodMaxLevel], whose
  ///         levelError is neither empty nor maxLevel + 1 long, or whose neighbour is not a chart
  static LodCharts fromAtlas(const Atlas& atlas);
};

struct LodView
{
  /// row-major 4x4; clip = M * (x, y, z, 1) (OpenGL clip space, column vectors)
  std::array<double, 16> worldToClip{};
  double width = 0, height = 0; ///< viewport in pixels
};

struct LodOptions
{
  double bias = 0.0; ///< levels added to the chosen level (positive: finer)
  /// > 0: screen-space error mode, the coarsest level within this many pixels (the default, 1,
  /// is a faithful picture for a user who changes nothing); 0: the paper's area rule (eq. 7)
  double errorPixels = 1.0;
  bool cull = true; ///< charts whose box lies wholly outside the view frustum get level -1
};

/// Levels of every chart for one instance: levels[c] in [0, maxLevel[c]], or -1 when culled.
/// Allocates nothing; runs in parallel over blocks of charts when #C is large.
/// @param[out] levels  #C
/// @throws InputError when the arrays of `charts` disagree in size or the viewport is empty
void selectLevels(
  const LodCharts& charts, const LodView& view, const LodOptions& options, int32_t* levels);

/// selectLevels with the boxes (#C x 12, LodCharts::box's layout) and world areas (#C) read from
/// `box` and `worldArea` instead of charts.box and charts.worldArea: the posed boxes of a skinned
/// instance (tc::poseLodBoxes), which change every frame while the rest of `charts` does not.
void selectLevels(const LodCharts& charts, const float* box, const float* worldArea,
  const LodView& view, const LodOptions& options, int32_t* levels);

/// The draw list: one entry per drawn (instance, chart), grouped by level.
///
/// Cell ids (what a picking pass writes for a drawn triangle): the triangles of the frame are
/// numbered instance by instance, chart by chart within an instance, and in grid order within a
/// chart (tc::rebuildMesh's order before stitching drops any), so that an entry's triangles are
/// the ids [first, first + 4^level). Ids go up to triangles - 1 and are kept below 2^31 (the
/// shader's int): an entry whose ids would pass INT32_MAX gets first = -1 (not pickable).
struct LodDrawList
{
  std::vector<int32_t> entries; ///< 4 ints per entry: chart, instance, packed levels, first id
  /// stride + 1: entries of level d are [levelStart[d], levelStart[d+1])
  std::vector<int64_t> levelStart;
  std::vector<int64_t> chartsPerLevel; ///< stride
  int64_t triangles = 0;               ///< sum over entries of 4^level (grid triangles issued)
};

/// Sorts the drawn charts of every instance by level (counting sort, O(instances * #C), stable:
/// within a level, entries follow instance, then chart). The list's vectors are reused, so a
/// list kept from frame to frame stops allocating once it has seen its largest frame.
///
/// levels: instances x #C (row per instance, as selectLevels writes them). Packed levels =
/// n | m0 << 4 | m1 << 8 | m2 << 12 with n the chart's level and m_k the level of the chart
/// across side k in the same instance: the four integers of the stitching rule of eq. (8)
/// (geometry_image_mesh.h). A neighbour that is absent (-1) or culled counts as level n (no
/// stitching on that side).
/// @throws InputError for a level outside [-1, maxLevel] of its chart, inconsistent arrays or a
///         neighbour id that is not a chart
void buildDrawList(
  const LodCharts& charts, const int32_t* levels, int32_t instances, LodDrawList& list);

/// A triangle of the draw list: its instance, chart, the chart's level and the triangle's index
/// in the chart's level-`level` grid (0 .. 4^level - 1, grid order). All -1 when not found.
struct LodTriangle
{
  int32_t instance = -1;
  int32_t chart = -1;
  int32_t level = -1;
  int64_t triangle = -1;
};

/// The triangle of cell id `cell` (LodDrawList above), or all -1 when no entry holds it.
/// O(levels x log(entries)): a binary search per level, whose entries ascend in first id.
LodTriangle locateTriangle(const LodDrawList& list, int64_t cell);

/// Axis-aligned bounds (xmin, xmax, ymin, ymax, zmin, zmax) of every sample the charts draw at
/// their finest level, transformed by each of the `instances` row-major 4 x 4 matrices (model to
/// actor coordinates; affine, the last row ignored). Coarser levels draw a subset of these
/// samples (the atlas's dyadic invariant) and stitching moves vertices onto samples, so every
/// level's surface lies inside, and the finest one touches every side: the bounds are exact,
/// unlike the union of the oriented boxes (which LOD selection and culling use). Each bound is
/// the extreme of the transformed samples evaluated in double, the same value a loop over the
/// samples gives; an instance whose 3 x 3 part has one nonzero per row (a translation, scale or
/// axis permutation) is bounded from the model bounds without that loop.
/// Cost: O(S) for S samples, plus O(S) per instance that is turned off the axes.
/// @param[in] instances  #instances x 16
/// @return (1, -1, 1, -1, 1, -1) (empty) when there are no charts or no instances
/// @throws InputError when the atlas's layout is invalid (validateAtlasLayout)
std::array<double, 6> drawnBounds(const Atlas& atlas, const std::vector<double>& instances);
} // namespace tc
