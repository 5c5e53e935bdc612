// SPDX-License-Identifier: BSD-3-Clause
/// @file refinement_band.h
/// The band of Feng et al. 2010, section 4.2: the faces nearest to the cluster boundaries, whose
/// clusters the minimum cuts (eq. 4) may change, each with the pair of clusters of its nearest
/// boundary.
#pragma once

#include "features/face_adjacency.h"

#include "tc/common/mesh_topology.h"
#include "tc/common/progress.h"

#include <cstdint>
#include <vector>

namespace tc
{
namespace detail
{
namespace refinement
{
/// Keys of unordered pairs of clusters a < b, key = a * numClusters + b: sorting the keys
/// sorts the pairs by a, then b.
struct ClusterPairs
{
  int64_t numClusters = 0;
  int64_t key(int32_t a, int32_t b) const { return static_cast<int64_t>(a) * numClusters + b; }
  int32_t first(int64_t key) const { return static_cast<int32_t>(key / numClusters); }
  int32_t second(int64_t key) const { return static_cast<int32_t>(key % numClusters); }
};

/// @return #E 1 where the labels of an edge's faces differ (mesh-boundary edges never do)
std::vector<uint8_t> boundaryEdges(const EdgeTable& edges, const std::vector<int32_t>& label);

/// The band, and for each band face the pair of clusters (index into the sorted pair keys)
/// whose boundary is nearest to it.
struct Band
{
  std::vector<int32_t> pair;     ///< #F nearest boundary pair of a band face, -1 outside the band
  std::vector<int64_t> pairKeys; ///< #P sorted ClusterPairs keys of the clusters that meet
  int64_t size = 0;              ///< faces in the band
};

/// How far the band reaches.
struct BandExtent
{
  double fraction = 0.1;        ///< of all faces, those nearest to a boundary
  int rings = 0;                ///< and every face this many dual steps from a boundary
  const Band* within = nullptr; ///< if set: the faces of that band only, however many
};

/// The ceil(fraction #F) faces nearest to a boundary by dual path length (face centroid to
/// centroid, multi-source Dijkstra from the faces that touch a boundary), and always the faces
/// within `rings` steps of those; a face at a junction takes the smallest pair among its
/// boundary edges.
/// @param[in] dual        buildFaceAdjacency() of the mesh
/// @param[in] centroids   #F x 3 face centroids
/// @param[in] label       #F compact cluster ids
/// @param[in] isBoundary  #E boundaryEdges(edges, label)
Band buildBand(const EdgeTable& edges, const FaceAdjacency& dual,
  const std::vector<double>& centroids, const std::vector<int32_t>& label,
  const ClusterPairs& pairs, const std::vector<uint8_t>& isBoundary, const BandExtent& extent,
  const Progress& progress);
} // namespace refinement
} // namespace detail
} // namespace tc
