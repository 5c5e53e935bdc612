// SPDX-License-Identifier: BSD-3-Clause
// Skinned scenes posed by tc::skinPoints against frames baked independently: the shared
// sequence baked from the snake FBX, and frames baked here from Assimp's own data structures.
#include "tc/common/errors.h"
#include "tc/skinning/skin.h"
#include "tc/io/scene_io.h"
#include "tc/io/soup_io.h"
#include "tc/metrics/surface_distance.h"

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

/// Frames baked from Assimp's structures alone (aiMatrix4x4, aiQuaternion::Interpolate): the
/// definition tc::skinPoints must meet, written without the project's code.
class AssimpBaker
{
public:
  explicit AssimpBaker(const aiScene& scene, unsigned animation)
    : Scene_(scene)
  {
    const aiAnimation& a = *scene.mAnimations[animation];
    for (unsigned c = 0; c < a.mNumChannels; ++c)
    {
      Channels_[a.mChannels[c]->mNodeName.C_Str()] = a.mChannels[c];
    }
  }

  /// Every mesh's points, placed as tc::readScene places them, at `ticks`.
  std::vector<double> frame(double ticks)
  {
    Globals_.clear();
    walk(*Scene_.mRootNode, aiMatrix4x4(), ticks);
    std::vector<double> points;
    place(*Scene_.mRootNode, points);
    return points;
  }

private:
  template <typename Key>
  static std::pair<unsigned, float> at(const Key* keys, unsigned n, double t)
  {
    unsigned i = 0;
    while (i + 1 < n && t >= keys[i + 1].mTime)
    {
      ++i;
    }
    if (i + 1 >= n || t <= keys[i].mTime)
    {
      return { i, 0.0f };
    }
    return { i, float((t - keys[i].mTime) / (keys[i + 1].mTime - keys[i].mTime)) };
  }

  aiMatrix4x4 local(const aiNode& node, double t) const
  {
    const auto it = Channels_.find(node.mName.C_Str());
    if (it == Channels_.end())
    {
      return node.mTransformation;
    }
    const aiNodeAnim& c = *it->second;
    aiVector3D p, s(1, 1, 1);
    aiQuaternion q;
    node.mTransformation.Decompose(s, q, p);
    if (c.mNumPositionKeys)
    {
      const auto [i, a] = at(c.mPositionKeys, c.mNumPositionKeys, t);
      p = a > 0 ? c.mPositionKeys[i].mValue * (1 - a) + c.mPositionKeys[i + 1].mValue * a
                : c.mPositionKeys[i].mValue;
    }
    if (c.mNumScalingKeys)
    {
      const auto [i, a] = at(c.mScalingKeys, c.mNumScalingKeys, t);
      s = a > 0 ? c.mScalingKeys[i].mValue * (1 - a) + c.mScalingKeys[i + 1].mValue * a
                : c.mScalingKeys[i].mValue;
    }
    if (c.mNumRotationKeys)
    {
      const auto [i, a] = at(c.mRotationKeys, c.mNumRotationKeys, t);
      q = c.mRotationKeys[i].mValue;
      if (a > 0)
      {
        aiQuaternion::Interpolate(q, c.mRotationKeys[i].mValue, c.mRotationKeys[i + 1].mValue, a);
      }
      q.Normalize();
    }
    return aiMatrix4x4(s, q, p);
  }

  void walk(const aiNode& node, const aiMatrix4x4& parent, double t)
  {
    Globals_[node.mName.C_Str()] = parent * local(node, t);
    for (unsigned c = 0; c < node.mNumChildren; ++c)
    {
      walk(*node.mChildren[c], Globals_[node.mName.C_Str()], t);
    }
  }

  void place(const aiNode& node, std::vector<double>& points)
  {
    for (unsigned k = 0; k < node.mNumMeshes; ++k)
    {
      const aiMesh& mesh = *Scene_.mMeshes[node.mMeshes[k]];
      std::vector<aiVector3D> sum(mesh.mNumVertices, aiVector3D(0, 0, 0));
      for (unsigned b = 0; b < mesh.mNumBones; ++b)
      {
        const aiBone& bone = *mesh.mBones[b];
        const aiMatrix4x4 m = Globals_[bone.mName.C_Str()] * bone.mOffsetMatrix;
        for (unsigned w = 0; w < bone.mNumWeights; ++w)
        {
          const aiVertexWeight& vw = bone.mWeights[w];
          sum[vw.mVertexId] += (m * mesh.mVertices[vw.mVertexId]) * vw.mWeight;
        }
      }
      for (unsigned v = 0; v < mesh.mNumVertices; ++v)
      {
        const aiVector3D p =
          mesh.mNumBones ? sum[v] : Globals_[node.mName.C_Str()] * mesh.mVertices[v];
        points.insert(points.end(), { p.x, p.y, p.z });
      }
    }
    for (unsigned c = 0; c < node.mNumChildren; ++c)
    {
      place(*node.mChildren[c], points);
    }
  }

  const aiScene& Scene_;
  std::map<std::string, const aiNodeAnim*> Channels_;
  std::map<std::string, aiMatrix4x4> Globals_;
};
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
      AssimpBaker baker(*raw, a);
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
