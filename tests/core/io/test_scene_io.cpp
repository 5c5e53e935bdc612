// SPDX-License-Identifier: BSD-3-Clause
#include "tc/common/errors.h"
#include "tc/io/scene_io.h"

#include "temp_folder.h"
#include "test_data.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <chrono>
#include <cstdint>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <iterator>
#include <random>
#include <set>
#include <string>
#include <vector>

namespace
{
namespace fs = std::filesystem;

/// Scene files in a fresh folder per test.
class SceneFiles : public tctest::TempFolderTest
{
};

std::string base64(const std::string& bytes)
{
  static const char* digits = "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
  std::string out;
  for (size_t i = 0; i < bytes.size(); i += 3)
  {
    uint32_t word = static_cast<uint8_t>(bytes[i]) << 16;
    word |= i + 1 < bytes.size() ? static_cast<uint8_t>(bytes[i + 1]) << 8 : 0;
    word |= i + 2 < bytes.size() ? static_cast<uint8_t>(bytes[i + 2]) : 0;
    const size_t n = std::min<size_t>(3, bytes.size() - i); // bytes in this group
    for (size_t k = 0; k < 4; ++k)
    {
      out += k <= n ? digits[(word >> (18 - 6 * k)) & 63] : '=';
    }
  }
  return out;
}

template <typename T>
void append(std::string& bytes, const T& value)
{
  bytes.append(reinterpret_cast<const char*>(&value), sizeof(T));
}

/// The unit tetrahedron (0,0,0), (1,0,0), (0,1,0), (0,0,1), faces outward.
const std::array<std::array<float, 3>, 4> kTet = { { { 0, 0, 0 }, { 1, 0, 0 }, { 0, 1, 0 },
  { 0, 0, 1 } } };
const std::array<uint16_t, 12> kTetFaces = { 0, 2, 1, 0, 1, 3, 0, 3, 2, 1, 2, 3 };

/// A glTF 2.0 file whose one mesh (the tetrahedron, drawn as `mode`: 4 triangles, 0 points) is
/// placed by three nodes: translated by (10, 0, 0), mirrored in x, and as the child (0, 0, 2) of
/// a node at (0, 5, 0).
std::string tetrahedronScene(int mode = 4)
{
  std::string buffer;
  for (const auto& p : kTet)
  {
    for (const float c : p)
    {
      append(buffer, c);
    }
  }
  for (const uint16_t i : kTetFaces)
  {
    append(buffer, i);
  }
  return R"({
  "asset": { "version": "2.0" },
  "scene": 0,
  "scenes": [ { "nodes": [ 0, 1, 2 ] } ],
  "nodes": [
    { "mesh": 0, "translation": [ 10, 0, 0 ] },
    { "mesh": 0, "scale": [ -1, 1, 1 ] },
    { "translation": [ 0, 5, 0 ], "children": [ 3 ] },
    { "mesh": 0, "translation": [ 0, 0, 2 ] }
  ],
  "meshes": [ { "name": "tet", "primitives": [ { "attributes": { "POSITION": 0 },
    "indices": 1, "mode": )" +
    std::to_string(mode) + R"( } ] } ],
  "buffers": [ { "byteLength": 72, "uri": "data:application/octet-stream;base64,)" +
    base64(buffer) + R"(" } ],
  "bufferViews": [ { "buffer": 0, "byteOffset": 0, "byteLength": 48 },
                   { "buffer": 0, "byteOffset": 48, "byteLength": 24 } ],
  "accessors": [
    { "bufferView": 0, "componentType": 5126, "count": 4, "type": "VEC3",
      "min": [ 0, 0, 0 ], "max": [ 1, 1, 1 ] },
    { "bufferView": 1, "componentType": 5123, "count": 12, "type": "SCALAR" }
  ]
})";
}

/// Six times the signed volume enclosed by polygons [first, last) of the soup.
double signedVolume(const tc::PolygonSoup& soup, int64_t first, int64_t last)
{
  double volume = 0.0;
  for (int64_t f = first; f < last; ++f)
  {
    const int64_t* ids = soup.connectivity.data() + soup.offsets[f];
    const double* a = soup.points.data() + 3 * ids[0];
    const double* b = soup.points.data() + 3 * ids[1];
    const double* c = soup.points.data() + 3 * ids[2];
    volume += a[0] * (b[1] * c[2] - b[2] * c[1]) - a[1] * (b[0] * c[2] - b[2] * c[0]) +
      a[2] * (b[0] * c[1] - b[1] * c[0]);
  }
  return volume;
}
} // namespace

TEST(SceneIo, Base64OfTheTestFilesIsStandard)
{
  EXPECT_EQ(base64("Man"), "TWFu");
  EXPECT_EQ(base64("Ma"), "TWE=");
  EXPECT_EQ(base64("M"), "TQ==");
}

TEST_F(SceneFiles, EveryNodePlacesItsMeshWithTheTransformFromTheRoot)
{
  const tc::Scene scene = tc::readScene(write("tets.gltf", tetrahedronScene()));
  EXPECT_EQ(scene.meshInstances, 3);
  ASSERT_EQ(scene.meshNames.size(), 1u);
  EXPECT_EQ(scene.meshNames[0], "tet");
  EXPECT_EQ(scene.importer, "glTF2 Importer");
  ASSERT_EQ(scene.soup.numPoints(), 12);
  ASSERT_EQ(scene.soup.numPolygons(), 12);
  EXPECT_EQ(scene.meshId, std::vector<int32_t>(12, 0));
  EXPECT_EQ(scene.bones + int64_t(scene.animations.size()) + scene.skippedPrimitives + scene.skinnedMeshes, 0);

  // Each instance is 4 consecutive points and 4 consecutive triangles.
  std::set<std::array<double, 3>> origins;
  for (int64_t instance = 0; instance < 3; ++instance)
  {
    const double* first = scene.soup.points.data() + 12 * instance;
    origins.insert({ first[0], first[1], first[2] });
    const double* x = scene.soup.points.data() + 12 * instance + 3;
    // (1, 0, 0) goes to origin + (1, 0, 0), or (-1, 0, 0) in the mirrored instance.
    EXPECT_EQ(std::abs(x[0] - first[0]), 1.0);
    EXPECT_EQ(x[1] - first[1], 0.0);
    // The faces keep facing outward, the mirrored instance's too (its winding is reversed).
    EXPECT_NEAR(signedVolume(scene.soup, 4 * instance, 4 * instance + 4), 1.0, 1e-6)
      << "instance " << instance;
    for (int64_t f = 4 * instance; f < 4 * instance + 4; ++f)
    {
      for (int64_t c = scene.soup.offsets[f]; c < scene.soup.offsets[f + 1]; ++c)
      {
        EXPECT_GE(scene.soup.connectivity[c], 4 * instance);
        EXPECT_LT(scene.soup.connectivity[c], 4 * instance + 4);
      }
    }
  }
  const std::set<std::array<double, 3>> expected = { { 10, 0, 0 }, { 0, 0, 0 }, { 0, 5, 2 } };
  EXPECT_EQ(origins, expected);
}

TEST_F(SceneFiles, PointsAndLinesAreSkippedAndASceneWithoutPolygonsIsRefused)
{
  try
  {
    tc::readScene(write("points.gltf", tetrahedronScene(0)));
    FAIL() << "a scene of points was read";
  }
  catch (const tc::InputError& e)
  {
    EXPECT_NE(std::string(e.what()).find("has no polygons"), std::string::npos) << e.what();
  }
}

TEST_F(SceneFiles, BadFilesAreRefusedWithAMessage)
{
  const auto message = [](const std::string& path)
  {
    try
    {
      tc::readScene(path);
    }
    catch (const tc::InputError& e)
    {
      return std::string(e.what());
    }
    return std::string("read");
  };
  EXPECT_NE(message((Folder / "missing.glb").string()).find("does not exist"), std::string::npos);
  EXPECT_NE(message(write("mesh.obj", "v 0 0 0\n")).find("no scene file"), std::string::npos);
  EXPECT_NE(message(write("text.fbx", "this is no FBX file\n")).find("cannot read"),
    std::string::npos);
  std::string scene = tetrahedronScene();
  EXPECT_NE(message(write("cut.gltf", scene.substr(0, scene.size() / 2))).find("cannot read"),
    std::string::npos);
  // A binary glTF cut in half.
  const std::string glb = tctest::sharedData("skinned/wuson/wuson.glb");
  if (!glb.empty())
  {
    std::ifstream in(glb, std::ios::binary);
    const std::string bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    EXPECT_NE(message(write("cut.glb", bytes.substr(0, bytes.size() / 2))).find("cannot read"),
      std::string::npos);
  }
}

TEST_F(SceneFiles, ProgressIsReportedAndCanAbort)
{
  const std::string path = write("tets.gltf", tetrahedronScene());
  int calls = 0;
  tc::readScene(path, tc::Progress([&calls](double) { return ++calls > 0; }));
  EXPECT_GT(calls, 0);
  EXPECT_THROW(tc::readScene(path, tc::Progress([](double) { return false; })), tc::Aborted);
}

TEST(SceneIo, SkinnedCharactersReadInTheirRestPoseAlikeFromEachFormat)
{
  const std::string glb = tctest::sharedData("skinned/wuson/wuson.glb");
  const std::string x = tctest::sharedData("skinned/wuson/Testwuson.X");
  if (glb.empty() || x.empty())
  {
    GTEST_SKIP() << "skinned/wuson is not in the shared data";
  }
  // The data README: 3732 triangles, 37 bones, animations Run, Walk and Bind.
  const tc::Scene a = tc::readScene(glb);
  const tc::Scene b = tc::readScene(x);
  for (const tc::Scene* s : { &a, &b })
  {
    EXPECT_EQ(s->soup.numPolygons(), 3732);
    EXPECT_EQ(s->bones, 37);
    EXPECT_EQ(s->skinnedMeshes, 1);
    EXPECT_EQ(s->animations.size(), 3u);
  }
  // The glTF was converted from the X file: the same points in the same place (in another
  // order).
  ASSERT_EQ(a.soup.numPoints(), b.soup.numPoints());
  const auto sorted = [](const tc::PolygonSoup& soup)
  {
    std::vector<std::array<double, 3>> points(soup.numPoints());
    std::memcpy(points.data(), soup.points.data(), soup.points.size() * sizeof(double));
    std::sort(points.begin(), points.end());
    return points;
  };
  const std::vector<std::array<double, 3>> pa = sorted(a.soup), pb = sorted(b.soup);
  double largest = 0.0;
  for (size_t i = 0; i < pa.size(); ++i)
  {
    for (int c = 0; c < 3; ++c)
    {
      largest = std::max(largest, std::abs(pa[i][c] - pb[i][c]));
    }
  }
  EXPECT_LT(largest, 1e-5);
}

TEST_F(SceneFiles, DamagedCopiesOfTheSharedScenesAreRefusedOrReadNeverCrash)
{
  // Truncated and byte-flipped copies of every format offered: each is read into a valid soup
  // or refused with tc::InputError (a crash fails the whole test program).
  int tried = 0, refused = 0;
  for (const char* name : { "skinned/wuson/wuson.glb", "skinned/wuson/Testwuson.X",
         "skinned/snake_fbx/animation_with_skeleton.fbx", "skinned/md2/sydney.md2" })
  {
    const std::string path = tctest::sharedData(name);
    if (path.empty())
    {
      GTEST_SKIP() << name << " is not in the shared data";
    }
    std::ifstream in(path, std::ios::binary);
    const std::string bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    const std::string ext = path.substr(path.rfind('.'));
    const std::vector<std::string> copies = tctest::damagedCopies(bytes, 11, 24);
    for (const std::string& copy : copies)
    {
      ++tried;
      try
      {
        const tc::Scene scene = tc::readScene(write("damaged" + ext, copy));
        for (const int64_t id : scene.soup.connectivity)
        {
          ASSERT_GE(id, 0);
          ASSERT_LT(id, scene.soup.numPoints());
        }
        ASSERT_EQ(scene.meshId.size(), static_cast<size_t>(scene.soup.numPolygons()));
      }
      catch (const tc::InputError&)
      {
        ++refused;
      }
    }
  }
  RecordProperty("refused", refused);
  std::cout << "[ figures  ] " << refused << " of " << tried << " damaged copies refused\n";
  EXPECT_GT(refused, 0);
}
