// SPDX-License-Identifier: BSD-3-Clause
#include "tc/gim/geometry_images.h"

#include "tc/common/errors.h"
#include "tc/common/parallel.h"

#include <Eigen/Dense>
#include <Eigen/SparseCholesky>
#include <Eigen/SparseCore>
#include <Eigen/SparseLU>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <limits>
#include <numeric>
#include <string>
#include <utility>
#include <vector>

// The mean-value system is assembled and solved by hand on Eigen (one SparseLU per patch)
// rather than with CGAL's Mean_value_coordinates_parameterizer_3: CGAL needs each patch copied
// into a halfedge graph, offers only circular and square borders (a triangle needs a custom
// Border_parameterizer model), and its weights divide by zero on the near-degenerate triangles
// that Steiner points close to an input vertex create, which the guarded weights below accept.
//
// The 2-D point location is a uniform bucket grid over the unit square rather than a CGAL
// AABB tree: CGAL 5.5 has no 2-D AABB traits, and the parameter domain is a fixed square.
//
// Packing is written by hand (paper section 5.2, no library packs triangle pairs); so are the
// oriented bounding boxes (principal axes; see orientedBox for why not CGAL's optimal box).

namespace tc
{
namespace
{
using Vec3 = Eigen::Vector3d;

constexpr int32_t kMaxLevelLimit = 12;
constexpr int32_t kMaxComponents = 64;
constexpr int32_t kMaxStretchIterations = 100;
// Angles within this of pi are clamped before tan(angle / 2) (a flat triangle would give an
// infinite mean-value weight).
constexpr double kMaxAngle = 3.14159265358979323846 - 1e-6;
// A uv triangle whose height is below this fraction of its longest side counts as degenerate
// (three corners on one straight side of the domain, up to the rounding of 1 - f).
constexpr double kDegenerateRatio = 1e-12;
// Barycentric tolerance of the 2-D point location (points on a shared uv edge).
constexpr double kInsideTolerance = 1e-12;

std::string num(int64_t v)
{
  return std::to_string(v);
}

int64_t gridSamples(int32_t d)
{
  const int64_t n = int64_t(1) << d;
  return (n + 1) * (n + 2) / 2;
}

/// Progress steps of a parallel loop over n patches or charts: parallel_for runs its steps one
/// after the other, so each must hold several items for both cores to work (a few dozen
/// charts are common, and one chart's box search alone takes tens of milliseconds).
int blockSteps(int64_t n)
{
  return static_cast<int>(std::clamp<int64_t>(n / 4, 1, 32));
}

/// Index of sample (i, j) in a level with n = 2^d samples per side, rows j = 0 .. n.
inline int64_t gridIndex(int64_t n, int64_t i, int64_t j)
{
  return j * (n + 1) - j * (j - 1) / 2 + i;
}

Vec3 pointOf(const TriMesh& mesh, int64_t v)
{
  return Vec3(mesh.points[3 * v], mesh.points[3 * v + 1], mesh.points[3 * v + 2]);
}

/// The checked input, with triangles grouped by patch and each base edge's two charts.
struct Layout
{
  int64_t numPoints = 0;
  int32_t numCharts = 0;
  int32_t numEdges = 0;
  std::vector<int64_t> patchOffsets;   // #Fb + 1
  std::vector<int32_t> patchTriangles; // triangle ids grouped by patch
  std::vector<int32_t> edgeChart;      // #Eb x 2: the two base faces of each base edge
  std::vector<int32_t> edgeSide;       // #Eb x 2: the side of that face
  std::vector<uint8_t> edgeFeature;    // #Eb 1 when either face flags the side as a feature
};

Layout checkInput(const PatchMesh& pm, const BaseComplexResult& base)
{
  const std::string where = "geometry images: ";
  const TriMesh& mesh = pm.mesh;
  if (mesh.points.size() % 3 != 0 || mesh.triangles.size() % 3 != 0)
  {
    throw InputError(where + "the patch mesh has " + num(mesh.points.size()) + " coordinates and " +
      num(mesh.triangles.size()) + " triangle indices; both must be multiples of 3");
  }
  Layout L;
  L.numPoints = mesh.numPoints();
  const int64_t nv = L.numPoints;
  const int64_t nf = mesh.numTriangles();
  if (nf == 0)
  {
    throw InputError(where + "the patch mesh has no triangle: trace the paths of a non-empty mesh");
  }
  if (nv > std::numeric_limits<int32_t>::max() / 2)
  {
    throw InputError(where + "the patch mesh has " + num(nv) + " points, more than supported");
  }
  for (double x : mesh.points)
  {
    if (!std::isfinite(x))
    {
      throw InputError(where + "the patch mesh has a non-finite coordinate; clean the input mesh");
    }
  }
  for (int64_t t = 0; t < nf; ++t)
  {
    const int32_t* c = &mesh.triangles[3 * t];
    for (int k = 0; k < 3; ++k)
    {
      if (c[k] < 0 || c[k] >= nv)
      {
        throw InputError(where + "triangle " + num(t) + " of the patch mesh has corner " +
          num(c[k]) + ", outside 0 .. " + num(nv - 1));
      }
    }
    if (c[0] == c[1] || c[1] == c[2] || c[2] == c[0])
    {
      throw InputError(where + "triangle " + num(t) + " of the patch mesh repeats a corner");
    }
  }
  if (static_cast<int64_t>(pm.inputPointId.size()) != nv)
  {
    throw InputError(where + "inputPointId has " + num(pm.inputPointId.size()) + " entries for " +
      num(nv) + " points");
  }
  if (static_cast<int64_t>(pm.patchId.size()) != nf ||
    static_cast<int64_t>(pm.inputTriangle.size()) != nf)
  {
    throw InputError(where + "patchId and inputTriangle need one entry per triangle (" + num(nf) +
      "), they have " + num(pm.patchId.size()) + " and " + num(pm.inputTriangle.size()));
  }

  const size_t nb = base.baseTriangles.size();
  if (nb == 0 || nb % 3 != 0)
  {
    throw InputError(where + "the base complex has " + num(nb) +
      " triangle indices; it needs at least one triangle (a multiple of 3)");
  }
  L.numCharts = static_cast<int32_t>(nb / 3);
  const int64_t nvb = static_cast<int64_t>(base.baseVertices.size());
  for (size_t b = 0; b < base.baseVertices.size(); ++b)
  {
    const int32_t v = base.baseVertices[b];
    if (v < 0 || v >= nv || pm.inputPointId[v] < 0)
    {
      throw InputError(where + "base vertex " + num(b) + " is point " + num(v) +
        ", not an input point of the patch mesh");
    }
  }
  for (size_t i = 0; i < nb; ++i)
  {
    if (base.baseTriangles[i] < 0 || base.baseTriangles[i] >= nvb)
    {
      throw InputError(where + "base triangle " + num(i / 3) + " has corner " +
        num(base.baseTriangles[i]) + ", outside 0 .. " + num(nvb - 1));
    }
  }
  if (!base.baseEdgeIsFeature.empty() && base.baseEdgeIsFeature.size() != nb)
  {
    throw InputError(where + "baseEdgeIsFeature has " + num(base.baseEdgeIsFeature.size()) +
      " entries; it needs 3 per base triangle (" + num(nb) + ") or none");
  }
  if (pm.faceEdges.size() != nb)
  {
    throw InputError(where + "faceEdges has " + num(pm.faceEdges.size()) +
      " entries; it needs 3 per base triangle (" + num(nb) + ")");
  }
  if (pm.baseEdges.size() % 2 != 0)
  {
    throw InputError(where + "baseEdges has an odd number of entries");
  }
  L.numEdges = static_cast<int32_t>(pm.baseEdges.size() / 2);
  const int32_t ne = L.numEdges;
  if (static_cast<int64_t>(pm.pathOffsets.size()) != ne + 1 || pm.pathOffsets[0] != 0 ||
    pm.pathOffsets.back() != static_cast<int64_t>(pm.pathPoints.size()))
  {
    throw InputError(where + "pathOffsets must have #base edges + 1 (" + num(ne + 1) +
      ") entries from 0 to the size of pathPoints (" + num(pm.pathPoints.size()) + ")");
  }
  for (int32_t e = 0; e < ne; ++e)
  {
    const int32_t a = pm.baseEdges[2 * e], b = pm.baseEdges[2 * e + 1];
    if (a < 0 || b >= nvb || a >= b)
    {
      throw InputError(where + "base edge " + num(e) + " joins base vertices " + num(a) + " and " +
        num(b) + "; they must be in 0 .. " + num(nvb - 1) + ", lower first");
    }
    const int64_t p0 = pm.pathOffsets[e], p1 = pm.pathOffsets[e + 1];
    if (p1 - p0 < 2)
    {
      throw InputError(where + "the path of base edge " + num(e) + " has fewer than 2 points");
    }
    for (int64_t i = p0; i < p1; ++i)
    {
      if (pm.pathPoints[i] < 0 || pm.pathPoints[i] >= nv)
      {
        throw InputError(where + "the path of base edge " + num(e) + " has point " +
          num(pm.pathPoints[i]) + ", not a point of the patch mesh");
      }
    }
    if (pm.pathPoints[p0] != base.baseVertices[a] || pm.pathPoints[p1 - 1] != base.baseVertices[b])
    {
      throw InputError(where + "the path of base edge " + num(e) +
        " must run from the point of base vertex " + num(a) + " to that of " + num(b));
    }
  }

  L.edgeChart.assign(2 * static_cast<size_t>(ne), -1);
  L.edgeSide.assign(2 * static_cast<size_t>(ne), -1);
  L.edgeFeature.assign(ne, 0);
  for (int32_t f = 0; f < L.numCharts; ++f)
  {
    const int32_t* tri = &base.baseTriangles[3 * f];
    if (tri[0] == tri[1] || tri[1] == tri[2] || tri[2] == tri[0])
    {
      throw InputError(where + "base triangle " + num(f) + " repeats a corner");
    }
    for (int k = 0; k < 3; ++k)
    {
      const int32_t e = pm.faceEdges[3 * f + k];
      if (e < 0 || e >= ne)
      {
        throw InputError(where + "side " + num(k) + " of base face " + num(f) + " is base edge " +
          num(e) + ", outside 0 .. " + num(ne - 1));
      }
      const int32_t a = tri[k], b = tri[(k + 1) % 3];
      if (std::min(a, b) != pm.baseEdges[2 * e] || std::max(a, b) != pm.baseEdges[2 * e + 1])
      {
        throw InputError(where + "side " + num(k) + " of base face " + num(f) + " joins base " +
          "vertices " + num(a) + " and " + num(b) + " but faceEdges names base edge " + num(e));
      }
      const int slot = L.edgeChart[2 * e] < 0 ? 0 : 1;
      if (slot == 1 && L.edgeChart[2 * e + 1] >= 0)
      {
        throw InputError(where + "base edge " + num(e) +
          " borders more than two base faces; the base complex must be a closed manifold");
      }
      if (slot == 1 && base.baseTriangles[3 * L.edgeChart[2 * e] + L.edgeSide[2 * e]] != b)
      {
        throw InputError(where + "base faces " + num(L.edgeChart[2 * e]) + " and " + num(f) +
          " run base edge " + num(e) + " the same way; the base complex must be oriented");
      }
      L.edgeChart[2 * e + slot] = f;
      L.edgeSide[2 * e + slot] = k;
      if (!base.baseEdgeIsFeature.empty() && base.baseEdgeIsFeature[3 * f + k] != 0)
      {
        L.edgeFeature[e] = 1;
      }
    }
  }
  for (int32_t e = 0; e < ne; ++e)
  {
    if (L.edgeChart[2 * e + 1] < 0)
    {
      throw InputError(where + "base edge " + num(e) +
        " borders fewer than two base faces; the base complex must be closed");
    }
  }

  L.patchOffsets.assign(static_cast<size_t>(L.numCharts) + 1, 0);
  for (int64_t t = 0; t < nf; ++t)
  {
    const int32_t p = pm.patchId[t];
    if (p < 0 || p >= L.numCharts)
    {
      throw InputError(where + "triangle " + num(t) + " has patch " + num(p) + ", outside 0 .. " +
        num(L.numCharts - 1));
    }
    ++L.patchOffsets[p + 1];
  }
  for (int32_t c = 0; c < L.numCharts; ++c)
  {
    if (L.patchOffsets[c + 1] == 0)
    {
      throw InputError(where + "patch " + num(c) + " has no triangle");
    }
    L.patchOffsets[c + 1] += L.patchOffsets[c];
  }
  L.patchTriangles.resize(nf);
  std::vector<int64_t> fill(L.patchOffsets.begin(), L.patchOffsets.end() - 1);
  for (int64_t t = 0; t < nf; ++t)
  {
    L.patchTriangles[fill[pm.patchId[t]]++] = static_cast<int32_t>(t);
  }
  return L;
}

/// Path of side k of chart c in the side's direction (corner k to corner k + 1).
std::vector<int32_t> sidePath(
  const PatchMesh& pm, const BaseComplexResult& base, int32_t c, int32_t k)
{
  const int32_t e = pm.faceEdges[3 * c + k];
  const bool forward = base.baseTriangles[3 * c + k] == pm.baseEdges[2 * e];
  std::vector<int32_t> path(
    pm.pathPoints.begin() + pm.pathOffsets[e], pm.pathPoints.begin() + pm.pathOffsets[e + 1]);
  if (!forward)
  {
    std::reverse(path.begin(), path.end());
  }
  return path;
}

int32_t findRoot(std::vector<int32_t>& parent, int32_t v)
{
  while (parent[v] != v)
  {
    parent[v] = parent[parent[v]];
    v = parent[v];
  }
  return v;
}

/// Tan of half the angle between e1 and e2 (the mean-value weight of Floater 2003, eq. 5.1).
double tanHalfAngle(const Vec3& e1, const Vec3& e2)
{
  const double angle = std::atan2(e1.cross(e2).norm(), e1.dot(e2));
  return std::tan(std::min(angle, kMaxAngle) / 2.0);
}

/// Sander et al.'s L2 stretch of the map from uv to 3-D over one patch triangle, squared
/// ((Gamma^2 + gamma^2) / 2 of its Jacobian), and the triangle's 3-D area; a uv triangle of no
/// area counts as infinitely stretched.
std::pair<double, double> triangleStretch2(
  const TriMesh& mesh, const PatchParameterization& p, int64_t t)
{
  const int32_t* c = &p.triangles[3 * t];
  const double* a = &p.uv[2 * c[0]];
  const double* b = &p.uv[2 * c[1]];
  const double* q = &p.uv[2 * c[2]];
  const Vec3 x0 = pointOf(mesh, p.points[c[0]]);
  const Vec3 x1 = pointOf(mesh, p.points[c[1]]);
  const Vec3 x2 = pointOf(mesh, p.points[c[2]]);
  const double area3 = 0.5 * (x1 - x0).cross(x2 - x0).norm();
  const double area2 = (b[0] - a[0]) * (q[1] - a[1]) - (q[0] - a[0]) * (b[1] - a[1]);
  if (!(area2 > 0.0))
  {
    return { std::numeric_limits<double>::infinity(), area3 };
  }
  const Vec3 ss = (x0 * (b[1] - q[1]) + x1 * (q[1] - a[1]) + x2 * (a[1] - b[1])) / area2;
  const Vec3 st = (x0 * (q[0] - b[0]) + x1 * (a[0] - q[0]) + x2 * (b[0] - a[0])) / area2;
  return { 0.5 * (ss.squaredNorm() + st.squaredNorm()), area3 };
}

/// The area-weighted L2 stretch of the whole patch (infinite if a triangle has no uv area)
/// and, with `sigma`, per point the L2 stretch of its triangles (area-weighted) normalized by the
/// patch's, clamped to [1e-3, 1e3] so that one sliver cannot make a weight vanish or explode.
double patchStretch(
  const TriMesh& mesh, const PatchParameterization& p, std::vector<double>* sigma = nullptr)
{
  const size_t np = p.points.size();
  std::vector<double> pointSum, pointArea;
  if (sigma)
  {
    pointSum.assign(np, 0.0);
    pointArea.assign(np, 0.0);
  }
  double sum = 0.0, area = 0.0;
  double clampedSum = 0.0; // the weights' mean: no infinite term
  for (int64_t t = 0; t < static_cast<int64_t>(p.triangles.size() / 3); ++t)
  {
    const auto [s2, a3] = triangleStretch2(mesh, p, t);
    if (a3 > 0.0)
    {
      sum += s2 * a3;
      area += a3;
    }
    if (sigma)
    {
      const double c = std::min(s2, 1e300);
      for (int k = 0; k < 3; ++k)
      {
        pointSum[p.triangles[3 * t + k]] += c * a3;
        pointArea[p.triangles[3 * t + k]] += a3;
      }
      clampedSum += c * a3;
    }
  }
  if (sigma)
  {
    const double mean = area > 0.0 && clampedSum > 0.0 ? std::sqrt(clampedSum / area) : 1.0;
    sigma->resize(np);
    for (size_t v = 0; v < np; ++v)
    {
      const double s = pointArea[v] > 0.0 ? std::sqrt(pointSum[v] / pointArea[v]) / mean : 1.0;
      (*sigma)[v] = std::clamp(std::isfinite(s) ? s : 1e3, 1e-3, 1e3);
    }
  }
  return area > 0.0 ? std::sqrt(sum / area) : 0.0;
}

PatchParameterization parameterize(const PatchMesh& pm, const BaseComplexResult& base,
  const Layout& L, int32_t c, int32_t stretchIterations)
{
  const std::string where = "geometry images: patch " + num(c) + " ";
  const TriMesh& mesh = pm.mesh;
  PatchParameterization p;
  const int64_t t0 = L.patchOffsets[c], t1 = L.patchOffsets[c + 1];
  const int64_t nt = t1 - t0;
  p.meshTriangles.assign(L.patchTriangles.begin() + t0, L.patchTriangles.begin() + t1);
  p.points.reserve(3 * nt);
  for (int32_t t : p.meshTriangles)
  {
    p.points.insert(p.points.end(), &mesh.triangles[3 * t], &mesh.triangles[3 * t] + 3);
  }
  std::sort(p.points.begin(), p.points.end());
  p.points.erase(std::unique(p.points.begin(), p.points.end()), p.points.end());
  const int32_t np = static_cast<int32_t>(p.points.size());
  auto local = [&p](int32_t v) -> int32_t
  {
    const auto it = std::lower_bound(p.points.begin(), p.points.end(), v);
    return it != p.points.end() && *it == v ? static_cast<int32_t>(it - p.points.begin()) : -1;
  };
  p.triangles.resize(3 * nt);
  for (int64_t t = 0; t < nt; ++t)
  {
    for (int k = 0; k < 3; ++k)
    {
      p.triangles[3 * t + k] = local(mesh.triangles[3 * p.meshTriangles[t] + k]);
    }
  }

  // Oriented sides; those whose reverse is absent form the boundary, counter-clockwise like the
  // base face, so side k's path must appear there from corner k to corner k + 1.
  std::vector<int64_t> half(3 * nt);
  for (int64_t i = 0; i < 3 * nt; ++i)
  {
    const int64_t a = p.triangles[i], b = p.triangles[i % 3 == 2 ? i - 2 : i + 1];
    half[i] = a * np + b;
  }
  std::sort(half.begin(), half.end());
  const auto dup = std::adjacent_find(half.begin(), half.end());
  if (dup != half.end())
  {
    throw InputError(where + "has two triangles with the same oriented side (" +
      num(p.points[*dup / np]) + ", " + num(p.points[*dup % np]) +
      "): the patch mesh is not a consistently oriented manifold");
  }
  auto hasHalf = [&](int64_t a, int64_t b)
  { return std::binary_search(half.begin(), half.end(), a * np + b); };
  int64_t boundaryHalf = 0;
  for (int64_t h : half)
  {
    boundaryHalf += hasHalf(h % np, h / np) ? 0 : 1;
  }

  p.uv.assign(2 * static_cast<size_t>(np), 0.0);
  std::vector<uint8_t> fixed(np, 0);
  std::vector<int32_t> loop;
  for (int32_t k = 0; k < 3; ++k)
  {
    const std::vector<int32_t> path = sidePath(pm, base, c, k);
    std::vector<double> arc(path.size(), 0.0);
    for (size_t i = 1; i < path.size(); ++i)
    {
      arc[i] = arc[i - 1] + (pointOf(mesh, path[i]) - pointOf(mesh, path[i - 1])).norm();
    }
    const double length = arc.back();
    for (size_t i = 0; i + 1 < path.size(); ++i)
    {
      const int32_t a = local(path[i]), b = local(path[i + 1]);
      if (a < 0 || b < 0 || !hasHalf(a, b) || hasHalf(b, a))
      {
        throw InputError(where + "is not bounded by the path of its side " + num(k) +
          " (base edge " + num(pm.faceEdges[3 * c + k]) + "): its piece " + num(path[i]) + "-" +
          num(path[i + 1]) + " is not a boundary side of the patch; check the traced paths");
      }
      loop.push_back(a);
      // The boundary map: arc-length fraction f along side k, on the right triangle's side k.
      const double f = length > 0.0 ? arc[i] / length
                                    : static_cast<double>(i) / static_cast<double>(path.size() - 1);
      const double u = k == 0 ? f : (k == 1 ? 1.0 - f : 0.0);
      const double v = k == 0 ? 0.0 : (k == 1 ? f : 1.0 - f);
      p.uv[2 * a] = u;
      p.uv[2 * a + 1] = v;
      fixed[a] = 1;
    }
  }
  if (static_cast<int64_t>(loop.size()) != boundaryHalf)
  {
    throw InputError(where + "has " + num(boundaryHalf) + " boundary sides but its three paths " +
      "have " + num(loop.size()) + ": it is not a disk bounded by its paths");
  }
  {
    std::vector<int32_t> sorted = loop;
    std::sort(sorted.begin(), sorted.end());
    const auto twice = std::adjacent_find(sorted.begin(), sorted.end());
    if (twice != sorted.end())
    {
      throw InputError(where + "has a boundary that passes twice through point " +
        num(p.points[*twice]) + ": it is not a disk");
    }
  }
  const int64_t edges = (3 * nt + boundaryHalf) / 2;
  const int64_t euler = np - edges + nt;
  if (euler != 1)
  {
    throw InputError(where + "has Euler characteristic " + num(euler) +
      " (a disk has 1): it has handles or holes; check the traced paths");
  }
  {
    std::vector<int32_t> parent(np);
    std::iota(parent.begin(), parent.end(), 0);
    for (int64_t t = 0; t < nt; ++t)
    {
      const int32_t r0 = findRoot(parent, p.triangles[3 * t]);
      for (int k = 1; k < 3; ++k)
      {
        const int32_t r = findRoot(parent, p.triangles[3 * t + k]);
        if (r != r0)
        {
          parent[r] = r0;
        }
      }
    }
    const int32_t root = findRoot(parent, 0);
    for (int32_t v = 1; v < np; ++v)
    {
      if (findRoot(parent, v) != root)
      {
        throw InputError(where + "is not connected: point " + num(p.points[v]) +
          " is not reachable from its boundary");
      }
    }
  }
  p.boundaryPoints = static_cast<int64_t>(loop.size());

  // Floater's mean-value coordinates: every interior point is the weighted mean of its
  // neighbours, w_ij = (tan(a_ij / 2) + tan(b_ij / 2)) / |x_j - x_i| with the angles at x_i.
  std::vector<int32_t> unknown(np, -1);
  int32_t nu = 0;
  for (int32_t v = 0; v < np; ++v)
  {
    unknown[v] = fixed[v] ? -1 : nu++;
  }
  if (nu > 0)
  {
    double extent = 0.0;
    {
      Vec3 lo = pointOf(mesh, p.points[0]), hi = lo;
      for (int32_t v : p.points)
      {
        lo = lo.cwiseMin(pointOf(mesh, v));
        hi = hi.cwiseMax(pointOf(mesh, v));
      }
      extent = (hi - lo).norm();
    }
    // Keeps 1 / |x_j - x_i| finite for a Steiner point on top of an input point.
    const double minLength = 1e-12 * std::max(extent, std::numeric_limits<double>::min());
    struct Entry
    {
      int32_t row, col;
      double w;
    };
    std::vector<Entry> entries;
    entries.reserve(6 * nt);
    std::vector<double> rowSum(nu, 0.0);
    for (int64_t t = 0; t < nt; ++t)
    {
      for (int r = 0; r < 3; ++r)
      {
        const int32_t i = p.triangles[3 * t + r];
        if (unknown[i] < 0)
        {
          continue;
        }
        const int32_t j = p.triangles[3 * t + (r + 1) % 3];
        const int32_t k = p.triangles[3 * t + (r + 2) % 3];
        const Vec3 xi = pointOf(mesh, p.points[i]);
        const Vec3 e1 = pointOf(mesh, p.points[j]) - xi, e2 = pointOf(mesh, p.points[k]) - xi;
        const double l1 = e1.norm(), l2 = e2.norm();
        if (l1 == 0.0 || l2 == 0.0)
        {
          continue;
        }
        const double th = tanHalfAngle(e1, e2);
        entries.push_back({ unknown[i], j, th / std::max(l1, minLength) });
        entries.push_back({ unknown[i], k, th / std::max(l2, minLength) });
        rowSum[unknown[i]] += entries[entries.size() - 2].w + entries.back().w;
      }
    }
    // A point whose every angle vanished (all its neighbours on top of it) falls back to
    // uniform (Tutte) weights, still a convex combination.
    for (Entry& en : entries)
    {
      if (!(rowSum[en.row] > 0.0))
      {
        en.w = 1.0;
      }
    }
    // One solve of the convex-combination system with the current weights; the pattern is
    // the same for every weight set, so it is analysed once.
    Eigen::SparseLU<Eigen::SparseMatrix<double>, Eigen::COLAMDOrdering<int>> lu;
    bool analysed = false;
    auto solve = [&]()
    {
      std::vector<Eigen::Triplet<double>> triplets;
      triplets.reserve(entries.size() + nu);
      Eigen::MatrixX2d rhs = Eigen::MatrixX2d::Zero(nu, 2);
      for (const Entry& en : entries)
      {
        triplets.emplace_back(en.row, en.row, en.w);
        if (unknown[en.col] >= 0)
        {
          triplets.emplace_back(en.row, unknown[en.col], -en.w);
        }
        else
        {
          rhs(en.row, 0) += en.w * p.uv[2 * en.col];
          rhs(en.row, 1) += en.w * p.uv[2 * en.col + 1];
        }
      }
      Eigen::SparseMatrix<double> A(nu, nu);
      A.setFromTriplets(triplets.begin(), triplets.end());
      if (!analysed)
      {
        lu.analyzePattern(A);
        analysed = true;
      }
      lu.factorize(A);
      if (lu.info() != Eigen::Success)
      {
        throw InputError(where + "gives a singular mean-value system (" + lu.lastErrorMessage() +
          "); check that the patch is a disk of non-degenerate triangles");
      }
      const Eigen::MatrixX2d uv = lu.solve(rhs);
      if (lu.info() != Eigen::Success || !uv.allFinite())
      {
        throw InputError(where + "gives a mean-value system that could not be solved; check " +
          "that the patch is a disk of non-degenerate triangles");
      }
      for (int32_t v = 0; v < np; ++v)
      {
        if (unknown[v] >= 0)
        {
          p.uv[2 * v] = uv(unknown[v], 0);
          p.uv[2 * v + 1] = uv(unknown[v], 1);
        }
      }
    };
    solve();
    std::vector<double> sigma;
    p.meanValueStretch = p.stretch =
      patchStretch(mesh, p, stretchIterations > 0 ? &sigma : nullptr);
    // Stretch reduction (Yoshizawa, Belyaev and Seidel 2004): divide each weight w_ij by the
    // L2 stretch of neighbour j and solve again, keeping the best map. The weights stay
    // positive, so every map is still a convex combination with a convex border (Tutte and
    // Floater: no flip); samples move from squeezed regions (a protrusion that the mean-value
    // map shrinks to a speck) to where the surface is.
    if (stretchIterations > 0)
    {
      std::vector<double> best = p.uv;
      for (int32_t it = 0; it < stretchIterations; ++it)
      {
        for (Entry& en : entries)
        {
          en.w /= sigma[en.col];
        }
        solve();
        const double s = patchStretch(mesh, p, &sigma);
        if (!(s < p.stretch))
        {
          break;
        }
        p.stretch = s;
        best = p.uv;
        ++p.stretchIterations;
      }
      p.uv = std::move(best);
    }
  }

  for (int64_t t = 0; t < nt; ++t)
  {
    const double* a = &p.uv[2 * p.triangles[3 * t]];
    const double* b = &p.uv[2 * p.triangles[3 * t + 1]];
    const double* q = &p.uv[2 * p.triangles[3 * t + 2]];
    const double area2 = (b[0] - a[0]) * (q[1] - a[1]) - (q[0] - a[0]) * (b[1] - a[1]);
    const double longest = std::max({ std::hypot(b[0] - a[0], b[1] - a[1]),
      std::hypot(q[0] - b[0], q[1] - b[1]), std::hypot(a[0] - q[0], a[1] - q[1]) });
    if (std::abs(area2) <= kDegenerateRatio * longest * longest)
    {
      ++p.degenerateTriangles;
    }
    else if (area2 < 0.0)
    {
      ++p.flippedTriangles;
    }
  }
  return p;
}

/// Point location in the parameterized patch: a uniform bucket grid over the unit square.
class UvLocator
{
public:
  struct Hit
  {
    int32_t triangle = -1;
    double w[3] = { 0.0, 0.0, 0.0 };
  };

  explicit UvLocator(const PatchParameterization& p)
    : P_(p)
  {
    const int64_t nt = static_cast<int64_t>(p.triangles.size() / 3);
    G_ = static_cast<int32_t>(std::clamp<double>(std::ceil(std::sqrt(double(nt))), 1.0, 1024.0));
    Offsets_.assign(static_cast<size_t>(G_) * G_ + 1, 0);
    for (int pass = 0; pass < 2; ++pass)
    {
      std::vector<int64_t> fill;
      if (pass == 1)
      {
        for (size_t i = 1; i < Offsets_.size(); ++i)
        {
          Offsets_[i] += Offsets_[i - 1];
        }
        Ids_.resize(static_cast<size_t>(Offsets_.back()));
        fill.assign(Offsets_.begin(), Offsets_.end() - 1);
      }
      for (int64_t t = 0; t < nt; ++t)
      {
        const double* a = &p.uv[2 * p.triangles[3 * t]];
        const double* b = &p.uv[2 * p.triangles[3 * t + 1]];
        const double* q = &p.uv[2 * p.triangles[3 * t + 2]];
        const double area2 = (b[0] - a[0]) * (q[1] - a[1]) - (q[0] - a[0]) * (b[1] - a[1]);
        if (area2 == 0.0)
        {
          continue;
        }
        const int32_t x0 = cell(std::min({ a[0], b[0], q[0] }));
        const int32_t x1 = cell(std::max({ a[0], b[0], q[0] }));
        const int32_t y0 = cell(std::min({ a[1], b[1], q[1] }));
        const int32_t y1 = cell(std::max({ a[1], b[1], q[1] }));
        for (int32_t y = y0; y <= y1; ++y)
        {
          for (int32_t x = x0; x <= x1; ++x)
          {
            const size_t id = static_cast<size_t>(y) * G_ + x;
            if (pass == 0)
            {
              ++Offsets_[id + 1];
            }
            else
            {
              Ids_[fill[id]++] = static_cast<int32_t>(t);
            }
          }
        }
      }
    }
  }

  /// The triangle that contains (u, v) best (largest smallest barycentric), searched in growing
  /// rings of cells until one contains it; barycentrics clamped to the triangle.
  Hit locate(double u, double v) const
  {
    Hit best;
    double bestMin = -std::numeric_limits<double>::infinity();
    const int32_t cx = cell(u), cy = cell(v);
    for (int32_t ring = 0; ring <= G_; ++ring)
    {
      for (int32_t y = cy - ring; y <= cy + ring; ++y)
      {
        for (int32_t x = cx - ring; x <= cx + ring; ++x)
        {
          const bool onRing = std::abs(x - cx) == ring || std::abs(y - cy) == ring;
          if (!onRing || x < 0 || y < 0 || x >= G_ || y >= G_)
          {
            continue;
          }
          const size_t id = static_cast<size_t>(y) * G_ + x;
          for (int64_t s = Offsets_[id]; s < Offsets_[id + 1]; ++s)
          {
            const int32_t t = Ids_[s];
            double w[3];
            barycentric(t, u, v, w);
            const double m = std::min({ w[0], w[1], w[2] });
            if (m > bestMin)
            {
              bestMin = m;
              best.triangle = t;
              std::copy(w, w + 3, best.w);
            }
          }
        }
      }
      if (bestMin >= -kInsideTolerance)
      {
        break;
      }
    }
    if (best.triangle >= 0)
    {
      double sum = 0.0;
      for (double& x : best.w)
      {
        x = std::max(x, 0.0);
        sum += x;
      }
      for (double& x : best.w)
      {
        x = sum > 0.0 ? x / sum : 1.0 / 3.0;
      }
    }
    return best;
  }

private:
  int32_t cell(double x) const
  {
    return static_cast<int32_t>(std::clamp(std::floor(x * G_), 0.0, double(G_ - 1)));
  }

  void barycentric(int32_t t, double u, double v, double (&w)[3]) const
  {
    const double* a = &P_.uv[2 * P_.triangles[3 * t]];
    const double* b = &P_.uv[2 * P_.triangles[3 * t + 1]];
    const double* q = &P_.uv[2 * P_.triangles[3 * t + 2]];
    const double area2 = (b[0] - a[0]) * (q[1] - a[1]) - (q[0] - a[0]) * (b[1] - a[1]);
    w[0] = ((b[0] - u) * (q[1] - v) - (q[0] - u) * (b[1] - v)) / area2;
    w[1] = ((q[0] - u) * (a[1] - v) - (a[0] - u) * (q[1] - v)) / area2;
    w[2] = 1.0 - w[0] - w[1];
  }

  const PatchParameterization& P_;
  int32_t G_ = 1;
  std::vector<int64_t> Offsets_;
  std::vector<int32_t> Ids_;
};

/// Angle-weighted normals (Thürmer and Wüthrich) of `points` from the triangles listed.
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

/// Float values of one sample: position, normal, then every extra attribute.
struct SampleLayout
{
  std::vector<int32_t> components; // per atlas attribute
  std::vector<int32_t> offset;     // of each attribute in a sample
  int32_t size = 0;
};

/// Sample values of a whole chart at its finest level (n = 2^d_max per side).
struct ChartGrid
{
  int64_t n = 0;
  int32_t size = 0;          // SampleLayout::size
  std::vector<float> values; // gridSamples x size
  /// Sample (i, j) of level d (2^d samples per side): the finest sample at stride n / 2^d.
  float* at(int32_t d, int64_t i, int64_t j)
  {
    const int64_t stride = n >> d;
    return &values[gridIndex(n, i * stride, j * stride) * size];
  }
  const float* at(int32_t d, int64_t i, int64_t j) const
  {
    return const_cast<ChartGrid*>(this)->at(d, i, j);
  }
};

/// The grid triangle of level nd (samples per side) holding parameter (u, v), clamped into the
/// right triangle, and the barycentric weights of its corners (i[k], j[k]).
struct GridHit
{
  int64_t i[3], j[3];
  double w[3];
};

GridHit gridHit(double u, double v, int64_t nd)
{
  const double x = std::clamp(u, 0.0, 1.0) * nd;
  const double y = std::clamp(v, 0.0, 1.0) * nd;
  const int64_t i = std::clamp<int64_t>(static_cast<int64_t>(std::floor(x)), 0, nd - 1);
  const int64_t j = std::clamp<int64_t>(static_cast<int64_t>(std::floor(y)), 0, nd - 1 - i);
  double fx = x - i, fy = y - j;
  if (fx + fy <= 1.0 || i + j + 1 >= nd)
  {
    // Lower triangle (i, j), (i + 1, j), (i, j + 1); clamped onto it at the hypotenuse.
    const double s = fx + fy;
    if (s > 1.0)
    {
      fx /= s;
      fy /= s;
    }
    return { { i, i + 1, i }, { j, j, j + 1 }, { 1.0 - fx - fy, fx, fy } };
  }
  // Upper triangle (i + 1, j + 1), (i, j + 1), (i + 1, j).
  return { { i + 1, i, i + 1 }, { j + 1, j + 1, j }, { fx + fy - 1.0, 1.0 - fx, 1.0 - fy } };
}

/// Membrane weight on sample offsets, relative to the mean data weight per sample (see
/// fitInterior), and the definiteness term. Measured on the bench meshes (finest Hausdorff /
/// RMS): 0.1 and 0.05 fit less closely (RMS 3-5% higher), 0.005 overshoots at fandisk_large's
/// creases (Hausdorff 0.42% -> 0.49%).
constexpr double kFitMembrane = 0.02;
constexpr double kFitDefinite = 1e-3;

/// Solves the symmetric positive definite system of a fit (entries summed, 3 right-hand sides);
/// an empty matrix if it fails.
Eigen::MatrixX3d solveOffsets(
  int32_t n, const std::vector<Eigen::Triplet<double>>& entries, const Eigen::MatrixX3d& rhs)
{
  Eigen::SparseMatrix<double> A(n, n);
  A.setFromTriplets(entries.begin(), entries.end());
  Eigen::SimplicialLDLT<Eigen::SparseMatrix<double>> ldlt(A);
  if (ldlt.info() != Eigen::Success)
  {
    return {};
  }
  Eigen::MatrixX3d x = ldlt.solve(rhs);
  if (ldlt.info() != Eigen::Success || !x.allFinite())
  {
    return {};
  }
  return x;
}

/// Adds data point P with weight w at the place of barycentrics b[] of samples id[] (-1: fixed)
/// whose current positions are x[] to the normal equations of a fit of the sample offsets.
template <int K>
void addFitData(const int32_t (&id)[K], const double (&b)[K], const Vec3 (&x)[K], const Vec3& P,
  double w, std::vector<Eigen::Triplet<double>>& entries, Eigen::MatrixX3d& rhs)
{
  Vec3 r = -P;
  for (int k = 0; k < K; ++k)
  {
    r += b[k] * x[k];
  }
  for (int a = 0; a < K; ++a)
  {
    if (id[a] < 0)
    {
      continue;
    }
    rhs.row(id[a]) -= w * b[a] * r.transpose();
    for (int c = 0; c < K; ++c)
    {
      if (id[c] >= 0)
      {
        entries.emplace_back(id[a], id[c], w * b[a] * b[c]);
      }
    }
  }
}

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

/// Inner edges of a patch (local point pairs) whose two triangles meet at more than
/// kCreaseDegrees: creases that no feature line follows, inside a chart.
std::vector<std::array<int32_t, 2>> patchCreases(
  const TriMesh& mesh, const PatchParameterization& p)
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
  const double cosine = std::cos(kCreaseDegrees * 3.14159265358979323846 / 180.0);
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

/// levelError[d] of a chart for d = 0 .. upTo: the largest distance from a patch point to the
/// level-d grid surface at the same (u, v), the piecewise-linear reconstruction in parameter
/// space; level d is grid g at stride g.n / 2^d. Also measured where a crease edge of the patch
/// (patchCreases) crosses a grid line (u, v or u + v a multiple of 2^-d): there grid edges cut
/// across the fold, and the deviation is largest between the crease's points.
std::vector<double> chartLevelErrors(const TriMesh& mesh, const PatchParameterization& p,
  const ChartGrid& g, const std::vector<std::array<int32_t, 2>>& creases, int32_t upTo)
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
          worst =
            std::max(worst, levelDeviation(g, d, ua + w * (ub - ua), va + w * (vb - va), P));
        }
      }
    }
    error[d] = worst;
  }
  return error;
}

/// The side samples of a path at level d (m = 2^d segments) fitted to the path by least squares,
/// as fitInterior fits a chart's interior: the path's points and its edges' midpoints, placed
/// by arc length on the chords between samples (weights a quarter and a half of the edge
/// lengths), a membrane on the offsets of consecutive samples and the ends fixed. `at(q)` gives
/// the interpolated position of sample q; returns the m + 1 fitted positions (empty: keep them).
template <typename At>
std::vector<Vec3> fitPath(const TriMesh& mesh, const int32_t* path, int64_t count, int32_t d,
  const At& at)
{
  const int64_t m = int64_t(1) << d;
  if (m < 2 || count < 2)
  {
    return {};
  }
  std::vector<double> arc(count, 0.0);
  for (int64_t i = 1; i < count; ++i)
  {
    arc[i] = arc[i - 1] + (pointOf(mesh, path[i]) - pointOf(mesh, path[i - 1])).norm();
  }
  const double length = arc.back();
  if (!(length > 0.0))
  {
    return {};
  }
  const int32_t nu = static_cast<int32_t>(m - 1);
  std::vector<Vec3> x(m + 1);
  for (int64_t q = 0; q <= m; ++q)
  {
    x[q] = at(q);
  }
  std::vector<Eigen::Triplet<double>> entries;
  Eigen::MatrixX3d rhs = Eigen::MatrixX3d::Zero(nu, 3);
  auto addData = [&](double s, const Vec3& P, double w)
  {
    const double t = std::clamp(s / length, 0.0, 1.0) * m;
    const int64_t q = std::clamp<int64_t>(static_cast<int64_t>(std::floor(t)), 0, m - 1);
    const int32_t id[2] = { q == 0 ? -1 : static_cast<int32_t>(q - 1),
      q + 1 == m ? -1 : static_cast<int32_t>(q) };
    const double b[2] = { 1.0 - (t - q), t - q };
    const Vec3 xs[2] = { x[q], x[q + 1] };
    addFitData(id, b, xs, P, w, entries, rhs);
  };
  for (int64_t i = 0; i + 1 < count; ++i)
  {
    const double l = arc[i + 1] - arc[i];
    const Vec3 a = pointOf(mesh, path[i]), b = pointOf(mesh, path[i + 1]);
    addData(arc[i], a, 0.25 * l);
    addData(arc[i + 1], b, 0.25 * l);
    addData(0.5 * (arc[i] + arc[i + 1]), 0.5 * (a + b), 0.5 * l);
  }
  const double mean = length / nu;
  const double mu = kFitMembrane * mean;
  for (int32_t a = 0; a < nu; ++a)
  {
    entries.emplace_back(a, a, kFitDefinite * mean + 2.0 * mu);
    if (a + 1 < nu)
    {
      entries.emplace_back(a, a + 1, -mu);
      entries.emplace_back(a + 1, a, -mu);
    }
  }
  const Eigen::MatrixX3d delta = solveOffsets(nu, entries, rhs);
  if (delta.rows() == 0)
  {
    return {};
  }
  for (int32_t a = 0; a < nu; ++a)
  {
    x[a + 1] += delta.row(a).transpose();
  }
  return x;
}

/// Moves the interior samples of level d of a chart (grid g at stride g.n / 2^d) off the
/// surface to fit it in the least-squares sense, instead of interpolating it: sample points
/// on a curved surface make every grid triangle a chord that lies to one side of it, and an
/// offset of about a third of that sagitta halves the largest deviation on both sides. The
/// offsets delta minimize
///   sum over data points q of w_q |sum_k b_qk (X0_k + delta_k) - P_q|^2
///   + mu sum over grid edges (a, b) of |delta_a - delta_b|^2 + lambda sum_a |delta_a|^2,
/// the data being the patch's points and its triangles' centroids at their (u, v) (weights a
/// sixth and a half of the areas of their triangles), b_qk the barycentrics of q's grid
/// triangle, X0 the interpolated samples. Side and corner samples (shared with the neighbours)
/// keep delta = 0; mu (a membrane on the offsets, relative to the mean data weight per sample)
/// keeps the offsets smooth where a sample has little data, lambda keeps the system definite.
/// Writes back the positions only.
void fitInterior(const TriMesh& mesh, const PatchParameterization& p, ChartGrid& g,
  const SampleLayout& S, int32_t d)
{
  const int64_t nd = int64_t(1) << d;
  std::vector<int32_t> unknown(static_cast<size_t>(gridSamples(d)), -1);
  int32_t nu = 0;
  for (int64_t j = 1; j < nd; ++j)
  {
    for (int64_t i = 1; i + j < nd; ++i)
    {
      unknown[gridIndex(nd, i, j)] = nu++;
    }
  }
  if (nu == 0)
  {
    return;
  }
  auto sample = [&](int64_t i, int64_t j) { return g.at(d, i, j); };

  // Data: points and centroids with their weights.
  const int64_t nt = static_cast<int64_t>(p.triangles.size() / 3);
  std::vector<double> pointWeight(p.points.size(), 0.0);
  std::vector<Eigen::Triplet<double>> entries;
  Eigen::MatrixX3d rhs = Eigen::MatrixX3d::Zero(nu, 3);
  double total = 0.0;
  auto addData = [&](double u, double v, const Vec3& P, double w)
  {
    if (!(w > 0.0))
    {
      return;
    }
    total += w;
    const GridHit h = gridHit(u, v, nd);
    int32_t id[3];
    Vec3 x[3];
    for (int k = 0; k < 3; ++k)
    {
      id[k] = unknown[gridIndex(nd, h.i[k], h.j[k])];
      const float* q = sample(h.i[k], h.j[k]);
      x[k] = Vec3(q[0], q[1], q[2]);
    }
    addFitData(id, h.w, x, P, w, entries, rhs);
  };
  for (int64_t t = 0; t < nt; ++t)
  {
    const int32_t* c = &p.triangles[3 * t];
    const Vec3 a = pointOf(mesh, p.points[c[0]]), b = pointOf(mesh, p.points[c[1]]),
               e = pointOf(mesh, p.points[c[2]]);
    const double area = 0.5 * (b - a).cross(e - a).norm();
    for (int k = 0; k < 3; ++k)
    {
      pointWeight[c[k]] += area / 6.0;
    }
    addData((p.uv[2 * c[0]] + p.uv[2 * c[1]] + p.uv[2 * c[2]]) / 3.0,
      (p.uv[2 * c[0] + 1] + p.uv[2 * c[1] + 1] + p.uv[2 * c[2] + 1]) / 3.0, (a + b + e) / 3.0,
      area / 2.0);
  }
  for (size_t v = 0; v < p.points.size(); ++v)
  {
    addData(p.uv[2 * v], p.uv[2 * v + 1], pointOf(mesh, p.points[v]), pointWeight[v]);
  }
  if (!(total > 0.0))
  {
    return;
  }
  // The membrane over the grid edges (each once: right, up and up-left neighbours) and the
  // definiteness term; offsets of side samples are 0.
  const double mean = total / nu;
  const double mu = kFitMembrane * mean;
  for (int64_t j = 0; j <= nd; ++j)
  {
    for (int64_t i = 0; i + j <= nd; ++i)
    {
      const int32_t a = unknown[gridIndex(nd, i, j)];
      if (a >= 0)
      {
        entries.emplace_back(a, a, kFitDefinite * mean);
      }
      const int64_t ni[3] = { i + 1, i, i - 1 }, nj[3] = { j, j + 1, j + 1 };
      for (int k = 0; k < 3; ++k)
      {
        if (ni[k] < 0 || ni[k] + nj[k] > nd)
        {
          continue;
        }
        const int32_t b = unknown[gridIndex(nd, ni[k], nj[k])];
        if (a >= 0)
        {
          entries.emplace_back(a, a, mu);
        }
        if (b >= 0)
        {
          entries.emplace_back(b, b, mu);
        }
        if (a >= 0 && b >= 0)
        {
          entries.emplace_back(a, b, -mu);
          entries.emplace_back(b, a, -mu);
        }
      }
    }
  }
  const Eigen::MatrixX3d delta = solveOffsets(nu, entries, rhs);
  if (delta.rows() == 0)
  {
    return; // keep the interpolated samples
  }
  for (int64_t j = 1; j < nd; ++j)
  {
    for (int64_t i = 1; i + j < nd; ++i)
    {
      float* s = sample(i, j);
      const int32_t a = unknown[gridIndex(nd, i, j)];
      for (int x = 0; x < 3; ++x)
      {
        s[x] = static_cast<float>(s[x] + delta(a, x));
      }
    }
  }
}

/// One path sampled by arc length from its lower base vertex to its higher one.
struct PathSamples
{
  int32_t level = 0;            // finer level of its two charts
  std::vector<int32_t> segment; // per sample: piece (point i to i + 1) of the path
  std::vector<double> tau;      // per sample: fraction along that piece
  std::vector<float> values;    // per sample: SampleLayout::size floats (shared normal)
};

struct Box
{
  std::array<double, 12> corners{};
};

/// The axis-aligned box of `points` in the frame of the rotation R (rows = axes), as c0 and its
/// three neighbours along the axes, back in world coordinates.
Box boxInFrame(const std::vector<Vec3>& points, const Eigen::Matrix3d& R)
{
  Vec3 lo = Vec3::Constant(std::numeric_limits<double>::infinity()), hi = -lo;
  for (const Vec3& q : points)
  {
    const Vec3 r = R * q;
    lo = lo.cwiseMin(r);
    hi = hi.cwiseMax(r);
  }
  Box b;
  const Vec3 c[4] = { lo, Vec3(hi.x(), lo.y(), lo.z()), Vec3(lo.x(), hi.y(), lo.z()),
    Vec3(lo.x(), lo.y(), hi.z()) };
  for (int i = 0; i < 4; ++i)
  {
    const Vec3 w = R.transpose() * c[i];
    for (int x = 0; x < 3; ++x)
    {
      b.corners[3 * i + x] = w[x];
    }
  }
  return b;
}

/// `x` to 8 significant decimal digits: the chart table's doubles (box corners, level errors)
/// feed estimates that the renderer evaluates in float (7.2 digits), and as the shortest decimal
/// text that reads back to the same double they take half the atlas file's metadata bytes of
/// full-precision values (on fandisk_large's 666 charts the box alone took 73 of 120 KB).
double storageRounded(double x)
{
  char text[32];
  std::snprintf(text, sizeof(text), "%.8g", x);
  return std::strtod(text, nullptr);
}

/// The box with every corner rounded by storageRounded after each axis of non-zero length grew
/// at both ends by more than that rounding can move a corner (3 x 5e-8 of the largest
/// coordinate), so it still holds every point. A flat box (a planar chart) stays flat: its points
/// may then lie off its rounded plane by the rounding, 5e-8 of the largest coordinate.
std::array<double, 12> storableBox(const std::array<double, 12>& corners)
{
  double largest = 0.0;
  for (double x : corners)
  {
    largest = std::max(largest, std::abs(x));
  }
  const double grow = 2e-7 * largest;
  std::array<double, 12> out = corners;
  Vec3 c0(corners[0], corners[1], corners[2]);
  Vec3 shift = Vec3::Zero();
  for (int k = 0; k < 3; ++k)
  {
    const Vec3 axis = Vec3(corners[3 + 3 * k], corners[4 + 3 * k], corners[5 + 3 * k]) - c0;
    const double length = axis.norm();
    const Vec3 unit = length > 0.0 ? Vec3(axis / length) : Vec3::Zero();
    shift -= grow * unit;
    for (int x = 0; x < 3; ++x)
    {
      out[3 + 3 * k + x] += 2.0 * grow * unit[x];
    }
  }
  for (int x = 0; x < 3; ++x)
  {
    out[x] += shift[x];
    for (int k = 0; k < 3; ++k)
    {
      out[3 + 3 * k + x] += shift[x];
    }
  }
  for (double& x : out)
  {
    x = storageRounded(x);
  }
  return out;
}

/// Oriented bounding box along the principal axes of the patch's points. Written by hand
/// rather than with CGAL::oriented_bounding_box: CGAL's optimal-box search costs 20-50 ms per
/// chart whatever its size (measured), tens of seconds for the thousand charts a detailed mesh
/// can have, while the box only feeds the projected-area LOD estimate of eq. 6, for which
/// principal axes are close enough.
/// With `also`: points the box must hold as well, which do not set its axes (fitted samples).
Box orientedBox(const std::vector<Vec3>& points, const std::vector<Vec3>* also = nullptr)
{
  Vec3 mean = Vec3::Zero();
  for (const Vec3& q : points)
  {
    mean += q;
  }
  mean /= static_cast<double>(std::max<size_t>(points.size(), 1));
  Eigen::Matrix3d cov = Eigen::Matrix3d::Zero();
  for (const Vec3& q : points)
  {
    cov += (q - mean) * (q - mean).transpose();
  }
  const Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> eig(cov);
  Eigen::Matrix3d R = eig.eigenvectors().transpose();
  if (!R.allFinite() || (R * R.transpose() - Eigen::Matrix3d::Identity()).norm() > 1e-6)
  {
    R = Eigen::Matrix3d::Identity();
  }
  if (!also)
  {
    return boxInFrame(points, R);
  }
  std::vector<Vec3> all(points);
  all.insert(all.end(), also->begin(), also->end());
  return boxInFrame(all, R);
}

/// d_max per chart: the largest alpha with floor(log4(alpha A_c)) clamped to [minLevel,
/// maxLevel] whose total of samples fits the budget. Levels rise in order of alpha; charts whose
/// thresholds tie (symmetric patches) rise together or not at all.
std::vector<int32_t> chooseLevels(
  const std::vector<double>& weightedArea, const GeometryImageOptions& o, int64_t budget)
{
  const int32_t n = static_cast<int32_t>(weightedArea.size());
  std::vector<int32_t> level(n, o.minLevel);
  int64_t total = n * gridSamples(o.minLevel);
  struct Event
  {
    double logAlpha;
    int32_t chart;
  };
  std::vector<Event> events;
  for (int32_t c = 0; c < n; ++c)
  {
    if (weightedArea[c] > 0.0 && std::isfinite(weightedArea[c]))
    {
      for (int32_t d = o.minLevel + 1; d <= o.maxLevel; ++d)
      {
        events.push_back({ d * std::log(4.0) - std::log(weightedArea[c]), c });
      }
    }
  }
  std::sort(events.begin(), events.end(),
    [](const Event& a, const Event& b)
    { return a.logAlpha < b.logAlpha || (a.logAlpha == b.logAlpha && a.chart < b.chart); });
  for (size_t i = 0; i < events.size();)
  {
    const double tol = 1e-9 * std::max(1.0, std::abs(events[i].logAlpha));
    size_t j = i;
    int64_t delta = 0;
    while (j < events.size() && events[j].logAlpha <= events[i].logAlpha + tol)
    {
      const int32_t d = level[events[j].chart];
      delta += gridSamples(d + 1) - gridSamples(d);
      ++j;
    }
    if (total + delta > budget)
    {
      break;
    }
    for (size_t k = i; k < j; ++k)
    {
      ++level[events[k].chart];
    }
    total += delta;
    i = j;
  }
  return level;
}

/// d_max per chart by measured error: from minLevel everywhere, the charts whose levelError at
/// their current level is largest rise one level while the rise fits the budget. Errors within
/// `tolerance` of the largest count as a tie and rise together or not at all (as chooseLevels
/// does for tied areas): congruent charts keep one d_max, and flat charts, whose errors are
/// only float rounding, share the budget evenly instead of in the order of their noise. A chart
/// at its cap (the last level measured) drops out; a group whose rise does not fit drops out
/// and the next largest errors are tried, so what is left of the budget still goes to the
/// worst charts that fit. With errors that fall with the level, every chart raised while the
/// largest error is above the area rule's was below its area level, so its rise fitted: the
/// largest error ends no higher than with the area rule (a feasible allocation below the caps).
std::vector<int32_t> allocateByError(const std::vector<std::vector<double>>& levelError,
  const GeometryImageOptions& o, int64_t budget, double tolerance)
{
  const int32_t n = static_cast<int32_t>(levelError.size());
  std::vector<int32_t> level(n, o.minLevel);
  int64_t total = n * gridSamples(o.minLevel);
  using Entry = std::pair<double, int32_t>;
  // Largest error on top; the lower id first on a tie, so the group is gathered in one order.
  auto below = [](const Entry& a, const Entry& b)
  { return a.first < b.first || (a.first == b.first && a.second > b.second); };
  std::vector<Entry> heap;
  heap.reserve(n);
  for (int32_t c = 0; c < n; ++c)
  {
    heap.emplace_back(levelError[c][o.minLevel], c);
  }
  std::make_heap(heap.begin(), heap.end(), below);
  std::vector<int32_t> group;
  while (!heap.empty())
  {
    const double largest = heap.front().first;
    group.clear();
    int64_t cost = 0;
    while (!heap.empty() && heap.front().first >= largest - tolerance)
    {
      std::pop_heap(heap.begin(), heap.end(), below);
      const int32_t c = heap.back().second;
      heap.pop_back();
      const int32_t d = level[c];
      if (d + 1 < static_cast<int32_t>(levelError[c].size()))
      {
        group.push_back(c);
        cost += gridSamples(d + 1) - gridSamples(d);
      }
    }
    if (total + cost > budget)
    {
      continue;
    }
    total += cost;
    for (int32_t c : group)
    {
      ++level[c];
      heap.emplace_back(levelError[c][level[c]], c);
      std::push_heap(heap.begin(), heap.end(), below);
    }
  }
  return level;
}

/// A rectangle of the packing: one chart pair (or a lone chart) in one image.
struct PackUnit
{
  int32_t first = -1;  // higher d_max, lower-left
  int32_t second = -1; // upper-right, turned by 180 degrees (-1: none)
};

/// Shelf packing of the rectangles of image k (tallest first, left to right, rows bottom to
/// top); returns the lower-left corner of each unit present (x = -1 for a unit absent from this
/// image) and the image size. The width is a multiple of 4 from the widest rectangle up to
/// twice sqrt(total area): the one that gives the shortest longer side (GPU textures are
/// limited in width and height, not area), the smaller image on a tie.
void packImage(const std::vector<PackUnit>& units, const std::vector<int32_t>& level, int32_t k,
  std::vector<std::array<int32_t, 2>>& corner, int32_t& width, int32_t& height)
{
  struct Rect
  {
    int32_t unit, w, h;
  };
  std::vector<Rect> rects;
  double area = 0.0;
  int32_t widest = 0;
  for (size_t u = 0; u < units.size(); ++u)
  {
    const int32_t d = level[units[u].first] - k;
    if (d < 0)
    {
      continue;
    }
    const int32_t n = int32_t(1) << d;
    // (2^dh + 2) x (2^dh + 1) for a pair: the two diagonals are separate texel rows.
    const Rect r{ static_cast<int32_t>(u), units[u].second >= 0 ? n + 2 : n + 1, n + 1 };
    rects.push_back(r);
    area += double(r.w) * double(r.h);
    widest = std::max(widest, r.w);
  }
  std::stable_sort(
    rects.begin(), rects.end(), [](const Rect& a, const Rect& b) { return a.h > b.h; });
  auto shelves = [&rects](int32_t w, std::vector<std::array<int32_t, 2>>* at)
  {
    int32_t x = 0, y = 0, shelf = 0;
    for (const Rect& r : rects)
    {
      if (x + r.w > w)
      {
        y += shelf;
        x = 0;
        shelf = 0;
      }
      if (at)
      {
        (*at)[r.unit] = { x, y };
      }
      x += r.w;
      shelf = std::max(shelf, r.h);
    }
    return y + shelf;
  };
  const int32_t first = (widest + 3) / 4 * 4;
  const int32_t last = std::max(first, static_cast<int32_t>(std::ceil(2.0 * std::sqrt(area))));
  width = first;
  height = shelves(first, nullptr);
  for (int32_t w = first + 4; w <= last; w += 4)
  {
    const int32_t h = shelves(w, nullptr);
    const int32_t side = std::max(w, h), bestSide = std::max(width, height);
    const int64_t size = int64_t(w) * h, best = int64_t(width) * height;
    if (side < bestSide || (side == bestSide && size < best))
    {
      width = w;
      height = h;
    }
  }
  corner.assign(units.size(), { -1, -1 });
  shelves(width, &corner);
}
/// Refuses options out of range, saying which and what is allowed.
void checkOptions(const GeometryImageOptions& options)
{
  const std::string where = "geometry images: ";
  if (options.minLevel < 0 || options.maxLevel > kMaxLevelLimit ||
    options.minLevel > options.maxLevel)
  {
    throw InputError(where +
      "levels must satisfy 0 <= minLevel <= maxLevel <= " + num(kMaxLevelLimit) + " (got " +
      num(options.minLevel) + " and " + num(options.maxLevel) + ")");
  }
  if (!(options.curvatureWeight >= 0.0) || !std::isfinite(options.curvatureWeight))
  {
    throw InputError(where + "curvatureWeight must be finite and >= 0");
  }
  if (options.levelRule != LevelRule::Area && options.levelRule != LevelRule::Error)
  {
    throw InputError(where + "levelRule must be LevelRule::Area (0) or LevelRule::Error (1), not " +
      num(static_cast<int32_t>(options.levelRule)));
  }
  if (options.stretchIterations < 0 || options.stretchIterations > kMaxStretchIterations)
  {
    throw InputError(where + "stretchIterations must be 0 .. " + num(kMaxStretchIterations) +
      " (0: Floater's mean-value map alone), not " + num(options.stretchIterations));
  }
  if (options.sampleBudget < 0)
  {
    throw InputError(where + "sampleBudget must be >= 0 (0: as many samples as input points)");
  }
}

} // namespace

PatchParameterization parameterizePatch(const PatchMesh& patches, const BaseComplexResult& base,
  int32_t patch, const GeometryImageOptions& options)
{
  checkOptions(options);
  const Layout L = checkInput(patches, base);
  if (patch < 0 || patch >= L.numCharts)
  {
    throw InputError("geometry images: patch " + num(patch) + " does not exist (0 .. " +
      num(L.numCharts - 1) + ")");
  }
  return parameterize(patches, base, L, patch, options.stretchIterations);
}

Atlas buildGeometryImages(const PatchMesh& patches, const BaseComplexResult& base,
  const std::vector<double>& normals, const std::vector<double>& meanCurvature,
  const std::vector<GeometryImageAttribute>& extra, const GeometryImageOptions& options,
  const Progress& progress)
{
  const std::string where = "geometry images: ";
  checkOptions(options);
  const Layout L = checkInput(patches, base);
  const TriMesh& mesh = patches.mesh;
  const int64_t nv = L.numPoints;
  const int32_t nc = L.numCharts;
  if (!normals.empty() && static_cast<int64_t>(normals.size()) != 3 * nv)
  {
    throw InputError(where + "normals has " + num(normals.size()) + " values; it needs 3 per " +
      "point of the patch mesh (" + num(3 * nv) + ") or none");
  }
  if (!meanCurvature.empty() && static_cast<int64_t>(meanCurvature.size()) != nv)
  {
    throw InputError(where + "meanCurvature has " + num(meanCurvature.size()) + " values; it " +
      "needs one per point of the patch mesh (" + num(nv) + ") or none");
  }
  for (const std::vector<double>* a : { &normals, &meanCurvature })
  {
    if (!std::all_of(a->begin(), a->end(), [](double x) { return std::isfinite(x); }))
    {
      throw InputError(where + "normals and meanCurvature must be finite");
    }
  }
  SampleLayout S;
  S.components = { 3, 3 };
  for (size_t a = 0; a < extra.size(); ++a)
  {
    const GeometryImageAttribute& x = extra[a];
    if (x.name.empty() || x.name == kAtlasPosition || x.name == kAtlasNormal)
    {
      throw InputError(where + "extra attribute " + num(a) + " needs a name other than \"" +
        kAtlasPosition + "\" and \"" + kAtlasNormal + "\"");
    }
    for (size_t b = 0; b < a; ++b)
    {
      if (extra[b].name == x.name)
      {
        throw InputError(where + "two extra attributes are named \"" + x.name + "\"");
      }
    }
    if (x.components < 1 || x.components > kMaxComponents ||
      static_cast<int64_t>(x.values.size()) != nv * x.components)
    {
      throw InputError(where + "extra attribute \"" + x.name + "\" needs 1 .. " +
        num(kMaxComponents) + " components and #points x components (" + num(nv) + " x " +
        num(x.components) + ") values; it has " + num(x.values.size()));
    }
    if (!std::all_of(x.values.begin(), x.values.end(), [](double v) { return std::isfinite(v); }))
    {
      throw InputError(where + "extra attribute \"" + x.name + "\" has a non-finite value");
    }
    S.components.push_back(x.components);
  }
  for (int32_t c : S.components)
  {
    S.offset.push_back(S.size);
    S.size += c;
  }
  const int32_t numAttributes = static_cast<int32_t>(S.components.size());

  Atlas atlas;
  atlas.attributes.push_back({ kAtlasPosition, 3 });
  atlas.attributes.push_back({ kAtlasNormal, 3 });
  for (const GeometryImageAttribute& x : extra)
  {
    atlas.attributes.push_back({ x.name, x.components });
  }
  {
    Vec3 lo = Vec3::Constant(std::numeric_limits<double>::infinity()), hi = -lo;
    bool any = false;
    for (int64_t v = 0; v < nv; ++v)
    {
      if (patches.inputPointId[v] >= 0)
      {
        ++atlas.inputPoints;
        lo = lo.cwiseMin(pointOf(mesh, v));
        hi = hi.cwiseMax(pointOf(mesh, v));
        any = true;
      }
    }
    atlas.inputDiagonal = any ? (hi - lo).norm() : 0.0;
    int32_t maxTriangle = -1;
    for (int32_t t : patches.inputTriangle)
    {
      maxTriangle = std::max(maxTriangle, t);
    }
    atlas.inputTriangles = int64_t(maxTriangle) + 1;
  }

  // Shared (two-sided) unit normals of every point.
  std::vector<double> shared(3 * static_cast<size_t>(nv), 0.0);
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
  progress.report(0.02);

  // 1. Parameterize every patch and measure its curvature-weighted area.
  std::vector<PatchParameterization> param(nc);
  std::vector<std::string> failure(nc);
  std::vector<double> weightedArea(nc, 0.0);
  const double diagonal = atlas.inputDiagonal;
  parallel_for(
    nc,
    [&](int64_t c)
    {
      try
      {
        param[c] =
          parameterize(patches, base, L, static_cast<int32_t>(c), options.stretchIterations);
      }
      catch (const InputError& e)
      {
        failure[c] = e.what();
        return;
      }
      double sum = 0.0;
      for (int64_t s = L.patchOffsets[c]; s < L.patchOffsets[c + 1]; ++s)
      {
        const int32_t* t = &mesh.triangles[3 * static_cast<int64_t>(L.patchTriangles[s])];
        const double area = 0.5 *
          (pointOf(mesh, t[1]) - pointOf(mesh, t[0]))
            .cross(pointOf(mesh, t[2]) - pointOf(mesh, t[0]))
            .norm();
        double h = 0.0;
        if (!meanCurvature.empty())
        {
          h = (std::abs(meanCurvature[t[0]]) + std::abs(meanCurvature[t[1]]) +
                std::abs(meanCurvature[t[2]])) /
            3.0;
        }
        sum += area * (1.0 + options.curvatureWeight * h * diagonal);
      }
      weightedArea[c] = sum;
    },
    progress.sub(0.02, 0.45), blockSteps(nc));
  for (const std::string& f : failure)
  {
    if (!f.empty())
    {
      throw InputError(f);
    }
  }

  // 2. The budget and the area rule's d_max of every chart.
  const int64_t minimum = nc * gridSamples(options.minLevel);
  int64_t budget = options.sampleBudget;
  if (budget == 0)
  {
    budget = std::max(minimum, atlas.inputPoints);
  }
  else if (budget < minimum)
  {
    throw InputError(where + "sampleBudget " + num(budget) + " is below " + num(minimum) +
      ", what " + num(nc) + " charts need at minLevel " + num(options.minLevel) +
      "; raise sampleBudget or lower minLevel");
  }
  // The area rule's levels are the result (LevelRule::Area) or, raised by
  // kErrorRuleLevelsAbove, the levels up to which the error rule measures each chart.
  std::vector<int32_t> sampled = chooseLevels(weightedArea, options, budget);
  if (options.levelRule == LevelRule::Error)
  {
    for (int32_t& d : sampled)
    {
      d = std::min(d + kErrorRuleLevelsAbove, options.maxLevel);
    }
  }

  atlas.charts.resize(nc);
  for (int32_t c = 0; c < nc; ++c)
  {
    AtlasChart& ch = atlas.charts[c];
    for (int k = 0; k < 3; ++k)
    {
      ch.cornerVertex[k] = patches.inputPointId[base.baseVertices[base.baseTriangles[3 * c + k]]];
      const int32_t e = patches.faceEdges[3 * c + k];
      const int slot = L.edgeChart[2 * e] == c && L.edgeSide[2 * e] == k ? 1 : 0;
      ch.neighborChart[k] = L.edgeChart[2 * e + slot];
      ch.neighborSide[k] = L.edgeSide[2 * e + slot];
      ch.featureSide[k] = L.edgeFeature[e];
    }
  }

  // 3. Corners and paths: sampled once, in float, and copied into every chart that shares them.
  auto sharedValues = [&](int64_t v, float* out)
  {
    for (int x = 0; x < 3; ++x)
    {
      out[x] = static_cast<float>(mesh.points[3 * v + x]);
      out[3 + x] = static_cast<float>(shared[3 * v + x]);
    }
    for (size_t a = 0; a < extra.size(); ++a)
    {
      const int32_t nComp = extra[a].components;
      for (int32_t x = 0; x < nComp; ++x)
      {
        out[S.offset[a + 2] + x] = static_cast<float>(extra[a].values[v * nComp + x]);
      }
    }
  };
  const int32_t ne = L.numEdges;
  // Base vertices on a feature curve: the shared normal there averages across the crease.
  std::vector<uint8_t> featureVertex(base.baseVertices.size(), 0);
  for (int32_t e = 0; e < ne; ++e)
  {
    if (L.edgeFeature[e])
    {
      featureVertex[patches.baseEdges[2 * e]] = 1;
      featureVertex[patches.baseEdges[2 * e + 1]] = 1;
    }
  }
  std::vector<PathSamples> paths(ne);
  parallel_for(
    ne,
    [&](int64_t e)
    {
      PathSamples& ps = paths[e];
      ps.level = std::max(sampled[L.edgeChart[2 * e]], sampled[L.edgeChart[2 * e + 1]]);
      const int64_t q1 = int64_t(1) << ps.level;
      const int64_t p0 = patches.pathOffsets[e], p1 = patches.pathOffsets[e + 1];
      std::vector<double> arc(p1 - p0, 0.0);
      for (int64_t i = 1; i < p1 - p0; ++i)
      {
        arc[i] = arc[i - 1] +
          (pointOf(mesh, patches.pathPoints[p0 + i]) -
            pointOf(mesh, patches.pathPoints[p0 + i - 1]))
            .norm();
      }
      const double length = arc.back();
      ps.segment.resize(q1 + 1);
      ps.tau.resize(q1 + 1);
      ps.values.resize((q1 + 1) * S.size);
      // Normals along the path: the shared ones, except at an end on a feature curve, where the
      // shared normal averages across the crease: there the normal of the two charts' own
      // triangles (e.g. the face normal where a diagonal meets a cube corner).
      const int64_t last = p1 - p0 - 1;
      Vec3 endNormal[2];
      for (int end = 0; end < 2; ++end)
      {
        const int32_t v = patches.pathPoints[end == 0 ? p0 : p1 - 1];
        endNormal[end] =
          Vec3(shared[3 * int64_t(v)], shared[3 * int64_t(v) + 1], shared[3 * int64_t(v) + 2]);
        if (!L.edgeFeature[e] && featureVertex[patches.baseEdges[2 * e + end]])
        {
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
            endNormal[end] = n.normalized();
          }
        }
      }
      auto normalAt = [&](int64_t i)
      {
        const int32_t v = patches.pathPoints[p0 + i];
        return i == 0 ? endNormal[0]
                      : (i == last ? endNormal[1]
                                   : Vec3(shared[3 * int64_t(v)], shared[3 * int64_t(v) + 1],
                                       shared[3 * int64_t(v) + 2]));
      };
      for (int64_t q = 0; q <= q1; ++q)
      {
        float* out = &ps.values[q * S.size];
        if (q == 0 || q == q1)
        {
          // The corners: the base vertex's own values.
          ps.segment[q] = q == 0 ? 0 : static_cast<int32_t>(p1 - p0 - 2);
          ps.tau[q] = q == 0 ? 0.0 : 1.0;
          sharedValues(patches.pathPoints[q == 0 ? p0 : p1 - 1], out);
          continue;
        }
        // Arc length q / 2^level of the way along the path.
        const double s = length * static_cast<double>(q) / static_cast<double>(q1);
        int64_t i = std::upper_bound(arc.begin(), arc.end(), s) - arc.begin() - 1;
        i = std::clamp<int64_t>(i, 0, p1 - p0 - 2);
        const double piece = arc[i + 1] - arc[i];
        const double tau = piece > 0.0 ? std::clamp((s - arc[i]) / piece, 0.0, 1.0) : 0.0;
        ps.segment[q] = static_cast<int32_t>(i);
        ps.tau[q] = tau;
        const int64_t a = patches.pathPoints[p0 + i], b = patches.pathPoints[p0 + i + 1];
        for (int x = 0; x < 3; ++x)
        {
          out[x] =
            static_cast<float>((1.0 - tau) * mesh.points[3 * a + x] + tau * mesh.points[3 * b + x]);
        }
        Vec3 n = (1.0 - tau) * normalAt(i) + tau * normalAt(i + 1);
        n = n.norm() > 0.0 ? Vec3(n.normalized()) : n;
        for (int x = 0; x < 3; ++x)
        {
          out[3 + x] = static_cast<float>(n[x]);
        }
        for (size_t at = 0; at < extra.size(); ++at)
        {
          const int32_t nComp = extra[at].components;
          for (int32_t x = 0; x < nComp; ++x)
          {
            out[S.offset[at + 2] + x] =
              static_cast<float>((1.0 - tau) * extra[at].values[a * nComp + x] +
                tau * extra[at].values[b * nComp + x]);
          }
        }
      }
    },
    progress.sub(0.45, 0.5), blockSteps(ne));

  // 4. Every chart's grid at its sampled level, its error per level and its oriented bounding
  // box.
  std::vector<ChartGrid> grids(nc);
  std::vector<std::vector<std::array<int32_t, 2>>> creases(nc);
  parallel_for(
    nc,
    [&](int64_t c)
    {
      const PatchParameterization& p = param[c];
      AtlasChart& ch = atlas.charts[c];
      const int32_t np = static_cast<int32_t>(p.points.size());
      creases[c] = patchCreases(mesh, p);
      auto local = [&p](int32_t v)
      {
        return static_cast<int32_t>(
          std::lower_bound(p.points.begin(), p.points.end(), v) - p.points.begin());
      };

      // Normals of this chart's points: shared, except one-sided ones (from this patch's
      // triangles only) on the sides that follow a feature curve and at corners on one, so the
      // crease stays sharp.
      std::vector<double> own(3 * static_cast<size_t>(np), 0.0);
      for (int32_t v = 0; v < np; ++v)
      {
        for (int x = 0; x < 3; ++x)
        {
          own[3 * v + x] = shared[3 * static_cast<int64_t>(p.points[v]) + x];
        }
      }
      bool featureCorner = false;
      for (int k = 0; k < 3; ++k)
      {
        featureCorner = featureCorner || featureVertex[base.baseTriangles[3 * c + k]];
      }
      if (featureCorner)
      {
        std::vector<double> oneSided(3 * static_cast<size_t>(np), 0.0);
        accumulateNormals(mesh, p.meshTriangles.data(),
          static_cast<int64_t>(p.meshTriangles.size()), p.triangles, oneSided);
        normalizeRows(oneSided);
        for (int k = 0; k < 3; ++k)
        {
          if (featureVertex[base.baseTriangles[3 * c + k]])
          {
            const int32_t l = local(ch.cornerVertex[k]);
            std::copy(&oneSided[3 * l], &oneSided[3 * l] + 3, &own[3 * l]);
          }
          if (!ch.featureSide[k])
          {
            continue;
          }
          for (int32_t v : sidePath(patches, base, static_cast<int32_t>(c), k))
          {
            const int32_t l = local(v);
            std::copy(&oneSided[3 * l], &oneSided[3 * l] + 3, &own[3 * l]);
          }
        }
      }

      ChartGrid& g = grids[c];
      const int32_t dmax = sampled[c];
      g.n = int64_t(1) << dmax;
      g.size = S.size;
      const int64_t n = g.n;
      g.values.assign(static_cast<size_t>(gridSamples(dmax)) * S.size, 0.0f);
      const UvLocator locator(p);
      for (int64_t j = 0; j <= n; ++j)
      {
        for (int64_t i = 0; i + j <= n; ++i)
        {
          float* out = &g.values[gridIndex(n, i, j) * S.size];
          // Side k and parameter t of a boundary sample (-1: interior).
          int k = -1;
          int64_t t = 0;
          if (j == 0)
          {
            k = 0;
            t = i;
          }
          else if (i + j == n)
          {
            k = 1;
            t = j;
          }
          else if (i == 0)
          {
            k = 2;
            t = n - j;
          }
          if (k >= 0)
          {
            const int32_t e = patches.faceEdges[3 * c + k];
            const PathSamples& ps = paths[e];
            const bool forward = base.baseTriangles[3 * c + k] == patches.baseEdges[2 * e];
            const int64_t q = (forward ? t : n - t) << (ps.level - dmax);
            const float* src = &ps.values[q * S.size];
            std::copy(src, src + S.size, out);
            const int64_t q1 = int64_t(1) << ps.level;
            if (ch.featureSide[k] && q != 0 && q != q1)
            {
              const int64_t at = patches.pathOffsets[e] + ps.segment[q];
              const int32_t a = local(patches.pathPoints[at]);
              const int32_t b = local(patches.pathPoints[at + 1]);
              const double tau = ps.tau[q];
              Vec3 nn;
              for (int x = 0; x < 3; ++x)
              {
                nn[x] = (1.0 - tau) * own[3 * a + x] + tau * own[3 * b + x];
              }
              nn = nn.norm() > 0.0 ? Vec3(nn.normalized()) : nn;
              for (int x = 0; x < 3; ++x)
              {
                out[3 + x] = static_cast<float>(nn[x]);
              }
            }
            continue;
          }
          const UvLocator::Hit hit =
            locator.locate(static_cast<double>(i) / n, static_cast<double>(j) / n);
          const int32_t* tri = &p.triangles[3 * static_cast<int64_t>(hit.triangle)];
          Vec3 pos = Vec3::Zero(), nn = Vec3::Zero();
          for (int r = 0; r < 3; ++r)
          {
            pos += hit.w[r] * pointOf(mesh, p.points[tri[r]]);
            nn += hit.w[r] * Vec3(own[3 * tri[r]], own[3 * tri[r] + 1], own[3 * tri[r] + 2]);
          }
          nn = nn.norm() > 0.0 ? Vec3(nn.normalized()) : nn;
          for (int x = 0; x < 3; ++x)
          {
            out[x] = static_cast<float>(pos[x]);
            out[3 + x] = static_cast<float>(nn[x]);
          }
          for (size_t at = 0; at < extra.size(); ++at)
          {
            const int32_t nComp = extra[at].components;
            for (int32_t x = 0; x < nComp; ++x)
            {
              double v = 0.0;
              for (int r = 0; r < 3; ++r)
              {
                v += hit.w[r] * extra[at].values[int64_t(p.points[tri[r]]) * nComp + x];
              }
              out[S.offset[at + 2] + x] = static_cast<float>(v);
            }
          }
        }
      }

      ch.levelError = chartLevelErrors(mesh, p, g, creases[c], dmax);
    },
    progress.sub(0.5, 0.85), blockSteps(nc));

  // 5. d_max of every chart under the budget; level d of a chart is its sampled grid at stride
  // 2^(sampled - d), whatever d_max is chosen.
  std::vector<int32_t> level = sampled;
  if (options.levelRule == LevelRule::Error)
  {
    std::vector<std::vector<double>> errors(nc);
    for (int32_t c = 0; c < nc; ++c)
    {
      errors[c] = atlas.charts[c].levelError;
    }
    // Float samples round each coordinate by up to 6e-8 of its magnitude: errors closer than
    // 1e-6 of the model's size (and of its distance from the origin) are not told apart.
    double extent = 0.0;
    for (double x : mesh.points)
    {
      extent = std::max(extent, std::abs(x));
    }
    level = allocateByError(errors, options, budget, 1e-6 * (diagonal + extent));
  }
  if (options.fitSamples)
  {
    // Sides first, then the interiors with their sides fixed. Eq. 8 draws a side at the lower
    // level of its two charts, so a side is fitted at the lower d_max of its two charts, the
    // finest level at which it is ever drawn, and written into both. The finer chart's samples
    // between those (drawn by no level: stitching moves them onto the coarser ones) are put on
    // the straight line between them, so its interior is fitted against the side it is drawn
    // with and its levelError measures that side.
    auto sideSample = [&](int32_t c, int k, int64_t t) -> float*
    {
      const int64_t n = int64_t(1) << level[c];
      const int64_t i = k == 0 ? t : (k == 1 ? n - t : 0);
      const int64_t j = k == 0 ? 0 : (k == 1 ? t : n - t);
      return grids[c].at(level[c], i, j);
    };
    parallel_for(
      ne,
      [&](int64_t e)
      {
        if (L.edgeFeature[e])
        {
          return; // a feature curve stays sampled on the curve, so the crease stays in place
        }
        const int32_t d = std::min(level[L.edgeChart[2 * e]], level[L.edgeChart[2 * e + 1]]);
        const int32_t finer = std::max(level[L.edgeChart[2 * e]], level[L.edgeChart[2 * e + 1]]);
        // Sample q of the path (lower base vertex first) at level d.
        const PathSamples& ps = paths[e];
        auto at = [&](int64_t q)
        {
          const float* v = &ps.values[(q << (ps.level - d)) * S.size];
          return Vec3(v[0], v[1], v[2]);
        };
        const int64_t p0 = patches.pathOffsets[e], p1 = patches.pathOffsets[e + 1];
        std::vector<Vec3> fitted = fitPath(mesh, &patches.pathPoints[p0], p1 - p0, d, at);
        if (fitted.empty())
        {
          if (finer == d)
          {
            return;
          }
          // Not fitted (a level below 1): the drawn samples stay, the finer chart's others
          // still go onto the straight lines between them.
          fitted.resize((size_t(1) << d) + 1);
          for (size_t q = 0; q < fitted.size(); ++q)
          {
            fitted[q] = at(static_cast<int64_t>(q));
          }
        }
        for (int slot = 0; slot < 2; ++slot)
        {
          const int32_t c = L.edgeChart[2 * e + slot], k = L.edgeSide[2 * e + slot];
          const bool forward = base.baseTriangles[3 * c + k] == patches.baseEdges[2 * e];
          const int32_t shift = level[c] - d;
          const int64_t n = int64_t(1) << level[c];
          for (int64_t t = 1; t < n; ++t)
          {
            // Place along the path at this chart's level: drawn sample q, or between q and q+1.
            const int64_t r = forward ? t : n - t;
            const int64_t q = r >> shift;
            const int64_t rest = r - (q << shift);
            Vec3 value = fitted[q];
            if (rest != 0)
            {
              const double w = static_cast<double>(rest) / static_cast<double>(int64_t(1) << shift);
              value = (1.0 - w) * fitted[q] + w * fitted[q + 1];
            }
            float* out = sideSample(c, k, t);
            for (int x = 0; x < 3; ++x)
            {
              out[x] = static_cast<float>(value[x]);
            }
          }
        }
      },
      progress.sub(0.85, 0.87), blockSteps(ne));
  }
  parallel_for(
    nc,
    [&](int64_t c)
    {
      AtlasChart& ch = atlas.charts[c];
      ch.maxLevel = level[c];
      std::vector<Vec3> pts(param[c].points.size());
      for (size_t v = 0; v < pts.size(); ++v)
      {
        pts[v] = pointOf(mesh, param[c].points[v]);
      }
      if (options.fitSamples)
      {
        fitInterior(mesh, param[c], grids[c], S, level[c]);
        ch.levelError = chartLevelErrors(mesh, param[c], grids[c], creases[c], level[c]);
        // The box holds the fitted samples too (they leave the surface), with the axes of the
        // patch's points.
        const int64_t n = int64_t(1) << level[c];
        std::vector<Vec3> samples;
        for (int64_t j = 0; j <= n; ++j)
        {
          for (int64_t i = 0; i + j <= n; ++i)
          {
            const float* q = grids[c].at(level[c], i, j);
            samples.emplace_back(q[0], q[1], q[2]);
          }
        }
        ch.box = storableBox(orientedBox(pts, &samples).corners);
      }
      else
      {
        ch.box = storableBox(orientedBox(pts).corners);
      }
      ch.levelError.resize(static_cast<size_t>(level[c]) + 1);
      for (double& e : ch.levelError)
      {
        e = storageRounded(e);
      }
    },
    progress.sub(0.87, 0.9), blockSteps(nc));

  // 6. Packing (paper 5.2): charts sorted by d_max, each paired with the next closest one; one
  // image per mip step, rectangles placed by a shelf packer.
  std::vector<int32_t> order(nc);
  std::iota(order.begin(), order.end(), 0);
  std::stable_sort(
    order.begin(), order.end(), [&level](int32_t a, int32_t b) { return level[a] > level[b]; });
  std::vector<PackUnit> units;
  for (size_t i = 0; i < order.size(); i += 2)
  {
    PackUnit u;
    u.first = order[i];
    u.second = i + 1 < order.size() ? order[i + 1] : -1;
    units.push_back(u);
    if (u.second >= 0)
    {
      atlas.charts[u.first].partner = u.second;
      atlas.charts[u.second].partner = u.first;
      atlas.charts[u.second].rotated = 1;
    }
  }
  const int32_t numImages = atlas.maxLevel() + 1;
  atlas.images.resize(numImages);
  for (AtlasChart& ch : atlas.charts)
  {
    ch.origin.assign(static_cast<size_t>(ch.maxLevel) + 1, { 0, 0 });
  }
  for (int32_t k = 0; k < numImages; ++k)
  {
    std::vector<std::array<int32_t, 2>> corner;
    AtlasImage& image = atlas.images[k];
    packImage(units, level, k, corner, image.width, image.height);
    for (size_t u = 0; u < units.size(); ++u)
    {
      if (corner[u][0] < 0)
      {
        continue;
      }
      const int32_t n = int32_t(1) << (level[units[u].first] - k);
      atlas.charts[units[u].first].origin[k] = corner[u];
      const int32_t second = units[u].second;
      if (second >= 0 && level[second] >= k)
      {
        atlas.charts[second].origin[k] = { corner[u][0] + n + 1, corner[u][1] + n };
      }
    }
    image.data.resize(numAttributes);
    for (int32_t a = 0; a < numAttributes; ++a)
    {
      image.data[a].assign(static_cast<size_t>(image.width) * static_cast<size_t>(image.height) *
          static_cast<size_t>(S.components[a]),
        0.0f);
    }
  }
  parallel_for(
    nc,
    [&](int64_t c)
    {
      const AtlasChart& ch = atlas.charts[c];
      const ChartGrid& g = grids[c];
      for (int32_t k = 0; k <= ch.maxLevel; ++k)
      {
        const int32_t d = ch.maxLevel - k;
        const int64_t nd = int64_t(1) << d;
        AtlasImage& image = atlas.images[k];
        for (int64_t j = 0; j <= nd; ++j)
        {
          for (int64_t i = 0; i + j <= nd; ++i)
          {
            // Level d is the sampled grid at stride 2^(sampled - d): the point-sampled pyramid.
            const float* src = g.at(d, i, j);
            const std::array<int32_t, 2> xy =
              atlasTexel(ch, d, static_cast<int32_t>(i), static_cast<int32_t>(j));
            const size_t texel = static_cast<size_t>(xy[1]) * image.width + xy[0];
            for (int32_t a = 0; a < numAttributes; ++a)
            {
              std::copy(src + S.offset[a], src + S.offset[a] + S.components[a],
                image.data[a].data() + texel * S.components[a]);
            }
          }
        }
      }
    },
    progress.sub(0.9, 1.0), blockSteps(nc));
  progress.report(1.0);
  return atlas;
}
} // namespace tc
