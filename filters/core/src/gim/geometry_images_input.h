// SPDX-License-Identifier: BSD-3-Clause
/// @file geometry_images_input.h
/// Private to buildGeometryImages (tc/gim/geometry_images.h): the checks of its options and
/// arrays, and the checked input laid out by patch and by base edge, which every step reads.
#pragma once

#include "tc/gim/geometry_images.h"

#include <cstdint>
#include <string>
#include <vector>

namespace tc::detail::geometry_images
{
constexpr int32_t kMaxLevelLimit = 12; ///< largest maxLevel: 4097 samples per side
constexpr int32_t kMaxComponents = 64; ///< of an extra attribute
constexpr int32_t kMaxStretchIterations = 100;

/// Prefix of every error message of the stage.
inline const std::string kWhere = "geometry images: ";

inline std::string num(int64_t v)
{
  return std::to_string(v);
}

/// The checked input, with triangles grouped by patch and each base edge's two charts.
struct Layout
{
  int64_t numPoints = 0;
  int32_t numCharts = 0;
  int32_t numEdges = 0;
  std::vector<int64_t> patchOffsets;   ///< #Fb + 1
  std::vector<int32_t> patchTriangles; ///< triangle ids grouped by patch
  std::vector<int32_t> edgeChart;      ///< #Eb x 2: the two base faces of each base edge
  std::vector<int32_t> edgeSide;       ///< #Eb x 2: the side of that face
  std::vector<uint8_t> edgeFeature;    ///< #Eb: 1 when either face flags the side as a feature
};

/// Refuses options out of range, saying which and what is allowed.
/// @throws InputError
void checkOptions(const GeometryImageOptions& options);

/// Checks the patch mesh, the base complex and the paths against each other (the message names
/// the first array, triangle, edge or patch that fails) and lays them out.
/// @throws InputError
Layout checkInput(const PatchMesh& pm, const BaseComplexResult& base);

/// Checks the optional per-point normals (#V' x 3) and mean curvature (#V').
/// @throws InputError
void checkPointArrays(
  const Layout& L, const std::vector<double>& normals, const std::vector<double>& meanCurvature);

/// Checks the extra attributes: named, unique, 1 .. kMaxComponents components, #V' x components
/// finite values each.
/// @throws InputError
void checkExtraAttributes(
  const std::vector<GeometryImageAttribute>& extra, int64_t numPoints, int64_t numTriangles);

/// Whether side k of base face c runs along its base edge's path (lower base vertex first).
inline bool sideRunsForward(
  const PatchMesh& pm, const BaseComplexResult& base, int32_t c, int32_t k)
{
  const int32_t e = pm.faceEdges[3 * c + k];
  return base.baseTriangles[3 * c + k] == pm.baseEdges[2 * e];
}

/// Path of side k of chart c in the side's direction (corner k to corner k + 1).
std::vector<int32_t> sidePath(
  const PatchMesh& pm, const BaseComplexResult& base, int32_t c, int32_t k);

/// Per base vertex: 1 where a feature side ends (a base vertex on a feature curve).
std::vector<uint8_t> featureVertices(const PatchMesh& pm, const Layout& L, size_t numBaseVertices);

/// The topology of the chart table: every chart's corner vertices (input point ids), the chart
/// and side across each of its sides, and which sides follow a feature curve.
std::vector<AtlasChart> chartTable(
  const PatchMesh& pm, const BaseComplexResult& base, const Layout& L);
} // namespace tc::detail::geometry_images
