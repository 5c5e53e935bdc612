// SPDX-License-Identifier: BSD-3-Clause
// validateAtlas: a consistent atlas passes, and each broken invariant is refused with a message
// that names it.
#include "tc/common/errors.h"
#include "tc/gim/atlas.h"

#include "octahedron_atlas.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <limits>
#include <string>
#include <vector>

namespace
{
using tctest::octahedronAtlas;

std::string refusal(const tc::Atlas& atlas)
{
  try
  {
    tc::validateAtlas(atlas);
  }
  catch (const tc::InputError& e)
  {
    return e.what();
  }
  return {};
}

const std::array<int32_t, 8> kLevels{ 3, 2, 4, 4, 1, 3, 0, 2 };
} // namespace

TEST(Atlas, AConsistentAtlasPasses)
{
  EXPECT_EQ(refusal(octahedronAtlas(kLevels)), "");
  EXPECT_EQ(refusal(octahedronAtlas({ 0, 0, 0, 0, 0, 0, 0, 0 })), "");
}

TEST(Atlas, TexelAddressingFollowsTheRotation)
{
  const tc::Atlas atlas = octahedronAtlas(kLevels);
  const tc::AtlasChart& lower = atlas.charts[2];
  const tc::AtlasChart& upper = atlas.charts[3];
  EXPECT_EQ(tc::atlasTexel(lower, 4, 1, 2), (std::array<int32_t, 2>{ lower.origin[0][0] + 1, 2 }));
  EXPECT_EQ(tc::atlasTexel(upper, 4, 1, 2),
    (std::array<int32_t, 2>{ upper.origin[0][0] - 1, upper.origin[0][1] - 2 }));
  EXPECT_EQ(tc::sidePoint(1, 3, 8), (std::array<int32_t, 2>{ 5, 3 }));
  EXPECT_EQ(tc::sidePoint(2, 3, 8), (std::array<int32_t, 2>{ 0, 5 }));
}

TEST(Atlas, RefusesAMovedSideSample)
{
  tc::Atlas atlas = octahedronAtlas(kLevels);
  // Charts 2 and 3 (both level 4) share side 1 of chart 2; move one of its samples in chart 2.
  const std::array<int32_t, 2> xy = tc::atlasTexel(atlas.charts[2], 4, 15, 1);
  atlas.images[0].data[0][static_cast<size_t>(3 * (xy[1] * atlas.images[0].width + xy[0]))] +=
    1e-6f;
  EXPECT_NE(refusal(atlas).find("copy of it"), std::string::npos) << refusal(atlas);
}

TEST(Atlas, RefusesACoarseSideThatIsNotASubsetOfTheFinerOne)
{
  tc::Atlas atlas = octahedronAtlas(kLevels);
  // Chart 2 (level 4) at its level 3, side 0 sample 1: moved in every chart that holds it would
  // still break the subset rule against its level 4.
  const std::array<int32_t, 2> xy = tc::atlasTexel(atlas.charts[2], 3, 1, 0);
  atlas.images[1].data[0][static_cast<size_t>(3 * (xy[1] * atlas.images[1].width + xy[0]) + 2)] =
    7.0f;
  EXPECT_NE(refusal(atlas), "");
}

TEST(Atlas, RefusesNeighboursThatDoNotNameEachOther)
{
  tc::Atlas atlas = octahedronAtlas(kLevels);
  atlas.charts[0].neighborSide[1] = (atlas.charts[0].neighborSide[1] + 1) % 3;
  EXPECT_NE(refusal(atlas).find("do not name each other"), std::string::npos) << refusal(atlas);
}

TEST(Atlas, RefusesOverlappingCharts)
{
  tc::Atlas atlas = octahedronAtlas({ 2, 2, 2, 2, 2, 2, 2, 2 });
  atlas.charts[3].origin = atlas.charts[1].origin;
  EXPECT_NE(refusal(atlas).find("share texel"), std::string::npos) << refusal(atlas);
}

TEST(Atlas, RefusesWrongSizesAndMissingParts)
{
  tc::Atlas atlas = octahedronAtlas(kLevels);
  atlas.images.pop_back();
  EXPECT_NE(refusal(atlas).find("images"), std::string::npos) << refusal(atlas);

  atlas = octahedronAtlas(kLevels);
  atlas.images[0].data[1].pop_back();
  EXPECT_NE(refusal(atlas).find("values, expected"), std::string::npos) << refusal(atlas);

  atlas = octahedronAtlas(kLevels);
  atlas.attributes[1].name = "Colour";
  EXPECT_NE(refusal(atlas).find("Position and Normal"), std::string::npos) << refusal(atlas);

  atlas = octahedronAtlas(kLevels);
  atlas.charts[5].origin[0][0] = atlas.images[0].width;
  EXPECT_NE(refusal(atlas).find("outside image"), std::string::npos) << refusal(atlas);
}

TEST(Atlas, RefusesNonFinitePositions)
{
  tc::Atlas atlas = octahedronAtlas(kLevels);
  const std::array<int32_t, 2> xy = tc::atlasTexel(atlas.charts[4], 1, 1, 1);
  atlas.images[0].data[0][static_cast<size_t>(3 * (xy[1] * atlas.images[0].width + xy[0]))] =
    std::numeric_limits<float>::quiet_NaN();
  EXPECT_NE(refusal(atlas).find("finite"), std::string::npos) << refusal(atlas);
}
