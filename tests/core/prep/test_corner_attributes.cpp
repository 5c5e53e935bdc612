// SPDX-License-Identifier: BSD-3-Clause
#include "tc/prep/corner_attributes.h"

#include <gtest/gtest.h>

#include <vector>

namespace
{
// A square of two triangles whose shared diagonal (points 0-2) is a UV seam: the right
// triangle's copies of its ends carry u + 1, as an exporter writes an island boundary.
struct SeamSquare
{
  tc::PolygonSoup soup;
  std::vector<double> uv;
};

SeamSquare seamSquare()
{
  SeamSquare s;
  s.soup.points = { 0, 0, 0, 1, 0, 0, 1, 1, 0, 0, 1, 0, 0, 0, 0, 1, 1, 0 };
  s.uv = { 0, 0, 1, 0, 1, 1, 0, 1, 1, 0, 2, 1 };
  const int64_t left[3] = { 0, 2, 3 };
  const int64_t right[3] = { 4, 1, 5 };
  s.soup.addPolygon(left, 3);
  s.soup.addPolygon(right, 3);
  return s;
}

double cornerU(const tc::CornerAttribute& a, const tc::PreparationResult& r, int64_t f, int32_t p)
{
  for (int k = 0; k < 3; ++k)
  {
    if (r.mesh.triangles[3 * f + k] == p)
    {
      return a.values[(3 * f + k) * 2];
    }
  }
  ADD_FAILURE() << "triangle " << f << " has no point " << p;
  return -1.0;
}
} // namespace

TEST(CornerAttributes, MergeKeepsEachCornersOwnValues)
{
  const SeamSquare s = seamSquare();
  const tc::PreparationResult r = tc::prepareMesh(s.soup);
  ASSERT_EQ(r.mesh.numPoints(), 4);
  const std::vector<int64_t> corners = tc::cornerInputPoints(s.soup, r);
  ASSERT_EQ(corners.size(), 6u);
  EXPECT_TRUE(tc::mergeSplitsAttribute(s.uv, 2, corners, r));
  const tc::CornerAttribute a = tc::makeCornerAttribute("UV", s.uv, 2, corners, r);
  // Point 0 (merged with soup point 4) has u = 0 in the left triangle and u = 1 in the right.
  EXPECT_EQ(cornerU(a, r, 0, 0), 0.0);
  EXPECT_EQ(cornerU(a, r, 1, 0), 1.0);
  EXPECT_EQ(cornerU(a, r, 0, 2), 1.0);
  EXPECT_EQ(cornerU(a, r, 1, 2), 2.0);
}

TEST(CornerAttributes, SeamSidesMarkTheDiagonalOnly)
{
  const SeamSquare s = seamSquare();
  const tc::PreparationResult r = tc::prepareMesh(s.soup);
  const std::vector<int64_t> corners = tc::cornerInputPoints(s.soup, r);
  const std::vector<uint8_t> seams =
    tc::seamSides(r.mesh.triangles, { tc::makeCornerAttribute("UV", s.uv, 2, corners, r) });
  ASSERT_EQ(seams.size(), 2u);
  for (int64_t f = 0; f < 2; ++f)
  {
    int marked = 0;
    for (int k = 0; k < 3; ++k)
    {
      if (seams[f] & (1u << k))
      {
        ++marked;
        const int32_t a = r.mesh.triangles[3 * f + k], b = r.mesh.triangles[3 * f + (k + 1) % 3];
        EXPECT_EQ(std::min(a, b), 0);
        EXPECT_EQ(std::max(a, b), 2);
      }
    }
    EXPECT_EQ(marked, 1) << "triangle " << f;
  }
}

TEST(CornerAttributes, ContinuousValuesNeedNoCorners)
{
  SeamSquare s = seamSquare();
  s.uv = { 0, 0, 1, 0, 1, 1, 0, 1, 0, 0, 1, 1 }; // the copies agree
  const tc::PreparationResult r = tc::prepareMesh(s.soup);
  const std::vector<int64_t> corners = tc::cornerInputPoints(s.soup, r);
  EXPECT_FALSE(tc::mergeSplitsAttribute(s.uv, 2, corners, r));
  const std::vector<uint8_t> seams =
    tc::seamSides(r.mesh.triangles, { tc::makeCornerAttribute("UV", s.uv, 2, corners, r) });
  EXPECT_EQ(seams, std::vector<uint8_t>(2, 0));
}
