// SPDX-License-Identifier: BSD-3-Clause
#include "octahedron_atlas.h"
#include "pipeline_fixture.h"
#include "tc/common/errors.h"
#include "tc/gim/atlas.h"
#include "tc/gim/geometry_images.h"
#include "tc/gim/path_tracing.h"
#include "tc/skinning/skinned_boxes.h"

#include "skin_fixtures.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <iostream>
#include <random>
#include <vector>

namespace
{
constexpr double kPi = 3.14159265358979323846;
/// The width of a joint's Gaussian weight, as a fraction of the chain.
constexpr double kWidth = 0.1;

using tctest::translation;

/// A quaternion (w, x, y, z) turning by `degrees` about unit `axis`.
std::array<double, 4> turn(double degrees, const std::array<double, 3>& axis)
{
  const double h = 0.5 * degrees * kPi / 180.0;
  return { std::cos(h), std::sin(h) * axis[0], std::sin(h) * axis[1], std::sin(h) * axis[2] };
}

tc::JointTrack rotationTrack(int32_t joint, const std::vector<double>& times,
  const std::vector<double>& degrees, const std::array<double, 3>& axis)
{
  tc::JointTrack track;
  track.joint = joint;
  track.rotationTimes = times;
  for (double d : degrees)
  {
    track.rotations.push_back(turn(d, axis));
  }
  return track;
}

/// A chain of 3 joints along x through [x0, x0 + 3 step], and two animations that bend it: "bend"
/// about z and "twist" about y and x.
tc::Rig chainRig(double x0, double step)
{
  tc::Rig rig;
  for (int32_t j = 0; j < 3; ++j)
  {
    tc::Joint joint;
    joint.name = "bone " + std::to_string(j);
    joint.parent = j - 1;
    joint.restLocal = j == 0 ? translation(x0, 0, 0) : translation(step, 0, 0);
    joint.inverseBind = tc::inverseAffine(translation(x0 + j * step, 0, 0));
    rig.skeleton.joints.push_back(joint);
  }
  tc::Animation bend;
  bend.name = "bend";
  bend.duration = 2.0;
  bend.tracks = { rotationTrack(1, { 0, 1, 2 }, { 0, 60, -40 }, { 0, 0, 1 }),
    rotationTrack(2, { 0, 1, 2 }, { 0, -50, 70 }, { 0, 0, 1 }) };
  tc::Animation twist;
  twist.name = "twist";
  twist.duration = 1.5;
  twist.tracks = { rotationTrack(1, { 0, 0.75, 1.5 }, { 0, 45, 0 }, { 0, 1, 0 }),
    rotationTrack(2, { 0, 1.5 }, { 0, 90 }, { 1, 0, 0 }) };
  rig.animations = { bend, twist };
  return rig;
}

/// The skin of a point at chain parameter t = (x - x0) / (3 step): Gaussian weights of the 3
/// joints (centres 1/6, 1/2, 5/6, width kWidth), normalized, largest first.
std::array<float, tc::kSkinValues> chainSkin(double t)
{
  std::array<std::pair<float, int>, 3> w{};
  float sum = 0.0f;
  for (int j = 0; j < 3; ++j)
  {
    const double c = (2 * j + 1) / 6.0;
    w[static_cast<size_t>(j)] = { static_cast<float>(std::exp(-std::pow((t - c) / kWidth, 2))), j };
    sum += w[static_cast<size_t>(j)].first;
  }
  std::sort(w.begin(), w.end(), [](const auto& a, const auto& b) { return a.first > b.first; });
  std::array<float, tc::kSkinValues> skin{};
  for (int k = 0; k < 3; ++k)
  {
    skin[static_cast<size_t>(k)] = static_cast<float>(w[static_cast<size_t>(k)].second);
    skin[static_cast<size_t>(tc::kMaxInfluences + k)] = w[static_cast<size_t>(k)].first / sum;
  }
  return skin;
}

/// `atlas` skinned to a chain along x over its x range: a Skin attribute that is a function of
/// each texel's position (so the copies of a shared side agree) and chainRig.
tc::Atlas withChain(tc::Atlas atlas)
{
  float lo = INFINITY, hi = -INFINITY;
  tc::forEachImageSample(atlas, 0,
    [&](int32_t, int32_t, int32_t, int32_t, size_t t)
    {
      lo = std::min(lo, atlas.images[0].data[0][3 * t]);
      hi = std::max(hi, atlas.images[0].data[0][3 * t]);
    });
  atlas.attributes.push_back({ tc::kAtlasSkin, tc::kSkinValues });
  for (tc::AtlasImage& image : atlas.images)
  {
    std::vector<float> skin;
    for (size_t t = 0; t < image.data[0].size() / 3; ++t)
    {
      const auto s = chainSkin((image.data[0][3 * t] - lo) / (hi - lo));
      skin.insert(skin.end(), s.begin(), s.end());
    }
    image.data.push_back(std::move(skin));
  }
  atlas.rig = chainRig(lo, (hi - lo) / 3.0);
  return atlas;
}

const tc::Atlas& skinnedBunny()
{
  static const tc::Atlas atlas = []
  {
    const tctest::PipelineCase* bunny = tctest::pipelineCase(tctest::pipelineMeshPath("bunny_npm"));
    return withChain(tc::buildGeometryImages(
      tc::tracePaths(bunny->mesh, bunny->result), bunny->result, {}, {}, {}));
  }();
  return atlas;
}

/// Samples of every chart of `atlas` outside their posed skinned box at `count` random times of
/// every animation; `tested` counts the samples checked.
int64_t samplesOutside(
  const tc::Atlas& atlas, const tc::SkinnedBoxesResult& fitted, int count, int64_t& tested)
{
  const int32_t skinAttr = tc::findAttribute(atlas, tc::kAtlasSkin);
  std::mt19937 random(20);
  int64_t outside = 0;
  for (const tc::Animation& animation : atlas.rig.animations)
  {
    std::uniform_real_distribution<double> time(0.0, animation.duration);
    for (int k = 0; k < count; ++k)
    {
      const std::vector<tc::Matrix4> m = tc::skinningMatrices(
        atlas.rig.skeleton, tc::jointGlobals(atlas.rig.skeleton, &animation, time(random)));
      for (size_t c = 0; c < atlas.charts.size(); ++c)
      {
        const tc::BoxFrame frame = tc::posedBoxFrame(tc::poseBox(fitted.boxes[c], m));
        const int32_t d = atlas.charts[c].maxLevel, n = 1 << d, ci = static_cast<int32_t>(c);
        for (int32_t j = 0; j <= n; ++j)
        {
          for (int32_t i = 0; i + j <= n; ++i)
          {
            const float* p = tc::atlasSample(atlas, ci, 0, d, i, j);
            const float* s = tc::atlasSample(atlas, ci, skinAttr, d, i, j);
            std::array<double, 3> q{ 0, 0, 0 };
            for (int a = 0; a < tc::kMaxInfluences; ++a)
            {
              const tc::Matrix4& t = m[static_cast<size_t>(s[a])];
              for (int r = 0; r < 3; ++r)
              {
                q[r] += s[tc::kMaxInfluences + a] *
                  (t[4 * r] * p[0] + t[4 * r + 1] * p[1] + t[4 * r + 2] * p[2] + t[4 * r + 3]);
              }
            }
            outside += tc::boxContains(frame, q) ? 0 : 1;
            ++tested;
          }
        }
      }
    }
  }
  return outside;
}
} // namespace

TEST(SkinnedBoxes, AnAffinelyPosedBoxIsItsParallelepiped)
{
  tc::SkinnedBox box;
  box.corners = { 1, 2, 3, 3, 2, 3, 1, 5, 3, 1, 2, 4 }; // c0 + (2,0,0), (0,3,0), (0,0,1)
  for (tc::PointSkin& s : box.skin)
  {
    s.joints = { 1, 0, 0, 0 };
    s.weights = { 1, 0, 0, 0 };
  }
  tc::Matrix4 shear = tc::identityMatrix();
  shear[1] = 0.5; // x += 0.5 y
  const std::vector<tc::Matrix4> m = { tc::identityMatrix(),
    tc::multiply(translation(4, 0, 1), shear) };
  const tc::BoxFrame frame = tc::posedBoxFrame(tc::poseBox(box, m));
  for (size_t r = 0; r < 3; ++r)
  {
    EXPECT_NEAR(frame.lo[r], 0.0, 1e-12);
    EXPECT_NEAR(frame.hi[r], 1.0, 1e-12);
  }
  EXPECT_NEAR(frame.volume, 6.0, 1e-12);
  // The posed centre (2 + 0.5 * 3.5 + 4, 3.5, 4.5) is inside, a point past the top is not.
  EXPECT_TRUE(tc::boxContains(frame, { 7.75, 3.5, 4.5 }));
  EXPECT_FALSE(tc::boxContains(frame, { 7.75, 3.5, 5.01 }));
}

TEST(SkinnedBoxes, RefusesAnAtlasWithoutSkin)
{
  EXPECT_THROW(
    tc::fitSkinnedBoxes(tctest::octahedronAtlas({ 2, 2, 2, 2, 2, 2, 2, 2 })), tc::InputError);
}

TEST(SkinnedBoxes, HoldTheBentBunnyAtRandomTimes)
{
  const tc::Atlas& atlas = skinnedBunny();
  const tc::SkinnedBoxesResult fitted = tc::fitSkinnedBoxes(atlas);
  ASSERT_EQ(fitted.boxes.size(), atlas.charts.size());
  for (const tc::SkinnedBox& box : fitted.boxes)
  {
    for (const tc::PointSkin& s : box.skin)
    {
      float sum = 0.0f;
      for (float w : s.weights)
      {
        EXPECT_GE(w, 0.0f);
        sum += w;
      }
      EXPECT_NEAR(sum, 1.0f, 1e-5f);
    }
  }
  int64_t tested = 0;
  const int64_t outside = samplesOutside(atlas, fitted, 50, tested);
  std::cout << "[ figures  ] bunny: " << atlas.charts.size() << " charts, " << fitted.frames
            << " fitted frames, volume ratio mean " << fitted.meanVolumeRatio << " median "
            << fitted.medianVolumeRatio << " largest " << fitted.largestVolumeRatio << "; "
            << outside << " of " << tested << " samples outside at 2 x 50 random times\n";
  EXPECT_EQ(outside, 0);
  // The mean is dominated by a few flat coarse charts across the bend (ratios up to 1e6, see
  // the report of issue 20 item 4): the median is what holds.
  EXPECT_LE(fitted.medianVolumeRatio, 2.0);
  EXPECT_GE(fitted.medianVolumeRatio, 1.0);
}
