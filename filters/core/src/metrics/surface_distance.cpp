// SPDX-License-Identifier: BSD-3-Clause
#include "tc/metrics/surface_distance.h"

#include "tc/common/errors.h"
#include "tc/common/parallel.h"

#include "detail/splitmix.h"

#include <CGAL/AABB_traits.h>
#include <CGAL/AABB_tree.h>
#include <CGAL/AABB_triangle_primitive.h>
#include <CGAL/Simple_cartesian.h>

#include <algorithm>
#include <cmath>
#include <string>

// CGAL::Polygon_mesh_processing::approximate_Hausdorff_distance returns only the maximum; the
// mean and RMS of Metro need the distance of every sample, so the sampling loop is ours and
// only the closest-point queries go to CGAL's AABB tree.

namespace tc
{
namespace
{
// Closest points are constructions, computed in doubles by any inexact kernel; Epick's filtered
// predicates would only slow the tree traversal down.
using Kernel = CGAL::Simple_cartesian<double>;
using Point = Kernel::Point_3;
using Triangle = Kernel::Triangle_3;
using Primitive = CGAL::AABB_triangle_primitive<Kernel, std::vector<Triangle>::const_iterator>;
using Tree = CGAL::AABB_tree<CGAL::AABB_traits<Kernel, Primitive>>;
using Hint = Tree::Point_and_primitive_id;

constexpr int64_t kAutoSamplesPerTriangle = 10;
constexpr int64_t kMinAutoSamples = 100000;
constexpr int64_t kMaxAutoSamples = 4000000;
constexpr int64_t kMaxSamples = 1000000000000;
// The closest point on a triangle is computed through its supporting plane, off by a few ulps
// of the coordinates (more on slivers); distances below this fraction of the largest absolute
// coordinate cannot be told from 0.
constexpr double kNoiseFloor = 1e-12;

void validate(const TriMesh& m, const char* name)
{
  const std::string what = std::string("surfaceDistance: the ") + name;
  if (m.points.size() % 3 != 0)
  {
    throw InputError(what + " has " + std::to_string(m.points.size()) +
      " coordinates, not a multiple of 3: pass x, y, z of every point");
  }
  if (m.triangles.size() % 3 != 0)
  {
    throw InputError(what + " has " + std::to_string(m.triangles.size()) +
      " triangle indices, not a multiple of 3: pass 3 point ids per triangle");
  }
  if (m.numPoints() == 0 || m.numTriangles() == 0)
  {
    throw InputError(what + " is empty (" + std::to_string(m.numPoints()) + " points, " +
      std::to_string(m.numTriangles()) + " triangles): pass a mesh with at least one triangle");
  }
  int64_t nonFinite = 0, firstNonFinite = -1;
  for (int64_t i = 0; i < static_cast<int64_t>(m.points.size()); ++i)
  {
    if (!std::isfinite(m.points[i]))
    {
      if (nonFinite++ == 0)
      {
        firstNonFinite = i / 3;
      }
    }
  }
  if (nonFinite > 0)
  {
    throw InputError(what + " has " + std::to_string(nonFinite) +
      " NaN or infinite coordinates, the first at point " + std::to_string(firstNonFinite) +
      ": fix or remove those points (tc::prepareMesh reports them)");
  }
  const int64_t n = m.numPoints();
  for (int64_t i = 0; i < static_cast<int64_t>(m.triangles.size()); ++i)
  {
    if (m.triangles[i] < 0 || m.triangles[i] >= n)
    {
      throw InputError(what + ": triangle " + std::to_string(i / 3) + " refers to point " +
        std::to_string(m.triangles[i]) + ", but the ids run from 0 to " + std::to_string(n - 1) +
        ": fix the connectivity");
    }
  }
}

/// One mesh as the target of closest-point queries and as a source of samples.
struct Surface
{
  std::vector<Triangle> triangles; ///< #F
  std::vector<double> area;        ///< #F
  double totalArea = 0.0;
  std::vector<uint8_t> used; ///< #V: 1 if a triangle uses the point
  std::vector<int64_t> k;    ///< #F: the triangle is cut into k x k sub-triangles
  int64_t areaSamples = 0;   ///< sum of k^2
  int64_t vertexSamples = 0; ///< used points
  Tree tree;
};

void prepare(Surface& s, const TriMesh& m, const char* name)
{
  const int64_t nf = m.numTriangles();
  s.triangles.resize(nf);
  s.area.resize(nf);
  s.used.assign(m.numPoints(), 0);
  for (int64_t t = 0; t < nf; ++t)
  {
    const int32_t* f = &m.triangles[3 * t];
    const double* a = &m.points[3 * f[0]];
    const double* b = &m.points[3 * f[1]];
    const double* c = &m.points[3 * f[2]];
    s.triangles[t] =
      Triangle(Point(a[0], a[1], a[2]), Point(b[0], b[1], b[2]), Point(c[0], c[1], c[2]));
    const double u[3] = { b[0] - a[0], b[1] - a[1], b[2] - a[2] };
    const double v[3] = { c[0] - a[0], c[1] - a[1], c[2] - a[2] };
    const double n[3] = { u[1] * v[2] - u[2] * v[1], u[2] * v[0] - u[0] * v[2],
      u[0] * v[1] - u[1] * v[0] };
    s.area[t] = 0.5 * std::sqrt(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]);
    s.totalArea += s.area[t];
    s.used[f[0]] = s.used[f[1]] = s.used[f[2]] = 1;
  }
  if (!(s.totalArea > 0.0))
  {
    throw InputError(std::string("surfaceDistance: the ") + name +
      " has zero area (every triangle has repeated or collinear corners): pass a surface");
  }
  s.vertexSamples = std::count(s.used.begin(), s.used.end(), uint8_t(1));
}

/// k per triangle such that k^2 is about target * (triangle area / total area), at least 1.
void allocateSamples(Surface& s, int64_t target)
{
  const int64_t nf = static_cast<int64_t>(s.area.size());
  s.k.resize(nf);
  s.areaSamples = 0;
  for (int64_t t = 0; t < nf; ++t)
  {
    const double share = static_cast<double>(target) * (s.area[t] / s.totalArea);
    s.k[t] = std::max<int64_t>(1, std::llround(std::sqrt(share)));
    s.areaSamples += s.k[t] * s.k[t];
  }
}

/// Uniform in [0, 1) with 53 random bits. SplitMix64 rather than a <random> engine: one stream
/// per triangle, keyed by (seed, triangle), costs two words of state and makes every sample
/// independent of the thread that draws it, so results are bitwise reproducible.
double uniform(uint64_t& state)
{
  return static_cast<double>(detail::splitMix(state) >> 11) * 0x1.0p-53;
}

/// Distance from p to its closest point, 0 below the noise floor.
double distanceTo(const Point& p, const Point& closest, double floor)
{
  const double d = std::sqrt(CGAL::squared_distance(p, closest));
  return d < floor ? 0.0 : d;
}

struct OneSided
{
  double max = 0.0;
  double mean = 0.0;
  double rms = 0.0;
};

/// The distances of the area samples of one triangle to a surface: their sum, sum of squares
/// and maximum.
class TriangleSampler
{
public:
  TriangleSampler(const Triangle& tri, int64_t k, const Tree& to, double floor)
    : A(tri.vertex(0))
    , AB{ tri.vertex(1).x() - A.x(), tri.vertex(1).y() - A.y(), tri.vertex(1).z() - A.z() }
    , AC{ tri.vertex(2).x() - A.x(), tri.vertex(2).y() - A.y(), tri.vertex(2).z() - A.z() }
    , Inv(1.0 / static_cast<double>(k))
    , To(to)
    , Floor(floor)
  {
  }

  /// The sample at lattice coordinates (s, r): a + (s / k)(b - a) + (r / k)(c - a).
  void sample(double s, double r)
  {
    const double bs = s * Inv, br = r * Inv;
    const Point p(A.x() + bs * AB[0] + br * AC[0], A.y() + bs * AB[1] + br * AC[1],
      A.z() + bs * AB[2] + br * AC[2]);
    // Neighbouring samples have nearby closest points: the previous answer is a good start.
    Closest =
      Hinted ? To.closest_point_and_primitive(p, Closest) : To.closest_point_and_primitive(p);
    Hinted = true;
    const double d = distanceTo(p, Closest.first, Floor);
    Sum += d;
    Sum2 += d * d;
    Max = std::max(Max, d);
  }

  double Sum = 0.0, Sum2 = 0.0, Max = 0.0;

private:
  const Point& A;
  const double AB[3];
  const double AC[3];
  const double Inv;
  const Tree& To;
  const double Floor;
  Hint Closest;
  bool Hinted = false;
};

/// Samples the k x k sub-triangles of one triangle (see the comment in measure), drawing from
/// the stream `state`.
void sampleTriangle(TriangleSampler& sampler, int64_t k, uint64_t state)
{
  for (int64_t i = 0; i < k; ++i)
  {
    for (int64_t j = 0; i + j < k; ++j)
    {
      if (i + j + 1 == k)
      {
        sampler.sample(static_cast<double>(i) + 1.0 / 3.0, static_cast<double>(j) + 1.0 / 3.0);
        continue;
      }
      // Uniform in the unit right triangle (fold the other half of the square onto it).
      double u = uniform(state), v = uniform(state);
      if (u + v > 1.0)
      {
        u = 1.0 - u;
        v = 1.0 - v;
      }
      sampler.sample(static_cast<double>(i) + u, static_cast<double>(j) + v);
      sampler.sample(static_cast<double>(i + 1) - u, static_cast<double>(j + 1) - v);
    }
  }
}

/// Distance of every point of `from` to `to` (of the used ones only, unless all are asked for).
std::vector<double> vertexDistances(const TriMesh& from, const Surface& source, const Surface& to,
  double floor, bool all, const Progress& progress)
{
  const int64_t nv = from.numPoints();
  std::vector<double> vertexDistance(nv, 0.0);
  parallel_for(
    nv,
    [&](int64_t v)
    {
      if (source.used[v] || all)
      {
        const Point p(from.points[3 * v], from.points[3 * v + 1], from.points[3 * v + 2]);
        vertexDistance[v] = distanceTo(p, to.tree.closest_point(p), floor);
      }
    },
    progress);
  return vertexDistance;
}

/// Distances of the samples of `from` to `to`.
OneSided measure(const TriMesh& from, const Surface& source, const Surface& to, uint32_t seed,
  double floor, std::vector<double>* pointDistance, const Progress& progress)
{
  const double vertexShare = static_cast<double>(source.vertexSamples) /
    static_cast<double>(source.vertexSamples + source.areaSamples);

  // Every vertex: Metro's vertex sampling; the maxima of the distance often sit there.
  std::vector<double> vertexDistance = vertexDistances(
    from, source, to, floor, pointDistance != nullptr, progress.sub(0.0, vertexShare));

  // Stratified area samples: triangle (a, b, c) is cut into k x k sub-triangles of area A / k^2
  // along the lattice a + (i / k)(b - a) + (j / k)(c - a). Upright cell (i, j), i + j < k,
  // spans lattice points (i, j), (i + 1, j), (i, j + 1); for i + j < k - 1 it and the inverted
  // cell across its long side ((i + 1, j + 1), (i, j + 1), (i + 1, j)) form a rhombus, and
  // point reflection through the rhombus centre (i + 1/2, j + 1/2) maps one onto the other.
  // Each rhombus gets a uniform random sample in its upright half and that sample's mirror
  // image (antithetic pair): the pair's mean of any linear function is its value at the centre,
  // i.e. its exact mean over the rhombus. The k upright cells along side bc have no partner and
  // are sampled at their centroid. So the estimate is exact for a distance that is linear over
  // a triangle (to a plane, say), and its error elsewhere comes from the curvature of the
  // distance only.
  const int64_t nf = from.numTriangles();
  std::vector<double> faceSum(nf), faceSum2(nf), faceMax(nf);
  const uint64_t seedKey = static_cast<uint64_t>(seed) << 32;
  parallel_for(
    nf,
    [&](int64_t t)
    {
      const int64_t k = source.k[t];
      TriangleSampler sampler(source.triangles[t], k, to.tree, floor);
      sampleTriangle(sampler, k, seedKey ^ static_cast<uint64_t>(t));
      const double inv = 1.0 / static_cast<double>(k);
      const double weight = source.area[t] * inv * inv;
      faceSum[t] = weight * sampler.Sum;
      faceSum2[t] = weight * sampler.Sum2;
      faceMax[t] = sampler.Max;
    },
    progress.sub(vertexShare, 1.0));

  // Serial sums in triangle order: the same bits whatever the thread count.
  OneSided r;
  double sum = 0.0, sum2 = 0.0;
  for (int64_t t = 0; t < nf; ++t)
  {
    sum += faceSum[t];
    sum2 += faceSum2[t];
    r.max = std::max(r.max, faceMax[t]);
  }
  for (int64_t v = 0; v < from.numPoints(); ++v)
  {
    if (source.used[v])
    {
      r.max = std::max(r.max, vertexDistance[v]);
    }
  }
  r.mean = sum / source.totalArea;
  r.rms = std::sqrt(sum2 / source.totalArea);
  if (pointDistance)
  {
    pointDistance->swap(vertexDistance);
  }
  return r;
}

/// Distances below this are rounding noise: kNoiseFloor times the largest absolute coordinate
/// of the two meshes.
double noiseFloor(const TriMesh& mesh, const TriMesh& reference)
{
  double largest = 0.0;
  for (const double x : mesh.points)
  {
    largest = std::max(largest, std::abs(x));
  }
  for (const double x : reference.points)
  {
    largest = std::max(largest, std::abs(x));
  }
  return kNoiseFloor * largest;
}

/// Diagonal of the bounding box of the points of `m`.
double boxDiagonal(const TriMesh& m)
{
  double lo[3] = { m.points[0], m.points[1], m.points[2] };
  double hi[3] = { lo[0], lo[1], lo[2] };
  for (int64_t v = 0; v < m.numPoints(); ++v)
  {
    for (int c = 0; c < 3; ++c)
    {
      const double x = m.points[3 * v + c];
      lo[c] = std::min(lo[c], x);
      hi[c] = std::max(hi[c], x);
    }
  }
  return std::sqrt((hi[0] - lo[0]) * (hi[0] - lo[0]) + (hi[1] - lo[1]) * (hi[1] - lo[1]) +
    (hi[2] - lo[2]) * (hi[2] - lo[2]));
}

/// The symmetric figures from the two one-sided ones, weighted by the areas.
void combine(const OneSided& forward, const OneSided& backward, const Surface& m, const Surface& r,
  SurfaceDistanceResult& result)
{
  result.forwardMax = forward.max;
  result.forwardMean = forward.mean;
  result.forwardRms = forward.rms;
  result.backwardMax = backward.max;
  result.backwardMean = backward.mean;
  result.backwardRms = backward.rms;
  result.hausdorff = std::max(forward.max, backward.max);
  const double total = m.totalArea + r.totalArea;
  result.meanDistance = (m.totalArea * forward.mean + r.totalArea * backward.mean) / total;
  result.rmsDistance = std::sqrt(
    (m.totalArea * forward.rms * forward.rms + r.totalArea * backward.rms * backward.rms) / total);
  result.samples = m.vertexSamples + m.areaSamples + r.vertexSamples + r.areaSamples;
}
} // namespace

SurfaceDistanceResult surfaceDistance(const TriMesh& mesh, const TriMesh& reference,
  const SurfaceDistanceOptions& options, const Progress& progress)
{
  // 1. Valid meshes and options.
  validate(mesh, "mesh");
  validate(reference, "reference");
  if (options.samplesPerMesh < 0 || options.samplesPerMesh > kMaxSamples)
  {
    throw InputError("surfaceDistance: samplesPerMesh is " +
      std::to_string(options.samplesPerMesh) +
      ": pass 0 (automatic) or a sample count of at most 10^12");
  }
  progress.report(0.0);

  // 2. Areas, used points and samples per triangle of each mesh.
  Surface m, r;
  prepare(m, mesh, "mesh");
  prepare(r, reference, "reference");
  auto target = [&options](int64_t triangles)
  {
    return options.samplesPerMesh > 0
      ? options.samplesPerMesh
      : std::min(kMaxAutoSamples, std::max(kMinAutoSamples, kAutoSamplesPerTriangle * triangles));
  };
  allocateSamples(m, target(mesh.numTriangles()));
  allocateSamples(r, target(reference.numTriangles()));
  SurfaceDistanceResult result;
  result.diagonal = boxDiagonal(reference);
  const double floor = noiseFloor(mesh, reference);

  // 3. The AABB trees. Building them takes a few percent of the time; it cannot be interrupted.
  const double forwardWork = static_cast<double>(m.vertexSamples + m.areaSamples);
  const double backwardWork = static_cast<double>(r.vertexSamples + r.areaSamples);
  const double built = 0.05;
  const double split = built + (1.0 - built) * forwardWork / (forwardWork + backwardWork);
  for (Surface* s : { &r, &m })
  {
    s->tree.insert(s->triangles.begin(), s->triangles.end());
    s->tree.build();
    s->tree.accelerate_distance_queries();
  }
  progress.report(built);

  // 4. Both directions, then the symmetric figures.
  const OneSided forward = measure(mesh, m, r, options.seed, floor,
    options.perPointDistance ? &result.pointDistance : nullptr, progress.sub(built, split));
  const OneSided backward =
    measure(reference, r, m, options.seed, floor, nullptr, progress.sub(split, 1.0));
  combine(forward, backward, m, r, result);
  return result;
}
} // namespace tc
