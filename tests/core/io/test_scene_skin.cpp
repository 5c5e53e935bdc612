// SPDX-License-Identifier: BSD-3-Clause
// Skinned scenes posed by tc::skinPoints against frames baked independently: the shared
// sequence baked from the snake FBX, and frames baked here from Assimp's own data structures.
#include "tc/common/errors.h"
#include "tc/io/scene_io.h"
#include "tc/io/soup_io.h"
#include "tc/metrics/surface_distance.h"
#include "tc/skinning/skin.h"

#include "assimp_poser.h"
#include "test_data.h"

#include <assimp/Importer.hpp>
#include <assimp/postprocess.h>
#include <assimp/scene.h>
#include <gtest/gtest.h>

#include <cstdio>
#include <functional>
#include <iostream>
#include <map>
#include <string>
#include <vector>

namespace
{
/// The soup's polygons as triangles (fans), over its points or over `points`.
tc::TriMesh triangles(const tc::PolygonSoup& soup, const std::vector<double>& points)
{
  tc::TriMesh mesh;
  mesh.points = points;
  for (int64_t p = 0; p < soup.numPolygons(); ++p)
  {
    for (int64_t k = soup.offsets[p] + 1; k + 1 < soup.offsets[p + 1]; ++k)
    {
      mesh.triangles.insert(mesh.triangles.end(),
        { int32_t(soup.connectivity[soup.offsets[p]]), int32_t(soup.connectivity[k]),
          int32_t(soup.connectivity[k + 1]) });
    }
  }
  return mesh;
}

/// The scene posed at `seconds` of animation `a`.
std::vector<double> posed(const tc::Scene& scene, size_t a, double seconds)
{
  const std::vector<tc::Matrix4> globals =
    tc::jointGlobals(scene.skeleton, &scene.animations.at(a), seconds);
  return tc::skinPoints(
    scene.soup.points, scene.skin, tc::skinningMatrices(scene.skeleton, globals));
}

/// Symmetric Hausdorff distance between two meshes over the reference's diagonal.
double relativeHausdorff(const tc::TriMesh& mesh, const tc::TriMesh& reference)
{
  tc::SurfaceDistanceOptions options;
  options.samplesPerMesh = 20000;
  options.perPointDistance = false;
  const tc::SurfaceDistanceResult d = tc::surfaceDistance(mesh, reference, options);
  return d.hausdorff / d.diagonal;
}

} // namespace

TEST(SceneSkin, SnakePosedAtEachBakedFrameTimeMatchesTheSharedSequence)
{
  const std::string frames = tctest::sharedData("sequences/snake_closed_21f/f_0000.obj");
  const std::vector<std::string> files = { tctest::sharedData(
                                             "skinned/snake_fbx/animation_with_skeleton.fbx"),
    tctest::sharedData("skinned/snake_fbx/snake_fbx.glb") };
  if (frames.empty() || files[0].empty() || files[1].empty())
  {
    GTEST_SKIP() << "the snake and its baked sequence are not in the shared data";
  }
  for (const std::string& file : files)
  {
    const tc::Scene scene = tc::readScene(file);
    ASSERT_EQ(scene.animations.size(), 1u);
    ASSERT_EQ(scene.skin.joints.size(), 4 * size_t(scene.soup.numPoints()));
    double worst = 0.0;
    for (int k = 0; k <= 20; ++k)
    {
      char name[64];
      std::snprintf(name, sizeof name, "sequences/snake_closed_21f/f_%04d.obj", k);
      const tc::PolygonSoup baked = tc::readOBJ(tctest::sharedData(name));
      const double t = scene.animations[0].duration * k / 20.0;
      const double d = relativeHausdorff(
        triangles(scene.soup, posed(scene, 0, t)), triangles(baked, baked.points));
      worst = std::max(worst, d);
      EXPECT_LE(d, 1e-4) << file << " frame " << k;
    }
    std::cout << "[ figures  ] " << file.substr(file.rfind('/') + 1)
              << ": largest Hausdorff / diagonal over 21 frames " << worst << "\n";
  }
}

TEST(SceneSkin, WusonAnimationsMatchFramesBakedFromAssimpsStructures)
{
  for (const char* name : { "skinned/wuson/wuson.glb", "skinned/wuson/Testwuson.X" })
  {
    const std::string file = tctest::sharedData(name);
    if (file.empty())
    {
      GTEST_SKIP() << name << " is not in the shared data";
    }
    const tc::Scene scene = tc::readScene(file);
    Assimp::Importer importer;
    const aiScene* raw =
      importer.ReadFile(file, aiProcess_JoinIdenticalVertices | aiProcess_ValidateDataStructure);
    ASSERT_TRUE(raw);
    ASSERT_EQ(scene.animations.size(), raw->mNumAnimations);
    for (unsigned a = 0; a < raw->mNumAnimations; ++a)
    {
      tctest::AssimpPoser baker(*raw, raw->mAnimations[a]);
      double worst = 0.0;
      for (int k = 0; k <= 8; ++k)
      {
        const double ticks = raw->mAnimations[a]->mDuration * k / 8.0;
        const std::vector<double> reference = baker.frame(ticks);
        const double d = relativeHausdorff(
          triangles(scene.soup, posed(scene, a, scene.animations[a].duration * k / 8.0)),
          triangles(scene.soup, reference));
        worst = std::max(worst, d);
        EXPECT_LE(d, 1e-4) << name << " " << scene.animations[a].name << " frame " << k;
      }
      std::cout << "[ figures  ] " << name << " " << scene.animations[a].name
                << ": largest Hausdorff / diagonal over 9 frames " << worst << "\n";
    }
  }
}
