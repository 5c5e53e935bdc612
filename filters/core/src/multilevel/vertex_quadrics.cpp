// SPDX-License-Identifier: BSD-3-Clause
// The quadrics of the multilevel mesh (Kircher and Garland 2005, section 3): M0's per-vertex
// quadrics of Garland and Heckbert (1997), and the position a summed quadric puts its vertex at.
#include "multilevel/multilevel_internal.h"

#include <Eigen/Eigenvalues>

#include <algorithm>

namespace tc
{
namespace detail
{
namespace multilevel
{
namespace
{
/// Eigenvalues below this fraction of the largest are treated as zero (Lindstrom 2000, "Out-of-
/// core simplification of large polygonal models"): a flat or cylindrical cluster then keeps
/// its mean along the directions its quadric does not constrain, instead of running off along
/// them on round-off.
constexpr double kSingularRatio = 1e-3;

V3 corner(const TriMesh& mesh, int64_t f, int i)
{
  const double* p = &mesh.points[3 * mesh.triangles[3 * f + i]];
  return { p[0], p[1], p[2] };
}

void addFacePlanes(const TriMesh& mesh, std::vector<Quadric>& quadrics)
{
  for (int64_t f = 0; f < mesh.numTriangles(); ++f)
  {
    const V3 a = corner(mesh, f, 0), b = corner(mesh, f, 1), c = corner(mesh, f, 2);
    V3 n = cross(sub(b, a), sub(c, a));
    const double len = norm(n);
    if (!(len > 0))
    {
      continue; // a zero-area face has no plane, and no area to weight one
    }
    n = { n.x / len, n.y / len, n.z / len };
    Quadric plane;
    plane.addPlane(n, -dot(n, a), 0.5 * len);
    for (int i = 0; i < 3; ++i)
    {
      quadrics[mesh.triangles[3 * f + i]].add(plane);
    }
  }
}

/// The plane through boundary edge (u, v) of face f perpendicular to f.
void addBoundaryPlane(const TriMesh& mesh, int32_t u, int32_t v, int32_t f, Quadric& plane)
{
  const V3 a = corner(mesh, f, 0), b = corner(mesh, f, 1), c = corner(mesh, f, 2);
  const V3 faceNormal = cross(sub(b, a), sub(c, a));
  const V3 pu{ mesh.points[3 * u], mesh.points[3 * u + 1], mesh.points[3 * u + 2] };
  const V3 pv{ mesh.points[3 * v], mesh.points[3 * v + 1], mesh.points[3 * v + 2] };
  const V3 e = sub(pv, pu);
  V3 m = cross(e, faceNormal);
  const double len = norm(m);
  if (!(len > 0))
  {
    return;
  }
  m = { m.x / len, m.y / len, m.z / len };
  plane.addPlane(m, -dot(m, pu), dot(e, e));
}
} // namespace

std::vector<Quadric> vertexQuadrics(const TriMesh& mesh, const std::vector<int32_t>& edges,
  const std::vector<int32_t>& edgeFaceCount, const std::vector<int32_t>& edgeFace)
{
  std::vector<Quadric> quadrics(mesh.numPoints());
  addFacePlanes(mesh, quadrics);
  for (size_t e = 0; e < edgeFaceCount.size(); ++e)
  {
    if (edgeFaceCount[e] != 1)
    {
      continue;
    }
    Quadric plane;
    addBoundaryPlane(mesh, edges[2 * e], edges[2 * e + 1], edgeFace[e], plane);
    quadrics[edges[2 * e]].add(plane);
    quadrics[edges[2 * e + 1]].add(plane);
  }
  return quadrics;
}

double evaluate(const Quadric& q, const V3& p)
{
  const Quadric zero;
  return evalSum(q, zero, p);
}

/// Minimizes q over mean + the span of the eigenvectors of A whose eigenvalue is not
/// negligible: with g = A mean + b, p = mean - sum_i (g.e_i / l_i) e_i. A well-conditioned A
/// keeps all three, and p is then A^-1 (-b) itself.
Placed placeVertex(const Quadric& q, const V3& mean)
{
  Eigen::Matrix3d a;
  a << q.q[0], q.q[1], q.q[2], q.q[1], q.q[3], q.q[4], q.q[2], q.q[4], q.q[5];
  const Eigen::Vector3d b(q.q[6], q.q[7], q.q[8]);
  const Eigen::Vector3d c(mean.x, mean.y, mean.z);
  const Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> eig(a);
  const Eigen::Vector3d lambda = eig.eigenvalues(); // ascending
  const Eigen::Vector3d g = a * c + b;
  Eigen::Vector3d p = c;
  int kept = 0;
  for (int i = 0; i < 3; ++i)
  {
    if (lambda[2] > 0 && lambda[i] > kSingularRatio * lambda[2])
    {
      const Eigen::Vector3d e = eig.eigenvectors().col(i);
      p -= (g.dot(e) / lambda[i]) * e;
      ++kept;
    }
  }
  Placed placed{ { p[0], p[1], p[2] }, 0.0, kept == 3 ? Placement::Optimal : Placement::Singular };
  placed.error = evaluate(q, placed.p);
  return placed;
}
} // namespace multilevel
} // namespace detail

double evaluateQuadric(const double* quadric, const double p[3])
{
  detail::Quadric q;
  std::copy_n(quadric, 10, q.q);
  return detail::multilevel::evaluate(q, detail::V3{ p[0], p[1], p[2] });
}
} // namespace tc
