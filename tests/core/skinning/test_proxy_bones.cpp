// SPDX-License-Identifier: BSD-3-Clause
#include "tc/common/errors.h"
#include "tc/common/mesh_topology.h"
#include "tc/io/scene_io.h"
#include "tc/io/sequence_io.h"
#include "tc/skinning/deformation_clustering.h"
#include "tc/skinning/proxy_bones.h"
#include "tc/skinning/skin.h"

#include "analytic_meshes.h"
#include "skin_fixtures.h"
#include "test_data.h"
#include "test_progress.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <set>
#include <string>
#include <vector>

namespace
{
/// A cylinder along z (radius 0.2, height 2) whose upper half (z > 0) turns rigidly about the x
/// axis through the origin, by `maxDegrees` over `numFrames` frames (frame 0 straight): two
/// rigid parts and a joint between them.
struct BendingCylinder
{
  std::vector<int32_t> triangles;
  std::vector<std::vector<float>> frames;

  explicit BendingCylinder(int numFrames = 8, double maxDegrees = 90.0)
  {
    const tc::TriMesh mesh = tctest::cylinder(0.2, 2.0, 16, 21).mesh;
    triangles = mesh.triangles;
    for (int k = 0; k < numFrames; ++k)
    {
      const double angle = maxDegrees * 3.14159265358979 / 180.0 * k / (numFrames - 1);
      std::vector<float> frame(mesh.points.size());
      for (int64_t v = 0; v < mesh.numPoints(); ++v)
      {
        const double x = mesh.points[3 * v], y = mesh.points[3 * v + 1], z = mesh.points[3 * v + 2];
        const bool turns = z > 1e-9;
        frame[3 * v] = static_cast<float>(x);
        frame[3 * v + 1] =
          static_cast<float>(turns ? y * std::cos(angle) - z * std::sin(angle) : y);
        frame[3 * v + 2] =
          static_cast<float>(turns ? y * std::sin(angle) + z * std::cos(angle) : z);
      }
      frames.push_back(frame);
    }
  }

  /// The rest height of a face's corners: -1 all below the joint, 1 all above, 0 across.
  int side(int64_t f) const
  {
    int below = 0, above = 0;
    for (int c = 0; c < 3; ++c)
    {
      const float z = frames[0][3 * triangles[3 * f + c] + 2];
      below += z < -0.05f ? 1 : 0;
      above += z > 0.05f ? 1 : 0;
    }
    return below == 3 ? -1 : above == 3 ? 1 : 0;
  }
};

/// The shared sequence in `folder`, or an empty one when ../shared/data lacks it.
tc::DeformingSequence sharedSequence(const std::string& folder, const std::string& firstFrame)
{
  if (tctest::sharedData("sequences/" + folder + "/" + firstFrame).empty())
  {
    return {};
  }
  return tc::readSequence(std::string(TC_SHARED_DATA_DIR) + "/sequences/" + folder);
}

/// Every point's weights are non-negative, at most 4 non-zero, on existing bones, summing to 1.
void expectValidSkin(const tc::SkinWeights& skin, int64_t numPoints, int32_t numBones)
{
  ASSERT_EQ(skin.joints.size(), static_cast<size_t>(tc::kMaxInfluences * numPoints));
  ASSERT_EQ(skin.weights.size(), skin.joints.size());
  for (int64_t v = 0; v < numPoints; ++v)
  {
    double sum = 0.0;
    for (int i = 0; i < tc::kMaxInfluences; ++i)
    {
      const float w = skin.weights[tc::kMaxInfluences * v + i];
      const int32_t j = skin.joints[tc::kMaxInfluences * v + i];
      EXPECT_GE(w, 0.0f) << "point " << v;
      EXPECT_TRUE(j >= 0 && j < numBones) << "point " << v << " joint " << j;
      sum += w;
    }
    EXPECT_NEAR(sum, 1.0, 1e-6) << "point " << v;
  }
  EXPECT_EQ(skin.pointsOffUnitSum, 0);
}

/// The LBS fit of a shared sequence meets the goals of issue 20: RMS over all frames at most
/// 0.5% of the diagonal and at most half the rigid baseline's.
void expectFigures(const tc::DeformingSequence& sequence)
{
  const tc::ProxyBonesResult fit = tc::fitProxyBones(sequence);
  expectValidSkin(fit.skin, sequence.soup.numPoints(), fit.clusters.numClusters);
  const double relative = fit.lbs.relative(fit.lbs.totalRms);
  const double ratio = fit.lbs.totalRms / fit.rigid.totalRms;
  EXPECT_LE(relative, 0.005);
  EXPECT_LE(ratio, 0.5);
  std::printf("%d bones: LBS rms %.4f%%, rigid rms %.4f%% of the diagonal, ratio %.3f\n",
    fit.clusters.numClusters, 100 * relative, 100 * fit.rigid.relative(fit.rigid.totalRms), ratio);
}
} // namespace

TEST(DeformationClustering, GradientOfARigidTurnIsItsRotation)
{
  const BendingCylinder c(2, 90.0);
  std::vector<uint8_t> degenerate;
  const std::vector<double> gamma =
    tc::deformationGradients(c.triangles, c.frames[0], c.frames[1], &degenerate);
  const int64_t nf = static_cast<int64_t>(c.triangles.size() / 3);
  ASSERT_EQ(gamma.size(), static_cast<size_t>(9 * nf));
  // A quarter turn about x: (x, y, z) -> (x, -z, y).
  const double turn[9] = { 1, 0, 0, 0, 0, -1, 0, 1, 0 };
  const double still[9] = { 1, 0, 0, 0, 1, 0, 0, 0, 1 };
  for (int64_t f = 0; f < nf; ++f)
  {
    EXPECT_EQ(degenerate[f], 0);
    if (c.side(f) == 0)
    {
      continue;
    }
    const double* expected = c.side(f) > 0 ? turn : still;
    for (int i = 0; i < 9; ++i)
    {
      EXPECT_NEAR(gamma[9 * f + i], expected[i], 1e-5) << "face " << f;
    }
  }
}

TEST(DeformationClustering, SeparatesTheRigidHalvesOfABendingCylinder)
{
  const BendingCylinder c;
  tc::DeformationClusteringOptions options;
  options.numClusters = 2;
  const tc::DeformationClusteringResult r = tc::clusterDeformation(c.triangles, c.frames, options);
  ASSERT_EQ(r.numClusters, 2);
  std::set<int32_t> below, above;
  for (int64_t f = 0; f < static_cast<int64_t>(r.clusterId.size()); ++f)
  {
    if (c.side(f) < 0)
    {
      below.insert(r.clusterId[f]);
    }
    else if (c.side(f) > 0)
    {
      above.insert(r.clusterId[f]);
    }
  }
  ASSERT_EQ(below.size(), 1u);
  ASSERT_EQ(above.size(), 1u);
  EXPECT_NE(*below.begin(), *above.begin());
  EXPECT_GT(r.sigmaGamma, 0.0);
  EXPECT_GT(r.sigmaD, 0.0);
}

TEST(DeformationClustering, EveryClusterBoundaryEdgeIsOnAFeatureLine)
{
  const BendingCylinder c;
  const tc::DeformationClusteringResult r = tc::clusterDeformation(c.triangles, c.frames);
  ASSERT_GT(r.numClusters, 2);
  const tc::EdgeTable edges = tc::buildEdgeTable(c.triangles);
  std::set<std::pair<int32_t, int32_t>> boundary, onLines;
  for (int64_t e = 0; e < edges.numEdges(); ++e)
  {
    if (edges.valence(e) == 2 &&
      r.clusterId[edges.edgeFaces[edges.faceOffsets[e]]] !=
        r.clusterId[edges.edgeFaces[edges.faceOffsets[e] + 1]])
    {
      boundary.emplace(edges.vertices[2 * e], edges.vertices[2 * e + 1]);
    }
  }
  for (int64_t l = 0; l < r.numLines(); ++l)
  {
    for (int64_t i = r.lineOffsets[l]; i + 1 < r.lineOffsets[l + 1]; ++i)
    {
      const int32_t a = r.lineVertices[i], b = r.lineVertices[i + 1];
      onLines.emplace(std::min(a, b), std::max(a, b));
      EXPECT_EQ(r.featureVertex[a], 1);
    }
  }
  EXPECT_FALSE(boundary.empty());
  EXPECT_EQ(onLines, boundary);
}

TEST(DeformationClustering, BoneDominanceFollowsTheHeaviestJoint)
{
  const BendingCylinder c(2);
  // Joint 1 dominates the points above z = 0.35, joint 2 the others (joint 0 unused).
  tc::SkinWeights skin;
  for (size_t v = 0; 3 * v < c.frames[0].size(); ++v)
  {
    const bool up = c.frames[0][3 * v + 2] > 0.35f;
    tc::addSkinPoint({ { 1, up ? 0.7f : 0.3f }, { 2, up ? 0.3f : 0.7f } }, 0, skin);
  }
  const tc::DeformationClusteringResult r = tc::boneDominanceClusters(c.triangles, skin);
  EXPECT_EQ(r.numClusters, 3);
  for (size_t f = 0; f < r.clusterId.size(); ++f)
  {
    int up = 0;
    for (int i = 0; i < 3; ++i)
    {
      up += c.frames[0][3 * c.triangles[3 * f + i] + 2] > 0.35f ? 1 : 0;
    }
    EXPECT_EQ(r.clusterId[f], up >= 2 ? 1 : 2) << "face " << f;
  }
  // One closed line around the cylinder between the two regions.
  ASSERT_EQ(r.numLines(), 1);
  EXPECT_EQ(r.lineVertices.front(), r.lineVertices.back());
  EXPECT_THROW(tc::boneDominanceClusters(c.triangles, tc::SkinWeights()), tc::InputError);
}

TEST(DeformationClustering, BoneDominanceOfASkinnedFileGivesFeatureLines)
{
  const std::string path = tctest::sharedData("skinned/snake_fbx/snake_fbx.glb");
  if (path.empty())
  {
    GTEST_SKIP() << "../shared/data/skinned/snake_fbx/snake_fbx.glb is absent";
  }
  const tc::Scene scene = tc::readScene(path);
  const std::vector<int32_t> triangles = tc::fanTriangles(scene.soup);
  const tc::DeformationClusteringResult r = tc::boneDominanceClusters(triangles, scene.skin);
  // Each face goes to a joint that weights one of its corners; the 13 bones of the snake
  // dominate bands along it, so there are several regions and lines between them.
  std::set<int32_t> used;
  for (size_t f = 0; f < r.clusterId.size(); ++f)
  {
    bool weighted = false;
    for (int c = 0; c < 3; ++c)
    {
      for (int i = 0; i < tc::kMaxInfluences; ++i)
      {
        const size_t slot = tc::kMaxInfluences * triangles[3 * f + c] + i;
        weighted |= scene.skin.joints[slot] == r.clusterId[f] && scene.skin.weights[slot] > 0.0f;
      }
    }
    EXPECT_TRUE(weighted) << "face " << f;
    used.insert(r.clusterId[f]);
  }
  EXPECT_GE(used.size(), 5u);
  EXPECT_GE(r.numLines(), static_cast<int64_t>(used.size()) - 1);
}

TEST(DeformationClustering, FanTrianglesKeepThePointIds)
{
  tc::PolygonSoup soup;
  soup.points.assign(3 * 5, 0.0);
  const int64_t quad[4] = { 0, 1, 2, 3 }, triangle[3] = { 3, 2, 4 }, edge[2] = { 0, 4 };
  soup.addPolygon(quad, 4);
  soup.addPolygon(triangle, 3);
  EXPECT_EQ(tc::fanTriangles(soup), (std::vector<int32_t>{ 0, 1, 2, 0, 2, 3, 3, 2, 4 }));
  soup.addPolygon(edge, 2);
  EXPECT_THROW(tc::fanTriangles(soup), tc::InputError);
}

TEST(ProxyBones, FitsABendingCylinderNearlyExactly)
{
  const BendingCylinder c;
  tc::ProxyBonesOptions options;
  options.clustering.numClusters = 2;
  const tc::ProxyBonesResult fit = tc::fitProxyBones(c.triangles, c.frames, options);
  ASSERT_EQ(fit.skeleton.joints.size(), 2u);
  EXPECT_EQ(fit.skeleton.joints[1].name, "proxy 1");
  EXPECT_EQ(fit.skeleton.joints[1].parent, -1);
  // Every point moves with one of the two halves: two bones reproduce it up to float rounding.
  EXPECT_LT(fit.lbs.relative(fit.lbs.totalRms), 1e-5);
  EXPECT_LT(fit.lbs.relative(fit.lbs.totalMax), 1e-4);
  EXPECT_LE(fit.lbs.totalRms, fit.rigid.totalRms);
  EXPECT_GT(fit.lbs.diagonal, 2.0);
}

TEST(ProxyBones, WeightsAreNonNegativeAtMostFourAndSumToOne)
{
  const BendingCylinder c;
  const tc::ProxyBonesResult fit = tc::fitProxyBones(c.triangles, c.frames);
  expectValidSkin(fit.skin, static_cast<int64_t>(c.frames[0].size() / 3), fit.clusters.numClusters);
  tc::ProxyBonesOptions two;
  two.maxInfluences = 2;
  const tc::ProxyBonesResult fit2 = tc::fitProxyBones(c.triangles, c.frames, two);
  for (size_t v = 0; v < fit2.skin.weights.size() / 4; ++v)
  {
    EXPECT_EQ(fit2.skin.weights[4 * v + 2], 0.0f);
    EXPECT_EQ(fit2.skin.weights[4 * v + 3], 0.0f);
  }
}

TEST(ProxyBones, TheirRigIsToldApartFromASkeletonOfTheFile)
{
  const BendingCylinder c;
  const tc::ProxyBonesResult fit = tc::fitProxyBones(c.triangles, c.frames);
  std::vector<double> times(c.frames.size());
  for (size_t k = 0; k < times.size(); ++k)
  {
    times[k] = double(k);
  }
  EXPECT_TRUE(tc::isProxyRig(tc::proxyRig(fit, times, "frames")));
  EXPECT_FALSE(tc::isProxyRig(tctest::chainRig(0.0, 1.0)));
  EXPECT_FALSE(tc::isProxyRig(tc::Rig{}));
}

TEST(ProxyBones, SkinPointsPosesTheFittedFrames)
{
  const BendingCylinder c;
  const tc::ProxyBonesResult fit = tc::fitProxyBones(c.triangles, c.frames);
  ASSERT_EQ(fit.frameMatrices.size(), c.frames.size());
  const std::vector<double> rest(c.frames[0].begin(), c.frames[0].end());
  std::vector<std::vector<double>> posed;
  for (const std::vector<tc::Matrix4>& matrices : fit.frameMatrices)
  {
    posed.push_back(tc::skinPoints(rest, fit.skin, matrices));
  }
  // Frame 0 is the rest within float noise; the others have the reported errors.
  for (size_t i = 0; i < rest.size(); ++i)
  {
    EXPECT_NEAR(posed[0][i], rest[i], 1e-6);
  }
  const tc::FitError error = tc::measureFit(posed, c.frames);
  for (size_t k = 0; k < c.frames.size(); ++k)
  {
    EXPECT_DOUBLE_EQ(error.rms[k], fit.lbs.rms[k]);
    EXPECT_DOUBLE_EQ(error.max[k], fit.lbs.max[k]);
  }
}

TEST(ProxyBones, SnakeMeetsTheFigures)
{
  const tc::DeformingSequence snake = sharedSequence("snake_closed_21f", "f_0000.obj");
  if (snake.frames.empty())
  {
    GTEST_SKIP() << "../shared/data/sequences/snake_closed_21f is absent";
  }
  expectFigures(snake);
}

TEST(ProxyBones, FrankieMeetsTheFigures)
{
  const tc::DeformingSequence frankie = sharedSequence("frankie_run_19f", "Frankie_Run_0000.obj");
  if (frankie.frames.empty())
  {
    GTEST_SKIP() << "../shared/data/sequences/frankie_run_19f is absent";
  }
  expectFigures(frankie);
}

TEST(ProxyBones, RejectsBadInput)
{
  const BendingCylinder c(3);
  const auto fit = [&](const std::vector<std::vector<float>>& frames, int clusters = 0)
  {
    tc::ProxyBonesOptions options;
    options.clustering.numClusters = clusters;
    tc::fitProxyBones(c.triangles, frames, options);
  };
  EXPECT_THROW(fit({}), tc::InputError);
  std::vector<std::vector<float>> shorter = c.frames;
  shorter[2].resize(shorter[2].size() - 3);
  EXPECT_THROW(fit(shorter), tc::InputError);
  std::vector<std::vector<float>> notFinite = c.frames;
  notFinite[1][7] = std::numeric_limits<float>::quiet_NaN();
  EXPECT_THROW(fit(notFinite), tc::InputError);
  EXPECT_THROW(fit(c.frames, static_cast<int>(c.triangles.size() / 3) + 1), tc::InputError);
  std::vector<int32_t> badIds = c.triangles;
  badIds[4] = static_cast<int32_t>(c.frames[0].size() / 3);
  EXPECT_THROW(tc::fitProxyBones(badIds, c.frames), tc::InputError);
  tc::ProxyBonesOptions fiveInfluences;
  fiveInfluences.maxInfluences = 5;
  EXPECT_THROW(tc::fitProxyBones(c.triangles, c.frames, fiveInfluences), tc::InputError);
}

TEST(ProxyBones, ReportsProgressAndAborts)
{
  const BendingCylinder c;
  tctest::expectProgressAndAbort([&](const tc::Progress& p)
    { tc::fitProxyBones(c.triangles, c.frames, {}, p); },
    10, [](double f) { return f < 0.5; });
  tctest::expectProgressAndAbort([&](const tc::Progress& p)
    { tc::clusterDeformation(c.triangles, c.frames, {}, p); },
    5, [](double f) { return f < 0.2; });
}
