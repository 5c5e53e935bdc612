// SPDX-License-Identifier: BSD-3-Clause
#include "tc/common/errors.h"
#include "tc/gim/atlas.h"
#include "tc/gim/build_memory.h"
#include "tc/gim/geometry_images.h"

#include <gtest/gtest.h>

#include <cstdint>
#include <limits>

namespace
{
/// A request under the budget rule (errorTarget 0) unless a target is given.
tc::BuildMemoryRequest request(int64_t points, int64_t triangles, int64_t budget = 0,
  int32_t maxLevel = 8, double errorTarget = 0.0)
{
  tc::BuildMemoryRequest r;
  r.points = points;
  r.triangles = triangles;
  r.sampleBudget = budget;
  r.maxLevel = maxLevel;
  r.errorTarget = errorTarget;
  return r;
}

constexpr double kMB = 1024.0 * 1024.0;
} // namespace

// The figures below are peak resident memory in MiB measured by /usr/bin/time -v for
// `trichart build MESH -o OUT -q --error-target 0` (2 threads), less the 105 MiB that Python and
// VTK hold before the build; the estimate must cover each, and by no more than half again to stay
// useful.
TEST(BuildMemory, CoversTheMeasuredPeaksOfTheSharedMeshes)
{
  struct Case
  {
    int64_t points, triangles, budget;
    int32_t maxLevel;
    double measuredMB;
  };
  const Case cases[] = {
    { 37706, 75408, 0, 8, 134 },        // static_medium/bunny00.off
    { 44460, 88928, 0, 8, 166 },        // static_medium/refined_elephant.off
    { 26002, 52000, 0, 8, 80 },         // static_medium/armadillo.off
    { 37706, 75408, 1600000, 10, 812 }, // bunny00.off --budget 1600000 --max-level 10
    { 603266, 1206528, 0, 8, 908 },     // static_large/bunny00_loop2.ply.gz (Nystrom)
  };
  for (const Case& c : cases)
  {
    const double mb =
      tc::estimateBuildMemory(request(c.points, c.triangles, c.budget, c.maxLevel)).peak() / kMB;
    EXPECT_GE(mb, c.measuredMB) << c.triangles << " triangles, budget " << c.budget;
    EXPECT_LE(mb, 1.5 * c.measuredMB) << c.triangles << " triangles, budget " << c.budget;
  }
}

TEST(BuildMemory, GrowsWithTheMeshAndTheBudget)
{
  const auto small = tc::estimateBuildMemory(request(1000, 2000));
  const auto large = tc::estimateBuildMemory(request(10000, 20000));
  EXPECT_GT(large.front, small.front);
  EXPECT_GT(large.images, small.images);
  const auto budget = tc::estimateBuildMemory(request(1000, 2000, 1000000, 12));
  EXPECT_GT(budget.images, small.images);
  EXPECT_EQ(budget.front, small.front); // the budget only matters to the geometry images
  EXPECT_EQ(budget.peak(), budget.images);
}

TEST(BuildMemory, AHundredMillionTrianglesNeedTensOfGigabytes)
{
  const auto e = tc::estimateBuildMemory(request(50000000, 100000000));
  EXPECT_GT(e.peak(), int64_t(60) << 30);
  EXPECT_LT(e.peak(), int64_t(120) << 30);
}

TEST(BuildMemory, TheLargestLevelCapsTheSamplesOfAHugeBudget)
{
  const auto e = tc::estimateBuildMemory(request(1839, 3674, 2000000000, 8));
  EXPECT_EQ(e.charts, 100); // the base target: fewer than 1 chart per 50 triangles here
  EXPECT_EQ(e.samples, 100 * tc::gridVertexCount(8));
  const auto fine = tc::estimateBuildMemory(request(1839, 3674, 2000000000, 12));
  EXPECT_EQ(fine.samples, 100 * tc::gridVertexCount(12));
  EXPECT_GT(fine.peak(), int64_t(20) << 30); // 840M samples: more than most machines have
  // Below the cap, the error rule measures up to two levels above the area rule: 16 x budget.
  EXPECT_EQ(tc::estimateBuildMemory(request(1839, 3674, 1000, 8)).samples, 16000);
  EXPECT_EQ(tc::estimateBuildMemory(request(1839, 3674, 0, 8)).samples, 16 * 1839);
  // An error target measures as many, each at more bytes.
  const auto target = tc::estimateBuildMemory(request(1839, 3674, 0, 8, 1e-3));
  EXPECT_EQ(target.samples, 16 * 1839);
  EXPECT_GT(target.images, tc::estimateBuildMemory(request(1839, 3674, 0, 8)).images);
  EXPECT_EQ(tc::BuildMemoryRequest{}.errorTarget, tc::GeometryImageOptions{}.errorTarget);
}

// Measured as above at the defaults (the error target). The estimate must cover each; it may be up
// to three times higher, since how many of the measuring's samples a target needs is not known
// before the build.
TEST(BuildMemory, CoversTheMeasuredPeaksUnderTheDefaultErrorTarget)
{
  struct Case
  {
    int64_t points, triangles;
    double measuredMB;
  };
  const Case cases[] = {
    { 221, 446, 11 },      // cad/joint.off
    { 1839, 3674, 11 },    // testing-data/meshes/bunny_npm.off
    { 6475, 12946, 26 },   // testing-data/meshes/fandisk.off
    { 4930, 9856, 22 },    // static_small/homer.off
    { 26002, 52000, 79 },  // static_medium/armadillo.off
    { 34835, 69666, 120 }, // static_medium/bunny_glmark2.obj
    { 37706, 75408, 132 }, // static_medium/bunny00.off
    { 44460, 88928, 165 }, // static_medium/refined_elephant.off
  };
  for (const Case& c : cases)
  {
    const double mb =
      tc::estimateBuildMemory(request(c.points, c.triangles, 0, 8, tc::kDefaultErrorTarget))
        .peak() /
      kMB;
    EXPECT_GE(mb, c.measuredMB) << c.triangles << " triangles";
    EXPECT_LE(mb, 3.0 * c.measuredMB) << c.triangles << " triangles";
  }
}

TEST(BuildMemory, TheExactGraphCostsMoreThanNystromPerTriangle)
{
  tc::BuildMemoryRequest exact = request(50000, 100000);
  tc::BuildMemoryRequest nystrom = exact;
  nystrom.nystromThreshold = 99999;
  EXPECT_GT(tc::estimateBuildMemory(exact).front, tc::estimateBuildMemory(nystrom).front);
}

TEST(BuildMemory, SaturatesInsteadOfOverflowingAndRefusesBadRequests)
{
  constexpr int64_t top = std::numeric_limits<int64_t>::max();
  const auto e = tc::estimateBuildMemory(request(top, top, top, 12));
  EXPECT_EQ(e.peak(), top);
  EXPECT_THROW(tc::estimateBuildMemory(request(-1, 10)), tc::InputError);
  EXPECT_THROW(tc::estimateBuildMemory(request(10, -1)), tc::InputError);
  EXPECT_THROW(tc::estimateBuildMemory(request(10, 10, -5)), tc::InputError);
  EXPECT_THROW(tc::estimateBuildMemory(request(10, 10, 0, 13)), tc::InputError);
  EXPECT_THROW(tc::estimateBuildMemory(request(10, 10, 0, -1)), tc::InputError);
}
