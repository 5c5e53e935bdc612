// SPDX-License-Identifier: BSD-3-Clause
#include "tc/common/errors.h"
#include "tc/io/off_io.h"

#include "temp_folder.h"
#include "test_data.h"

#include <gtest/gtest.h>

#include <chrono>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <limits>
#include <random>
#include <string>

namespace
{
namespace fs = std::filesystem;

/// Files in a fresh folder per test.
class OffFiles : public tctest::TempFolderTest
{
protected:
  /// The message of the tc::InputError that readOFF throws for `text` ("" if none).
  std::string readError(const std::string& text) const
  {
    const std::string path = write("bad.off", text);
    try
    {
      tc::readOFF(path);
    }
    catch (const tc::InputError& error)
    {
      return error.what();
    }
    return "";
  }
};

struct SharedMesh
{
  const char* path;
  int64_t vertices;
  int64_t triangles;
};

// Counts from ../shared/data/README.md.
const SharedMesh kSharedMeshes[] = {
  { "static_small/bunny_npm.off", 1839, 3674 },
  { "static_small/elephant.off", 2775, 5558 },
  { "static_small/cow.off", 2904, 5804 },
  { "static_small/homer.off", 4930, 9856 },
  { "static_small/teapot_npm.off", 792, 992 },
  { "static_medium/armadillo.off", 26002, 52000 },
  { "static_medium/bunny00.off", 37706, 75408 },
  { "static_medium/refined_elephant.off", 44460, 88928 },
  { "cad/fandisk.off", 6475, 12946 },
  { "cad/fandisk_large.off", 15843, 31682 },
  { "cad/couplingdown.off", 1841, 3714 },
  { "cad/rotor.off", 600, 1200 },
  { "cad/pinion.off", 650, 1300 },
  { "cad/anchor.off", 519, 1050 },
  { "cad/joint.off", 221, 446 },
  { "cad/cube.off", 8, 12 },
  { "cad/blade.off", 8231, 16222 },
};
} // namespace

TEST_F(OffFiles, OffReadsEverySharedMeshWithTheReadmeCounts)
{
  int missing = 0;
  for (const SharedMesh& mesh : kSharedMeshes)
  {
    SCOPED_TRACE(mesh.path);
    const std::string path = tctest::sharedData(mesh.path);
    if (path.empty())
    {
      ++missing;
      continue;
    }
    const tc::PolygonSoup soup = tc::readOFF(path);
    EXPECT_EQ(soup.numPoints(), mesh.vertices);
    ASSERT_EQ(soup.numPolygons(), mesh.triangles);
    for (int64_t p = 0; p < soup.numPolygons(); ++p)
    {
      ASSERT_EQ(soup.offsets[p + 1] - soup.offsets[p], 3) << "polygon " << p;
    }
    for (int64_t id : soup.connectivity)
    {
      ASSERT_TRUE(id >= 0 && id < soup.numPoints());
    }
    for (double x : soup.points)
    {
      ASSERT_TRUE(std::isfinite(x));
    }
  }
  if (missing > 0)
  {
    GTEST_SKIP() << missing << " meshes of ../shared/data are absent";
  }
}

TEST_F(OffFiles, OffReadsCubeValuesExactly)
{
  const std::string path = tctest::sharedData("cad/cube.off");
  if (path.empty())
  {
    GTEST_SKIP() << "../shared/data/cad/cube.off is absent";
  }
  const tc::PolygonSoup soup = tc::readOFF(path);
  ASSERT_EQ(soup.numPoints(), 8);
  EXPECT_EQ(soup.points[0], -1.0);
  EXPECT_EQ(soup.points[3 * 7 + 2], 1.0);
  const std::vector<int64_t> first = { 0, 1, 3 };
  const std::vector<int64_t> last = { 2, 1, 6 };
  EXPECT_EQ(std::vector<int64_t>(soup.connectivity.begin(), soup.connectivity.begin() + 3), first);
  EXPECT_EQ(std::vector<int64_t>(soup.connectivity.end() - 3, soup.connectivity.end()), last);
}

TEST_F(OffFiles, OffReadsALargeFile)
{
  const std::string path = tctest::sharedData("static_medium/refined_elephant.off");
  if (path.empty())
  {
    GTEST_SKIP() << "../shared/data/static_medium/refined_elephant.off is absent";
  }
  const tc::PolygonSoup soup = tc::readOFF(path);
  EXPECT_EQ(soup.numPolygons(), 88928);
  EXPECT_EQ(soup.numPoints(), 44460);
}

TEST_F(OffFiles, OffReadsVariantsCommentsColoursAndCountsOnTheKeywordLine)
{
  const std::string text = "# made by hand\r\n"
                           "COFF 4 2 5 # counts on the keyword line\r\n"
                           "\r\n"
                           "0 0 0 255 0 0 255\r\n"
                           "+1.5 0 0 0 255 0 255   # a comment after data\r\n"
                           "0 2e0 -0 0 0 255 255\r\n"
                           "\t1 1 1 10 10 10 255\r\n"
                           "# faces\r\n"
                           "3 0 1 2 1 0 0\r\n"
                           "4 0 1 3 2\r\n"
                           "2 0 1\r\n"; // an edge list after the faces is ignored
  const tc::PolygonSoup soup = tc::readOFF(write("coloured.off", text));
  ASSERT_EQ(soup.numPoints(), 4);
  ASSERT_EQ(soup.numPolygons(), 2);
  EXPECT_EQ(soup.points[3], 1.5);
  EXPECT_EQ(soup.points[7], 2.0);
  EXPECT_TRUE(std::signbit(soup.points[8]));
  EXPECT_EQ(soup.points[9], 1.0);
  EXPECT_EQ(soup.offsets, (std::vector<int64_t>{ 0, 3, 7 }));
  EXPECT_EQ(soup.connectivity, (std::vector<int64_t>{ 0, 1, 2, 0, 1, 3, 2 }));
}

TEST_F(OffFiles, OffReadsNormalsTextureAnd4DVariants)
{
  const tc::PolygonSoup noff =
    tc::readOFF(write("n.off", "NOFF\n3 1 0\n0 0 0 0 0 1\n1 0 0 0 0 1\n0 1 0 0 0 1\n3 0 1 2\n"));
  EXPECT_EQ(noff.points, (std::vector<double>{ 0, 0, 0, 1, 0, 0, 0, 1, 0 }));
  const tc::PolygonSoup stoff = tc::readOFF(write("st.off",
    "STCNOFF\n3 1 0\n0 0 0 0 0 1 1 1 1 1 0 0\n1 0 0 0 0 1 1 1 1 1 1 "
    "0\n0 1 0 0 0 1 1 1 1 1 0 1\n3 0 1 2\n"));
  EXPECT_EQ(stoff.points, noff.points);
  const tc::PolygonSoup homogeneous =
    tc::readOFF(write("4.off", "4OFF\n3 1 0\n0 0 0 2\n2 0 0 2\n0 2 0 2\n3 0 1 2\n"));
  EXPECT_EQ(homogeneous.points, noff.points);
  const tc::PolygonSoup dimension =
    tc::readOFF(write("n2.off", "nOFF\n2\n3 1 0\n0 0\n1 0\n0 1\n3 0 1 2\n"));
  EXPECT_EQ(dimension.points, noff.points);
  const tc::PolygonSoup noEdgeCount =
    tc::readOFF(write("ve.off", "OFF\n3 1\n0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n"));
  EXPECT_EQ(noEdgeCount.points, noff.points);
}

TEST_F(OffFiles, OffReadsNanAndInfCoordinates)
{
  const tc::PolygonSoup soup =
    tc::readOFF(write("nan.off", "OFF\n3 1 0\nnan 0 0\n1 inf 0\n0 1 -Infinity\n3 0 1 2\n"));
  EXPECT_TRUE(std::isnan(soup.points[0]));
  EXPECT_EQ(soup.points[4], std::numeric_limits<double>::infinity());
  EXPECT_EQ(soup.points[8], -std::numeric_limits<double>::infinity());
}

TEST_F(OffFiles, OffMissingFileThrowsNamingIt)
{
  const std::string path = (Folder / "nowhere.off").string();
  try
  {
    tc::readOFF(path);
    FAIL() << "no exception";
  }
  catch (const tc::InputError& error)
  {
    EXPECT_NE(std::string(error.what()).find(path), std::string::npos) << error.what();
    EXPECT_NE(std::string(error.what()).find("does not exist"), std::string::npos);
  }
}

TEST_F(OffFiles, OffGarbageThrowsNotAnOffFile)
{
  const std::string message = readError("ply\nformat ascii 1.0\n");
  EXPECT_NE(message.find("bad.off:1:"), std::string::npos) << message;
  EXPECT_NE(message.find("not an OFF file"), std::string::npos) << message;
  EXPECT_NE(readError("").find("empty"), std::string::npos);
  EXPECT_NE(readError("\x01\x02\xff\xfe garbage").find("not an OFF file"), std::string::npos);
}

TEST_F(OffFiles, OffTruncatedFileThrowsWithTheLine)
{
  const std::string vertices = readError("OFF\n4 2 0\n0 0 0\n1 0 0\n");
  EXPECT_NE(vertices.find("bad.off:4:"), std::string::npos) << vertices;
  EXPECT_NE(vertices.find("2 of 4 vertices"), std::string::npos) << vertices;
  const std::string faces = readError("OFF\n3 2 0\n0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n");
  EXPECT_NE(faces.find("bad.off:6:"), std::string::npos) << faces;
  EXPECT_NE(faces.find("1 of 2 faces"), std::string::npos) << faces;
  const std::string face = readError("OFF\n3 1 0\n0 0 0\n1 0 0\n0 1 0\n3 0 1\n");
  EXPECT_NE(face.find("bad.off:6:"), std::string::npos) << face;
  EXPECT_NE(face.find("2 corner indices, expected 3"), std::string::npos) << face;
  const std::string vertex = readError("OFF\n3 1 0\n0 0 0\n1 0\n0 1 0\n3 0 1 2\n");
  EXPECT_NE(vertex.find("bad.off:4:"), std::string::npos) << vertex;
  EXPECT_NE(vertex.find("2 coordinates"), std::string::npos) << vertex;
}

TEST_F(OffFiles, OffNonNumericTokenThrowsWithTheLine)
{
  const std::string coordinate = readError("OFF\n3 1 0\n0 0 0\n1 zero 0\n0 1 0\n3 0 1 2\n");
  EXPECT_NE(coordinate.find("bad.off:4:"), std::string::npos) << coordinate;
  EXPECT_NE(coordinate.find("'zero' is not a number"), std::string::npos) << coordinate;
  const std::string index = readError("OFF\n3 1 0\n0 0 0\n1 0 0\n0 1 0\n3 0 1.5 2\n");
  EXPECT_NE(index.find("bad.off:6:"), std::string::npos) << index;
  EXPECT_NE(index.find("'1.5' is not a vertex index"), std::string::npos) << index;
}

TEST_F(OffFiles, OffBadCountsThrow)
{
  EXPECT_NE(readError("OFF\n-3 1 0\n").find("bad.off:2: bad vertex count"), std::string::npos);
  EXPECT_NE(readError("OFF\n3\n").find("face count"), std::string::npos);
  EXPECT_NE(readError("OFF\n").find("counts"), std::string::npos);
  const std::string huge = readError("OFF 1000000000 1 0\n0 0 0\n");
  EXPECT_NE(huge.find("do not fit"), std::string::npos) << huge;
  const std::string corners = readError("OFF\n3 1 0\n0 0 0\n1 0 0\n0 1 0\n0\n");
  EXPECT_NE(corners.find("bad.off:6:"), std::string::npos) << corners;
  EXPECT_NE(readError("OFF BINARY\n").find("binary"), std::string::npos);
}

TEST_F(OffFiles, OffIndexOutOfRangeThrowsWithTheLine)
{
  const std::string message = readError("OFF\n3 1 0\n0 0 0\n1 0 0\n0 1 0\n\n# face\n3 0 1 3\n");
  EXPECT_NE(message.find("bad.off:8:"), std::string::npos) << message;
  EXPECT_NE(message.find("vertex index 3 is out of range"), std::string::npos) << message;
  EXPECT_NE(readError("OFF\n3 1 0\n0 0 0\n1 0 0\n0 1 0\n3 0 -1 2\n").find("out of range"),
    std::string::npos);
}

TEST_F(OffFiles, OffWriteThenReadIsBitExact)
{
  std::mt19937_64 random(7);
  std::uniform_real_distribution<double> uniform(-1.0, 1.0);
  tc::TriMesh mesh;
  const int nv = 500;
  for (int i = 0; i < 3 * nv; ++i)
  {
    mesh.points.push_back(uniform(random) * std::pow(10.0, static_cast<int>(i % 41) - 20));
  }
  // Values whose text form is hard to get right.
  mesh.points[0] = -0.0;
  mesh.points[1] = std::numeric_limits<double>::denorm_min();
  mesh.points[2] = std::numeric_limits<double>::max();
  mesh.points[3] = 0.1;
  mesh.points[4] = 1.0 / 3.0;
  mesh.points[5] = -std::numeric_limits<double>::min();
  for (int f = 0; f < 800; ++f)
  {
    for (int c = 0; c < 3; ++c)
    {
      mesh.triangles.push_back(static_cast<int32_t>(random() % nv));
    }
  }
  const std::string path = (Folder / "round.off").string();
  tc::writeOFF(path, mesh);
  const tc::PolygonSoup soup = tc::readOFF(path);
  ASSERT_EQ(soup.points.size(), mesh.points.size());
  EXPECT_EQ(std::memcmp(soup.points.data(), mesh.points.data(), 8 * mesh.points.size()), 0);
  ASSERT_EQ(soup.numPolygons(), mesh.numTriangles());
  for (size_t k = 0; k < mesh.triangles.size(); ++k)
  {
    ASSERT_EQ(soup.connectivity[k], mesh.triangles[k]);
  }
}

TEST_F(OffFiles, OffWriteReplacesAFileAndLeavesNoTemporary)
{
  const std::string path = write("mesh.off", "old content");
  tc::TriMesh mesh;
  mesh.points = { 0, 0, 0, 1, 0, 0, 0, 1, 0 };
  mesh.triangles = { 0, 1, 2 };
  tc::writeOFF(path, mesh);
  EXPECT_EQ(tc::readOFF(path).numPolygons(), 1);
  int files = 0;
  for (const auto& entry : fs::directory_iterator(Folder))
  {
    ++files;
    EXPECT_EQ(entry.path().filename(), "mesh.off");
  }
  EXPECT_EQ(files, 1);
}

TEST_F(OffFiles, OffWriteIntoAMissingFolderThrowsAndLeavesNothing)
{
  tc::TriMesh mesh;
  mesh.points = { 0, 0, 0, 1, 0, 0, 0, 1, 0 };
  mesh.triangles = { 0, 1, 2 };
  const fs::path target = Folder / "missing" / "mesh.off";
  try
  {
    tc::writeOFF(target.string(), mesh);
    FAIL() << "no exception";
  }
  catch (const tc::InputError& error)
  {
    EXPECT_NE(std::string(error.what()).find(target.string()), std::string::npos) << error.what();
  }
  EXPECT_FALSE(fs::exists(target.parent_path()));
  EXPECT_TRUE(fs::is_empty(Folder));
}

TEST_F(OffFiles, OffWriteRejectsATriangleOutOfRange)
{
  tc::TriMesh mesh;
  mesh.points = { 0, 0, 0, 1, 0, 0, 0, 1, 0 };
  mesh.triangles = { 0, 1, 3 };
  const std::string path = (Folder / "mesh.off").string();
  EXPECT_THROW(tc::writeOFF(path, mesh), tc::InputError);
  EXPECT_TRUE(fs::is_empty(Folder));
}
