// SPDX-License-Identifier: BSD-3-Clause
// The preparation's component options: DropNonOrientable, MinComponentTriangles,
// KeepLargestComponent (step 9 of prepareMesh), on soups of several components and on scans.
#include "tc/common/errors.h"
#include "tc/common/mesh_topology.h"
#include "tc/io/soup_io.h"
#include "tc/prep/mesh_preparation.h"

#include "test_data.h"

#include "mesh_checks.h"

#include <gtest/gtest.h>

#include <chrono>
#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

namespace
{
using Polygons = std::vector<std::vector<int64_t>>;

/// A soup built part by part, each part's polygons numbered in order.
struct Soup
{
  std::vector<double> points;
  Polygons polygons;

  int64_t addPoint(double x, double y, double z)
  {
    points.insert(points.end(), { x, y, z });
    return static_cast<int64_t>(points.size() / 3) - 1;
  }

  tc::PolygonSoup soup() const
  {
    tc::PolygonSoup s;
    s.points = points;
    for (const auto& p : polygons)
    {
      s.addPolygon(p.data(), static_cast<int64_t>(p.size()));
    }
    return s;
  }
};

/// Appends a closed, outward-facing cube of side `size` at (x, 0, 0), each face an n x n grid:
/// 12 n^2 triangles. Grid points are shared along the cube's edges. Returns the first polygon.
int64_t addBox(Soup& s, double x, double size, int n)
{
  const int64_t first = static_cast<int64_t>(s.polygons.size());
  std::vector<int64_t> ids(static_cast<size_t>(n + 1) * (n + 1) * (n + 1), -1);
  auto idOf = [&](int i, int j, int k)
  {
    // One point per lattice node on the surface, made on first use.
    const size_t key = (static_cast<size_t>(i) * (n + 1) + j) * (n + 1) + k;
    if (ids[key] < 0)
    {
      ids[key] = s.addPoint(x + size * i / n, size * j / n, size * k / n);
    }
    return ids[key];
  };
  // Each face: the axis it is normal to, its side, and two in-plane axes whose cross product
  // points outward.
  for (int axis = 0; axis < 3; ++axis)
  {
    for (int side = 0; side < 2; ++side)
    {
      const int u = side == 1 ? (axis + 1) % 3 : (axis + 2) % 3;
      const int v = side == 1 ? (axis + 2) % 3 : (axis + 1) % 3;
      for (int a = 0; a < n; ++a)
      {
        for (int b = 0; b < n; ++b)
        {
          auto node = [&](int da, int db)
          {
            int c[3];
            c[axis] = side * n;
            c[u] = a + da;
            c[v] = b + db;
            return idOf(c[0], c[1], c[2]);
          };
          s.polygons.push_back({ node(0, 0), node(1, 0), node(1, 1) });
          s.polygons.push_back({ node(0, 0), node(1, 1), node(0, 1) });
        }
      }
    }
  }
  return first;
}

/// Appends a Moebius strip of 2 n triangles around (x, 0, 0); returns its first polygon.
int64_t addMoebius(Soup& s, double x, int n)
{
  const int64_t first = static_cast<int64_t>(s.polygons.size());
  const double pi = std::acos(-1.0);
  const int64_t base = static_cast<int64_t>(s.points.size() / 3);
  for (int i = 0; i < n; ++i)
  {
    const double t = 2.0 * pi * i / n;
    const double h = 0.3 * std::cos(t / 2.0);
    const double z = 0.3 * std::sin(t / 2.0);
    for (const double sign : { 1.0, -1.0 })
    {
      s.addPoint(x + std::cos(t) * (1.0 + sign * h), std::sin(t) * (1.0 + sign * h), sign * z);
    }
  }
  for (int i = 0; i < n; ++i)
  {
    const int64_t top = base + 2 * i;
    const int64_t bottom = top + 1;
    // The half twist: after the last segment, top and bottom swap.
    const int64_t nextTop = i + 1 < n ? top + 2 : base + 1;
    const int64_t nextBottom = i + 1 < n ? top + 3 : base;
    s.polygons.push_back({ top, bottom, nextBottom });
    s.polygons.push_back({ top, nextBottom, nextTop });
  }
  return first;
}

/// Appends a lone triangle at (x, 0, 0).
int64_t addTriangle(Soup& s, double x)
{
  const int64_t a = s.addPoint(x, 0, 0);
  const int64_t b = s.addPoint(x + 1, 0, 0);
  const int64_t c = s.addPoint(x, 1, 0);
  s.polygons.push_back({ a, b, c });
  return static_cast<int64_t>(s.polygons.size()) - 1;
}

/// The input polygons of the output triangles, in output order.
std::vector<int64_t> survivors(const tc::PreparationResult& r)
{
  return r.inputCellId;
}

/// first, first + 1, ..., first + n - 1.
std::vector<int64_t> range(int64_t first, int64_t n)
{
  std::vector<int64_t> ids(static_cast<size_t>(n));
  for (int64_t i = 0; i < n; ++i)
  {
    ids[static_cast<size_t>(i)] = first + i;
  }
  return ids;
}

/// Six times the signed volume of a mesh.
double volume6(const tc::TriMesh& mesh)
{
  double v = 0.0;
  for (int64_t f = 0; f < mesh.numTriangles(); ++f)
  {
    const auto a = mesh.point(mesh.triangles[3 * f]);
    const auto b = mesh.point(mesh.triangles[3 * f + 1]);
    const auto c = mesh.point(mesh.triangles[3 * f + 2]);
    v += a[0] * (b[1] * c[2] - b[2] * c[1]) - a[1] * (b[0] * c[2] - b[2] * c[0]) +
      a[2] * (b[0] * c[1] - b[1] * c[0]);
  }
  return v;
}

/// The report's point balance (mesh_preparation.h).
void expectPointsBalance(const tc::PreparationReport& r)
{
  EXPECT_EQ(r.inputPoints,
    r.mergedPoints + r.unusedPoints + r.outputPoints - r.splitVertices - r.holePoints +
      r.sliverPoints + r.droppedComponentPoints);
}

bool contains(const std::string& text, const std::string& part)
{
  return text.find(part) != std::string::npos;
}

std::string preparationError(const tc::PolygonSoup& soup, const tc::PreparationOptions& options)
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

/// Two closed boxes of 12 and 108 triangles and a stray triangle, in that order.
struct BoxesAndTriangle
{
  Soup s;
  int64_t smallBox = 0, largeBox = 0, stray = 0;
  BoxesAndTriangle()
  {
    smallBox = addBox(s, 0.0, 1.0, 1);
    largeBox = addBox(s, 3.0, 2.0, 3);
    stray = addTriangle(s, 7.0);
  }
};
} // namespace

TEST(PreparationComponents, ByDefaultEveryComponentStaysAndTheRepairNamesTheLargest)
{
  const BoxesAndTriangle m;
  const tc::PreparationOptions options;
  const tc::PreparationResult r = tc::prepareMesh(m.s.soup(), options);
  EXPECT_EQ(r.report.components, 3);
  EXPECT_EQ(r.report.closedComponents, 2);
  EXPECT_EQ(r.report.outputTriangles, 121);
  EXPECT_EQ(r.report.largestComponentTriangles, 108);
  EXPECT_TRUE(r.report.largestComponentClosed);
  EXPECT_FALSE(r.report.changed());
  EXPECT_FALSE(tc::closedManifold(r.report, options));
  const std::string repairs = tc::closedManifoldRepairs(r.report, options);
  EXPECT_TRUE(contains(repairs, "3 boundary edges (close the holes")) << repairs;
  EXPECT_TRUE(contains(repairs,
    "or keep only the largest component, which is closed and "
    "oriented (108 of the 121 triangles): KeepLargestComponent, "
    "trichart build --keep-largest-component"))
    << repairs;
}

TEST(PreparationComponents, KeepLargestComponentLeavesTheLargeBoxClosedAndOutward)
{
  const BoxesAndTriangle m;
  tc::PreparationOptions options;
  options.keepLargestComponent = true;
  const tc::PreparationResult r = tc::prepareMesh(m.s.soup(), options);
  EXPECT_EQ(survivors(r), range(m.largeBox, 108));
  EXPECT_EQ(r.report.droppedMinorComponents, 2);
  EXPECT_EQ(r.report.droppedMinorTriangles, 13);
  EXPECT_EQ(r.report.droppedSmallComponents, 0);
  EXPECT_EQ(r.report.droppedComponentPoints, 8 + 3);
  EXPECT_EQ(r.report.components, 1);
  EXPECT_EQ(r.report.boundaryEdges, 0);
  EXPECT_EQ(r.componentId, std::vector<int32_t>(108, 0));
  EXPECT_TRUE(tctest::consistentlyOriented(r.mesh, true));
  EXPECT_NEAR(volume6(r.mesh), 6.0 * 8.0, 1e-9);
  EXPECT_TRUE(tc::closedManifold(r.report, options));
  EXPECT_TRUE(r.report.changed());
  expectPointsBalance(r.report);
  // Points keep the input order, and each is the input point it came from.
  for (int64_t v = 0; v < r.mesh.numPoints(); ++v)
  {
    EXPECT_EQ(r.mesh.point(v)[0], m.s.points[3 * r.inputPointId[v]]);
    EXPECT_TRUE(v == 0 || r.inputPointId[v] > r.inputPointId[v - 1]);
  }
  const std::string text = r.report.text();
  EXPECT_TRUE(contains(text,
    "dropped 2 components other than the largest, with 13 triangles in "
    "all (KeepLargestComponent)\n"))
    << text;
  EXPECT_TRUE(contains(text, "dropped 11 points with the dropped components\n")) << text;
}

TEST(PreparationComponents, MinComponentTrianglesDropsWhatIsBelowIt)
{
  const BoxesAndTriangle m;
  tc::PreparationOptions options;
  options.minComponentTriangles = 12; // the small box has exactly 12: kept
  const tc::PreparationResult r = tc::prepareMesh(m.s.soup(), options);
  std::vector<int64_t> boxes = range(m.smallBox, 12);
  for (const int64_t f : range(m.largeBox, 108))
  {
    boxes.push_back(f);
  }
  EXPECT_EQ(survivors(r), boxes);
  EXPECT_EQ(r.report.droppedSmallComponents, 1);
  EXPECT_EQ(r.report.droppedSmallTriangles, 1);
  EXPECT_EQ(r.report.droppedComponentPoints, 3);
  EXPECT_EQ(r.report.components, 2);
  EXPECT_EQ(r.report.closedComponents, 2);
  EXPECT_TRUE(tctest::consistentlyOriented(r.mesh, true));
  EXPECT_TRUE(tc::closedManifold(r.report, options));
  expectPointsBalance(r.report);
  EXPECT_TRUE(contains(r.report.text(),
    "dropped 1 component of fewer triangles than "
    "MinComponentTriangles, with 1 triangle in all\n"))
    << r.report.text();

  options.minComponentTriangles = 13;
  const tc::PreparationResult r13 = tc::prepareMesh(m.s.soup(), options);
  EXPECT_EQ(survivors(r13), range(m.largeBox, 108));
  EXPECT_EQ(r13.report.droppedSmallComponents, 2);
  EXPECT_EQ(r13.report.droppedSmallTriangles, 13);

  // Everything below the floor: an error that says what dropped what.
  options.minComponentTriangles = 109;
  const std::string error = preparationError(m.s.soup(), options);
  EXPECT_TRUE(contains(error,
    "no component is left: MinComponentTriangles = 109 dropped 3 "
    "components (121 triangles)"))
    << error;
  options.minComponentTriangles = -1;
  EXPECT_TRUE(contains(preparationError(m.s.soup(), options), "minComponentTriangles must be"));
}

TEST(PreparationComponents, EachDroppedComponentIsCountedUnderTheFirstRuleThatDropsIt)
{
  const BoxesAndTriangle m;
  tc::PreparationOptions options;
  options.keepLargestComponent = true;
  options.minComponentTriangles = 2;
  const tc::PreparationResult r = tc::prepareMesh(m.s.soup(), options);
  EXPECT_EQ(survivors(r), range(m.largeBox, 108));
  EXPECT_EQ(r.report.droppedSmallComponents, 1); // the stray triangle
  EXPECT_EQ(r.report.droppedSmallTriangles, 1);
  EXPECT_EQ(r.report.droppedMinorComponents, 1); // the small box
  EXPECT_EQ(r.report.droppedMinorTriangles, 12);
}

TEST(PreparationComponents, DropNonOrientableLeavesTheClosedBox)
{
  Soup s;
  addMoebius(s, 0.0, 12);
  const int64_t box = addBox(s, 3.0, 1.0, 2);
  tc::PreparationOptions options;
  const tc::PreparationResult kept = tc::prepareMesh(s.soup(), options);
  EXPECT_EQ(kept.report.nonOrientableComponents, 1);
  EXPECT_EQ(kept.report.nonOrientableTriangles, 24);
  EXPECT_TRUE(contains(kept.report.text(), "1 non-orientable component with 24 triangles"));
  const std::string repairs = tc::closedManifoldRepairs(kept.report, options);
  EXPECT_TRUE(contains(repairs,
    "1 non-orientable (Moebius-like) component (24 of the 72 "
    "triangles), which no orientation fixes (drop it: "
    "DropNonOrientable, trichart build --drop-non-orientable"))
    << repairs;
  EXPECT_TRUE(contains(repairs, "--keep-largest-component")) << repairs; // the box: 48

  options.dropNonOrientable = true;
  const tc::PreparationResult r = tc::prepareMesh(s.soup(), options);
  EXPECT_EQ(survivors(r), range(box, 48));
  EXPECT_EQ(r.report.droppedNonOrientable, 1);
  EXPECT_EQ(r.report.droppedNonOrientableTriangles, 24);
  EXPECT_EQ(r.report.droppedComponentPoints, 24);
  EXPECT_EQ(r.report.nonOrientableComponents, 0);
  EXPECT_EQ(r.report.components, 1);
  EXPECT_TRUE(tctest::consistentlyOriented(r.mesh, true));
  EXPECT_GT(volume6(r.mesh), 0.0);
  EXPECT_TRUE(tc::closedManifold(r.report, options));
  expectPointsBalance(r.report);
  EXPECT_TRUE(contains(
    r.report.text(), "dropped 1 non-orientable component with 24 triangles (DropNonOrientable)\n"))
    << r.report.text();
}

TEST(PreparationComponents, DropNonOrientableLetsHoleFillingRun)
{
  // A Moebius strip and an open box (one face grid missing): hole filling refuses the
  // non-orientable strip, and says which option drops it.
  Soup s;
  addMoebius(s, 0.0, 12);
  addBox(s, 3.0, 1.0, 2);
  s.polygons.resize(s.polygons.size() - 8); // the last face grid: 2 x 2 x 2 triangles
  tc::PreparationOptions options;
  options.fillHoles = true;
  const std::string error = preparationError(s.soup(), options);
  EXPECT_TRUE(contains(error, "cannot fill holes")) << error;
  EXPECT_TRUE(contains(error, "drop it (DropNonOrientable, --drop-non-orientable)")) << error;

  options.dropNonOrientable = true;
  const tc::PreparationResult r = tc::prepareMesh(s.soup(), options);
  EXPECT_EQ(r.report.droppedNonOrientable, 1);
  EXPECT_EQ(r.report.filledHoles, 1);
  EXPECT_EQ(r.report.boundaryEdges, 0);
  EXPECT_TRUE(tctest::consistentlyOriented(r.mesh, true));
  EXPECT_GT(volume6(r.mesh), 0.0);
  EXPECT_TRUE(tc::closedManifold(r.report, options));
  expectPointsBalance(r.report);
}

TEST(PreparationComponents, AStripGluedToABoxMakesItOneNonOrientableComponent)
{
  // Two triangles bridge a box edge (then non-manifold) and a boundary edge of the strip (then
  // manifold): one component, which cannot be oriented; dropping it would leave nothing, and
  // the error says so.
  Soup s;
  const int64_t box = addBox(s, 0.0, 1.0, 1);
  const int64_t strip = static_cast<int64_t>(s.points.size() / 3);
  addMoebius(s, 3.0, 12);
  const int64_t p = s.polygons[box][0], q = s.polygons[box][1];
  const int64_t top0 = strip, top1 = strip + 2; // a boundary edge of the strip
  s.polygons.push_back({ p, q, top0 });
  s.polygons.push_back({ q, top1, top0 });
  tc::PreparationOptions options;
  const tc::PreparationResult r = tc::prepareMesh(s.soup(), options);
  EXPECT_EQ(r.report.components, 1);
  EXPECT_EQ(r.report.nonOrientableComponents, 1);
  EXPECT_EQ(r.report.nonManifoldEdges, 1);
  EXPECT_EQ(r.report.nonOrientableTriangles, 12 + 24 + 2);
  options.dropNonOrientable = true;
  const std::string error = preparationError(s.soup(), options);
  EXPECT_TRUE(contains(error,
    "no component is left: DropNonOrientable dropped 1 "
    "non-orientable component (38 triangles)"))
    << error;
}

namespace
{
/// Prepares a scan with the options a scan needs, prints what was dropped and how long it
/// took, and checks that the output is a closed, oriented manifold.
tc::PreparationResult prepareScan(
  const std::string& relative, const tc::PreparationOptions& options)
{
  const std::string path = tctest::sharedData(relative);
  if (path.empty())
  {
    return {};
  }
  const tc::PolygonSoup soup = tc::readPLY(path);
  const auto start = std::chrono::steady_clock::now();
  const tc::PreparationResult r = tc::prepareMesh(soup, options);
  const double seconds =
    std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  std::printf("%s: %.2f s\n%s", relative.c_str(), seconds, r.report.text().c_str());
  EXPECT_TRUE(tc::closedManifold(r.report, options))
    << tc::closedManifoldRepairs(r.report, options);
  EXPECT_TRUE(tctest::consistentlyOriented(r.mesh, true));
  expectPointsBalance(r.report);
  return r;
}
} // namespace

TEST(PreparationComponents, DragonRes3IsMostlyOneNonOrientableBodyOnceSplit)
{
  // Splitting its 1564 non-manifold edges leaves the decimated dragon one body that cannot be
  // oriented and 146 islands of 1 to 42 triangles: the hint does not offer to drop the body.
  const std::string relative = "static_medium/dragon_vrip_res3.ply.gz";
  if (tctest::sharedData(relative).empty())
  {
    GTEST_SKIP() << "../shared/data/" << relative << " is absent";
  }
  tc::PreparationOptions options;
  options.splitNonManifold = true;
  const tc::PreparationResult split =
    tc::prepareMesh(tc::readPLY(tctest::sharedData(relative)), options);
  EXPECT_EQ(split.report.components, 147);
  EXPECT_EQ(split.report.nonOrientableComponents, 1);
  EXPECT_EQ(split.report.nonOrientableTriangles, 46324);
  const std::string repairs = tc::closedManifoldRepairs(split.report, options);
  EXPECT_TRUE(contains(repairs,
    "(46324 of the 46540 triangles), which no orientation fixes "
    "(most of the mesh, which DropNonOrientable would drop"))
    << repairs;
  EXPECT_FALSE(contains(repairs, "--keep-largest-component")) << repairs; // not closed

  // The scan options let it through, by dropping the body: the report says so.
  options.fillHoles = true;
  options.dropNonOrientable = true;
  options.minComponentTriangles = 5;
  options.keepLargestComponent = true;
  const tc::PreparationResult r = prepareScan(relative, options);
  EXPECT_EQ(r.report.droppedNonOrientable, 1);
  EXPECT_EQ(r.report.droppedNonOrientableTriangles, 46324);
  EXPECT_EQ(r.report.droppedSmallComponents, 144);
  EXPECT_EQ(r.report.droppedMinorComponents, 1);
  EXPECT_EQ(r.report.droppedSmallTriangles + r.report.droppedMinorTriangles +
      r.report.droppedNonOrientableTriangles + r.report.largestComponentTriangles -
      r.report.holeTriangles,
    split.report.outputTriangles);
  EXPECT_EQ(r.report.components, 1);
}

TEST(PreparationComponents, DragonVripIsOneComponentThatTheOptionsKeep)
{
  // The full scan welds into one component (its file's 151 are unwelded seams): the component
  // options change nothing, and filling its holes closes it.
  const std::string relative = "static_large/dragon_vrip.ply.gz";
  if (tctest::sharedData(relative).empty())
  {
    GTEST_SKIP() << "../shared/data/" << relative << " is absent";
  }
  tc::PreparationOptions options;
  options.fillHoles = true;
  options.dropNonOrientable = true;
  options.minComponentTriangles = 100;
  options.keepLargestComponent = true;
  const tc::PreparationResult r = prepareScan(relative, options);
  EXPECT_EQ(r.report.droppedNonOrientable + r.report.droppedSmallComponents +
      r.report.droppedMinorComponents,
    0);
  EXPECT_EQ(r.report.components, 1);
  EXPECT_EQ(r.report.filledHoles, 258);
}
