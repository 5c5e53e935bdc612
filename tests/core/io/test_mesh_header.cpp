// SPDX-License-Identifier: BSD-3-Clause
#include "tc/io/mesh_header.h"
#include "tc/io/off_io.h"

#include "temp_folder.h"
#include "test_data.h"

#include <gtest/gtest.h>

#include <zlib.h>

#include <cstdint>
#include <string>

namespace
{
using MeshHeader = tctest::TempFolderTest;

const std::string kPlyHeader = "ply\nformat binary_little_endian 1.0\ncomment made by hand\n"
                               "element vertex 50000000\nproperty float x\nproperty float y\n"
                               "property float z\nelement face 100000000\n"
                               "property list uchar int vertex_indices\nend_header\n";

void expectCounts(const tc::MeshFileCounts& c, int64_t points, int64_t triangles)
{
  EXPECT_EQ(c.points, points);
  EXPECT_EQ(c.triangles, triangles);
}
} // namespace

TEST_F(MeshHeader, PlyDeclaresItsCountsWithoutItsBody)
{
  // The header of a 100M-face file with no body: the counts come from the header alone.
  expectCounts(tc::readMeshFileCounts(write("huge.ply", kPlyHeader)), 50000000, 100000000);
  expectCounts(tc::readMeshFileCounts(write("HUGE.PLY", kPlyHeader)), 50000000, 100000000);
}

TEST_F(MeshHeader, GzipPlyIsInflatedForItsHeader)
{
  const std::string path = file("huge.ply.gz");
  gzFile gz = gzopen(path.c_str(), "wb");
  ASSERT_NE(gz, nullptr);
  gzwrite(gz, kPlyHeader.data(), static_cast<unsigned>(kPlyHeader.size()));
  gzclose(gz);
  expectCounts(tc::readMeshFileCounts(path), 50000000, 100000000);
}

TEST_F(MeshHeader, OffCountsSkipComments)
{
  expectCounts(
    tc::readMeshFileCounts(write("a.off", "# made by hand\nOFF\n# counts\n8 12 0\n")), 8, 12);
  expectCounts(tc::readMeshFileCounts(write("b.off", "OFF 4 2 0\n0 0 0\n")), 4, 2);
  expectCounts(tc::readMeshFileCounts(write("c.off", "COFF\n3 1 0\n")), 3, 1);
  const tc::PolygonSoup bunny = tc::readOFF(tctest::testingData("meshes/bunny_npm.off"));
  expectCounts(tc::readMeshFileCounts(tctest::testingData("meshes/bunny_npm.off")),
    bunny.numPoints(), bunny.numPolygons());
}

TEST_F(MeshHeader, BinaryStlCountsItsFacetsWhenTheSizeAgrees)
{
  std::string stl(80, ' ');
  const uint32_t facets = 3;
  stl.append(reinterpret_cast<const char*>(&facets), 4); // little-endian, as the format
  stl.append(50 * facets, '\0');
  expectCounts(tc::readMeshFileCounts(write("a.stl", stl)), 1, 3);
  // A size that disagrees with the count (truncated, or ASCII) says nothing.
  expectCounts(tc::readMeshFileCounts(write("b.stl", stl.substr(0, stl.size() - 1))), -1, -1);
  expectCounts(tc::readMeshFileCounts(write("c.stl", "solid x\nendsolid x\n")), -1, -1);
}

TEST_F(MeshHeader, ObjCountsItsVertexAndFaceLines)
{
  const std::string obj = "# comment\nv 0 0 0\nv 1 0 0\nvn 0 0 1\nv 0 1 0\n\nvt 0 0\n"
                          "f 1 2 3\nf\t1/1 3/1 2/1\nusemtl x\nv 1 1 1";
  expectCounts(tc::readMeshFileCounts(write("a.obj", obj)), 4, 2);
}

TEST_F(MeshHeader, UnknownFormatsDamagedHeadersAndMissingFilesSayNothing)
{
  expectCounts(tc::readMeshFileCounts(write("a.vtp", "<VTKFile>")), -1, -1);
  expectCounts(tc::readMeshFileCounts(write("a.ply", "plx\nelement face 4\n")), -1, -1);
  expectCounts(tc::readMeshFileCounts(write("b.off", "OFF\nmany 12 0\n")), -1, -1);
  expectCounts(tc::readMeshFileCounts(write("c.off", "OFF\n-8 12 0\n")), -1, -1);
  expectCounts(tc::readMeshFileCounts(file("missing.off")), -1, -1);
  expectCounts(tc::readMeshFileCounts(file("missing.obj")), -1, -1);
  // A PLY without a face element declares its points only.
  expectCounts(
    tc::readMeshFileCounts(write("d.ply", "ply\nformat ascii 1.0\nelement vertex 3\nend_header\n")),
    3, -1);
}
