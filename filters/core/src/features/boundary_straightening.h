// SPDX-License-Identifier: BSD-3-Clause
/// @file boundary_straightening.h
/// One-face zig-zags of refined cluster boundaries straightened (see
/// FeatureRefinementOptions::straightenLines): a cut runs along mesh edges, so a boundary
/// across the mesh's grain is a staircase, and each step is a sharp turn that the base complex
/// (Feng et al. 2010, section 5.1) keeps as a feature vertex.
#pragma once

#include "tc/common/mesh.h"
#include "tc/common/mesh_topology.h"

#include <cstdint>
#include <vector>

namespace tc
{
namespace detail
{
namespace refinement
{
/// A face whose two sides at vertex u are boundary edges to one other cluster, whose third side
/// (v, w) is not, and where u is on no other boundary edge, goes to that other cluster, so the
/// boundary runs v - w instead of v - u - w. Creases are kept: a step with a side of at least
/// creaseAngle moves only onto a third side at least as sharp. No cluster loses its last face.
/// Each change removes one boundary edge, so this ends; faces are visited in id order, pass
/// after pass, so the result does not depend on the thread count.
/// @param[in]     dihedral     #E edgeDihedrals()
/// @param[in]     creaseAngle  radians
/// @param[in,out] label        #F compact cluster ids in [0, numClusters)
/// @return the number of faces relabelled
int64_t straightenBoundaries(const TriMesh& mesh, const EdgeTable& edges,
  const std::vector<double>& dihedral, double creaseAngle, int64_t numClusters,
  std::vector<int32_t>& label);
} // namespace refinement
} // namespace detail
} // namespace tc
