// SPDX-License-Identifier: BSD-3-Clause
#include "tc/metrics/surface_distance.h"

#include "tc/prep/mesh_preparation.h"
#include "tc/io/off_io.h"

#include "analytic_meshes.h"
#include "test_data.h"
#include "test_progress.h"

#include <tbb/global_control.h>

#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <limits>
#include <string>
#include <vector>

namespace
{
tc::TriMesh loadBunny()
{
  return tc::prepareMesh(tc::readOFF(tctest::testingData("meshes/bunny_npm.off"))).mesh;
}

void printFigures(const char* what, const tc::SurfaceDistanceResult& r)
{
  std::printf("[ figures  ] %s: hausdorff %.9g mean %.9g rms %.9g; forward max %.9g mean %.9g "
              "rms %.9g; backward max %.9g mean %.9g rms %.9g; %lld samples\n",
    what, r.hausdorff, r.meanDistance, r.rmsDistance, r.forwardMax, r.forwardMean, r.forwardRms,
    r.backwardMax, r.backwardMean, r.backwardRms, static_cast<long long>(r.samples));
}

/// Every scalar of the result, in declaration order.
std::vector<double> scalars(const tc::SurfaceDistanceResult& r)
{
  return { r.hausdorff, r.meanDistance, r.rmsDistance, r.forwardMax, r.forwardMean, r.forwardRms,
    r.backwardMax, r.backwardMean, r.backwardRms };
}

/// Cross product of the edges of triangle t: twice its area times its unit normal.
std::array<double, 3> areaNormal(const tc::TriMesh& mesh, int64_t t)
{
  const auto a = mesh.point(mesh.triangles[3 * t]);
  const auto b = mesh.point(mesh.triangles[3 * t + 1]);
  const auto c = mesh.point(mesh.triangles[3 * t + 2]);
  const double u[3] = { b[0] - a[0], b[1] - a[1], b[2] - a[2] };
  const double v[3] = { c[0] - a[0], c[1] - a[1], c[2] - a[2] };
  return { u[1] * v[2] - u[2] * v[1], u[2] * v[0] - u[0] * v[2], u[0] * v[1] - u[1] * v[0] };
}

/// #V x 3 area-weighted unit vertex normals.
std::vector<double> vertexNormals(const tc::TriMesh& mesh)
{
  std::vector<double> normal(mesh.points.size(), 0.0);
  for (int64_t t = 0; t < mesh.numTriangles(); ++t)
  {
    const std::array<double, 3> n = areaNormal(mesh, t);
    for (int k = 0; k < 3; ++k)
    {
      for (int c = 0; c < 3; ++c)
      {
        normal[3 * mesh.triangles[3 * t + k] + c] += n[c];
      }
    }
  }
  for (int64_t v = 0; v < mesh.numPoints(); ++v)
  {
    double* n = &normal[3 * v];
    const double len = std::hypot(n[0], n[1], n[2]);
    for (int c = 0; c < 3; ++c)
    {
      n[c] /= len;
    }
  }
  return normal;
}

/// A copy of `mesh` with every point moved by `offset` along its unit vertex normal.
tc::TriMesh offsetAlongNormals(const tc::TriMesh& mesh, double offset)
{
  const std::vector<double> normal = vertexNormals(mesh);
  tc::TriMesh out = mesh;
  for (size_t i = 0; i < out.points.size(); ++i)
  {
    out.points[i] += offset * normal[i];
  }
  return out;
}

/// The message of the tc::InputError that `f` throws ("" if it throws none).
template <typename F>
std::string inputErrorOf(const F& f)
{
  try
  {
    f();
  }
  catch (const tc::InputError& e)
  {
    return e.what();
  }
  return "";
}
} // namespace

TEST(SurfaceDistance, IdenticalMeshesAreExactlyZeroApart)
{
  const tc::TriMesh bunny = loadBunny();
  const tc::SurfaceDistanceResult r = tc::surfaceDistance(bunny, bunny);
  for (const double x : scalars(r))
  {
    EXPECT_EQ(x, 0.0);
  }
  ASSERT_EQ(r.pointDistance.size(), static_cast<size_t>(bunny.numPoints()));
  EXPECT_EQ(*std::max_element(r.pointDistance.begin(), r.pointDistance.end()), 0.0);
  // Default sampling on 3674 triangles: 100000 area samples per mesh (k^2 rounding moves the
  // count a little) plus every vertex, in both directions.
  EXPECT_GT(r.samples, 2 * (90000 + bunny.numPoints()));
  EXPECT_LT(r.samples, 2 * (110000 + bunny.numPoints()));

  double lo[3], hi[3];
  for (int c = 0; c < 3; ++c)
  {
    lo[c] = hi[c] = bunny.points[c];
  }
  for (int64_t v = 0; v < bunny.numPoints(); ++v)
  {
    for (int c = 0; c < 3; ++c)
    {
      lo[c] = std::min(lo[c], bunny.points[3 * v + c]);
      hi[c] = std::max(hi[c], bunny.points[3 * v + c]);
    }
  }
  EXPECT_NEAR(r.diagonal, std::hypot(hi[0] - lo[0], hi[1] - lo[1], hi[2] - lo[2]), 1e-12);
}

// Icosphere S of radius R against 1.1 S. Both are convex and inscribed in their spheres; let
// h be the smallest distance of a face plane of S from the centre (the tessellation error is
// R - h). Forward, a point p on S lies inside 1.1 S; its distance to the boundary of the convex
// 1.1 S is min over faces g of (1.1 h_g - n_g . p), and n_g . p <= h_g with equality on p's
// own face, so it lies in [0.1 h, 0.1 R]. Backward, a point q on face f of 1.1 S is at least
// 1.1 h_f - h_f >= 0.1 h from the plane of f, which bounds S, and at most |q - q / 1.1| <= 0.1 R
// from q / 1.1 on S; a vertex of 1.1 S is exactly 0.1 R from the vertex of S below it (the
// radial direction lies in the normal cone of an inscribed vertex). So every distance, mean
// and RMS lies in [0.1 h, 0.1 R] and the backward maximum is 0.1 R.
TEST(SurfaceDistance, ScaledSphereStaysWithinTheTessellationBound)
{
  const double R = 2.0;
  const tc::TriMesh sphere = tctest::icosphere(R, 3).mesh;
  double h = R;
  for (int64_t t = 0; t < sphere.numTriangles(); ++t)
  {
    const auto a = sphere.point(sphere.triangles[3 * t]);
    const auto b = sphere.point(sphere.triangles[3 * t + 1]);
    const auto c = sphere.point(sphere.triangles[3 * t + 2]);
    const double u[3] = { b[0] - a[0], b[1] - a[1], b[2] - a[2] };
    const double v[3] = { c[0] - a[0], c[1] - a[1], c[2] - a[2] };
    const double n[3] = { u[1] * v[2] - u[2] * v[1], u[2] * v[0] - u[0] * v[2],
      u[0] * v[1] - u[1] * v[0] };
    h =
      std::min(h, std::abs(n[0] * a[0] + n[1] * a[1] + n[2] * a[2]) / std::hypot(n[0], n[1], n[2]));
  }
  const double lower = 0.1 * h * (1 - 1e-12), upper = 0.1 * R * (1 + 1e-12);
  std::printf("[ figures  ] icosphere R = %g, 1280 faces: distances must lie in [%.9g, %.9g]\n", R,
    lower, upper);

  const tc::SurfaceDistanceResult r =
    tc::surfaceDistance(sphere, tctest::scaled(sphere, 1.1), { 0, 7, true });
  printFigures("sphere vs 1.1 sphere", r);
  for (const double x : scalars(r))
  {
    EXPECT_GE(x, lower);
    EXPECT_LE(x, upper);
  }
  EXPECT_NEAR(r.backwardMax, 0.1 * R, 1e-12);
  EXPECT_EQ(r.hausdorff, r.backwardMax);
  ASSERT_EQ(r.pointDistance.size(), static_cast<size_t>(sphere.numPoints()));
  for (const double d : r.pointDistance)
  {
    EXPECT_GE(d, lower);
    EXPECT_LE(d, upper);
  }
}

// Two parallel planes at distance `gap`, in a tilted frame: every point of each lies exactly
// `gap` above or below a point of the other, so every distance is `gap`.
TEST(SurfaceDistance, ParallelPlanesAreTheirGapApart)
{
  const double gap = 0.0137;
  // Rotation by 0.7 rad about the unit axis (1, 2, 2) / 3 (Rodrigues' formula).
  const double k[3] = { 1.0 / 3, 2.0 / 3, 2.0 / 3 };
  const double cs = std::cos(0.7), sn = std::sin(0.7);
  double rot[3][3];
  for (int i = 0; i < 3; ++i)
  {
    for (int j = 0; j < 3; ++j)
    {
      rot[i][j] = (i == j ? cs : 0.0) + (1 - cs) * k[i] * k[j];
    }
  }
  rot[0][1] -= sn * k[2];
  rot[0][2] += sn * k[1];
  rot[1][0] += sn * k[2];
  rot[1][2] -= sn * k[0];
  rot[2][0] -= sn * k[1];
  rot[2][1] += sn * k[0];

  const tc::TriMesh flat = tctest::plane(2.0, 15).mesh;
  tc::TriMesh lower = flat, upper = flat;
  for (int64_t v = 0; v < flat.numPoints(); ++v)
  {
    const double p[3] = { flat.points[3 * v], flat.points[3 * v + 1], flat.points[3 * v + 2] };
    for (int i = 0; i < 3; ++i)
    {
      lower.points[3 * v + i] = rot[i][0] * p[0] + rot[i][1] * p[1] + rot[i][2] * p[2];
      // Translated by gap along the rotated normal rot * (0, 0, 1).
      upper.points[3 * v + i] = lower.points[3 * v + i] + gap * rot[i][2];
    }
  }
  const tc::SurfaceDistanceResult r = tc::surfaceDistance(lower, upper);
  printFigures("parallel planes, gap 0.0137", r);
  for (const double x : scalars(r))
  {
    EXPECT_NEAR(x, gap, 1e-14);
  }
  ASSERT_EQ(r.pointDistance.size(), static_cast<size_t>(lower.numPoints()));
  for (const double d : r.pointDistance)
  {
    EXPECT_NEAR(d, gap, 1e-14);
  }
}

// A flat grid of spacing s against the same grid with its centre vertex lifted by H (a spike
// over its 8 triangles). Backward, the apex is H above the flat grid: backwardMax = H, and the
// distance of a spike point to the plane is its height, linear on each spike triangle, so the
// backward mean is (sum of spike areas * H / 3) / area, which the antithetic stratified
// sampling integrates exactly. Forward, the flat point below the apex
// is the farthest from the spike: its closest points are on the 4 spike triangles over the
// axis-aligned sides of the square ring, at s H / sqrt(s^2 + H^2), which is less than H.
TEST(SurfaceDistance, BumpMakesTheTwoDirectionsDiffer)
{
  const int n = 21;
  const double size = 2.0, s = size / (n - 1), H = 0.2;
  const tc::TriMesh flat = tctest::plane(size, n).mesh;
  tc::TriMesh bumped = flat;
  const int64_t centre = (n / 2) * n + n / 2;
  ASSERT_EQ(flat.point(centre)[0], 0.0);
  ASSERT_EQ(flat.point(centre)[1], 0.0);
  bumped.points[3 * centre + 2] = H;

  double spikeArea = 0.0;
  int spikeTriangles = 0;
  for (int64_t t = 0; t < bumped.numTriangles(); ++t)
  {
    const int32_t* f = &bumped.triangles[3 * t];
    if (f[0] != centre && f[1] != centre && f[2] != centre)
    {
      continue;
    }
    const auto a = bumped.point(f[0]), b = bumped.point(f[1]), c = bumped.point(f[2]);
    const double u[3] = { b[0] - a[0], b[1] - a[1], b[2] - a[2] };
    const double v[3] = { c[0] - a[0], c[1] - a[1], c[2] - a[2] };
    spikeArea += 0.5 *
      std::hypot(u[1] * v[2] - u[2] * v[1], u[2] * v[0] - u[0] * v[2], u[0] * v[1] - u[1] * v[0]);
    ++spikeTriangles;
  }
  ASSERT_EQ(spikeTriangles, 8);
  const double bumpedArea = size * size - 4 * s * s + spikeArea;
  const double expectedForwardMax = s * H / std::hypot(s, H);
  const double expectedBackwardMean = spikeArea * H / 3 / bumpedArea;

  const tc::SurfaceDistanceResult r = tc::surfaceDistance(flat, bumped);
  printFigures("flat vs spike of height 0.2", r);
  std::printf("[ figures  ] expected forward max %.9g, backward max %.9g, backward mean %.9g\n",
    expectedForwardMax, H, expectedBackwardMean);
  EXPECT_NEAR(r.forwardMax, expectedForwardMax, 1e-12);
  EXPECT_NEAR(r.backwardMax, H, 1e-12);
  EXPECT_EQ(r.hausdorff, r.backwardMax);
  EXPECT_LT(r.forwardMax, 0.5 * r.backwardMax);
  EXPECT_NEAR(r.backwardMean, expectedBackwardMean, 1e-12 * expectedBackwardMean);
  // The forward distance is positive only on the 4 flat triangles below the spike, and there
  // at most the forward maximum.
  EXPECT_GT(r.forwardMean, 0.0);
  EXPECT_LT(r.forwardMean, expectedForwardMax * 4 * s * s / (size * size));

  // Every flat point but the centre is also a point of the bumped grid.
  ASSERT_EQ(r.pointDistance.size(), static_cast<size_t>(flat.numPoints()));
  for (int64_t v = 0; v < flat.numPoints(); ++v)
  {
    EXPECT_EQ(r.pointDistance[v], v == centre ? r.forwardMax : 0.0) << "point " << v;
  }

  // Swapping the meshes swaps the directions.
  const tc::SurfaceDistanceResult swapped = tc::surfaceDistance(bumped, flat);
  EXPECT_NEAR(swapped.forwardMax, H, 1e-12);
  EXPECT_NEAR(swapped.backwardMax, expectedForwardMax, 1e-12);
  EXPECT_NEAR(swapped.pointDistance[centre], H, 1e-12);
}

// Each point moved by `offset` along a unit vector stays within `offset` of its old position,
// and so does every convex combination of moved points: no distance exceeds the offset, in
// either direction. The mean is less: the point at barycentric coordinates l of a moved
// triangle f is offset * (sum of l_i n_i) away from the old one, and its distance to the plane
// of f is offset * (sum of l_i n_i) . n_f, linear in l, whose mean over f is offset * (mean of
// the 3 vertex normals) . n_f. For a small offset the foot of almost every sample lies in its own
// old triangle, so the area-weighted mean of that over the faces predicts the mean distance.
TEST(SurfaceDistance, BunnyOffsetAlongNormalsIsTheOffsetApart)
{
  const tc::TriMesh bunny = loadBunny();
  const double diagonal = tc::surfaceDistance(bunny, bunny, { 1000, 1, false }).diagonal;
  const double offset = 1e-4 * diagonal;
  const tc::TriMesh moved = offsetAlongNormals(bunny, offset);

  const std::vector<double> normal = vertexNormals(bunny);
  double area = 0.0, weighted = 0.0;
  for (int64_t t = 0; t < bunny.numTriangles(); ++t)
  {
    const std::array<double, 3> n = areaNormal(bunny, t);
    double cosine = 0.0;
    for (int k = 0; k < 3; ++k)
    {
      const double* nv = &normal[3 * bunny.triangles[3 * t + k]];
      cosine += (nv[0] * n[0] + nv[1] * n[1] + nv[2] * n[2]) / 3;
    }
    // |n| is twice the area; cosine is scaled by |n|.
    area += std::hypot(n[0], n[1], n[2]);
    weighted += cosine;
  }
  const double predictedMean = offset * weighted / area;

  const tc::SurfaceDistanceResult r = tc::surfaceDistance(moved, bunny);
  printFigures("bunny_npm offset by 1e-4 diagonal along its normals", r);
  std::printf("[ figures  ] offset %.9g, predicted mean %.9g: mean / offset %.6f, mean / "
              "predicted %.6f, hausdorff / offset %.9f\n",
    offset, predictedMean, r.meanDistance / offset, r.meanDistance / predictedMean,
    r.hausdorff / offset);
  EXPECT_LE(r.hausdorff, offset * (1 + 1e-9));
  EXPECT_GE(r.hausdorff, offset * (1 - 1e-9));
  EXPECT_GT(r.meanDistance, 0.95 * offset);
  EXPECT_NEAR(r.meanDistance, predictedMean, 5e-4 * predictedMean);
  EXPECT_NEAR(r.forwardMean, predictedMean, 5e-4 * predictedMean);
  EXPECT_NEAR(r.backwardMean, predictedMean, 5e-4 * predictedMean);
  EXPECT_LE(r.meanDistance, r.rmsDistance);
  EXPECT_LE(r.rmsDistance, r.hausdorff);
  for (const double d : r.pointDistance)
  {
    EXPECT_LE(d, offset * (1 + 1e-9));
  }
}

TEST(SurfaceDistance, SameSeedGivesBitwiseTheSameResultOnAnyThreadCount)
{
  const tc::TriMesh bunny = loadBunny();
  const tc::TriMesh moved = offsetAlongNormals(bunny, 0.01);
  const tc::SurfaceDistanceOptions options{ 50000, 42, true };
  const tc::SurfaceDistanceResult a = tc::surfaceDistance(moved, bunny, options);
  tc::SurfaceDistanceResult b;
  {
    tbb::global_control serial(tbb::global_control::max_allowed_parallelism, 1);
    b = tc::surfaceDistance(moved, bunny, options);
  }
  const std::vector<double> sa = scalars(a), sb = scalars(b);
  EXPECT_EQ(std::memcmp(sa.data(), sb.data(), sa.size() * sizeof(double)), 0);
  EXPECT_EQ(a.samples, b.samples);
  ASSERT_EQ(a.pointDistance.size(), b.pointDistance.size());
  EXPECT_EQ(std::memcmp(a.pointDistance.data(), b.pointDistance.data(),
              a.pointDistance.size() * sizeof(double)),
    0);

  // Another seed moves the area samples: a different estimate of the same mean.
  const tc::SurfaceDistanceResult c = tc::surfaceDistance(moved, bunny, { 50000, 43, true });
  EXPECT_NE(c.meanDistance, a.meanDistance);
  EXPECT_NEAR(c.meanDistance, a.meanDistance, 0.005 * a.meanDistance);
  EXPECT_EQ(c.pointDistance, a.pointDistance);
}

TEST(SurfaceDistance, SampleCountFollowsTheOptions)
{
  const tc::TriMesh sphere = tctest::icosphere(1.0, 2).mesh;
  const tc::TriMesh bunny = loadBunny();
  // One sample per triangle at least, plus every vertex.
  const tc::SurfaceDistanceResult one = tc::surfaceDistance(sphere, bunny, { 1, 1, false });
  EXPECT_EQ(one.samples,
    sphere.numTriangles() + sphere.numPoints() + bunny.numTriangles() + bunny.numPoints());
  EXPECT_TRUE(one.pointDistance.empty());
  // A grid of 200 equal triangles: k = round(sqrt(9800 / 200)) = 7 for each.
  const tc::TriMesh grid = tctest::plane(2.0, 11).mesh;
  const tc::SurfaceDistanceResult many = tc::surfaceDistance(grid, grid, { 9800, 1, true });
  EXPECT_EQ(many.samples, 2 * (grid.numTriangles() * 49 + grid.numPoints()));
}

TEST(SurfaceDistance, UnusedPointsGetADistanceButStayOutOfTheMaximum)
{
  const tc::TriMesh sphere = tctest::icosphere(1.0, 2).mesh;
  tc::TriMesh withStray = sphere;
  withStray.points.insert(withStray.points.end(), { 10.0, 0.0, 0.0 });
  const tc::SurfaceDistanceResult r = tc::surfaceDistance(withStray, sphere);
  EXPECT_EQ(r.hausdorff, 0.0);
  ASSERT_EQ(r.pointDistance.size(), static_cast<size_t>(withStray.numPoints()));
  EXPECT_NEAR(r.pointDistance.back(), 9.0, 1e-12);
}

TEST(SurfaceDistance, RejectsBadInputWithAMessageThatSaysWhatToFix)
{
  const tc::TriMesh good = tctest::icosphere(1.0, 1).mesh;
  auto expectError = [&good](const tc::TriMesh& mesh, bool asReference, const char* part)
  {
    const std::string what = inputErrorOf(
      [&] { asReference ? tc::surfaceDistance(good, mesh) : tc::surfaceDistance(mesh, good); });
    EXPECT_NE(what.find(part), std::string::npos) << "got: \"" << what << "\"";
    EXPECT_NE(what.find(asReference ? "reference" : "mesh"), std::string::npos) << what;
  };

  expectError(tc::TriMesh{}, false, "empty");
  tc::TriMesh noTriangles = good;
  noTriangles.triangles.clear();
  expectError(noTriangles, true, "empty");
  tc::TriMesh ragged = good;
  ragged.points.pop_back();
  expectError(ragged, false, "multiple of 3");
  tc::TriMesh raggedTriangles = good;
  raggedTriangles.triangles.pop_back();
  expectError(raggedTriangles, true, "multiple of 3");
  tc::TriMesh nan = good;
  nan.points[3 * 5 + 1] = std::numeric_limits<double>::quiet_NaN();
  expectError(nan, false, "point 5");
  tc::TriMesh inf = good;
  inf.points[3 * 7] = -std::numeric_limits<double>::infinity();
  expectError(inf, true, "infinite");
  tc::TriMesh outOfRange = good;
  outOfRange.triangles[3 * 4 + 2] = static_cast<int32_t>(good.numPoints());
  expectError(outOfRange, true, "triangle 4 refers to point 42");
  tc::TriMesh negative = good;
  negative.triangles[0] = -1;
  expectError(negative, false, "refers to point -1");
  // Every triangle collapsed to a segment: no surface to measure against.
  tc::TriMesh flat = good;
  for (int64_t v = 0; v < flat.numPoints(); ++v)
  {
    flat.points[3 * v + 1] = flat.points[3 * v + 2] = 0.0;
  }
  expectError(flat, true, "zero area");
  expectError(flat, false, "zero area");

  const std::string what = inputErrorOf([&] { tc::surfaceDistance(good, good, { -5, 1, true }); });
  EXPECT_NE(what.find("samplesPerMesh"), std::string::npos) << what;
}

TEST(SurfaceDistance, ReportsProgressAndHonoursAbort)
{
  const tc::TriMesh sphere = tctest::icosphere(1.0, 3).mesh;
  const tc::TriMesh big = tctest::scaled(sphere, 1.05);
  tctest::expectProgressAndAbort(
    [&](const tc::Progress& p) {
      tc::surfaceDistance(sphere, big, { 20000, 1, true }, p);
    },
    100, [](double f) { return f < 0.5; });
}
