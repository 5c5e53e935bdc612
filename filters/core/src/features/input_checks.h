// SPDX-License-Identifier: BSD-3-Clause
/// @file input_checks.h
/// Input checks that every feature stage makes the same way, with the same advice.
#pragma once

#include "tc/common/errors.h"
#include "tc/common/mesh.h"

#include <cstdint>
#include <string>

namespace tc
{
namespace detail
{
/// @param[in] stage  the message's prefix, e.g. "computeCurvature: "
/// @throws InputError when a triangle references a vertex that the mesh does not have
inline void requireVertexIds(const TriMesh& mesh, const std::string& stage)
{
  const int64_t nv = mesh.numPoints();
  for (int32_t id : mesh.triangles)
  {
    if (id < 0 || id >= nv)
    {
      throw InputError(stage + "a triangle references vertex " + std::to_string(id) +
        " of a mesh with " + std::to_string(nv) + " vertices; fix the connectivity");
    }
  }
}
} // namespace detail
} // namespace tc
