// SPDX-License-Identifier: BSD-3-Clause
#include "tc/features/crest_lines.h"

#include "tc/features/curvature.h"
#include "tc/common/mesh_topology.h"

#include "analytic_meshes.h"
#include "test_progress.h"

#include <tbb/global_control.h>

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

namespace
{
tc::CrestLines crestsOf(const tc::TriMesh& mesh, const tc::CrestLineOptions& options = {})
{
  return tc::extractCrestLines(mesh, tc::computeCurvature(mesh), options);
}

double lineLength(const tc::CrestLines& lines, int64_t l)
{
  double length = 0.0;
  for (int64_t i = lines.offsets[l]; i + 1 < lines.offsets[l + 1]; ++i)
  {
    const double* p = &lines.points[3 * lines.connectivity[i]];
    const double* q = &lines.points[3 * lines.connectivity[i + 1]];
    length += std::sqrt((p[0] - q[0]) * (p[0] - q[0]) + (p[1] - q[1]) * (p[1] - q[1]) +
      (p[2] - q[2]) * (p[2] - q[2]));
  }
  return length;
}

double totalLength(const tc::CrestLines& lines, int type)
{
  double length = 0.0;
  for (int64_t l = 0; l < lines.numLines(); ++l)
  {
    length += lines.type[l] == type ? lineLength(lines, l) : 0.0;
  }
  return length;
}

/// Where the exact curvature across z = h exp(-x^2 / (2 w^2)), f'' / (1 + f'^2)^(3/2), is
/// minimal for x > 0 (the exact valley lines of the Gaussian ridge), by dense sampling.
double exactGaussianValley(double h, double w)
{
  double best = 0.0, bestK = 0.0;
  for (double x = 0.0; x < 4.0 * w; x += 1e-5 * w)
  {
    const double g = h * std::exp(-x * x / (2 * w * w));
    const double fx = -x / (w * w) * g, fxx = (x * x / (w * w) - 1) / (w * w) * g;
    const double k = -fxx / std::pow(1 + fx * fx, 1.5);
    if (k < bestK)
    {
      bestK = k;
      best = x;
    }
  }
  return best;
}

/// The faces whose closure holds crest point p: those of its edge, or all faces around a mesh
/// vertex where the crest passes exactly through one.
std::vector<int32_t> facesHolding(const tc::TriMesh& mesh, const tc::EdgeTable& edges,
  const tc::VertexFaces& faces, const tc::CrestLines& lines, int64_t p)
{
  const int32_t e = lines.pointEdge[p];
  std::vector<int32_t> out(edges.edgeFaces.begin() + edges.faceOffsets[e],
    edges.edgeFaces.begin() + edges.faceOffsets[e + 1]);
  for (int k = 0; k < 2; ++k)
  {
    const int32_t v = edges.vertices[2 * e + k];
    if (std::equal(&lines.points[3 * p], &lines.points[3 * p] + 3, &mesh.points[3 * v]))
    {
      out.assign(
        faces.faceIds.begin() + faces.offsets[v], faces.faceIds.begin() + faces.offsets[v + 1]);
    }
  }
  return out;
}

constexpr double kRidgeHeight = 0.5, kRidgeWidth = 0.3, kRidgeSide = 4.0;
constexpr int kRidgeGrid = 80; // even: no vertex exactly on the crest x = 0
} // namespace

TEST(CrestLinesRidge, GaussianRidgeIsTracedOnItsCrestAndValleysBesideIt)
{
  const tctest::AnalyticMesh m =
    tctest::gaussianRidge(kRidgeHeight, kRidgeWidth, kRidgeSide, kRidgeGrid);
  const tc::CrestLines lines = crestsOf(m.mesh);
  const double spacing = kRidgeSide / (kRidgeGrid - 1);
  const double valley = exactGaussianValley(kRidgeHeight, kRidgeWidth);
  ASSERT_GT(lines.numLines(), 0);
  for (int64_t l = 0; l < lines.numLines(); ++l)
  {
    for (int64_t i = lines.offsets[l]; i < lines.offsets[l + 1]; ++i)
    {
      const double x = lines.points[3 * lines.connectivity[i]];
      if (lines.type[l] == 0)
      {
        EXPECT_NEAR(x, 0.0, 0.1 * spacing);
      }
      else
      {
        EXPECT_NEAR(std::abs(x), valley, 0.1 * spacing);
      }
    }
  }
  // The ridge runs across the whole patch; the two valleys too.
  EXPECT_GE(totalLength(lines, 0), 0.95 * kRidgeSide);
  EXPECT_LE(totalLength(lines, 0), 1.05 * kRidgeSide);
  EXPECT_GE(totalLength(lines, 1), 2 * 0.95 * kRidgeSide);
  EXPECT_LE(totalLength(lines, 1), 2 * 1.05 * kRidgeSide);
}

TEST(CrestLinesRidge, InvertedRidgeSwapsRidgesAndValleys)
{
  const tc::CrestLines up =
    crestsOf(tctest::gaussianRidge(kRidgeHeight, kRidgeWidth, kRidgeSide, kRidgeGrid).mesh);
  const tc::CrestLines down =
    crestsOf(tctest::gaussianRidge(-kRidgeHeight, kRidgeWidth, kRidgeSide, kRidgeGrid).mesh);
  ASSERT_EQ(up.numLines(), down.numLines());
  ASSERT_GT(up.numLines(), 0);
  for (int64_t l = 0; l < up.numLines(); ++l)
  {
    EXPECT_EQ(up.type[l], 1 - down.type[l]);
    EXPECT_NEAR(up.strength[l], down.strength[l], 1e-6 * up.strength[l]);
  }
}

TEST(CrestLinesBox, RidgesFollowTheRoundedEdgesOfABox)
{
  const double a = 1.0, rounding = 0.3;
  const tc::CrestLines lines = crestsOf(tctest::roundedBox(a, rounding, 24).mesh);
  ASSERT_GT(lines.numLines(), 0);
  for (int64_t l = 0; l < lines.numLines(); ++l)
  {
    EXPECT_EQ(lines.type[l], 0); // a convex box has no valley
  }
  // Every crest point lies on a rounded edge or corner: at least two coordinates beyond the
  // flat faces' extent.
  for (size_t p = 0; p < lines.points.size(); p += 3)
  {
    int beyond = 0;
    for (int c = 0; c < 3; ++c)
    {
      beyond += std::abs(lines.points[p + c]) > a ? 1 : 0;
    }
    EXPECT_GE(beyond, 2);
  }
  // Together the lines cover the 12 edges (and may continue round the corners).
  EXPECT_GE(totalLength(lines, 0), 0.9 * 12 * 2 * a);
}

TEST(CrestLinesBox, SharpCubeHasOneRidgeOnEachEdge)
{
  const double a = 1.0;
  const tc::CrestLines lines = crestsOf(tctest::roundedBox(a, 0.0, 16).mesh);
  ASSERT_EQ(lines.numLines(), 12);
  for (int64_t l = 0; l < lines.numLines(); ++l)
  {
    EXPECT_EQ(lines.type[l], 0);
    // Along most of the edge (the umbilic corner regions have no direction to follow).
    EXPECT_GE(lineLength(lines, l), 0.8 * 2 * a);
    for (int64_t i = lines.offsets[l]; i < lines.offsets[l + 1]; ++i)
    {
      const double* p = &lines.points[3 * lines.connectivity[i]];
      int onEdge = 0;
      for (int c = 0; c < 3; ++c)
      {
        onEdge += std::abs(std::abs(p[c]) - a) < 1e-9 ? 1 : 0;
      }
      EXPECT_GE(onEdge, 2);
    }
  }
}

TEST(CrestLinesNone, NoCrestOnSurfacesWithoutSalientExtrema)
{
  // Constant curvature (sphere, cylinder), constant k1 and never-dominant k2 (torus), flat.
  const tctest::AnalyticMesh meshes[] = { tctest::icosphere(2.0, 4),
    tctest::jitteredSphere(2.0, 4, 0.3), tctest::cylinder(1.0, 4.0, 64, 48),
    tctest::torus(3.0, 1.0, 120, 40), tctest::plane(2.0, 31) };
  for (const auto& m : meshes)
  {
    SCOPED_TRACE(m.mesh.numPoints());
    EXPECT_EQ(crestsOf(m.mesh).numLines(), 0);
  }
}

TEST(CrestLinesNone, SalienceIsWhatRemovesTheNoiseCrestsOfASphere)
{
  // Without the salience and strength filters the estimation noise of a sphere's (constant)
  // curvature does have extrema: the filters, not luck, make the previous test pass.
  tc::CrestLineOptions unfiltered;
  unfiltered.minRelativeCurvature = 0.0;
  unfiltered.minCurvatureTimesSize = 0.0;
  unfiltered.minStrength = 0.0;
  unfiltered.minSegments = 1;
  EXPECT_GT(crestsOf(tctest::icosphere(2.0, 4).mesh, unfiltered).numLines(), 0);
}

TEST(CrestLinesScale, StrengthIsScaleInvariant)
{
  // Not the rounded box: its umbilic corners (no principal direction) break the lines where
  // rounding noise decides, so the number of pieces is not a property of the shape there.
  const tc::TriMesh meshes[] = {
    tctest::gaussianRidge(kRidgeHeight, kRidgeWidth, kRidgeSide, kRidgeGrid).mesh,
    tctest::roundedBox(1.0, 0.0, 16).mesh
  };
  for (const auto& mesh : meshes)
  {
    const tc::CrestLines ref = crestsOf(mesh);
    ASSERT_GT(ref.numLines(), 0);
    for (double s : { 1000.0, 0.001 })
    {
      SCOPED_TRACE(s);
      const tc::CrestLines lines = crestsOf(tctest::scaled(mesh, s));
      ASSERT_EQ(lines.numLines(), ref.numLines());
      ASSERT_EQ(lines.points.size(), ref.points.size());
      for (int64_t l = 0; l < ref.numLines(); ++l)
      {
        EXPECT_EQ(lines.type[l], ref.type[l]);
        EXPECT_NEAR(lines.strength[l], ref.strength[l], 1e-6 * ref.strength[l]);
      }
      for (size_t i = 0; i < ref.points.size(); ++i)
      {
        EXPECT_NEAR(lines.points[i] / s, ref.points[i], 1e-6);
      }
    }
  }
}

TEST(CrestLinesOptions, RidgesOrValleysAlone)
{
  const tc::TriMesh mesh =
    tctest::gaussianRidge(kRidgeHeight, kRidgeWidth, kRidgeSide, kRidgeGrid).mesh;
  const tc::CurvatureResult curvature = tc::computeCurvature(mesh);
  tc::CrestLineOptions ridgesOnly, valleysOnly;
  ridgesOnly.valleys = false;
  valleysOnly.ridges = false;
  const tc::CrestLines r = tc::extractCrestLines(mesh, curvature, ridgesOnly);
  const tc::CrestLines v = tc::extractCrestLines(mesh, curvature, valleysOnly);
  ASSERT_GT(r.numLines(), 0);
  ASSERT_GT(v.numLines(), 0);
  EXPECT_TRUE(std::all_of(r.type.begin(), r.type.end(), [](int8_t t) { return t == 0; }));
  EXPECT_TRUE(std::all_of(v.type.begin(), v.type.end(), [](int8_t t) { return t == 1; }));
  EXPECT_EQ(r.numLines() + v.numLines(), tc::extractCrestLines(mesh, curvature).numLines());
}

TEST(CrestLinesOptions, MinStrengthDropsWeakerLines)
{
  const tc::TriMesh mesh =
    tctest::gaussianRidge(kRidgeHeight, kRidgeWidth, kRidgeSide, kRidgeGrid).mesh;
  const tc::CurvatureResult curvature = tc::computeCurvature(mesh);
  const tc::CrestLines all = tc::extractCrestLines(mesh, curvature);
  ASSERT_GE(all.numLines(), 2);
  const double weakest = *std::min_element(all.strength.begin(), all.strength.end());
  const double strongest = *std::max_element(all.strength.begin(), all.strength.end());
  ASSERT_LT(weakest, strongest);
  tc::CrestLineOptions options;
  options.minStrength = 0.5 * (weakest + strongest);
  const tc::CrestLines strong = tc::extractCrestLines(mesh, curvature, options);
  ASSERT_GT(strong.numLines(), 0);
  EXPECT_LT(strong.numLines(), all.numLines());
  for (double s : strong.strength)
  {
    EXPECT_GE(s, options.minStrength);
  }
}

TEST(CrestLinesOutput, PolylinesAreWellFormedAndLieOnMeshEdges)
{
  const tc::TriMesh mesh = tctest::roundedBox(1.0, 0.3, 24).mesh;
  const tc::CrestLines lines = crestsOf(mesh);
  const tc::EdgeTable edges = tc::buildEdgeTable(mesh.triangles);
  const tc::VertexFaces faces = tc::buildVertexFaces(mesh.triangles, mesh.numPoints());
  const int64_t np = static_cast<int64_t>(lines.points.size() / 3);
  ASSERT_GT(lines.numLines(), 0);
  ASSERT_EQ(lines.offsets.front(), 0);
  ASSERT_EQ(lines.offsets.back(), static_cast<int64_t>(lines.connectivity.size()));
  ASSERT_EQ(static_cast<int64_t>(lines.strength.size()), lines.numLines());
  ASSERT_EQ(static_cast<int64_t>(lines.type.size()), lines.numLines());
  ASSERT_EQ(static_cast<int64_t>(lines.pointEdge.size()), np);
  for (int64_t l = 0; l < lines.numLines(); ++l)
  {
    EXPECT_GE(lines.offsets[l + 1] - lines.offsets[l], 2);
    EXPECT_GT(lines.strength[l], 0.0);
    for (int64_t i = lines.offsets[l]; i < lines.offsets[l + 1]; ++i)
    {
      ASSERT_GE(lines.connectivity[i], 0);
      ASSERT_LT(lines.connectivity[i], np);
    }
    // Consecutive points lie in one triangle.
    for (int64_t i = lines.offsets[l]; i + 1 < lines.offsets[l + 1]; ++i)
    {
      const std::vector<int32_t> fa =
        facesHolding(mesh, edges, faces, lines, lines.connectivity[i]);
      const std::vector<int32_t> fb =
        facesHolding(mesh, edges, faces, lines, lines.connectivity[i + 1]);
      EXPECT_TRUE(std::any_of(fa.begin(), fa.end(),
        [&fb](int32_t f) { return std::find(fb.begin(), fb.end(), f) != fb.end(); }));
    }
  }
  // Every point is on the segment of its mesh edge.
  for (int64_t p = 0; p < np; ++p)
  {
    const int32_t e = lines.pointEdge[p];
    const double* a = &mesh.points[3 * edges.vertices[2 * e]];
    const double* b = &mesh.points[3 * edges.vertices[2 * e + 1]];
    const double* x = &lines.points[3 * p];
    double ab2 = 0.0, t = 0.0;
    for (int c = 0; c < 3; ++c)
    {
      ab2 += (b[c] - a[c]) * (b[c] - a[c]);
      t += (x[c] - a[c]) * (b[c] - a[c]);
    }
    t /= ab2;
    EXPECT_GE(t, -1e-12);
    EXPECT_LE(t, 1.0 + 1e-12);
    for (int c = 0; c < 3; ++c)
    {
      EXPECT_NEAR(x[c], a[c] + t * (b[c] - a[c]), 1e-12);
    }
  }
}

TEST(CrestLinesDeterminism, SameLinesWithOneThreadOrMany)
{
  const tc::TriMesh mesh = tctest::roundedBox(1.0, 0.3, 24).mesh;
  const tc::CurvatureResult curvature = tc::computeCurvature(mesh);
  const tc::CrestLines many = tc::extractCrestLines(mesh, curvature);
  tc::CrestLines one;
  {
    tbb::global_control single(tbb::global_control::max_allowed_parallelism, 1);
    one = tc::extractCrestLines(mesh, curvature);
  }
  EXPECT_EQ(many.points, one.points);
  EXPECT_EQ(many.offsets, one.offsets);
  EXPECT_EQ(many.connectivity, one.connectivity);
  EXPECT_EQ(many.strength, one.strength);
  EXPECT_EQ(many.type, one.type);
}

TEST(CrestLinesInput, RejectsTheCurvatureOfAnotherMesh)
{
  const tc::CurvatureResult curvature = tc::computeCurvature(tctest::icosphere(1.0, 2).mesh);
  EXPECT_THROW(tc::extractCrestLines(tctest::icosphere(1.0, 3).mesh, curvature), tc::InputError);
}

TEST(CrestLinesProgress, ReportsAndHonoursAbort)
{
  const tc::TriMesh mesh = tctest::roundedBox(1.0, 0.3, 12).mesh;
  const tc::CurvatureResult curvature = tc::computeCurvature(mesh);
  tctest::expectProgressAndAbort([&](const tc::Progress& p)
    { tc::extractCrestLines(mesh, curvature, {}, p); },
    1, [](double f) { return f < 0.5; });
}
