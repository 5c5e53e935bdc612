// SPDX-License-Identifier: BSD-3-Clause
// Per-frame LOD selection (eqs. (6) and (7) of Feng et al. 2010, section 6.1) and the draw list:
// known answers on hand-made boxes under orthographic and perspective cameras, the error mode's
// boundary, culling and the near-eye rule, the arrays of an atlas, the draw list's grouping and
// packed neighbour levels, and a randomized comparison against a double-precision reference that
// projects all 8 corners one by one.
#include "tc/gim/lod_selection.h"

#include "tc/common/errors.h"
#include "tc/gim/atlas.h"

#include "octahedron_atlas.h"
#include "view_matrices.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <limits>
#include <random>
#include <vector>

namespace
{
using tctest::lookAt;
using tctest::Matrix;
using tctest::multiply;
using tctest::ortho;
using tctest::perspective;
using Vec3 = std::array<double, 3>;
constexpr float kInf = std::numeric_limits<float>::infinity();

Vec3 cross(const Vec3& a, const Vec3& b)
{
  return { a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0] };
}

double norm(const Vec3& a)
{
  return std::sqrt(a[0] * a[0] + a[1] * a[1] + a[2] * a[2]);
}

/// Eq. (6) on unprojected axes.
double worldAreaOf(const std::array<Vec3, 3>& a)
{
  return norm(cross(a[0], a[1])) + norm(cross(a[0], a[2])) + norm(cross(a[1], a[2]));
}

/// Appends one chart to `charts` (stride must be set first; errors may be empty: not measured).
void addChart(tc::LodCharts& charts, const Vec3& c0, const std::array<Vec3, 3>& axes,
  int32_t maxLevel, const std::vector<float>& errors = {})
{
  for (int i = 0; i < 3; ++i)
  {
    charts.box.push_back(static_cast<float>(c0[static_cast<size_t>(i)]));
  }
  for (const Vec3& a : axes)
  {
    for (const double v : a)
    {
      charts.box.push_back(static_cast<float>(v));
    }
  }
  charts.worldArea.push_back(static_cast<float>(worldAreaOf(axes)));
  charts.maxLevel.push_back(maxLevel);
  for (int32_t d = 0; d < charts.stride; ++d)
  {
    charts.levelError.push_back(
      errors.empty() || d > maxLevel ? kInf : errors[static_cast<size_t>(d)]);
  }
  for (int k = 0; k < 3; ++k)
  {
    charts.neighbor.push_back(-1);
  }
}

/// The level of a single chart.
int32_t levelOf(const Vec3& c0, const std::array<Vec3, 3>& axes, int32_t maxLevel,
  const tc::LodView& view, const tc::LodOptions& options = {},
  const std::vector<float>& errors = {})
{
  tc::LodCharts charts;
  charts.stride = maxLevel + 1;
  addChart(charts, c0, axes, maxLevel, errors);
  int32_t level = -2;
  tc::selectLevels(charts, view, options, &level);
  return level;
}

/// An orthographic view in which world x, y in [-1, 1] fill the viewport exactly.
tc::LodView orthoView(double width = 800, double height = 600)
{
  tc::LodView view;
  view.worldToClip = ortho(-1, 1, -1, 1, -10, 10);
  view.width = width;
  view.height = height;
  return view;
}

/// A box in the plane z = 0 covering [x0, x0 + size] x [y0, y0 + size], 0.5 deep.
std::array<Vec3, 3> square(double size)
{
  return { Vec3{ size, 0, 0 }, Vec3{ 0, size, 0 }, Vec3{ 0, 0, 0.5 } };
}

constexpr int32_t kMax = 6;

TEST(LodSelection, BoxFillingTheViewportGetsMaxLevel)
{
  EXPECT_EQ(levelOf({ -1, -1, 0 }, square(2), kMax, orthoView()), kMax);
}

TEST(LodSelection, EachQuarterOfTheAreaIsOneLevelLess)
{
  // Eq. (7): d = floor(maxLevel + log4(A / (width height)) + 1/2).
  EXPECT_EQ(levelOf({ -1, -1, 0 }, square(1), kMax, orthoView()), kMax - 1);
  EXPECT_EQ(levelOf({ -1, -1, 0 }, square(0.5), kMax, orthoView()), kMax - 2);
  EXPECT_EQ(levelOf({ 0.2, -0.3, 0 }, square(0.25), kMax, orthoView()), kMax - 3);
}

TEST(LodSelection, BiasShiftsByOneLevelAndIsClamped)
{
  tc::LodOptions finer;
  finer.bias = 1.0;
  EXPECT_EQ(levelOf({ -1, -1, 0 }, square(1), kMax, orthoView(), finer), kMax);
  EXPECT_EQ(levelOf({ -1, -1, 0 }, square(0.5), kMax, orthoView(), finer), kMax - 1);
  EXPECT_EQ(levelOf({ -1, -1, 0 }, square(2), kMax, orthoView(), finer), kMax);
  tc::LodOptions coarser;
  coarser.bias = -1.0;
  EXPECT_EQ(levelOf({ -1, -1, 0 }, square(2), kMax, orthoView(), coarser), kMax - 1);
}

TEST(LodSelection, TinyBoxGetsLevelZero)
{
  EXPECT_EQ(levelOf({ 0.1, 0.1, 0 }, square(1e-4), kMax, orthoView()), 0);
}

TEST(LodSelection, DegenerateBoxGetsLevelZeroUnlessCulled)
{
  const std::array<Vec3, 3> zero{};
  tc::LodOptions finer;
  finer.bias = 4.0;
  EXPECT_EQ(levelOf({ 0.1, 0.1, 0 }, zero, kMax, orthoView(), finer), 0);
  EXPECT_EQ(levelOf({ 5, 0.1, 0 }, zero, kMax, orthoView()), -1);
}

TEST(LodSelection, BoxOutsideTheFrustumIsCulled)
{
  const tc::LodView view = orthoView();
  EXPECT_EQ(levelOf({ -3, -0.5, 0 }, square(1), kMax, view), -1);    // wholly left
  EXPECT_EQ(levelOf({ -0.5, 1.5, 0 }, square(1), kMax, view), -1);   // wholly above
  EXPECT_EQ(levelOf({ -0.5, -0.5, 11 }, square(1), kMax, view), -1); // beyond the near plane
  tc::LodOptions noCull;
  noCull.cull = false;
  EXPECT_EQ(levelOf({ -3, -0.5, 0 }, square(1), kMax, view, noCull), kMax - 1);
}

TEST(LodSelection, BoxStraddlingTheFrustumEdgeIsKept)
{
  // x in [-1.5, -0.5]: half inside. A quarter of the viewport's area (eq. (6) does not clip).
  EXPECT_EQ(levelOf({ -1.5, -0.5, 0 }, square(1), kMax, orthoView()), kMax - 1);
}

TEST(LodSelection, CullingIsPerPlane)
{
  // Beyond the frustum's corner (x > 1 and y > 1 hold only together, never at all 8 corners
  // of one plane's outside): kept, as the plane test is conservative.
  const std::array<Vec3, 3> diagonal{ Vec3{ 1, 1, 0 }, Vec3{ -0.4, 0.4, 0 }, Vec3{ 0, 0, 0.5 } };
  EXPECT_GE(levelOf({ 0.8, 0.9, 0 }, diagonal, kMax, orthoView()), 0);
}

TEST(LodSelection, BoxBehindTheEyeIsCulled)
{
  tc::LodView view;
  view.worldToClip = perspective(90, 1, 0.1, 100);
  view.width = view.height = 1000;
  const std::array<Vec3, 3> unit{ Vec3{ 1, 0, 0 }, Vec3{ 0, 1, 0 }, Vec3{ 0, 0, 1 } };
  EXPECT_EQ(levelOf({ -0.5, -0.5, 1 }, unit, kMax, view), -1);
  // Without culling the near-eye rule takes it (some corner has w <= 0).
  tc::LodOptions noCull;
  noCull.cull = false;
  EXPECT_EQ(levelOf({ -0.5, -0.5, 1 }, unit, kMax, view, noCull), kMax);
}

TEST(LodSelection, BoxAroundTheEyeGetsMaxLevel)
{
  tc::LodView view;
  view.worldToClip = perspective(60, 1.5, 0.1, 100);
  view.width = 1200;
  view.height = 800;
  const std::array<Vec3, 3> big{ Vec3{ 2, 0, 0 }, Vec3{ 0, 2, 0 }, Vec3{ 0, 0, 2 } };
  EXPECT_EQ(levelOf({ -1, -1, -1 }, big, kMax, view), kMax);
  // A far small box in the same view is coarse: the rule is about the eye, not the view.
  EXPECT_LT(levelOf({ -0.05, -0.05, -50 }, square(0.1), kMax, view), kMax);
}

TEST(LodSelection, DoublingTheDistanceLowersTheLevelByOne)
{
  // A unit square facing a 90-degree camera at distance D covers 1 / D^2 of the normalized
  // square [-1, 1]^2 of area 4, so d = floor(m + log4(1 / (4 D^2)) + 1/2) = floor(m - 1/2 -
  // log2 D).
  tc::LodView view;
  view.worldToClip = perspective(90, 1, 0.01, 1000);
  view.width = view.height = 1024;
  const std::array<Vec3, 3> facing{ Vec3{ 1, 0, 0 }, Vec3{ 0, 1, 0 }, Vec3{ 0, 0, 0 } };
  constexpr int32_t m = 12;
  for (const double distance : { 1.5, 2.0, 3.0, 5.0, 7.0 })
  {
    const int32_t nearer = levelOf({ -0.5, -0.5, -distance }, facing, m, view);
    const int32_t farther = levelOf({ -0.5, -0.5, -2 * distance }, facing, m, view);
    EXPECT_EQ(nearer, static_cast<int32_t>(std::floor(m - 0.5 - std::log2(distance)))) << distance;
    EXPECT_EQ(farther, nearer - 1) << distance;
  }
}

/// The error-mode fixture: a box filling a 512 x 512 viewport, A = 512^2 pixels^2 over a world
/// area of 4, so s = 256 pixels per world unit; a target of 1 pixel means levelError <= 1/256.
class LodErrorMode : public ::testing::Test
{
protected:
  tc::LodView view = orthoView(512, 512);
  const std::array<Vec3, 3> axes{ Vec3{ 2, 0, 0 }, Vec3{ 0, 2, 0 }, Vec3{ 0, 0, 0 } };
  tc::LodOptions options;
  static constexpr float kTarget = 1.0f / 256.0f;

  void SetUp() override { options.errorPixels = 1.0; }

  int32_t level(const std::vector<float>& errors, int32_t maxLevel = 5)
  {
    return levelOf({ -1, -1, 0 }, axes, maxLevel, view, options, errors);
  }
};

TEST_F(LodErrorMode, PicksTheSmallestLevelUnderTheTarget)
{
  EXPECT_EQ(level({ 0.1f, 0.02f, kTarget * 1.001f, kTarget * 0.5f, 0.0f, 0.0f }), 3);
  EXPECT_EQ(level({ 0.1f, 0.02f, kTarget * 0.999f, kTarget * 0.5f, 0.0f, 0.0f }), 2);
}

TEST_F(LodErrorMode, NotMonotoneStillSmallest)
{
  EXPECT_EQ(level({ 0.1f, kTarget * 0.9f, 0.05f, 0.0f, 0.0f, 0.0f }), 1);
}

TEST_F(LodErrorMode, NoLevelUnderTheTargetGivesMaxLevel)
{
  EXPECT_EQ(level({ 0.5f, 0.4f, 0.3f, 0.2f, 0.1f, 0.05f }), 5);
}

TEST_F(LodErrorMode, BiasIsRoundedAndClamped)
{
  const std::vector<float> errors{ 0.1f, 0.02f, kTarget * 0.5f, 0.0f, 0.0f, 0.0f };
  options.bias = 1.0;
  EXPECT_EQ(level(errors), 3);
  options.bias = -0.6;
  EXPECT_EQ(level(errors), 1);
  options.bias = -3.0;
  EXPECT_EQ(level(errors), 0);
}

TEST_F(LodErrorMode, UnmeasuredChartFallsBackToTheAreaMode)
{
  // The box fills the viewport: area mode gives maxLevel.
  EXPECT_EQ(level({}, 5), 5);
  // The same with errors that are all met at level 0.
  EXPECT_EQ(level({ 0.0f, 0.0f, 0.0f, 0.0f, 0.0f, 0.0f }, 5), 0);
}

TEST(LodSelection, RejectsInconsistentArraysAndEmptyViewport)
{
  tc::LodCharts charts;
  charts.stride = 3;
  addChart(charts, { 0, 0, 0 }, square(1), 2);
  int32_t level = 0;
  tc::LodView empty;
  EXPECT_THROW(tc::selectLevels(charts, empty, {}, &level), tc::InputError);
  charts.worldArea.push_back(1.0f);
  EXPECT_THROW(tc::selectLevels(charts, orthoView(), {}, &level), tc::InputError);
  const tc::LodCharts none;
  EXPECT_NO_THROW(tc::selectLevels(none, orthoView(), {}, nullptr));
}

TEST(LodSelection, FromAtlasReadsTheCharts)
{
  tc::Atlas atlas;
  atlas.charts.resize(3);
  tc::AtlasChart& a = atlas.charts[0];
  a.maxLevel = 2;
  // c0 = (1, 2, 3), axes (1, 1, 0), (-1, 1, 0), (0, 0, 2).
  a.box = { 1, 2, 3, 2, 3, 3, 0, 3, 3, 1, 2, 5 };
  a.levelError = { 0.3, 0.2, 0.1 };
  a.neighborChart = { 1, 2, -1 };
  tc::AtlasChart& b = atlas.charts[1];
  b.maxLevel = 4;
  b.neighborChart = { 0, -1, 2 };
  tc::AtlasChart& c = atlas.charts[2];
  c.maxLevel = 1;
  c.levelError = { 0.5, 0.25 };
  c.neighborChart = { 1, 0, -1 };

  const tc::LodCharts charts = tc::LodCharts::fromAtlas(atlas);
  EXPECT_EQ(charts.size(), 3);
  EXPECT_EQ(charts.stride, 5);
  const std::vector<float> box0{ 1, 2, 3, 1, 1, 0, -1, 1, 0, 0, 0, 2 };
  EXPECT_EQ(std::vector<float>(charts.box.begin(), charts.box.begin() + 12), box0);
  EXPECT_FLOAT_EQ(charts.worldArea[0], static_cast<float>(2 + 4 * std::sqrt(2.0)));
  EXPECT_EQ(charts.worldArea[1], 0.0f);
  EXPECT_EQ(charts.maxLevel, (std::vector<int32_t>{ 2, 4, 1 }));
  const std::vector<float> errors{ 0.3f, 0.2f, 0.1f, kInf, kInf, kInf, kInf, kInf, kInf, kInf, 0.5f,
    0.25f, kInf, kInf, kInf };
  EXPECT_EQ(charts.levelError, errors);
  EXPECT_EQ(charts.neighbor, (std::vector<int32_t>{ 1, 2, -1, 0, -1, 2, 1, 0, -1 }));
}

TEST(LodSelection, FromAtlasRejectsWhatTheDrawListCannotHold)
{
  tc::Atlas atlas;
  atlas.charts.resize(2);
  atlas.charts[0].maxLevel = 2;
  atlas.charts[0].levelError = { 0.1, 0.05 };
  EXPECT_THROW(tc::LodCharts::fromAtlas(atlas), tc::InputError);
  atlas.charts[0].levelError.clear();
  atlas.charts[1].neighborChart = { 0, 2, -1 };
  EXPECT_THROW(tc::LodCharts::fromAtlas(atlas), tc::InputError);
  atlas.charts[1].neighborChart = { 0, -1, -1 };
  atlas.charts[1].maxLevel = tc::kLodMaxLevel + 1;
  EXPECT_THROW(tc::LodCharts::fromAtlas(atlas), tc::InputError);
  atlas.charts[1].maxLevel = tc::kLodMaxLevel;
  EXPECT_NO_THROW(tc::LodCharts::fromAtlas(atlas));
}

/// Four charts with maxLevel 3, neighbours (1, 2, -1), (0, 3, 2), (3, 0, 1), (2, 1, -1).
tc::LodCharts fourCharts()
{
  tc::LodCharts charts;
  charts.stride = 4;
  for (int c = 0; c < 4; ++c)
  {
    addChart(charts, { 0, 0, 0 }, square(1), 3);
  }
  charts.neighbor = { 1, 2, -1, 0, 3, 2, 3, 0, 1, 2, 1, -1 };
  return charts;
}

int32_t packed(int32_t n, int32_t m0, int32_t m1, int32_t m2)
{
  return n | m0 << 4 | m1 << 8 | m2 << 12;
}

TEST(LodDrawList, GroupsByLevelWithNeighbourLevels)
{
  const tc::LodCharts charts = fourCharts();
  // Instance 0: chart 2 culled; instance 1: all drawn.
  const std::vector<int32_t> levels{ 2, 1, -1, 3, 0, 0, 2, 1 };
  tc::LodDrawList list;
  tc::buildDrawList(charts, levels.data(), 2, list);

  // Level 0: (0, 1), (1, 1); level 1: (1, 0), (3, 1); level 2: (0, 0), (2, 1); level 3: (3, 0).
  // Absent (-1) and culled neighbours count as the chart's own level.
  const std::vector<int32_t> expected{
    0, 1, packed(0, 0, 2, 0), 84,  //
    1, 1, packed(0, 0, 1, 2), 85,  //
    1, 0, packed(1, 2, 3, 1), 16,  // chart 2 culled in instance 0: side 2 counts as 1
    3, 1, packed(1, 2, 0, 1), 102, //
    0, 0, packed(2, 1, 2, 2), 0,   // chart 2 culled: side 1 counts as 2; side 2 absent
    2, 1, packed(2, 1, 0, 0), 86,  //
    3, 0, packed(3, 3, 1, 3), 20,  // chart 2 culled: side 0 counts as 3
  };
  // First cell ids, instance by instance and chart by chart: (0, 0) 16 triangles from 0,
  // (1, 0) 4 from 16, (3, 0) 64 from 20, then instance 1's 1 + 1 + 16 + 4 from 84.
  EXPECT_EQ(list.entries, expected);
  EXPECT_EQ(list.levelStart, (std::vector<int64_t>{ 0, 2, 4, 6, 7 }));
  EXPECT_EQ(list.chartsPerLevel, (std::vector<int64_t>{ 2, 2, 2, 1 }));
  EXPECT_EQ(list.triangles, 1 + 1 + 4 + 4 + 16 + 16 + 64);
}

TEST(LodDrawList, ReusesItsStorage)
{
  const tc::LodCharts charts = fourCharts();
  const std::vector<int32_t> many{ 3, 3, 3, 3, 2, 2, 2, 2 };
  tc::LodDrawList list;
  tc::buildDrawList(charts, many.data(), 2, list);
  ASSERT_EQ(list.entries.size(), 32u);
  const int32_t* storage = list.entries.data();
  const std::vector<int32_t> few{ -1, 1, -1, -1 };
  tc::buildDrawList(charts, few.data(), 1, list);
  EXPECT_EQ(list.entries.data(), storage);
  EXPECT_EQ(list.entries, (std::vector<int32_t>{ 1, 0, packed(1, 1, 1, 1), 0 }));
  EXPECT_EQ(list.levelStart, (std::vector<int64_t>{ 0, 0, 1, 1, 1 }));
  EXPECT_EQ(list.chartsPerLevel, (std::vector<int64_t>{ 0, 1, 0, 0 }));
  EXPECT_EQ(list.triangles, 4);
}

TEST(LodDrawList, RejectsLevelsOutsideTheChartsRange)
{
  const tc::LodCharts charts = fourCharts();
  tc::LodDrawList list;
  const std::vector<int32_t> tooFine{ 0, 4, 0, 0 };
  EXPECT_THROW(tc::buildDrawList(charts, tooFine.data(), 1, list), tc::InputError);
  const std::vector<int32_t> belowCulled{ 0, -2, 0, 0 };
  EXPECT_THROW(tc::buildDrawList(charts, belowCulled.data(), 1, list), tc::InputError);
  tc::LodCharts badNeighbour = fourCharts();
  badNeighbour.neighbor[4] = 7;
  const std::vector<int32_t> fine{ 0, 1, 2, 3 };
  EXPECT_THROW(tc::buildDrawList(badNeighbour, fine.data(), 1, list), tc::InputError);
}

TEST(LodDrawList, EveryCellIdLocatesItsTriangle)
{
  const tc::LodCharts charts = fourCharts();
  const std::vector<int32_t> levels{ 2, 1, -1, 3, 0, 0, 2, 1 };
  tc::LodDrawList list;
  tc::buildDrawList(charts, levels.data(), 2, list);
  // The numbering of lod_selection.h, enumerated directly: instance, chart, grid triangle.
  int64_t cell = 0;
  for (int32_t r = 0; r < 2; ++r)
  {
    for (int32_t c = 0; c < 4; ++c)
    {
      const int32_t level = levels[static_cast<size_t>(4 * r + c)];
      for (int64_t t = 0; level >= 0 && t < (int64_t(1) << (2 * level)); ++t, ++cell)
      {
        const tc::LodTriangle found = tc::locateTriangle(list, cell);
        EXPECT_EQ(found.instance, r) << "cell " << cell;
        EXPECT_EQ(found.chart, c) << "cell " << cell;
        EXPECT_EQ(found.level, level) << "cell " << cell;
        EXPECT_EQ(found.triangle, t) << "cell " << cell;
      }
    }
  }
  EXPECT_EQ(cell, list.triangles);
  for (const int64_t outside : { int64_t(-1), list.triangles, list.triangles + 1000 })
  {
    const tc::LodTriangle none = tc::locateTriangle(list, outside);
    EXPECT_EQ(none.chart, -1);
    EXPECT_EQ(none.instance, -1);
    EXPECT_EQ(none.level, -1);
    EXPECT_EQ(none.triangle, -1);
  }
  EXPECT_EQ(tc::locateTriangle(tc::LodDrawList(), 0).chart, -1);
}

/// The bounds a loop over every finest sample gives, under the row-major matrix `t`.
std::array<double, 6> sampleBounds(const tc::Atlas& atlas, const double* t)
{
  std::array<double, 6> b{ kInf, -kInf, kInf, -kInf, kInf, -kInf };
  const tc::AtlasImage& image = atlas.images[0];
  tc::forEachImageSample(atlas, 0,
    [&](int32_t, int32_t, int32_t, int32_t, size_t texel)
    {
      const float* p = image.data[0].data() + 3 * texel;
      for (size_t r = 0; r < 3; ++r)
      {
        const double v = t[4 * r] * p[0] + t[4 * r + 1] * p[1] + t[4 * r + 2] * p[2] + t[4 * r + 3];
        b[2 * r] = std::min(b[2 * r], v);
        b[2 * r + 1] = std::max(b[2 * r + 1], v);
      }
    });
  return b;
}

TEST(LodBounds, AreTheFinestSamplesBoundsInEveryInstance)
{
  const tc::Atlas atlas = tctest::octahedronAtlas({ 3, 2, 4, 4, 1, 3, 0, 2 });
  const double c = std::cos(0.3), s = std::sin(0.3);
  // Identity; a translation with a scale and an axis swap (the fast path); a turn about z.
  const std::vector<double> instances{ 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, //
    0, 2, 0, 5, 2, 0, 0, -1, 0, 0, -2, 0.25, 0, 0, 0, 1,                               //
    c, -s, 0, 0, s, c, 0, 0, 0, 0, 1, 3, 0, 0, 0, 1 };
  for (size_t i = 0; i < 3; ++i)
  {
    const std::vector<double> one(instances.begin() + 16 * i, instances.begin() + 16 * (i + 1));
    EXPECT_EQ(tc::drawnBounds(atlas, one), sampleBounds(atlas, one.data())) << "instance " << i;
  }
  // The octahedron's vertices are samples: its bounds are exact, [-1, 1] on every axis.
  EXPECT_EQ(tc::drawnBounds(atlas, { instances.begin(), instances.begin() + 16 }),
    (std::array<double, 6>{ -1, 1, -1, 1, -1, 1 }));
  // All three: the union; the turned one reaches x = cos 0.3 (vertex (1, 0, 0)), not the box's.
  const std::array<double, 6> all = tc::drawnBounds(atlas, instances);
  EXPECT_EQ(all, (std::array<double, 6>{ -1, 7, -3, 1, -1.75, 4 }));
  EXPECT_DOUBLE_EQ(sampleBounds(atlas, instances.data() + 32)[1], c);
}

TEST(LodBounds, EmptyWithoutChartsOrInstancesAndRefuseABrokenLayout)
{
  const std::array<double, 6> empty{ 1, -1, 1, -1, 1, -1 };
  EXPECT_EQ(
    tc::drawnBounds(tc::Atlas(), { 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1 }), empty);
  const tc::Atlas atlas = tctest::octahedronAtlas({ 1, 1, 1, 1, 1, 1, 1, 1 });
  EXPECT_EQ(tc::drawnBounds(atlas, {}), empty);
  tc::Atlas broken = atlas;
  broken.images[0].data[0].resize(5);
  EXPECT_THROW(
    tc::drawnBounds(broken, { 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1 }), tc::InputError);
}

/// The rules of lod_selection.h in double, with all 8 corners projected one by one.
struct Reference
{
  int32_t level = 0;
  /// Whether float rounding may decide differently: the continuous level within 1e-4 of a
  /// rounding boundary, an error within 1e-4 (relative) of the target, or a corner within 1e-5
  /// (relative) of a clip plane or of the near-eye threshold.
  bool ambiguous = false;
};

Reference reference(const Vec3& c0, const std::array<Vec3, 3>& a, int32_t maxLevel,
  const std::vector<float>& errors, const tc::LodView& view, const tc::LodOptions& options)
{
  const Matrix& m = view.worldToClip;
  const auto clip = [&](const Vec3& p)
  {
    std::array<double, 4> h{};
    for (int r = 0; r < 4; ++r)
    {
      h[r] = m[4 * r] * p[0] + m[4 * r + 1] * p[1] + m[4 * r + 2] * p[2] + m[4 * r + 3];
    }
    return h;
  };
  std::vector<std::array<double, 4>> corners;
  for (int s = 0; s < 8; ++s)
  {
    Vec3 p = c0;
    for (int k = 0; k < 3; ++k)
    {
      if (s & (1 << k))
      {
        for (int i = 0; i < 3; ++i)
        {
          p[i] += a[k][i];
        }
      }
    }
    corners.push_back(clip(p));
  }
  Reference out;
  double scale = 0.0; // of the box in clip space, for the ambiguity margins
  for (const auto& h : corners)
  {
    for (const double v : h)
    {
      scale = std::max(scale, std::fabs(v));
    }
  }
  if (options.cull)
  {
    for (int axis = 0; axis < 3; ++axis)
    {
      for (const double sign : { 1.0, -1.0 })
      {
        double largest = -std::numeric_limits<double>::infinity();
        for (const auto& h : corners)
        {
          largest = std::max(largest, h[3] + sign * h[axis]);
        }
        out.ambiguous = out.ambiguous || std::fabs(largest) < 1e-5 * scale;
        if (largest < 0)
        {
          out.level = -1;
          return out;
        }
      }
    }
  }
  // Near the eye: the threshold on w relative to the box's extent in w, as documented.
  const std::array<double, 4> h0 = clip(c0);
  double wScale = std::fabs(h0[3]);
  for (int k = 0; k < 3; ++k)
  {
    wScale += std::fabs(m[12] * a[k][0] + m[13] * a[k][1] + m[14] * a[k][2]);
  }
  double minW = std::numeric_limits<double>::infinity();
  for (const auto& h : corners)
  {
    minW = std::min(minW, h[3]);
  }
  const double threshold = tc::kLodNearEpsilon * wScale;
  out.ambiguous = out.ambiguous || std::fabs(minW - threshold) < 1e-5 * scale;
  if (minW <= threshold)
  {
    out.level = maxLevel;
    return out;
  }
  const double world = worldAreaOf(a);
  if (!(world > 0))
  {
    out.level = 0;
    return out;
  }
  // Eq. (6) on the projected pivot and its three neighbours (corners 1, 2, 4).
  std::array<std::array<double, 2>, 4> px{};
  const int index[4] = { 0, 1, 2, 4 };
  for (int i = 0; i < 4; ++i)
  {
    const auto& h = corners[static_cast<size_t>(index[i])];
    px[i] = { h[0] / h[3] * view.width / 2, h[1] / h[3] * view.height / 2 };
  }
  double area = 0.0;
  for (int i = 1; i < 4; ++i)
  {
    for (int k = i + 1; k < 4; ++k)
    {
      area += std::fabs((px[i][0] - px[0][0]) * (px[k][1] - px[0][1]) -
        (px[i][1] - px[0][1]) * (px[k][0] - px[0][0]));
    }
  }
  const bool measured = !errors.empty();
  if (options.errorPixels > 0 && measured)
  {
    const double s = std::sqrt(area / world);
    int32_t d = maxLevel;
    for (int32_t l = maxLevel; l >= 0; --l)
    {
      const double e = errors[static_cast<size_t>(l)] * s;
      out.ambiguous =
        out.ambiguous || std::fabs(e - options.errorPixels) < 1e-4 * options.errorPixels;
      if (e <= options.errorPixels)
      {
        d = l;
      }
    }
    out.level = std::clamp(d + static_cast<int32_t>(std::lround(options.bias)), 0, maxLevel);
    return out;
  }
  const double continuous =
    maxLevel + std::log(area / (view.width * view.height)) / std::log(4.0) + options.bias + 0.5;
  out.ambiguous = out.ambiguous || std::fabs(continuous - std::round(continuous)) < 1e-4;
  out.level = area > 0
    ? std::clamp(static_cast<int32_t>(std::floor(std::max(continuous, -1.0))), 0, maxLevel)
    : 0;
  return out;
}

/// A random camera: perspective from a random eye towards a random target (3 in 4), else
/// orthographic; random viewport.
tc::LodView randomView(std::mt19937& rng)
{
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  tc::LodView view;
  view.width = std::uniform_real_distribution<double>(200, 2000)(rng);
  view.height = std::uniform_real_distribution<double>(200, 2000)(rng);
  const double aspect = view.width / view.height;
  Matrix projection;
  if (std::uniform_int_distribution<int>(0, 3)(rng) > 0)
  {
    projection =
      perspective(std::uniform_real_distribution<double>(20, 100)(rng), aspect, 0.05, 50);
  }
  else
  {
    const double half = std::uniform_real_distribution<double>(0.5, 3)(rng);
    projection = ortho(-half * aspect, half * aspect, -half, half, -20, 20);
  }
  const Vec3 eye{ 2 * u(rng), 2 * u(rng), 2 * u(rng) };
  const Vec3 target{ 0.3 * u(rng), 0.3 * u(rng), 0.3 * u(rng) };
  view.worldToClip = multiply(projection, lookAt(eye, target));
  return view;
}

/// A random box in [-1, 1]^3 with skewed axes of lengths 10^-3 .. 10^0.3, maxLevel 0 .. 10 and
/// (2 in 3) measured errors that roughly halve per level.
struct RandomBox
{
  Vec3 c0;
  std::array<Vec3, 3> axes;
  int32_t maxLevel;
  std::vector<float> errors;
};

RandomBox randomBox(std::mt19937& rng)
{
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  RandomBox box;
  box.c0 = { u(rng), u(rng), u(rng) };
  for (Vec3& a : box.axes)
  {
    const double length = std::pow(10.0, std::uniform_real_distribution<double>(-3, 0.3)(rng));
    a = { u(rng), u(rng), u(rng) };
    const double l = norm(a);
    for (double& v : a)
    {
      v *= length / l;
    }
  }
  box.maxLevel = std::uniform_int_distribution<int32_t>(0, 10)(rng);
  if (std::uniform_int_distribution<int>(0, 2)(rng) > 0)
  {
    double e = std::pow(10.0, std::uniform_real_distribution<double>(-3, -1)(rng));
    for (int32_t d = 0; d <= box.maxLevel; ++d)
    {
      box.errors.push_back(static_cast<float>(e));
      e *= std::uniform_real_distribution<double>(0.3, 0.7)(rng);
    }
  }
  return box;
}

TEST(LodSelection, MatchesTheEightCornerReferenceOnRandomBoxes)
{
  std::mt19937 rng(20100601);
  int compared = 0, culled = 0, nearOrMax = 0, between = 0, errorMode = 0;
  for (int trial = 0; trial < 1000; ++trial)
  {
    const tc::LodView view = randomView(rng);
    const RandomBox box = randomBox(rng);
    tc::LodOptions options;
    options.cull = std::uniform_int_distribution<int>(0, 3)(rng) > 0;
    options.bias = std::uniform_real_distribution<double>(-1.5, 1.5)(rng);
    if (std::uniform_int_distribution<int>(0, 2)(rng) == 0)
    {
      options.errorPixels = std::uniform_real_distribution<double>(0.25, 4)(rng);
    }
    const Reference expected = reference(box.c0, box.axes, box.maxLevel, box.errors, view, options);
    if (expected.ambiguous)
    {
      continue;
    }
    ++compared;
    culled += expected.level < 0;
    nearOrMax += expected.level == box.maxLevel;
    between += expected.level > 0 && expected.level < box.maxLevel;
    errorMode += options.errorPixels > 0 && !box.errors.empty() && expected.level >= 0;
    EXPECT_EQ(levelOf(box.c0, box.axes, box.maxLevel, view, options, box.errors), expected.level)
      << "trial " << trial;
  }
  // The random cases must exercise every rule, or the comparison says little.
  EXPECT_GE(compared, 950);
  EXPECT_GE(culled, 100);
  EXPECT_GE(nearOrMax, 100);
  EXPECT_GE(between, 100);
  EXPECT_GE(errorMode, 100);
}

TEST(LodSelection, ManyChartsInParallelMatchTheReference)
{
  // 40000 charts in one call: the parallel path over blocks, with partial blocks at the end.
  std::mt19937 rng(7);
  const tc::LodView view = randomView(rng);
  tc::LodOptions options;
  options.errorPixels = 1.0;
  tc::LodCharts charts;
  charts.stride = 11;
  std::vector<RandomBox> boxes;
  for (int c = 0; c < 40003; ++c)
  {
    boxes.push_back(randomBox(rng));
    addChart(
      charts, boxes.back().c0, boxes.back().axes, boxes.back().maxLevel, boxes.back().errors);
  }
  std::vector<int32_t> levels(boxes.size(), -2);
  tc::selectLevels(charts, view, options, levels.data());
  int compared = 0;
  for (size_t c = 0; c < boxes.size(); ++c)
  {
    const RandomBox& b = boxes[c];
    const Reference expected = reference(b.c0, b.axes, b.maxLevel, b.errors, view, options);
    if (!expected.ambiguous)
    {
      ++compared;
      ASSERT_EQ(levels[c], expected.level) << "chart " << c;
    }
  }
  EXPECT_GE(compared, 39000);
}
} // namespace
