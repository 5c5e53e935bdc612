// SPDX-License-Identifier: BSD-3-Clause
// validateAtlas: a consistent atlas passes, and each broken invariant is refused with a message
// that names it.
#include "tc/gim/atlas.h"
#include "tc/common/errors.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <limits>
#include <string>
#include <vector>

namespace
{
// Octahedron: 6 base vertices, 8 counter-clockwise faces.
const double kCorners[6][3] = { { 1, 0, 0 }, { -1, 0, 0 }, { 0, 1, 0 }, { 0, -1, 0 }, { 0, 0, 1 },
  { 0, 0, -1 } };
const int kFaces[8][3] = { { 0, 2, 4 }, { 2, 1, 4 }, { 1, 3, 4 }, { 3, 0, 4 }, { 2, 0, 5 },
  { 1, 2, 5 }, { 3, 1, 5 }, { 0, 3, 5 } };

// A flat atlas over the octahedron: sample (i, j) of face (a, b, c) at level d is
// a + i/N (b - a) + j/N (c - a). Side samples are computed from the lower-numbered end so
// neighbours agree bit for bit. Charts 2m and 2m + 1 share rectangles.
tc::Atlas octahedronAtlas(const std::array<int32_t, 8>& maxLevels)
{
  tc::Atlas atlas;
  atlas.attributes = { { tc::kAtlasPosition, 3 }, { tc::kAtlasNormal, 3 } };
  atlas.charts.resize(8);
  for (int f = 0; f < 8; ++f)
  {
    tc::AtlasChart& c = atlas.charts[static_cast<size_t>(f)];
    c.maxLevel = maxLevels[static_cast<size_t>(f)];
    c.partner = f ^ 1;
    c.rotated = static_cast<uint8_t>(f & 1);
    for (int k = 0; k < 3; ++k)
    {
      c.cornerVertex[static_cast<size_t>(k)] = kFaces[f][k];
      const int a = kFaces[f][k];
      const int b = kFaces[f][(k + 1) % 3];
      for (int g = 0; g < 8; ++g)
      {
        for (int s = 0; s < 3; ++s)
        {
          if (kFaces[g][s] == b && kFaces[g][(s + 1) % 3] == a)
          {
            c.neighborChart[static_cast<size_t>(k)] = g;
            c.neighborSide[static_cast<size_t>(k)] = s;
          }
        }
      }
    }
  }
  const int32_t top = *std::max_element(maxLevels.begin(), maxLevels.end());
  atlas.images.resize(static_cast<size_t>(top) + 1);
  for (int32_t k = 0; k <= top; ++k)
  {
    // Pair m's rectangle (2^dh + 2) x (2^dh + 1) at x = m * (2^(top - k) + 2).
    const int32_t width = 4 * ((1 << (top - k)) + 2);
    const int32_t height = (1 << (top - k)) + 1;
    tc::AtlasImage& image = atlas.images[static_cast<size_t>(k)];
    image.width = width;
    image.height = height;
    image.data.assign(2, std::vector<float>(static_cast<size_t>(width * height * 3), 0.0f));
    for (int pair = 0; pair < 4; ++pair)
    {
      const int32_t dh = std::max(maxLevels[static_cast<size_t>(2 * pair)],
                           maxLevels[static_cast<size_t>(2 * pair + 1)]) -
        k;
      const int32_t x0 = pair * ((1 << (top - k)) + 2);
      for (int member = 0; member < 2; ++member)
      {
        tc::AtlasChart& c = atlas.charts[static_cast<size_t>(2 * pair + member)];
        if (c.maxLevel - k < 0)
        {
          continue;
        }
        if (dh >= 0)
        {
          c.origin.push_back(member == 0 ? std::array<int32_t, 2>{ x0, 0 }
                                         : std::array<int32_t, 2>{ x0 + (1 << dh) + 1, 1 << dh });
        }
      }
    }
  }
  for (int f = 0; f < 8; ++f)
  {
    const tc::AtlasChart& c = atlas.charts[static_cast<size_t>(f)];
    for (int32_t d = 0; d <= c.maxLevel; ++d)
    {
      const int32_t n = 1 << d;
      tc::AtlasImage& image = atlas.images[static_cast<size_t>(c.maxLevel - d)];
      for (int32_t j = 0; j <= n; ++j)
      {
        for (int32_t i = 0; i + j <= n; ++i)
        {
          // The side (if any) the sample lies on, evaluated from its lower-numbered end.
          int from = kFaces[f][0];
          int to = kFaces[f][1];
          int other = kFaces[f][2];
          double s = static_cast<double>(i) / n;
          double r = static_cast<double>(j) / n;
          if (i + j == n && j > 0)
          {
            from = kFaces[f][1];
            to = kFaces[f][2];
            s = static_cast<double>(j) / n;
            r = 0;
          }
          else if (i == 0 && j > 0)
          {
            from = kFaces[f][2];
            to = kFaces[f][0];
            s = static_cast<double>(n - j) / n;
            r = 0;
          }
          if (r == 0 && from > to)
          {
            std::swap(from, to);
            s = 1.0 - s;
          }
          const std::array<int32_t, 2> xy = tc::atlasTexel(c, d, i, j);
          float* p = image.data[0].data() + 3 * (xy[1] * image.width + xy[0]);
          float* nrm = image.data[1].data() + 3 * (xy[1] * image.width + xy[0]);
          for (int x = 0; x < 3; ++x)
          {
            p[x] =
              static_cast<float>(kCorners[from][x] + s * (kCorners[to][x] - kCorners[from][x]) +
                r * (kCorners[other][x] - kCorners[from][x]));
          }
          nrm[0] = nrm[1] = nrm[2] = 0.57735f;
        }
      }
    }
  }
  return atlas;
}

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
