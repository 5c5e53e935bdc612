// SPDX-License-Identifier: BSD-3-Clause
/// @file corners.h
/// Corners of Feng et al. 2010, section 4.2: the vertices of maximal |mean curvature| within an
/// N-ring, of which the top fraction is kept, and the junctions of feature lines.
#pragma once

#include "tc/common/mesh_topology.h"
#include "tc/common/progress.h"
#include "tc/features/feature_refinement.h"

#include <cstdint>
#include <vector>

namespace tc
{
namespace detail
{
namespace refinement
{
/// Vertices of the highest rank within cornerRings rings (rank = position in byCurvature, so
/// ties go to the smaller id), found by cornerRings min-dilations of the rank over the one-ring;
/// the top cornerFraction of them that reach result.curvatureThreshold; with junctionCorners
/// also every vertex where 3 or more edges of result's feature lines meet. Sets
/// result.cornerVertex and result.corners.
/// @param[in] byCurvature    the vertices that triangles use, by |H| descending, ties by id
/// @param[in] meanCurvature  #V mean curvature H
void findCorners(const EdgeTable& edges, const std::vector<int32_t>& byCurvature,
  const std::vector<double>& meanCurvature, const FeatureRefinementOptions& options,
  FeatureRefinementResult& result, const Progress& progress);
} // namespace refinement
} // namespace detail
} // namespace tc
