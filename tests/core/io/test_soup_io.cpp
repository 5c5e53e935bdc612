// SPDX-License-Identifier: BSD-3-Clause
#include "tc/common/errors.h"
#include "tc/io/soup_io.h"

#include "temp_folder.h"
#include "test_data.h"

#include <gtest/gtest.h>

#include <zlib.h>

#include <algorithm>
#include <cstdint>
#include <cstring>
#include <iostream>
#include <string>
#include <vector>

namespace
{
/// PLY and OBJ files in a fresh folder per test.
class SoupFiles : public tctest::TempFolderTest
{
protected:
  /// The message of the tc::InputError readPLY throws for `bytes` ("" if it reads).
  std::string readError(const std::string& bytes, const std::string& name = "bad.ply") const
  {
    try
    {
      tc::readPLY(write(name, bytes));
    }
    catch (const tc::InputError& e)
    {
      return e.what();
    }
    return "";
  }

  /// Reads every copy with `read` as `name`: each gives faces whose corners exist, or is
  /// refused with tc::InputError (a crash fails the test program). Returns the refused count.
  template <typename Read>
  int refusedCopies(const std::vector<std::string>& copies, const std::string& name, Read read)
  {
    int refused = 0;
    for (const std::string& copy : copies)
    {
      try
      {
        const tc::PolygonSoup soup = read(write(name, copy));
        for (const int64_t id : soup.connectivity)
        {
          EXPECT_TRUE(id >= 0 && id < soup.numPoints()) << id;
        }
      }
      catch (const tc::InputError&)
      {
        ++refused;
      }
    }
    return refused;
  }
};

bool mentions(const std::string& message, const std::string& what)
{
  return message.find(what) != std::string::npos;
}

/// A square of two triangles and a quad face on top, as PLY in `format`.
std::string squarePly(const std::string& format)
{
  const float points[5][3] = { { 0, 0, 0 }, { 1, 0, 0 }, { 1, 1, 0 }, { 0, 1, 0 }, { 0.5f, 0.5f,
    1 } };
  const std::vector<std::vector<int32_t>> faces = { { 0, 1, 2 }, { 0, 2, 3 }, { 0, 1, 4, 3 } };
  std::string out = "ply\nformat " + format +
    " 1.0\ncomment a test square\nelement vertex 5\nproperty float x\nproperty float y\n"
    "property float z\nproperty uchar red\nelement face 3\n"
    "property list uchar int vertex_indices\nend_header\n";
  const bool big = format == "binary_big_endian";
  const auto put = [&out, big](const void* value, size_t n)
  {
    std::string bytes(static_cast<const char*>(value), n);
    if (big)
    {
      std::reverse(bytes.begin(), bytes.end());
    }
    out += bytes;
  };
  for (const auto& p : points)
  {
    if (format == "ascii")
    {
      out += std::to_string(p[0]) + " " + std::to_string(p[1]) + " " + std::to_string(p[2]) +
        " 7\n";
      continue;
    }
    for (const float c : p)
    {
      put(&c, 4);
    }
    const uint8_t red = 7;
    put(&red, 1);
  }
  for (const auto& f : faces)
  {
    if (format == "ascii")
    {
      out += std::to_string(f.size());
      for (const int32_t i : f)
      {
        out += " " + std::to_string(i);
      }
      out += "\n";
      continue;
    }
    const uint8_t n = static_cast<uint8_t>(f.size());
    put(&n, 1);
    for (const int32_t i : f)
    {
      put(&i, 4);
    }
  }
  return out;
}
} // namespace

TEST_F(SoupFiles, AsciiAndBinaryOfBothByteOrdersReadTheSameMesh)
{
  for (const char* format : { "ascii", "binary_little_endian", "binary_big_endian" })
  {
    const tc::PolygonSoup soup = tc::readPLY(write("square.ply", squarePly(format)));
    ASSERT_EQ(soup.numPoints(), 5) << format;
    ASSERT_EQ(soup.numPolygons(), 3) << format;
    EXPECT_EQ(soup.offsets, (std::vector<int64_t>{ 0, 3, 6, 10 })) << format;
    EXPECT_EQ(soup.connectivity, (std::vector<int64_t>{ 0, 1, 2, 0, 2, 3, 0, 1, 4, 3 }));
    EXPECT_EQ(soup.points[3 * 4 + 0], 0.5) << format;
    EXPECT_EQ(soup.points[3 * 4 + 2], 1.0) << format;
  }
}

TEST_F(SoupFiles, GzipCompressedFilesAreInflatedFirst)
{
  const std::string raw = squarePly("binary_little_endian");
  const std::string path = file("square.ply.gz");
  gzFile gz = gzopen(path.c_str(), "wb");
  gzwrite(gz, raw.data(), static_cast<unsigned>(raw.size()));
  gzclose(gz);
  EXPECT_EQ(tc::readPLY(path).numPolygons(), 3);
  EXPECT_TRUE(mentions(readError("not gzip data", "broken.ply.gz"), "is not a valid gzip file"));
}

TEST_F(SoupFiles, BadFilesAreRefusedWithWhatIsWrong)
{
  EXPECT_TRUE(mentions(readError("OFF\n3 1 0\n"), "does not start with 'ply'"));
  EXPECT_TRUE(mentions(readError(""), "does not start with 'ply'"));
  const std::string binary = squarePly("binary_little_endian");
  const std::string cut = readError(binary.substr(0, binary.size() - 10));
  EXPECT_TRUE(mentions(cut, "declares 5 vertices and 3 faces, and 5 vertices and 2 faces were "
                            "read"))
    << cut;
  std::string outOfRange = squarePly("ascii");
  outOfRange.replace(outOfRange.rfind("4 0 1 4 3"), 9, "4 0 1 9 3");
  EXPECT_TRUE(mentions(readError(outOfRange), "face 2 refers to vertex 9, and the file has 5"))
    << readError(outOfRange);
  const std::string cloud = "ply\nformat ascii 1.0\nelement vertex 2\nproperty float x\n"
                            "property float y\nproperty float z\nend_header\n0 0 0\n1 1 1\n";
  EXPECT_TRUE(mentions(readError(cloud), "has no faces (2 vertices)")) << readError(cloud);
  EXPECT_TRUE(mentions(readError(squarePly("ascii"), "missing/none.ply"), "cannot open"));
}

TEST_F(SoupFiles, DamagedCopiesOfAScanAreRefusedOrReadNeverCrash)
{
  // VTK's PLY reader crashed on 44 of 324 truncated or byte-flipped files; every copy here is
  // read into faces that refer to existing vertices, or refused with tc::InputError.
  std::vector<std::string> sources = { squarePly("binary_little_endian"), squarePly("ascii") };
  const std::string scan = tctest::sharedData("static_small/dragon_vrip_res4.ply.gz");
  if (!scan.empty())
  {
    sources.push_back(tc::readGzip(scan));
  }
  int tried = 0, refused = 0;
  for (const std::string& bytes : sources)
  {
    const std::vector<std::string> copies = tctest::damagedCopies(bytes, 5, 30);
    tried += static_cast<int>(copies.size());
    refused += refusedCopies(copies, "damaged.ply", tc::readPLY);
  }
  std::cout << "[ figures  ] " << refused << " of " << tried << " damaged copies refused\n";
  EXPECT_GT(refused, 0);
}

TEST_F(SoupFiles, ObjFacesTakeTheFirstIndexOfEachCornerAndCountNegativeOnesBack)
{
  const tc::PolygonSoup soup = tc::readOBJ(write("tet.obj",
    "# a tetrahedron\nv 0 0 0\nv 1 0 0\nv 0 1 0\nv 0 0 1\nvt 0 0\nvn 0 0 1\ng part\n"
    "f -4 -2 -3\nf 1/1 2/1 4/1\nf 1//1 4//1 3//1\nf 2/1/1 3/1/1 4/1/1\n"));
  ASSERT_EQ(soup.numPoints(), 4);
  EXPECT_EQ(soup.connectivity, (std::vector<int64_t>{ 0, 2, 1, 0, 1, 3, 0, 3, 2, 1, 2, 3 }));
  EXPECT_EQ(soup.points[3 * 3 + 2], 1.0);
}

TEST_F(SoupFiles, BadObjFilesAreRefusedWithWhatIsWrong)
{
  const auto error = [this](const std::string& text)
  {
    try
    {
      tc::readOBJ(write("bad.obj", text));
    }
    catch (const tc::InputError& e)
    {
      return std::string(e.what());
    }
    return std::string();
  };
  EXPECT_TRUE(mentions(error("v 0 0 0\nv 1 0 0\nf 1 2 9\n"), "cannot read")) << error("f 1 2 9");
  EXPECT_TRUE(mentions(error("v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 0\n"), "refers to vertex"));
  EXPECT_TRUE(mentions(error("v 0 0 0\nv 1 0 0\nf 1 2\n"), "has 2 corners"));
  EXPECT_TRUE(mentions(error("v 0 0 0\nv 1 0 0\n"), "has no faces (2 vertices)"));
  EXPECT_TRUE(mentions(error(""), "has no faces"));
}

TEST_F(SoupFiles, DamagedCopiesOfAnObjAreRefusedOrReadNeverCrash)
{
  // vtkOBJReader crashed on "f 1207 1396/1189" (a texture index the file does not have).
  std::string obj;
  for (int i = 0; i < 10; ++i)
  {
    for (int j = 0; j < 10; ++j)
    {
      obj += "v " + std::to_string(i) + " " + std::to_string(j) + " " + std::to_string(i * j) +
        "\nvt 0.5 0.5\n";
    }
  }
  for (int i = 0; i < 9; ++i)
  {
    for (int j = 0; j < 9; ++j)
    {
      const int a = 10 * i + j + 1;
      obj += "f " + std::to_string(a) + "/1 " + std::to_string(a + 10) + "/2 " +
        std::to_string(a + 11) + "/3 " + std::to_string(a + 1) + "/4\n";
    }
  }
  const std::vector<std::string> copies = tctest::damagedCopies(obj, 9, 120);
  const int tried = static_cast<int>(copies.size());
  const int refused = refusedCopies(copies, "damaged.obj", tc::readOBJ);
  std::cout << "[ figures  ] " << refused << " of " << tried << " damaged OBJ copies refused\n";
  EXPECT_GT(refused, 0);
}
