// SPDX-License-Identifier: BSD-3-Clause
#include "tc/gim/geometry_images.h"

#include "tc/common/errors.h"
#include "tc/common/mesh_topology.h"
#include "tc/gim/atlas.h"
#include "tc/gim/geometry_image_mesh.h"
#include "tc/metrics/surface_distance.h"

#include "analytic_meshes.h"
#include "test_progress.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <functional>
#include <map>
#include <string>
#include <utility>
#include <vector>

namespace
{
using Vec = std::array<double, 3>;

Vec sub(const Vec& a, const Vec& b)
{
  return { a[0] - b[0], a[1] - b[1], a[2] - b[2] };
}
double dot(const Vec& a, const Vec& b)
{
  return a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
}
Vec cross(const Vec& a, const Vec& b)
{
  return { a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0] };
}
double norm(const Vec& a)
{
  return std::sqrt(dot(a, a));
}

/// The farthest the lattice of the atlas file (docs/atlas-format.md, version 4) moves a sample:
/// half the diagonal of a cube of its step, the largest power of two <= diagonal * 2^-16.
double latticeMove(const tc::Atlas& atlas)
{
  return std::ldexp(std::sqrt(3.0) / 2.0, std::ilogb(atlas.inputDiagonal) - 16);
}

Vec toVec(const float* f)
{
  return { f[0], f[1], f[2] };
}

/// A base complex and its patch mesh built by hand: every base triangle subdivided into n x n
/// triangles (shared points along shared base edges), then every point moved by `place`. The
/// base vertices are points 0 .. #Vb-1; the paths are the subdivided base edges.
struct Synthetic
{
  tc::PatchMesh patches;
  tc::BaseComplexResult base;
};

Synthetic subdivide(const std::vector<Vec>& corners, const std::vector<std::array<int, 3>>& faces,
  int n, const std::function<Vec(const Vec&)>& place, const std::vector<int>& featureEdges = {})
{
  Synthetic s;
  tc::PatchMesh& pm = s.patches;
  std::vector<Vec> pts(corners.begin(), corners.end());
  std::map<std::pair<int, int>, int> edgeId;
  auto edge = [&](int a, int b)
  {
    const std::pair<int, int> key(std::min(a, b), std::max(a, b));
    const auto it = edgeId.find(key);
    if (it != edgeId.end())
    {
      return it->second;
    }
    const int e = static_cast<int>(edgeId.size());
    edgeId[key] = e;
    pm.baseEdges.push_back(key.first);
    pm.baseEdges.push_back(key.second);
    pm.pathPoints.push_back(key.first);
    for (int i = 1; i < n; ++i)
    {
      const double t = double(i) / n;
      const Vec& p = corners[key.first];
      const Vec& q = corners[key.second];
      pts.push_back(
        { p[0] + t * (q[0] - p[0]), p[1] + t * (q[1] - p[1]), p[2] + t * (q[2] - p[2]) });
      pm.pathPoints.push_back(static_cast<int32_t>(pts.size() - 1));
    }
    pm.pathPoints.push_back(key.second);
    pm.pathOffsets.push_back(static_cast<int64_t>(pm.pathPoints.size()));
    return e;
  };
  // Point of step s (0 .. n) from base vertex a towards b.
  auto onEdge = [&](int a, int b, int step)
  {
    if (step == 0)
    {
      return a;
    }
    if (step == n)
    {
      return b;
    }
    const int e = edge(a, b);
    const int64_t first = pm.pathOffsets[e];
    return static_cast<int>(pm.pathPoints[first + (a < b ? step : n - step)]);
  };
  for (size_t f = 0; f < faces.size(); ++f)
  {
    const int A = faces[f][0], B = faces[f][1], C = faces[f][2];
    for (int k = 0; k < 3; ++k)
    {
      const int e = edge(faces[f][k], faces[f][(k + 1) % 3]);
      pm.faceEdges.push_back(e);
      const bool feature =
        std::find(featureEdges.begin(), featureEdges.end(), e) != featureEdges.end();
      s.base.baseEdgeIsFeature.push_back(feature ? 1 : 0);
    }
    std::vector<int> id((n + 1) * (n + 1), -1);
    for (int j = 0; j <= n; ++j)
    {
      for (int i = 0; i + j <= n; ++i)
      {
        int v;
        if (j == 0)
        {
          v = onEdge(A, B, i);
        }
        else if (i + j == n)
        {
          v = onEdge(B, C, j);
        }
        else if (i == 0)
        {
          v = onEdge(C, A, n - j);
        }
        else
        {
          const Vec &a = corners[A], &b = corners[B], &c = corners[C];
          Vec p;
          for (int x = 0; x < 3; ++x)
          {
            p[x] = a[x] + (b[x] - a[x]) * i / n + (c[x] - a[x]) * j / n;
          }
          pts.push_back(p);
          v = static_cast<int>(pts.size() - 1);
        }
        id[j * (n + 1) + i] = v;
      }
    }
    for (int j = 0; j < n; ++j)
    {
      for (int i = 0; i + j < n; ++i)
      {
        const int a = id[j * (n + 1) + i], b = id[j * (n + 1) + i + 1],
                  c = id[(j + 1) * (n + 1) + i];
        pm.mesh.triangles.insert(pm.mesh.triangles.end(), { a, b, c });
        pm.patchId.push_back(static_cast<int32_t>(f));
        if (i + j + 1 < n)
        {
          const int d = id[(j + 1) * (n + 1) + i + 1];
          pm.mesh.triangles.insert(pm.mesh.triangles.end(), { b, d, c });
          pm.patchId.push_back(static_cast<int32_t>(f));
        }
      }
    }
    s.base.baseTriangles.insert(s.base.baseTriangles.end(), { A, B, C });
  }
  for (const Vec& p : pts)
  {
    const Vec q = place(p);
    pm.mesh.points.insert(pm.mesh.points.end(), q.begin(), q.end());
  }
  for (size_t v = 0; v < corners.size(); ++v)
  {
    s.base.baseVertices.push_back(static_cast<int32_t>(v));
  }
  pm.inputPointId.resize(pts.size());
  for (size_t v = 0; v < pts.size(); ++v)
  {
    pm.inputPointId[v] = static_cast<int32_t>(v);
  }
  for (size_t t = 0; t < pm.patchId.size(); ++t)
  {
    pm.inputTriangle.push_back(static_cast<int32_t>(t));
  }
  return s;
}

/// Octahedron +x, -x, +y, -y, top, -z (top = +z unless skewed) with outward faces.
std::vector<std::array<int, 3>> octahedronFaces()
{
  std::vector<std::array<int, 3>> faces;
  for (int sx : { 1, -1 })
  {
    for (int sy : { 1, -1 })
    {
      for (int sz : { 1, -1 })
      {
        const int X = sx > 0 ? 0 : 1, Y = sy > 0 ? 2 : 3, Z = sz > 0 ? 4 : 5;
        if (sx * sy * sz > 0)
        {
          faces.push_back({ X, Y, Z });
        }
        else
        {
          faces.push_back({ X, Z, Y });
        }
      }
    }
  }
  return faces;
}

constexpr double kRadius = 2.0;

/// A sphere of radius 2 from an octahedron subdivided n x n per face; `topTilt` moves the top
/// vertex that many degrees from +z towards +x, which makes the patches unequal.
Synthetic sphere(int n, double topTilt = 0.0)
{
  const double a = topTilt * 3.14159265358979323846 / 180.0;
  const std::vector<Vec> corners = { { 1, 0, 0 }, { -1, 0, 0 }, { 0, 1, 0 }, { 0, -1, 0 },
    { std::sin(a), 0, std::cos(a) }, { 0, 0, -1 } };
  return subdivide(corners, octahedronFaces(), n,
    [](const Vec& p)
    {
      const double l = norm(p);
      return Vec{ kRadius * p[0] / l, kRadius * p[1] / l, kRadius * p[2] / l };
    });
}

/// The unit cube, each face split by a diagonal into two base triangles; the 12 cube edges are
/// feature curves, the 6 diagonals are not.
Synthetic cube(int n)
{
  std::vector<Vec> corners;
  for (int z = 0; z < 2; ++z)
  {
    for (int y = 0; y < 2; ++y)
    {
      for (int x = 0; x < 2; ++x)
      {
        corners.push_back({ double(x), double(y), double(z) });
      }
    }
  }
  // Quads counter-clockwise seen from outside, as vertex ids x + 2y + 4z.
  const int quads[6][4] = { { 0, 2, 3, 1 }, { 4, 5, 7, 6 }, { 0, 1, 5, 4 }, { 2, 6, 7, 3 },
    { 0, 4, 6, 2 }, { 1, 3, 7, 5 } };
  std::vector<std::array<int, 3>> faces;
  for (const auto& q : quads)
  {
    faces.push_back({ q[0], q[1], q[2] });
    faces.push_back({ q[0], q[2], q[3] });
  }
  // Base edges are numbered as first met: per quad, sides q0q1, q1q2, q2q0 (diagonal), q2q3,
  // q3q0. Mark every edge that is not a diagonal.
  Synthetic probe = subdivide(corners, faces, 1, [](const Vec& p) { return p; });
  std::vector<int> features;
  for (size_t e = 0; e < probe.patches.baseEdges.size() / 2; ++e)
  {
    const Vec d =
      sub(corners[probe.patches.baseEdges[2 * e + 1]], corners[probe.patches.baseEdges[2 * e]]);
    if (std::abs(norm(d) - 1.0) < 1e-12)
    {
      features.push_back(static_cast<int>(e));
    }
  }
  return subdivide(
    corners, faces, n, [](const Vec& p) { return p; }, features);
}

/// What path tracing produces, imitated on a sphere: a jittered icosphere whose vertices nearest
/// to the six axis points are moved onto them (the base vertices), cut by the planes x = 0,
/// y = 0 and z = 0. Every triangle a plane crosses is split at Steiner points (inputPointId -1)
/// into pieces (slivers included); the patches are the octants, the paths the cut polylines.
Synthetic cutSphere(int subdivisions, double jitter)
{
  const tctest::AnalyticMesh am = tctest::jitteredSphere(kRadius, subdivisions, jitter);
  std::vector<Vec> pts;
  for (int64_t v = 0; v < am.mesh.numPoints(); ++v)
  {
    pts.push_back(am.mesh.point(v));
  }
  const int64_t nInput = static_cast<int64_t>(pts.size());
  std::vector<int32_t> tris = am.mesh.triangles;
  std::vector<int32_t> parent(tris.size() / 3);
  for (size_t t = 0; t < parent.size(); ++t)
  {
    parent[t] = static_cast<int32_t>(t);
  }
  // Axis points in the order +x, -x, +y, -y, +z, -z (the octahedron of octahedronFaces).
  std::array<int32_t, 6> axisVertex{};
  for (int a = 0; a < 6; ++a)
  {
    Vec target{ 0, 0, 0 };
    target[a / 2] = a % 2 == 0 ? kRadius : -kRadius;
    int32_t best = 0;
    for (int32_t v = 1; v < nInput; ++v)
    {
      if (norm(sub(pts[v], target)) < norm(sub(pts[best], target)))
      {
        best = v;
      }
    }
    pts[best] = target;
    axisVertex[a] = best;
  }
  for (int axis = 0; axis < 3; ++axis)
  {
    auto sign = [&](int32_t v) { return pts[v][axis] > 0 ? 1 : (pts[v][axis] < 0 ? -1 : 0); };
    std::map<std::pair<int32_t, int32_t>, int32_t> steiner;
    auto cut = [&](int32_t a, int32_t b)
    {
      const std::pair<int32_t, int32_t> key(std::min(a, b), std::max(a, b));
      const auto it = steiner.find(key);
      if (it != steiner.end())
      {
        return it->second;
      }
      const Vec &p = pts[key.first], &q = pts[key.second];
      const double t = p[axis] / (p[axis] - q[axis]);
      Vec x{ p[0] + t * (q[0] - p[0]), p[1] + t * (q[1] - p[1]), p[2] + t * (q[2] - p[2]) };
      x[axis] = 0.0;
      pts.push_back(x);
      const int32_t id = static_cast<int32_t>(pts.size() - 1);
      steiner[key] = id;
      return id;
    };
    std::vector<int32_t> out;
    std::vector<int32_t> outParent;
    for (size_t t = 0; t < tris.size() / 3; ++t)
    {
      int32_t c[3] = { tris[3 * t], tris[3 * t + 1], tris[3 * t + 2] };
      int s3[3] = { sign(c[0]), sign(c[1]), sign(c[2]) };
      auto emit = [&](int32_t a, int32_t b, int32_t d)
      {
        out.insert(out.end(), { a, b, d });
        outParent.push_back(parent[t]);
      };
      bool done = false;
      for (int r = 0; r < 3 && !done; ++r)
      {
        const int32_t a = c[r], b = c[(r + 1) % 3], d = c[(r + 2) % 3];
        const int sa = s3[r], sb = s3[(r + 1) % 3], sd = s3[(r + 2) % 3];
        if (sa == 0 && sb * sd < 0)
        {
          const int32_t p = cut(b, d);
          emit(a, b, p);
          emit(a, p, d);
          done = true;
        }
        else if (sa != 0 && sb == sd && sb == -sa)
        {
          const int32_t p = cut(a, b), q = cut(a, d);
          emit(a, p, q);
          emit(p, b, d);
          emit(p, d, q);
          done = true;
        }
      }
      if (!done)
      {
        emit(c[0], c[1], c[2]);
      }
    }
    tris = out;
    parent = outParent;
  }

  Synthetic s;
  tc::PatchMesh& pm = s.patches;
  pm.mesh.triangles = tris;
  for (const Vec& p : pts)
  {
    pm.mesh.points.insert(pm.mesh.points.end(), p.begin(), p.end());
  }
  for (int64_t v = 0; v < static_cast<int64_t>(pts.size()); ++v)
  {
    pm.inputPointId.push_back(v < nInput ? static_cast<int32_t>(v) : -1);
  }
  pm.inputTriangle = parent;
  for (size_t t = 0; t < tris.size() / 3; ++t)
  {
    Vec g{ 0, 0, 0 };
    for (int k = 0; k < 3; ++k)
    {
      for (int x = 0; x < 3; ++x)
      {
        g[x] += pts[tris[3 * t + k]][x];
      }
    }
    pm.patchId.push_back((g[0] < 0 ? 4 : 0) + (g[1] < 0 ? 2 : 0) + (g[2] < 0 ? 1 : 0));
  }
  // Base vertices: the six axis vertices, ascending by id.
  std::array<int, 6> byId{ 0, 1, 2, 3, 4, 5 };
  std::sort(byId.begin(), byId.end(), [&](int a, int b) { return axisVertex[a] < axisVertex[b]; });
  std::array<int32_t, 6> baseOfAxis{};
  for (int i = 0; i < 6; ++i)
  {
    s.base.baseVertices.push_back(axisVertex[byId[i]]);
    baseOfAxis[byId[i]] = i;
  }
  std::map<std::pair<int32_t, int32_t>, int32_t> edgeId;
  for (const auto& f : octahedronFaces())
  {
    for (int k = 0; k < 3; ++k)
    {
      s.base.baseTriangles.push_back(baseOfAxis[f[k]]);
      s.base.baseEdgeIsFeature.push_back(0);
      const int u = f[k], w = f[(k + 1) % 3];
      const std::pair<int32_t, int32_t> key(
        std::min(baseOfAxis[u], baseOfAxis[w]), std::max(baseOfAxis[u], baseOfAxis[w]));
      auto it = edgeId.find(key);
      if (it == edgeId.end())
      {
        // The path: every point on the plane of the third axis, on the quarter circle from the
        // lower base vertex to the higher one, ordered by angle.
        const int from = baseOfAxis[u] < baseOfAxis[w] ? u : w, to = from == u ? w : u;
        const int plane = 3 - from / 2 - to / 2;
        const Vec a = pts[axisVertex[from]], b = pts[axisVertex[to]];
        std::vector<std::pair<double, int32_t>> arc;
        for (int32_t v = 0; v < static_cast<int32_t>(pts.size()); ++v)
        {
          if (pts[v][plane] == 0.0 && dot(pts[v], a) >= 0.0 && dot(pts[v], b) >= 0.0)
          {
            arc.push_back({ std::atan2(dot(pts[v], b), dot(pts[v], a)), v });
          }
        }
        std::sort(arc.begin(), arc.end());
        for (const auto& [angle, v] : arc)
        {
          pm.pathPoints.push_back(v);
        }
        pm.pathOffsets.push_back(static_cast<int64_t>(pm.pathPoints.size()));
        pm.baseEdges.push_back(key.first);
        pm.baseEdges.push_back(key.second);
        it = edgeId.emplace(key, static_cast<int32_t>(edgeId.size())).first;
      }
      pm.faceEdges.push_back(it->second);
    }
  }
  return s;
}

int64_t samplesAt(int32_t d)
{
  const int64_t n = int64_t(1) << d;
  return (n + 1) * (n + 2) / 2;
}

bool sameFloats(const float* a, const float* b, int32_t n)
{
  return std::memcmp(a, b, sizeof(float) * static_cast<size_t>(n)) == 0;
}

/// The invariants of tc/atlas.h: validateAtlas, and directly, for every attribute: layout, texels
/// inside the image and owned by one chart, neighbour symmetry, bit-identical shared sides (normals
/// exempt on feature sides) and corners, and every coarser level a subset of the finer one.
void expectAtlasInvariants(const tc::Atlas& atlas)
{
  EXPECT_NO_THROW(tc::validateAtlas(atlas));
  ASSERT_GE(atlas.attributes.size(), 2u);
  EXPECT_EQ(atlas.attributes[0].name, tc::kAtlasPosition);
  EXPECT_EQ(atlas.attributes[1].name, tc::kAtlasNormal);
  const int32_t numImages = atlas.maxLevel() + 1;
  ASSERT_EQ(static_cast<int32_t>(atlas.images.size()), numImages);
  std::vector<std::vector<int32_t>> owner(atlas.images.size());
  for (size_t k = 0; k < atlas.images.size(); ++k)
  {
    const tc::AtlasImage& im = atlas.images[k];
    EXPECT_EQ(im.width % 4, 0);
    ASSERT_EQ(im.data.size(), atlas.attributes.size());
    for (size_t a = 0; a < atlas.attributes.size(); ++a)
    {
      ASSERT_EQ(im.data[a].size(), size_t(im.width) * im.height * atlas.attributes[a].components);
    }
    owner[k].assign(size_t(im.width) * im.height, -1);
  }
  const int32_t nc = static_cast<int32_t>(atlas.charts.size());
  int64_t overlaps = 0, outside = 0;
  for (int32_t c = 0; c < nc; ++c)
  {
    const tc::AtlasChart& ch = atlas.charts[c];
    ASSERT_EQ(static_cast<int32_t>(ch.origin.size()), ch.maxLevel + 1);
    ASSERT_EQ(static_cast<int32_t>(ch.levelError.size()), ch.maxLevel + 1);
    if (ch.partner >= 0)
    {
      EXPECT_EQ(atlas.charts[ch.partner].partner, c);
      EXPECT_NE(atlas.charts[ch.partner].rotated, ch.rotated);
    }
    for (int32_t d = 0; d <= ch.maxLevel; ++d)
    {
      const int32_t n = 1 << d;
      const tc::AtlasImage& im = atlas.images[ch.maxLevel - d];
      for (int32_t j = 0; j <= n; ++j)
      {
        for (int32_t i = 0; i + j <= n; ++i)
        {
          const auto xy = tc::atlasTexel(ch, d, i, j);
          if (xy[0] < 0 || xy[1] < 0 || xy[0] >= im.width || xy[1] >= im.height)
          {
            ++outside;
            continue;
          }
          int32_t& o = owner[ch.maxLevel - d][size_t(xy[1]) * im.width + xy[0]];
          overlaps += o >= 0 ? 1 : 0;
          o = c;
        }
      }
    }
  }
  EXPECT_EQ(outside, 0);
  EXPECT_EQ(overlaps, 0);
  if (outside > 0 || overlaps > 0)
  {
    return;
  }
  // Texels of no chart hold 0.
  int64_t dirty = 0;
  for (size_t k = 0; k < atlas.images.size(); ++k)
  {
    const tc::AtlasImage& im = atlas.images[k];
    for (size_t t = 0; t < owner[k].size(); ++t)
    {
      for (size_t a = 0; a < atlas.attributes.size() && owner[k][t] < 0; ++a)
      {
        const int32_t nComp = atlas.attributes[a].components;
        for (int32_t x = 0; x < nComp; ++x)
        {
          dirty += im.data[a][t * nComp + x] != 0.0f ? 1 : 0;
        }
      }
    }
  }
  EXPECT_EQ(dirty, 0);

  int64_t sideMismatch = 0, cornerMismatch = 0, mipMismatch = 0, asymmetric = 0;
  std::map<int32_t, std::vector<std::pair<int32_t, int32_t>>> corners; // vertex -> (chart, corner)
  for (int32_t c = 0; c < nc; ++c)
  {
    const tc::AtlasChart& ch = atlas.charts[c];
    for (int k = 0; k < 3; ++k)
    {
      corners[ch.cornerVertex[k]].push_back({ c, k });
      const int32_t o = ch.neighborChart[k], os = ch.neighborSide[k];
      ASSERT_GE(o, 0);
      ASSERT_LT(o, nc);
      const tc::AtlasChart& oc = atlas.charts[o];
      if (oc.neighborChart[os] != c || oc.neighborSide[os] != k ||
        oc.featureSide[os] != ch.featureSide[k] ||
        oc.cornerVertex[os] != ch.cornerVertex[(k + 1) % 3])
      {
        ++asymmetric;
      }
      for (int32_t d = 0; d <= std::min(ch.maxLevel, oc.maxLevel); ++d)
      {
        const int32_t n = 1 << d;
        for (int32_t t = 0; t <= n; ++t)
        {
          const auto p = tc::sidePoint(k, t, n);
          const auto q = tc::sidePoint(os, n - t, n);
          for (size_t a = 0; a < atlas.attributes.size(); ++a)
          {
            if (a == 1 && ch.featureSide[k] && t > 0 && t < n)
            {
              continue;
            }
            sideMismatch += sameFloats(tc::atlasSample(atlas, c, int32_t(a), d, p[0], p[1]),
                              tc::atlasSample(atlas, o, int32_t(a), d, q[0], q[1]),
                              atlas.attributes[a].components)
              ? 0
              : 1;
          }
        }
      }
    }
    for (int32_t d = 0; d < ch.maxLevel; ++d)
    {
      const int32_t n = 1 << d;
      for (int32_t j = 0; j <= n; ++j)
      {
        for (int32_t i = 0; i + j <= n; ++i)
        {
          for (size_t a = 0; a < atlas.attributes.size(); ++a)
          {
            mipMismatch += sameFloats(tc::atlasSample(atlas, c, int32_t(a), d, i, j),
                             tc::atlasSample(atlas, c, int32_t(a), d + 1, 2 * i, 2 * j),
                             atlas.attributes[a].components)
              ? 0
              : 1;
          }
        }
      }
    }
  }
  for (const auto& [vertex, list] : corners)
  {
    for (const auto& [c, k] : list)
    {
      const auto& [c0, k0] = list.front();
      for (size_t a = 0; a < atlas.attributes.size(); ++a)
      {
        const tc::AtlasChart& ch = atlas.charts[c];
        const tc::AtlasChart& ch0 = atlas.charts[c0];
        for (int32_t d = 0; d <= std::min(ch.maxLevel, ch0.maxLevel); ++d)
        {
          const auto p = tc::sidePoint(k, 0, 1 << d);
          const auto p0 = tc::sidePoint(k0, 0, 1 << d);
          cornerMismatch += sameFloats(tc::atlasSample(atlas, c, int32_t(a), d, p[0], p[1]),
                              tc::atlasSample(atlas, c0, int32_t(a), d, p0[0], p0[1]),
                              atlas.attributes[a].components)
            ? 0
            : 1;
        }
      }
    }
  }
  EXPECT_EQ(asymmetric, 0);
  EXPECT_EQ(sideMismatch, 0);
  EXPECT_EQ(cornerMismatch, 0);
  EXPECT_EQ(mipMismatch, 0);
}

int64_t finestSamples(const tc::Atlas& atlas)
{
  int64_t total = 0;
  for (const tc::AtlasChart& ch : atlas.charts)
  {
    total += samplesAt(ch.maxLevel);
  }
  return total;
}

/// Largest distance between a flat input triangle and the sphere through its corners.
double largestSagitta(const tc::TriMesh& m)
{
  double worst = 0.0;
  for (int64_t t = 0; t < m.numTriangles(); ++t)
  {
    const Vec a = m.point(m.triangles[3 * t]), b = m.point(m.triangles[3 * t + 1]),
              c = m.point(m.triangles[3 * t + 2]);
    const Vec ab = sub(b, a), ac = sub(c, a);
    const Vec n = cross(ab, ac);
    // Circumradius of the triangle.
    const double rho = norm(ab) * norm(ac) * norm(sub(c, b)) / (2.0 * norm(n));
    worst = std::max(worst, kRadius - std::sqrt(kRadius * kRadius - rho * rho));
  }
  return worst;
}

std::vector<double> patchAreas(const tc::PatchMesh& pm, int32_t charts)
{
  std::vector<double> area(charts, 0.0);
  const tc::TriMesh& m = pm.mesh;
  for (int64_t t = 0; t < m.numTriangles(); ++t)
  {
    const Vec a = m.point(m.triangles[3 * t]), b = m.point(m.triangles[3 * t + 1]),
              c = m.point(m.triangles[3 * t + 2]);
    area[pm.patchId[t]] += 0.5 * norm(cross(sub(b, a), sub(c, a)));
  }
  return area;
}

/// A synthetic input and its atlas, built once and shared by the tests (CGAL's optimal box
/// search costs tens of milliseconds per chart).
struct Case
{
  Synthetic input;
  tc::Atlas atlas;
};

/// The default options under the budget rule (no error target), whose sample counts the
/// synthetic cases pin.
tc::GeometryImageOptions budgetRule()
{
  tc::GeometryImageOptions options;
  options.errorTarget = 0.0;
  return options;
}

/// Options that interpolate the surface at every sample (no least-squares fit), so that the
/// samples lie on it; budget rule.
tc::GeometryImageOptions interpolating()
{
  tc::GeometryImageOptions options = budgetRule();
  options.fitSamples = false;
  return options;
}

/// The regular sphere, 16 x 16 triangles per octant, budget 0 (as many samples as points),
/// samples interpolated.
const Case& sphereCase()
{
  static const Case c = []
  {
    Case k{ sphere(16), {} };
    k.atlas = tc::buildGeometryImages(k.input.patches, k.input.base, {}, {}, {}, interpolating());
    return k;
  }();
  return c;
}

/// The same sphere with the default options under the budget rule: interior and side samples
/// fitted.
const Case& fittedSphereCase()
{
  static const Case c = []
  {
    Case k{ sphere(16), {} };
    k.atlas = tc::buildGeometryImages(k.input.patches, k.input.base, {}, {}, {}, budgetRule());
    return k;
  }();
  return c;
}

/// The sphere on an octahedron with its top tilted 60 degrees (octants from 2.1 to 10.3 in
/// area), budget 3000, with a 1- and a 2-component extra attribute linear in the position;
/// samples interpolated.
const Case& skewedCase()
{
  static const Case c = []
  {
    Case k{ sphere(16, 60.0), {} };
    const int64_t nv = k.input.patches.mesh.numPoints();
    tc::GeometryImageAttribute height{ "Height", 1, {} };
    tc::GeometryImageAttribute twice{ "Twice", 2, {} };
    for (int64_t v = 0; v < nv; ++v)
    {
      const Vec p = k.input.patches.mesh.point(v);
      height.values.push_back(p[2]);
      twice.values.insert(twice.values.end(), { 2.0 * p[0], -p[1] });
    }
    tc::GeometryImageOptions options = interpolating();
    options.sampleBudget = 3000;
    k.atlas =
      tc::buildGeometryImages(k.input.patches, k.input.base, {}, {}, { height, twice }, options);
    return k;
  }();
  return c;
}

/// The cube with feature edges, 8 x 8 triangles per base triangle, budget for level 4 each.
const Case& cubeCase()
{
  static const Case c = []
  {
    Case k{ cube(8), {} };
    tc::GeometryImageOptions options = budgetRule();
    options.sampleBudget = 12 * samplesAt(4);
    k.atlas = tc::buildGeometryImages(k.input.patches, k.input.base, {}, {}, {}, options);
    return k;
  }();
  return c;
}
} // namespace

TEST(GeometryImages, ParameterizationHasNoFlipAndFixesTheBoundaryByArcLength)
{
  for (const Synthetic& s : { sphere(12), sphere(12, 60.0), cube(8) })
  {
    const tc::PatchMesh& pm = s.patches;
    const tc::TriMesh& m = pm.mesh;
    const int32_t nc = static_cast<int32_t>(s.base.baseTriangles.size() / 3);
    for (int32_t c = 0; c < nc; ++c)
    {
      const tc::PatchParameterization p = tc::parameterizePatch(pm, s.base, c);
      EXPECT_EQ(p.flippedTriangles, 0) << "patch " << c;
      EXPECT_EQ(p.degenerateTriangles, 0) << "patch " << c;
      // Sphere patches: 12 x 12 triangles; cube patches: 8 x 8.
      EXPECT_EQ(p.triangles.size(), size_t(3) * (nc == 12 ? 64 : 144));
      EXPECT_EQ(p.boundaryPoints, nc == 12 ? 24 : 36);
      const int32_t* corner = &s.base.baseTriangles[3 * c];
      const double expected[3][2] = { { 0, 0 }, { 1, 0 }, { 0, 1 } };
      for (int k = 0; k < 3; ++k)
      {
        const auto it = std::lower_bound(p.points.begin(), p.points.end(), corner[k]);
        ASSERT_TRUE(it != p.points.end() && *it == corner[k]);
        const size_t l = static_cast<size_t>(it - p.points.begin());
        EXPECT_EQ(p.uv[2 * l], expected[k][0]);
        EXPECT_EQ(p.uv[2 * l + 1], expected[k][1]);
      }
      // Side 0 (corner 0 to corner 1) lies on v = 0 with u = arc-length fraction.
      const int32_t e = pm.faceEdges[3 * c];
      std::vector<int32_t> path(
        pm.pathPoints.begin() + pm.pathOffsets[e], pm.pathPoints.begin() + pm.pathOffsets[e + 1]);
      if (path.front() != corner[0])
      {
        std::reverse(path.begin(), path.end());
      }
      std::vector<double> arc(path.size(), 0.0);
      for (size_t i = 1; i < path.size(); ++i)
      {
        arc[i] = arc[i - 1] + norm(sub(m.point(path[i]), m.point(path[i - 1])));
      }
      for (size_t i = 0; i < path.size(); ++i)
      {
        const size_t l = static_cast<size_t>(
          std::lower_bound(p.points.begin(), p.points.end(), path[i]) - p.points.begin());
        EXPECT_NEAR(p.uv[2 * l], arc[i] / arc.back(), 1e-14);
        EXPECT_EQ(p.uv[2 * l + 1], 0.0);
      }
      // Interior points strictly inside the right triangle.
      int64_t inside = 0;
      for (size_t l = 0; l < p.points.size(); ++l)
      {
        const double u = p.uv[2 * l], v = p.uv[2 * l + 1];
        inside += u > 0.0 && v > 0.0 && u + v < 1.0 ? 1 : 0;
      }
      EXPECT_EQ(inside, static_cast<int64_t>(p.points.size()) - p.boundaryPoints);
    }
  }
}

TEST(GeometryImages, MeanValueMapOfAPlanarPatchIsAffine)
{
  // Mean-value coordinates reproduce linear functions: on a flat patch whose boundary is placed
  // by an affine map (arc length on straight sides is affine), every interior point must land on
  // the affine image, i.e. at its barycentric coordinates in the base triangle.
  const Synthetic s = cube(10);
  const tc::TriMesh& m = s.patches.mesh;
  double worst = 0.0;
  for (int32_t c = 0; c < 12; ++c)
  {
    const tc::PatchParameterization p = tc::parameterizePatch(s.patches, s.base, c);
    const Vec A = m.point(s.base.baseTriangles[3 * c]),
              B = m.point(s.base.baseTriangles[3 * c + 1]),
              C = m.point(s.base.baseTriangles[3 * c + 2]);
    const Vec n = cross(sub(B, A), sub(C, A));
    for (size_t l = 0; l < p.points.size(); ++l)
    {
      const Vec x = m.point(p.points[l]);
      const double l1 = dot(cross(sub(x, A), sub(C, A)), n) / dot(n, n);
      const double l2 = dot(cross(sub(B, A), sub(x, A)), n) / dot(n, n);
      worst = std::max({ worst, std::abs(p.uv[2 * l] - l1), std::abs(p.uv[2 * l + 1] - l2) });
    }
  }
  std::printf("[          ] planar patches: largest |uv - barycentric| %.3g\n", worst);
  EXPECT_LT(worst, 1e-12);
}

TEST(GeometryImages, SphereSamplesLieOnTheSphereWithinTheChordError)
{
  const Synthetic& s = sphereCase().input;
  const tc::Atlas& atlas = sphereCase().atlas;
  expectAtlasInvariants(atlas);
  const double sagitta = largestSagitta(s.patches.mesh);
  ASSERT_EQ(atlas.charts.size(), 8u);
  double below = 0.0, above = 0.0, worstNormal = 0.0;
  int64_t samples = 0;
  for (int32_t c = 0; c < 8; ++c)
  {
    const tc::AtlasChart& ch = atlas.charts[c];
    EXPECT_EQ(ch.maxLevel, atlas.charts[0].maxLevel) << "the eight octants are congruent";
    for (int32_t d = 0; d <= ch.maxLevel; ++d)
    {
      const int32_t n = 1 << d;
      for (int32_t j = 0; j <= n; ++j)
      {
        for (int32_t i = 0; i + j <= n; ++i)
        {
          const Vec p = toVec(tc::atlasSample(atlas, c, 0, d, i, j));
          const Vec q = toVec(tc::atlasSample(atlas, c, 1, d, i, j));
          const double r = norm(p);
          below = std::max(below, kRadius - r);
          above = std::max(above, r - kRadius);
          worstNormal = std::max(worstNormal, 1.0 - dot(p, q) / r);
          EXPECT_NEAR(norm(q), 1.0, 1e-6);
          ++samples;
        }
      }
    }
  }
  std::printf("[          ] sphere: d_max %d, %lld samples over all levels, below the sphere "
              "%.3g (input chord error %.3g), above %.3g, largest 1 - n.p/|p| %.3g\n",
    atlas.charts[0].maxLevel, static_cast<long long>(samples), below, sagitta, above, worstNormal);
  EXPECT_LE(below, sagitta + 1e-6);
  EXPECT_LE(above, 1e-6);
  EXPECT_LT(worstNormal, 1e-3);
  EXPECT_EQ(atlas.inputPoints, s.patches.mesh.numPoints());
  EXPECT_EQ(atlas.inputTriangles, s.patches.mesh.numTriangles());
  EXPECT_NEAR(atlas.inputDiagonal, 2.0 * kRadius * std::sqrt(3.0), 1e-12);
  // Budget 0: at most as many samples as input points.
  EXPECT_LE(finestSamples(atlas), s.patches.mesh.numPoints());
}

namespace
{
/// Largest and RMS distance from the sphere of the finest level's surface of `atlas`, at every
/// grid triangle's corners, edge midpoints and centroid.
std::pair<double, double> sphereDeviation(const tc::Atlas& atlas)
{
  double worst = 0.0, sum2 = 0.0;
  int64_t count = 0;
  auto at = [&](int32_t c, int32_t d, int32_t i, int32_t j)
  { return toVec(tc::atlasSample(atlas, c, 0, d, i, j)); };
  for (int32_t c = 0; c < static_cast<int32_t>(atlas.charts.size()); ++c)
  {
    const int32_t d = atlas.charts[c].maxLevel, n = 1 << d;
    for (int32_t j = 0; j < n; ++j)
    {
      for (int32_t i = 0; i + j < n; ++i)
      {
        for (int upper = 0; upper < (i + j + 1 < n ? 2 : 1); ++upper)
        {
          const Vec a = upper ? at(c, d, i + 1, j + 1) : at(c, d, i, j);
          const Vec b = upper ? at(c, d, i, j + 1) : at(c, d, i + 1, j);
          const Vec e = upper ? at(c, d, i + 1, j) : at(c, d, i, j + 1);
          const double w[7][3] = { { 1, 0, 0 }, { 0, 1, 0 }, { 0, 0, 1 }, { 0.5, 0.5, 0 },
            { 0, 0.5, 0.5 }, { 0.5, 0, 0.5 }, { 1 / 3.0, 1 / 3.0, 1 / 3.0 } };
          for (const auto& x : w)
          {
            Vec p{};
            for (int k = 0; k < 3; ++k)
            {
              p[k] = x[0] * a[k] + x[1] * b[k] + x[2] * e[k];
            }
            const double dev = std::abs(norm(p) - kRadius);
            worst = std::max(worst, dev);
            sum2 += dev * dev;
            ++count;
          }
        }
      }
    }
  }
  return { worst, std::sqrt(sum2 / static_cast<double>(count)) };
}
} // namespace

TEST(GeometryImages, FittedSamplesStraddleTheSphereAndHalveItsLargestDeviation)
{
  // Interpolated samples lie on the sphere and every grid triangle below it, by up to its
  // sagitta; fitted ones move out (sides too), so that the surface lies on both sides.
  const tc::Atlas& fitted = fittedSphereCase().atlas;
  const tc::Atlas& interpolated = sphereCase().atlas;
  expectAtlasInvariants(fitted);
  ASSERT_EQ(fitted.charts.size(), interpolated.charts.size());
  double above = 0.0, sideAbove = 0.0;
  for (int32_t c = 0; c < 8; ++c)
  {
    ASSERT_EQ(fitted.charts[c].maxLevel, interpolated.charts[c].maxLevel);
    const int32_t d = fitted.charts[c].maxLevel, n = 1 << d;
    for (int32_t j = 0; j <= n; ++j)
    {
      for (int32_t i = 0; i + j <= n; ++i)
      {
        const double r = norm(toVec(tc::atlasSample(fitted, c, 0, d, i, j)));
        above = std::max(above, r - kRadius);
        if (j == 0 && i > 0 && i < n)
        {
          sideAbove = std::max(sideAbove, r - kRadius);
        }
      }
    }
  }
  const auto [fitWorst, fitRms] = sphereDeviation(fitted);
  const auto [interpWorst, interpRms] = sphereDeviation(interpolated);
  std::printf("[          ] sphere, d_max %d: largest / RMS distance to the sphere %.3g / %.3g "
              "interpolated, %.3g / %.3g fitted; samples up to %.3g above it (sides %.3g)\n",
    fitted.charts[0].maxLevel, interpWorst, interpRms, fitWorst, fitRms, above, sideAbove);
  EXPECT_GT(sideAbove, 0.1 * interpWorst);
  EXPECT_LT(fitWorst, 0.6 * interpWorst);
  EXPECT_LT(fitRms, 0.6 * interpRms);
  // levelError is measured on the fitted samples.
  EXPECT_LT(fitted.charts[0].levelError.back(), interpolated.charts[0].levelError.back());
}

TEST(GeometryImages, SidesAreFittedAtTheLevelTheyAreDrawnAt)
{
  // The skewed sphere (32 x 32 triangles per octant) with fitted samples: neighbours of unequal
  // d_max. Eq. 8 draws a shared
  // side at the lower d_max m of its two charts, so that is the level it is fitted at: its
  // drawn chords then straddle the sphere (a fit at the finer chart's level would leave the
  // level-m samples almost on the sphere and every chord inside it by its full sagitta), and
  // the finer chart's samples between the drawn ones lie on the chords it is drawn with. (A
  // fit at the finer level gives 0.93 here.)
  tc::GeometryImageOptions options;
  options.sampleBudget = 1000; // d_max 3 and 4: sides drawn 8 segments long, 32 input edges
  const Synthetic s = sphere(32, 60.0);
  const tc::Atlas atlas = tc::buildGeometryImages(s.patches, s.base, {}, {}, {}, options);
  expectAtlasInvariants(atlas);
  int sides = 0;
  double chordRatio = 0.0, offLine = 0.0;
  for (int32_t c = 0; c < static_cast<int32_t>(atlas.charts.size()); ++c)
  {
    const tc::AtlasChart& ch = atlas.charts[c];
    for (int k = 0; k < 3; ++k)
    {
      const int32_t m = atlas.charts[ch.neighborChart[k]].maxLevel, n = ch.maxLevel;
      if (m >= n)
      {
        continue;
      }
      ++sides;
      const int32_t step = 1 << (n - m), big = 1 << n;
      auto at = [&](int32_t t)
      {
        const auto ij = tc::sidePoint(k, t, big);
        return toVec(tc::atlasSample(atlas, c, 0, n, ij[0], ij[1]));
      };
      // Drawn chords: their midpoints' distance to the sphere against the sagitta of the
      // same chords with their ends projected onto the sphere.
      double drawn = 0.0, sagitta = 0.0;
      for (int32_t t = 0; t < big; t += step)
      {
        const Vec a = at(t), b = at(t + step);
        const Vec mid{ 0.5 * (a[0] + b[0]), 0.5 * (a[1] + b[1]), 0.5 * (a[2] + b[2]) };
        drawn = std::max(drawn, std::abs(norm(mid) - kRadius));
        const double na = norm(a), nb = norm(b);
        const Vec pa{ a[0] * kRadius / na, a[1] * kRadius / na, a[2] * kRadius / na };
        const Vec pb{ b[0] * kRadius / nb, b[1] * kRadius / nb, b[2] * kRadius / nb };
        const Vec pm{ 0.5 * (pa[0] + pb[0]), 0.5 * (pa[1] + pb[1]), 0.5 * (pa[2] + pb[2]) };
        sagitta = std::max(sagitta, kRadius - norm(pm));
        for (int32_t r = 1; r < step; ++r)
        {
          const double w = static_cast<double>(r) / step;
          const Vec x = at(t + r);
          const Vec on{ a[0] + w * (b[0] - a[0]), a[1] + w * (b[1] - a[1]),
            a[2] + w * (b[2] - a[2]) };
          offLine = std::max(offLine, norm(sub(x, on)));
        }
      }
      chordRatio = std::max(chordRatio, drawn / sagitta);
    }
  }
  std::printf("[          ] skewed sphere, fitted: %d sides drawn coarser than their chart; "
              "drawn chords off the sphere by at most %.2f of their sagitta; finer samples "
              "off the drawn chords by at most %.2g\n",
    sides, chordRatio, offLine);
  ASSERT_GT(sides, 0) << "the test needs neighbours of different d_max";
  EXPECT_LT(chordRatio, 0.75);
  // The lattice snap (docs/atlas-format.md, version 4) moves the sample and the chord.
  EXPECT_LT(offLine, 1e-5 + 2.0 * latticeMove(atlas));
}

TEST(GeometryImages, SharedSidesAndCornersAreBitIdenticalAcrossUnequalLevels)
{
  const tc::Atlas& atlas = skewedCase().atlas;
  ASSERT_EQ(atlas.attributes.size(), 4u);
  EXPECT_EQ(atlas.attributes[2].name, "Height");
  EXPECT_EQ(atlas.attributes[2].components, 1);
  EXPECT_EQ(atlas.attributes[3].name, "Twice");
  EXPECT_EQ(atlas.attributes[3].components, 2);
  int32_t lo = 99, hi = -1, unequal = 0;
  for (const tc::AtlasChart& ch : atlas.charts)
  {
    lo = std::min(lo, ch.maxLevel);
    hi = std::max(hi, ch.maxLevel);
    for (int k = 0; k < 3; ++k)
    {
      unequal += atlas.charts[ch.neighborChart[k]].maxLevel != ch.maxLevel ? 1 : 0;
    }
  }
  std::printf("[          ] skewed sphere: d_max from %d to %d, %lld samples (budget 3000), %d "
              "chart sides with a neighbour of another d_max\n",
    lo, hi, static_cast<long long>(finestSamples(atlas)), unequal);
  EXPECT_GT(unequal, 0) << "the test needs neighbours of different d_max";
  expectAtlasInvariants(atlas);
  // The extra attributes follow the positions they were interpolated with.
  double worst = 0.0;
  for (int32_t c = 0; c < 8; ++c)
  {
    const int32_t d = atlas.charts[c].maxLevel, n = 1 << d;
    for (int32_t j = 0; j <= n; ++j)
    {
      for (int32_t i = 0; i + j <= n; ++i)
      {
        const float* p = tc::atlasSample(atlas, c, 0, d, i, j);
        const float* h = tc::atlasSample(atlas, c, 2, d, i, j);
        const float* t = tc::atlasSample(atlas, c, 3, d, i, j);
        worst = std::max({ worst, std::abs(double(h[0]) - p[2]),
          std::abs(double(t[0]) - 2.0 * p[0]), std::abs(double(t[1]) + p[1]) });
      }
    }
  }
  // The lattice snap moves a coordinate by at most half a step (twice that in 2 p[0]); the
  // extra attributes are not snapped.
  EXPECT_LT(worst, 1e-5 + latticeMove(atlas));
}

TEST(GeometryImages, CoarserLevelsAreEveryOtherSampleAndPackingKeepsChartsApart)
{
  // expectAtlasInvariants checks both (level d = every other sample of level d + 1, texels of
  // one chart each, inside the image, the rest 0); here on the cube at two budgets.
  tc::GeometryImageOptions options;
  options.sampleBudget = 200;
  options.minLevel = 1;
  const tc::Atlas coarse =
    tc::buildGeometryImages(cubeCase().input.patches, cubeCase().input.base, {}, {}, {}, options);
  for (const tc::Atlas* atlas : { &coarse, &cubeCase().atlas, &skewedCase().atlas })
  {
    expectAtlasInvariants(*atlas);
    const int64_t used = finestSamples(*atlas);
    const tc::AtlasImage& im = atlas->images[0];
    std::printf("[          ] %zu charts, d_max up to %d: %lld samples in image 0 of %d x %d "
                "(%.0f%% used), %zu images\n",
      atlas->charts.size(), atlas->maxLevel(), static_cast<long long>(used), im.width, im.height,
      100.0 * double(used) / (double(im.width) * im.height), atlas->images.size());
    // Paired rectangles waste little: at least 60% of the image holds samples.
    EXPECT_GT(double(used) / (double(im.width) * im.height), 0.6);
    for (const tc::AtlasChart& ch : atlas->charts)
    {
      EXPECT_GE(ch.partner, 0) << "an even number of charts: all paired";
      EXPECT_LE(std::abs(atlas->charts[ch.partner].maxLevel - ch.maxLevel), 1)
        << "partners have the closest d_max";
    }
  }
  EXPECT_LE(finestSamples(coarse), 200);
}

TEST(GeometryImages, BudgetIsRespectedAndLevelsFollowIt)
{
  const Synthetic s = sphere(12, 60.0);
  int64_t previous = 0;
  for (int64_t budget : { 1000, 4000, 16000 })
  {
    tc::GeometryImageOptions options;
    options.sampleBudget = budget;
    options.maxLevel = 6;
    const tc::Atlas atlas = tc::buildGeometryImages(s.patches, s.base, {}, {}, {}, options);
    const int64_t total = finestSamples(atlas);
    std::printf("[          ] budget %lld: %lld samples, d_max", static_cast<long long>(budget),
      static_cast<long long>(total));
    for (const tc::AtlasChart& ch : atlas.charts)
    {
      std::printf(" %d", ch.maxLevel);
      EXPECT_GE(ch.maxLevel, options.minLevel);
      EXPECT_LE(ch.maxLevel, options.maxLevel);
    }
    std::printf("\n");
    EXPECT_LE(total, budget);
    EXPECT_GT(total, previous);
    // One level more for the next charts would not fit, so the total is not far below.
    EXPECT_GT(total * 5, budget);
    previous = total;
  }
  // Below what minLevel needs: a clear error.
  tc::GeometryImageOptions tight;
  tight.sampleBudget = 8 * samplesAt(tight.minLevel) - 1;
  EXPECT_THROW(tc::buildGeometryImages(s.patches, s.base, {}, {}, {}, tight), tc::InputError);
}

TEST(GeometryImages, AreaRuleGivesLargerOrMoreCurvedPatchesFinerLevels)
{
  // Skewed octahedron: the octants on the far side of the tilted vertex are 5x larger than
  // those on its near side.
  const Synthetic& s = skewedCase().input;
  tc::GeometryImageOptions areaRule;
  areaRule.levelRule = tc::LevelRule::Area;
  tc::GeometryImageOptions skewedOptions = areaRule;
  skewedOptions.sampleBudget = 3000;
  const tc::Atlas atlas = tc::buildGeometryImages(s.patches, s.base, {}, {}, {}, skewedOptions);
  const std::vector<double> area = patchAreas(s.patches, 8);
  const auto big = std::max_element(area.begin(), area.end()) - area.begin();
  const auto small = std::min_element(area.begin(), area.end()) - area.begin();
  std::printf("[          ] patch areas from %.3f (d_max %d) to %.3f (d_max %d)\n", area[small],
    atlas.charts[small].maxLevel, area[big], atlas.charts[big].maxLevel);
  ASSERT_GT(area[big], 4.0 * area[small]);
  EXPECT_GT(atlas.charts[big].maxLevel, atlas.charts[small].maxLevel);
  for (int32_t a = 0; a < 8; ++a)
  {
    for (int32_t b = 0; b < 8; ++b)
    {
      if (area[a] > area[b] * (1.0 + 1e-9))
      {
        EXPECT_GE(atlas.charts[a].maxLevel, atlas.charts[b].maxLevel);
      }
    }
  }

  // Regular sphere: the octants are equal (sphereCase checks they get one d_max); 20x |H| on
  // octant 5 alone lifts its level above the others, unless the curvature weight is 0.
  const Synthetic& r = sphereCase().input;
  std::vector<double> H(r.patches.mesh.numPoints(), 1.0 / kRadius);
  for (size_t t = 0; t < r.patches.patchId.size(); ++t)
  {
    if (r.patches.patchId[t] == 5)
    {
      for (int k = 0; k < 3; ++k)
      {
        H[r.patches.mesh.triangles[3 * t + k]] = 20.0 / kRadius;
      }
    }
  }
  const tc::Atlas curved = tc::buildGeometryImages(r.patches, r.base, {}, H, {}, areaRule);
  for (int32_t c = 0; c < 8; ++c)
  {
    if (c != 5)
    {
      EXPECT_GT(curved.charts[5].maxLevel, curved.charts[c].maxLevel);
    }
  }
  std::printf("[          ] uniform d_max %d; with 20x |H| on one octant: %d there, %d elsewhere\n",
    sphereCase().atlas.charts[0].maxLevel, curved.charts[5].maxLevel, curved.charts[0].maxLevel);
  tc::GeometryImageOptions options = areaRule;
  options.curvatureWeight = 0.0;
  const tc::Atlas unweighted = tc::buildGeometryImages(r.patches, r.base, {}, H, {}, options);
  for (int32_t c = 0; c < 8; ++c)
  {
    EXPECT_EQ(unweighted.charts[c].maxLevel, unweighted.charts[0].maxLevel);
  }
}

/// The unit cube of cube(n) with a bump of height 0.3 on its top face (z = 1; charts 2 and 3):
/// z += 0.3 sin(pi x) sin(pi y) there, which leaves the cube's edges where they are.
Synthetic bumpedCube(int n)
{
  Synthetic s = cube(n);
  std::vector<double>& x = s.patches.mesh.points;
  for (size_t v = 0; v + 2 < x.size(); v += 3)
  {
    if (x[v + 2] == 1.0)
    {
      const double pi = 3.14159265358979323846;
      x[v + 2] += 0.3 * std::sin(pi * x[v]) * std::sin(pi * x[v + 1]);
    }
  }
  return s;
}

double largestFinestError(const tc::Atlas& atlas)
{
  double worst = 0.0;
  for (const tc::AtlasChart& ch : atlas.charts)
  {
    worst = std::max(worst, ch.levelError[static_cast<size_t>(ch.maxLevel)]);
  }
  return worst;
}

TEST(GeometryImages, ErrorRuleGivesACurvedRegionFinerLevelsThanAreaAlone)
{
  // A budget of level 4 for each of the 12 charts: the area rule spreads it evenly (the two
  // bumped charts are only 1.2x larger), the error rule moves it from the ten flat charts,
  // whose error is float rounding at any level, to the two bumped ones.
  const Synthetic s = bumpedCube(16);
  tc::GeometryImageOptions options;
  options.sampleBudget = 12 * samplesAt(4);
  options.levelRule = tc::LevelRule::Area;
  const tc::Atlas byArea = tc::buildGeometryImages(s.patches, s.base, {}, {}, {}, options);
  options.levelRule = tc::LevelRule::Error;
  const tc::Atlas byError = tc::buildGeometryImages(s.patches, s.base, {}, {}, {}, options);
  expectAtlasInvariants(byError);
  std::printf("[          ] bumped cube, d_max by area / by error:");
  for (int32_t c = 0; c < 12; ++c)
  {
    std::printf(" %d/%d", byArea.charts[c].maxLevel, byError.charts[c].maxLevel);
  }
  std::printf("\n[          ] largest finest levelError: area rule %.5f, error rule %.5f "
              "(samples %lld and %lld of %lld)\n",
    largestFinestError(byArea), largestFinestError(byError),
    static_cast<long long>(finestSamples(byArea)), static_cast<long long>(finestSamples(byError)),
    static_cast<long long>(options.sampleBudget));
  for (int32_t c = 0; c < 12; ++c)
  {
    if (c == 2 || c == 3)
    {
      EXPECT_GT(byError.charts[c].maxLevel, byArea.charts[c].maxLevel) << "bumped chart " << c;
      EXPECT_GT(byError.charts[c].levelError[0], 0.1) << "the bump is 0.3 high";
    }
    else
    {
      EXPECT_LT(byError.charts[c].maxLevel, byArea.charts[c].maxLevel) << "flat chart " << c;
      EXPECT_LT(byError.charts[c].levelError[0], 1e-6) << "flat chart " << c;
      EXPECT_EQ(byError.charts[c].maxLevel, byError.charts[0].maxLevel)
        << "flat charts tie and share the budget evenly";
    }
  }
  EXPECT_LE(finestSamples(byError), options.sampleBudget);
  EXPECT_LT(largestFinestError(byError), 0.75 * largestFinestError(byArea));
}

/// The cube with a narrow spike 0.8 high on chart 2, the top triangle (0,0,1), (1,0,1), (1,1,1),
/// centred on its centroid: a protrusion that the mean-value map squeezes.
Synthetic spikedCube(int n)
{
  Synthetic s = cube(n);
  std::vector<double>& x = s.patches.mesh.points;
  for (size_t v = 0; v + 2 < x.size(); v += 3)
  {
    if (x[v + 2] == 1.0)
    {
      const double dx = x[v] - 2.0 / 3.0, dy = x[v + 1] - 1.0 / 3.0;
      x[v + 2] += 0.8 * std::exp(-(dx * dx + dy * dy) / (0.06 * 0.06));
    }
  }
  return s;
}

TEST(GeometryImages, StretchReductionSpreadsSamplesOverASpike)
{
  const Synthetic s = spikedCube(48);
  tc::GeometryImageOptions floater;
  floater.stretchIterations = 0;
  const tc::GeometryImageOptions reduced;
  ASSERT_GT(reduced.stretchIterations, 0) << "stretch reduction is the default";
  const tc::PatchParameterization a = tc::parameterizePatch(s.patches, s.base, 2, floater);
  const tc::PatchParameterization b = tc::parameterizePatch(s.patches, s.base, 2, reduced);
  EXPECT_EQ(a.stretchIterations, 0);
  EXPECT_EQ(a.stretch, a.meanValueStretch);
  EXPECT_EQ(b.meanValueStretch, a.meanValueStretch);
  EXPECT_GE(b.stretchIterations, 1);
  EXPECT_LE(b.stretchIterations, reduced.stretchIterations);
  EXPECT_EQ(b.flippedTriangles, 0);
  EXPECT_EQ(b.degenerateTriangles, 0);
  // The boundary stays where Floater's map put it (arc length); only the interior moves.
  for (size_t l = 0; l < a.points.size(); ++l)
  {
    const double u = a.uv[2 * l], v = a.uv[2 * l + 1];
    if (u == 0.0 || v == 0.0 || u + v == 1.0)
    {
      EXPECT_EQ(b.uv[2 * l], u);
      EXPECT_EQ(b.uv[2 * l + 1], v);
    }
  }
  // Share of the triangle's parameter area given to the spike (points above z = 1.1).
  auto spikeShare = [&s](const tc::PatchParameterization& p)
  {
    double spike = 0.0;
    for (size_t t = 0; t < p.triangles.size() / 3; ++t)
    {
      const int32_t* c = &p.triangles[3 * t];
      const double* q0 = &p.uv[2 * c[0]];
      const double* q1 = &p.uv[2 * c[1]];
      const double* q2 = &p.uv[2 * c[2]];
      const double area =
        0.5 * ((q1[0] - q0[0]) * (q2[1] - q0[1]) - (q2[0] - q0[0]) * (q1[1] - q0[1]));
      bool high = true;
      for (int k = 0; k < 3; ++k)
      {
        high = high && s.patches.mesh.point(p.points[c[k]])[2] > 1.1;
      }
      spike += high ? area : 0.0;
    }
    return spike / 0.5;
  };
  // The same budget for both atlases: level 5 on every chart.
  floater.sampleBudget = 12 * samplesAt(5);
  tc::GeometryImageOptions reducedBudget = reduced;
  reducedBudget.sampleBudget = floater.sampleBudget;
  const tc::Atlas byFloater = tc::buildGeometryImages(s.patches, s.base, {}, {}, {}, floater);
  const tc::Atlas byReduced = tc::buildGeometryImages(s.patches, s.base, {}, {}, {}, reducedBudget);
  expectAtlasInvariants(byReduced);
  const tc::AtlasChart& f = byFloater.charts[2];
  const tc::AtlasChart& r = byReduced.charts[2];
  const int32_t d = std::min(f.maxLevel, r.maxLevel);
  std::printf("[          ] spike chart: L2 stretch %.3f -> %.3f after %d passes; parameter area "
              "of the spike %.4f -> %.4f; levelError at level %d %.4f -> %.4f; largest finest "
              "levelError %.4f -> %.4f\n",
    a.stretch, b.stretch, b.stretchIterations, spikeShare(a), spikeShare(b), d,
    f.levelError[static_cast<size_t>(d)], r.levelError[static_cast<size_t>(d)],
    largestFinestError(byFloater), largestFinestError(byReduced));
  EXPECT_LT(b.stretch, 0.8 * a.stretch);
  EXPECT_GT(spikeShare(b), 2.0 * spikeShare(a));
  EXPECT_LT(r.levelError[static_cast<size_t>(d)], 0.7 * f.levelError[static_cast<size_t>(d)]);
  EXPECT_LT(largestFinestError(byReduced), largestFinestError(byFloater));
  // Flat charts keep their affine map: the same error (float rounding) either way.
  for (int32_t c : { 0, 1, 4, 5 })
  {
    EXPECT_LT(byReduced.charts[c].levelError.back(), 1e-6) << "flat chart " << c;
  }
}

TEST(GeometryImages, ErrorRuleRespectsTheBudgetAndIsDeterministic)
{
  const Synthetic skewed = sphere(12, 60.0);
  const Synthetic bumped = bumpedCube(8);
  for (const Synthetic* s : { &skewed, &bumped })
  {
    const int32_t charts = static_cast<int32_t>(s->base.baseTriangles.size() / 3);
    for (int64_t budget : { charts * samplesAt(2), int64_t(1000), int64_t(4000), int64_t(16000) })
    {
      tc::GeometryImageOptions options;
      options.sampleBudget = budget;
      options.maxLevel = 6;
      const tc::Atlas a = tc::buildGeometryImages(s->patches, s->base, {}, {}, {}, options);
      const tc::Atlas b = tc::buildGeometryImages(s->patches, s->base, {}, {}, {}, options);
      options.levelRule = tc::LevelRule::Area;
      const tc::Atlas area = tc::buildGeometryImages(s->patches, s->base, {}, {}, {}, options);
      std::printf("[          ] %d charts, budget %lld: %lld samples by error (%lld by area), "
                  "largest finest error %.4f (%.4f by area)\n",
        charts, static_cast<long long>(budget), static_cast<long long>(finestSamples(a)),
        static_cast<long long>(finestSamples(area)), largestFinestError(a),
        largestFinestError(area));
      EXPECT_LE(finestSamples(a), budget);
      EXPECT_LE(largestFinestError(a), largestFinestError(area) * (1.0 + 1e-12));
      ASSERT_EQ(a.charts.size(), b.charts.size());
      for (size_t c = 0; c < a.charts.size(); ++c)
      {
        EXPECT_GE(a.charts[c].maxLevel, options.minLevel);
        EXPECT_LE(a.charts[c].maxLevel, options.maxLevel);
        EXPECT_EQ(a.charts[c].maxLevel, b.charts[c].maxLevel) << "chart " << c;
        EXPECT_EQ(a.charts[c].levelError, b.charts[c].levelError) << "chart " << c;
      }
      ASSERT_EQ(a.images.size(), b.images.size());
      for (size_t k = 0; k < a.images.size(); ++k)
      {
        EXPECT_EQ(a.images[k].data, b.images[k].data) << "image " << k;
      }
    }
  }
  // The rule must be one of the two.
  tc::GeometryImageOptions bad;
  bad.levelRule = static_cast<tc::LevelRule>(7);
  EXPECT_THROW(
    tc::buildGeometryImages(skewed.patches, skewed.base, {}, {}, {}, bad), tc::InputError);
}

TEST(GeometryImages, FeatureSidesKeepOneSidedNormalsAndIdenticalPositions)
{
  const Synthetic& s = cubeCase().input;
  const tc::Atlas& atlas = cubeCase().atlas;
  expectAtlasInvariants(atlas);
  const tc::TriMesh& m = s.patches.mesh;
  int64_t featureSides = 0, sharp = 0, off = 0, cornerSamples = 0;
  for (int32_t c = 0; c < 12; ++c)
  {
    const tc::AtlasChart& ch = atlas.charts[c];
    EXPECT_EQ(ch.maxLevel, 4);
    const Vec A = m.point(s.base.baseTriangles[3 * c]),
              B = m.point(s.base.baseTriangles[3 * c + 1]),
              C = m.point(s.base.baseTriangles[3 * c + 2]);
    Vec face = cross(sub(B, A), sub(C, A));
    const double l = norm(face);
    face = { face[0] / l, face[1] / l, face[2] / l };
    featureSides += ch.featureSide[0] + ch.featureSide[1] + ch.featureSide[2];
    EXPECT_EQ(ch.featureSide[0] + ch.featureSide[1] + ch.featureSide[2], 2)
      << "two cube edges and one diagonal";
    const int32_t n = 1 << ch.maxLevel;
    for (int32_t j = 0; j <= n; ++j)
    {
      for (int32_t i = 0; i + j <= n; ++i)
      {
        const bool corner = (i == 0 && j == 0) || i == n || j == n;
        const Vec q = toVec(tc::atlasSample(atlas, c, 1, ch.maxLevel, i, j));
        if (corner)
        {
          // The corner keeps the shared normal, the cube's corner diagonal, the same in every
          // chart (expectAtlasInvariants compared them bit for bit), up to the 0.041 degrees
          // of the atlas file's 12-bit octahedral normals (docs/atlas-format.md, version 4).
          EXPECT_NEAR(dot(q, face), 1.0 / std::sqrt(3.0), 1e-6 + 0.041 * 3.14159265358979 / 180);
          ++cornerSamples;
          continue;
        }
        // Every other sample, on a feature side, on the diagonal or inside, has the face normal.
        off += 1.0 - dot(q, face) > 1e-6 ? 1 : 0;
        sharp += (j == 0 && ch.featureSide[0]) || (i + j == n && ch.featureSide[1]) ||
            (i == 0 && ch.featureSide[2])
          ? 1
          : 0;
      }
    }
  }
  std::printf("[          ] cube: %lld feature sides, %lld one-sided samples on them, %lld "
              "samples off the face normal\n",
    static_cast<long long>(featureSides), static_cast<long long>(sharp),
    static_cast<long long>(off));
  EXPECT_EQ(featureSides, 24);
  EXPECT_EQ(off, 0);
  EXPECT_EQ(sharp, 12 * 2 * 15);
  EXPECT_EQ(cornerSamples, 36);
}

TEST(GeometryImages, OrientedBoxContainsEveryPatchPointAndSample)
{
  for (const Case* k : { &skewedCase(), &cubeCase(), &fittedSphereCase() })
  {
    const Synthetic& s = k->input;
    const tc::Atlas& atlas = k->atlas;
    const tc::TriMesh& m = s.patches.mesh;
    double outside = 0.0, skew = 0.0, volume = 0.0, aabbVolume = 0.0;
    for (size_t c = 0; c < atlas.charts.size(); ++c)
    {
      const std::array<double, 12>& b = atlas.charts[c].box;
      const Vec c0{ b[0], b[1], b[2] };
      Vec axis[3];
      double len[3];
      for (int k = 0; k < 3; ++k)
      {
        axis[k] = sub(Vec{ b[3 + 3 * k], b[4 + 3 * k], b[5 + 3 * k] }, c0);
        len[k] = norm(axis[k]);
      }
      for (int k = 0; k < 3; ++k)
      {
        for (int l = k + 1; l < 3; ++l)
        {
          if (len[k] > 1e-12 && len[l] > 1e-12)
          {
            skew = std::max(skew, std::abs(dot(axis[k], axis[l])) / (len[k] * len[l]));
          }
        }
      }
      volume += len[0] * len[1] * len[2];
      Vec lo{ 1e9, 1e9, 1e9 }, hi{ -1e9, -1e9, -1e9 };
      auto check = [&](const Vec& p, bool input)
      {
        for (int k = 0; k < 3; ++k)
        {
          const double t = len[k] > 0 ? dot(sub(p, c0), axis[k]) / len[k] : 0.0;
          outside = std::max({ outside, -t, t - len[k] });
          if (input)
          {
            lo[k] = std::min(lo[k], p[k]);
            hi[k] = std::max(hi[k], p[k]);
          }
        }
      };
      for (size_t t = 0; t < s.patches.patchId.size(); ++t)
      {
        if (s.patches.patchId[t] == static_cast<int32_t>(c))
        {
          for (int k = 0; k < 3; ++k)
          {
            check(m.point(s.patches.mesh.triangles[3 * t + k]), true);
          }
        }
      }
      aabbVolume += (hi[0] - lo[0]) * (hi[1] - lo[1]) * (hi[2] - lo[2]);
      const int32_t d = atlas.charts[c].maxLevel, n = 1 << d;
      for (int32_t j = 0; j <= n; ++j)
      {
        for (int32_t i = 0; i + j <= n; ++i)
        {
          check(toVec(tc::atlasSample(atlas, static_cast<int32_t>(c), 0, d, i, j)), false);
        }
      }
    }
    std::printf("[          ] boxes: farthest point or sample outside %.3g, largest axis cosine "
                "%.3g, total volume %.4f (axis-aligned boxes %.4f)\n",
      outside, skew, volume, aabbVolume);
    // Float samples may poke out by their rounding.
    EXPECT_LT(outside, 1e-6);
    // Corners are stored to 8 significant digits: the axes stay square to about 1e-7.
    EXPECT_LT(skew, 1e-6);
    EXPECT_LE(volume, aabbVolume + 1e-12);
  }
}

TEST(GeometryImages, LevelErrorShrinksWithTheLevelAndBoundsTheSurfaceDistance)
{
  const Synthetic& s = sphereCase().input;
  tc::GeometryImageOptions options;
  options.sampleBudget = 8 * samplesAt(5);
  const tc::Atlas atlas = tc::buildGeometryImages(s.patches, s.base, {}, {}, {}, options);
  const tc::AtlasChart& ch = atlas.charts[0];
  ASSERT_EQ(ch.maxLevel, 5);
  std::printf("[          ] sphere octant (16 x 16 input) levelError / radius:");
  for (double e : ch.levelError)
  {
    std::printf(" %.4f", e / kRadius);
  }
  std::printf("\n");
  // Level 0 is the flat triangle of the three corners: the bound cannot be below the largest
  // distance of a patch point from that plane, and nothing is farther than the radius.
  const tc::TriMesh& m = s.patches.mesh;
  const Vec A = m.point(s.base.baseTriangles[0]), B = m.point(s.base.baseTriangles[1]),
            C = m.point(s.base.baseTriangles[2]);
  Vec n = cross(sub(B, A), sub(C, A));
  const double l = norm(n);
  n = { n[0] / l, n[1] / l, n[2] / l };
  double fromPlane = 0.0;
  for (size_t t = 0; t < s.patches.patchId.size(); ++t)
  {
    if (s.patches.patchId[t] == 0)
    {
      for (int k = 0; k < 3; ++k)
      {
        fromPlane = std::max(fromPlane, std::abs(dot(sub(m.point(m.triangles[3 * t + k]), A), n)));
      }
    }
  }
  EXPECT_GE(ch.levelError[0], fromPlane * (1.0 - 1e-6));
  EXPECT_LE(ch.levelError[0], kRadius);
  for (size_t d = 1; d < ch.levelError.size(); ++d)
  {
    EXPECT_LT(ch.levelError[d], ch.levelError[d - 1]);
  }
  // While the grid is coarser than the input, the piecewise-linear error falls ~4x per level;
  // finer than the input (16 x 16 here) it only halves, bounded by the input's own corners.
  EXPECT_LT(ch.levelError[3], ch.levelError[1] / 8.0);
  // Flat patches are reproduced exactly at every level (up to float rounding).
  for (const tc::AtlasChart& f : cubeCase().atlas.charts)
  {
    for (double e : f.levelError)
    {
      EXPECT_LT(e, 1e-6);
    }
  }
}

TEST(GeometryImages, LevelErrorBoundsTheDeviationAlongCreasesBetweenPatchPoints)
{
  // An octahedron of 2 x 2 triangles per face whose edge midpoints are moved out 3x and along
  // their edge: each patch's middle triangle meets the three corner ones at creases that run
  // across the grid between two side points. The grid, finer than the patch, cuts across each
  // crease between its points, where the largest deviation is: levelError must include it.
  // Measured at the patch points alone (as before) it was 3.2x too small here.
  constexpr double lift = 3.0, shift = 0.3;
  const Synthetic s =
    subdivide({ { 1, 0, 0 }, { -1, 0, 0 }, { 0, 1, 0 }, { 0, -1, 0 }, { 0, 0, 1 }, { 0, 0, -1 } },
      octahedronFaces(), 2,
      [](const Vec& p)
      {
        // Edge midpoints: one coordinate 0, two of magnitude 1/2.
        int zero = -1, half = 0;
        for (int x = 0; x < 3; ++x)
        {
          zero = std::abs(p[x]) < 1e-9 ? x : zero;
          half += std::abs(std::abs(p[x]) - 0.5) < 1e-9 ? 1 : 0;
        }
        if (zero < 0 || half != 2)
        {
          return p;
        }
        const int a = (zero + 1) % 3, b = (zero + 2) % 3;
        Vec q = p;
        q[a] += shift * (p[a] > 0 ? 1 : -1);
        q[b] -= shift * (p[b] > 0 ? 1 : -1);
        return Vec{ lift * q[0], lift * q[1], lift * q[2] };
      });
  tc::GeometryImageOptions options = interpolating();
  options.sampleBudget = 8 * samplesAt(4);
  const tc::Atlas atlas = tc::buildGeometryImages(s.patches, s.base, {}, {}, {}, options);
  const tc::TriMesh& m = s.patches.mesh;
  int creases = 0;
  double worstRatio = 0.0;
  for (int32_t c = 0; c < 8; ++c)
  {
    const tc::AtlasChart& ch = atlas.charts[c];
    const tc::PatchParameterization p = tc::parameterizePatch(s.patches, s.base, c, options);
    const size_t nt = p.triangles.size() / 3;
    auto corner = [&](size_t t, int k) { return m.point(p.points[p.triangles[3 * t + k]]); };
    std::vector<Vec> normal(nt);
    for (size_t t = 0; t < nt; ++t)
    {
      normal[t] = cross(sub(corner(t, 1), corner(t, 0)), sub(corner(t, 2), corner(t, 0)));
    }
    for (size_t t = 0; t < nt; ++t)
    {
      for (int k = 0; k < 3; ++k)
      {
        const int32_t a = p.triangles[3 * t + k], b = p.triangles[3 * t + (k + 1) % 3];
        // The triangle across a -> b runs b -> a; each inner edge is taken once, from t.
        size_t across = nt;
        for (size_t o = 0; o < nt; ++o)
        {
          for (int q = 0; q < 3; ++q)
          {
            across =
              p.triangles[3 * o + q] == b && p.triangles[3 * o + (q + 1) % 3] == a ? o : across;
          }
        }
        if (across == nt || a > b ||
          dot(normal[t], normal[across]) > std::cos(45.0 * 3.14159265358979323846 / 180.0) *
              norm(normal[t]) * norm(normal[across]))
        {
          continue;
        }
        ++creases;
        for (int32_t d = 0; d <= ch.maxLevel; ++d)
        {
          const int32_t n = 1 << d;
          double worst = 0.0;
          for (int step = 0; step <= 400; ++step)
          {
            const double w = step / 400.0;
            const double u = (1 - w) * p.uv[2 * a] + w * p.uv[2 * b];
            const double v = (1 - w) * p.uv[2 * a + 1] + w * p.uv[2 * b + 1];
            const Vec A = m.point(p.points[a]), B = m.point(p.points[b]);
            const Vec P{ (1 - w) * A[0] + w * B[0], (1 - w) * A[1] + w * B[1],
              (1 - w) * A[2] + w * B[2] };
            // The level-d grid triangle at (u, v) and its barycentrics.
            const double x = std::clamp(u, 0.0, 1.0) * n, y = std::clamp(v, 0.0, 1.0) * n;
            const int32_t i = std::clamp(static_cast<int32_t>(std::floor(x)), 0, n - 1);
            const int32_t j = std::clamp(static_cast<int32_t>(std::floor(y)), 0, n - 1 - i);
            const double fx = x - i, fy = y - j;
            int32_t gi[3], gj[3];
            double gw[3];
            if (fx + fy <= 1.0 || i + j + 1 >= n)
            {
              gi[0] = i, gj[0] = j, gi[1] = i + 1, gj[1] = j, gi[2] = i, gj[2] = j + 1;
              gw[0] = 1.0 - fx - fy, gw[1] = fx, gw[2] = fy;
            }
            else
            {
              gi[0] = i + 1, gj[0] = j + 1, gi[1] = i, gj[1] = j + 1, gi[2] = i + 1, gj[2] = j;
              gw[0] = fx + fy - 1.0, gw[1] = 1.0 - fx, gw[2] = 1.0 - fy;
            }
            Vec r{ 0, 0, 0 };
            for (int q = 0; q < 3; ++q)
            {
              const Vec g = toVec(tc::atlasSample(atlas, c, 0, d, gi[q], gj[q]));
              r = { r[0] + gw[q] * g[0], r[1] + gw[q] * g[1], r[2] + gw[q] * g[2] };
            }
            worst = std::max(worst, norm(sub(r, P)));
          }
          EXPECT_LE(worst, ch.levelError[d] * (1.0 + 1e-6) + 1e-6)
            << "chart " << c << " level " << d << " crease " << a << "-" << b;
          worstRatio = std::max(worstRatio, worst / ch.levelError[d]);
        }
      }
    }
  }
  std::printf("[          ] folded octahedron: %d crease edges inside patches; the deviation "
              "along them reaches %.3f of levelError\n",
    creases, worstRatio);
  ASSERT_GT(creases, 0);
  EXPECT_GT(worstRatio, 0.9) << "the bound is not loose on creases";
}

TEST(GeometryImages, RebuiltMeshIsClosedAndLevelErrorBoundsTheInputPoints)
{
  const Synthetic& s = skewedCase().input;
  const tc::Atlas& atlas = skewedCase().atlas;
  // Charts at levels 0 .. 5 side by side: stitching by eq. 8 must close every seam.
  std::vector<int32_t> levels;
  for (size_t c = 0; c < atlas.charts.size(); ++c)
  {
    levels.push_back(static_cast<int32_t>(c % 6));
  }
  const tc::RebuiltMesh mixed = tc::rebuildMesh(atlas, levels);
  const tc::EdgeTable edges = tc::buildEdgeTable(mixed.mesh.triangles);
  int64_t open = 0;
  for (int64_t e = 0; e < edges.numEdges(); ++e)
  {
    open += edges.valence(e) != 2 ? 1 : 0;
  }
  EXPECT_EQ(open, 0);
  EXPECT_EQ(mixed.mesh.numPoints() - edges.numEdges() + mixed.mesh.numTriangles(), 2) << "a sphere";

  // Every chart at level 4 (no stitching): each input point is at most its chart's
  // levelError[4] from the rebuilt surface.
  const tc::RebuiltMesh uniform = tc::rebuildMesh(atlas, 4);
  tc::SurfaceDistanceOptions options;
  options.samplesPerMesh = 20000;
  const tc::SurfaceDistanceResult dist = tc::surfaceDistance(s.patches.mesh, uniform.mesh, options);
  std::vector<double> bound(s.patches.mesh.numPoints(), 0.0);
  for (size_t t = 0; t < s.patches.patchId.size(); ++t)
  {
    for (int k = 0; k < 3; ++k)
    {
      double& b = bound[s.patches.mesh.triangles[3 * t + k]];
      b = std::max(b, atlas.charts[s.patches.patchId[t]].levelError[4]);
    }
  }
  int64_t above = 0;
  double tightest = 0.0;
  for (size_t v = 0; v < bound.size(); ++v)
  {
    above += dist.pointDistance[v] > bound[v] + 1e-6 ? 1 : 0;
    tightest = std::max(tightest, dist.pointDistance[v] / bound[v]);
  }
  std::printf("[          ] rebuilt at level 4: Hausdorff %.3g of the diagonal, input points at "
              "most %.2f of their chart's levelError[4]\n",
    dist.hausdorff / dist.diagonal, tightest);
  EXPECT_EQ(above, 0);
  EXPECT_GT(tightest, 0.5) << "the bound is not loose";
}

TEST(GeometryImages, SphereCutLikeTracedPathsGivesAValidAtlas)
{
  // Steiner points, sliver pieces and paths that cut across the input triangles, as tracePaths
  // makes them.
  const Synthetic s = cutSphere(3, 0.3);
  const tc::PatchMesh& pm = s.patches;
  int64_t steiner = 0, flipped = 0, degenerate = 0;
  for (int32_t id : pm.inputPointId)
  {
    steiner += id < 0 ? 1 : 0;
  }
  for (int32_t c = 0; c < 8; ++c)
  {
    const tc::PatchParameterization p = tc::parameterizePatch(pm, s.base, c);
    flipped += p.flippedTriangles;
    degenerate += p.degenerateTriangles;
  }
  const tc::Atlas atlas = tc::buildGeometryImages(pm, s.base, {}, {}, {}, interpolating());
  std::printf("[          ] cut sphere: %lld points (%lld Steiner), %lld pieces of %lld input "
              "triangles; %lld flipped, %lld degenerate uv triangles; d_max %d\n",
    static_cast<long long>(pm.mesh.numPoints()), static_cast<long long>(steiner),
    static_cast<long long>(pm.mesh.numTriangles()), static_cast<long long>(atlas.inputTriangles),
    static_cast<long long>(flipped), static_cast<long long>(degenerate), atlas.maxLevel());
  EXPECT_GT(steiner, 0);
  EXPECT_EQ(flipped, 0);
  EXPECT_EQ(degenerate, 0);
  EXPECT_EQ(atlas.inputPoints, pm.mesh.numPoints() - steiner);
  EXPECT_EQ(atlas.inputTriangles, 1280);
  EXPECT_LE(finestSamples(atlas), atlas.inputPoints);
  expectAtlasInvariants(atlas);
  // Samples on the sphere within the chord error of the pieces (Steiner points lie on chords).
  double below = 0.0, above = 0.0;
  for (int32_t c = 0; c < 8; ++c)
  {
    const int32_t d = atlas.charts[c].maxLevel, n = 1 << d;
    for (int32_t j = 0; j <= n; ++j)
    {
      for (int32_t i = 0; i + j <= n; ++i)
      {
        const double r = norm(toVec(tc::atlasSample(atlas, c, 0, d, i, j)));
        below = std::max(below, kRadius - r);
        above = std::max(above, r - kRadius);
      }
    }
  }
  // The input triangles (on the moved axis vertices) bound how far below the sphere a piece
  // of them reaches.
  tc::TriMesh input;
  input.points.assign(pm.mesh.points.begin(), pm.mesh.points.begin() + 3 * atlas.inputPoints);
  input.triangles = tctest::jitteredSphere(kRadius, 3, 0.3).mesh.triangles;
  std::printf(
    "[          ] below the sphere %.3g, input chord error %.3g\n", below, largestSagitta(input));
  EXPECT_LE(below, largestSagitta(input) + 1e-6);
  EXPECT_LE(above, 1e-6);
  // Every level stitched together closes the sphere.
  std::vector<int32_t> levels;
  for (int32_t c = 0; c < 8; ++c)
  {
    levels.push_back(c % (atlas.charts[c].maxLevel + 1));
  }
  const tc::RebuiltMesh mixed = tc::rebuildMesh(atlas, levels);
  const tc::EdgeTable edges = tc::buildEdgeTable(mixed.mesh.triangles);
  int64_t open = 0;
  for (int64_t e = 0; e < edges.numEdges(); ++e)
  {
    open += edges.valence(e) != 2 ? 1 : 0;
  }
  EXPECT_EQ(open, 0);
}

TEST(GeometryImages, TriangleWithAllCornersOnOnePathIsFlattenedNotFlipped)
{
  // Retriangulate around the middle point P of side 0 of patch 0 so that one triangle has the
  // three consecutive path points P-, P, P+ as corners (Floater's theorem excludes such a
  // triangle: it can only map to a segment of the straight side). Before: (P-, P, A), (P, B, A),
  // (P, P+, B); after: (P-, P, P+), (P-, P+, B), (P-, B, A).
  Synthetic s = sphere(8);
  tc::PatchMesh& pm = s.patches;
  const int32_t e = pm.faceEdges[0];
  const int64_t m = (pm.pathOffsets[e] + pm.pathOffsets[e + 1]) / 2;
  const int32_t P = pm.pathPoints[m], Pm = pm.pathPoints[m - 1], Pp = pm.pathPoints[m + 1];
  int32_t t1 = -1, t2 = -1, t3 = -1, A = -1, B = -1;
  for (int32_t t = 0; t < static_cast<int32_t>(pm.patchId.size()); ++t)
  {
    const int32_t* c = &pm.mesh.triangles[3 * t];
    const bool hasP = c[0] == P || c[1] == P || c[2] == P;
    if (pm.patchId[t] != 0 || !hasP)
    {
      continue;
    }
    auto other = [&](int32_t x, int32_t y)
    {
      for (int k = 0; k < 3; ++k)
      {
        if (c[k] != x && c[k] != y)
        {
          return c[k];
        }
      }
      return -1;
    };
    if (c[0] == Pm || c[1] == Pm || c[2] == Pm)
    {
      t1 = t;
      A = other(P, Pm);
    }
    else if (c[0] == Pp || c[1] == Pp || c[2] == Pp)
    {
      t3 = t;
      B = other(P, Pp);
    }
    else
    {
      t2 = t;
    }
  }
  ASSERT_TRUE(t1 >= 0 && t2 >= 0 && t3 >= 0);
  auto set = [&pm](int32_t t, int32_t a, int32_t b, int32_t c)
  {
    pm.mesh.triangles[3 * t] = a;
    pm.mesh.triangles[3 * t + 1] = b;
    pm.mesh.triangles[3 * t + 2] = c;
  };
  set(t1, Pm, P, Pp);
  set(t2, Pm, Pp, B);
  set(t3, Pm, B, A);
  const tc::PatchParameterization p = tc::parameterizePatch(pm, s.base, 0);
  EXPECT_EQ(p.flippedTriangles, 0);
  EXPECT_EQ(p.degenerateTriangles, 1);
  const tc::Atlas atlas = tc::buildGeometryImages(pm, s.base, {}, {}, {});
  expectAtlasInvariants(atlas);
  double below = 0.0;
  const int32_t d = atlas.charts[0].maxLevel, n = 1 << d;
  for (int32_t j = 0; j <= n; ++j)
  {
    for (int32_t i = 0; i + j <= n; ++i)
    {
      below = std::max(below, kRadius - norm(toVec(tc::atlasSample(atlas, 0, 0, d, i, j))));
    }
  }
  EXPECT_LE(below, largestSagitta(pm.mesh) + 1e-6);
}

TEST(GeometryImages, ReportsProgressAndHonoursAbort)
{
  const Synthetic s = sphere(8, 30.0);
  tctest::expectProgressAndAbort([&](const tc::Progress& p)
    { tc::buildGeometryImages(s.patches, s.base, {}, {}, {}, {}, p); },
    4, [calls = 0](double) mutable { return ++calls < 3; });
}

TEST(GeometryImages, RejectsInputThatDoesNotMatchOrIsNotAPatchDisk)
{
  const Synthetic s = sphere(4);
  const int64_t nv = s.patches.mesh.numPoints();
  auto build = [&](const tc::PatchMesh& pm, const tc::BaseComplexResult& base)
  { return tc::buildGeometryImages(pm, base, {}, {}, {}); };

  tc::PatchMesh pm = s.patches;
  pm.patchId.pop_back();
  EXPECT_THROW(build(pm, s.base), tc::InputError);
  pm = s.patches;
  pm.patchId[0] = 1; // a triangle of patch 0 handed to patch 1: neither is a disk any more
  EXPECT_THROW(build(pm, s.base), tc::InputError);
  EXPECT_THROW(tc::parameterizePatch(pm, s.base, 0), tc::InputError);
  EXPECT_THROW(tc::parameterizePatch(pm, s.base, 1), tc::InputError);
  EXPECT_NO_THROW(tc::parameterizePatch(pm, s.base, 2));
  pm = s.patches;
  std::swap(pm.pathPoints[1], pm.pathPoints[2]); // a path that leaves the patch boundary
  EXPECT_THROW(build(pm, s.base), tc::InputError);
  pm = s.patches;
  pm.inputPointId[0] = -1; // base vertex 0 made a Steiner point
  EXPECT_THROW(build(pm, s.base), tc::InputError);
  pm = s.patches;
  pm.faceEdges[0] = pm.faceEdges[1];
  EXPECT_THROW(build(pm, s.base), tc::InputError);
  pm = s.patches;
  std::swap(pm.mesh.triangles[0], pm.mesh.triangles[1]); // one triangle turned over
  EXPECT_THROW(build(pm, s.base), tc::InputError);

  tc::BaseComplexResult base = s.base;
  base.baseEdgeIsFeature.pop_back();
  EXPECT_THROW(build(s.patches, base), tc::InputError);
  base = s.base;
  std::swap(base.baseTriangles[0], base.baseTriangles[1]);
  EXPECT_THROW(build(s.patches, base), tc::InputError);

  EXPECT_THROW(tc::buildGeometryImages(s.patches, s.base, std::vector<double>(3 * nv - 3), {}, {}),
    tc::InputError);
  EXPECT_THROW(tc::buildGeometryImages(s.patches, s.base, {}, std::vector<double>(nv + 1), {}),
    tc::InputError);
  EXPECT_THROW(tc::buildGeometryImages(s.patches, s.base, {}, {},
                 { tc::GeometryImageAttribute{ "Position", 1, std::vector<double>(nv) } }),
    tc::InputError);
  EXPECT_THROW(tc::buildGeometryImages(s.patches, s.base, {}, {},
                 { tc::GeometryImageAttribute{ "A", 2, std::vector<double>(nv) } }),
    tc::InputError);
  tc::GeometryImageOptions options;
  options.minLevel = 5;
  options.maxLevel = 4;
  EXPECT_THROW(tc::buildGeometryImages(s.patches, s.base, {}, {}, {}, options), tc::InputError);
  options = {};
  options.maxLevel = 13;
  EXPECT_THROW(tc::buildGeometryImages(s.patches, s.base, {}, {}, {}, options), tc::InputError);
  EXPECT_THROW(tc::parameterizePatch(s.patches, s.base, 8), tc::InputError);
  {
    tc::GeometryImageOptions bad;
    bad.stretchIterations = -1;
    EXPECT_THROW(tc::parameterizePatch(s.patches, s.base, 0, bad), tc::InputError);
    bad.stretchIterations = 101;
    EXPECT_THROW(tc::buildGeometryImages(s.patches, s.base, {}, {}, {}, bad), tc::InputError);
  }
}
