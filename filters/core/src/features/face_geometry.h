// SPDX-License-Identifier: BSD-3-Clause
/// @file face_geometry.h
/// Per-face and per-edge measures shared by the feature stages (Feng et al. 2010, section 4.2):
/// centroids (the lengths of the dual graph), face normals (the Nystrom kernel, eq. 4's crease
/// factor, area-weighted vertex normals) and dihedral angles (creases). One definition, so that
/// every stage measures the same mesh the same way.
#pragma once

#include "tc/common/mesh.h"
#include "tc/common/mesh_topology.h"

#include <cmath>
#include <cstdint>
#include <vector>

namespace tc
{
namespace detail
{
/// |p - q| of two 3-vectors.
inline double distance3(const double* p, const double* q)
{
  const double dx = p[0] - q[0];
  const double dy = p[1] - q[1];
  const double dz = p[2] - q[2];
  return std::sqrt(dx * dx + dy * dy + dz * dz);
}

/// |p_a - p_b|, the length of a mesh edge.
inline double vertexDistance(const TriMesh& mesh, int64_t a, int64_t b)
{
  return distance3(&mesh.points[3 * a], &mesh.points[3 * b]);
}

/// @return #F x 3 face centroids, (a + b + c) / 3
std::vector<double> faceCentroids(const TriMesh& mesh);

/// (b - a) x (c - a) of every face (a, b, c): twice its area along its normal, outward for
/// counter-clockwise faces.
/// @return #F x 3
std::vector<double> faceCrossProducts(const TriMesh& mesh);

/// @return #F x 3 unit face normals, zero for a degenerate face
std::vector<double> faceUnitNormals(const TriMesh& mesh);

/// The angle between the unit normals of the two faces of every manifold edge, in radians
/// (0 on boundary and non-manifold edges).
/// @return #E, in tc::buildEdgeTable order
std::vector<double> edgeDihedrals(const TriMesh& mesh, const EdgeTable& edges);
} // namespace detail
} // namespace tc
