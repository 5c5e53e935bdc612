// SPDX-License-Identifier: BSD-3-Clause
/// @file crease_lines.h
/// Crease and seam chains joined to the feature lines (an addition to Feng et al. 2010,
/// section 4.2): the cluster boundaries of the spectral clusters follow the creases of a mechanical
/// part only where a boundary happens to run along one, and a part has far more creases than a
/// fixed number of clusters has boundaries. The sharp edges themselves locate the creases exactly.
#pragma once

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
/// Appends to result's lines the crease chains: the manifold edges whose dihedral angle (the
/// angle between their faces' normals) is at least options.creaseLineAngle and that no kept
/// line holds, chained into non-branching paths that also break at the vertices of the kept
/// lines, so that a chain meets a line only at its ends. A chain is kept when it has at least
/// options.creaseLineEdges edges; its vertices are marked in result.featureVertex and its
/// lineCurvature is its length-weighted mean |H|. No-op when creaseLineAngle <= 0.
/// @param[in] dihedral       #E edgeDihedrals() in radians
/// @param[in] meanCurvature  #V mean curvature H
void addCreaseLines(const TriMesh& mesh, const EdgeTable& edges,
  const std::vector<double>& dihedral, const std::vector<double>& meanCurvature,
  const FeatureRefinementOptions& options, FeatureRefinementResult& result);
/// Appends to result's lines the seam chains: the manifold edges marked in
/// options.seamSides (tc::seamSides) that no kept line holds, chained and cut as the crease
/// chains are; every chain is kept, however short, since a texture seam inside a chart is wrong
/// at any length. No-op when options.seamSides is empty.
void addSeamLines(const TriMesh& mesh, const EdgeTable& edges,
  const std::vector<double>& meanCurvature, const FeatureRefinementOptions& options,
  FeatureRefinementResult& result);

/// Appends to result's lines the skin chains: the manifold edges between faces of different
/// options.skinRegions that no kept line holds, chained and cut as the seam chains are, every
/// chain kept. No-op when options.skinRegions is empty.
void addSkinLines(const TriMesh& mesh, const EdgeTable& edges,
  const std::vector<double>& meanCurvature, const FeatureRefinementOptions& options,
  FeatureRefinementResult& result);
} // namespace refinement
} // namespace detail
} // namespace tc
