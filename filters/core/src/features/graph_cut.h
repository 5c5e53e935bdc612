// SPDX-License-Identifier: BSD-3-Clause
/// @file graph_cut.h
/// The minimum s-t cuts of Feng et al. 2010, section 4.2 (after Katz and Tal 2003), that move
/// the cluster boundaries inside the band onto short paths of high curvature: the capacities of
/// eq. 4 on the dual graph, and one Boykov-Kolmogorov max-flow for every pair of clusters.
#pragma once

#include "features/face_adjacency.h"
#include "features/refinement_band.h"

#include "tc/common/mesh.h"
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
/// Eq. 4 for every entry of the dual graph: g(i, j) = beta |e_ij| exp(-(|k_i| + |k_j|) /
/// sigma_k), beta = crestBeta where a crest line runs along the shared edge (both its ends next
/// to a crest), times exp(-dihedralWeight theta_ij / sigma_theta) (see
/// FeatureRefinementOptions::dihedralWeight).
/// @param[in] dihedral  #E edgeDihedrals(), needed only when dihedralWeight > 0
/// @return one capacity per entry of `dual`
std::vector<double> dualCapacity(const TriMesh& mesh, const EdgeTable& edges,
  const FaceAdjacency& dual, const std::vector<double>& faceMeanCurvature,
  const std::vector<uint8_t>& crestVertex, const std::vector<double>& dihedral,
  const FeatureRefinementOptions& options, const Progress& progress);

/// Minimum s-t cuts for every pair of adjacent clusters at once. The band faces nearest to the
/// boundary of clusters (a, b) that belong to a or b are the free nodes of that pair; their
/// neighbours outside (faces of a just beyond the band or in the band of another pair) are
/// contracted into the source, those of b into the sink, faces of other clusters are left out.
/// The regions of different pairs share no free node and no n-link, so one max-flow over their
/// disjoint union solves every pair's cut. A free node in neither search tree keeps its
/// cluster; if a cluster would lose all its faces, the cuts of its pairs are undone.
/// @param[in]     capacity  dualCapacity()
/// @param[in,out] label     #F compact cluster ids
/// @return the number of faces relabelled
int64_t cutBand(const FaceAdjacency& dual, const std::vector<double>& capacity, const Band& band,
  const ClusterPairs& pairs, std::vector<int32_t>& label, const Progress& progress);
} // namespace refinement
} // namespace detail
} // namespace tc
