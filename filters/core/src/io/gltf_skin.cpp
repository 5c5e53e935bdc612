// SPDX-License-Identifier: BSD-3-Clause
#include "io/gltf_skin.h"

#include <Eigen/Geometry>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>

namespace tc
{
namespace detail
{
int addGltfView(tinygltf::Model& model, const void* bytes, size_t n, int target)
{
  std::vector<unsigned char>& data = model.buffers[0].data;
  data.resize((data.size() + 3) / 4 * 4, 0);
  tinygltf::BufferView view;
  view.buffer = 0;
  view.byteOffset = data.size();
  view.byteLength = n;
  view.target = target;
  data.insert(data.end(), static_cast<const unsigned char*>(bytes),
    static_cast<const unsigned char*>(bytes) + n);
  model.bufferViews.push_back(view);
  return static_cast<int>(model.bufferViews.size()) - 1;
}

int addGltfFloats(tinygltf::Model& model, const std::vector<float>& values, int type,
  int components, bool bounds, int target)
{
  tinygltf::Accessor a;
  a.bufferView = addGltfView(model, values.data(), values.size() * sizeof(float), target);
  a.componentType = TINYGLTF_COMPONENT_TYPE_FLOAT;
  a.type = type;
  a.count = values.size() / static_cast<size_t>(components);
  if (bounds)
  {
    a.minValues.assign(components, std::numeric_limits<double>::max());
    a.maxValues.assign(components, std::numeric_limits<double>::lowest());
    for (size_t i = 0; i < values.size(); ++i)
    {
      const size_t k = i % static_cast<size_t>(components);
      a.minValues[k] = std::min(a.minValues[k], double(values[i]));
      a.maxValues[k] = std::max(a.maxValues[k], double(values[i]));
    }
  }
  model.accessors.push_back(a);
  return static_cast<int>(model.accessors.size()) - 1;
}

namespace
{
template <typename Id>
int addJointIds(tinygltf::Model& model, const std::vector<int32_t>& ids, int componentType)
{
  const std::vector<Id> narrow(ids.begin(), ids.end());
  tinygltf::Accessor a;
  a.bufferView =
    addGltfView(model, narrow.data(), narrow.size() * sizeof(Id), TINYGLTF_TARGET_ARRAY_BUFFER);
  a.componentType = componentType;
  a.type = TINYGLTF_TYPE_VEC4;
  a.count = ids.size() / kMaxInfluences;
  model.accessors.push_back(a);
  return static_cast<int>(model.accessors.size()) - 1;
}

/// Eigen's view of a row-major tc::Matrix4.
Eigen::Affine3d affine(const Matrix4& m)
{
  return Eigen::Affine3d(Eigen::Map<const Eigen::Matrix<double, 4, 4, Eigen::RowMajor>>(m.data()));
}

/// `m` column-major, as glTF stores matrices (tc's are row-major).
std::vector<double> columnMajor(const Matrix4& m)
{
  std::vector<double> out(16);
  for (int c = 0; c < 4; ++c)
  {
    for (int r = 0; r < 4; ++r)
    {
      out[size_t(4 * c + r)] = m[size_t(4 * r + c)];
    }
  }
  return out;
}

/// The joint whose transform and keys node j carries: a second joint of a node takes the
/// first's (as tc::jointGlobals poses it).
int32_t sourceJoint(const Skeleton& skeleton, size_t j)
{
  const int32_t same = skeleton.joints[j].sameNodeAs;
  return same >= 0 ? same : static_cast<int32_t>(j);
}

bool isKeyed(const JointTrack& t)
{
  return !t.positions.empty() || !t.rotations.empty() || !t.scales.empty();
}

/// Whether an animation glTF can hold (keyframed, see gltf_export.h) keys joint `joint`.
bool isAnimated(const Rig& rig, int32_t joint)
{
  for (const Animation& a : rig.animations)
  {
    for (const JointTrack& t : a.tracks)
    {
      if (a.frameTimes.empty() && t.joint == joint && isKeyed(t))
      {
        return true;
      }
    }
  }
  return false;
}

/// The node's rest transform: T R S decomposed as tc::jointGlobals decomposes a rest transform
/// for the components a track does not key (the polar decomposition, S its diagonal), so
/// that keyed and unkeyed components compose exactly as there. A node no animation moves and
/// whose transform T R S cannot say (a shear) keeps it as a matrix, which glTF allows there.
void setRestTransform(tinygltf::Node& node, const Matrix4& rest, bool animated)
{
  const Eigen::Affine3d m = affine(rest);
  Eigen::Matrix3d rotation, scaling;
  m.computeRotationScaling(&rotation, &scaling);
  const Eigen::Quaterniond q(rotation);
  const Eigen::Vector3d s = scaling.diagonal();
  const Eigen::Affine3d trs = Eigen::Translation3d(m.translation()) * q * Eigen::Scaling(s);
  const double size = std::max(1.0, m.matrix().cwiseAbs().maxCoeff());
  if (!animated && !((trs.matrix() - m.matrix()).cwiseAbs().maxCoeff() <= 1e-12 * size))
  {
    node.matrix = columnMajor(rest);
    return;
  }
  node.translation = { m.translation().x(), m.translation().y(), m.translation().z() };
  node.rotation = { q.x(), q.y(), q.z(), q.w() }; // glTF's order; tc's is w, x, y, z
  node.scale = { s.x(), s.y(), s.z() };
}

void addSkin(tinygltf::Model& model, const Skeleton& skeleton, int first)
{
  tinygltf::Skin skin;
  skin.name = "TriChart";
  std::vector<float> inverseBinds;
  for (size_t j = 0; j < skeleton.joints.size(); ++j)
  {
    skin.joints.push_back(first + static_cast<int>(j));
    for (const double x : columnMajor(skeleton.joints[j].inverseBind))
    {
      inverseBinds.push_back(static_cast<float>(x));
    }
  }
  skin.inverseBindMatrices = addGltfFloats(model, inverseBinds, TINYGLTF_TYPE_MAT4, 16, false, 0);
  model.skins.push_back(skin);
}

/// `times` and `values` (components each) with a held key at `duration` when the keys end
/// before it, so that the animation's length (glTF's: its last input time) stays `duration`.
template <size_t N>
std::pair<std::vector<float>, std::vector<float>> heldKeys(const std::vector<double>& times,
  const std::vector<std::array<double, N>>& values, double duration, bool quaternion)
{
  std::vector<float> in(times.begin(), times.end()), out;
  for (const std::array<double, N>& v : values)
  {
    for (size_t k = 0; k < N; ++k)
    {
      // tc's quaternions are w, x, y, z; glTF's x, y, z, w.
      out.push_back(static_cast<float>(quaternion ? v[(k + 1) % 4] : v[k]));
    }
  }
  if (!times.empty() && duration > times.back())
  {
    in.push_back(static_cast<float>(duration));
    out.insert(out.end(), out.end() - long(N), out.end());
  }
  return { in, out };
}

/// One LINEAR sampler of `times` and `values` (linear for translation and scale; for rotation
/// glTF's LINEAR is the spherical interpolation tc::jointGlobals does), with a channel on each
/// of `nodes`.
template <size_t N>
void addChannels(tinygltf::Model& model, tinygltf::Animation& animation,
  const std::vector<double>& times, const std::vector<std::array<double, N>>& values,
  double duration, const std::string& path, const std::vector<int>& nodes)
{
  if (times.empty() || nodes.empty())
  {
    return;
  }
  const auto [in, out] = heldKeys(times, values, duration, path == "rotation");
  tinygltf::AnimationSampler sampler;
  sampler.input = addGltfFloats(model, in, TINYGLTF_TYPE_SCALAR, 1, true, 0); // min, max required
  sampler.output =
    addGltfFloats(model, out, N == 4 ? TINYGLTF_TYPE_VEC4 : TINYGLTF_TYPE_VEC3, int(N), false, 0);
  sampler.interpolation = "LINEAR";
  animation.samplers.push_back(sampler);
  for (const int node : nodes)
  {
    tinygltf::AnimationChannel channel;
    channel.sampler = static_cast<int>(animation.samplers.size()) - 1;
    channel.target_node = node;
    channel.target_path = path;
    animation.channels.push_back(channel);
  }
}

/// The nodes that carry joint `joint`'s keys: its own and those of its second joints.
std::vector<int> trackNodes(const Skeleton& skeleton, int32_t joint, int first)
{
  std::vector<int> nodes;
  for (size_t j = 0; j < skeleton.joints.size(); ++j)
  {
    if (sourceJoint(skeleton, j) == joint)
    {
      nodes.push_back(first + static_cast<int>(j));
    }
  }
  return nodes;
}
} // namespace

void addGltfSkinAttributes(tinygltf::Model& model, const std::vector<float>& skinValues,
  size_t jointCount, tinygltf::Primitive& primitive)
{
  std::vector<int32_t> ids;
  std::vector<float> weights;
  for (size_t v = 0; v + kSkinValues <= skinValues.size(); v += kSkinValues)
  {
    const float* w = skinValues.data() + v + kMaxInfluences;
    const float sum =
      std::max(0.0f, w[0]) + std::max(0.0f, w[1]) + std::max(0.0f, w[2]) + std::max(0.0f, w[3]);
    for (int k = 0; k < kMaxInfluences; ++k)
    {
      const long id = std::lround(skinValues[v + size_t(k)]);
      ids.push_back(static_cast<int32_t>(std::clamp(id, 0L, long(jointCount) - 1)));
      // glTF requires weights that sum to 1 (Khronos, 3.7.3.3), tc poses the file's as given.
      weights.push_back(sum > 0.0f ? std::max(0.0f, w[k]) / sum : (k == 0 ? 1.0f : 0.0f));
    }
  }
  primitive.attributes["JOINTS_0"] = jointCount < 256
    ? addJointIds<uint8_t>(model, ids, TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE)
    : addJointIds<uint16_t>(model, ids, TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT);
  primitive.attributes["WEIGHTS_0"] = addGltfFloats(
    model, weights, TINYGLTF_TYPE_VEC4, kMaxInfluences, false, TINYGLTF_TARGET_ARRAY_BUFFER);
}

std::vector<int> addGltfSkeleton(tinygltf::Model& model, const Rig& rig)
{
  const Skeleton& skeleton = rig.skeleton;
  const int first = static_cast<int>(model.nodes.size());
  std::vector<int> roots;
  for (size_t j = 0; j < skeleton.joints.size(); ++j)
  {
    const Joint& joint = skeleton.joints[j];
    const int32_t source = sourceJoint(skeleton, j);
    tinygltf::Node node;
    // A second joint of a node is a copy of it under the same parent; its name differs so
    // that readers matching bones by name keep them apart.
    node.name = joint.sameNodeAs >= 0 ? joint.name + ".bind" + std::to_string(j) : joint.name;
    setRestTransform(node, skeleton.joints[size_t(source)].restLocal, isAnimated(rig, source));
    model.nodes.push_back(node);
    if (joint.parent >= 0)
    {
      model.nodes[size_t(first + joint.parent)].children.push_back(first + int(j));
    }
    else
    {
      roots.push_back(first + static_cast<int>(j));
    }
  }
  addSkin(model, skeleton, first);
  return roots;
}

void addGltfAnimations(tinygltf::Model& model, const Rig& rig, int firstJointNode)
{
  for (const Animation& a : rig.animations)
  {
    if (!a.frameTimes.empty() || a.tracks.empty())
    {
      continue; // sampled poses: see gltfRigNotes
    }
    tinygltf::Animation animation;
    animation.name = a.name;
    for (const JointTrack& t : a.tracks)
    {
      if (t.joint < 0 || size_t(t.joint) >= rig.skeleton.joints.size())
      {
        continue;
      }
      const std::vector<int> nodes = trackNodes(rig.skeleton, t.joint, firstJointNode);
      addChannels(model, animation, t.positionTimes, t.positions, a.duration, "translation", nodes);
      addChannels(model, animation, t.rotationTimes, t.rotations, a.duration, "rotation", nodes);
      addChannels(model, animation, t.scaleTimes, t.scales, a.duration, "scale", nodes);
    }
    if (!animation.channels.empty())
    {
      model.animations.push_back(animation);
    }
  }
}

std::vector<std::string> gltfRigNotes(const Rig& rig)
{
  std::vector<std::string> notes;
  for (size_t k = 0; k < rig.animations.size(); ++k)
  {
    const Animation& a = rig.animations[k];
    if (!a.frameTimes.empty())
    {
      notes.push_back("animation " + std::to_string(k) + " '" + a.name + "' is sampled poses of " +
        "affine proxy bones, which glTF's translation, rotation and scale keys cannot hold: " +
        "not exported");
    }
  }
  return notes;
}
} // namespace detail
} // namespace tc
