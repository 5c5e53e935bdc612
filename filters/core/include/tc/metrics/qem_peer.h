// SPDX-License-Identifier: BSD-3-Clause
/// @file qem_peer.h
/// The peer every error curve is compared with: meshoptimizer's meshopt_simplify, the quadric
/// simplifier a game engine's discrete LOD chain (gltfpack) is made with.
#pragma once

#include "tc/common/mesh.h"

#include <cstdint>

namespace tc
{
/// meshoptimizer's quadric simplification of `mesh` to at most `targetTriangles` triangles,
/// returned as a mesh of the vertices it still uses; `mesh` itself for a target at or above its
/// count (meshopt_simplify requires a target no larger than its input). Only the count stops
/// it (no error bound).
/// @throws InputError for a negative target or a mesh of more than 2^32 - 1 indices
TriMesh simplifyQem(const TriMesh& mesh, int64_t targetTriangles);
} // namespace tc
