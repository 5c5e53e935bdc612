// SPDX-License-Identifier: BSD-3-Clause
/// @file mesh.h
/// Plain mesh containers of the core: flat arrays, the same layout as VTK's points and
/// vtkCellArray (offsets + connectivity), so the VTK layer converts with one copy.
#pragma once

#include <array>
#include <cstdint>
#include <vector>

namespace tc
{
/// Polygons of any size over shared points, as read from a file.
struct PolygonSoup
{
  std::vector<double> points;        ///< #V x 3 positions, xyz interleaved
  std::vector<int64_t> offsets{ 0 }; ///< #P + 1 offsets into connectivity
  std::vector<int64_t> connectivity; ///< point ids of every polygon, back to back

  int64_t numPoints() const { return static_cast<int64_t>(points.size() / 3); }
  int64_t numPolygons() const { return static_cast<int64_t>(offsets.size()) - 1; }
  void addPolygon(const int64_t* ids, int64_t n)
  {
    connectivity.insert(connectivity.end(), ids, ids + n);
    offsets.push_back(static_cast<int64_t>(connectivity.size()));
  }
};

/// A triangle mesh: #V x 3 positions and #F x 3 vertex indices.
struct TriMesh
{
  std::vector<double> points;     ///< #V x 3 positions, xyz interleaved
  std::vector<int32_t> triangles; ///< #F x 3 vertex ids, counter-clockwise seen from outside

  int64_t numPoints() const { return static_cast<int64_t>(points.size() / 3); }
  int64_t numTriangles() const { return static_cast<int64_t>(triangles.size() / 3); }
  std::array<double, 3> point(int64_t v) const
  {
    return { points[3 * v], points[3 * v + 1], points[3 * v + 2] };
  }
};
} // namespace tc
