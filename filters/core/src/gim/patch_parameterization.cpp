// SPDX-License-Identifier: BSD-3-Clause
#include "gim/patch_parameterization.h"

#include "gim/geometry_images_vec3.h"
#include "tc/common/errors.h"

#include <Eigen/SparseCore>
#include <Eigen/SparseLU>

#include <algorithm>
#include <cmath>
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

namespace tc::detail::geometry_images
{
namespace
{
// Angles within this of pi are clamped before tan(angle / 2) (a flat triangle would give an
// infinite mean-value weight).
constexpr double kMaxAngle = kPi - 1e-6;
// A uv triangle whose height is below this fraction of its longest side counts as degenerate
// (three corners on one straight side of the domain, up to the rounding of 1 - f).
constexpr double kDegenerateRatio = 1e-12;

/// Index of point v in the ascending `points`, or -1.
int32_t localIndex(const std::vector<int32_t>& points, int32_t v)
{
  const auto it = std::lower_bound(points.begin(), points.end(), v);
  return it != points.end() && *it == v ? static_cast<int32_t>(it - points.begin()) : -1;
}

/// The points of patch c, ascending, its triangles (PatchParameterization::meshTriangles) and
/// their corners as indices into those points.
PatchParameterization collectPatch(const TriMesh& mesh, const Layout& L, int32_t c)
{
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
  p.triangles.resize(3 * nt);
  for (int64_t t = 0; t < nt; ++t)
  {
    for (int k = 0; k < 3; ++k)
    {
      p.triangles[3 * t + k] = localIndex(p.points, mesh.triangles[3 * p.meshTriangles[t] + k]);
    }
  }
  return p;
}

/// The oriented sides a -> b of the patch's triangles as sorted keys a * np + b; those whose
/// reverse is absent form the boundary.
struct OrientedSides
{
  std::vector<int64_t> keys;
  int32_t np = 0;
  int64_t boundary = 0; ///< sides whose reverse is absent

  bool has(int64_t a, int64_t b) const
  {
    return std::binary_search(keys.begin(), keys.end(), a * np + b);
  }
};

/// @throws InputError when two triangles share an oriented side (not an oriented manifold)
OrientedSides orientedSides(const PatchParameterization& p, const std::string& where)
{
  OrientedSides half;
  half.np = static_cast<int32_t>(p.points.size());
  const int32_t np = half.np;
  const int64_t nt = static_cast<int64_t>(p.triangles.size() / 3);
  half.keys.resize(3 * nt);
  for (int64_t i = 0; i < 3 * nt; ++i)
  {
    const int64_t a = p.triangles[i], b = p.triangles[i % 3 == 2 ? i - 2 : i + 1];
    half.keys[i] = a * np + b;
  }
  std::sort(half.keys.begin(), half.keys.end());
  const auto dup = std::adjacent_find(half.keys.begin(), half.keys.end());
  if (dup != half.keys.end())
  {
    throw InputError(where + "has two triangles with the same oriented side (" +
      num(p.points[*dup / np]) + ", " + num(p.points[*dup % np]) +
      "): the patch mesh is not a consistently oriented manifold");
  }
  for (int64_t h : half.keys)
  {
    half.boundary += half.has(h % np, h / np) ? 0 : 1;
  }
  return half;
}

/// The boundary map: side k's path, which must appear on the boundary from corner k to corner
/// k + 1 (counter-clockwise like the base face), is put on side k of the right triangle by arc
/// length. Sets the uv of its points and marks them fixed; returns the boundary loop.
/// @throws InputError when a piece of a path is not a boundary side of the patch
std::vector<int32_t> fixBoundary(const PatchMesh& pm, const BaseComplexResult& base, int32_t c,
  const OrientedSides& half, PatchParameterization& p, std::vector<uint8_t>& fixed,
  const std::string& where)
{
  const int32_t np = half.np;
  p.uv.assign(2 * static_cast<size_t>(np), 0.0);
  fixed.assign(np, 0);
  std::vector<int32_t> loop;
  for (int32_t k = 0; k < 3; ++k)
  {
    const std::vector<int32_t> path = sidePath(pm, base, c, k);
    const std::vector<double> arc =
      arcLengths(pm.mesh, path.data(), static_cast<int64_t>(path.size()));
    const double length = arc.back();
    for (size_t i = 0; i + 1 < path.size(); ++i)
    {
      const int32_t a = localIndex(p.points, path[i]), b = localIndex(p.points, path[i + 1]);
      if (a < 0 || b < 0 || !half.has(a, b) || half.has(b, a))
      {
        throw InputError(where + "is not bounded by the path of its side " + num(k) +
          " (base edge " + num(pm.faceEdges[3 * c + k]) + "): its piece " + num(path[i]) + "-" +
          num(path[i + 1]) + " is not a boundary side of the patch; check the traced paths");
      }
      loop.push_back(a);
      // The arc-length fraction f along side k, on the right triangle's side k.
      const double f = length > 0.0 ? arc[i] / length
                                    : static_cast<double>(i) / static_cast<double>(path.size() - 1);
      const double u = k == 0 ? f : (k == 1 ? 1.0 - f : 0.0);
      const double v = k == 0 ? 0.0 : (k == 1 ? f : 1.0 - f);
      p.uv[2 * a] = u;
      p.uv[2 * a + 1] = v;
      fixed[a] = 1;
    }
  }
  return loop;
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

/// @throws InputError when a point is not reachable from point 0 through the triangles
void checkConnected(const PatchParameterization& p, const std::string& where)
{
  const int32_t np = static_cast<int32_t>(p.points.size());
  const int64_t nt = static_cast<int64_t>(p.triangles.size() / 3);
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

/// Floater's theorem needs a disk: the three paths make the whole boundary, pass each point
/// once, the Euler characteristic is 1 and the patch is connected.
/// @throws InputError saying which of these fails
void checkDisk(const PatchParameterization& p, const OrientedSides& half,
  const std::vector<int32_t>& loop, const std::string& where)
{
  if (static_cast<int64_t>(loop.size()) != half.boundary)
  {
    throw InputError(where + "has " + num(half.boundary) +
      " boundary sides but its three paths have " + num(loop.size()) +
      ": it is not a disk bounded by its paths");
  }
  std::vector<int32_t> sorted = loop;
  std::sort(sorted.begin(), sorted.end());
  const auto twice = std::adjacent_find(sorted.begin(), sorted.end());
  if (twice != sorted.end())
  {
    throw InputError(where + "has a boundary that passes twice through point " +
      num(p.points[*twice]) + ": it is not a disk");
  }
  const int64_t np = static_cast<int64_t>(p.points.size());
  const int64_t nt = static_cast<int64_t>(p.triangles.size() / 3);
  const int64_t edges = (3 * nt + half.boundary) / 2;
  const int64_t euler = np - edges + nt;
  if (euler != 1)
  {
    throw InputError(where + "has Euler characteristic " + num(euler) +
      " (a disk has 1): it has handles or holes; check the traced paths");
  }
  checkConnected(p, where);
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
  const double area2 = uvArea2(p, t);
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

/// Weight w of neighbour `col` (a patch point) in the row of unknown `row`.
struct WeightEntry
{
  int32_t row, col;
  double w;
};

/// Floater's mean-value coordinates: every interior point is the weighted mean of its
/// neighbours, w_ij = (tan(a_ij / 2) + tan(b_ij / 2)) / |x_j - x_i| with the angles at x_i, one
/// entry per triangle corner and neighbour. A point whose every angle vanished (all its
/// neighbours on top of it) falls back to uniform (Tutte) weights, still a convex combination.
std::vector<WeightEntry> meanValueWeights(const TriMesh& mesh, const PatchParameterization& p,
  const std::vector<int32_t>& unknown, int32_t nu)
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
  const int64_t nt = static_cast<int64_t>(p.triangles.size() / 3);
  std::vector<WeightEntry> entries;
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
  for (WeightEntry& en : entries)
  {
    if (!(rowSum[en.row] > 0.0))
    {
      en.w = 1.0;
    }
  }
  return entries;
}

/// Solves the convex-combination system of the unknown points for a set of weights; the
/// pattern is the same for every weight set, so it is analysed once.
class ConvexCombinationSolver
{
public:
  ConvexCombinationSolver(const std::vector<int32_t>& unknown, int32_t nu, std::string where)
    : Unknown_(unknown)
    , Nu_(nu)
    , Where_(std::move(where))
  {
  }

  /// Writes the solution into p.uv (the fixed points' uv are the right-hand side).
  /// @throws InputError when the system is singular or its solution not finite
  void solve(const std::vector<WeightEntry>& entries, PatchParameterization& p)
  {
    std::vector<Eigen::Triplet<double>> triplets;
    triplets.reserve(entries.size() + Nu_);
    Eigen::MatrixX2d rhs = Eigen::MatrixX2d::Zero(Nu_, 2);
    for (const WeightEntry& en : entries)
    {
      triplets.emplace_back(en.row, en.row, en.w);
      if (Unknown_[en.col] >= 0)
      {
        triplets.emplace_back(en.row, Unknown_[en.col], -en.w);
      }
      else
      {
        rhs(en.row, 0) += en.w * p.uv[2 * en.col];
        rhs(en.row, 1) += en.w * p.uv[2 * en.col + 1];
      }
    }
    Eigen::SparseMatrix<double> A(Nu_, Nu_);
    A.setFromTriplets(triplets.begin(), triplets.end());
    if (!Analysed_)
    {
      Lu_.analyzePattern(A);
      Analysed_ = true;
    }
    Lu_.factorize(A);
    if (Lu_.info() != Eigen::Success)
    {
      throw InputError(Where_ + "gives a singular mean-value system (" + Lu_.lastErrorMessage() +
        "); check that the patch is a disk of non-degenerate triangles");
    }
    const Eigen::MatrixX2d uv = Lu_.solve(rhs);
    if (Lu_.info() != Eigen::Success || !uv.allFinite())
    {
      throw InputError(Where_ + "gives a mean-value system that could not be solved; check " +
        "that the patch is a disk of non-degenerate triangles");
    }
    const int32_t np = static_cast<int32_t>(p.points.size());
    for (int32_t v = 0; v < np; ++v)
    {
      if (Unknown_[v] >= 0)
      {
        p.uv[2 * v] = uv(Unknown_[v], 0);
        p.uv[2 * v + 1] = uv(Unknown_[v], 1);
      }
    }
  }

private:
  const std::vector<int32_t>& Unknown_;
  const int32_t Nu_;
  const std::string Where_;
  Eigen::SparseLU<Eigen::SparseMatrix<double>, Eigen::COLAMDOrdering<int>> Lu_;
  bool Analysed_ = false;
};

/// Stretch reduction (Yoshizawa, Belyaev and Seidel 2004): divide each weight w_ij by the L2
/// stretch sigma of neighbour j and solve again while the patch's stretch falls, keeping the
/// best map. The weights stay positive, so every map is still a convex combination with a convex
/// border (Tutte and Floater: no flip); samples move from squeezed regions (a protrusion that the
/// mean-value map shrinks to a speck) to where the surface is.
void reduceStretch(const TriMesh& mesh, int32_t iterations, std::vector<WeightEntry>& entries,
  std::vector<double>& sigma, ConvexCombinationSolver& solver, PatchParameterization& p)
{
  std::vector<double> best = p.uv;
  for (int32_t it = 0; it < iterations; ++it)
  {
    for (WeightEntry& en : entries)
    {
      en.w /= sigma[en.col];
    }
    solver.solve(entries, p);
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

/// The uv of the points not on the boundary: the mean-value map, then the stretch passes.
void solveInterior(const TriMesh& mesh, const std::vector<uint8_t>& fixed,
  int32_t stretchIterations, PatchParameterization& p, const std::string& where)
{
  const int32_t np = static_cast<int32_t>(p.points.size());
  std::vector<int32_t> unknown(np, -1);
  int32_t nu = 0;
  for (int32_t v = 0; v < np; ++v)
  {
    unknown[v] = fixed[v] ? -1 : nu++;
  }
  if (nu == 0)
  {
    return;
  }
  std::vector<WeightEntry> entries = meanValueWeights(mesh, p, unknown, nu);
  ConvexCombinationSolver solver(unknown, nu, where);
  solver.solve(entries, p);
  std::vector<double> sigma;
  p.meanValueStretch = p.stretch = patchStretch(mesh, p, stretchIterations > 0 ? &sigma : nullptr);
  if (stretchIterations > 0)
  {
    reduceStretch(mesh, stretchIterations, entries, sigma, solver, p);
  }
}

/// PatchParameterization::degenerateTriangles and flippedTriangles of the map.
void countFlips(PatchParameterization& p)
{
  const int64_t nt = static_cast<int64_t>(p.triangles.size() / 3);
  for (int64_t t = 0; t < nt; ++t)
  {
    const double* a = &p.uv[2 * p.triangles[3 * t]];
    const double* b = &p.uv[2 * p.triangles[3 * t + 1]];
    const double* q = &p.uv[2 * p.triangles[3 * t + 2]];
    const double area2 = uvArea2(p, t);
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
}
} // namespace

PatchParameterization parameterize(const PatchMesh& pm, const BaseComplexResult& base,
  const Layout& L, int32_t c, int32_t stretchIterations)
{
  const std::string where = kWhere + "patch " + num(c) + " ";
  PatchParameterization p = collectPatch(pm.mesh, L, c);
  const OrientedSides half = orientedSides(p, where);
  std::vector<uint8_t> fixed;
  const std::vector<int32_t> loop = fixBoundary(pm, base, c, half, p, fixed, where);
  checkDisk(p, half, loop, where);
  p.boundaryPoints = static_cast<int64_t>(loop.size());
  solveInterior(pm.mesh, fixed, stretchIterations, p, where);
  countFlips(p);
  return p;
}

double curvatureWeightedArea(const TriMesh& mesh, const Layout& L, int32_t c,
  const std::vector<double>& meanCurvature, double curvatureWeight, double diagonal)
{
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
    sum += area * (1.0 + curvatureWeight * h * diagonal);
  }
  return sum;
}
} // namespace tc::detail::geometry_images

namespace tc
{
PatchParameterization parameterizePatch(const PatchMesh& patches, const BaseComplexResult& base,
  int32_t patch, const GeometryImageOptions& options)
{
  using namespace detail::geometry_images;
  checkOptions(options);
  const Layout L = checkInput(patches, base);
  if (patch < 0 || patch >= L.numCharts)
  {
    throw InputError(
      kWhere + "patch " + num(patch) + " does not exist (0 .. " + num(L.numCharts - 1) + ")");
  }
  return parameterize(patches, base, L, patch, options.stretchIterations);
}
} // namespace tc
