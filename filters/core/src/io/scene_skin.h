// SPDX-License-Identifier: BSD-3-Clause
/// @file scene_skin.h
/// The skeleton, skin weights and animations of a scene Assimp read (tc::readScene).
#pragma once

#include "tc/skinning/skin.h"

#include <assimp/matrix4x4.h>

#include <map>
#include <set>
#include <string>
#include <vector>

struct aiScene;
struct aiNode;
struct aiMesh;

namespace tc
{
/// Builds the skeleton of a scene while its meshes are placed, then its animations.
///
/// The joints are the nodes that move points (every bone, and the node of every mesh when the
/// scene is skinned or animated) and their ancestors, parents first. The mesh's points are
/// read placed by their node's transform N (the rest pose as the file positions it), so a
/// bone's inverse bind matrix is Assimp's offset matrix times N^-1: posing gives
/// global(bone) offset p, as Assimp defines skinning, whatever N is. A bone whose inverse bind
/// differs between two meshes (their nodes differ) gets one joint per matrix, on one node.
class SceneSkinBuilder
{
public:
  /// Marks the joints of `scene`; none when it has neither bones nor animations.
  explicit SceneSkinBuilder(const aiScene& scene);

  /// True when the scene has a skeleton to read.
  bool active() const { return !NodeJoint_.empty(); }

  /// Appends the weights of `mesh`'s points, placed by `placement` (its node's transform
  /// accumulated from the root) under `node`, to `skin`: a bone's weights, or weight 1 to the
  /// node's joint for a mesh without bones and for the points no bone weights.
  void addMesh(
    const aiMesh& mesh, const aiNode& node, const aiMatrix4x4& placement, SkinWeights& skin);

  /// The skeleton, complete once every mesh was added.
  const Skeleton& skeleton() const { return Skeleton_; }

  /// The scene's animations, tracks on the first joint of each animated node; times in seconds
  /// (a file without ticks per second is read at 25 per second, with a warning).
  std::vector<Animation> animations(const aiScene& scene, std::vector<std::string>& warnings) const;

  /// Points of skinned meshes that no bone weights (bound rigidly to their mesh's node).
  int64_t unweightedPoints() const { return Unweighted_; }

private:
  int32_t jointFor(const aiNode* node, const Matrix4& inverseBind);
  void addJoints(const aiNode& node, int32_t parent, const std::set<const aiNode*>& marked);

  Skeleton Skeleton_;
  std::map<const aiNode*, int32_t> NodeJoint_; ///< the first joint of each joint node
  std::map<std::string, const aiNode*> Named_; ///< every node by name (bones name nodes)
  std::vector<bool> Bound_;                    ///< per joint: its inverseBind was set by a mesh
  int64_t Unweighted_ = 0;
};
} // namespace tc
