// SPDX-License-Identifier: BSD-3-Clause
#include "octahedron_atlas.h"
#include "pipeline_fixture.h"
#include "tc/common/errors.h"
#include "tc/gim/atlas.h"
#include "tc/gim/geometry_images.h"
#include "tc/gim/lod_selection.h"
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
using tctest::chainRig;
using tctest::chainSkin;
using tctest::translation;

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

/// The bent bunny's boxes, fitted once for all the tests that read them.
const tc::SkinnedBoxesResult& bunnyBoxes()
{
  static const tc::SkinnedBoxesResult fitted = tc::fitSkinnedBoxes(skinnedBunny());
  return fitted;
}

/// The bind position and skin of one finest-level sample.
std::array<double, 3> posedSample(const tc::Atlas& atlas, int32_t skinAttribute, int32_t chart,
  int32_t i, int32_t j, const std::vector<tc::Matrix4>& m)
{
  const int32_t d = atlas.charts[static_cast<size_t>(chart)].maxLevel;
  const float* p = tc::atlasSample(atlas, chart, 0, d, i, j);
  const float* s = tc::atlasSample(atlas, chart, skinAttribute, d, i, j);
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
  return q;
}

/// The posed box of LodCharts' layout (pivot, then the axes) as a BoxFrame, grown by `slack` on
/// every side.
tc::BoxFrame lodBoxFrame(const float* box, double slack)
{
  std::array<std::array<double, 3>, 4> corners{};
  std::array<std::array<double, 3>, 3> axes{};
  for (size_t r = 0; r < 3; ++r)
  {
    corners[0][r] = box[r];
  }
  for (size_t k = 0; k < 3; ++k)
  {
    double length = 0.0;
    for (size_t r = 0; r < 3; ++r)
    {
      axes[k][r] = box[3 + 3 * k + r];
      length += axes[k][r] * axes[k][r];
    }
    length = std::sqrt(length);
    for (size_t r = 0; r < 3; ++r)
    {
      corners[0][r] -= slack * axes[k][r] / length;
      axes[k][r] *= 1.0 + 2.0 * slack / length;
    }
  }
  for (size_t k = 0; k < 3; ++k)
  {
    for (size_t r = 0; r < 3; ++r)
    {
      corners[k + 1][r] = corners[0][r] + axes[k][r];
    }
  }
  return tc::posedBoxFrame(corners);
}

/// Samples outside their chart's posed box, at `count` random times of every animation: by
/// posedBoxFrame (double) in `outside`, by poseLodBoxes (float, LodCharts' layout, within 1e-5 of
/// the atlas's diagonal of the box: float rounding) in `outsideLod`; `tested` counts the samples
/// checked.
struct Containment
{
  int64_t outside = 0;
  int64_t outsideLod = 0;
  int64_t tested = 0;
};

Containment samplesOutside(const tc::Atlas& atlas, const tc::SkinnedBoxesResult& fitted, int count)
{
  const int32_t skinAttr = tc::findAttribute(atlas, tc::kAtlasSkin);
  const tc::LodSkinnedBoxes lod = tc::LodSkinnedBoxes::fromBoxes(fitted.boxes);
  std::vector<float> box(12 * atlas.charts.size()), area(atlas.charts.size());
  const std::array<double, 6> bounds =
    tc::drawnBounds(atlas, { 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1 });
  const double slack = 1e-5 *
    std::sqrt(std::pow(bounds[1] - bounds[0], 2) + std::pow(bounds[3] - bounds[2], 2) +
      std::pow(bounds[5] - bounds[4], 2));
  std::mt19937 random(20);
  Containment result;
  for (size_t a = 0; a < atlas.rig.animations.size(); ++a)
  {
    std::uniform_real_distribution<double> time(0.0, atlas.rig.animations[a].duration);
    for (int k = 0; k < count; ++k)
    {
      const std::vector<tc::Matrix4> m =
        tc::poseMatrices(atlas.rig, static_cast<int>(a), time(random));
      std::vector<float> palette;
      tc::appendPaletteRows(m, palette);
      tc::poseLodBoxes(
        lod, palette.data(), static_cast<int32_t>(m.size()), box.data(), area.data());
      for (size_t c = 0; c < atlas.charts.size(); ++c)
      {
        const tc::BoxFrame frame = tc::posedBoxFrame(tc::poseBox(fitted.boxes[c], m));
        const tc::BoxFrame lodFrame = lodBoxFrame(box.data() + 12 * c, slack);
        const int32_t n = 1 << atlas.charts[c].maxLevel, ci = static_cast<int32_t>(c);
        for (int32_t j = 0; j <= n; ++j)
        {
          for (int32_t i = 0; i + j <= n; ++i)
          {
            const std::array<double, 3> q = posedSample(atlas, skinAttr, ci, i, j, m);
            result.outside += tc::boxContains(frame, q) ? 0 : 1;
            result.outsideLod += tc::boxContains(lodFrame, q) ? 0 : 1;
            ++result.tested;
          }
        }
      }
    }
  }
  return result;
}

/// `atlas` (skinned by withChain) posed instead by one animation of sampled poses, as the proxy
/// bones of a deforming sequence are (tc::Animation::frameGlobals, interpolated linearly between
/// frames, and free to shear, which no track can): joints 1 and 2 shear along y by up to 0.6 of
/// their distance along x, and stretch by up to 30%, about their rest positions, over 6 frames.
tc::Atlas withSampledShear(tc::Atlas atlas)
{
  tc::Rig& rig = atlas.rig;
  const std::vector<tc::Matrix4> rest = tc::jointGlobals(rig.skeleton, nullptr, 0.0);
  tc::Animation sampled;
  sampled.name = "sampled shear";
  sampled.duration = 2.5;
  const double shear[6] = { 0.0, 0.6, -0.4, 0.3, -0.6, 0.0 };
  const double stretch[6] = { 1.0, 1.3, 0.8, 1.1, 0.9, 1.0 };
  for (int f = 0; f < 6; ++f)
  {
    sampled.frameTimes.push_back(0.5 * f);
    std::vector<tc::Matrix4> globals = rest;
    for (size_t j = 1; j < 3; ++j)
    {
      tc::Matrix4 deform = tc::identityMatrix();
      deform[0] = stretch[f];
      deform[4] = shear[f] * static_cast<double>(j);
      const tc::Matrix4 about = tc::multiply(translation(rest[j][3], rest[j][7], rest[j][11]),
        tc::multiply(deform, translation(-rest[j][3], -rest[j][7], -rest[j][11])));
      globals[j] = tc::multiply(about, rest[j]);
    }
    sampled.frameGlobals.push_back(globals);
  }
  rig.animations = { sampled };
  return atlas;
}

/// A random rigid motion: a rotation by up to 90 degrees about a random axis, then a
/// translation in [-1, 1]^3.
tc::Matrix4 randomMotion(std::mt19937& random)
{
  std::uniform_real_distribution<double> unit(-1.0, 1.0);
  std::array<double, 3> axis{ unit(random), unit(random), unit(random) };
  const double l = std::sqrt(axis[0] * axis[0] + axis[1] * axis[1] + axis[2] * axis[2]);
  for (double& x : axis)
  {
    x /= l;
  }
  const std::array<double, 4> q = tctest::turn(90.0 * unit(random), axis);
  const double w = q[0], x = q[1], y = q[2], z = q[3];
  tc::Matrix4 m = translation(unit(random), unit(random), unit(random));
  const double r[9] = { 1 - 2 * (y * y + z * z), 2 * (x * y - w * z), 2 * (x * z + w * y),
    2 * (x * y + w * z), 1 - 2 * (x * x + z * z), 2 * (y * z - w * x), 2 * (x * z - w * y),
    2 * (y * z + w * x), 1 - 2 * (x * x + y * y) };
  for (int i = 0; i < 3; ++i)
  {
    for (int k = 0; k < 3; ++k)
    {
      m[static_cast<size_t>(4 * i + k)] = r[3 * i + k];
    }
  }
  return m;
}

/// `count` boxes with random corners in [0, 1]^3 and per corner random weights of the same 4
/// random joints of `joints`.
std::vector<tc::SkinnedBox> randomBoxes(int count, int32_t joints, std::mt19937& random)
{
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  std::vector<tc::SkinnedBox> boxes(static_cast<size_t>(count));
  for (tc::SkinnedBox& box : boxes)
  {
    for (double& x : box.corners)
    {
      x = unit(random);
    }
    std::array<int32_t, 4> chosen{};
    for (int32_t& j : chosen)
    {
      j = static_cast<int32_t>(random() % static_cast<uint32_t>(joints));
    }
    for (tc::PointSkin& s : box.skin)
    {
      float sum = 0.0f;
      for (size_t m = 0; m < 4; ++m)
      {
        s.joints[m] = chosen[m];
        s.weights[m] = static_cast<float>(unit(random));
        sum += s.weights[m];
      }
      for (float& w : s.weights)
      {
        w /= sum;
      }
    }
  }
  return boxes;
}
} // namespace

TEST(SkinnedBoxes, ARigidlyPosedBoxIsItsBoxMoved)
{
  tc::SkinnedBox box;
  box.corners = { 1, 2, 3, 2, 2, 3, 1, 5, 3, 1, 2, 5 }; // c0 + (1,0,0), (0,3,0), (0,0,2)
  for (tc::PointSkin& s : box.skin)
  {
    s.joints = { 1, 0, 0, 0 };
    s.weights = { 1, 0, 0, 0 };
  }
  box.lo = { -1, 0, 0 };
  box.hi = { 2, 1, 0.5 };
  // A quarter turn about z (x -> y, y -> -x), then a shift by (4, 0, 1).
  tc::Matrix4 turn = translation(4, 0, 1);
  turn[0] = 0;
  turn[1] = -1;
  turn[4] = 1;
  turn[5] = 0;
  const std::vector<tc::Matrix4> m = { tc::identityMatrix(), turn };
  const tc::BoxFrame frame = tc::posedBoxFrame(tc::poseBox(box, m));
  // The range: x in [0, 3], y in [2, 5], z in [3, 4] before the motion, so volume 9.
  EXPECT_NEAR(frame.volume, 9.0, 1e-12);
  // The centre (1.5, 3.5, 3.5) moves to (4 - 3.5, 1.5, 4.5); past the top it is outside.
  EXPECT_TRUE(tc::boxContains(frame, { 0.5, 1.5, 4.5 }));
  EXPECT_FALSE(tc::boxContains(frame, { 0.5, 1.5, 5.01 }));
  EXPECT_TRUE(tc::boxContains(frame, { 0.5, 1.5, 5.01 }, 0.02));
}

TEST(SkinnedBoxes, RefusesAnAtlasWithoutSkin)
{
  EXPECT_THROW(
    tc::fitSkinnedBoxes(tctest::octahedronAtlas({ 2, 2, 2, 2, 2, 2, 2, 2 })), tc::InputError);
}

TEST(SkinnedBoxes, HoldTheBentBunnyAtRandomTimes)
{
  const tc::Atlas& atlas = skinnedBunny();
  const tc::SkinnedBoxesResult& fitted = bunnyBoxes();
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
  const Containment held = samplesOutside(atlas, fitted, 50);
  std::cout << "[ figures  ] bunny: " << atlas.charts.size() << " charts, " << fitted.frames
            << " fitted frames, volume ratio mean " << fitted.meanVolumeRatio << " median "
            << fitted.medianVolumeRatio << " largest " << fitted.largestVolumeRatio << " summed "
            << fitted.summedVolumeRatio << "; outside at 2 x 50 random times: " << held.outside
            << " (double), " << held.outsideLod << " (poseLodBoxes) of " << held.tested
            << " samples\n";
  EXPECT_EQ(held.outside, 0);
  EXPECT_EQ(held.outsideLod, 0);
  // Measured: median 1.09, summed 7.5 (a few large coarse charts that fold across the bend hold
  // most of the volume), mean 31 (flat charts whose box must be as thick as their bend in every
  // frame, against a tight box as thin as minExtent at rest).
  EXPECT_LE(fitted.medianVolumeRatio, 1.25);
  EXPECT_GE(fitted.medianVolumeRatio, 1.0);
  EXPECT_LE(fitted.summedVolumeRatio, 10.0);
  EXPECT_GE(fitted.summedVolumeRatio, 1.0);
}

TEST(SkinnedBoxes, HoldTheBunnyUnderSampledShearingPoses)
{
  const tc::Atlas atlas = withSampledShear(skinnedBunny());
  const tc::SkinnedBoxesResult fitted = tc::fitSkinnedBoxes(atlas);
  const Containment held = samplesOutside(atlas, fitted, 50);
  std::cout << "[ figures  ] bunny, sampled shear: volume ratio mean " << fitted.meanVolumeRatio
            << " median " << fitted.medianVolumeRatio << " largest " << fitted.largestVolumeRatio
            << " summed " << fitted.summedVolumeRatio
            << "; outside at 50 random times: " << held.outside << " (double), " << held.outsideLod
            << " (poseLodBoxes) of " << held.tested << " samples\n";
  EXPECT_EQ(held.outside, 0);
  EXPECT_EQ(held.outsideLod, 0);
  // Measured: median 1.09, summed 1.9, mean 2.4.
  EXPECT_LE(fitted.medianVolumeRatio, 1.25);
  EXPECT_GE(fitted.medianVolumeRatio, 1.0);
  EXPECT_LE(fitted.summedVolumeRatio, 3.0);
  EXPECT_GE(fitted.summedVolumeRatio, 1.0);
}

TEST(SkinnedBoxes, PoseLodBoxesAgreesWithPoseBox)
{
  std::mt19937 random(7);
  const int32_t joints = 64;
  const std::vector<tc::SkinnedBox> boxes = randomBoxes(20000, joints, random);
  std::vector<tc::Matrix4> m;
  for (int32_t j = 0; j < joints; ++j)
  {
    m.push_back(randomMotion(random));
  }
  std::vector<float> palette;
  tc::appendPaletteRows(m, palette);
  const tc::LodSkinnedBoxes lod = tc::LodSkinnedBoxes::fromBoxes(boxes);
  ASSERT_EQ(lod.size(), 20000);
  EXPECT_EQ(lod.paletteJoints, joints);
  std::vector<float> box(12 * boxes.size()), area(boxes.size());
  tc::poseLodBoxes(lod, palette.data(), joints, box.data(), area.data());
  double worstCorner = 0.0, worstArea = 0.0;
  for (size_t c = 0; c < boxes.size(); ++c)
  {
    const std::array<std::array<double, 3>, 4> q = tc::poseBox(boxes[c], m);
    double axes[3][3];
    for (size_t r = 0; r < 3; ++r)
    {
      worstCorner = std::max(worstCorner, std::abs(box[12 * c + r] - q[0][r]));
      for (size_t k = 0; k < 3; ++k)
      {
        axes[k][r] = q[k + 1][r] - q[0][r];
        worstCorner = std::max(worstCorner, std::abs(box[12 * c + 3 + 3 * k + r] - axes[k][r]));
      }
    }
    double expected = 0.0;
    for (int p = 0; p < 3; ++p)
    {
      const double* u = axes[p == 2 ? 1 : 0];
      const double* v = axes[p == 0 ? 1 : 2];
      expected += std::sqrt(std::pow(u[1] * v[2] - u[2] * v[1], 2) +
        std::pow(u[2] * v[0] - u[0] * v[2], 2) + std::pow(u[0] * v[1] - u[1] * v[0], 2));
    }
    worstArea = std::max(worstArea, std::abs(area[c] - expected) / expected);
  }
  // Coordinates of magnitude about 2, through the frame's cross products and normalizations: a few
  // dozen float roundings of that (2^-23 each).
  EXPECT_LE(worstCorner, 2e-5);
  EXPECT_LE(worstArea, 1e-4);
}

TEST(SkinnedBoxes, LodLayoutRefusesWhatItCannotPose)
{
  tc::SkinnedBox box;
  for (size_t i = 0; i < 3; ++i)
  {
    box.skin[i].joints = { static_cast<int32_t>(2 * i), static_cast<int32_t>(2 * i + 1), 0, 0 };
    box.skin[i].weights = { 0.5f, 0.5f, 0.0f, 0.0f };
  }
  // 6 distinct joints over the 3 skins: more than one box's 4 slots.
  EXPECT_THROW(tc::LodSkinnedBoxes::fromBoxes({ box }), tc::InputError);
  for (size_t i = 0; i < 3; ++i)
  {
    box.skin[i].joints = { 3, 1, 0, 0 };
  }
  const tc::LodSkinnedBoxes lod = tc::LodSkinnedBoxes::fromBoxes({ box });
  EXPECT_EQ(lod.paletteJoints, 4);
  EXPECT_EQ(lod.jointCount[0], 2);
  std::vector<float> palette;
  tc::appendPaletteRows(std::vector<tc::Matrix4>(3, tc::identityMatrix()), palette);
  std::vector<float> out(12), area(1);
  EXPECT_THROW(tc::poseLodBoxes(lod, palette.data(), 3, out.data(), area.data()), tc::InputError);
}
