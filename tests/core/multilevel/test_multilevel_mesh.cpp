// SPDX-License-Identifier: BSD-3-Clause
// The multilevel mesh (Kircher and Garland 2005, section 3) on real meshes: level sizes, parents,
// connected clusters, the topology of M1 under the link condition, optimal positions, summed
// quadrics, determinism, bad input, progress and abort.
#include "tc/common/errors.h"
#include "tc/io/sequence_io.h"
#include "tc/multilevel/multilevel_mesh.h"

#include "analytic_meshes.h"
#include "pipeline_fixture.h"
#include "test_data.h"
#include "test_progress.h"

#include <gtest/gtest.h>

#include <chrono>
#include <cmath>
#include <cstdio>
#include <limits>
#include <string>
#include <vector>

namespace
{
tc::TriMesh bundled(const std::string& name)
{
  return tctest::loadMesh(tctest::testingData("meshes/" + name));
}

/// Meshes of ../shared/data that are present: closed manifolds of genus 0, 3 and 9.
std::vector<std::string> sharedClosedMeshes()
{
  std::vector<std::string> paths;
  for (const char* name : { "static_small/elephant.off", "cad/couplingdown.off", "cad/rotor.off" })
  {
    const std::string path = tctest::sharedData(name);
    if (!path.empty())
    {
      paths.push_back(path);
    }
  }
  return paths;
}

/// Frame 0 of a deforming sequence of ../shared/data as a triangle mesh (polygons as fans), or
/// an empty mesh when the folder is absent.
tc::TriMesh sequenceFrame0(const std::string& folder)
{
  const std::string path = tctest::sharedData("sequences/" + folder);
  tc::TriMesh mesh;
  if (path.empty() && tctest::sharedData("README.md").empty())
  {
    return mesh;
  }
  const tc::DeformingSequence sequence =
    tc::readSequence(std::string(TC_SHARED_DATA_DIR) + "/sequences/" + folder);
  mesh.points = sequence.soup.points;
  for (int64_t p = 0; p < sequence.soup.numPolygons(); ++p)
  {
    const int64_t b = sequence.soup.offsets[p], n = sequence.soup.offsets[p + 1] - b;
    for (int64_t i = 1; i + 1 < n; ++i)
    {
      for (const int64_t c : { b, b + i, b + i + 1 })
      {
        mesh.triangles.push_back(static_cast<int32_t>(sequence.soup.connectivity[c]));
      }
    }
  }
  return mesh;
}

void expectValid(const tc::TriMesh& mesh, const tc::MultilevelMesh& m, const std::string& name)
{
  const tc::MultilevelCheck check = tc::checkMultilevelMesh(mesh, m);
  EXPECT_TRUE(check.valid()) << name << ": " << check.firstProblem;
  ASSERT_EQ(check.levels.size(), m.levels.size()) << name;
  for (size_t k = 0; k < check.levels.size(); ++k)
  {
    EXPECT_EQ(check.levels[k].disconnectedClusters, 0) << name << " level " << k;
    EXPECT_EQ(check.levels[k].invalidParents, 0) << name << " level " << k;
  }
}

TEST(MultilevelMesh, VertexCountsFallByTheBranchingFactor)
{
  const tc::TriMesh bunny = bundled("bunny_npm.off");
  for (const int branching : { 8, 3, 2 })
  {
    tc::MultilevelOptions options;
    options.branchingFactor = branching;
    options.coarsestVertices = 16;
    const tc::MultilevelMesh m = tc::buildMultilevelMesh(bunny, options);
    ASSERT_GE(m.levels.size(), 3u) << branching;
    EXPECT_EQ(m.levels[0].numVertices(), bunny.numPoints());
    for (size_t k = 1; k < m.levels.size(); ++k)
    {
      const double wanted = std::round(m.levels[k - 1].numVertices() / double(branching));
      // M1 may stop short where the link condition refuses every remaining edge; above it
      // every level reaches its target on this closed, connected mesh.
      EXPECT_LE(m.levels[k].numVertices(), k == 1 ? 1.02 * wanted : wanted) << branching;
      EXPECT_GE(m.levels[k].numVertices(), wanted) << branching;
    }
    EXPECT_LT(std::round(m.levels.back().numVertices() / double(branching)), 16) << branching;
  }
}

TEST(MultilevelMesh, MaxLevelsLimitsTheHierarchy)
{
  tc::MultilevelOptions options;
  options.maxLevels = 2;
  options.coarsestVertices = 1;
  const tc::MultilevelMesh m = tc::buildMultilevelMesh(bundled("bunny_npm.off"), options);
  EXPECT_EQ(m.levels.size(), 3u);
  for (const int32_t p : m.levels.back().parents)
  {
    EXPECT_EQ(p, -1);
  }
}

TEST(MultilevelMesh, ClustersAreConnectedAndParentsValid)
{
  std::vector<std::string> paths = { tctest::testingData("meshes/bunny_npm.off"),
    tctest::testingData("meshes/fandisk.off"), tctest::testingData("meshes/cube.off") };
  for (const std::string& path : sharedClosedMeshes())
  {
    paths.push_back(path);
  }
  for (const std::string& path : paths)
  {
    const tc::TriMesh mesh = tctest::loadMesh(path);
    tc::MultilevelOptions options;
    options.coarsestVertices = 4;
    const tc::MultilevelMesh m = tc::buildMultilevelMesh(mesh, options);
    expectValid(mesh, m, path);
    for (size_t k = 0; k < m.levels.size(); ++k)
    {
      int64_t total = 0;
      for (const int32_t size : m.levels[k].clusterSizes)
      {
        EXPECT_GE(size, 1);
        total += size;
      }
      EXPECT_EQ(total, mesh.numPoints()) << path << " level " << k;
    }
  }
}

/// M0 and M1 of `mesh` have the same Euler characteristic, boundary and genus, and M1 is a
/// manifold; returns M0's genus.
int64_t expectLevelOneHomeomorphic(const tc::TriMesh& mesh, const std::string& name)
{
  const tc::MultilevelMesh m = tc::buildMultilevelMesh(mesh);
  const tc::MultilevelCheck check = tc::checkMultilevelMesh(mesh, m);
  EXPECT_TRUE(check.valid()) << name << ": " << check.firstProblem;
  EXPECT_GE(check.levels.size(), 2u) << name;
  if (check.levels.size() < 2)
  {
    return -1;
  }
  const tc::MultilevelLevelCheck& m0 = check.levels[0];
  const tc::MultilevelLevelCheck& m1 = check.levels[1];
  EXPECT_EQ(m1.nonManifoldEdges, 0) << name;
  EXPECT_EQ(m1.eulerCharacteristic, m0.eulerCharacteristic) << name;
  EXPECT_GE(m0.genus, 0) << name;
  EXPECT_EQ(m1.genus, m0.genus) << name;
  EXPECT_EQ(m1.boundaryEdges == 0, m0.boundaryEdges == 0) << name;
  return m0.genus;
}

TEST(MultilevelMesh, LinkConditionKeepsTheGenusOfLevelOne)
{
  EXPECT_EQ(expectLevelOneHomeomorphic(bundled("bunny_npm.off"), "bunny_npm"), 0);
  EXPECT_EQ(expectLevelOneHomeomorphic(bundled("fandisk.off"), "fandisk"), 0);
  const std::string elephant = tctest::sharedData("static_small/elephant.off");
  const std::string coupling = tctest::sharedData("cad/couplingdown.off");
  if (elephant.empty() || coupling.empty())
  {
    GTEST_SKIP() << "../shared/data is absent: genus 3 and 9 not checked";
  }
  EXPECT_EQ(expectLevelOneHomeomorphic(tctest::loadMesh(elephant), "elephant"), 3);
  const tc::TriMesh couplingdown = tctest::loadMesh(coupling);
  EXPECT_EQ(expectLevelOneHomeomorphic(couplingdown, "couplingdown"), 9);
  // Without the link condition the same contraction pinches this mesh's thin walls: M1 is no
  // longer a manifold of M0's Euler characteristic, which is what the condition prevents.
  tc::MultilevelOptions off;
  off.linkCondition = false;
  const tc::MultilevelCheck check =
    tc::checkMultilevelMesh(couplingdown, tc::buildMultilevelMesh(couplingdown, off));
  EXPECT_TRUE(check.valid()) << check.firstProblem;
  EXPECT_TRUE(check.levels[1].nonManifoldEdges > 0 ||
    check.levels[1].eulerCharacteristic != check.levels[0].eulerCharacteristic);
}

TEST(MultilevelMesh, LinkConditionKeepsTheBoundariesOfAnOpenMesh)
{
  const tc::TriMesh frankie = sequenceFrame0("frankie_run_19f");
  if (frankie.numTriangles() == 0)
  {
    GTEST_SKIP() << "../shared/data/sequences is absent";
  }
  expectLevelOneHomeomorphic(frankie, "frankie_run_19f frame 0");
}

/// Every vertex of every level above M0 is where its cluster's quadric is lowest among its own
/// position and those of the cluster's M0 vertices; returns how many were placed as singular.
int64_t expectPositionsMinimize(const tc::TriMesh& mesh, const std::string& name)
{
  tc::MultilevelOptions options;
  options.coarsestVertices = 4;
  const tc::MultilevelMesh m = tc::buildMultilevelMesh(mesh, options);
  int64_t singular = 0;
  for (size_t k = 1; k < m.levels.size(); ++k)
  {
    const tc::MultilevelLevel& level = m.levels[k];
    const std::vector<int32_t> cluster = m.clusterOf(static_cast<int>(k));
    for (int64_t a = 0; a < level.numVertices(); ++a)
    {
      EXPECT_NEAR(level.errors[a],
        tc::evaluateQuadric(&level.quadrics[10 * a], &level.points[3 * a]),
        1e-12 * (1 + level.errors[a]));
      singular += level.placements[a] != tc::Placement::Optimal;
    }
    for (int64_t v = 0; v < mesh.numPoints(); ++v)
    {
      const int32_t a = cluster[v];
      const double* q = &level.quadrics[10 * a];
      const double* p = &mesh.points[3 * v];
      const double atVertex = tc::evaluateQuadric(q, p);
      // Round-off of the evaluation: relative to the error, and to the size of its terms
      // (p^T A p), which matters where the minimum is 0 (a flat cluster).
      const double terms = (q[0] + q[3] + q[5]) * (1 + p[0] * p[0] + p[1] * p[1] + p[2] * p[2]);
      EXPECT_LE(level.errors[a], atVertex * (1 + 1e-9) + 1e-14 * terms)
        << name << " level " << k << " vertex " << a << " placement " << int(level.placements[a]);
    }
  }
  return singular;
}

TEST(MultilevelMesh, PositionsMinimizeTheClusterQuadric)
{
  expectPositionsMinimize(bundled("bunny_npm.off"), "bunny_npm");
  // Flat faces: quadrics of one plane are singular, and take the fallback.
  EXPECT_GT(expectPositionsMinimize(bundled("fandisk.off"), "fandisk"), 0);
  const tc::TriMesh frankie = sequenceFrame0("frankie_run_19f");
  if (frankie.numTriangles() > 0)
  {
    expectPositionsMinimize(frankie, "frankie_run_19f frame 0");
  }
}

TEST(MultilevelMesh, QuadricsAreSumsOverTheClusters)
{
  const tc::TriMesh fandisk = bundled("fandisk.off");
  const tc::MultilevelMesh m = tc::buildMultilevelMesh(fandisk);
  ASSERT_GE(m.levels.size(), 3u);
  const tc::MultilevelLevel& m0 = m.levels[0];
  for (size_t k = 1; k < m.levels.size(); ++k)
  {
    const tc::MultilevelLevel& level = m.levels[k];
    std::vector<double> sums(level.quadrics.size(), 0.0), scale(level.quadrics.size(), 0.0);
    const std::vector<int32_t> cluster = m.clusterOf(static_cast<int>(k));
    for (int64_t v = 0; v < fandisk.numPoints(); ++v)
    {
      for (int i = 0; i < 10; ++i)
      {
        sums[10 * cluster[v] + i] += m0.quadrics[10 * v + i];
        scale[10 * cluster[v] + i] += std::abs(m0.quadrics[10 * v + i]);
      }
    }
    for (size_t i = 0; i < sums.size(); ++i)
    {
      EXPECT_NEAR(level.quadrics[i], sums[i], 1e-12 * scale[i] + 1e-300) << "level " << k;
    }
  }
  // The faces of M0 carry area-weighted planes: every vertex quadric of a closed mesh has a
  // positive-definite part only where its faces are not all coplanar, but always A's trace > 0.
  for (int64_t v = 0; v < fandisk.numPoints(); ++v)
  {
    EXPECT_GT(m0.quadrics[10 * v] + m0.quadrics[10 * v + 3] + m0.quadrics[10 * v + 5], 0.0);
  }
}

TEST(MultilevelMesh, LevelFacesAreDerivedFromM0WithoutDuplicates)
{
  const tc::TriMesh bunny = bundled("bunny_npm.off");
  const tc::MultilevelMesh m = tc::buildMultilevelMesh(bunny);
  for (size_t k = 1; k < m.levels.size(); ++k)
  {
    const tc::MultilevelLevel& level = m.levels[k];
    const std::vector<int32_t> cluster = m.clusterOf(static_cast<int>(k));
    std::vector<std::array<int32_t, 3>> keys;
    ASSERT_EQ(level.sourceFaces.size(), static_cast<size_t>(level.numTriangles()));
    for (int64_t t = 0; t < level.numTriangles(); ++t)
    {
      std::array<int32_t, 3> key;
      for (int i = 0; i < 3; ++i)
      {
        key[i] = level.triangles[3 * t + i];
        EXPECT_EQ(key[i], cluster[bunny.triangles[3 * level.sourceFaces[t] + i]]);
      }
      std::sort(key.begin(), key.end());
      EXPECT_TRUE(key[0] != key[1] && key[1] != key[2]);
      keys.push_back(key);
    }
    std::sort(keys.begin(), keys.end());
    EXPECT_EQ(std::unique(keys.begin(), keys.end()), keys.end()) << "level " << k;
  }
}

TEST(MultilevelMesh, TwoRunsAreEqual)
{
  const tc::TriMesh fandisk = bundled("fandisk.off");
  const tc::MultilevelMesh a = tc::buildMultilevelMesh(fandisk);
  const tc::MultilevelMesh b = tc::buildMultilevelMesh(fandisk);
  ASSERT_EQ(a.levels.size(), b.levels.size());
  for (size_t k = 0; k < a.levels.size(); ++k)
  {
    EXPECT_EQ(a.levels[k].points, b.levels[k].points);
    EXPECT_EQ(a.levels[k].parents, b.levels[k].parents);
    EXPECT_EQ(a.levels[k].triangles, b.levels[k].triangles);
    EXPECT_EQ(a.levels[k].quadrics, b.levels[k].quadrics);
  }
}

TEST(MultilevelMesh, BadInputIsRefused)
{
  const tc::TriMesh bunny = bundled("bunny_npm.off");
  EXPECT_THROW(tc::buildMultilevelMesh(tc::TriMesh{}), tc::InputError);
  tc::TriMesh nan = bunny;
  nan.points[7] = std::numeric_limits<double>::quiet_NaN();
  EXPECT_THROW(tc::buildMultilevelMesh(nan), tc::InputError);
  tc::MultilevelOptions one;
  one.branchingFactor = 1;
  EXPECT_THROW(tc::buildMultilevelMesh(bunny, one), tc::InputError);
  tc::TriMesh outOfRange = bunny;
  outOfRange.triangles[5] = static_cast<int32_t>(bunny.numPoints());
  EXPECT_THROW(tc::buildMultilevelMesh(outOfRange), tc::InputError);
  tc::TriMesh repeated = bunny;
  repeated.triangles[1] = repeated.triangles[0];
  EXPECT_THROW(tc::buildMultilevelMesh(repeated), tc::InputError);
  try
  {
    tc::buildMultilevelMesh(bunny, one);
  }
  catch (const tc::InputError& e)
  {
    EXPECT_NE(std::string(e.what()).find("at least 2"), std::string::npos) << e.what();
  }
}

/// Two icospheres sharing one vertex: a non-manifold vertex.
tc::TriMesh pinchedSpheres()
{
  const tc::TriMesh sphere = tctest::icosphere(1.0, 3).mesh;
  tc::TriMesh mesh = sphere;
  const int32_t n = static_cast<int32_t>(sphere.numPoints());
  for (int32_t v = 0; v < n; ++v)
  {
    mesh.points.push_back(sphere.points[3 * v] + 2.0);
    mesh.points.push_back(sphere.points[3 * v + 1]);
    mesh.points.push_back(sphere.points[3 * v + 2]);
  }
  // Vertex 0 of the second sphere is vertex 0 of the first, moved onto it.
  for (const int32_t id : sphere.triangles)
  {
    mesh.triangles.push_back(id == 0 ? 0 : id + n);
  }
  return mesh;
}

TEST(MultilevelMesh, NonManifoldInputNeedsTheLinkConditionOff)
{
  const tc::TriMesh pinched = pinchedSpheres();
  EXPECT_THROW(tc::buildMultilevelMesh(pinched), tc::InputError);
  tc::MultilevelOptions options;
  options.linkCondition = false;
  options.coarsestVertices = 2;
  const tc::MultilevelMesh m = tc::buildMultilevelMesh(pinched, options);
  expectValid(pinched, m, "pinched spheres");
  EXPECT_GE(m.levels.size(), 3u);
}

TEST(MultilevelMesh, ReportsProgressAndAborts)
{
  const tc::TriMesh bunny = bundled("bunny_npm.off");
  tctest::expectProgressAndAbort([&](const tc::Progress& progress)
    { tc::buildMultilevelMesh(bunny, {}, progress); },
    10, [](double f) { return f < 0.3; });
}

/// Level sizes and times of the first frames of the two deforming sequences of ../shared/data.
TEST(MultilevelMesh, SequenceFirstFrames)
{
  for (const char* folder : { "snake_closed_21f", "frankie_run_19f" })
  {
    const tc::TriMesh mesh = sequenceFrame0(folder);
    if (mesh.numTriangles() == 0)
    {
      GTEST_SKIP() << "../shared/data/sequences is absent";
    }
    const auto start = std::chrono::steady_clock::now();
    const tc::MultilevelMesh m = tc::buildMultilevelMesh(mesh);
    const double ms =
      std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
    std::string sizes;
    for (const tc::MultilevelLevel& level : m.levels)
    {
      sizes += " " + std::to_string(level.numVertices()) + "v/" +
        std::to_string(level.numTriangles()) + "f";
    }
    std::printf("[ multilevel ] %s frame 0:%s in %.1f ms\n", folder, sizes.c_str(), ms);
    expectValid(mesh, m, folder);
    EXPECT_GE(m.levels.size(), 3u) << folder;
  }
}
} // namespace
