// SPDX-License-Identifier: BSD-3-Clause
/// @file skin.h
/// Linear blend skinning: a skeleton of joints, keyframed animations of its joints, the skin
/// weights of a mesh's points, and posing (Feng et al. 2010, 5.2: "the skinned mesh is
/// deformed in the vertex shader by linear blend skinning"; here the reference on the CPU).
///
/// Matrices are 4 x 4, row-major (m[4 * row + column]), acting on column vectors (p' = M p),
/// as Assimp's aiMatrix4x4 and glTF's (column-major) matrices read back.
#pragma once

#include <array>
#include <cstdint>
#include <string>
#include <vector>

namespace tc
{
using Matrix4 = std::array<double, 16>;

/// The identity matrix.
Matrix4 identityMatrix();

/// a b (a applied after b).
Matrix4 multiply(const Matrix4& a, const Matrix4& b);

/// The inverse of an invertible affine matrix (last row 0 0 0 1).
Matrix4 inverseAffine(const Matrix4& m);

/// One joint: a node of the scene's hierarchy that moves points.
struct Joint
{
  std::string name;
  int32_t parent = -1;     ///< index of the parent joint (always < this one's), -1 for a root
  Matrix4 restLocal{};     ///< transform relative to the parent when no animation moves it
  Matrix4 inverseBind{};   ///< from the mesh's bind pose into this joint's frame
  int32_t sameNodeAs = -1; ///< another joint of the same node (with its own inverseBind), or -1
};

/// The joints, parents before children.
struct Skeleton
{
  std::vector<Joint> joints;

  bool empty() const { return joints.empty(); }
};

/// Keyframes of one joint; times in seconds, ascending. A component without keys stays at the
/// joint's rest value.
struct JointTrack
{
  int32_t joint = -1;
  std::vector<double> positionTimes;
  std::vector<std::array<double, 3>> positions;
  std::vector<double> rotationTimes;
  std::vector<std::array<double, 4>> rotations; ///< unit quaternions (w, x, y, z)
  std::vector<double> scaleTimes;
  std::vector<std::array<double, 3>> scales;
};

/// A keyframed animation of a skeleton: positions and scales interpolated linearly, rotations
/// spherically, held at the first and last key outside them. Or, for the proxy bones of a
/// deforming sequence (whose bones may shear, which no track can say), sampled poses: every
/// joint's global transform at each frame time, interpolated linearly between frames.
struct Animation
{
  std::string name;
  double duration = 0.0;       ///< seconds; the animation plays over [0, duration]
  double ticksPerSecond = 0.0; ///< the file's time unit (informative: times are in seconds)
  std::vector<JointTrack> tracks;
  /// Sampled poses, ascending seconds; when there are any, they pose the skeleton, not tracks.
  std::vector<double> frameTimes;
  /// #frameTimes x #joints: each joint's transform to the scene at that frame.
  std::vector<std::vector<Matrix4>> frameGlobals;
};

/// The distinct key times of `animation` in [0, duration], with 0 and the duration, ascending
/// (what a reader announces as its time steps).
std::vector<double> animationKeyTimes(const Animation& animation);

/// Up to 4 joint influences per point.
constexpr int kMaxInfluences = 4;

/// Skin weights of a mesh's points: each point's kMaxInfluences largest influences (unused
/// slots: joint 0, weight 0). Weights are kept as the file gives them, also when they do not
/// sum to 1 (linear blend skinning does not normalize, nor does Assimp); a point cut to 4
/// influences has the 4 renormalized to sum 1, as Assimp's LimitBoneWeights step does.
struct SkinWeights
{
  std::vector<int32_t> joints;  ///< #V x 4 joint indices
  std::vector<float> weights;   ///< #V x 4 weights, descending
  int64_t pointsOverLimit = 0;  ///< points that had more than 4 influences before the cut
  double largestDropped = 0.0;  ///< the largest weight cut (before renormalizing)
  int64_t pointsOffUnitSum = 0; ///< points whose kept weights sum to 1 +- 1e-3 not
  double smallestSum = 1.0;     ///< the smallest and largest sums of those points
  double largestSum = 1.0;

  bool empty() const { return joints.empty(); }
};

/// The skin of one point (SkinWeights), as one record; the atlas stores it as kSkinValues
/// floats (the joints, then the weights).
struct PointSkin
{
  std::array<int32_t, kMaxInfluences> joints{};
  std::array<float, kMaxInfluences> weights{};
};
constexpr int kSkinValues = 2 * kMaxInfluences;

/// Keeps the kMaxInfluences largest of `influences` (joint, weight), renormalizing them when
/// some were cut, and appends the point's 4 joints and weights to `skin`, counting a cut in
/// pointsOverLimit and largestDropped and a sum away from 1 in pointsOffUnitSum. Weights <= 0
/// or non-finite are ignored; a point left without weight is bound to `fallbackJoint` with
/// weight 1.
void addSkinPoint(
  std::vector<std::pair<int32_t, float>> influences, int32_t fallbackJoint, SkinWeights& skin);

/// The skin of a point between `count` points (1 .. 3: a corner, a point on an edge, a point in
/// a triangle) with barycentric weights `blend` (Feng et al. 2010, 5.2, weights interpolated):
/// the union of their joints, each weighted by its interpolated weight, the 4 largest kept and
/// scaled so that they sum to the interpolated total (a blend of points with at most 4 joints
/// in all is the linear one). Joint ids are never blended.
/// @param[in] skins  count skins of the points
/// @param[in] blend  count barycentric weights, summing to 1
PointSkin blendInfluences(int count, const PointSkin* skins, const double* blend);

/// The index of the animation `choice` names: "" the first, an animation's name, or its index
/// as digits; -1 when there is none at all.
/// @throws tc::InputError  for a choice that names none of them (the message lists them all)
int findAnimation(const std::vector<Animation>& animations, const std::string& choice);

/// findAnimation without the exception, for readers and renderers that report and go on: -1
/// with `error` (the message that lists the animations) for a choice that names none of them.
int findAnimation(
  const std::vector<Animation>& animations, const std::string& choice, std::string& error);

/// A skeleton and its animations: what poses a skinned mesh, and what travels with it from the
/// reader through the pipeline into the atlas.
struct Rig
{
  Skeleton skeleton;
  std::vector<Animation> animations;

  bool empty() const { return skeleton.empty(); }
};

/// `rig` as JSON text (doubles written so that they read back bit-exactly): what the readers'
/// field array "Rig" and the atlas file's metadata hold.
std::string encodeRig(const Rig& rig);

/// The rig of encodeRig's text.
/// @throws tc::InputError  for text that is no rig (says what is wrong: a parent after its
///   child, a track of a joint the skeleton lacks, keys out of order, a non-finite number...)
Rig decodeRig(const std::string& text);

/// Every joint's transform from its frame to the scene at `seconds` of `animation` (nullptr:
/// the rest pose), composed from the root: global[j] = global[parent] local[j](t).
std::vector<Matrix4> jointGlobals(
  const Skeleton& skeleton, const Animation* animation, double seconds);

/// The skinning matrices global[j] inverseBind[j], which carry a bind-pose point of joint j
/// into the pose `globals` describes.
std::vector<Matrix4> skinningMatrices(
  const Skeleton& skeleton, const std::vector<Matrix4>& globals);

/// The skinning matrices of `rig` at `seconds` of its animation `animation` (an index of
/// rig.animations; -1 or out of range: the rest pose): skinningMatrices(jointGlobals(...)).
std::vector<Matrix4> poseMatrices(const Rig& rig, int animation, double seconds);

/// Floats per joint of a palette: the three rows of its skinning matrix (the last row of an
/// affine matrix, 0 0 0 1, is left out).
constexpr int kPaletteFloats = 12;

/// Appends the first three rows of every matrix of `matrices` to `palette` as floats, joint
/// after joint: the palette a vertex shader skins with (shaders/SkinningVS.glsl).
void appendPaletteRows(const std::vector<Matrix4>& matrices, std::vector<float>& palette);

/// Poses `bindPoints` (#V x 3) by linear blend skinning: p' = sum_k w_k M[j_k] p.
/// @throws tc::InputError when the sizes of the points, the skin and the matrices disagree
std::vector<double> skinPoints(const std::vector<double>& bindPoints, const SkinWeights& skin,
  const std::vector<Matrix4>& matrices);
} // namespace tc
