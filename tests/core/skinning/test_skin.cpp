// SPDX-License-Identifier: BSD-3-Clause
#include "tc/common/errors.h"
#include "tc/skinning/skin.h"

#include "skin_fixtures.h"

#include <gtest/gtest.h>

#include <cmath>
#include <vector>

namespace
{
using tctest::translation;

/// Two joints: a root at the origin and a child one unit up x; the child turns about z by a
/// quarter turn over one second.
struct Arm
{
  tc::Skeleton skeleton;
  tc::Animation animation;

  Arm()
  {
    skeleton.joints.resize(2);
    skeleton.joints[0].name = "root";
    skeleton.joints[0].restLocal = tc::identityMatrix();
    skeleton.joints[0].inverseBind = tc::identityMatrix();
    skeleton.joints[1].name = "child";
    skeleton.joints[1].parent = 0;
    skeleton.joints[1].restLocal = translation(1, 0, 0);
    skeleton.joints[1].inverseBind = translation(-1, 0, 0);
    animation.duration = 1.0;
    tc::JointTrack turn;
    turn.joint = 1;
    turn.rotationTimes = { 0.0, 1.0 };
    turn.rotations = { { 1, 0, 0, 0 }, { std::sqrt(0.5), 0, 0, std::sqrt(0.5) } };
    animation.tracks.push_back(turn);
  }
};
} // namespace

TEST(Skin, AJointTurnsItsPointsAndKeepsItsRestTranslation)
{
  const Arm arm;
  tc::SkinWeights skin;
  tc::addSkinPoint({ { 1, 1.0f } }, 0, skin); // (2, 0, 0) follows the child
  tc::addSkinPoint({ { 0, 1.0f } }, 0, skin); // (2, 0, 0) stays with the root
  tc::addSkinPoint({ { 0, 0.5f }, { 1, 0.5f } }, 0, skin);
  const std::vector<double> bind = { 2, 0, 0, 2, 0, 0, 2, 0, 0 };
  const auto pose = [&](double t)
  {
    return tc::skinPoints(bind, skin,
      tc::skinningMatrices(arm.skeleton, tc::jointGlobals(arm.skeleton, &arm.animation, t)));
  };
  const std::vector<double> end = pose(1.0);
  // The child's point turns a quarter about (1, 0, 0): (1, 1, 0); the blend lies half-way.
  EXPECT_NEAR(end[0], 1.0, 1e-12);
  EXPECT_NEAR(end[1], 1.0, 1e-12);
  EXPECT_NEAR(end[3], 2.0, 1e-12);
  EXPECT_NEAR(end[6], 1.5, 1e-12);
  EXPECT_NEAR(end[7], 0.5, 1e-12);
  // Half-way in time is an eighth of a turn (slerp), and the keys hold outside [0, 1].
  const std::vector<double> half = pose(0.5);
  EXPECT_NEAR(half[0], 1.0 + std::sqrt(0.5), 1e-12);
  EXPECT_NEAR(half[1], std::sqrt(0.5), 1e-12);
  EXPECT_EQ(pose(7.0), end);
  EXPECT_EQ(pose(-1.0), bind);
  // Without an animation, the rest pose: the bind points.
  EXPECT_EQ(tc::skinPoints(bind, skin,
              tc::skinningMatrices(arm.skeleton, tc::jointGlobals(arm.skeleton, nullptr, 0.0))),
    bind);
}

TEST(Skin, TheFourLargestInfluencesAreKeptAndRenormalizedOnlyWhenCut)
{
  tc::SkinWeights skin;
  tc::addSkinPoint({ { 3, 0.1f }, { 1, 0.3f }, { 2, 0.2f }, { 5, 0.25f }, { 4, 0.15f } }, 0, skin);
  EXPECT_EQ(skin.joints, (std::vector<int32_t>{ 1, 5, 2, 4 }));
  EXPECT_NEAR(skin.weights[0], 0.3f / 0.9f, 1e-6);
  EXPECT_NEAR(skin.weights[0] + skin.weights[1] + skin.weights[2] + skin.weights[3], 1.0, 1e-6);
  EXPECT_EQ(skin.pointsOverLimit, 1);
  EXPECT_NEAR(skin.largestDropped, 0.1, 1e-7);
  // Uncut weights stay as given, also when they do not sum to 1 (Assimp's definition).
  tc::addSkinPoint({ { 2, 0.6f }, { 7, 0.7f } }, 0, skin);
  EXPECT_FLOAT_EQ(skin.weights[4], 0.7f);
  EXPECT_FLOAT_EQ(skin.weights[5], 0.6f);
  EXPECT_EQ(skin.weights[6], 0.0f);
  EXPECT_EQ(skin.pointsOffUnitSum, 1);
  EXPECT_NEAR(skin.largestSum, 1.3, 1e-6);
  // No usable weight: bound to the fallback joint.
  tc::addSkinPoint({ { 2, 0.0f }, { 3, std::nanf("") } }, 9, skin);
  EXPECT_EQ(skin.joints[8], 9);
  EXPECT_EQ(skin.weights[8], 1.0f);
  EXPECT_EQ(skin.joints.size(), 12u);
}

TEST(Skin, KeyTimesAndBadSizes)
{
  const Arm arm;
  EXPECT_EQ(tc::animationKeyTimes(arm.animation), (std::vector<double>{ 0.0, 1.0 }));
  tc::Animation late = arm.animation;
  late.duration = 2.0;
  late.tracks[0].rotationTimes = { 0.5, 3.0 };
  EXPECT_EQ(tc::animationKeyTimes(late), (std::vector<double>{ 0.0, 0.5, 2.0 }));
  tc::SkinWeights skin;
  tc::addSkinPoint({ { 1, 1.0f } }, 0, skin);
  EXPECT_THROW(
    tc::skinPoints({ 0, 0, 0, 1, 1, 1 }, skin, { tc::identityMatrix() }), tc::InputError);
  EXPECT_THROW(tc::skinPoints({ 0, 0, 0 }, skin, { tc::identityMatrix() }), tc::InputError);
}

TEST(Skin, BlendedInfluencesAreTheUnionOfJointsWithInterpolatedWeights)
{
  tc::PointSkin a, b, c;
  a.joints = { 2, 7, 0, 0 };
  a.weights = { 0.75f, 0.25f, 0.0f, 0.0f };
  b.joints = { 7, 3, 0, 0 };
  b.weights = { 0.5f, 0.5f, 0.0f, 0.0f };
  // Two points, at most 4 joints in all: the linear blend of the weights, by joint.
  const tc::PointSkin ab[2] = { a, b };
  const double half[2] = { 0.5, 0.5 };
  const tc::PointSkin m = tc::blendInfluences(2, ab, half);
  EXPECT_EQ(m.joints, (std::array<int32_t, 4>{ 2, 7, 3, 0 })); // a tie goes to the lower id
  EXPECT_FLOAT_EQ(m.weights[0], 0.375f);
  EXPECT_FLOAT_EQ(m.weights[1], 0.375f);
  EXPECT_FLOAT_EQ(m.weights[2], 0.25f);
  EXPECT_EQ(m.weights[3], 0.0f);
  // Three points with six joints: the 4 largest, scaled to the interpolated total (1).
  c.joints = { 4, 5, 6, 0 };
  c.weights = { 0.5f, 0.3f, 0.2f, 0.0f };
  const tc::PointSkin abc[3] = { a, b, c };
  const double third[3] = { 0.4, 0.3, 0.3 };
  const tc::PointSkin n = tc::blendInfluences(3, abc, third);
  EXPECT_EQ(n.joints[0], 2); // 0.4 x 0.75 = 0.30
  EXPECT_EQ(n.joints[1], 7); // 0.10 + 0.15 = 0.25
  double sum = 0.0;
  for (const float w : n.weights)
  {
    sum += w;
  }
  EXPECT_NEAR(sum, 1.0, 1e-6);
  for (const int32_t j : n.joints)
  {
    EXPECT_TRUE(j == 2 || j == 7 || j == 3 || j == 4 || j == 5 || j == 6) << j; // never a blend
  }
  // A corner keeps its own skin.
  const double one[1] = { 1.0 };
  const tc::PointSkin own = tc::blendInfluences(1, &a, one);
  EXPECT_EQ(own.joints[0], 2);
  EXPECT_EQ(own.weights[0], 0.75f);
}

TEST(Skin, SampledPosesInterpolateBetweenFramesAndRoundTripThroughTheRigText)
{
  tc::Rig rig;
  rig.skeleton.joints.resize(1);
  rig.skeleton.joints[0].name = "proxy 0";
  rig.skeleton.joints[0].restLocal = tc::identityMatrix();
  rig.skeleton.joints[0].inverseBind = tc::identityMatrix();
  tc::Animation frames;
  frames.name = "frames";
  frames.duration = 2.0;
  frames.frameTimes = { 0.0, 1.0, 2.0 };
  tc::Matrix4 sheared = translation(2, 0, 0);
  sheared[1] = 0.5; // x += y / 2: a bone that shears, which no track can say
  frames.frameGlobals = { { tc::identityMatrix() }, { sheared }, { translation(0, 0, 4) } };
  rig.animations.push_back(frames);
  const tc::Rig back = tc::decodeRig(tc::encodeRig(rig));
  ASSERT_EQ(back.animations[0].frameGlobals.size(), 3u);
  EXPECT_EQ(back.animations[0].frameGlobals[1][0], sheared);
  EXPECT_EQ(tc::animationKeyTimes(back.animations[0]), (std::vector<double>{ 0.0, 1.0, 2.0 }));
  // At a frame its pose; half-way the matrices blended; outside, held.
  EXPECT_EQ(tc::jointGlobals(back.skeleton, &back.animations[0], 1.0)[0], sheared);
  const tc::Matrix4 half = tc::jointGlobals(back.skeleton, &back.animations[0], 1.5)[0];
  EXPECT_DOUBLE_EQ(half[3], 1.0);
  EXPECT_DOUBLE_EQ(half[11], 2.0);
  EXPECT_DOUBLE_EQ(half[1], 0.25);
  EXPECT_EQ(tc::jointGlobals(back.skeleton, &back.animations[0], 9.0)[0], translation(0, 0, 4));
  // A pose per frame of the skeleton's joint count, or an error.
  tc::Animation broken = frames;
  broken.frameGlobals.pop_back();
  EXPECT_THROW(tc::jointGlobals(rig.skeleton, &broken, 0.5), tc::InputError);
}
