// SPDX-License-Identifier: BSD-3-Clause
/// @file polyline_chains.h
/// Segments joined into non-branching polylines at the nodes they share: the crest lines of
/// section 4.2 of Feng et al. 2010 (nodes: crest points on mesh edges) and its feature-line
/// segments (nodes: mesh vertices on the refined cluster boundaries) follow the same rule.
#pragma once

#include <cstdint>
#include <vector>

namespace tc
{
namespace detail
{
/// Polylines as node sequences; a closed one repeats its first node.
struct Polylines
{
  std::vector<int64_t> offsets{ 0 }; ///< #L + 1 offsets into nodes
  std::vector<int64_t> nodes;
};

/// Chains segments into polylines that break at every node with other than 2 segments (ends,
/// branchings): first the paths out of such nodes, in node order and, at a node, in segment
/// order; then the closed loops that remain, each started at the first node of its lowest
/// segment. Every segment is used once; the output is deterministic.
/// @param[in] segmentNodes  #S x 2 node ids of each segment (two different nodes)
/// @param[in] numNodes      node ids are in [0, numNodes)
Polylines chainSegments(const std::vector<int64_t>& segmentNodes, int64_t numNodes);
} // namespace detail
} // namespace tc
