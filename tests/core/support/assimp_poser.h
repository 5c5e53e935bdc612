// SPDX-License-Identifier: BSD-3-Clause
/// @file assimp_poser.h
/// Skinned meshes posed from Assimp's data structures alone (aiMatrix4x4,
/// aiQuaternion::Interpolate): the definition of skinning that tc::skinPoints must meet,
/// written without the project's code, for the tests of the scene reader and the glTF export.
#pragma once

#include <assimp/scene.h>

#include <map>
#include <string>
#include <utility>
#include <vector>

namespace tctest
{
class AssimpPoser
{
public:
  /// Poses `scene` by `animation` (nullptr: the nodes' own transforms).
  AssimpPoser(const aiScene& scene, const aiAnimation* animation)
    : Scene_(scene)
  {
    for (unsigned c = 0; animation && c < animation->mNumChannels; ++c)
    {
      Channels_[animation->mChannels[c]->mNodeName.C_Str()] = animation->mChannels[c];
    }
  }

  /// Skinned mesh `mesh`'s points at `ticks`: sum over its bones of w global(bone) offset p.
  std::vector<double> pose(const aiMesh& mesh, double ticks)
  {
    walk(*Scene_.mRootNode, aiMatrix4x4(), ticks);
    return skinned(mesh);
  }

  /// Every mesh's points at `ticks`, in node order, placed as tc::readScene places them:
  /// skinned meshes by their bones, the others by their node's global transform.
  std::vector<double> frame(double ticks)
  {
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

  template <typename Key>
  static aiVector3D lerp(const Key* keys, unsigned n, double t)
  {
    const auto [i, a] = at(keys, n, t);
    return a > 0 ? keys[i].mValue * (1 - a) + keys[i + 1].mValue * a : keys[i].mValue;
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
    p = c.mNumPositionKeys ? lerp(c.mPositionKeys, c.mNumPositionKeys, t) : p;
    s = c.mNumScalingKeys ? lerp(c.mScalingKeys, c.mNumScalingKeys, t) : s;
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

  std::vector<double> skinned(const aiMesh& mesh) const
  {
    std::vector<aiVector3D> sum(mesh.mNumVertices, aiVector3D(0, 0, 0));
    for (unsigned b = 0; b < mesh.mNumBones; ++b)
    {
      const aiBone& bone = *mesh.mBones[b];
      const aiMatrix4x4 m = Globals_.at(bone.mName.C_Str()) * bone.mOffsetMatrix;
      for (unsigned w = 0; w < bone.mNumWeights; ++w)
      {
        const aiVertexWeight& vw = bone.mWeights[w];
        sum[vw.mVertexId] += (m * mesh.mVertices[vw.mVertexId]) * vw.mWeight;
      }
    }
    std::vector<double> points;
    for (const aiVector3D& p : sum)
    {
      points.insert(points.end(), { p.x, p.y, p.z });
    }
    return points;
  }

  void place(const aiNode& node, std::vector<double>& points) const
  {
    for (unsigned k = 0; k < node.mNumMeshes; ++k)
    {
      const aiMesh& mesh = *Scene_.mMeshes[node.mMeshes[k]];
      if (mesh.mNumBones > 0)
      {
        const std::vector<double> posed = skinned(mesh);
        points.insert(points.end(), posed.begin(), posed.end());
        continue;
      }
      const aiMatrix4x4& global = Globals_.at(node.mName.C_Str());
      for (unsigned v = 0; v < mesh.mNumVertices; ++v)
      {
        const aiVector3D p = global * mesh.mVertices[v];
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
} // namespace tctest
