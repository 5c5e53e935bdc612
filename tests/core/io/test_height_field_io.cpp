// SPDX-License-Identifier: BSD-3-Clause
#include "tc/common/errors.h"
#include "tc/io/height_field_io.h"

#include "temp_folder.h"
#include "test_data.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <set>
#include <string>
#include <utility>
#include <vector>

namespace
{
class HeightFieldIo : public tctest::TempFolderTest
{
protected:
  /// A 4 x 3 ESRI ASCII grid at (1000, 2000) with 10 m cells; `corner` is the first value.
  std::string asciiGrid(const std::string& corner = "1")
  {
    return write("dem.asc",
      "ncols 4\nnrows 3\nxllcorner 1000\nyllcorner 2000\ncellsize 10\nNODATA_value -9999\n" +
        corner + " 2 3 4\n5 6 7 8\n9 10 11 12\n");
  }

  /// A 16-bit binary PGM of `columns` x `rows` heights 100, 101, ...
  std::string pgm(const std::string& name, int columns, int rows)
  {
    std::string bytes = "P5\n" + std::to_string(columns) + " " + std::to_string(rows) + "\n65535\n";
    for (int k = 0; k < columns * rows; ++k)
    {
      bytes += static_cast<char>((100 + k) >> 8);
      bytes += static_cast<char>((100 + k) & 255);
    }
    return write(name, bytes);
  }
};

/// The z of the normal of every triangle (unnormalized).
std::vector<double> normalZ(const tc::TriMesh& mesh)
{
  std::vector<double> z;
  for (int64_t t = 0; t < mesh.numTriangles(); ++t)
  {
    const auto a = mesh.point(mesh.triangles[3 * t]), b = mesh.point(mesh.triangles[3 * t + 1]),
               c = mesh.point(mesh.triangles[3 * t + 2]);
    z.push_back((b[0] - a[0]) * (c[1] - a[1]) - (b[1] - a[1]) * (c[0] - a[0]));
  }
  return z;
}

std::set<std::pair<int32_t, int32_t>> edges(const tc::TriMesh& mesh)
{
  std::set<std::pair<int32_t, int32_t>> out;
  for (size_t t = 0; t < mesh.triangles.size(); t += 3)
  {
    for (int k = 0; k < 3; ++k)
    {
      const int32_t u = mesh.triangles[t + k], v = mesh.triangles[t + (k + 1) % 3];
      out.insert({ std::min(u, v), std::max(u, v) });
    }
  }
  return out;
}
} // namespace

TEST_F(HeightFieldIo, AnAsciiGridIsReadAtItsCellCentresInMetres)
{
  const tc::HeightField field = tc::readHeightField(asciiGrid());
  ASSERT_EQ(field.columns, 4);
  ASSERT_EQ(field.rows, 3);
  // The first row is the northern one: its centres lie half a cell below the top edge (2030).
  EXPECT_DOUBLE_EQ(field.origin[0], 1005.0);
  EXPECT_DOUBLE_EQ(field.origin[1], 2025.0);
  EXPECT_EQ(field.steps, (std::array<double, 4>{ 10.0, 0.0, 0.0, -10.0 }));
  EXPECT_EQ(field.heights.front(), 1.0);
  EXPECT_EQ(field.heights.back(), 12.0);
}

TEST_F(HeightFieldIo, EveryTriangleFacesUpAndNoDataLeavesAHole)
{
  const tc::HeightFieldMesh full = tc::triangulateHeightField(tc::readHeightField(asciiGrid()));
  EXPECT_EQ(full.mesh.numPoints(), 12);
  EXPECT_EQ(full.mesh.numTriangles(), 12); // 3 x 2 squares, 2 triangles each
  const tc::HeightFieldMesh holed =
    tc::triangulateHeightField(tc::readHeightField(asciiGrid("-9999")));
  EXPECT_EQ(holed.noDataCells, 1);
  EXPECT_EQ(holed.mesh.numPoints(), 11);
  EXPECT_EQ(holed.mesh.numTriangles(), 11); // the corner square keeps its 3 cells' triangle
  for (const tc::HeightFieldMesh* mesh : { &full, &holed })
  {
    for (const double z : normalZ(mesh->mesh))
    {
      EXPECT_GT(z, 0.0);
    }
  }
  EXPECT_EQ(holed.heights.front(), 2.0f);
}

TEST_F(HeightFieldIo, ASquareIsSplitAlongTheDiagonalOfLeastHeightChange)
{
  // Cells 0 1 / 2 3: a ridge of 9s along 1-2 is cut along it, one along 0-3 along that one.
  for (const auto& [values, a, b] : { std::tuple{ "0 9\n9 1\n", 1, 2 }, { "9 0\n1 9\n", 0, 3 } })
  {
    const std::string path = write("ridge.asc",
      std::string("ncols 2\nnrows 2\nxllcorner 0\nyllcorner 0\ncellsize 1\n") + values);
    const tc::HeightFieldMesh mesh = tc::triangulateHeightField(tc::readHeightField(path));
    ASSERT_EQ(mesh.mesh.numTriangles(), 2);
    EXPECT_TRUE(edges(mesh.mesh).count({ a, b })) << values;
  }
}

TEST_F(HeightFieldIo, TheVerticalScaleMultipliesHeightsAndMustBePositive)
{
  const tc::HeightField field = tc::readHeightField(asciiGrid());
  tc::HeightFieldOptions options;
  options.verticalScale = 2.5;
  const tc::HeightFieldMesh mesh = tc::triangulateHeightField(field, options);
  EXPECT_DOUBLE_EQ(mesh.mesh.points[2], 2.5);
  EXPECT_EQ(mesh.heights[0], 1.0f);
  for (const double bad : { 0.0, -1.0, std::nan("") })
  {
    options.verticalScale = bad;
    EXPECT_THROW(tc::triangulateHeightField(field, options), tc::InputError);
  }
}

TEST_F(HeightFieldIo, ASideFileGivesSpacingInDegreesConvertedToMetres)
{
  const std::string raster = pgm("dem_3x2.pgm", 3, 2);
  write("dem.json",
    R"({"dx": 0.001, "dy": 0.001, "xmin": -84.4, "ymin": 36.6005, "ymax": 36.5995,
        "rows": 2, "cols": 3, "height_units": "m"})");
  const tc::HeightField field = tc::readHeightField(raster);
  ASSERT_EQ(field.columns, 3);
  EXPECT_EQ(field.heights[4], 104.0);
  // At latitude 36.6 a degree of longitude is 89,470 m and one of latitude 110,966 m.
  EXPECT_NEAR(field.steps[0], 89.470, 0.05);
  EXPECT_NEAR(field.steps[3], -110.966, 0.05);
  EXPECT_EQ(field.heightUnit, "m");
  write("dem.json", R"({"dx": 0.001, "dy": 0.001, "rows": 5, "cols": 3})");
  EXPECT_THROW(tc::readHeightField(raster), tc::InputError);
  write("dem.json", "{ not json");
  EXPECT_THROW(tc::readHeightField(raster), tc::InputError);
}

TEST_F(HeightFieldIo, APlainHeightMapIsOneUnitPerCell)
{
  const tc::HeightField field = tc::readHeightField(pgm("plain.pgm", 3, 2));
  EXPECT_EQ(field.steps, (std::array<double, 4>{ 1.0, 0.0, 0.0, -1.0 }));
  ASSERT_FALSE(field.notes.empty());
  EXPECT_NE(field.notes.back().find("no unit"), std::string::npos);
}

TEST_F(HeightFieldIo, WhatIsNoHeightFieldIsRefusedWithTheReason)
{
  EXPECT_THROW(tc::readHeightField(write("text.tif", "not a tiff at all")), tc::InputError);
  EXPECT_THROW(tc::readHeightField(file("missing.tif")), tc::InputError);
  EXPECT_THROW(tc::readHeightField(
                 write("one.asc", "ncols 1\nnrows 1\nxllcorner 0\nyllcorner 0\ncellsize 1\n5\n")),
    tc::InputError);
  EXPECT_THROW(
    tc::readHeightField(write("empty.asc",
      "ncols 2\nnrows 2\nxllcorner 0\nyllcorner 0\ncellsize 1\nNODATA_value 0\n0 0\n0 0\n")),
    tc::InputError);
  try
  {
    tc::readHeightField(write("text.tif", "not a tiff at all"));
  }
  catch (const tc::InputError& e)
  {
    EXPECT_NE(std::string(e.what()).find("text.tif"), std::string::npos) << e.what();
  }
}

TEST_F(HeightFieldIo, AHeaderDeclaringMoreCellsThanFitIsRefusedBeforeTheRead)
{
  // 46,000^2 cells: 135 GB of grid, declared in a 70-byte file.
  const std::string path =
    write("huge.asc", "ncols 46000\nnrows 46000\nxllcorner 0\nyllcorner 0\ncellsize 1\n1 2 3\n");
  try
  {
    tc::readHeightField(path);
    FAIL() << "a huge declared raster was read";
  }
  catch (const tc::InputError& e)
  {
    EXPECT_NE(std::string(e.what()).find("2116000000 cells"), std::string::npos) << e.what();
  }
}

TEST_F(HeightFieldIo, TheExtensionsAreTheRasterFormats)
{
  EXPECT_TRUE(tc::isHeightFieldFile("dem.TIF"));
  EXPECT_TRUE(tc::isHeightFieldFile("a/b/srtm.hgt"));
  EXPECT_FALSE(tc::isHeightFieldFile(".tif"));
  EXPECT_FALSE(tc::isHeightFieldFile("mesh.ply"));
}

TEST(HeightFieldShared, TheSharedDemBuildsAGridOfItsCellsInMetres)
{
  const std::string path = tctest::sharedData("terrain/jacksboro_fault_dem_403x344.pgm");
  if (path.empty())
  {
    GTEST_SKIP() << "terrain/jacksboro_fault_dem_403x344.pgm is not in the shared data";
  }
  const tc::HeightFieldMesh mesh = tc::triangulateHeightField(tc::readHeightField(path));
  EXPECT_EQ(mesh.mesh.numPoints(), 403 * 344);
  EXPECT_EQ(mesh.mesh.numTriangles(), 2 * 402 * 343);
  const auto [low, high] = std::minmax_element(mesh.heights.begin(), mesh.heights.end());
  EXPECT_EQ(*low, 236.0f);
  EXPECT_EQ(*high, 1076.0f);
  // 3 arc-seconds at latitude 36.6: 74.6 m east-west, 92.5 m north-south.
  EXPECT_NEAR(mesh.mesh.points[3], 74.6, 0.1);
  EXPECT_NEAR(mesh.mesh.points[3 * 403 + 1], -92.5, 0.1);
}
