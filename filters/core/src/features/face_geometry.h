// SPDX-License-Identifier: BSD-3-Clause
/// @file face_geometry.h
/// Per-face and per-edge measures shared by the feature stages (Feng et al. 2010, section 4.2):
/// centroids (the lengths of the dual graph), face normals (the Nystrom kernel, eq. 4's crease
/// factor, area-weighted vertex normals) and dihedral angles (creases). One definition, so that
/// every stage measures the same mesh the same way.
#pragma once

#include "tc/common/mesh.h"
#include "tc/common/mesh_topology.h"
#include "tc/common/progress.h"

#include <cmath>
#include <cstdint>
#include <vector>

namespace tc
{
namespace detail
{
/// |p_a - p_b|, the length of a mesh edge.
inline double vertexDistance(const TriMesh& mesh, int64_t a, int64_t b)
{
  const double dx = mesh.points[3 * a] - mesh.points[3 * b];
  const double dy = mesh.points[3 * a + 1] - mesh.points[3 * b + 1];
  const double dz = mesh.points[3 * a + 2] - mesh.points[3 * b + 2];
  return std::sqrt(dx * dx + dy * dy + dz * dz);
}

/// @return #F x 3 face centroids, (a + b + c) / 3
std::vector<double> faceCentroids(const TriMesh& mesh);

/// (b - a) x (c - a) of every face (a, b, c): twice its area along its normal, outward for
/// counter-clockwise faces.
/// @param[in] progress, steps  forwarded to parallel_for
/// @return #F x 3
std::vector<double> faceCrossProducts(
  const TriMesh& mesh, const Progress& progress = Progress(), int steps = 32);

/// @return #F x 3 unit face normals, zero for a degenerate face
std::vector<double> faceUnitNormals(const TriMesh& mesh);

/// The angle between the unit normals of the two faces of every manifold edge, in radians
/// (0 on boundary and non-manifold edges).
/// @return #E, in tc::buildEdgeTable order
std::vector<double> edgeDihedrals(const TriMesh& mesh, const EdgeTable& edges);
} // namespace detail
} // namespace tc
