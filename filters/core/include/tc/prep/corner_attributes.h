// SPDX-License-Identifier: BSD-3-Clause
/// @file corner_attributes.h
/// Attributes that are not functions of the surface point: texture coordinates across a UV seam
/// (and colours across a colour seam) take two values at one position. A file stores a seam by
/// duplicating the vertex; tc::prepareMesh merges the copies, because every later stage needs
/// one connected surface. These helpers keep, per triangle corner, the value of the copy the
/// corner used, and mark the triangle sides along which the values jump, so that the feature
/// stage can make them chart sides and the geometry images can sample each side from its own
/// triangles.
#pragma once

#include "tc/common/mesh.h"
#include "tc/prep/mesh_preparation.h"

#include <cstdint>
#include <string>
#include <vector>

namespace tc
{
/// Values of one attribute at every triangle corner.
struct CornerAttribute
{
  std::string name;           ///< the point array's name
  int32_t components = 1;     ///< 1 .. 64
  std::vector<double> values; ///< #F x 3 x components, corner k of triangle f at (3 f + k)
};

/// The soup point each corner of each output triangle of `result` used: the point of the
/// triangle's input polygon nearest to the corner's output point (the same point unless the
/// merge joined copies). -1 for corners of hole-filling triangles.
/// @return #Fout x 3 soup point ids
std::vector<int64_t> cornerInputPoints(const PolygonSoup& soup, const PreparationResult& result);

/// True if the point values `pointValues` (#Vsoup x components) differ at the two ends of some
/// corner of `corners` whose soup point is not the one result.inputPointId kept for it: i.e.
/// the merge made this attribute discontinuous and it needs its corner values.
bool mergeSplitsAttribute(const std::vector<double>& pointValues, int32_t components,
  const std::vector<int64_t>& corners, const PreparationResult& result);

/// The corner values of an attribute: pointValues of each corner's soup point (`corners`, from
/// cornerInputPoints), the kept point's value for hole-filling corners.
CornerAttribute makeCornerAttribute(const std::string& name, const std::vector<double>& pointValues,
  int32_t components, const std::vector<int64_t>& corners, const PreparationResult& result);

/// Seam sides: bit k of entry f is set when side k (corner k to corner k + 1) of triangle f is
/// shared with exactly one other triangle and some attribute takes different values on the two
/// triangles at both ends of the side. A side whose values differ at one end only (the fan of
/// copies at the pole of a UV sphere) is no seam: its grid triangles touch the seam at a point.
/// @param[in] triangles  #F x 3 vertex ids
/// @return #F bit masks (0 .. 7)
std::vector<uint8_t> seamSides(
  const std::vector<int32_t>& triangles, const std::vector<CornerAttribute>& attributes);
} // namespace tc
