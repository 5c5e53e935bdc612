// SPDX-License-Identifier: BSD-3-Clause
#include "tc/features/spectral_clustering.h"

#include "tc/features/crest_lines.h"
#include "tc/features/curvature.h"
#include "tc/common/errors.h"
#include "tc/prep/mesh_preparation.h"
#include "tc/common/mesh_topology.h"
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
#include <map>
#include <numeric>
#include <set>
#include <string>
#include <vector>

namespace
{
/// A mesh with the inputs spectralClustering() takes, computed as the pipeline does.
struct Prepared
{
  tc::TriMesh mesh;
  std::vector<double> faceMean;
  std::vector<uint8_t> crest;
};

Prepared prepare(const tc::TriMesh& mesh)
{
  Prepared p;
  p.mesh = mesh;
  const tc::CurvatureResult curvature = tc::computeCurvature(mesh);
  p.faceMean = curvature.faceMean;
  p.crest = tc::crestVertices(mesh, tc::extractCrestLines(mesh, curvature));
  return p;
}

Prepared prepareFile(const std::string& path)
{
  tc::PreparationResult prepared = tc::prepareMesh(tc::readOFF(path));
  return prepare(prepared.mesh);
}

tc::SpectralClusteringResult cluster(const Prepared& p, const tc::SpectralClusteringOptions& o)
{
  return tc::spectralClustering(p.mesh, p.faceMean, p.crest, o);
}

/// Appends `b` to `a` (vertex ids shifted), keeping both as separate components.
tc::TriMesh merged(const tc::TriMesh& a, const tc::TriMesh& b)
{
  tc::TriMesh m = a;
  const int32_t shift = static_cast<int32_t>(a.numPoints());
  m.points.insert(m.points.end(), b.points.begin(), b.points.end());
  for (int32_t v : b.triangles)
  {
    m.triangles.push_back(v + shift);
  }
  return m;
}

tc::TriMesh translated(tc::TriMesh m, double dx, double dy, double dz)
{
  for (int64_t v = 0; v < m.numPoints(); ++v)
  {
    m.points[3 * v] += dx;
    m.points[3 * v + 1] += dy;
    m.points[3 * v + 2] += dz;
  }
  return m;
}

/// Side of the cube [-a, a]^3 that face f lies on: 2 * axis + (normal points to +).
int cubeSide(const tc::TriMesh& mesh, int64_t f)
{
  double c[3] = { 0, 0, 0 };
  for (int i = 0; i < 3; ++i)
  {
    for (int d = 0; d < 3; ++d)
    {
      c[d] += mesh.points[3 * mesh.triangles[3 * f + i] + d] / 3.0;
    }
  }
  int axis = 0;
  for (int d = 1; d < 3; ++d)
  {
    if (std::abs(c[d]) > std::abs(c[axis]))
    {
      axis = d;
    }
  }
  return 2 * axis + (c[axis] > 0 ? 1 : 0);
}

/// Edge-connected pieces of the clusters: for every cluster, the face count of each piece.
std::vector<std::vector<int64_t>> clusterPieces(
  const tc::TriMesh& mesh, const std::vector<int32_t>& clusterId, int numClusters)
{
  const tc::EdgeTable edges = tc::buildEdgeTable(mesh.triangles);
  const int64_t nf = mesh.numTriangles();
  std::vector<int32_t> parent(nf);
  std::iota(parent.begin(), parent.end(), 0);
  auto find = [&](int32_t x)
  {
    while (parent[x] != x)
    {
      x = parent[x] = parent[parent[x]];
    }
    return x;
  };
  for (int64_t e = 0; e < edges.numEdges(); ++e)
  {
    for (int64_t i = edges.faceOffsets[e] + 1; i < edges.faceOffsets[e + 1]; ++i)
    {
      const int32_t a = edges.edgeFaces[edges.faceOffsets[e]], b = edges.edgeFaces[i];
      if (clusterId[a] == clusterId[b])
      {
        parent[find(a)] = find(b);
      }
    }
  }
  std::map<int32_t, int64_t> size;
  for (int64_t f = 0; f < nf; ++f)
  {
    ++size[find(static_cast<int32_t>(f))];
  }
  std::vector<std::vector<int64_t>> pieces(numClusters);
  for (const auto& [root, count] : size)
  {
    pieces[clusterId[root]].push_back(count);
  }
  return pieces;
}

/// Every face has an id in [0, numClusters), every id is used, ids follow the first faces.
void expectValidClusters(const tc::SpectralClusteringResult& r, int64_t numFaces)
{
  ASSERT_EQ(static_cast<int64_t>(r.clusterId.size()), numFaces);
  ASSERT_GT(r.numClusters, 0);
  std::vector<int64_t> count(r.numClusters, 0);
  int32_t nextNew = 0;
  for (int32_t id : r.clusterId)
  {
    ASSERT_GE(id, 0);
    ASSERT_LT(id, r.numClusters);
    if (count[id]++ == 0)
    {
      EXPECT_EQ(id, nextNew) << "clusters are numbered in the order of their first face";
      ++nextNew;
    }
  }
  for (int32_t c = 0; c < r.numClusters; ++c)
  {
    EXPECT_GT(count[c], 0) << "cluster " << c << " is empty";
  }
}

/// The cube [-1, 1]^3 with an n x n grid on each side.
Prepared subdividedCube(int n)
{
  return prepare(tctest::roundedBox(1.0, 0.0, n).mesh);
}

/// Fraction of the 6 cube sides whose faces are (up to `band` of them) one cluster that holds
/// no face of another side, again up to `band`.
void expectCubeSidesSeparated(
  const Prepared& cube, const tc::SpectralClusteringResult& r, double band)
{
  ASSERT_EQ(r.numClusters, 6);
  const int64_t nf = cube.mesh.numTriangles();
  std::vector<std::vector<int64_t>> table(6, std::vector<int64_t>(6, 0)); // side x cluster
  for (int64_t f = 0; f < nf; ++f)
  {
    ++table[cubeSide(cube.mesh, f)][r.clusterId[f]];
  }
  std::set<int> clustersUsed;
  for (int side = 0; side < 6; ++side)
  {
    const auto& row = table[side];
    const int best = static_cast<int>(std::max_element(row.begin(), row.end()) - row.begin());
    const int64_t sideFaces = std::accumulate(row.begin(), row.end(), int64_t(0));
    int64_t clusterFaces = 0;
    for (int s = 0; s < 6; ++s)
    {
      clusterFaces += table[s][best];
    }
    EXPECT_GE(row[best], (1.0 - band) * sideFaces) << "side " << side << " is split";
    EXPECT_GE(row[best], (1.0 - band) * clusterFaces) << "cluster " << best << " spans sides";
    clustersUsed.insert(best);
  }
  EXPECT_EQ(clustersUsed.size(), 6u) << "two sides share their main cluster";
}
} // namespace

TEST(SpectralClustering, DeterministicAcrossRunsAndThreadCounts)
{
  const Prepared bunny = prepareFile(tctest::testingData("meshes/bunny_npm.off"));
  tc::SpectralClusteringOptions o;
  o.numClusters = 10;
  const tc::SpectralClusteringResult a = cluster(bunny, o);
  const tc::SpectralClusteringResult b = cluster(bunny, o);
  EXPECT_EQ(a.clusterId, b.clusterId);
  EXPECT_EQ(a.eigenvalues, b.eigenvalues);
  {
    tbb::global_control one(tbb::global_control::max_allowed_parallelism, 1);
    const tc::SpectralClusteringResult c = cluster(bunny, o);
    EXPECT_EQ(a.clusterId, c.clusterId);
  }
  // Another seed is another k-means start: still a valid clustering.
  o.seed = 12345;
  const tc::SpectralClusteringResult d = cluster(bunny, o);
  expectValidClusters(d, bunny.mesh.numTriangles());
  EXPECT_EQ(d.numClusters, 10);
}

TEST(SpectralClustering, NystromIsDeterministicAcrossThreadCounts)
{
  const Prepared bunny = prepareFile(tctest::testingData("meshes/bunny_npm.off"));
  tc::SpectralClusteringOptions o;
  o.numClusters = 8;
  o.nystromThreshold = 1000;
  o.nystromSamples = 300;
  o.kmeansSampleSize = 1000;
  const tc::SpectralClusteringResult a = cluster(bunny, o);
  ASSERT_TRUE(a.usedNystrom);
  tbb::global_control one(tbb::global_control::max_allowed_parallelism, 1);
  const tc::SpectralClusteringResult b = cluster(bunny, o);
  EXPECT_EQ(a.clusterId, b.clusterId);
  EXPECT_EQ(a.eigenvalues, b.eigenvalues);
}

TEST(SpectralClustering, EveryFaceGetsOneOfTheRequestedClusters)
{
  for (const char* file : { "meshes/bunny_npm.off", "meshes/fandisk.off" })
  {
    SCOPED_TRACE(file);
    const Prepared p = prepareFile(tctest::testingData(file));
    for (int k : { 2, 7, 16 })
    {
      tc::SpectralClusteringOptions o;
      o.numClusters = k;
      const tc::SpectralClusteringResult r = cluster(p, o);
      expectValidClusters(r, p.mesh.numTriangles());
      EXPECT_EQ(r.numClusters, k);
      EXPECT_FALSE(r.usedNystrom);
      ASSERT_EQ(static_cast<int>(r.eigenvalues.size()), k);
      EXPECT_NEAR(r.eigenvalues.front(), 1.0, 1e-9) << "D^1/2 1 has eigenvalue 1";
      for (size_t i = 0; i < r.eigenvalues.size(); ++i)
      {
        EXPECT_LE(r.eigenvalues[i], 1.0 + 1e-9);
        EXPECT_GT(r.eigenvalues[i], -1.0 - 1e-9);
        if (i > 0)
        {
          EXPECT_LE(r.eigenvalues[i], r.eigenvalues[i - 1]) << "not descending at " << i;
        }
      }
    }
  }
}

TEST(SpectralClustering, NumEigenvectorsSetsTheEmbeddingSize)
{
  const Prepared p = prepareFile(tctest::testingData("meshes/fandisk.off"));
  tc::SpectralClusteringOptions o;
  o.numClusters = 6;
  o.numEigenvectors = 10;
  const tc::SpectralClusteringResult r = cluster(p, o);
  EXPECT_EQ(r.eigenvalues.size(), 10u);
  EXPECT_EQ(r.numClusters, 6);
}

TEST(SpectralClustering, CubeSidesBecomeTheSixClusters)
{
  const Prepared cube = subdividedCube(10);
  tc::SpectralClusteringOptions o;
  o.numClusters = 6;
  const tc::SpectralClusteringResult r = cluster(cube, o);
  EXPECT_FALSE(r.usedNystrom);
  expectCubeSidesSeparated(cube, r, 0.0);
}

TEST(SpectralClustering, NystromKeepsCubeSidesApart)
{
  const Prepared cube = subdividedCube(24);
  tc::SpectralClusteringOptions o;
  o.numClusters = 6;
  o.nystromThreshold = 2000;
  o.nystromSamples = 400;
  const tc::SpectralClusteringResult r = cluster(cube, o);
  EXPECT_TRUE(r.usedNystrom);
  expectValidClusters(r, cube.mesh.numTriangles());
  // The Euclidean kernel sees no crest line; allow a band of 2% of the faces along the edges.
  expectCubeSidesSeparated(cube, r, 0.02);
}

TEST(SpectralClustering, NystromClustersAreSpatiallyCoherent)
{
  const Prepared bunny = prepareFile(tctest::testingData("meshes/bunny_npm.off"));
  tc::SpectralClusteringOptions o;
  o.numClusters = 12;
  o.nystromThreshold = 1000;
  o.nystromSamples = 400;
  o.connectedClusters = false; // judge the embedding itself, not the clean-up
  const tc::SpectralClusteringResult r = cluster(bunny, o);
  ASSERT_TRUE(r.usedNystrom);
  expectValidClusters(r, bunny.mesh.numTriangles());
  EXPECT_EQ(r.numClusters, 12);
  // Compact regions: few adjacent faces lie in different clusters (a random labelling would
  // split 11 of 12 pairs; 12 round regions of ~300 faces split about 1 in 15).
  const tc::EdgeTable edges = tc::buildEdgeTable(bunny.mesh.triangles);
  int64_t pairs = 0, split = 0;
  for (int64_t e = 0; e < edges.numEdges(); ++e)
  {
    if (edges.valence(e) == 2)
    {
      ++pairs;
      split += r.clusterId[edges.edgeFaces[edges.faceOffsets[e]]] !=
        r.clusterId[edges.edgeFaces[edges.faceOffsets[e] + 1]];
    }
  }
  EXPECT_LT(split, pairs / 8) << split << " of " << pairs << " adjacent pairs are split";
  // And most faces lie in the largest piece of their cluster (the Euclidean kernel joins the
  // two ear tips, a few faces apart in space; the clean-up of connectedClusters handles them).
  int64_t inLargest = 0;
  for (const std::vector<int64_t>& sizes : clusterPieces(bunny.mesh, r.clusterId, r.numClusters))
  {
    inLargest += *std::max_element(sizes.begin(), sizes.end());
  }
  EXPECT_GE(inLargest, 0.75 * bunny.mesh.numTriangles());
}

TEST(SpectralClustering, ConnectedClustersLeavesOnePiecePerCluster)
{
  const Prepared bunny = prepareFile(tctest::testingData("meshes/bunny_npm.off"));
  for (int64_t threshold : { int64_t(1000), int64_t(100000) })
  {
    SCOPED_TRACE(threshold);
    tc::SpectralClusteringOptions o;
    o.numClusters = 14;
    o.nystromThreshold = threshold;
    o.nystromSamples = 300;
    const tc::SpectralClusteringResult r = cluster(bunny, o);
    expectValidClusters(r, bunny.mesh.numTriangles());
    EXPECT_EQ(r.numClusters, 14);
    for (const std::vector<int64_t>& sizes : clusterPieces(bunny.mesh, r.clusterId, r.numClusters))
    {
      EXPECT_EQ(sizes.size(), 1u);
    }
  }
}

/// The model of Fig. 5 of Feng et al.: a plane with a narrow ridge and a hemisphere. The ridge
/// (a tent of half-width 3 grid cells) runs along the grid column x = -0.35.
TEST(SpectralClustering, ClusterBoundaryFollowsTheRidgeOfFigure5)
{
  constexpr double ridgeX = -0.35, ridgeWidth = 0.075, ridgeHeight = 0.1;
  constexpr double radius = 0.35, centerX = 0.4;
  const tctest::AnalyticMesh model = tctest::heightField(
    [&](double x, double y)
    {
      tctest::HeightSample s;
      s.f = ridgeHeight * std::max(0.0, 1.0 - std::abs(x - ridgeX) / ridgeWidth);
      const double d2 = (x - centerX) * (x - centerX) + y * y;
      s.f += d2 < radius * radius ? std::sqrt(radius * radius - d2) : 0.0;
      return s;
    },
    -1, 1, -1, 1, 81, 81);
  const Prepared p = prepare(model.mesh);
  tc::SpectralClusteringOptions o;
  o.numClusters = 3;
  const tc::SpectralClusteringResult r = cluster(p, o);
  ASSERT_EQ(r.numClusters, 3);

  // Mesh edges along the crest of the ridge: faces on their two sides in different clusters.
  const tc::EdgeTable edges = tc::buildEdgeTable(p.mesh.triangles);
  int crestEdges = 0, separating = 0;
  for (int64_t e = 0; e < edges.numEdges(); ++e)
  {
    const double xa = p.mesh.points[3 * edges.vertices[2 * e]];
    const double xb = p.mesh.points[3 * edges.vertices[2 * e + 1]];
    if (std::abs(xa - ridgeX) < 1e-9 && std::abs(xb - ridgeX) < 1e-9 && edges.valence(e) == 2)
    {
      ++crestEdges;
      separating += r.clusterId[edges.edgeFaces[edges.faceOffsets[e]]] !=
        r.clusterId[edges.edgeFaces[edges.faceOffsets[e] + 1]];
    }
  }
  ASSERT_EQ(crestEdges, 80);
  EXPECT_GE(separating, 76) << "a cluster boundary should run along the ridge";

  // Unlike VSA (Fig. 5, left), the hemisphere is not divided.
  std::map<int32_t, int> onDome;
  int domeFaces = 0;
  for (int64_t f = 0; f < p.mesh.numTriangles(); ++f)
  {
    double cx = 0, cy = 0;
    for (int i = 0; i < 3; ++i)
    {
      cx += p.mesh.points[3 * p.mesh.triangles[3 * f + i]] / 3;
      cy += p.mesh.points[3 * p.mesh.triangles[3 * f + i] + 1] / 3;
    }
    if ((cx - centerX) * (cx - centerX) + cy * cy < 0.8 * 0.8 * radius * radius)
    {
      ++domeFaces;
      ++onDome[r.clusterId[f]];
    }
  }
  int largest = 0;
  for (const auto& [id, count] : onDome)
  {
    largest = std::max(largest, count);
  }
  EXPECT_GE(largest, 0.95 * domeFaces) << "the hemisphere is split between clusters";
}

/// Fraction of the mesh edges whose faces meet at more than 45 degrees that separate two
/// clusters.
double sharpEdgesOnBoundaries(const tc::TriMesh& mesh, const std::vector<int32_t>& clusterId)
{
  auto normal = [&](int32_t f)
  {
    const int32_t* t = &mesh.triangles[3 * f];
    double u[3], v[3];
    for (int c = 0; c < 3; ++c)
    {
      u[c] = mesh.points[3 * t[1] + c] - mesh.points[3 * t[0] + c];
      v[c] = mesh.points[3 * t[2] + c] - mesh.points[3 * t[0] + c];
    }
    std::array<double, 3> n = { u[1] * v[2] - u[2] * v[1], u[2] * v[0] - u[0] * v[2],
      u[0] * v[1] - u[1] * v[0] };
    const double l = std::sqrt(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]);
    for (double& x : n)
    {
      x /= l;
    }
    return n;
  };
  const tc::EdgeTable edges = tc::buildEdgeTable(mesh.triangles);
  int sharp = 0, separating = 0;
  for (int64_t e = 0; e < edges.numEdges(); ++e)
  {
    if (edges.valence(e) != 2)
    {
      continue;
    }
    const int32_t f = edges.edgeFaces[edges.faceOffsets[e]];
    const int32_t g = edges.edgeFaces[edges.faceOffsets[e] + 1];
    const auto a = normal(f), b = normal(g);
    if (a[0] * b[0] + a[1] * b[1] + a[2] * b[2] < std::cos(M_PI / 4))
    {
      ++sharp;
      separating += clusterId[f] != clusterId[g] ? 1 : 0;
    }
  }
  return sharp > 0 ? static_cast<double>(separating) / sharp : 1.0;
}

TEST(SpectralClustering, NormalTermPutsFandiskBoundariesOnSharpEdges)
{
  const Prepared p = prepareFile(tctest::testingData("meshes/fandisk.off"));
  tc::SpectralClusteringOptions o;
  o.numClusters = 24;
  const double paper = sharpEdgesOnBoundaries(p.mesh, cluster(p, o).clusterId);
  o.exactNormalSigma = 0.05;
  const double withNormals = sharpEdgesOnBoundaries(p.mesh, cluster(p, o).clusterId);
  std::printf("fandisk, sharp edges on cluster boundaries: %.3f (eq. 3), %.3f (normal term)\n",
    paper, withNormals);
  EXPECT_GE(withNormals, 0.97);
  EXPECT_GT(withNormals, paper);
  o.exactNormalSigma = -1.0;
  EXPECT_THROW(cluster(p, o), tc::InputError);
}

TEST(SpectralClustering, SeparateComponentsGetTheirOwnClusters)
{
  const tc::TriMesh big = tctest::icosphere(1.0, 3).mesh;   // 1280 faces
  const tc::TriMesh small = tctest::icosphere(0.5, 2).mesh; // 320 faces
  const Prepared p = prepare(merged(big, translated(small, 4.0, 0.0, 0.0)));
  const int64_t bigFaces = big.numTriangles();
  for (int k : { 2, 5, 10 })
  {
    SCOPED_TRACE(k);
    tc::SpectralClusteringOptions o;
    o.numClusters = k;
    const tc::SpectralClusteringResult r = cluster(p, o);
    expectValidClusters(r, p.mesh.numTriangles());
    EXPECT_EQ(r.numClusters, k);
    std::set<int32_t> onBig, onSmall;
    for (int64_t f = 0; f < p.mesh.numTriangles(); ++f)
    {
      (f < bigFaces ? onBig : onSmall).insert(r.clusterId[f]);
    }
    for (int32_t id : onBig)
    {
      EXPECT_EQ(onSmall.count(id), 0u) << "cluster " << id << " spans both spheres";
    }
    // Clusters in proportion to the face counts (4:1).
    EXPECT_EQ(static_cast<int>(onSmall.size()), std::max(1, k / 5));
    EXPECT_EQ(static_cast<int>(onBig.size()), k - std::max(1, k / 5));
  }
}

TEST(SpectralClustering, TinyComponentGetsOneClusterOfItsOwn)
{
  tc::TriMesh mesh = tctest::icosphere(1.0, 3).mesh;
  const int32_t v = static_cast<int32_t>(mesh.numPoints());
  mesh.points.insert(mesh.points.end(), { 5, 0, 0, 6, 0, 0, 5, 1, 0 });
  mesh.triangles.insert(mesh.triangles.end(), { v, v + 1, v + 2 });
  const Prepared p = prepare(mesh);
  tc::SpectralClusteringOptions o;
  o.numClusters = 6;
  const tc::SpectralClusteringResult r = cluster(p, o);
  expectValidClusters(r, p.mesh.numTriangles());
  EXPECT_EQ(r.numClusters, 6) << "the triangle's cluster is taken from the sphere's share";
  const int32_t lonely = r.clusterId.back();
  EXPECT_EQ(std::count(r.clusterId.begin(), r.clusterId.end(), lonely), 1);
}

TEST(SpectralClustering, FewerFacesThanClustersIsAnInputError)
{
  const Prepared cube = prepareFile(tctest::testingData("meshes/cube.off"));
  const int64_t faces = cube.mesh.numTriangles();
  tc::SpectralClusteringOptions o;
  o.numClusters = static_cast<int>(faces) + 1;
  try
  {
    cluster(cube, o);
    FAIL() << "expected tc::InputError";
  }
  catch (const tc::InputError& e)
  {
    const std::string what = e.what();
    EXPECT_NE(what.find(std::to_string(faces) + " faces"), std::string::npos) << what;
    EXPECT_NE(what.find(std::to_string(faces + 1) + " clusters"), std::string::npos) << what;
    EXPECT_NE(what.find("numClusters"), std::string::npos) << what;
  }
  o.numClusters = static_cast<int>(faces);
  const tc::SpectralClusteringResult r = cluster(cube, o);
  EXPECT_EQ(r.numClusters, faces) << "one face per cluster is still possible";
}

TEST(SpectralClustering, MismatchedInputsAreInputErrors)
{
  const Prepared cube = subdividedCube(4);
  std::vector<double> shortCurvature(cube.faceMean.begin(), cube.faceMean.end() - 1);
  EXPECT_THROW(tc::spectralClustering(cube.mesh, shortCurvature, cube.crest), tc::InputError);
  std::vector<uint8_t> shortCrest(3, 0);
  EXPECT_THROW(tc::spectralClustering(cube.mesh, cube.faceMean, shortCrest), tc::InputError);
  std::vector<double> nanCurvature = cube.faceMean;
  nanCurvature[5] = std::nan("");
  EXPECT_THROW(tc::spectralClustering(cube.mesh, nanCurvature, cube.crest), tc::InputError);
  tc::SpectralClusteringOptions o;
  o.numClusters = 0;
  EXPECT_THROW(tc::spectralClustering(cube.mesh, cube.faceMean, cube.crest, o), tc::InputError);
  // No crest input at all is allowed.
  o.numClusters = 6;
  EXPECT_NO_THROW(tc::spectralClustering(cube.mesh, cube.faceMean, {}, o));
}

TEST(SpectralClustering, FlatPlaneHasNoNaN)
{
  // Zero curvature everywhere: sigma_k = 0.
  const tc::TriMesh plane = tctest::plane(2.0, 30).mesh;
  const std::vector<double> zero(plane.numTriangles(), 0.0);
  for (double extra : { 2.0, 0.0 })
  {
    tc::SpectralClusteringOptions o;
    o.numClusters = 4;
    o.extraEdgeFactor = extra;
    const tc::SpectralClusteringResult r = tc::spectralClustering(plane, zero, {}, o);
    expectValidClusters(r, plane.numTriangles());
    EXPECT_EQ(r.numClusters, 4);
    for (double e : r.eigenvalues)
    {
      EXPECT_TRUE(std::isfinite(e));
    }
    o.nystromThreshold = 100;
    o.nystromSamples = 100;
    const tc::SpectralClusteringResult n = tc::spectralClustering(plane, zero, {}, o);
    EXPECT_TRUE(n.usedNystrom);
    expectValidClusters(n, plane.numTriangles());
    for (double e : n.eigenvalues)
    {
      EXPECT_TRUE(std::isfinite(e));
    }
  }
  // Two faces, one dual edge: sigma_d = 0 as well.
  tc::TriMesh square;
  square.points = { 0, 0, 0, 1, 0, 0, 1, 1, 0, 0, 1, 0 };
  square.triangles = { 0, 1, 2, 0, 2, 3 };
  tc::SpectralClusteringOptions o;
  o.numClusters = 2;
  const tc::SpectralClusteringResult r = tc::spectralClustering(square, { 0.0, 0.0 }, {}, o);
  EXPECT_EQ(r.clusterId, (std::vector<int32_t>{ 0, 1 }));
}

TEST(SpectralClustering, ReportsProgressAndHonoursAbort)
{
  const Prepared bunny = prepareFile(tctest::testingData("meshes/bunny_npm.off"));
  for (int64_t threshold : { int64_t(1000), int64_t(100000) })
  {
    SCOPED_TRACE(threshold);
    tc::SpectralClusteringOptions o;
    o.nystromThreshold = threshold;
    tctest::expectProgressAndAbort([&](const tc::Progress& p)
      { tc::spectralClustering(bunny.mesh, bunny.faceMean, bunny.crest, o, p); },
      4, [calls = 0](double) mutable { return ++calls < 3; });
  }
}

TEST(SpectralClustering, LargerSharedMeshesGiveValidClusters)
{
  const std::string path = tctest::sharedData("static_medium/armadillo.off");
  if (path.empty())
  {
    GTEST_SKIP() << "shared data not found";
  }
  const Prepared p = prepareFile(path);
  tc::SpectralClusteringOptions o;
  const tc::SpectralClusteringResult r = cluster(p, o);
  EXPECT_FALSE(r.usedNystrom) << "52K faces are below the default Nystrom threshold";
  expectValidClusters(r, p.mesh.numTriangles());
  EXPECT_EQ(r.numClusters, o.numClusters);
}
