// SPDX-License-Identifier: BSD-3-Clause
/// @file analytic_meshes.h
/// Triangle meshes of surfaces whose differential geometry is known in closed form, for tests:
/// spheres (regular and jittered), open cylinders, tori, height fields z = f(x, y) and a box
/// with rounded edges. Every generator returns a tc::TriMesh (counter-clockwise seen from
/// outside, i.e. from the side the normal points to) together with the exact principal
/// curvatures k1 >= k2 at every vertex (positive where the surface is convex w.r.t. the outward
/// normal) and, where it is defined, the exact unit direction of k1. Header-only; no test
/// framework dependency, so any core test can use it.
#pragma once

#include "tc/common/mesh.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <functional>
#include <map>
#include <random>
#include <utility>
#include <vector>

namespace tctest
{
/// A mesh and its exact curvature.
struct AnalyticMesh
{
  tc::TriMesh mesh;
  std::vector<double> k1; ///< #V exact maximal principal curvature
  std::vector<double> k2; ///< #V exact minimal principal curvature (k2 <= k1)
  std::vector<double> d1; ///< #V x 3 exact unit direction of k1; zero where umbilic (k1 == k2)
};

namespace detail
{
constexpr double kPi = 3.14159265358979323846;

inline void setDirection(AnalyticMesh& m, int64_t v, double x, double y, double z)
{
  const double n = std::sqrt(x * x + y * y + z * z);
  m.d1[3 * v] = n > 0 ? x / n : 0.0;
  m.d1[3 * v + 1] = n > 0 ? y / n : 0.0;
  m.d1[3 * v + 2] = n > 0 ? z / n : 0.0;
}

inline void resize(AnalyticMesh& m)
{
  const size_t n = m.mesh.points.size() / 3;
  m.k1.assign(n, 0.0);
  m.k2.assign(n, 0.0);
  m.d1.assign(3 * n, 0.0);
}

/// Triangles of an nu x nv grid whose odd rows are shifted by half a column (nearly equilateral
/// triangles, valence 6), periodic in u. Vertex (i, j) has id j * nu + i. Rows j and j + 1
/// are joined for j < nv - 1, and row nv - 1 to row 0 when periodicV (then nv must be even).
/// The triangles are counter-clockwise in the (u, v) parameter plane.
inline std::vector<int32_t> offsetGridTriangles(int nu, int nv, bool periodicV)
{
  std::vector<int32_t> tris;
  const int rows = periodicV ? nv : nv - 1;
  for (int j = 0; j < rows; ++j)
  {
    const int jn = (j + 1) % nv;
    for (int i = 0; i < nu; ++i)
    {
      const int in = (i + 1) % nu;
      const int32_t a = j * nu + i, b = j * nu + in, c = jn * nu + i, d = jn * nu + in;
      if (j % 2 == 0)
      {
        // Row j+1 is shifted by +1/2: c sits between a and b.
        tris.insert(tris.end(), { a, b, c, b, d, c });
      }
      else
      {
        // Row j is shifted by +1/2: a sits between c and d.
        tris.insert(tris.end(), { a, d, c, a, b, d });
      }
    }
  }
  return tris;
}

/// Exact principal curvatures of the graph z = f(x, y) with the upward normal (convex, i.e.
/// f'' < 0, is positive), from the first and second fundamental forms; direction of k1 in 3-D.
inline void graphCurvature(double fx, double fy, double fxx, double fxy, double fyy, double& k1,
  double& k2, std::array<double, 3>& d1)
{
  const double w = std::sqrt(1.0 + fx * fx + fy * fy);
  const double E = 1.0 + fx * fx, F = fx * fy, G = 1.0 + fy * fy;
  // Shape operator S = -I^-1 II (the minus makes convex positive); II taken w.r.t. the upward
  // normal.
  const double L = fxx / w, M = fxy / w, N = fyy / w;
  const double det = E * G - F * F;
  const double s11 = -(G * L - F * M) / det, s12 = -(G * M - F * N) / det;
  const double s21 = -(E * M - F * L) / det, s22 = -(E * N - F * M) / det;
  const double tr = s11 + s22, dt = s11 * s22 - s12 * s21;
  const double disc = std::sqrt(std::max(0.0, tr * tr / 4 - dt));
  k1 = tr / 2 + disc;
  k2 = tr / 2 - disc;
  // Eigenvector of S for k1 in parameter space, mapped by (r_x, r_y) = ((1,0,fx), (0,1,fy)).
  double u = s12, v = k1 - s11;
  if (std::abs(u) + std::abs(v) < 1e-300 || std::hypot(u, v) < 1e-12 * (std::abs(k1) + 1e-300))
  {
    u = k1 - s22;
    v = s21;
  }
  if (std::abs(u) + std::abs(v) < 1e-300 || disc <= 1e-14 * (std::abs(tr) + 1e-300))
  {
    d1 = { 0.0, 0.0, 0.0 };
    return;
  }
  d1 = { u, v, u * fx + v * fy };
}
} // namespace detail

/// Icosahedron subdivided `subdivisions` times (each triangle into 4), projected on the sphere
/// of `radius` around the origin: 10 * 4^s + 2 vertices. Exact k1 = k2 = 1 / radius, no
/// direction (umbilic).
inline AnalyticMesh icosphere(double radius, int subdivisions)
{
  const double t = (1.0 + std::sqrt(5.0)) / 2.0;
  std::vector<std::array<double, 3>> p = { { -1, t, 0 }, { 1, t, 0 }, { -1, -t, 0 }, { 1, -t, 0 },
    { 0, -1, t }, { 0, 1, t }, { 0, -1, -t }, { 0, 1, -t }, { t, 0, -1 }, { t, 0, 1 },
    { -t, 0, -1 }, { -t, 0, 1 } };
  std::vector<int32_t> f = { 0, 11, 5, 0, 5, 1, 0, 1, 7, 0, 7, 10, 0, 10, 11, 1, 5, 9, 5, 11, 4, 11,
    10, 2, 10, 7, 6, 7, 1, 8, 3, 9, 4, 3, 4, 2, 3, 2, 6, 3, 6, 8, 3, 8, 9, 4, 9, 5, 2, 4, 11, 6, 2,
    10, 8, 6, 7, 9, 8, 1 };
  auto normalize = [](std::array<double, 3> a)
  {
    const double n = std::sqrt(a[0] * a[0] + a[1] * a[1] + a[2] * a[2]);
    return std::array<double, 3>{ a[0] / n, a[1] / n, a[2] / n };
  };
  for (auto& q : p)
  {
    q = normalize(q);
  }
  for (int s = 0; s < subdivisions; ++s)
  {
    std::map<std::pair<int32_t, int32_t>, int32_t> mid;
    auto midpoint = [&](int32_t a, int32_t b)
    {
      const auto key = std::make_pair(std::min(a, b), std::max(a, b));
      const auto it = mid.find(key);
      if (it != mid.end())
      {
        return it->second;
      }
      p.push_back(normalize({ p[a][0] + p[b][0], p[a][1] + p[b][1], p[a][2] + p[b][2] }));
      const int32_t id = static_cast<int32_t>(p.size() - 1);
      mid.emplace(key, id);
      return id;
    };
    std::vector<int32_t> g;
    for (size_t i = 0; i < f.size(); i += 3)
    {
      const int32_t a = f[i], b = f[i + 1], c = f[i + 2];
      const int32_t ab = midpoint(a, b), bc = midpoint(b, c), ca = midpoint(c, a);
      g.insert(g.end(), { a, ab, ca, b, bc, ab, c, ca, bc, ab, bc, ca });
    }
    f.swap(g);
  }
  AnalyticMesh m;
  for (const auto& q : p)
  {
    m.mesh.points.insert(m.mesh.points.end(), { radius * q[0], radius * q[1], radius * q[2] });
  }
  // Orient every face outwards (normal . centroid > 0), whatever the table above says.
  for (size_t i = 0; i < f.size(); i += 3)
  {
    const auto &a = p[f[i]], &b = p[f[i + 1]], &c = p[f[i + 2]];
    const double u[3] = { b[0] - a[0], b[1] - a[1], b[2] - a[2] };
    const double v[3] = { c[0] - a[0], c[1] - a[1], c[2] - a[2] };
    const double n[3] = { u[1] * v[2] - u[2] * v[1], u[2] * v[0] - u[0] * v[2],
      u[0] * v[1] - u[1] * v[0] };
    if (n[0] * (a[0] + b[0] + c[0]) + n[1] * (a[1] + b[1] + c[1]) + n[2] * (a[2] + b[2] + c[2]) < 0)
    {
      std::swap(f[i + 1], f[i + 2]);
    }
  }
  m.mesh.triangles = f;
  detail::resize(m);
  std::fill(m.k1.begin(), m.k1.end(), 1.0 / radius);
  std::fill(m.k2.begin(), m.k2.end(), 1.0 / radius);
  return m;
}

/// An icosphere whose vertices are moved tangentially by up to `jitter` times the local edge
/// length (uniformly random, fixed seed) and projected back on the sphere: irregular triangles
/// on the same exact surface.
inline AnalyticMesh jitteredSphere(
  double radius, int subdivisions, double jitter, uint32_t seed = 12345)
{
  AnalyticMesh m = icosphere(radius, subdivisions);
  const double edge = radius * 1.1 / (1 << subdivisions);
  std::mt19937 rng(seed);
  auto uniform = [&rng]() { return static_cast<double>(rng()) / 4294967296.0 * 2.0 - 1.0; };
  for (size_t i = 0; i < m.mesh.points.size(); i += 3)
  {
    double* q = &m.mesh.points[i];
    for (int c = 0; c < 3; ++c)
    {
      q[c] += jitter * edge * uniform();
    }
    const double n = std::sqrt(q[0] * q[0] + q[1] * q[1] + q[2] * q[2]);
    for (int c = 0; c < 3; ++c)
    {
      q[c] *= radius / n;
    }
  }
  return m;
}

/// Open cylinder of `radius` around the z axis, z in [-height/2, height/2], `around` vertices
/// per row and `rows` rows (odd rows rotated by half a step). Exact k1 = 1 / radius with the
/// circumferential direction, k2 = 0 along the axis.
inline AnalyticMesh cylinder(double radius, double height, int around, int rows)
{
  AnalyticMesh m;
  for (int j = 0; j < rows; ++j)
  {
    for (int i = 0; i < around; ++i)
    {
      const double phi = 2.0 * detail::kPi * (i + 0.5 * (j % 2)) / around;
      const double z = -height / 2 + height * j / (rows - 1);
      m.mesh.points.insert(
        m.mesh.points.end(), { radius * std::cos(phi), radius * std::sin(phi), z });
    }
  }
  // (u, v) = (phi, z): r_phi x r_z points outwards.
  m.mesh.triangles = detail::offsetGridTriangles(around, rows, false);
  detail::resize(m);
  for (int64_t v = 0; v < m.mesh.numPoints(); ++v)
  {
    m.k1[v] = 1.0 / radius;
    m.k2[v] = 0.0;
    detail::setDirection(m, v, -m.mesh.points[3 * v + 1], m.mesh.points[3 * v], 0.0);
  }
  return m;
}

/// Torus around the z axis with major radius R (to the tube centre) and minor radius r < R,
/// `around` vertices along the big circle and `tube` (even) around the tube. At tube angle
/// theta (0 on the outer equator): k1 = 1 / r along the tube's circle, k2 = cos(theta) /
/// (R + r cos(theta)) along the big circle (negative on the inner half: saddle points).
inline AnalyticMesh torus(double R, double r, int around, int tube)
{
  AnalyticMesh m;
  std::vector<double> theta;
  for (int j = 0; j < tube; ++j)
  {
    for (int i = 0; i < around; ++i)
    {
      const double phi = 2.0 * detail::kPi * (i + 0.5 * (j % 2)) / around;
      const double th = 2.0 * detail::kPi * j / tube;
      const double rho = R + r * std::cos(th);
      m.mesh.points.insert(
        m.mesh.points.end(), { rho * std::cos(phi), rho * std::sin(phi), r * std::sin(th) });
      theta.push_back(th);
    }
  }
  // (u, v) = (phi, theta): r_phi x r_theta is the outward normal.
  m.mesh.triangles = detail::offsetGridTriangles(around, tube, true);
  detail::resize(m);
  for (int64_t v = 0; v < m.mesh.numPoints(); ++v)
  {
    const double th = theta[v];
    const double x = m.mesh.points[3 * v], y = m.mesh.points[3 * v + 1];
    const double rho = std::hypot(x, y);
    m.k1[v] = 1.0 / r;
    m.k2[v] = std::cos(th) / (R + r * std::cos(th));
    // d(position)/d(theta) direction.
    detail::setDirection(m, v, -std::sin(th) * x / rho, -std::sin(th) * y / rho, std::cos(th));
  }
  return m;
}

/// Values and derivatives of a height function z = f(x, y) at one point.
struct HeightSample
{
  double f = 0, fx = 0, fy = 0, fxx = 0, fxy = 0, fyy = 0;
};

/// Graph of z = f(x, y) over [x0, x1] x [y0, y1] on an nx x ny vertex grid, quads split along
/// alternating diagonals (valences 4 and 8: deliberately not the regular pattern). Outward is
/// +z (a bump is convex: positive curvature).
inline AnalyticMesh heightField(const std::function<HeightSample(double, double)>& f, double x0,
  double x1, double y0, double y1, int nx, int ny)
{
  AnalyticMesh m;
  std::vector<HeightSample> samples;
  for (int j = 0; j < ny; ++j)
  {
    for (int i = 0; i < nx; ++i)
    {
      const double x = x0 + (x1 - x0) * i / (nx - 1), y = y0 + (y1 - y0) * j / (ny - 1);
      samples.push_back(f(x, y));
      m.mesh.points.insert(m.mesh.points.end(), { x, y, samples.back().f });
    }
  }
  for (int j = 0; j + 1 < ny; ++j)
  {
    for (int i = 0; i + 1 < nx; ++i)
    {
      const int32_t a = j * nx + i, b = a + 1, c = a + nx, d = c + 1;
      if ((i + j) % 2 == 0)
      {
        m.mesh.triangles.insert(m.mesh.triangles.end(), { a, b, d, a, d, c });
      }
      else
      {
        m.mesh.triangles.insert(m.mesh.triangles.end(), { a, b, c, b, d, c });
      }
    }
  }
  detail::resize(m);
  for (int64_t v = 0; v < m.mesh.numPoints(); ++v)
  {
    const HeightSample& s = samples[v];
    std::array<double, 3> d1;
    detail::graphCurvature(s.fx, s.fy, s.fxx, s.fxy, s.fyy, m.k1[v], m.k2[v], d1);
    detail::setDirection(m, v, d1[0], d1[1], d1[2]);
  }
  return m;
}

/// The plane z = 0 over [-size/2, size/2]^2 (k1 = k2 = 0).
inline AnalyticMesh plane(double size, int n)
{
  return heightField(
    [](double, double) { return HeightSample{}; }, -size / 2, size / 2, -size / 2, size / 2, n, n);
}

/// A ridge along the y axis: z = height * exp(-x^2 / (2 width^2)) over [-size/2, size/2]^2.
/// Its crest (maximum of k1 along d1 = x) is the line x = 0; the two valleys (minimum of k2,
/// across) are the lines x = +-x_v where f'' / (1 + f'^2)^(3/2) is minimal (x_v -> sqrt(3)
/// width for a shallow ridge). A negative height turns the ridge into a valley.
inline AnalyticMesh gaussianRidge(double height, double width, double size, int n)
{
  return heightField(
    [height, width](double x, double)
    {
      const double w2 = width * width;
      const double g = height * std::exp(-x * x / (2 * w2));
      HeightSample s;
      s.f = g;
      s.fx = -x / w2 * g;
      s.fxx = (x * x / w2 - 1) / w2 * g;
      return s;
    },
    -size / 2, size / 2, -size / 2, size / 2, n, n);
}

/// A box with rounded edges: all points at distance `rounding` from the core cube [-a, a]^3.
/// Built from an n x n grid on each face of the cube of half size a + rounding, each vertex
/// moved to the closest point of the rounded surface along the direction from the core.
/// Exact curvature: 0 on the flat faces, (1/rounding, 0) on the 12 quarter-cylinders (k1 across
/// the edge), 1/rounding on the 8 sphere octants. rounding = 0 gives the sharp cube [-a, a]^3
/// with an n x n grid per face; its curvature (a Dirac on the edges) is then reported as 0.
inline AnalyticMesh roundedBox(double a, double rounding, int n)
{
  AnalyticMesh m;
  const double half = a + rounding;
  std::vector<int32_t> id((n + 1) * (n + 1) * (n + 1), -1);
  auto vertex = [&](int i, int j, int k)
  {
    int32_t& slot = id[(k * (n + 1) + j) * (n + 1) + i];
    if (slot < 0)
    {
      const double p[3] = { -half + 2 * half * i / n, -half + 2 * half * j / n,
        -half + 2 * half * k / n };
      double q[3], d[3];
      for (int c = 0; c < 3; ++c)
      {
        q[c] = std::clamp(p[c], -a, a);
        d[c] = p[c] - q[c];
      }
      const double len = std::sqrt(d[0] * d[0] + d[1] * d[1] + d[2] * d[2]);
      slot = static_cast<int32_t>(m.mesh.points.size() / 3);
      for (int c = 0; c < 3; ++c)
      {
        m.mesh.points.push_back(len > 0 ? q[c] + rounding * d[c] / len : p[c]);
      }
    }
    return slot;
  };
  for (int axis = 0; axis < 3; ++axis)
  {
    for (int side = 0; side < 2; ++side)
    {
      const int a1 = (axis + 1) % 3, a2 = (axis + 2) % 3; // e_a1 x e_a2 = e_axis
      for (int v = 0; v < n; ++v)
      {
        for (int u = 0; u < n; ++u)
        {
          int32_t c[4];
          const int du[4] = { 0, 1, 1, 0 }, dv[4] = { 0, 0, 1, 1 };
          for (int k = 0; k < 4; ++k)
          {
            int ijk[3];
            ijk[axis] = side ? n : 0;
            ijk[a1] = u + du[k];
            ijk[a2] = v + dv[k];
            c[k] = vertex(ijk[0], ijk[1], ijk[2]);
          }
          // Diagonal alternating so that the pattern is symmetric about each face centre.
          const bool flipDiag = ((u < n / 2) != (v < n / 2));
          int32_t t[6];
          if (!flipDiag)
          {
            const int32_t tt[6] = { c[0], c[1], c[2], c[0], c[2], c[3] };
            std::copy(tt, tt + 6, t);
          }
          else
          {
            const int32_t tt[6] = { c[0], c[1], c[3], c[1], c[2], c[3] };
            std::copy(tt, tt + 6, t);
          }
          if (side == 0)
          {
            std::swap(t[1], t[2]);
            std::swap(t[4], t[5]);
          }
          m.mesh.triangles.insert(m.mesh.triangles.end(), t, t + 6);
        }
      }
    }
  }
  detail::resize(m);
  for (int64_t v = 0; v < m.mesh.numPoints(); ++v)
  {
    const double* p = &m.mesh.points[3 * v];
    int curved = 0, along = -1;
    for (int c = 0; c < 3; ++c)
    {
      if (std::abs(p[c]) > a * (1 + 1e-12))
      {
        ++curved;
      }
      else
      {
        along = c;
      }
    }
    if (curved >= 2)
    {
      m.k1[v] = 1.0 / rounding;
    }
    if (curved == 3)
    {
      m.k2[v] = 1.0 / rounding;
    }
    if (curved == 2)
    {
      // k1 is across the edge: perpendicular to the edge axis and to the normal.
      double nrm[3], e[3] = { 0, 0, 0 };
      for (int c = 0; c < 3; ++c)
      {
        nrm[c] = p[c] - std::clamp(p[c], -a, a);
      }
      e[along] = 1.0;
      detail::setDirection(m, v, e[1] * nrm[2] - e[2] * nrm[1], e[2] * nrm[0] - e[0] * nrm[2],
        e[0] * nrm[1] - e[1] * nrm[0]);
    }
  }
  return m;
}

/// A copy of `mesh` with every position multiplied by `s`.
inline tc::TriMesh scaled(const tc::TriMesh& mesh, double s)
{
  tc::TriMesh out = mesh;
  for (double& x : out.points)
  {
    x *= s;
  }
  return out;
}

/// A copy of `mesh` with every triangle's orientation reversed (normals point inwards).
inline tc::TriMesh reversed(const tc::TriMesh& mesh)
{
  tc::TriMesh out = mesh;
  for (size_t i = 0; i < out.triangles.size(); i += 3)
  {
    std::swap(out.triangles[i + 1], out.triangles[i + 2]);
  }
  return out;
}

/// Six times the signed volume enclosed by a closed mesh (positive when oriented outwards).
inline double signedVolume6(const tc::TriMesh& mesh)
{
  double vol = 0;
  for (size_t i = 0; i < mesh.triangles.size(); i += 3)
  {
    const double* a = &mesh.points[3 * mesh.triangles[i]];
    const double* b = &mesh.points[3 * mesh.triangles[i + 1]];
    const double* c = &mesh.points[3 * mesh.triangles[i + 2]];
    vol += a[0] * (b[1] * c[2] - b[2] * c[1]) - a[1] * (b[0] * c[2] - b[2] * c[0]) +
      a[2] * (b[0] * c[1] - b[1] * c[0]);
  }
  return vol;
}
} // namespace tctest
