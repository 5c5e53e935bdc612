// SPDX-License-Identifier: BSD-3-Clause
/// @file component_selection.h
/// Step 9 of tcMeshPreparation (internal): which edge-connected components to drop (Moebius-like
/// ones, small ones, all but the largest), and dropping components from a mesh (also the
/// fragments that hole filling cannot close).
///
/// Written over the preparation's own component numbering rather than with CGAL's
/// keep_largest_connected_components / remove_connected_components: those need a
/// Surface_mesh, which cannot hold the meshes this step is for (a non-orientable component, or
/// a non-manifold edge that was not split, makes Surface_mesh::add_face fail).
#pragma once

#include "prep/orientation.h"

#include "tc/common/mesh.h"
#include "tc/prep/mesh_preparation.h"

#include <cstdint>
#include <vector>

namespace tc
{
namespace detail
{
/// #components: the number of triangles of each component.
std::vector<int64_t> componentTriangles(
  const std::vector<int32_t>& componentId, int64_t numComponents);

/// The largest component (the lowest-numbered of equal ones); -1 when there is none.
int32_t largestComponent(const std::vector<int64_t>& triangles);

/// The report's nonOrientableTriangles, largestComponentTriangles and largestComponentClosed.
void describeComponents(
  const std::vector<int32_t>& componentId, const ComponentKinds& kinds, PreparationReport& report);

/// The components the options keep (1) or drop (0), each dropped one counted in the report
/// (droppedNonOrientable..., droppedSmall..., droppedMinor...) under the first rule that drops
/// it: non-orientable, fewer than minComponentTriangles, not the largest (of those left).
///
/// @throws tc::InputError  when no component is left, saying how many each rule dropped
std::vector<uint8_t> selectComponents(const std::vector<int32_t>& componentId,
  const ComponentKinds& kinds, const PreparationOptions& options, PreparationReport& report);

struct ComponentRemoval
{
  std::vector<int32_t> keptPoints;    ///< #V' old index of every point kept, ascending
  std::vector<int32_t> keptTriangles; ///< #F' old index of every triangle kept, ascending
  int64_t droppedPoints = 0;          ///< points only the dropped components used
};

/// Drops the triangles of the components whose `keep` is 0 and the points only they use; the
/// rest keep their order.
///
/// @param[in,out] mesh  #V points, #F triangles
/// @param[in] componentId  #F component of every triangle, 0 .. #keep - 1
ComponentRemoval keepComponents(
  TriMesh& mesh, const std::vector<int32_t>& componentId, const std::vector<uint8_t>& keep);
} // namespace detail
} // namespace tc
