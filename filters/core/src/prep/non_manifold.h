// SPDX-License-Identifier: BSD-3-Clause
/// @file non_manifold.h
/// Steps 6 and 7 of tcMeshPreparation (internal): finding non-manifold edges and vertices, and
/// (opt-in) splitting them by duplicating vertices.
#pragma once

#include "tc/common/mesh_topology.h"
#include "tc/prep/mesh_preparation.h"

#include <cstdint>
#include <vector>

namespace tc
{
namespace detail
{
/// Flags non-manifold edges (more than 2 faces) and vertices (faces around it form more than
/// one fan, fans being joined across edges with exactly 2 faces) and counts them.
/// @param[in] tri  #F x 3 triangles over numVertices vertices
/// @param[out] result  nonManifoldEdge (#F), nonManifoldVertex (#V) and the two report counts
void findNonManifold(const std::vector<int32_t>& tri, const EdgeTable& edges, int32_t numVertices,
  PreparationResult& result);

/// Makes the mesh manifold by duplicating vertices. Sides stay glued across edges with 2 faces
/// and, on a non-manifold edge, for the first two consistent faces (or the first two, if none
/// are); every other side there is cut. Each fan of corners joined through glued sides becomes
/// one vertex, the fan of the lowest corner keeping the original vertex; copies are appended
/// (with the inputPointId and nonManifoldVertex of their original in `result`).
/// A cut face can still lie on its edge's other faces when its fans wrap around to them; it is
/// then cut away at one end (one more glued side through that corner is cut) and the fans are
/// found again. Cutting only splits fans, so this ends (after 1 or 2 rounds in practice).
/// @param[in,out] tri    #F x 3 triangles, renumbered
/// @param[in,out] edges  rebuilt for the new triangles
/// @return  the number of vertices, copies included
int32_t splitNonManifold(
  std::vector<int32_t>& tri, EdgeTable& edges, int32_t numVertices, PreparationResult& result);
} // namespace detail
} // namespace tc
