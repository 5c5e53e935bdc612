// SPDX-License-Identifier: BSD-3-Clause
#include "io/scene_skin.h"

#include <assimp/scene.h>

#include <algorithm>
#include <cmath>
#include <functional>
#include <numeric>

namespace tc
{
namespace
{
Matrix4 toMatrix(const aiMatrix4x4& m)
{
  return { m.a1, m.a2, m.a3, m.a4, m.b1, m.b2, m.b3, m.b4, m.c1, m.c2, m.c3, m.c4, m.d1, m.d2, m.d3,
    m.d4 };
}

/// Equal up to float rounding of the larger entries: two meshes' offset matrices for one bone
/// are the same when their files wrote the same numbers.
bool sameMatrix(const Matrix4& a, const Matrix4& b)
{
  double scale = 1.0, largest = 0.0;
  for (size_t k = 0; k < a.size(); ++k)
  {
    scale = std::max({ scale, std::abs(a[k]), std::abs(b[k]) });
    largest = std::max(largest, std::abs(a[k] - b[k]));
  }
  return largest <= 1e-6 * scale;
}

/// Every node of the hierarchy under `node`, by name (the first of a name wins).
void indexNodes(const aiNode& node, std::map<std::string, const aiNode*>& named)
{
  named.emplace(node.mName.C_Str(), &node);
  for (unsigned c = 0; c < node.mNumChildren; ++c)
  {
    indexNodes(*node.mChildren[c], named);
  }
}

/// The nodes that hold meshes, under `node`.
void meshNodes(const aiNode& node, std::set<const aiNode*>& marked)
{
  if (node.mNumMeshes > 0)
  {
    marked.insert(&node);
  }
  for (unsigned c = 0; c < node.mNumChildren; ++c)
  {
    meshNodes(*node.mChildren[c], marked);
  }
}

/// The times of `keys` in seconds, and their values through `value`, sorted by time.
template <typename Key, typename Value>
void readKeys(const Key* keys, unsigned n, double ticksPerSecond, std::vector<double>& times,
  std::vector<Value>& values, const std::function<Value(const Key&)>& value)
{
  std::vector<unsigned> order(n);
  std::iota(order.begin(), order.end(), 0u);
  std::stable_sort(order.begin(), order.end(),
    [keys](unsigned a, unsigned b) { return keys[a].mTime < keys[b].mTime; });
  for (const unsigned k : order)
  {
    if (std::isfinite(keys[k].mTime))
    {
      times.push_back(keys[k].mTime / ticksPerSecond);
      values.push_back(value(keys[k]));
    }
  }
}

/// Assimp's ticks per second for a file that gives none, as its own viewer assumes.
constexpr double kDefaultTicksPerSecond = 25.0;
} // namespace

SceneSkinBuilder::SceneSkinBuilder(const aiScene& scene)
{
  indexNodes(*scene.mRootNode, Named_);
  std::set<const aiNode*> marked;
  for (unsigned m = 0; m < scene.mNumMeshes; ++m)
  {
    const aiMesh& mesh = *scene.mMeshes[m];
    for (unsigned b = 0; b < mesh.mNumBones; ++b)
    {
      const auto it = Named_.find(mesh.mBones[b]->mName.C_Str());
      if (it != Named_.end())
      {
        marked.insert(it->second);
      }
    }
  }
  if (marked.empty() && scene.mNumAnimations == 0)
  {
    return;
  }
  meshNodes(*scene.mRootNode, marked);
  for (const aiNode* node : std::set<const aiNode*>(marked))
  {
    for (const aiNode* up = node->mParent; up; up = up->mParent)
    {
      marked.insert(up);
    }
  }
  addJoints(*scene.mRootNode, -1, marked);
}

void SceneSkinBuilder::addJoints(
  const aiNode& node, int32_t parent, const std::set<const aiNode*>& marked)
{
  if (marked.count(&node) == 0)
  {
    return;
  }
  Joint joint;
  joint.name = node.mName.C_Str();
  joint.parent = parent;
  joint.restLocal = toMatrix(node.mTransformation);
  // Until a mesh binds it, a joint's bind pose is its rest pose.
  Matrix4 restGlobal = joint.restLocal;
  for (int32_t up = parent; up >= 0; up = Skeleton_.joints[up].parent)
  {
    restGlobal = multiply(Skeleton_.joints[up].restLocal, restGlobal);
  }
  joint.inverseBind = inverseAffine(restGlobal);
  const int32_t index = static_cast<int32_t>(Skeleton_.joints.size());
  Skeleton_.joints.push_back(joint);
  Bound_.push_back(false);
  NodeJoint_[&node] = index;
  for (unsigned c = 0; c < node.mNumChildren; ++c)
  {
    addJoints(*node.mChildren[c], index, marked);
  }
}

int32_t SceneSkinBuilder::jointFor(const aiNode* node, const Matrix4& inverseBind)
{
  const int32_t first = NodeJoint_.at(node);
  if (!Bound_[first])
  {
    Skeleton_.joints[first].inverseBind = inverseBind;
    Bound_[first] = true;
    return first;
  }
  for (size_t j = first; j < Skeleton_.joints.size(); ++j)
  {
    const Joint& joint = Skeleton_.joints[j];
    if ((j == size_t(first) || joint.sameNodeAs == first) &&
      sameMatrix(joint.inverseBind, inverseBind))
    {
      return static_cast<int32_t>(j);
    }
  }
  Joint twin = Skeleton_.joints[first];
  twin.inverseBind = inverseBind;
  twin.sameNodeAs = first;
  Skeleton_.joints.push_back(twin);
  Bound_.push_back(true);
  return static_cast<int32_t>(Skeleton_.joints.size() - 1);
}

void SceneSkinBuilder::addMesh(
  const aiMesh& mesh, const aiNode& node, const aiMatrix4x4& placement, SkinWeights& skin)
{
  const Matrix4 unplace = inverseAffine(toMatrix(placement));
  std::vector<std::vector<std::pair<int32_t, float>>> influences(mesh.mNumVertices);
  for (unsigned b = 0; b < mesh.mNumBones; ++b)
  {
    const aiBone& bone = *mesh.mBones[b];
    const auto it = Named_.find(bone.mName.C_Str());
    if (it == Named_.end())
    {
      continue; // a bone without a node moves nothing Assimp could pose either
    }
    const int32_t joint = jointFor(it->second, multiply(toMatrix(bone.mOffsetMatrix), unplace));
    for (unsigned w = 0; w < bone.mNumWeights; ++w)
    {
      const aiVertexWeight& weight = bone.mWeights[w];
      if (weight.mVertexId < mesh.mNumVertices)
      {
        influences[weight.mVertexId].emplace_back(joint, weight.mWeight);
      }
    }
  }
  const auto unweighted = [](const std::vector<std::pair<int32_t, float>>& list)
  {
    return std::none_of(list.begin(), list.end(),
      [](const auto& jw) { return jw.second > 0.0f && std::isfinite(jw.second); });
  };
  const int64_t loose = std::count_if(influences.begin(), influences.end(), unweighted);
  const int32_t fallback = loose > 0 ? jointFor(&node, unplace) : 0;
  Unweighted_ += mesh.mNumBones > 0 ? loose : 0;
  for (auto& list : influences)
  {
    addSkinPoint(std::move(list), fallback, skin);
  }
}

std::vector<Animation> SceneSkinBuilder::animations(
  const aiScene& scene, std::vector<std::string>& warnings) const
{
  std::vector<Animation> out;
  for (unsigned a = 0; a < scene.mNumAnimations; ++a)
  {
    const aiAnimation& source = *scene.mAnimations[a];
    Animation animation;
    animation.name =
      source.mName.length > 0 ? source.mName.C_Str() : "animation " + std::to_string(a);
    animation.ticksPerSecond =
      source.mTicksPerSecond > 0 ? source.mTicksPerSecond : kDefaultTicksPerSecond;
    if (!(source.mTicksPerSecond > 0))
    {
      warnings.push_back("animation '" + animation.name + "' gives no ticks per second: read at " +
        std::to_string(int(kDefaultTicksPerSecond)) + " per second");
    }
    const double tps = animation.ticksPerSecond;
    animation.duration =
      std::isfinite(source.mDuration) ? std::max(0.0, source.mDuration / tps) : 0.0;
    for (unsigned c = 0; c < source.mNumChannels; ++c)
    {
      const aiNodeAnim& channel = *source.mChannels[c];
      const auto named = Named_.find(channel.mNodeName.C_Str());
      const auto joint = named == Named_.end() ? NodeJoint_.end() : NodeJoint_.find(named->second);
      if (joint == NodeJoint_.end())
      {
        continue; // a node that moves no point
      }
      JointTrack track;
      track.joint = joint->second;
      readKeys<aiVectorKey, std::array<double, 3>>(channel.mPositionKeys, channel.mNumPositionKeys,
        tps, track.positionTimes, track.positions,
        [](const aiVectorKey& k) {
          return std::array<double, 3>{ k.mValue.x, k.mValue.y, k.mValue.z };
        });
      readKeys<aiQuatKey, std::array<double, 4>>(channel.mRotationKeys, channel.mNumRotationKeys,
        tps, track.rotationTimes, track.rotations,
        [](const aiQuatKey& k) {
          return std::array<double, 4>{ k.mValue.w, k.mValue.x, k.mValue.y, k.mValue.z };
        });
      readKeys<aiVectorKey, std::array<double, 3>>(channel.mScalingKeys, channel.mNumScalingKeys,
        tps, track.scaleTimes, track.scales,
        [](const aiVectorKey& k) {
          return std::array<double, 3>{ k.mValue.x, k.mValue.y, k.mValue.z };
        });
      animation.tracks.push_back(std::move(track));
    }
    out.push_back(std::move(animation));
  }
  return out;
}
} // namespace tc
