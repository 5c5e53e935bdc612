// SPDX-License-Identifier: BSD-3-Clause
/// @file report_text.h
/// The wording of the mesh preparation's counts and errors (internal), one home for each noun
/// so that the report, the repair hints and the errors say the same thing.
#pragma once

#include "tc/common/errors.h"
#include "tc/prep/mesh_preparation.h"

#include <cstdint>
#include <string>

namespace tc
{
namespace detail
{
/// A noun in the singular and the plural.
struct Noun
{
  const char* one;
  const char* many;
};

/// n and the noun for it: counted(1, kHole) is "1 hole", counted(3, kHole) "3 holes".
std::string counted(int64_t n, const Noun& noun);

/// The nouns more than one message uses.
constexpr Noun kDegenerateFace{ "degenerate face", "degenerate faces" };
constexpr Noun kNonManifoldEdge{ "non-manifold edge", "non-manifold edges" };
constexpr Noun kNonManifoldVertex{ "non-manifold vertex", "non-manifold vertices" };
constexpr Noun kNonOrientableComponent{ "non-orientable component", "non-orientable components" };
constexpr Noun kComponent{ "component", "components" };
constexpr Noun kBoundaryEdge{ "boundary edge", "boundary edges" };
constexpr Noun kHole{ "hole", "holes" };
constexpr Noun kPoint{ "point", "points" };
constexpr Noun kTriangle{ "triangle", "triangles" };
constexpr Noun kSliver{ "sliver", "slivers" };

/// The error for a CGAL repair (`repair`: "fill holes", "remove slivers") that found the mesh
/// not an oriented manifold: why (unsplit non-manifold elements, else non-orientable
/// components) and what to do (split them, or leave `option` off).
InputError notManifoldError(const PreparationReport& report, const PreparationOptions& options,
  const std::string& repair, const char* option);
} // namespace detail
} // namespace tc
