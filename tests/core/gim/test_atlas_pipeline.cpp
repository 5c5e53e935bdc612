// SPDX-License-Identifier: BSD-3-Clause
// The static pipeline from base complex to rebuilt mesh on real meshes: every chart
// parameterization is free of flips, the atlas is valid, and 100 random level assignments per
// mesh (neighbours several levels apart included) each rebuild a closed oriented manifold with
// the input's Euler characteristic and no degenerate triangle (Feng et al. 5.1-5.2, 6.3).
#include "mesh_checks.h"
#include "pipeline_fixture.h"

#include "tc/gim/atlas.h"
#include "tc/gim/geometry_image_mesh.h"
#include "tc/gim/geometry_images.h"
#include "tc/gim/path_tracing.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <memory>
#include <random>

namespace
{
struct Built
{
  const tctest::PipelineCase* input = nullptr;
  tc::PatchMesh patches;
  tc::GeometryImageOptions options;
  tc::Atlas atlas;
};

const Built* builtFor(const std::string& name)
{
  static std::map<std::string, std::unique_ptr<Built>> cache;
  auto& slot = cache[name];
  if (!slot)
  {
    const tctest::PipelineCase* c = tctest::pipelineCase(tctest::pipelineMeshPath(name));
    if (!c)
    {
      return nullptr;
    }
    slot = std::make_unique<Built>();
    slot->input = c;
    slot->patches = tc::tracePaths(c->mesh, c->result);
    // Eight samples per input point, all spent (the budget rule, no error target): enough
    // levels for neighbours 3+ levels apart even where the base complex keeps many small
    // charts, and on flat ones.
    tc::GeometryImageOptions& options = slot->options;
    options.errorTarget = 0.0;
    options.sampleBudget = std::max<int64_t>(
      8 * c->mesh.numPoints(), 400 * static_cast<int64_t>(c->result.baseTriangles.size() / 3));
    slot->atlas = tc::buildGeometryImages(slot->patches, c->result, {}, {}, {}, options);
    std::printf("[ atlas    ] %s: %zu charts, finest level %d, %zu images\n", name.c_str(),
      slot->atlas.charts.size(), slot->atlas.maxLevel(), slot->atlas.images.size());
  }
  return slot.get();
}

class AtlasOnMesh : public ::testing::TestWithParam<std::string>
{
protected:
  void SetUp() override
  {
    B_ = builtFor(GetParam());
    if (!B_)
    {
      GTEST_SKIP() << GetParam() << " is not in the shared data";
    }
  }
  const Built* B_ = nullptr;
};

/// The farthest the lattice of the atlas file moves a sample, as a fraction of the input's
/// diagonal: half the diagonal of a cube of the step, step <= diagonal * 2^-16
/// (docs/atlas-format.md, version 4).
const double kLatticeMove = std::ldexp(std::sqrt(3.0) / 2.0, -16);

int64_t eulerOf(const tc::TriMesh& mesh)
{
  int64_t euler = 0;
  const std::string defect = tctest::manifoldDefect(mesh, euler);
  return defect.empty() ? euler : INT64_MIN;
}
} // namespace

TEST_P(AtlasOnMesh, ChartParameterizationsHaveNoFlippedTriangle)
{
  int64_t flipped = 0, degenerate = 0;
  const int32_t nf = static_cast<int32_t>(B_->input->result.baseTriangles.size() / 3);
  for (int32_t f = 0; f < nf; ++f)
  {
    const tc::PatchParameterization p = tc::parameterizePatch(B_->patches, B_->input->result, f);
    flipped += p.flippedTriangles;
    degenerate += p.degenerateTriangles;
  }
  std::printf("%s: %d charts, %lld flipped, %lld flattened onto a side\n", GetParam().c_str(), nf,
    static_cast<long long>(flipped), static_cast<long long>(degenerate));
  EXPECT_EQ(flipped, 0);
}

TEST_P(AtlasOnMesh, IsAValidAtlas)
{
  EXPECT_NO_THROW(tc::validateAtlas(B_->atlas));
  EXPECT_EQ(B_->atlas.charts.size(), B_->input->result.baseTriangles.size() / 3);
  EXPECT_EQ(B_->atlas.inputTriangles, B_->input->mesh.numTriangles());
}

TEST_P(AtlasOnMesh, FittedInteriorSamplesMoveNoFartherThanTheInterpolatedError)
{
  // The same atlas with interpolated samples: the levels are chosen before the fit, so the
  // charts agree on them, and each fitted interior sample of a chart's finest level lies within
  // that chart's interpolated levelError of where interpolation put it.
  tc::GeometryImageOptions options = B_->options;
  options.fitSamples = false;
  const tc::Atlas interpolated =
    tc::buildGeometryImages(B_->patches, B_->input->result, {}, {}, {}, options);
  const tc::Atlas& fitted = B_->atlas;
  ASSERT_EQ(fitted.charts.size(), interpolated.charts.size());
  double worst = 0.0; // largest offset over its bound
  int64_t moved = 0;
  for (size_t c = 0; c < fitted.charts.size(); ++c)
  {
    const int32_t d = fitted.charts[c].maxLevel, n = 1 << d;
    ASSERT_EQ(d, interpolated.charts[c].maxLevel) << "chart " << c;
    const double bound = interpolated.charts[c].levelError[static_cast<size_t>(d)];
    for (int32_t j = 1; j < n; ++j)
    {
      for (int32_t i = 1; i + j < n; ++i)
      {
        const float* f = tc::atlasSample(fitted, static_cast<int32_t>(c), 0, d, i, j);
        const float* s = tc::atlasSample(interpolated, static_cast<int32_t>(c), 0, d, i, j);
        const double offset = std::sqrt(double(f[0] - s[0]) * (f[0] - s[0]) +
          double(f[1] - s[1]) * (f[1] - s[1]) + double(f[2] - s[2]) * (f[2] - s[2]));
        moved += offset > 0.0 ? 1 : 0;
        // Float samples and the stored error round by a few 1e-7 of the model's size; the
        // interpolated error holds its own lattice snap, not the fitted sample's.
        worst = std::max(worst, (offset - bound) / fitted.inputDiagonal - kLatticeMove);
      }
    }
  }
  std::printf("%s: %lld interior samples fitted; largest offset beyond the interpolated error "
              "%.3g of the diagonal\n",
    GetParam().c_str(), static_cast<long long>(moved), worst);
  // The cube's faces are planes: the fit moves its samples by float rounding, which the
  // lattice snap undoes.
  if (GetParam() != "cube")
  {
    EXPECT_GT(moved, 0);
  }
  EXPECT_LE(worst, 1e-6);
}

TEST_P(AtlasOnMesh, RandomLevelsRebuildClosedManifoldsWithTheInputsEulerCharacteristic)
{
  int64_t euler = 0;
  ASSERT_EQ(tctest::manifoldDefect(B_->input->mesh, euler), "");
  const tc::Atlas& atlas = B_->atlas;
  std::mt19937 random(12345);
  int64_t farApart = 0, flat = 0, triangles = 0;
  for (int trial = 0; trial < 100; ++trial)
  {
    std::vector<int32_t> levels(atlas.charts.size());
    for (size_t c = 0; c < levels.size(); ++c)
    {
      const int32_t top = atlas.charts[c].maxLevel;
      // Every fourth trial sends each chart to 0 or its finest level: the largest gaps.
      levels[c] = trial % 4 == 3 ? (random() % 2 ? top : 0)
                                 : static_cast<int32_t>(random() % static_cast<uint32_t>(top + 1));
    }
    for (size_t c = 0; c < levels.size(); ++c)
    {
      for (int k = 0; k < 3; ++k)
      {
        farApart += levels[c] - levels[static_cast<size_t>(atlas.charts[c].neighborChart[k])] >= 3;
      }
    }
    const tc::RebuiltMesh rebuilt = tc::rebuildMesh(atlas, levels);
    int64_t e = 0;
    const std::string defect = tctest::manifoldDefect(rebuilt.mesh, e, &flat);
    triangles += rebuilt.mesh.numTriangles();
    ASSERT_EQ(defect, "") << "trial " << trial;
    ASSERT_EQ(e, euler) << "trial " << trial;
  }
  std::printf("%s: 100 rebuilds closed, Euler characteristic %lld, %lld chart sides 3+ levels "
              "finer than their neighbour, %lld of %lld triangles flattened by the lattice\n",
    GetParam().c_str(), static_cast<long long>(euler), static_cast<long long>(farApart),
    static_cast<long long>(flat), static_cast<long long>(triangles));
  EXPECT_GT(farApart, 0);
  // Slivers thinner than the lattice step are rare: 9 per million triangles on fandisk.
  EXPECT_LE(flat, triangles / 10000);
}

TEST_P(AtlasOnMesh, ErrorRuleKeepsTheLargestFinestErrorAtOrBelowTheAreaRules)
{
  // Four samples per input point (at least 45, level 3, per chart, so that the many small
  // charts of some base complexes leave minLevel) under both level rules, no target: the error rule
  // spends them on the charts with the largest measured levelError, so its largest error at
  // the finest level is not above the area rule's, and it stays within the budget.
  const tctest::PipelineCase& c = *B_->input;
  const int64_t budget = std::max<int64_t>(
    4 * c.mesh.numPoints(), 45 * static_cast<int64_t>(c.result.baseTriangles.size() / 3));
  double largest[2] = { 0.0, 0.0 };
  int64_t samples[2] = { 0, 0 };
  int32_t finest[2] = { 0, 0 };
  for (const tc::LevelRule rule : { tc::LevelRule::Area, tc::LevelRule::Error })
  {
    tc::GeometryImageOptions options;
    options.errorTarget = 0.0;
    options.sampleBudget = budget;
    options.levelRule = rule;
    const tc::Atlas atlas = tc::buildGeometryImages(B_->patches, c.result, {}, {}, {}, options);
    const int r = static_cast<int>(rule);
    for (const tc::AtlasChart& ch : atlas.charts)
    {
      largest[r] = std::max(largest[r], ch.levelError[static_cast<size_t>(ch.maxLevel)]);
      const int64_t n = int64_t(1) << ch.maxLevel;
      samples[r] += (n + 1) * (n + 2) / 2;
    }
    finest[r] = atlas.maxLevel();
  }
  std::printf("%s: budget %lld; area rule: %lld samples, finest level %d, largest finest error "
              "%.4f%% of the diagonal; error rule: %lld, %d, %.4f%%\n",
    GetParam().c_str(), static_cast<long long>(budget), static_cast<long long>(samples[0]),
    finest[0], 100.0 * largest[0] / B_->atlas.inputDiagonal, static_cast<long long>(samples[1]),
    finest[1], 100.0 * largest[1] / B_->atlas.inputDiagonal);
  EXPECT_LE(samples[1], budget);
  EXPECT_LE(largest[1], largest[0]);
}

TEST_P(AtlasOnMesh, ErrorTargetRaisesEachChartToTheFirstLevelBelowIt)
{
  // A target of 1% of the diagonal (which no mesh here needs 16x its points for) and no budget
  // (interpolated samples, whose levelError is the one the rule measured): every chart ends at the
  // first level whose error is at or below the target, or at maxLevel; none stops above it while a
  // level is left, and none is finer than the target needs.
  const tctest::PipelineCase& c = *B_->input;
  tc::GeometryImageOptions options;
  options.errorTarget = 1e-2;
  options.fitSamples = false;
  const tc::Atlas atlas = tc::buildGeometryImages(B_->patches, c.result, {}, {}, {}, options);
  const double target = options.errorTarget * atlas.inputDiagonal;
  int64_t samples = 0, atMaxLevel = 0;
  for (size_t k = 0; k < atlas.charts.size(); ++k)
  {
    const tc::AtlasChart& ch = atlas.charts[k];
    const size_t d = static_cast<size_t>(ch.maxLevel);
    const int64_t n = int64_t(1) << ch.maxLevel;
    samples += (n + 1) * (n + 2) / 2;
    atMaxLevel += ch.maxLevel == options.maxLevel ? 1 : 0;
    if (ch.maxLevel < options.maxLevel)
    {
      EXPECT_LE(ch.levelError[d], target) << "chart " << k << " stopped above the target";
    }
    if (ch.maxLevel > options.minLevel)
    {
      EXPECT_GT(ch.levelError[d - 1], target) << "chart " << k << " is finer than needed";
    }
  }
  std::printf("%s: target 1%%: %lld samples for %lld input points, %lld of %zu charts at "
              "maxLevel\n",
    GetParam().c_str(), static_cast<long long>(samples), static_cast<long long>(c.mesh.numPoints()),
    static_cast<long long>(atMaxLevel), atlas.charts.size());
}

INSTANTIATE_TEST_SUITE_P(Atlas, AtlasOnMesh, ::testing::ValuesIn(tctest::pipelineMeshes()),
  [](const ::testing::TestParamInfo<std::string>& info) { return info.param; });
