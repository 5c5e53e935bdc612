// SPDX-License-Identifier: BSD-3-Clause
/// @file ear_clipping.h
/// Step 3 of tcMeshPreparation (internal): triangulation of one polygon by ear clipping in the
/// plane of its Newell normal.
#pragma once

#include "detail/geometry2d.h"

#include <cstdint>
#include <vector>

namespace tc
{
namespace detail
{
/// Scratch arrays reused for every polygon, so triangulating allocates only for the largest.
struct EarScratch
{
  std::vector<P2> uv;        ///< corners in the polygon's plane
  std::vector<int32_t> prev; ///< previous corner of the remaining polygon
  std::vector<int32_t> next; ///< next corner of the remaining polygon
};

/// Ear clipping of one polygon of m >= 4 distinct consecutive corners in the plane of its
/// Newell normal; robust to non-convex polygons. Appends m - 2 triangles with the polygon's
/// orientation. Self-intersecting polygons (no ear in a whole round) get the most convex corner
/// clipped so the loop always ends; a polygon with a zero Newell normal gets a fan.
///
/// Hand-written rather than CGAL::Polygon_mesh_processing::triangulate_faces, which needs a
/// valid polygon mesh (a raw soup, with non-manifold or badly oriented polygons, is not one),
/// and rather than triangulate_hole_polyline, which is cubic in the corner count and adds no
/// robustness for the planar-ish faces of real files.
///
/// @param[in] points      #V x 3 positions
/// @param[in] ids         m point ids, the polygon's corners in order
/// @param[in,out] triangles  3 (m - 2) point ids appended
void earClip(const double* points, const int32_t* ids, int32_t m, EarScratch& scratch,
  std::vector<int32_t>& triangles);
} // namespace detail
} // namespace tc
