// SPDX-License-Identifier: BSD-3-Clause
// The rig as JSON: one text for the readers' field array and the atlas file's metadata.
#include "tc/common/errors.h"
#include "tc/skinning/skin.h"

#include <nlohmann/json.hpp>

#include <cmath>

namespace tc
{
namespace
{
using Json = nlohmann::json;

template <typename Values>
Json flat(const Values& rows)
{
  Json out = Json::array();
  for (const auto& row : rows)
  {
    for (const double x : row)
    {
      out.push_back(x);
    }
  }
  return out;
}

Json trackJson(const JointTrack& t)
{
  return { { "joint", t.joint }, { "positionTimes", t.positionTimes },
    { "positions", flat(t.positions) }, { "rotationTimes", t.rotationTimes },
    { "rotations", flat(t.rotations) }, { "scaleTimes", t.scaleTimes },
    { "scales", flat(t.scales) } };
}

/// Reads the members of one JSON object with checks that name where a value is wrong.
class Reader
{
public:
  const Json& member(const Json& object, const char* name, const std::string& where) const
  {
    if (!object.is_object() || !object.contains(name))
    {
      fail(where + " has no '" + name + "'");
    }
    return object.at(name);
  }

  double number(const Json& value, const std::string& where) const
  {
    if (!value.is_number() || !std::isfinite(value.get<double>()))
    {
      fail(where + " is not a finite number");
    }
    return value.get<double>();
  }

  int32_t integer(const Json& value, int64_t low, int64_t high, const std::string& where) const
  {
    if (!value.is_number_integer() || value.get<int64_t>() < low || value.get<int64_t>() > high)
    {
      fail(where + " is not an integer in " + std::to_string(low) + " .. " + std::to_string(high));
    }
    return static_cast<int32_t>(value.get<int64_t>());
  }

  std::vector<double> numbers(const Json& value, size_t multiple, const std::string& where) const
  {
    if (!value.is_array() || value.size() % multiple != 0)
    {
      fail(where + " is not an array of a multiple of " + std::to_string(multiple) + " numbers");
    }
    std::vector<double> out;
    for (size_t k = 0; k < value.size(); ++k)
    {
      out.push_back(number(value[k], where + "[" + std::to_string(k) + "]"));
    }
    return out;
  }

  [[noreturn]] void fail(const std::string& what) const
  {
    throw InputError("the rig is damaged: " + what);
  }
};

Matrix4 matrix(const Reader& in, const Json& value, const std::string& where)
{
  const std::vector<double> m = in.numbers(value, 16, where);
  if (m.size() != 16)
  {
    in.fail(where + " is not 16 numbers");
  }
  Matrix4 out;
  std::copy(m.begin(), m.end(), out.begin());
  return out;
}

/// Key times ascending, and one value of `n` numbers per time.
template <size_t N>
void keys(const Reader& in, const Json& track, const char* timesName, const char* valuesName,
  const std::string& where, std::vector<double>& times, std::vector<std::array<double, N>>& values)
{
  times = in.numbers(in.member(track, timesName, where), 1, where + "." + timesName);
  const std::vector<double> flatValues =
    in.numbers(in.member(track, valuesName, where), N, where + "." + valuesName);
  if (flatValues.size() != N * times.size() || !std::is_sorted(times.begin(), times.end()))
  {
    in.fail(where + ": " + timesName + " are not ascending, one per value of " + valuesName);
  }
  values.resize(times.size());
  for (size_t k = 0; k < times.size(); ++k)
  {
    std::copy_n(&flatValues[N * k], N, values[k].begin());
  }
}

Joint jointOf(const Reader& in, const Json& j, int32_t index)
{
  const std::string where = "joints[" + std::to_string(index) + "]";
  Joint joint;
  const Json& name = in.member(j, "name", where);
  if (!name.is_string())
  {
    in.fail(where + ".name is not text");
  }
  joint.name = name.get<std::string>();
  joint.parent = in.integer(in.member(j, "parent", where), -1, index - 1, where + ".parent");
  joint.sameNodeAs =
    in.integer(in.member(j, "sameNodeAs", where), -1, index - 1, where + ".sameNodeAs");
  joint.restLocal = matrix(in, in.member(j, "restLocal", where), where + ".restLocal");
  joint.inverseBind = matrix(in, in.member(j, "inverseBind", where), where + ".inverseBind");
  return joint;
}

/// The sampled poses of an animation ("frameTimes" ascending, one pose of #joints matrices in
/// "frameGlobals" per time), when it has them.
void sampledPoses(
  const Reader& in, const Json& a, const std::string& where, size_t joints, Animation& animation)
{
  if (!a.contains("frameTimes"))
  {
    return;
  }
  animation.frameTimes = in.numbers(a.at("frameTimes"), 1, where + ".frameTimes");
  const Json& frames = in.member(a, "frameGlobals", where);
  if (!frames.is_array() || frames.size() != animation.frameTimes.size() ||
    !std::is_sorted(animation.frameTimes.begin(), animation.frameTimes.end()))
  {
    in.fail(where + ": frameTimes are not ascending, one per pose of frameGlobals");
  }
  for (size_t k = 0; k < frames.size(); ++k)
  {
    const std::string at = where + ".frameGlobals[" + std::to_string(k) + "]";
    const std::vector<double> values = in.numbers(frames[k], 16, at);
    if (values.size() != 16 * joints)
    {
      in.fail(at + " is not one matrix per joint");
    }
    std::vector<Matrix4> pose(joints);
    for (size_t j = 0; j < joints; ++j)
    {
      std::copy_n(&values[16 * j], 16, pose[j].begin());
    }
    animation.frameGlobals.push_back(std::move(pose));
  }
}

Animation animationOf(const Reader& in, const Json& a, size_t index, int32_t joints)
{
  const std::string where = "animations[" + std::to_string(index) + "]";
  Animation animation;
  const Json& name = in.member(a, "name", where);
  if (!name.is_string())
  {
    in.fail(where + ".name is not text");
  }
  animation.name = name.get<std::string>();
  animation.duration = in.number(in.member(a, "duration", where), where + ".duration");
  animation.ticksPerSecond =
    in.number(in.member(a, "ticksPerSecond", where), where + ".ticksPerSecond");
  const Json& tracks = in.member(a, "tracks", where);
  if (!tracks.is_array() || animation.duration < 0)
  {
    in.fail(where + " has no track list or a negative duration");
  }
  for (size_t t = 0; t < tracks.size(); ++t)
  {
    const std::string at = where + ".tracks[" + std::to_string(t) + "]";
    JointTrack track;
    track.joint = in.integer(in.member(tracks[t], "joint", at), 0, joints - 1, at + ".joint");
    keys(in, tracks[t], "positionTimes", "positions", at, track.positionTimes, track.positions);
    keys(in, tracks[t], "rotationTimes", "rotations", at, track.rotationTimes, track.rotations);
    keys(in, tracks[t], "scaleTimes", "scales", at, track.scaleTimes, track.scales);
    animation.tracks.push_back(std::move(track));
  }
  sampledPoses(in, a, where, static_cast<size_t>(joints), animation);
  return animation;
}
} // namespace

std::string encodeRig(const Rig& rig)
{
  Json joints = Json::array();
  for (const Joint& j : rig.skeleton.joints)
  {
    joints.push_back({ { "name", j.name }, { "parent", j.parent }, { "sameNodeAs", j.sameNodeAs },
      { "restLocal", j.restLocal }, { "inverseBind", j.inverseBind } });
  }
  Json animations = Json::array();
  for (const Animation& a : rig.animations)
  {
    Json tracks = Json::array();
    for (const JointTrack& t : a.tracks)
    {
      tracks.push_back(trackJson(t));
    }
    Json frames = Json::array();
    for (const std::vector<Matrix4>& pose : a.frameGlobals)
    {
      frames.push_back(flat(pose));
    }
    animations.push_back(
      { { "name", a.name }, { "duration", a.duration }, { "ticksPerSecond", a.ticksPerSecond },
        { "tracks", tracks }, { "frameTimes", a.frameTimes }, { "frameGlobals", frames } });
  }
  // Invalid UTF-8 in a joint's name (a file's bytes) is replaced rather than refused.
  return Json{ { "joints", joints }, { "animations", animations } }.dump(
    -1, ' ', false, Json::error_handler_t::replace);
}

Rig decodeRig(const std::string& text)
{
  const Reader in;
  const Json root = Json::parse(text, nullptr, false);
  if (root.is_discarded())
  {
    in.fail("its text is not JSON");
  }
  const Json& joints = in.member(root, "joints", "the rig");
  const Json& animations = in.member(root, "animations", "the rig");
  if (!joints.is_array() || !animations.is_array() || joints.size() > (1u << 20))
  {
    in.fail("its joints or animations are not lists");
  }
  Rig rig;
  for (size_t j = 0; j < joints.size(); ++j)
  {
    rig.skeleton.joints.push_back(jointOf(in, joints[j], static_cast<int32_t>(j)));
  }
  for (size_t a = 0; a < animations.size(); ++a)
  {
    rig.animations.push_back(
      animationOf(in, animations[a], a, static_cast<int32_t>(joints.size())));
  }
  return rig;
}
} // namespace tc
