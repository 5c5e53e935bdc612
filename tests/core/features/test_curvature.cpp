// SPDX-License-Identifier: BSD-3-Clause
#include "tc/features/curvature.h"

#include "analytic_meshes.h"
#include "test_progress.h"

#include <tbb/global_control.h>

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <functional>
#include <random>
#include <vector>

namespace
{
struct ErrorStats
{
  double mean = 0.0;
  double p95 = 0.0;
  double max = 0.0;
};

ErrorStats statsOf(std::vector<double> errors)
{
  ErrorStats s;
  if (errors.empty())
  {
    return s;
  }
  std::sort(errors.begin(), errors.end());
  for (double e : errors)
  {
    s.mean += e;
  }
  s.mean /= static_cast<double>(errors.size());
  s.p95 = errors[static_cast<size_t>(0.95 * static_cast<double>(errors.size() - 1))];
  s.max = errors.back();
  return s;
}

/// Prints the measured errors, so that the test log carries the figures it checked.
void printErrors(const char* surface, int64_t vertices, const ErrorStats& e1, const ErrorStats& e2)
{
  std::printf("[ figures  ] %s, %lld vertices: k1 error mean %.3f%% p95 %.3f%% max %.3f%%; "
              "k2 error mean %.3f%% p95 %.3f%% max %.3f%%\n",
    surface, static_cast<long long>(vertices), 100 * e1.mean, 100 * e1.p95, 100 * e1.max,
    100 * e2.mean, 100 * e2.p95, 100 * e2.max);
}

/// Relative errors of |k1| and |k2| against the exact values, over the vertices `keep` accepts.
/// `scale(v)` is the denominator of the relative error at v.
void relativeErrors(const tctest::AnalyticMesh& m, const tc::CurvatureResult& r,
  const std::function<bool(int64_t)>& keep, const std::function<double(int64_t, int)>& scale,
  ErrorStats& e1, ErrorStats& e2)
{
  std::vector<double> a, b;
  for (int64_t v = 0; v < m.mesh.numPoints(); ++v)
  {
    if (keep(v))
    {
      a.push_back(std::abs(r.k1[v] - m.k1[v]) / scale(v, 1));
      b.push_back(std::abs(r.k2[v] - m.k2[v]) / scale(v, 2));
    }
  }
  e1 = statsOf(a);
  e2 = statsOf(b);
}

bool allVertices(int64_t)
{
  return true;
}

double dot3(const std::vector<double>& a, const std::vector<double>& b, int64_t v)
{
  return a[3 * v] * b[3 * v] + a[3 * v + 1] * b[3 * v + 1] + a[3 * v + 2] * b[3 * v + 2];
}
} // namespace

TEST(CurvatureSphere, RadiusTwoAtTwoDensitiesAndJittered)
{
  // Subdivisions 4 and 5: at subdivision 3 (642 vertices) the 3-ring neighbourhood that the
  // default minNeighbors = 20 needs spans 0.4 rad of the sphere and the cubic fit's bias (the
  // unmodelled quartic term) alone is ~5%.
  const tctest::AnalyticMesh meshes[] = { tctest::icosphere(2.0, 4), tctest::icosphere(2.0, 5),
    tctest::jitteredSphere(2.0, 4, 0.3) };
  const char* names[] = { "sphere r=2", "sphere r=2", "sphere r=2 (jittered)" };
  for (int i = 0; i < 3; ++i)
  {
    const tctest::AnalyticMesh& m = meshes[i];
    SCOPED_TRACE(names[i]);
    const tc::CurvatureResult r = tc::computeCurvature(m.mesh);
    ErrorStats e1, e2;
    relativeErrors(
      m, r, allVertices, [](int64_t, int) { return 0.5; }, e1, e2);
    printErrors(names[i], m.mesh.numPoints(), e1, e2);
    EXPECT_LE(e1.mean, 0.02);
    EXPECT_LE(e1.p95, 0.05);
    EXPECT_LE(e2.mean, 0.02);
    EXPECT_LE(e2.p95, 0.05);
  }
}

TEST(CurvatureCylinder, RadiusOneAwayFromTheOpenEnds)
{
  for (const auto& [around, rows] : { std::pair{ 64, 48 }, std::pair{ 128, 96 } })
  {
    SCOPED_TRACE(around);
    const tctest::AnalyticMesh m = tctest::cylinder(1.0, 4.0, around, rows);
    const tc::CurvatureResult r = tc::computeCurvature(m.mesh);
    // At least 20% of the height (many more than 3 rings) away from either open end.
    const auto inside = [&m](int64_t v) { return std::abs(m.mesh.points[3 * v + 2]) <= 1.2; };
    ErrorStats e1, e2;
    relativeErrors(
      m, r, inside, [](int64_t, int) { return 1.0; }, e1, e2);
    printErrors(
      "cylinder r=1 (errors relative to 1/r = 1, so absolute)", m.mesh.numPoints(), e1, e2);
    EXPECT_LE(e1.mean, 0.02);
    EXPECT_LE(e1.p95, 0.05);
    EXPECT_LE(e2.max, 0.02); // k2 = 0: the error is absolute, per vertex
    double alignment = 0.0;
    int count = 0;
    for (int64_t v = 0; v < m.mesh.numPoints(); ++v)
    {
      if (inside(v))
      {
        alignment += std::abs(dot3(r.d1, m.d1, v));
        ++count;
      }
    }
    ASSERT_GT(count, 0);
    EXPECT_GE(alignment / count, 0.95);
  }
}

TEST(CurvatureTorus, ExactPrincipalCurvaturesAtTwoDensities)
{
  for (const auto& [around, tube] : { std::pair{ 180, 60 }, std::pair{ 240, 80 } })
  {
    SCOPED_TRACE(tube);
    const tctest::AnalyticMesh m = tctest::torus(3.0, 1.0, around, tube);
    ASSERT_GT(tctest::signedVolume6(m.mesh), 0.0);
    const tc::CurvatureResult r = tc::computeCurvature(m.mesh);
    // k2 changes sign on the torus (saddles inside, convex outside), so a plain ratio is
    // undefined where it vanishes: the error of either curvature is relative to the largest
    // exact curvature magnitude at that vertex, max(|k1|, |k2|).
    const auto scale = [&m](int64_t v, int)
    { return std::max(std::abs(m.k1[v]), std::abs(m.k2[v])); };
    ErrorStats e1, e2;
    relativeErrors(m, r, allVertices, scale, e1, e2);
    printErrors("torus R=3 r=1 (relative to max |k|)", m.mesh.numPoints(), e1, e2);
    EXPECT_LE(e1.mean, 0.03);
    EXPECT_LE(e2.mean, 0.03);
  }
}

TEST(CurvatureScale, ScaledCopiesGiveInverselyScaledCurvature)
{
  const tctest::AnalyticMesh m = tctest::torus(3.0, 1.0, 60, 20);
  const tc::CurvatureResult ref = tc::computeCurvature(m.mesh);
  for (double s : { 1000.0, 0.001 })
  {
    SCOPED_TRACE(s);
    const tc::CurvatureResult r = tc::computeCurvature(tctest::scaled(m.mesh, s));
    for (int64_t v = 0; v < m.mesh.numPoints(); ++v)
    {
      const double tol = 1e-6 * std::max(std::abs(ref.k1[v]), std::abs(ref.k2[v]));
      ASSERT_NEAR(r.k1[v] * s, ref.k1[v], tol);
      ASSERT_NEAR(r.k2[v] * s, ref.k2[v], tol);
      ASSERT_NEAR(r.mean[v] * s, ref.mean[v], tol);
      ASSERT_NEAR(
        r.gaussian[v] * s * s, ref.gaussian[v], tol * tol + 2 * tol * std::abs(ref.k1[v]));
      // Same directions, sign included (the sign rule is deterministic).
      ASSERT_GT(dot3(r.d1, ref.d1, v), 1.0 - 1e-9);
      ASSERT_GT(dot3(r.d2, ref.d2, v), 1.0 - 1e-9);
      ASSERT_GT(dot3(r.normals, ref.normals, v), 1.0 - 1e-9);
    }
  }
}

TEST(CurvatureSign, ConvexIsPositiveAndReversedOrientationIsNegative)
{
  const tctest::AnalyticMesh m = tctest::icosphere(2.0, 4);
  const tc::CurvatureResult outward = tc::computeCurvature(m.mesh);
  const tc::CurvatureResult inward = tc::computeCurvature(tctest::reversed(m.mesh));
  for (int64_t v = 0; v < m.mesh.numPoints(); ++v)
  {
    // The position of a sphere vertex is its outward normal times the radius.
    ASSERT_GT(dot3(outward.normals, m.mesh.points, v), 0.0);
    ASSERT_LT(dot3(inward.normals, m.mesh.points, v), 0.0);
    ASSERT_NEAR(outward.k2[v], 0.5, 0.05);
    ASSERT_NEAR(inward.k1[v], -0.5, 0.05);
    ASSERT_NEAR(inward.k1[v], -outward.k2[v], 1e-9);
    ASSERT_NEAR(inward.k2[v], -outward.k1[v], 1e-9);
  }
}

TEST(CurvatureArrays, MeanGaussianFaceMeanAndFramesAreConsistent)
{
  const tctest::AnalyticMesh m = tctest::torus(3.0, 1.0, 48, 16);
  const tc::CurvatureResult r = tc::computeCurvature(m.mesh);
  const int64_t nv = m.mesh.numPoints();
  ASSERT_EQ(static_cast<int64_t>(r.k1.size()), nv);
  ASSERT_EQ(static_cast<int64_t>(r.d1.size()), 3 * nv);
  ASSERT_EQ(static_cast<int64_t>(r.faceMean.size()), m.mesh.numTriangles());
  for (int64_t v = 0; v < nv; ++v)
  {
    EXPECT_GE(r.k1[v], r.k2[v]);
    EXPECT_NEAR(r.mean[v], 0.5 * (r.k1[v] + r.k2[v]), 1e-12);
    EXPECT_NEAR(r.gaussian[v], r.k1[v] * r.k2[v], 1e-12);
    EXPECT_NEAR(dot3(r.d1, r.d1, v), 1.0, 1e-12);
    EXPECT_NEAR(dot3(r.d2, r.d2, v), 1.0, 1e-12);
    EXPECT_NEAR(dot3(r.normals, r.normals, v), 1.0, 1e-12);
    EXPECT_NEAR(dot3(r.d1, r.d2, v), 0.0, 1e-12);
    EXPECT_NEAR(dot3(r.d1, r.normals, v), 0.0, 1e-12);
    // Right-handed: d1 x d2 = normal.
    const double* a = &r.d1[3 * v];
    const double* b = &r.d2[3 * v];
    const double z = a[0] * b[1] - a[1] * b[0];
    EXPECT_NEAR(z, r.normals[3 * v + 2], 1e-12);
  }
  for (int64_t f = 0; f < m.mesh.numTriangles(); ++f)
  {
    const int32_t* t = &m.mesh.triangles[3 * f];
    EXPECT_NEAR(r.faceMean[f], (r.mean[t[0]] + r.mean[t[1]] + r.mean[t[2]]) / 3.0, 1e-12);
  }
}

TEST(CurvatureBoundary, OpenCylinderHasFiniteValuesEverywhere)
{
  const tctest::AnalyticMesh m = tctest::cylinder(1.0, 2.0, 24, 6);
  const tc::CurvatureResult r = tc::computeCurvature(m.mesh);
  for (int64_t v = 0; v < m.mesh.numPoints(); ++v)
  {
    ASSERT_TRUE(std::isfinite(r.k1[v]) && std::isfinite(r.k2[v]));
    for (int c = 0; c < 3; ++c)
    {
      ASSERT_TRUE(std::isfinite(r.d1[3 * v + c]) && std::isfinite(r.normals[3 * v + c]));
    }
    // Even on the open rows, the estimate stays a coarse cylinder estimate.
    EXPECT_NEAR(r.k1[v], 1.0, 0.2);
    EXPECT_NEAR(r.k2[v], 0.0, 0.2);
  }
}

TEST(CurvaturePlane, FlatIsZeroWithUpwardNormals)
{
  const tctest::AnalyticMesh m = tctest::plane(2.0, 21);
  const tc::CurvatureResult r = tc::computeCurvature(m.mesh);
  for (int64_t v = 0; v < m.mesh.numPoints(); ++v)
  {
    ASSERT_NEAR(r.k1[v], 0.0, 1e-9);
    ASSERT_NEAR(r.k2[v], 0.0, 1e-9);
    ASSERT_NEAR(r.normals[3 * v + 2], 1.0, 1e-12);
  }
}

TEST(CurvatureFallback, TinyMeshesAndIsolatedVerticesGiveFiniteValues)
{
  tc::TriMesh m;
  // A lone triangle, a tetrahedron and an isolated vertex.
  m.points = { 0, 0, 0, 1, 0, 0, 0, 1, 0, 5, 5, 5, 6, 5, 5, 5, 6, 5, 5, 5, 6, 9, 9, 9 };
  m.triangles = { 0, 1, 2, 3, 5, 4, 3, 4, 6, 4, 5, 6, 3, 6, 5 };
  const tc::CurvatureResult r = tc::computeCurvature(m);
  for (int64_t v = 0; v < m.numPoints(); ++v)
  {
    EXPECT_TRUE(std::isfinite(r.k1[v]) && std::isfinite(r.k2[v]));
    EXPECT_NEAR(dot3(r.normals, r.normals, v), 1.0, 1e-12);
    EXPECT_NEAR(dot3(r.d1, r.d1, v), 1.0, 1e-12);
  }
  EXPECT_EQ(r.k1[7], 0.0);
  EXPECT_NEAR(r.normals[2], 1.0, 1e-12); // the triangle is counter-clockwise seen from +z
}

TEST(CurvatureRobust, OutliersDoNotSpoilTheirNeighbours)
{
  // 2% of the vertices of a sphere pushed out by one edge length: the robust fit ignores them
  // (and repairs their own estimate), the plain least-squares fit does not.
  tctest::AnalyticMesh m = tctest::icosphere(2.0, 5);
  std::mt19937 rng(9);
  const double edge = 2.0 * 1.1 / 32.0;
  for (size_t i = 0; i < m.mesh.points.size(); i += 3)
  {
    if (rng() % 50 == 0)
    {
      for (int c = 0; c < 3; ++c)
      {
        m.mesh.points[i + c] *= (2.0 + edge) / 2.0;
      }
    }
  }
  tc::CurvatureOptions plain;
  plain.robust = false;
  ErrorStats robust1, robust2, plain1, plain2;
  const auto half = [](int64_t, int) { return 0.5; };
  relativeErrors(m, tc::computeCurvature(m.mesh), allVertices, half, robust1, robust2);
  relativeErrors(m, tc::computeCurvature(m.mesh, plain), allVertices, half, plain1, plain2);
  EXPECT_LE(robust1.p95, 0.02);
  EXPECT_LE(robust2.p95, 0.02);
  EXPECT_GT(plain1.p95, 5 * robust1.p95);
}

TEST(CurvatureDeterminism, SameResultWithOneThreadOrMany)
{
  const tctest::AnalyticMesh m = tctest::jitteredSphere(1.0, 4, 0.3);
  const tc::CurvatureResult many = tc::computeCurvature(m.mesh);
  tc::CurvatureResult one;
  {
    tbb::global_control single(tbb::global_control::max_allowed_parallelism, 1);
    one = tc::computeCurvature(m.mesh);
  }
  EXPECT_EQ(many.k1, one.k1);
  EXPECT_EQ(many.k2, one.k2);
  EXPECT_EQ(many.d1, one.d1);
  EXPECT_EQ(many.normals, one.normals);
}

TEST(CurvatureInput, RejectsBadConnectivityAndOptions)
{
  tc::TriMesh m;
  m.points = { 0, 0, 0, 1, 0, 0, 0, 1, 0 };
  m.triangles = { 0, 1, 3 };
  EXPECT_THROW(tc::computeCurvature(m), tc::InputError);
  m.triangles = { 0, 1, 2 };
  tc::CurvatureOptions options;
  options.degree = 4;
  EXPECT_THROW(tc::computeCurvature(m, options), tc::InputError);
}

TEST(CurvatureProgress, ReportsAndHonoursAbort)
{
  const tctest::AnalyticMesh m = tctest::icosphere(1.0, 3);
  tctest::expectProgressAndAbort([&](const tc::Progress& p)
    { tc::computeCurvature(m.mesh, {}, p); },
    1, [](double f) { return f < 0.5; });
}
