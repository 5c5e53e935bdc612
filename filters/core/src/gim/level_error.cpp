// SPDX-License-Identifier: BSD-3-Clause
#include "gim/level_error.h"

#include "detail/geometry2d.h"
#include "gim/geometry_images_vec3.h"

#include <algorithm>
#include <cmath>

namespace tc::detail::geometry_images
{
namespace
{
/// Distance from 3-D point P at parameter (u, v) to the level-d grid surface there.
double levelDeviation(const ChartGrid& g, int32_t d, double u, double v, const Vec3& P)
{
  const GridHit h = gridHit(u, v, int64_t(1) << d);
  Vec3 r = Vec3::Zero();
  for (int k = 0; k < 3; ++k)
  {
    const float* s = g.at(d, h.i[k], h.j[k]);
    r += h.w[k] * Vec3(s[0], s[1], s[2]);
  }
  return (r - P).norm();
}

/// Dihedral angle above which a patch edge is a crease for chartLevelErrors.
constexpr double kCreaseDegrees = 45.0;
} // namespace

Creases patchCreases(const TriMesh& mesh, const PatchParameterization& p)
{
  const size_t nt = p.triangles.size() / 3;
  std::vector<Vec3> normal(nt);
  std::vector<std::array<int32_t, 3>> edges; // lower point, higher point, triangle
  edges.reserve(3 * nt);
  for (size_t t = 0; t < nt; ++t)
  {
    const int32_t* c = &p.triangles[3 * t];
    const Vec3 a = pointOf(mesh, p.points[c[0]]);
    normal[t] = (pointOf(mesh, p.points[c[1]]) - a).cross(pointOf(mesh, p.points[c[2]]) - a);
    for (int k = 0; k < 3; ++k)
    {
      const int32_t x = c[k], y = c[(k + 1) % 3];
      edges.push_back({ std::min(x, y), std::max(x, y), static_cast<int32_t>(t) });
    }
  }
  std::sort(edges.begin(), edges.end());
  const double cosine = std::cos(kCreaseDegrees * kPi / 180.0);
  std::vector<std::array<int32_t, 2>> out;
  for (size_t i = 0; i + 1 < edges.size(); ++i)
  {
    if (edges[i][0] != edges[i + 1][0] || edges[i][1] != edges[i + 1][1])
    {
      continue;
    }
    const Vec3& n0 = normal[edges[i][2]];
    const Vec3& n1 = normal[edges[i + 1][2]];
    const double l = n0.norm() * n1.norm();
    if (l > 0.0 && n0.dot(n1) < cosine * l)
    {
      out.push_back({ edges[i][0], edges[i][1] });
    }
  }
  return out;
}

std::vector<double> chartLevelErrors(const TriMesh& mesh, const PatchParameterization& p,
  const ChartGrid& g, const Creases& creases, int32_t upTo)
{
  std::vector<double> error(static_cast<size_t>(upTo) + 1, 0.0);
  for (int32_t d = 0; d <= upTo; ++d)
  {
    const int64_t nd = int64_t(1) << d;
    double worst = 0.0;
    for (size_t v = 0; v < p.points.size(); ++v)
    {
      worst = std::max(
        worst, levelDeviation(g, d, p.uv[2 * v], p.uv[2 * v + 1], pointOf(mesh, p.points[v])));
    }
    for (const auto& edge : creases)
    {
      const int32_t a = edge[0], b = edge[1];
      const double ua = p.uv[2 * a], va = p.uv[2 * a + 1];
      const double ub = p.uv[2 * b], vb = p.uv[2 * b + 1];
      const double fa[3] = { ua * nd, va * nd, (ua + va) * nd };
      const double fb[3] = { ub * nd, vb * nd, (ub + vb) * nd };
      for (int f = 0; f < 3; ++f)
      {
        const double lo = std::min(fa[f], fb[f]), hi = std::max(fa[f], fb[f]);
        for (double line = std::floor(lo) + 1.0; line < hi; line += 1.0)
        {
          const double w = (line - fa[f]) / (fb[f] - fa[f]);
          const Vec3 P = (1.0 - w) * pointOf(mesh, p.points[a]) + w * pointOf(mesh, p.points[b]);
          worst = std::max(worst, levelDeviation(g, d, ua + w * (ub - ua), va + w * (vb - va), P));
        }
      }
    }
    error[d] = worst;
  }
  return error;
}
} // namespace tc::detail::geometry_images
