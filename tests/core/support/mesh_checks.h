// SPDX-License-Identifier: BSD-3-Clause
/// @file mesh_checks.h
/// Checks that the rebuilt meshes of the atlas tests are closed oriented manifolds.
#pragma once

#include "tc/common/mesh.h"
#include "tc/common/mesh_topology.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <string>
#include <utility>
#include <vector>

namespace tctest
{
/// True if every edge with two faces is run through in opposite directions by them; with
/// `closed`, also every edge has exactly two faces.
inline bool consistentlyOriented(const tc::TriMesh& mesh, bool closed = false)
{
  const tc::EdgeTable edges = tc::buildEdgeTable(mesh.triangles);
  for (int64_t e = 0; e < edges.numEdges(); ++e)
  {
    if (edges.valence(e) != 2)
    {
      if (closed)
      {
        return false;
      }
      continue;
    }
    int forward = 0;
    for (int64_t k = edges.faceOffsets[e]; k < edges.faceOffsets[e + 1]; ++k)
    {
      const int64_t f = edges.edgeFaces[k];
      for (int i = 0; i < 3; ++i)
      {
        forward += mesh.triangles[3 * f + i] == edges.vertices[2 * e] &&
          mesh.triangles[3 * f + (i + 1) % 3] == edges.vertices[2 * e + 1];
      }
    }
    if (forward != 1)
    {
      return false;
    }
  }
  return true;
}

/// The first way `mesh` fails to be a closed, oriented 2-manifold without degenerate triangles
/// and isolated points, or "" when it is one; `euler` receives V - E + F. With `flat`, triangles
/// of three distinct points without area are allowed and counted there: the lattice an atlas's
/// positions are snapped to (docs/atlas-format.md, version 4) flattens slivers thinner than its
/// step, which changes no topology.
inline std::string manifoldDefect(const tc::TriMesh& mesh, int64_t& euler, int64_t* flat = nullptr)
{
  const int64_t nv = mesh.numPoints(), nf = mesh.numTriangles();
  double lo[3] = { 1e300, 1e300, 1e300 }, hi[3] = { -1e300, -1e300, -1e300 };
  for (int64_t v = 0; v < nv; ++v)
  {
    for (int x = 0; x < 3; ++x)
    {
      lo[x] = std::min(lo[x], mesh.points[3 * v + x]);
      hi[x] = std::max(hi[x], mesh.points[3 * v + x]);
    }
  }
  const double diag2 = (hi[0] - lo[0]) * (hi[0] - lo[0]) + (hi[1] - lo[1]) * (hi[1] - lo[1]) +
    (hi[2] - lo[2]) * (hi[2] - lo[2]);
  std::vector<int64_t> directed;
  std::vector<int32_t> used(static_cast<size_t>(nv), 0);
  for (int64_t f = 0; f < nf; ++f)
  {
    const int32_t* t = &mesh.triangles[3 * f];
    if (t[0] == t[1] || t[1] == t[2] || t[2] == t[0])
    {
      return "triangle " + std::to_string(f) + " repeats a corner";
    }
    const auto a = mesh.point(t[0]), b = mesh.point(t[1]), c = mesh.point(t[2]);
    const double u[3] = { b[0] - a[0], b[1] - a[1], b[2] - a[2] };
    const double w[3] = { c[0] - a[0], c[1] - a[1], c[2] - a[2] };
    const double n[3] = { u[1] * w[2] - u[2] * w[1], u[2] * w[0] - u[0] * w[2],
      u[0] * w[1] - u[1] * w[0] };
    if (0.5 * std::sqrt(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]) <= 1e-12 * diag2)
    {
      if (!flat)
      {
        return "triangle " + std::to_string(f) + " has no area";
      }
      ++*flat;
    }
    for (int k = 0; k < 3; ++k)
    {
      directed.push_back(int64_t(t[k]) * nv + t[(k + 1) % 3]);
      ++used[static_cast<size_t>(t[k])];
    }
  }
  std::sort(directed.begin(), directed.end());
  for (size_t e = 0; e < directed.size(); ++e)
  {
    if (e > 0 && directed[e] == directed[e - 1])
    {
      return "an edge is used twice in the same direction (inconsistent orientation or a "
             "non-manifold edge)";
    }
    const int64_t reverse = (directed[e] % nv) * nv + directed[e] / nv;
    if (!std::binary_search(directed.begin(), directed.end(), reverse))
    {
      return "edge " + std::to_string(directed[e] / nv) + "-" + std::to_string(directed[e] % nv) +
        " is a boundary edge (a crack)";
    }
  }
  // One disk per vertex: the links (a -> b of every triangle (v, a, b)) form one cycle.
  std::vector<std::vector<std::pair<int32_t, int32_t>>> link(static_cast<size_t>(nv));
  for (int64_t f = 0; f < nf; ++f)
  {
    const int32_t* t = &mesh.triangles[3 * f];
    for (int k = 0; k < 3; ++k)
    {
      link[static_cast<size_t>(t[k])].push_back({ t[(k + 1) % 3], t[(k + 2) % 3] });
    }
  }
  for (int64_t v = 0; v < nv; ++v)
  {
    const auto& l = link[static_cast<size_t>(v)];
    if (l.empty())
    {
      return "point " + std::to_string(v) + " is in no triangle";
    }
    int32_t at = l[0].second;
    size_t steps = 1;
    while (at != l[0].first && steps <= l.size())
    {
      const auto it = std::find_if(
        l.begin(), l.end(), [at](const std::pair<int32_t, int32_t>& e) { return e.first == at; });
      if (it == l.end())
      {
        return "the triangles around point " + std::to_string(v) + " do not close into a fan";
      }
      at = it->second;
      ++steps;
    }
    if (steps != l.size())
    {
      return "the triangles around point " + std::to_string(v) + " form more than one fan";
    }
  }
  euler = nv - static_cast<int64_t>(directed.size() / 2) + nf;
  return "";
}
} // namespace tctest
