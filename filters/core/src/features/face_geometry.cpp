// SPDX-License-Identifier: BSD-3-Clause
#include "features/face_geometry.h"

#include <algorithm>
#include <cmath>

// Sequential on purpose: each loop is a few operations per face, far below the cost of the
// stages that use them.

namespace tc
{
namespace detail
{
std::vector<double> faceCentroids(const TriMesh& mesh)
{
  const int64_t nf = mesh.numTriangles();
  std::vector<double> centroids(3 * nf);
  for (int64_t f = 0; f < nf; ++f)
  {
    for (int c = 0; c < 3; ++c)
    {
      centroids[3 * f + c] = (mesh.points[3 * mesh.triangles[3 * f] + c] +
                               mesh.points[3 * mesh.triangles[3 * f + 1] + c] +
                               mesh.points[3 * mesh.triangles[3 * f + 2] + c]) /
        3.0;
    }
  }
  return centroids;
}

std::vector<double> faceCrossProducts(const TriMesh& mesh)
{
  const int64_t nf = mesh.numTriangles();
  std::vector<double> cross(3 * nf);
  for (int64_t f = 0; f < nf; ++f)
  {
    const double* a = &mesh.points[3 * mesh.triangles[3 * f]];
    const double* b = &mesh.points[3 * mesh.triangles[3 * f + 1]];
    const double* c = &mesh.points[3 * mesh.triangles[3 * f + 2]];
    const double u[3] = { b[0] - a[0], b[1] - a[1], b[2] - a[2] };
    const double v[3] = { c[0] - a[0], c[1] - a[1], c[2] - a[2] };
    cross[3 * f] = u[1] * v[2] - u[2] * v[1];
    cross[3 * f + 1] = u[2] * v[0] - u[0] * v[2];
    cross[3 * f + 2] = u[0] * v[1] - u[1] * v[0];
  }
  return cross;
}

std::vector<double> faceUnitNormals(const TriMesh& mesh)
{
  std::vector<double> normals = faceCrossProducts(mesh);
  const int64_t nf = mesh.numTriangles();
  for (int64_t f = 0; f < nf; ++f)
  {
    double* n = &normals[3 * f];
    const double len = std::sqrt(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]);
    for (int c = 0; c < 3; ++c)
    {
      n[c] = len > 0.0 ? n[c] / len : 0.0;
    }
  }
  return normals;
}

std::vector<double> edgeDihedrals(const TriMesh& mesh, const EdgeTable& edges)
{
  const std::vector<double> normal = faceUnitNormals(mesh);
  const int64_t ne = edges.numEdges();
  std::vector<double> dihedral(ne, 0.0);
  for (int64_t e = 0; e < ne; ++e)
  {
    if (edges.valence(e) == 2)
    {
      const double* n0 = &normal[3 * edges.edgeFaces[edges.faceOffsets[e]]];
      const double* n1 = &normal[3 * edges.edgeFaces[edges.faceOffsets[e] + 1]];
      dihedral[e] = std::acos(std::clamp(n0[0] * n1[0] + n0[1] * n1[1] + n0[2] * n1[2], -1.0, 1.0));
    }
  }
  return dihedral;
}
} // namespace detail
} // namespace tc
