// SPDX-License-Identifier: BSD-3-Clause
/// @file orientation.h
/// Step 8 of tcMeshPreparation (internal): components, consistent orientation, outward facing.
#pragma once

#include "tc/common/mesh_topology.h"
#include "tc/prep/mesh_preparation.h"

#include <cstdint>
#include <vector>

namespace tc
{
namespace detail
{
/// Components (across every shared edge) and orientation patches (across edges with exactly
/// 2 faces), numbered from their lowest face. Within a patch that lowest face keeps its
/// orientation; a patch where two paths disagree cannot be oriented and is left as it is.
/// A closed, oriented component then faces outward when its signed volume is positive.
/// Union-find over the edges in order rather than a breadth-first search over faces: it visits
/// memory in order, and gives the same result (the orientation of an orientable patch relative
/// to its first face is unique).
///
/// What orientComponents found of each component (numbered as result.componentId).
struct ComponentKinds
{
  std::vector<uint8_t> closed;        ///< 1: no edge of it has other than 2 faces
  std::vector<uint8_t> nonOrientable; ///< 1: a patch of it cannot be oriented
};

/// @param[in] orient  flip the faces (else only count and number)
/// @param[in] edges   edge table of result.mesh.triangles
/// @param[in,out] result  mesh.triangles flipped; componentId (#F) and the report's
///   components, closedComponents, nonOrientableComponents and flippedFaces (added to) set
/// @return what each component is
ComponentKinds orientComponents(bool orient, const EdgeTable& edges, PreparationResult& result);
} // namespace detail
} // namespace tc
