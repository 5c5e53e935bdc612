// SPDX-License-Identifier: BSD-3-Clause
/// @file point_merging.h
/// Step 2 of tcMeshPreparation (internal): the groups of duplicate points, before triangulation
/// so that every polygon sees merged corners.
#pragma once

#include "tc/common/mesh.h"

#include <array>
#include <cstdint>
#include <vector>

namespace tc
{
namespace detail
{
/// Representative of every used point: the lowest id of its group of duplicates. Exact
/// duplicates (tolerance <= 0) are found by hashing; with a tolerance, points are visited in id
/// order and join the lowest-id representative within the tolerance (found in a grid of
/// cells), else become one.
///
/// @param[in] soup       validated polygon soup, #V points
/// @param[in] used       #V: 1 for a point some polygon uses (unused points represent themselves)
/// @param[in] low        lowest corner of the bounding box of the used points
/// @param[in] diagonal   diagonal of that box
/// @param[in] tolerance  merge distance, in the units of the points
/// @return  #V representative ids
std::vector<int32_t> mergePoints(const PolygonSoup& soup, const std::vector<uint8_t>& used,
  const std::array<double, 3>& low, double diagonal, double tolerance);
} // namespace detail
} // namespace tc
