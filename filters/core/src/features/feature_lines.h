// SPDX-License-Identifier: BSD-3-Clause
/// @file feature_lines.h
/// Feature lines of Feng et al. 2010, section 4.2: the refined cluster boundaries broken into
/// non-branching segments, kept where the curvature along them is high.
#pragma once

#include "features/polyline_chains.h"

#include "tc/common/mesh.h"
#include "tc/common/mesh_topology.h"
#include "tc/features/feature_refinement.h"

#include <cstdint>
#include <vector>

namespace tc
{
namespace detail
{
namespace refinement
{
/// The boundary graph over mesh vertices broken at vertices with other than 2 boundary edges
/// (junctions of 3 or more boundaries, ends on the mesh border or at non-manifold spots); closed
/// loops without such a vertex are one segment each, started at their smallest edge. Paths go
/// out of each end vertex in edge-table order, so the output is deterministic.
/// @param[in] isBoundary  #E boundaryEdges()
/// @return segments as vertex paths
Polylines boundarySegments(
  const EdgeTable& edges, const std::vector<uint8_t>& isBoundary, int64_t nv);

/// Appends to result's lines the segments whose length-weighted mean |H| (each edge: its length
/// times the mean |H| of its ends, so the density of vertices does not matter) reaches
/// result.curvatureThreshold, and marks their vertices in result.featureVertex.
/// @param[in] meanCurvature  #V mean curvature H
void keepFeatureSegments(const TriMesh& mesh, const Polylines& segments,
  const std::vector<double>& meanCurvature, FeatureRefinementResult& result);

/// The length-weighted mean |H| of the path lines.nodes[begin, end) (each edge: its length times
/// the mean |H| of its ends); 0 for a path without length.
double meanCurvatureAlong(const TriMesh& mesh, const Polylines& lines, int64_t begin, int64_t end,
  const std::vector<double>& meanCurvature);

/// Appends the path lines.nodes[begin, end) to result's lines, with its meanCurvatureAlong, and
/// marks its vertices in result.featureVertex.
void appendLine(const TriMesh& mesh, const Polylines& lines, int64_t begin, int64_t end,
  const std::vector<double>& meanCurvature, FeatureRefinementResult& result);
} // namespace refinement
} // namespace detail
} // namespace tc
