// SPDX-License-Identifier: BSD-3-Clause
#include "gim/resampling.h"

#include "tc/skinning/skin.h"

#include "gim/geometry_images_vec3.h"
#include "gim/uv_locator.h"

#include <algorithm>
#include <cmath>

namespace tc::detail::geometry_images
{
namespace
{
/// Angle-weighted normals (Thürmer and Wüthrich) from the triangles listed, added to row
/// index[k + 3 t] of `normals` for corner k of triangle t (to row of the mesh point when
/// `index` is empty).
void accumulateNormals(const TriMesh& mesh, const int32_t* triangles, int64_t count,
  const std::vector<int32_t>& index, std::vector<double>& normals)
{
  for (int64_t t = 0; t < count; ++t)
  {
    const int32_t* c = &mesh.triangles[3 * static_cast<int64_t>(triangles[t])];
    const Vec3 p[3] = { pointOf(mesh, c[0]), pointOf(mesh, c[1]), pointOf(mesh, c[2]) };
    const Vec3 n = (p[1] - p[0]).cross(p[2] - p[0]);
    const double len = n.norm();
    if (!(len > 0.0))
    {
      continue;
    }
    for (int k = 0; k < 3; ++k)
    {
      const Vec3 e1 = p[(k + 1) % 3] - p[k], e2 = p[(k + 2) % 3] - p[k];
      const double angle = std::atan2(e1.cross(e2).norm(), e1.dot(e2));
      const int64_t v = index.empty() ? c[k] : index[k + 3 * t];
      for (int x = 0; x < 3; ++x)
      {
        normals[3 * v + x] += angle * n[x] / len;
      }
    }
  }
}

void normalizeRows(std::vector<double>& v)
{
  for (size_t i = 0; i + 2 < v.size(); i += 3)
  {
    const double len = std::sqrt(v[i] * v[i] + v[i + 1] * v[i + 1] + v[i + 2] * v[i + 2]);
    if (len > 0.0)
    {
      v[i] /= len;
      v[i + 1] /= len;
      v[i + 2] /= len;
    }
  }
}

/// The skin (tc::blendInfluences) of `count` points of the influences attribute `x` with
/// barycentric weights `w`, written as kSkinValues floats (joints, weights) to `out`.
void blendedInfluences(
  const GeometryImageAttribute& x, int count, const int64_t* points, const double* w, float* out)
{
  PointSkin skins[3];
  for (int p = 0; p < count; ++p)
  {
    const double* row = &x.values[static_cast<size_t>(points[p]) * kSkinValues];
    for (int k = 0; k < kMaxInfluences; ++k)
    {
      skins[p].joints[k] = static_cast<int32_t>(row[k]);
      skins[p].weights[k] = static_cast<float>(row[kMaxInfluences + k]);
    }
  }
  const PointSkin skin = blendInfluences(count, skins, w);
  std::transform(skin.joints.begin(), skin.joints.end(), out, [](int32_t j) { return float(j); });
  std::copy(skin.weights.begin(), skin.weights.end(), out + kMaxInfluences);
}

/// Index of point v in the ascending points of a patch that holds it.
int32_t patchIndex(const PatchParameterization& p, int32_t v)
{
  return static_cast<int32_t>(
    std::lower_bound(p.points.begin(), p.points.end(), v) - p.points.begin());
}

/// The values of point v: position, shared normal, extra attributes, as floats.
void sharedValues(const SamplingInput& in, int64_t v, float* out)
{
  for (int x = 0; x < 3; ++x)
  {
    out[x] = static_cast<float>(in.patches.mesh.points[3 * v + x]);
    out[3 + x] = static_cast<float>(in.shared[3 * v + x]);
  }
  for (size_t a = 0; a < in.extra.size(); ++a)
  {
    const int32_t nComp = in.extra[a].components;
    for (int32_t x = 0; x < nComp; ++x)
    {
      out[in.S.offset[a + 2] + x] = static_cast<float>(in.extra[a].values[v * nComp + x]);
    }
  }
}

/// The normal at end `end` (0: lower base vertex) of path e: the shared one, except where the
/// path is no feature but its end is on a feature curve, where the shared normal averages across
/// the crease: there the normal of the two charts' own triangles (e.g. the face normal where a
/// diagonal meets a cube corner).
Vec3 pathEndNormal(const SamplingInput& in, int32_t e, int end)
{
  const PatchMesh& pm = in.patches;
  const TriMesh& mesh = pm.mesh;
  const Layout& L = in.L;
  const int32_t v = pm.pathPoints[end == 0 ? pm.pathOffsets[e] : pm.pathOffsets[e + 1] - 1];
  Vec3 normal = rowOf(in.shared, v);
  if (L.edgeFeature[e] || !in.featureVertex[pm.baseEdges[2 * e + end]])
  {
    return normal;
  }
  std::vector<int32_t> around;
  for (int side = 0; side < 2; ++side)
  {
    const int32_t c = L.edgeChart[2 * e + side];
    for (int64_t s = L.patchOffsets[c]; s < L.patchOffsets[c + 1]; ++s)
    {
      const int32_t* t = &mesh.triangles[3 * int64_t(L.patchTriangles[s])];
      if (t[0] == v || t[1] == v || t[2] == v)
      {
        around.push_back(L.patchTriangles[s]);
      }
    }
  }
  std::vector<int32_t> slot(3 * around.size(), 0);
  for (size_t t = 0; t < around.size(); ++t)
  {
    for (int k = 0; k < 3; ++k)
    {
      slot[3 * t + k] = mesh.triangles[3 * int64_t(around[t]) + k] == v ? 0 : 1;
    }
  }
  std::vector<double> acc(6, 0.0);
  accumulateNormals(mesh, around.data(), static_cast<int64_t>(around.size()), slot, acc);
  const Vec3 n(acc[0], acc[1], acc[2]);
  if (n.norm() > 0.0)
  {
    normal = n.normalized();
  }
  return normal;
}

/// Sample q of 2^level + 1 of path e, at arc length q / 2^level of the way along it: the point
/// of its piece there and every value interpolated between the piece's two points.
void samplePathAt(const SamplingInput& in, int32_t e, const std::vector<double>& arc,
  const Vec3 (&endNormal)[2], int64_t q, PathSamples& ps)
{
  const PatchMesh& pm = in.patches;
  const int64_t q1 = int64_t(1) << ps.level;
  const int64_t p0 = pm.pathOffsets[e], p1 = pm.pathOffsets[e + 1];
  const int64_t last = p1 - p0 - 1;
  float* out = &ps.values[q * in.S.size];
  if (q == 0 || q == q1)
  {
    // The corners: the base vertex's own values.
    ps.segment[q] = q == 0 ? 0 : static_cast<int32_t>(p1 - p0 - 2);
    ps.tau[q] = q == 0 ? 0.0 : 1.0;
    sharedValues(in, pm.pathPoints[q == 0 ? p0 : p1 - 1], out);
    return;
  }
  const double length = arc.back();
  const double s = length * static_cast<double>(q) / static_cast<double>(q1);
  int64_t i = std::upper_bound(arc.begin(), arc.end(), s) - arc.begin() - 1;
  i = std::clamp<int64_t>(i, 0, p1 - p0 - 2);
  const double piece = arc[i + 1] - arc[i];
  const double tau = piece > 0.0 ? std::clamp((s - arc[i]) / piece, 0.0, 1.0) : 0.0;
  ps.segment[q] = static_cast<int32_t>(i);
  ps.tau[q] = tau;
  const int64_t a = pm.pathPoints[p0 + i], b = pm.pathPoints[p0 + i + 1];
  const std::vector<double>& points = pm.mesh.points;
  for (int x = 0; x < 3; ++x)
  {
    out[x] = static_cast<float>((1.0 - tau) * points[3 * a + x] + tau * points[3 * b + x]);
  }
  // Normals along the path: the shared ones, with the end normals at its two ends.
  auto normalAt = [&](int64_t k)
  {
    const int32_t v = pm.pathPoints[p0 + k];
    return k == 0 ? endNormal[0] : (k == last ? endNormal[1] : rowOf(in.shared, v));
  };
  const Vec3 n = normalizedOrZero((1.0 - tau) * normalAt(i) + tau * normalAt(i + 1));
  for (int x = 0; x < 3; ++x)
  {
    out[3 + x] = static_cast<float>(n[x]);
  }
  for (size_t at = 0; at < in.extra.size(); ++at)
  {
    const int32_t nComp = in.extra[at].components;
    const std::vector<double>& values = in.extra[at].values;
    if (in.extra[at].influences)
    {
      const int64_t ends[2] = { a, b };
      const double w[2] = { 1.0 - tau, tau };
      blendedInfluences(in.extra[at], 2, ends, w, &out[in.S.offset[at + 2]]);
      continue;
    }
    for (int32_t x = 0; x < nComp; ++x)
    {
      out[in.S.offset[at + 2] + x] =
        static_cast<float>((1.0 - tau) * values[a * nComp + x] + tau * values[b * nComp + x]);
    }
  }
}

/// Normals of chart c's points: shared, except one-sided ones (from this patch's triangles
/// only) on the sides that follow a feature curve and at corners on one, so the crease stays
/// sharp. #Vp x 3.
std::vector<double> chartNormals(
  const SamplingInput& in, const PatchParameterization& p, const AtlasChart& ch, int32_t c)
{
  const int32_t np = static_cast<int32_t>(p.points.size());
  const std::vector<int32_t>& baseTriangles = in.base.baseTriangles;
  std::vector<double> own(3 * static_cast<size_t>(np), 0.0);
  for (int32_t v = 0; v < np; ++v)
  {
    for (int x = 0; x < 3; ++x)
    {
      own[3 * v + x] = in.shared[3 * static_cast<int64_t>(p.points[v]) + x];
    }
  }
  bool featureCorner = false;
  for (int k = 0; k < 3; ++k)
  {
    featureCorner = featureCorner || in.featureVertex[baseTriangles[3 * c + k]];
  }
  if (!featureCorner)
  {
    return own;
  }
  std::vector<double> oneSided(3 * static_cast<size_t>(np), 0.0);
  accumulateNormals(in.patches.mesh, p.meshTriangles.data(),
    static_cast<int64_t>(p.meshTriangles.size()), p.triangles, oneSided);
  normalizeRows(oneSided);
  for (int k = 0; k < 3; ++k)
  {
    if (in.featureVertex[baseTriangles[3 * c + k]])
    {
      const int32_t l = patchIndex(p, ch.cornerVertex[k]);
      std::copy(&oneSided[3 * l], &oneSided[3 * l] + 3, &own[3 * l]);
    }
    if (!ch.featureSide[k])
    {
      continue;
    }
    for (int32_t v : sidePath(in.patches, in.base, c, k))
    {
      const int32_t l = patchIndex(p, v);
      std::copy(&oneSided[3 * l], &oneSided[3 * l] + 3, &own[3 * l]);
    }
  }
  return own;
}

/// Per extra attribute with corner values, the values of chart c's points as its own triangles
/// give them (#Vp x components; empty for an attribute without corner values): along a seam,
/// which the feature stage makes a chart side, each chart keeps the values of its own side.
std::vector<std::vector<double>> chartCornerValues(
  const SamplingInput& in, const PatchParameterization& p)
{
  std::vector<std::vector<double>> own(in.extra.size());
  const std::vector<int32_t>& triangles = in.patches.mesh.triangles;
  for (size_t a = 0; a < in.extra.size(); ++a)
  {
    const GeometryImageAttribute& x = in.extra[a];
    if (x.cornerValues.empty())
    {
      continue;
    }
    const size_t n = static_cast<size_t>(x.components);
    own[a].assign(p.points.size() * n, 0.0);
    std::vector<uint8_t> done(p.points.size(), 0);
    for (size_t f = 0; f < p.meshTriangles.size(); ++f)
    {
      const size_t t = static_cast<size_t>(p.meshTriangles[f]);
      for (size_t k = 0; k < 3; ++k)
      {
        const size_t l = static_cast<size_t>(patchIndex(p, triangles[3 * t + k]));
        if (!done[l])
        {
          done[l] = 1;
          std::copy_n(&x.cornerValues[(3 * t + k) * n], n, &own[a][l * n]);
        }
      }
    }
  }
  return own;
}

/// The corner-valued extras of a side sample between chart points a and b (patch indices) at
/// tau: from the chart's own values.
void ownSideValues(const SamplingInput& in, const std::vector<std::vector<double>>& ownExtra,
  int32_t a, int32_t b, double tau, float* out)
{
  for (size_t at = 0; at < in.extra.size(); ++at)
  {
    const std::vector<double>& own = ownExtra[at];
    if (own.empty())
    {
      continue;
    }
    const int64_t n = in.extra[at].components;
    for (int64_t x = 0; x < n; ++x)
    {
      out[in.S.offset[at + 2] + x] =
        static_cast<float>((1.0 - tau) * own[a * n + x] + tau * own[b * n + x]);
    }
  }
}

/// Sample t of side k of chart c at its grid level (n = 2^level per side): the path's floats,
/// with the normal interpolated from the chart's own (one-sided) normals along a feature side.
void copySideSample(const SamplingInput& in, const PatchParameterization& p, const AtlasChart& ch,
  int32_t c, int32_t k, int64_t t, int32_t level, const std::vector<PathSamples>& paths,
  const std::vector<double>& own, const std::vector<std::vector<double>>& ownExtra, float* out)
{
  const PatchMesh& pm = in.patches;
  const int64_t n = int64_t(1) << level;
  const int32_t e = pm.faceEdges[3 * c + k];
  const PathSamples& ps = paths[e];
  const int64_t q = (sideRunsForward(pm, in.base, c, k) ? t : n - t) << (ps.level - level);
  const float* src = &ps.values[q * in.S.size];
  std::copy(src, src + in.S.size, out);
  const int64_t q1 = int64_t(1) << ps.level;
  const bool oneSidedNormal = ch.featureSide[k] && q != 0 && q != q1;
  const bool ownValues = std::any_of(
    ownExtra.begin(), ownExtra.end(), [](const std::vector<double>& v) { return !v.empty(); });
  if (!oneSidedNormal && !ownValues)
  {
    return;
  }
  const int64_t at = pm.pathOffsets[e] + ps.segment[q];
  const int32_t a = patchIndex(p, pm.pathPoints[at]);
  const int32_t b = patchIndex(p, pm.pathPoints[at + 1]);
  const double tau = ps.tau[q];
  ownSideValues(in, ownExtra, a, b, tau, out);
  if (!oneSidedNormal)
  {
    return;
  }
  Vec3 nn;
  for (int x = 0; x < 3; ++x)
  {
    nn[x] = (1.0 - tau) * own[3 * a + x] + tau * own[3 * b + x];
  }
  nn = normalizedOrZero(nn);
  for (int x = 0; x < 3; ++x)
  {
    out[3 + x] = static_cast<float>(nn[x]);
  }
}

/// Interior sample (i, j) of a grid with n samples per side: position, normal (renormalized) and
/// every extra attribute interpolated barycentrically at the grid point's (u, v) in the patch.
void interpolateSample(const SamplingInput& in, const PatchParameterization& p,
  const UvLocator& locator, const std::vector<double>& own, int64_t i, int64_t j, int64_t n,
  float* out)
{
  const std::vector<int32_t>& meshTriangles = in.patches.mesh.triangles;
  const UvLocator::Hit hit = locator.locate(static_cast<double>(i) / n, static_cast<double>(j) / n);
  const int32_t* tri = &p.triangles[3 * static_cast<int64_t>(hit.triangle)];
  Vec3 pos = Vec3::Zero(), nn = Vec3::Zero();
  for (int r = 0; r < 3; ++r)
  {
    pos += hit.w[r] * pointOf(in.patches.mesh, p.points[tri[r]]);
    nn += hit.w[r] * rowOf(own, tri[r]);
  }
  nn = normalizedOrZero(nn);
  for (int x = 0; x < 3; ++x)
  {
    out[x] = static_cast<float>(pos[x]);
    out[3 + x] = static_cast<float>(nn[x]);
  }
  // Where an attribute has corner values, the slot of each corner among its mesh triangle's.
  int64_t slot[3] = { 0, 0, 0 };
  if (std::any_of(in.extra.begin(), in.extra.end(),
        [](const GeometryImageAttribute& x) { return !x.cornerValues.empty(); }))
  {
    const int64_t t = p.meshTriangles[static_cast<size_t>(hit.triangle)];
    for (int r = 0; r < 3; ++r)
    {
      const int32_t v = p.points[tri[r]];
      slot[r] = 3 * t + (meshTriangles[3 * t] == v ? 0 : (meshTriangles[3 * t + 1] == v ? 1 : 2));
    }
  }
  for (size_t at = 0; at < in.extra.size(); ++at)
  {
    const GeometryImageAttribute& attribute = in.extra[at];
    const int32_t nComp = attribute.components;
    if (attribute.influences)
    {
      const int64_t corners[3] = { p.points[tri[0]], p.points[tri[1]], p.points[tri[2]] };
      blendedInfluences(attribute, 3, corners, hit.w, &out[in.S.offset[at + 2]]);
      continue;
    }
    for (int32_t x = 0; x < nComp; ++x)
    {
      double v = 0.0;
      for (int r = 0; r < 3; ++r)
      {
        v += hit.w[r] *
          (attribute.cornerValues.empty() ? attribute.values[int64_t(p.points[tri[r]]) * nComp + x]
                                          : attribute.cornerValues[slot[r] * nComp + x]);
      }
      out[in.S.offset[at + 2] + x] = static_cast<float>(v);
    }
  }
}
} // namespace

std::vector<double> sharedNormals(
  const TriMesh& mesh, const Layout& L, const std::vector<double>& normals)
{
  std::vector<double> shared(3 * static_cast<size_t>(L.numPoints), 0.0);
  if (normals.empty())
  {
    accumulateNormals(
      mesh, L.patchTriangles.data(), static_cast<int64_t>(L.patchTriangles.size()), {}, shared);
  }
  else
  {
    shared = normals;
  }
  normalizeRows(shared);
  return shared;
}

PathSamples samplePath(const SamplingInput& in, int32_t e, int32_t level)
{
  const PatchMesh& pm = in.patches;
  PathSamples ps;
  ps.level = level;
  const int64_t q1 = int64_t(1) << ps.level;
  const int64_t p0 = pm.pathOffsets[e], p1 = pm.pathOffsets[e + 1];
  const std::vector<double> arc = arcLengths(pm.mesh, &pm.pathPoints[p0], p1 - p0);
  ps.segment.resize(q1 + 1);
  ps.tau.resize(q1 + 1);
  ps.values.resize((q1 + 1) * in.S.size);
  const Vec3 endNormal[2] = { pathEndNormal(in, e, 0), pathEndNormal(in, e, 1) };
  for (int64_t q = 0; q <= q1; ++q)
  {
    samplePathAt(in, e, arc, endNormal, q, ps);
  }
  return ps;
}

ChartGrid sampleChartGrid(const SamplingInput& in, const PatchParameterization& p,
  const AtlasChart& chart, int32_t c, int32_t level, const std::vector<PathSamples>& paths)
{
  const std::vector<double> own = chartNormals(in, p, chart, c);
  const std::vector<std::vector<double>> ownExtra = chartCornerValues(in, p);
  ChartGrid g;
  g.level = level;
  g.n = int64_t(1) << level;
  g.size = in.S.size;
  const int64_t n = g.n;
  g.values.assign(static_cast<size_t>(gridVertexCount(level)) * in.S.size, 0.0f);
  const UvLocator locator(p);
  for (int64_t j = 0; j <= n; ++j)
  {
    for (int64_t i = 0; i + j <= n; ++i)
    {
      float* out = g.at(level, i, j);
      const std::array<int32_t, 2> side =
        gridSide(static_cast<int32_t>(i), static_cast<int32_t>(j), static_cast<int32_t>(n));
      if (side[0] >= 0)
      {
        copySideSample(in, p, chart, c, side[0], side[1], level, paths, own, ownExtra, out);
      }
      else
      {
        interpolateSample(in, p, locator, own, i, j, n, out);
      }
    }
  }
  return g;
}
} // namespace tc::detail::geometry_images
