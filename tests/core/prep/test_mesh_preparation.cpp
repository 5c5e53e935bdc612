// SPDX-License-Identifier: BSD-3-Clause
#include "tc/common/errors.h"
#include "tc/common/mesh_topology.h"
#include "tc/io/off_io.h"
#include "tc/prep/mesh_preparation.h"

#include "analytic_meshes.h"
#include "test_data.h"
#include "test_progress.h"

#include "mesh_checks.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <numeric>
#include <random>
#include <string>
#include <vector>

namespace
{
using Polygons = std::vector<std::vector<int64_t>>;

tc::PolygonSoup makeSoup(const std::vector<double>& points, const Polygons& polygons)
{
  tc::PolygonSoup soup;
  soup.points = points;
  for (const auto& polygon : polygons)
  {
    soup.addPolygon(polygon.data(), static_cast<int64_t>(polygon.size()));
  }
  return soup;
}

std::array<double, 3> cornerVector(const tc::TriMesh& mesh, int64_t f, int a, int b)
{
  const auto pa = mesh.point(mesh.triangles[3 * f + a]);
  const auto pb = mesh.point(mesh.triangles[3 * f + b]);
  return { pb[0] - pa[0], pb[1] - pa[1], pb[2] - pa[2] };
}

std::array<double, 3> faceNormal(const tc::TriMesh& mesh, int64_t f)
{
  const auto u = cornerVector(mesh, f, 0, 1);
  const auto v = cornerVector(mesh, f, 0, 2);
  return { u[1] * v[2] - u[2] * v[1], u[2] * v[0] - u[0] * v[2], u[0] * v[1] - u[1] * v[0] };
}

double totalArea(const tc::TriMesh& mesh)
{
  double area = 0.0;
  for (int64_t f = 0; f < mesh.numTriangles(); ++f)
  {
    const auto n = faceNormal(mesh, f);
    area += 0.5 * std::sqrt(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]);
  }
  return area;
}

double signedVolume(const tc::TriMesh& mesh)
{
  double volume = 0.0;
  for (int64_t f = 0; f < mesh.numTriangles(); ++f)
  {
    const auto p = mesh.point(mesh.triangles[3 * f]);
    const auto n = faceNormal(mesh, f);
    volume += (p[0] * n[0] + p[1] * n[1] + p[2] * n[2]) / 6.0;
  }
  return volume;
}

tc::TriMesh toMesh(const tc::PolygonSoup& soup)
{
  tc::TriMesh mesh;
  mesh.points = soup.points;
  for (int64_t id : soup.connectivity)
  {
    mesh.triangles.push_back(static_cast<int32_t>(id));
  }
  return mesh;
}

int64_t maxEdgeValence(const tc::TriMesh& mesh)
{
  const tc::EdgeTable edges = tc::buildEdgeTable(mesh.triangles);
  int64_t most = 0;
  for (int64_t e = 0; e < edges.numEdges(); ++e)
  {
    most = std::max(most, edges.valence(e));
  }
  return most;
}

/// Number of fans around each vertex: its faces, joined across edges that have 2 faces.
/// Written independently of prepareMesh (quadratic per vertex, fine for tests).
std::vector<int> fansPerVertex(const tc::TriMesh& mesh)
{
  const tc::EdgeTable edges = tc::buildEdgeTable(mesh.triangles);
  const tc::VertexFaces around = tc::buildVertexFaces(mesh.triangles, mesh.numPoints());
  std::vector<int> fans(mesh.numPoints(), 0);
  for (int64_t v = 0; v < mesh.numPoints(); ++v)
  {
    const int64_t begin = around.offsets[v];
    const int64_t n = around.offsets[v + 1] - begin;
    std::vector<int64_t> label(n);
    std::iota(label.begin(), label.end(), 0);
    for (int64_t a = 0; a < n; ++a)
    {
      for (int64_t b = 0; b < n; ++b)
      {
        const int64_t fa = around.faceIds[begin + a];
        const int64_t fb = around.faceIds[begin + b];
        for (int i = 0; i < 3; ++i)
        {
          const int32_t e = edges.faceEdges[3 * fa + i];
          const bool hasV = edges.vertices[2 * e] == v || edges.vertices[2 * e + 1] == v;
          const bool inB = edges.faceEdges[3 * fb] == e || edges.faceEdges[3 * fb + 1] == e ||
            edges.faceEdges[3 * fb + 2] == e;
          if (fa != fb && hasV && inB && edges.valence(e) == 2)
          {
            const int64_t la = label[a];
            const int64_t lb = label[b];
            for (auto& l : label)
            {
              l = (l == la || l == lb) ? std::min(la, lb) : l;
            }
          }
        }
      }
    }
    std::sort(label.begin(), label.end());
    fans[v] = static_cast<int>(std::unique(label.begin(), label.end()) - label.begin());
  }
  return fans;
}

/// Output is manifold: no edge with more than 2 faces, one fan around every vertex.
void expectManifold(const tc::TriMesh& mesh)
{
  EXPECT_LE(maxEdgeValence(mesh), 2);
  const std::vector<int> fans = fansPerVertex(mesh);
  for (size_t v = 0; v < fans.size(); ++v)
  {
    EXPECT_EQ(fans[v], 1) << "vertex " << v;
  }
}

/// Octahedron with corners on the unit axes, outward-facing.
tc::PolygonSoup octahedron()
{
  return makeSoup({ 1, 0, 0, -1, 0, 0, 0, 1, 0, 0, -1, 0, 0, 0, 1, 0, 0, -1 },
    { { 0, 2, 4 }, { 2, 1, 4 }, { 1, 3, 4 }, { 3, 0, 4 }, { 2, 0, 5 }, { 1, 2, 5 }, { 3, 1, 5 },
      { 0, 3, 5 } });
}

/// Appends a tetrahedron with corners (x, y, z) and (x, y, z) + each unit axis, outward-facing.
void addTetrahedron(std::vector<double>& points, Polygons& polygons, double x, double y, double z)
{
  const int64_t first = static_cast<int64_t>(points.size() / 3);
  const std::vector<double> corners = { 0, 0, 0, 1, 0, 0, 0, 1, 0, 0, 0, 1 };
  for (size_t i = 0; i < corners.size(); ++i)
  {
    points.push_back(corners[i] + (i % 3 == 0 ? x : (i % 3 == 1 ? y : z)));
  }
  for (const auto& face : Polygons{ { 0, 2, 1 }, { 0, 1, 3 }, { 0, 3, 2 }, { 1, 2, 3 } })
  {
    polygons.push_back({ first + face[0], first + face[1], first + face[2] });
  }
}

/// The message of the tc::InputError that prepareMesh throws ("" if none).
std::string preparationError(
  const tc::PolygonSoup& soup, const tc::PreparationOptions& options = {})
{
  try
  {
    tc::prepareMesh(soup, options);
  }
  catch (const tc::InputError& error)
  {
    return error.what();
  }
  return "";
}

bool contains(const std::string& text, const std::string& part)
{
  return text.find(part) != std::string::npos;
}
} // namespace

TEST(Preparation, CleanClosedMeshesPassUnchanged)
{
  int tested = 0;
  for (const char* name : { "static_small/elephant.off", "static_small/homer.off",
         "static_small/bunny_npm.off", "cad/fandisk.off", "cad/couplingdown.off", "cad/cube.off" })
  {
    SCOPED_TRACE(name);
    const std::string path = tctest::sharedData(name);
    if (path.empty())
    {
      continue;
    }
    ++tested;
    const tc::PolygonSoup soup = tc::readOFF(path);
    const tc::PreparationResult result = tc::prepareMesh(soup);
    EXPECT_FALSE(result.report.changed()) << result.report.text();
    EXPECT_EQ(result.mesh.points, soup.points);
    EXPECT_EQ(result.mesh.triangles, toMesh(soup).triangles);
    EXPECT_EQ(result.report.components, 1);
    EXPECT_EQ(result.report.closedComponents, 1);
    EXPECT_EQ(result.report.boundaryEdges, 0);
    EXPECT_EQ(result.report.nonManifoldEdges + result.report.nonManifoldVertices, 0);
    EXPECT_GT(signedVolume(result.mesh), 0.0);
    std::vector<int64_t> identity(soup.numPoints());
    std::iota(identity.begin(), identity.end(), 0);
    EXPECT_EQ(result.inputPointId, identity);
  }
  if (tested == 0)
  {
    GTEST_SKIP() << "the closed meshes of ../shared/data are absent";
  }
}

TEST(Preparation, OctahedronPassesUnchanged)
{
  const tc::PolygonSoup soup = octahedron();
  const tc::PreparationResult result = tc::prepareMesh(soup);
  EXPECT_FALSE(result.report.changed()) << result.report.text();
  EXPECT_EQ(result.mesh.triangles, toMesh(soup).triangles);
  EXPECT_EQ(result.report.closedComponents, 1);
}

TEST(Preparation, CowHasOneCoincidentPointPairThatMergesIntoAPinch)
{
  // cow.off repeats point 44 as point 2903; merging it pinches the surface at that point.
  const std::string path = tctest::sharedData("static_small/cow.off");
  if (path.empty())
  {
    GTEST_SKIP() << "../shared/data/static_small/cow.off is absent";
  }
  const tc::PolygonSoup soup = tc::readOFF(path);
  const tc::PreparationResult merged = tc::prepareMesh(soup);
  EXPECT_EQ(merged.report.mergedPoints, 1);
  EXPECT_EQ(merged.report.outputPoints, 2903);
  EXPECT_EQ(merged.report.nonManifoldVertices, 1);
  EXPECT_EQ(merged.nonManifoldVertex[44], 1);
  EXPECT_TRUE(merged.report.changed());
  tc::PreparationOptions split;
  split.splitNonManifold = true;
  const tc::PreparationResult result = tc::prepareMesh(soup, split);
  EXPECT_EQ(result.report.splitVertices, 1);
  EXPECT_EQ(result.report.outputPoints, 2904);
  EXPECT_EQ(result.report.closedComponents, 1);
  expectManifold(result.mesh);
}

TEST(Preparation, QuadsAreTriangulatedWithTheirArea)
{
  // Unit cube of 6 outward quads.
  const tc::PolygonSoup soup =
    makeSoup({ 0, 0, 0, 1, 0, 0, 1, 1, 0, 0, 1, 0, 0, 0, 1, 1, 0, 1, 1, 1, 1, 0, 1, 1 },
      { { 0, 3, 2, 1 }, { 4, 5, 6, 7 }, { 0, 1, 5, 4 }, { 2, 3, 7, 6 }, { 1, 2, 6, 5 },
        { 0, 4, 7, 3 } });
  const tc::PreparationResult result = tc::prepareMesh(soup);
  EXPECT_EQ(result.report.polygonsTriangulated, 6);
  EXPECT_EQ(result.mesh.numTriangles(), 12);
  EXPECT_NEAR(totalArea(result.mesh), 6.0, 1e-12);
  EXPECT_NEAR(signedVolume(result.mesh), 1.0, 1e-12);
  EXPECT_EQ(result.report.flippedFaces, 0);
  EXPECT_EQ(result.report.closedComponents, 1);
  EXPECT_TRUE(result.report.changed());
  for (int64_t f = 0; f < 12; ++f)
  {
    EXPECT_EQ(result.inputCellId[f], f / 2);
  }
}

TEST(Preparation, NonConvexPentagonIsTriangulatedInsideItself)
{
  // An arrow-head pentagon, reflex at (2, 1), tilted out of every coordinate plane.
  const std::vector<std::array<double, 2>> plane = { { 0, 0 }, { 4, 0 }, { 4, 4 }, { 2, 1 },
    { 0, 4 } };
  const double planeArea = 10.0; // 16 minus the notch (2 * 3)
  const std::array<double, 3> u = { 0.6, 0.0, 0.8 };
  const std::array<double, 3> v = { -0.64, 0.6, 0.48 }; // orthonormal to u
  std::vector<double> points;
  for (const auto& p : plane)
  {
    for (int c = 0; c < 3; ++c)
    {
      points.push_back(1.0 + p[0] * u[c] + p[1] * v[c]);
    }
  }
  for (int start = 0; start < 5; ++start)
  {
    SCOPED_TRACE(start);
    std::vector<int64_t> polygon;
    for (int k = 0; k < 5; ++k)
    {
      polygon.push_back((start + k) % 5);
    }
    const tc::PreparationResult result = tc::prepareMesh(makeSoup(points, { polygon }));
    ASSERT_EQ(result.mesh.numTriangles(), 3);
    EXPECT_EQ(result.report.polygonsTriangulated, 1);
    EXPECT_NEAR(totalArea(result.mesh), planeArea, 1e-12);
    // Every triangle keeps the polygon's orientation (normal along u x v).
    const std::array<double, 3> n = { u[1] * v[2] - u[2] * v[1], u[2] * v[0] - u[0] * v[2],
      u[0] * v[1] - u[1] * v[0] };
    for (int64_t f = 0; f < 3; ++f)
    {
      const auto fn = faceNormal(result.mesh, f);
      EXPECT_GT(fn[0] * n[0] + fn[1] * n[1] + fn[2] * n[2], 0.0);
    }
  }
}

TEST(Preparation, StarShapedPolygonsKeepTheirArea)
{
  // Random star-shaped (so simple, mostly non-convex) polygons of 4 to 40 corners in the plane
  // z = x + 2y: ear clipping must cover each exactly once.
  std::mt19937 random(3);
  std::uniform_real_distribution<double> radius(0.2, 1.0);
  const double pi = std::acos(-1.0);
  for (int trial = 0; trial < 50; ++trial)
  {
    SCOPED_TRACE(trial);
    const int n = 4 + trial % 37;
    std::vector<double> points;
    std::vector<int64_t> polygon;
    double planeArea = 0.0;
    std::vector<std::array<double, 2>> xy;
    for (int k = 0; k < n; ++k)
    {
      const double angle = 2.0 * pi * (k + 0.4 * radius(random)) / n;
      const double r = radius(random);
      xy.push_back({ r * std::cos(angle), r * std::sin(angle) });
      points.insert(points.end(), { xy[k][0], xy[k][1], xy[k][0] + 2.0 * xy[k][1] });
      polygon.push_back(k);
    }
    for (int k = 0; k < n; ++k)
    {
      const auto& a = xy[k];
      const auto& b = xy[(k + 1) % n];
      planeArea += 0.5 * (a[0] * b[1] - a[1] * b[0]);
    }
    const tc::PreparationResult result = tc::prepareMesh(makeSoup(points, { polygon }));
    EXPECT_EQ(result.mesh.numTriangles(), n - 2);
    // The plane z = x + 2y stretches areas by |(-1, -2, 1)| = sqrt(6).
    EXPECT_NEAR(totalArea(result.mesh), planeArea * std::sqrt(6.0), 1e-12 * n);
    for (int64_t f = 0; f < result.mesh.numTriangles(); ++f)
    {
      EXPECT_GT(faceNormal(result.mesh, f)[2], 0.0);
    }
  }
}

TEST(Preparation, ExactDuplicatePointsAreMerged)
{
  // Two triangles of a square, each with its own copies of the diagonal's ends (ids 3, 4 are
  // copies of 2 and 0).
  const tc::PolygonSoup soup = makeSoup(
    { 0, 0, 0, 1, 0, 0, 1, 1, 0, 1, 1, 0, 0, 0, 0, 0, 1, 0 }, { { 0, 1, 2 }, { 4, 3, 5 } });
  const tc::PreparationResult result = tc::prepareMesh(soup);
  EXPECT_EQ(result.report.mergedPoints, 2);
  EXPECT_EQ(result.mesh.numPoints(), 4);
  EXPECT_EQ(result.inputPointId, (std::vector<int64_t>{ 0, 1, 2, 5 }));
  EXPECT_EQ(result.report.components, 1);
  EXPECT_EQ(result.report.boundaryEdges, 4);
  EXPECT_TRUE(result.report.changed());
}

TEST(Preparation, PointsWithinTheToleranceAreMerged)
{
  // As above, with the copies off by 1e-7 of the diagonal.
  const double d = 1e-7 * std::sqrt(2.0);
  const tc::PolygonSoup soup = makeSoup(
    { 0, 0, 0, 1, 0, 0, 1, 1, 0, 1 + d, 1, 0, 0, d, 0, 0, 1, 0 }, { { 0, 1, 2 }, { 4, 3, 5 } });
  const tc::PreparationResult exact = tc::prepareMesh(soup);
  EXPECT_EQ(exact.report.mergedPoints, 0);
  EXPECT_EQ(exact.report.components, 2);
  tc::PreparationOptions loose;
  loose.mergeTolerance = 1e-8;
  EXPECT_EQ(tc::prepareMesh(soup, loose).report.mergedPoints, 0);
  loose.mergeTolerance = 1e-5;
  const tc::PreparationResult merged = tc::prepareMesh(soup, loose);
  EXPECT_EQ(merged.report.mergedPoints, 2);
  EXPECT_EQ(merged.report.components, 1);
  EXPECT_EQ(merged.inputPointId, (std::vector<int64_t>{ 0, 1, 2, 5 }));
  EXPECT_EQ(merged.mesh.points[3 * 2], 1.0); // the lowest id of a group gives the position
}

TEST(Preparation, ToleranceMergeWeldsACubeOfSeparateFaces)
{
  // Every quad of a unit cube (scaled by 1e3) with its own 4 corners, jittered by 1e-9.
  const int corners[6][4] = { { 0, 3, 2, 1 }, { 4, 5, 6, 7 }, { 0, 1, 5, 4 }, { 2, 3, 7, 6 },
    { 1, 2, 6, 5 }, { 0, 4, 7, 3 } };
  std::vector<double> points;
  Polygons polygons;
  for (int f = 0; f < 6; ++f)
  {
    std::vector<int64_t> polygon;
    for (int k = 0; k < 4; ++k)
    {
      const int c = corners[f][k];
      polygon.push_back(static_cast<int64_t>(points.size() / 3));
      const double jitter = 1e-9 * ((f * 4 + k) % 3);
      points.push_back(1e3 * ((c == 1 || c == 2 || c == 5 || c == 6) ? 1 : 0) + jitter);
      points.push_back(1e3 * ((c == 2 || c == 3 || c == 6 || c == 7) ? 1 : 0) - jitter);
      points.push_back(1e3 * (c >= 4 ? 1 : 0) + jitter);
    }
    polygons.push_back(polygon);
  }
  tc::PreparationOptions options;
  options.mergeTolerance = 1e-6;
  const tc::PreparationResult result = tc::prepareMesh(makeSoup(points, polygons), options);
  EXPECT_EQ(result.report.mergedPoints, 16);
  EXPECT_EQ(result.mesh.numPoints(), 8);
  EXPECT_EQ(result.report.closedComponents, 1);
  EXPECT_GT(signedVolume(result.mesh), 0.0);
}

TEST(Preparation, DegenerateFacesAreDropped)
{
  for (const double scale : { 1e-6, 1.0, 1e6 })
  {
    SCOPED_TRACE(scale);
    std::vector<double> points = { 0, 0, 0, 1, 0, 0, 0, 1, 0, 2, 0, 0, 1, 1e-12, 0 };
    for (double& x : points)
    {
      x *= scale;
    }
    // A good triangle; a repeated corner; three collinear corners; a sliver of area 2e-13 of
    // the diagonal squared (below the 1e-12 rule at every scale); a polygon of 2 corners.
    const tc::PolygonSoup soup =
      makeSoup(points, { { 0, 1, 2 }, { 0, 1, 1 }, { 0, 1, 3 }, { 0, 3, 4 }, { 1, 2 } });
    const tc::PreparationResult result = tc::prepareMesh(soup);
    EXPECT_EQ(result.report.degenerateFaces, 4);
    EXPECT_EQ(result.mesh.numTriangles(), 1);
    EXPECT_EQ(result.report.unusedPoints, 2);
    EXPECT_EQ(result.inputCellId, (std::vector<int64_t>{ 0 }));
  }
}

TEST(Preparation, DuplicateFacesAreDropped)
{
  tc::PolygonSoup soup = octahedron();
  // The first face again, rotated, and reversed.
  soup.addPolygon(std::vector<int64_t>{ 2, 4, 0 }.data(), 3);
  soup.addPolygon(std::vector<int64_t>{ 0, 4, 2 }.data(), 3);
  const tc::PreparationResult result = tc::prepareMesh(soup);
  EXPECT_EQ(result.report.duplicateFaces, 2);
  EXPECT_EQ(result.mesh.numTriangles(), 8);
  EXPECT_EQ(result.report.nonManifoldEdges, 0);
  EXPECT_EQ(result.report.closedComponents, 1);
}

TEST(Preparation, HalfFlippedClosedMeshIsReorientedOutward)
{
  std::vector<tc::PolygonSoup> meshes = { octahedron() };
  const std::string path = tctest::sharedData("static_small/elephant.off");
  if (!path.empty())
  {
    meshes.push_back(tc::readOFF(path));
  }
  for (tc::PolygonSoup& soup : meshes)
  {
    // Flip every odd face, and the first one too, so that the seed faces inward.
    int64_t flipped = 0;
    for (int64_t p = 0; p < soup.numPolygons(); ++p)
    {
      if (p % 2 == 1 || p == 0)
      {
        std::swap(soup.connectivity[3 * p + 1], soup.connectivity[3 * p + 2]);
        ++flipped;
      }
    }
    const tc::PreparationResult result = tc::prepareMesh(soup);
    EXPECT_EQ(result.report.flippedFaces, flipped);
    EXPECT_TRUE(tctest::consistentlyOriented(result.mesh));
    EXPECT_GT(signedVolume(result.mesh), 0.0);
    EXPECT_EQ(result.report.nonOrientableComponents, 0);

    tc::PreparationOptions keep;
    keep.orient = false;
    const tc::PreparationResult unoriented = tc::prepareMesh(soup, keep);
    EXPECT_EQ(unoriented.report.flippedFaces, 0);
    EXPECT_EQ(unoriented.mesh.triangles, toMesh(soup).triangles);
  }
}

TEST(Preparation, InsideOutClosedMeshIsTurnedOutward)
{
  tc::PolygonSoup soup = octahedron();
  for (int64_t p = 0; p < soup.numPolygons(); ++p)
  {
    std::swap(soup.connectivity[3 * p + 1], soup.connectivity[3 * p + 2]);
  }
  const tc::PreparationResult result = tc::prepareMesh(soup);
  EXPECT_EQ(result.report.flippedFaces, 8);
  EXPECT_GT(signedVolume(result.mesh), 0.0);
}

TEST(Preparation, OpenMeshIsOrientedLikeItsFirstFace)
{
  // A 4 x 4 grid of quads split into triangles, every third triangle flipped.
  std::vector<double> points;
  for (int j = 0; j <= 4; ++j)
  {
    for (int i = 0; i <= 4; ++i)
    {
      points.insert(points.end(), { double(i), double(j), 0.1 * i * j });
    }
  }
  Polygons polygons;
  for (int j = 0; j < 4; ++j)
  {
    for (int i = 0; i < 4; ++i)
    {
      const int64_t a = j * 5 + i;
      polygons.push_back({ a, a + 1, a + 6 });
      polygons.push_back({ a, a + 6, a + 5 });
    }
  }
  int64_t flipped = 0;
  for (size_t p = 1; p < polygons.size(); p += 3)
  {
    std::swap(polygons[p][1], polygons[p][2]);
    ++flipped;
  }
  const tc::PreparationResult result = tc::prepareMesh(makeSoup(points, polygons));
  EXPECT_EQ(result.report.flippedFaces, flipped);
  EXPECT_TRUE(tctest::consistentlyOriented(result.mesh));
  EXPECT_GT(faceNormal(result.mesh, 0)[2], 0.0);
  EXPECT_EQ(result.report.boundaryEdges, 16);
  EXPECT_EQ(result.report.closedComponents, 0);
  int rim = 0;
  for (int64_t v = 0; v < 25; ++v)
  {
    const int i = static_cast<int>(v % 5);
    const int j = static_cast<int>(v / 5);
    const bool onRim = i == 0 || j == 0 || i == 4 || j == 4;
    EXPECT_EQ(result.boundaryVertex[v], onRim ? 1 : 0) << v;
    rim += onRim;
  }
  EXPECT_EQ(rim, 16);
}

TEST(Preparation, MoebiusStripIsReportedAndLeftAsItIs)
{
  const int n = 12;
  const double pi = std::acos(-1.0);
  std::vector<double> points;
  for (int i = 0; i < n; ++i)
  {
    const double t = 2.0 * pi * i / n;
    const double h = 0.3 * std::cos(t / 2.0);
    const double z = 0.3 * std::sin(t / 2.0);
    for (const double s : { 1.0, -1.0 })
    {
      points.insert(
        points.end(), { std::cos(t) * (1.0 + s * h), std::sin(t) * (1.0 + s * h), s * z });
    }
  }
  Polygons polygons;
  for (int i = 0; i < n; ++i)
  {
    const int64_t top = 2 * i;
    const int64_t bottom = 2 * i + 1;
    // The half twist: after the last segment, top and bottom swap.
    const int64_t nextTop = i + 1 < n ? 2 * (i + 1) : 1;
    const int64_t nextBottom = i + 1 < n ? 2 * (i + 1) + 1 : 0;
    polygons.push_back({ top, bottom, nextBottom });
    polygons.push_back({ top, nextBottom, nextTop });
  }
  const tc::PolygonSoup soup = makeSoup(points, polygons);
  const tc::PreparationResult result = tc::prepareMesh(soup);
  EXPECT_EQ(result.report.nonOrientableComponents, 1);
  EXPECT_EQ(result.report.flippedFaces, 0);
  EXPECT_EQ(result.mesh.triangles, toMesh(soup).triangles);
  EXPECT_EQ(result.report.boundaryEdges, 2 * n);
  EXPECT_EQ(result.report.components, 1);
  EXPECT_NE(result.report.text().find("1 non-orientable component"), std::string::npos);
}

TEST(Preparation, NonManifoldEdgeIsFlaggedAndSplit)
{
  // Three fins on edge (0, 1); faces 0 and 1 run along it the same way, face 2 the other way,
  // so faces 0 and 2 are the first consistent pair and stay joined.
  const tc::PolygonSoup soup = makeSoup({ 0, 0, 0, 1, 0, 0, 0.5, 1, 0, 0.5, 0, 1, 0.5, -1, 0 },
    { { 0, 1, 2 }, { 0, 1, 3 }, { 1, 0, 4 } });
  const tc::PreparationResult flagged = tc::prepareMesh(soup);
  EXPECT_EQ(flagged.report.nonManifoldEdges, 1);
  EXPECT_EQ(flagged.nonManifoldEdge, (std::vector<uint8_t>{ 1, 1, 1 }));
  EXPECT_EQ(flagged.nonManifoldVertex, (std::vector<uint8_t>{ 1, 1, 0, 0, 0 }));
  EXPECT_EQ(flagged.report.nonManifoldVertices, 2);
  EXPECT_EQ(maxEdgeValence(flagged.mesh), 3);

  tc::PreparationOptions options;
  options.splitNonManifold = true;
  const tc::PreparationResult split = tc::prepareMesh(soup, options);
  expectManifold(split.mesh);
  EXPECT_EQ(split.report.splitVertices, 2);
  EXPECT_EQ(split.mesh.numPoints(), 7);
  EXPECT_EQ(split.report.nonManifoldEdges, 1); // counted before splitting
  EXPECT_EQ(split.nonManifoldEdge, (std::vector<uint8_t>{ 1, 1, 1 }));
  EXPECT_EQ(split.inputPointId, (std::vector<int64_t>{ 0, 1, 2, 3, 4, 0, 1 }));
  EXPECT_EQ(split.nonManifoldVertex, (std::vector<uint8_t>{ 1, 1, 0, 0, 0, 1, 1 }));
  // Faces 0 and 2 still share their edge; face 1 got the copies.
  EXPECT_EQ(split.mesh.triangles[3 * 1], 5);
  EXPECT_EQ(split.mesh.triangles[3 * 1 + 1], 6);
  EXPECT_EQ(split.report.components, 2);
  EXPECT_EQ(split.report.boundaryEdges, 7);
  EXPECT_TRUE(tctest::consistentlyOriented(split.mesh));
}

TEST(Preparation, FinOnAClosedSurfaceIsSplitOff)
{
  // A fin on edge (0, 1) of a tetrahedron, listed first and consistent with the tetrahedron's
  // face (0, 2, 1): that pair stays joined, so the other tetrahedron face on the edge is the
  // one set apart, although the fans around 0 and 1 wrap around to it.
  std::vector<double> points;
  Polygons polygons = { { 0, 1, 4 } };
  addTetrahedron(points, polygons, 0, 0, 0);
  points.insert(points.end(), { 0.5, -1, -1 });
  const tc::PolygonSoup soup = makeSoup(points, polygons);
  const tc::PreparationResult flagged = tc::prepareMesh(soup);
  EXPECT_EQ(flagged.report.nonManifoldEdges, 1);
  tc::PreparationOptions options;
  options.splitNonManifold = true;
  const tc::PreparationResult split = tc::prepareMesh(soup, options);
  expectManifold(split.mesh);
  EXPECT_EQ(split.report.splitVertices, 1);
  EXPECT_TRUE(tctest::consistentlyOriented(split.mesh));
  EXPECT_EQ(split.report.closedComponents, 0);
}

TEST(Preparation, TwoConesTouchingAtTheTipAreFlaggedAndSplit)
{
  // Two open cones (4 faces each around apex 0), one above and one below the apex.
  std::vector<double> points = { 0, 0, 0 };
  Polygons polygons;
  for (const double z : { 1.0, -1.0 })
  {
    const int64_t first = static_cast<int64_t>(points.size() / 3);
    points.insert(points.end(), { 1, 0, z, 0, 1, z, -1, 0, z, 0, -1, z });
    for (int64_t k = 0; k < 4; ++k)
    {
      polygons.push_back({ 0, first + (k + 1) % 4, first + k });
    }
  }
  const tc::PolygonSoup soup = makeSoup(points, polygons);
  const tc::PreparationResult flagged = tc::prepareMesh(soup);
  EXPECT_EQ(flagged.report.nonManifoldVertices, 1);
  EXPECT_EQ(flagged.report.nonManifoldEdges, 0);
  EXPECT_EQ(flagged.nonManifoldVertex[0], 1);
  EXPECT_EQ(
    std::accumulate(flagged.nonManifoldVertex.begin(), flagged.nonManifoldVertex.end(), 0), 1);
  EXPECT_EQ(flagged.report.components, 2);
  EXPECT_EQ(flagged.report.boundaryEdges, 8);
  EXPECT_EQ(flagged.boundaryVertex[0], 0);

  tc::PreparationOptions options;
  options.splitNonManifold = true;
  const tc::PreparationResult split = tc::prepareMesh(soup, options);
  expectManifold(split.mesh);
  EXPECT_EQ(split.report.splitVertices, 1);
  EXPECT_EQ(split.mesh.numPoints(), 10);
  EXPECT_EQ(split.inputPointId.back(), 0);
  EXPECT_EQ(split.nonManifoldVertex.back(), 1);
  EXPECT_TRUE(split.report.changed());
}

TEST(Preparation, SplitMakesRandomSoupsManifold)
{
  // Random triangles and polygons over a few grid points: non-manifold edges and vertices,
  // duplicates and degenerate faces everywhere.
  std::mt19937 random(1);
  int nonManifold = 0;
  for (int trial = 0; trial < 300; ++trial)
  {
    SCOPED_TRACE(trial);
    const int numPoints = 4 + static_cast<int>(random() % 12);
    std::vector<double> points;
    for (int k = 0; k < 3 * numPoints; ++k)
    {
      points.push_back(0.25 * static_cast<double>(random() % 5));
    }
    Polygons polygons(1 + random() % 30);
    for (auto& polygon : polygons)
    {
      const int n = 3 + (random() % 6 == 0 ? static_cast<int>(random() % 3) : 0);
      for (int k = 0; k < n; ++k)
      {
        polygon.push_back(static_cast<int64_t>(random() % numPoints));
      }
    }
    const tc::PolygonSoup soup = makeSoup(points, polygons);
    tc::PreparationOptions options;
    options.splitNonManifold = true;
    options.mergeTolerance = 0.1 * (trial % 3);
    tc::PreparationResult result;
    try
    {
      result = tc::prepareMesh(soup, options);
    }
    catch (const tc::InputError&)
    {
      continue; // all faces degenerate
    }
    nonManifold += result.report.nonManifoldEdges > 0 ? 1 : 0;
    expectManifold(result.mesh);
    if (result.report.nonOrientableComponents == 0)
    {
      EXPECT_TRUE(tctest::consistentlyOriented(result.mesh));
    }
    const tc::PreparationReport& report = result.report;
    EXPECT_EQ(report.inputPoints,
      report.mergedPoints + report.unusedPoints + report.outputPoints - report.splitVertices);
    ASSERT_EQ(result.inputPointId.size(), static_cast<size_t>(result.mesh.numPoints()));
    ASSERT_EQ(result.inputCellId.size(), static_cast<size_t>(result.mesh.numTriangles()));
    ASSERT_EQ(result.nonManifoldVertex.size(), result.inputPointId.size());
    ASSERT_EQ(result.boundaryVertex.size(), result.inputPointId.size());
    ASSERT_EQ(result.componentId.size(), result.inputCellId.size());
    for (int64_t v = 0; v < result.mesh.numPoints(); ++v)
    {
      for (int c = 0; c < 3; ++c)
      {
        ASSERT_EQ(result.mesh.points[3 * v + c], soup.points[3 * result.inputPointId[v] + c]);
      }
    }
  }
  EXPECT_GT(nonManifold, 100);
}

TEST(Preparation, ComponentsAreCountedInTheOrderOfTheirFirstFace)
{
  std::vector<double> points;
  Polygons a;
  Polygons b;
  addTetrahedron(points, a, 0, 0, 0);
  addTetrahedron(points, b, 5, 0, 0);
  // Faces interleaved: A B A B ...; then B comes first.
  Polygons polygons;
  for (size_t k = 0; k < 4; ++k)
  {
    polygons.push_back(a[k]);
    polygons.push_back(b[k]);
  }
  const tc::PreparationResult result = tc::prepareMesh(makeSoup(points, polygons));
  EXPECT_EQ(result.report.components, 2);
  EXPECT_EQ(result.report.closedComponents, 2);
  EXPECT_EQ(result.componentId, (std::vector<int32_t>{ 0, 1, 0, 1, 0, 1, 0, 1 }));
  std::swap(polygons[0], polygons[1]);
  const tc::PreparationResult swapped = tc::prepareMesh(makeSoup(points, polygons));
  EXPECT_EQ(swapped.componentId[0], 0);
  EXPECT_EQ(swapped.componentId[2], 1);
}

TEST(Preparation, TeapotIsOpenWithSeveralComponents)
{
  const std::string path = tctest::sharedData("static_small/teapot_npm.off");
  if (path.empty())
  {
    GTEST_SKIP() << "../shared/data/static_small/teapot_npm.off is absent";
  }
  const tc::PolygonSoup soup = tc::readOFF(path);
  ASSERT_EQ(soup.numPolygons(), 992);
  const tc::PreparationResult result = tc::prepareMesh(soup);
  // README counts (cc 32, bnd 528) are of the unwelded file: its 32 Bezier patches each have
  // their own seam points; merging those exact duplicates leaves the 4 parts of the teapot.
  EXPECT_EQ(result.report.mergedPoints, 263);
  EXPECT_EQ(result.report.components, 4);
  EXPECT_EQ(result.report.boundaryEdges, 64);
  EXPECT_EQ(result.report.closedComponents, 0);
  EXPECT_EQ(result.mesh.numTriangles(), 992);
  EXPECT_TRUE(tctest::consistentlyOriented(result.mesh));
  int64_t boundary = 0;
  for (uint8_t b : result.boundaryVertex)
  {
    boundary += b;
  }
  EXPECT_GT(boundary, 0);
}

TEST(Preparation, ReportTextHasOneLinePerNonZeroItem)
{
  const tc::PolygonSoup soup = makeSoup(
    { 0, 0, 0, 1, 0, 0, 1, 1, 0, 1, 1, 0, 0, 0, 0, 0, 1, 0 }, { { 0, 1, 2 }, { 4, 3, 5 } });
  const std::string text = tc::prepareMesh(soup).report.text();
  EXPECT_TRUE(contains(text, "merged 2 duplicate points\n")) << text;
  EXPECT_TRUE(contains(text, "4 boundary edges\n")) << text;
  EXPECT_TRUE(contains(text, "1 connected component\n")) << text;
  EXPECT_FALSE(contains(text, "flipped")) << text;
  EXPECT_FALSE(contains(text, "degenerate")) << text;
  EXPECT_EQ(std::count(text.begin(), text.end(), '\n'), 7) << text;
}

TEST(Preparation, ProgressIsReportedInOrderAndAbortStops)
{
  tctest::expectProgressAndAbort([](const tc::Progress& p)
    { tc::prepareMesh(octahedron(), {}, p); },
    3, [](double f) { return f < 0.5; });
}

TEST(Preparation, EmptyInputThrows)
{
  EXPECT_TRUE(contains(preparationError(tc::PolygonSoup()), "no points"));
  EXPECT_TRUE(contains(preparationError(makeSoup({ 0, 0, 0, 1, 0, 0 }, {})), "no polygons"));
}

TEST(Preparation, OutOfRangeIdThrows)
{
  const std::string message =
    preparationError(makeSoup({ 0, 0, 0, 1, 0, 0, 0, 1, 0 }, { { 0, 1, 2 }, { 0, 2, 3 } }));
  EXPECT_TRUE(contains(message, "polygon 1")) << message;
  EXPECT_TRUE(contains(message, "point id 3, out of range")) << message;
  EXPECT_TRUE(contains(
    preparationError(makeSoup({ 0, 0, 0, 1, 0, 0, 0, 1, 0 }, { { 0, -1, 2 } })), "out of range"));
}

TEST(Preparation, NanAndInfCoordinatesThrowNamingTheFirstPoint)
{
  const double nan = std::nan("");
  const double inf = std::numeric_limits<double>::infinity();
  const std::string message = preparationError(
    makeSoup({ 0, 0, 0, 1, 0, 0, 0, 1, 0, 0, nan, 0, inf, 0, 0 }, { { 0, 1, 2 } }));
  EXPECT_TRUE(contains(message, "point 3 has a NaN or infinite coordinate")) << message;
  EXPECT_TRUE(contains(message, "2 points have one")) << message;
}

TEST(Preparation, ZeroAreaInputThrows)
{
  const std::string collinear =
    preparationError(makeSoup({ 0, 0, 0, 1, 0, 0, 2, 0, 0 }, { { 0, 1, 2 } }));
  EXPECT_TRUE(contains(collinear, "zero total area")) << collinear;
  // Non-zero, but below 1e-12 of the diagonal squared: nothing is left after cleaning.
  const std::string sliver =
    preparationError(makeSoup({ 0, 0, 0, 1, 0, 0, 0, 1e-13, 0 }, { { 0, 1, 2 } }));
  EXPECT_TRUE(contains(sliver, "no triangles with non-zero area")) << sliver;
}

TEST(Preparation, IsDeterministic)
{
  const std::string path = tctest::sharedData("static_small/teapot_npm.off");
  if (path.empty())
  {
    GTEST_SKIP() << "../shared/data/static_small/teapot_npm.off is absent";
  }
  tc::PreparationOptions options;
  options.splitNonManifold = true;
  options.mergeTolerance = 1e-4;
  const tc::PolygonSoup soup = tc::readOFF(path);
  const tc::PreparationResult a = tc::prepareMesh(soup, options);
  const tc::PreparationResult b = tc::prepareMesh(soup, options);
  EXPECT_EQ(a.mesh.points, b.mesh.points);
  EXPECT_EQ(a.mesh.triangles, b.mesh.triangles);
  EXPECT_EQ(a.inputPointId, b.inputPointId);
  EXPECT_EQ(a.report.text(), b.report.text());
}

TEST(Preparation, LeavesAClosedMediumMeshUnchanged)
{
  const std::string path = tctest::sharedData("static_medium/refined_elephant.off");
  if (path.empty())
  {
    GTEST_SKIP() << "../shared/data/static_medium/refined_elephant.off is absent";
  }
  const tc::PolygonSoup soup = tc::readOFF(path);
  const tc::PreparationResult result = tc::prepareMesh(soup);
  EXPECT_EQ(result.report.closedComponents, 1);
  EXPECT_EQ(result.report.outputTriangles, 88928);
  EXPECT_FALSE(result.report.changed());
}

namespace
{
/// The unit icosphere (5120 triangles) without the triangles whose centroid lies in one of two
/// caps, z > 0.8 and x > 0.9, as a soup: a sphere with two holes.
tc::PolygonSoup sphereWithTwoHoles()
{
  const tc::TriMesh sphere = tctest::icosphere(1.0, 4).mesh;
  tc::PolygonSoup soup;
  soup.points = sphere.points;
  soup.offsets.push_back(0);
  for (int64_t f = 0; f < sphere.numTriangles(); ++f)
  {
    std::array<double, 3> c{ 0.0, 0.0, 0.0 };
    for (int k = 0; k < 3; ++k)
    {
      for (int x = 0; x < 3; ++x)
      {
        c[x] += sphere.points[3 * sphere.triangles[3 * f + k] + x] / 3.0;
      }
    }
    if (c[2] > 0.8 || c[0] > 0.9)
    {
      continue;
    }
    for (int k = 0; k < 3; ++k)
    {
      soup.connectivity.push_back(sphere.triangles[3 * f + k]);
    }
    soup.offsets.push_back(static_cast<int64_t>(soup.connectivity.size()));
  }
  return soup;
}
} // namespace

TEST(Preparation, HolesAreClosedByFairedPatchesWhenAsked)
{
  const tc::PolygonSoup soup = sphereWithTwoHoles();
  const tc::PreparationResult open = tc::prepareMesh(soup);
  EXPECT_GT(open.report.boundaryEdges, 20);
  EXPECT_EQ(open.report.closedComponents, 0);
  EXPECT_EQ(open.report.filledHoles, 0);

  tc::PreparationOptions options;
  options.fillHoles = true;
  const tc::PreparationResult r = tc::prepareMesh(soup, options);
  const tc::PreparationReport& report = r.report;
  std::printf("[ figures  ] sphere with two holes (%lld boundary edges): %lld holes filled with "
              "%lld triangles and %lld points\n",
    static_cast<long long>(open.report.boundaryEdges), static_cast<long long>(report.filledHoles),
    static_cast<long long>(report.holeTriangles), static_cast<long long>(report.holePoints));
  EXPECT_EQ(report.filledHoles, 2);
  EXPECT_EQ(report.openHoles, 0);
  EXPECT_EQ(report.unfairedHoles, 0);
  EXPECT_EQ(report.boundaryEdges, 0);
  EXPECT_EQ(report.components, 1);
  EXPECT_EQ(report.closedComponents, 1);
  EXPECT_TRUE(report.changed());
  EXPECT_TRUE(contains(report.text(), "filled 2 holes"));
  expectManifold(r.mesh);
  EXPECT_TRUE(tctest::consistentlyOriented(r.mesh));
  EXPECT_GT(signedVolume(r.mesh), 0.0);
  // A closed genus-0 surface: V - E + F = 2.
  EXPECT_EQ(
    r.mesh.numPoints() - tc::buildEdgeTable(r.mesh.triangles).numEdges() + r.mesh.numTriangles(),
    2);
  // The old points and triangles come first and keep their input ids; the new ones say -1.
  EXPECT_EQ(r.mesh.numPoints(), open.mesh.numPoints() + report.holePoints);
  EXPECT_EQ(r.mesh.numTriangles(), open.mesh.numTriangles() + report.holeTriangles);
  EXPECT_GT(report.holePoints, 10);
  for (int64_t v = 0; v < r.mesh.numPoints(); ++v)
  {
    EXPECT_EQ(r.inputPointId[v] < 0, v >= open.mesh.numPoints());
  }
  for (int64_t f = 0; f < r.mesh.numTriangles(); ++f)
  {
    EXPECT_EQ(r.inputCellId[f] < 0, f >= open.mesh.numTriangles());
  }
  // Faired patches follow the sphere: the cap of z > 0.8 bulges 0.2 above its rim's plane, and
  // the new points lie well above that plane, near the sphere.
  double farthest = 0.0;
  for (int64_t v = open.mesh.numPoints(); v < r.mesh.numPoints(); ++v)
  {
    const std::array<double, 3> p = r.mesh.point(v);
    farthest = std::max(farthest, std::abs(std::sqrt(p[0] * p[0] + p[1] * p[1] + p[2] * p[2]) - 1));
  }
  std::printf("[ figures  ] new points within %.4f of the unit sphere\n", farthest);
  EXPECT_LT(farthest, 0.05);

  // Loops longer than maxHoleEdges stay open and are reported.
  options.maxHoleEdges = 5;
  const tc::PreparationResult capped = tc::prepareMesh(soup, options);
  EXPECT_EQ(capped.report.filledHoles, 0);
  EXPECT_EQ(capped.report.openHoles, 2);
  EXPECT_EQ(capped.report.boundaryEdges, open.report.boundaryEdges);
  EXPECT_TRUE(contains(capped.report.text(), "left 2 holes open"));
}

namespace
{
/// A triangle on the first edge of the first polygon, out to (3, 3, 3): a non-manifold edge.
void addFin(tc::PolygonSoup& soup)
{
  const int64_t a = soup.connectivity[0], b = soup.connectivity[1];
  soup.points.insert(soup.points.end(), { 3.0, 3.0, 3.0 });
  soup.connectivity.insert(soup.connectivity.end(), { a, b, soup.numPoints() - 1 });
  soup.offsets.push_back(static_cast<int64_t>(soup.connectivity.size()));
}
} // namespace

TEST(Preparation, HolesOfANonManifoldMeshAreRefusedUntilSplit)
{
  // The sphere with two holes and a fin on one of its edges.
  tc::PolygonSoup soup = sphereWithTwoHoles();
  addFin(soup);
  tc::PreparationOptions options;
  options.fillHoles = true;
  const std::string error = preparationError(soup, options);
  EXPECT_TRUE(contains(error, "cannot fill holes")) << error;
  EXPECT_TRUE(contains(error, "--split-non-manifold")) << error;
  // Split off, the fin is a lone triangle: closing its 3-edge loop would give a flat two-sided
  // pair, no surface a base complex can cover, so the fragment is dropped.
  options.splitNonManifold = true;
  const tc::PreparationResult r = tc::prepareMesh(soup, options);
  EXPECT_EQ(r.report.filledHoles, 3);
  EXPECT_EQ(r.report.droppedFragments, 1);
  EXPECT_EQ(r.report.boundaryEdges, 0);
  EXPECT_EQ(r.report.components, 1);
  EXPECT_EQ(r.report.closedComponents, 1);
  EXPECT_TRUE(contains(r.report.text(), "dropped 1 fragment of fewer than 4 triangles"));
  // The per-element arrays follow the kept points and triangles.
  EXPECT_EQ(r.inputPointId.size(), static_cast<size_t>(r.mesh.numPoints()));
  EXPECT_EQ(r.inputCellId.size(), static_cast<size_t>(r.mesh.numTriangles()));
  EXPECT_EQ(r.componentId.size(), static_cast<size_t>(r.mesh.numTriangles()));
  for (const int32_t v : r.mesh.triangles)
  {
    ASSERT_LT(v, r.mesh.numPoints());
  }
  // Without FillHoles the fin stays, as the user's data.
  options.fillHoles = false;
  const tc::PreparationResult open = tc::prepareMesh(soup, options);
  EXPECT_EQ(open.report.droppedFragments, 0);
  EXPECT_EQ(open.report.components, 2);
}

namespace
{
/// An icosphere with a needle pair (a point 3% along an edge, splitting both its triangles: two
/// triangles with sides 33 times their shortest) and a cap (a point 1% of a triangle's height off
/// the middle of a side, splitting that triangle in three: one angle of 178 degrees).
tc::PolygonSoup sphereWithSlivers()
{
  const tc::TriMesh sphere = tctest::icosphere(1.0, 2).mesh;
  std::vector<std::array<int64_t, 3>> faces;
  for (int64_t f = 0; f < sphere.numTriangles(); ++f)
  {
    faces.push_back(
      { sphere.triangles[3 * f], sphere.triangles[3 * f + 1], sphere.triangles[3 * f + 2] });
  }
  tc::PolygonSoup soup;
  soup.points = sphere.points;
  auto add = [&](const std::array<double, 3>& p)
  {
    soup.points.insert(soup.points.end(), p.begin(), p.end());
    return soup.numPoints() - 1;
  };
  auto at = [&](int64_t v) { return sphere.point(v); };
  // Needles: edge (a, b) of face 0 and its twin (b, a, d).
  const int64_t a = faces[0][0], b = faces[0][1], c = faces[0][2];
  size_t twin = 0;
  int64_t d = -1;
  for (size_t f = 1; f < faces.size(); ++f)
  {
    for (int k = 0; k < 3; ++k)
    {
      if (faces[f][k] == b && faces[f][(k + 1) % 3] == a)
      {
        twin = f;
        d = faces[f][(k + 2) % 3];
      }
    }
  }
  std::array<double, 3> p{};
  for (int x = 0; x < 3; ++x)
  {
    p[x] = at(a)[x] + 0.03 * (at(b)[x] - at(a)[x]);
  }
  const int64_t n = add(p);
  faces[0] = { a, n, c };
  faces.push_back({ n, b, c });
  faces[twin] = { b, n, d };
  faces.push_back({ n, a, d });
  // Cap: the last original face (e, f, g), far from face 0.
  const size_t last = static_cast<size_t>(sphere.numTriangles() - 1);
  const int64_t e = faces[last][0], f = faces[last][1], g = faces[last][2];
  std::array<double, 3> q{};
  for (int x = 0; x < 3; ++x)
  {
    const double mid = 0.5 * (at(e)[x] + at(f)[x]);
    q[x] = mid + 0.01 * (at(g)[x] - mid);
  }
  const int64_t m = add(q);
  faces[last] = { e, f, m };
  faces.push_back({ f, g, m });
  faces.push_back({ g, e, m });
  soup.offsets.push_back(0);
  for (const auto& t : faces)
  {
    soup.connectivity.insert(soup.connectivity.end(), t.begin(), t.end());
    soup.offsets.push_back(static_cast<int64_t>(soup.connectivity.size()));
  }
  return soup;
}

/// Triangles with an angle above 170 degrees or a side 10 times another.
int64_t countSlivers(const tc::TriMesh& mesh)
{
  int64_t count = 0;
  for (int64_t f = 0; f < mesh.numTriangles(); ++f)
  {
    double len[3];
    for (int k = 0; k < 3; ++k)
    {
      const std::array<double, 3> u = cornerVector(mesh, f, (k + 1) % 3, (k + 2) % 3);
      len[k] = std::sqrt(u[0] * u[0] + u[1] * u[1] + u[2] * u[2]);
    }
    std::sort(len, len + 3);
    const double largestAngle = std::acos(std::clamp(
      (len[0] * len[0] + len[1] * len[1] - len[2] * len[2]) / (2 * len[0] * len[1]), -1.0, 1.0));
    count += len[2] > 10 * len[0] || largestAngle > 170.0 * M_PI / 180.0 ? 1 : 0;
  }
  return count;
}
} // namespace

TEST(Preparation, SliversAreCollapsedAndFlippedWhenAsked)
{
  const tc::PolygonSoup soup = sphereWithSlivers();
  const tc::PreparationResult plain = tc::prepareMesh(soup);
  EXPECT_EQ(countSlivers(plain.mesh), 3);
  EXPECT_EQ(plain.report.slivers, 0); // not looked for

  tc::PreparationOptions options;
  options.removeSlivers = true;
  const tc::PreparationResult r = tc::prepareMesh(soup, options);
  const tc::PreparationReport& report = r.report;
  EXPECT_EQ(report.slivers, 3);
  EXPECT_EQ(report.remainingSlivers, 0);
  EXPECT_EQ(countSlivers(r.mesh), 0);
  // The needles go with one collapse (one point and their two triangles); the cap's longest
  // side is flipped, and the collapse reshapes the triangles round the point it removed.
  EXPECT_EQ(report.sliverPoints, 1);
  EXPECT_EQ(r.mesh.numPoints(), plain.mesh.numPoints() - 1);
  EXPECT_EQ(r.mesh.numTriangles(), plain.mesh.numTriangles() - 2);
  EXPECT_GE(report.reshapedTriangles, 2);
  EXPECT_TRUE(report.changed());
  EXPECT_TRUE(contains(report.text(), "found 3 slivers (caps and needles): collapsed 1 point"))
    << report.text();
  EXPECT_FALSE(contains(report.text(), "left")) << report.text();
  expectManifold(r.mesh);
  EXPECT_TRUE(tctest::consistentlyOriented(r.mesh));
  EXPECT_EQ(report.closedComponents, 1);
  EXPECT_EQ(
    r.mesh.numPoints() - tc::buildEdgeTable(r.mesh.triangles).numEdges() + r.mesh.numTriangles(),
    2);
  EXPECT_NEAR(signedVolume(r.mesh), signedVolume(plain.mesh), 1e-3);
  // No point moved; the per-element arrays follow the kept points and triangles.
  ASSERT_EQ(r.inputPointId.size(), static_cast<size_t>(r.mesh.numPoints()));
  ASSERT_EQ(r.inputCellId.size(), static_cast<size_t>(r.mesh.numTriangles()));
  ASSERT_EQ(r.nonManifoldVertex.size(), r.inputPointId.size());
  ASSERT_EQ(r.boundaryVertex.size(), r.inputPointId.size());
  ASSERT_EQ(r.componentId.size(), r.inputCellId.size());
  for (int64_t v = 0; v < r.mesh.numPoints(); ++v)
  {
    ASSERT_GE(r.inputPointId[v], 0);
    EXPECT_TRUE(v == 0 || r.inputPointId[v] > r.inputPointId[v - 1]);
    for (int x = 0; x < 3; ++x)
    {
      EXPECT_EQ(r.mesh.points[3 * v + x], soup.points[3 * r.inputPointId[v] + x]);
    }
  }
  for (int64_t f = 0; f < r.mesh.numTriangles(); ++f)
  {
    EXPECT_TRUE(f == 0 || r.inputCellId[f] > r.inputCellId[f - 1]);
  }

  // Deterministic.
  const tc::PreparationResult again = tc::prepareMesh(soup, options);
  EXPECT_EQ(again.mesh.points, r.mesh.points);
  EXPECT_EQ(again.mesh.triangles, r.mesh.triangles);

  // Thresholds that would take ordinary triangles for slivers are refused.
  for (const auto& [angle, ratio] : { std::pair<double, double>{ 90.0, 10.0 }, { 170.0, 1.5 },
         { 181.0, 10.0 }, { std::nan(""), 10.0 } })
  {
    tc::PreparationOptions bad = options;
    bad.sliverAngle = angle;
    bad.sliverEdgeRatio = ratio;
    EXPECT_TRUE(contains(preparationError(soup, bad), "sliverEdgeRatio at least 3")) << angle;
  }
}

TEST(Preparation, SliversOfANonManifoldMeshAreRefusedUntilSplit)
{
  tc::PolygonSoup soup = sphereWithSlivers();
  addFin(soup);
  tc::PreparationOptions options;
  options.removeSlivers = true;
  const std::string error = preparationError(soup, options);
  EXPECT_TRUE(contains(error, "cannot remove slivers")) << error;
  EXPECT_TRUE(contains(error, "--split-non-manifold")) << error;
  options.splitNonManifold = true;
  const tc::PreparationResult r = tc::prepareMesh(soup, options);
  // The fin, split off, is a lone needle: no collapse keeps it a triangle, so it stays.
  EXPECT_EQ(r.report.slivers, 4);
  EXPECT_EQ(r.report.remainingSlivers, 1);
  EXPECT_EQ(countSlivers(r.mesh), 1);
  EXPECT_TRUE(contains(r.report.text(), "left 1 sliver")) << r.report.text();
}
