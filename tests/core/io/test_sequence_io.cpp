// SPDX-License-Identifier: BSD-3-Clause
#include "tc/common/errors.h"
#include "tc/io/scene_io.h"
#include "tc/io/sequence_io.h"
#include "tc/io/soup_io.h"

#include "temp_folder.h"
#include "test_data.h"
#include "test_progress.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <limits>
#include <string>
#include <vector>

namespace
{
namespace fs = std::filesystem;

class SequenceFolder : public tctest::TempFolderTest
{
};
class SequencePattern : public tctest::TempFolderTest
{
};
class SequenceMD2 : public tctest::TempFolderTest
{
};

/// The folder of a shared sequence, or "" when ../shared/data lacks it.
std::string sharedSequence(const std::string& folder, const std::string& firstFrame)
{
  const std::string frame = tctest::sharedData("sequences/" + folder + "/" + firstFrame);
  return frame.empty() ? std::string() : fs::path(frame).parent_path().string();
}

/// The message of the tc::InputError that readSequence throws for `path` ("" if none).
std::string sequenceError(const std::string& path)
{
  try
  {
    tc::readSequence(path);
  }
  catch (const tc::InputError& error)
  {
    return error.what();
  }
  return "";
}

/// A tetrahedron as OFF, moved by `shift` along x; `faces` replaces its faces when given.
std::string tetrahedronOff(double shift, const std::string& faces = "")
{
  std::string text = "OFF\n4 4 0\n";
  for (const auto& p : { std::array<double, 3>{ 0, 0, 0 }, { 1, 0, 0 }, { 0, 1, 0 }, { 0, 0, 1 } })
  {
    text +=
      std::to_string(p[0] + shift) + " " + std::to_string(p[1]) + " " + std::to_string(p[2]) + "\n";
  }
  return text + (faces.empty() ? "3 0 2 1\n3 0 1 3\n3 0 3 2\n3 1 2 3\n" : faces);
}

/// The largest distance between frames `a` and `b` of `sequence`'s points.
double largestMove(const tc::DeformingSequence& sequence, size_t a, size_t b)
{
  double largest = 0;
  for (size_t i = 0; i < sequence.frames[a].size(); ++i)
  {
    largest = std::max<double>(largest, std::abs(sequence.frames[a][i] - sequence.frames[b][i]));
  }
  return largest;
}

/// Checks the shape every sequence has: #frames frames of #V x 3 floats, frame k at time k,
/// frame 0 equal to the soup's points as floats.
void expectWellFormed(const tc::DeformingSequence& sequence, size_t frames)
{
  ASSERT_EQ(sequence.frames.size(), frames);
  ASSERT_EQ(sequence.times.size(), frames);
  ASSERT_EQ(sequence.frameNames.size(), frames);
  for (size_t k = 0; k < frames; ++k)
  {
    ASSERT_EQ(sequence.frames[k].size(), sequence.soup.points.size()) << "frame " << k;
    EXPECT_EQ(sequence.times[k], static_cast<double>(k));
  }
  for (size_t i = 0; i < sequence.soup.points.size(); ++i)
  {
    ASSERT_EQ(sequence.frames[0][i], static_cast<float>(sequence.soup.points[i])) << i;
  }
}
} // namespace

TEST_F(SequenceFolder, SnakeHas21FramesOfOneConnectivityAndFrameZeroIsItsFirstFile)
{
  const std::string folder = sharedSequence("snake_closed_21f", "f_0000.obj");
  if (folder.empty())
  {
    GTEST_SKIP() << "../shared/data/sequences/snake_closed_21f is absent";
  }
  const tc::DeformingSequence sequence = tc::readSequence(folder);
  expectWellFormed(sequence, 21);
  EXPECT_EQ(sequence.source, "folder");
  EXPECT_EQ(sequence.soup.numPoints(), 1058);
  EXPECT_EQ(sequence.soup.numPolygons(), 2112);
  EXPECT_EQ(sequence.frameNames.front(), "f_0000.obj");
  EXPECT_EQ(sequence.frameNames.back(), "f_0020.obj");
  // Zero-padded numbers sort the same in natural and in byte order.
  EXPECT_TRUE(std::is_sorted(sequence.frameNames.begin(), sequence.frameNames.end()));
  const tc::PolygonSoup first = tc::readOBJ(folder + "/f_0000.obj");
  EXPECT_EQ(sequence.soup.points, first.points);
  EXPECT_EQ(sequence.soup.offsets, first.offsets);
  EXPECT_EQ(sequence.soup.connectivity, first.connectivity);
  EXPECT_GT(largestMove(sequence, 0, 10), 1.0); // the snake moves
  const tc::PolygonSoup last = tc::readOBJ(folder + "/f_0020.obj");
  EXPECT_EQ(sequence.frames[20], std::vector<float>(last.points.begin(), last.points.end()));
}

TEST_F(SequenceFolder, FrankieHas19FramesOfOneConnectivity)
{
  const std::string folder = sharedSequence("frankie_run_19f", "Frankie_Run_0000.obj");
  if (folder.empty())
  {
    GTEST_SKIP() << "../shared/data/sequences/frankie_run_19f is absent";
  }
  const tc::DeformingSequence sequence = tc::readSequence(folder);
  expectWellFormed(sequence, 19);
  EXPECT_EQ(sequence.soup.numPoints(), 2456);
  EXPECT_EQ(sequence.soup.numPolygons(), 4794);
  EXPECT_EQ(sequence.frameNames[18], "Frankie_Run_0018.obj");
  EXPECT_GT(largestMove(sequence, 0, 9), 0.0);
}

TEST_F(SequenceFolder, SortsFramesInNaturalOrder)
{
  write("f_2.off", tetrahedronOff(2));
  write("f_10.off", tetrahedronOff(10));
  write("f_1.off", tetrahedronOff(1));
  write("notes.txt", "not a frame");
  write(".f_0.off", "a hidden file, not a frame");
  const tc::DeformingSequence sequence = tc::readSequence(Folder.string());
  expectWellFormed(sequence, 3);
  EXPECT_EQ(sequence.frameNames, (std::vector<std::string>{ "f_1.off", "f_2.off", "f_10.off" }));
  EXPECT_EQ(sequence.frames[0][0], 1.0f);
  EXPECT_EQ(sequence.frames[1][0], 2.0f);
  EXPECT_EQ(sequence.frames[2][0], 10.0f);
}

TEST_F(SequenceFolder, ReadsFramesOfMixedFormats)
{
  write("a_0.off", tetrahedronOff(0));
  write("a_1.obj", "v 5 0 0\nv 6 0 0\nv 5 1 0\nv 5 0 1\nf 1 3 2\nf 1 2 4\nf 1 4 3\nf 2 3 4\n");
  write("a_2.ply",
    "ply\nformat ascii 1.0\nelement vertex 4\nproperty float x\nproperty float y\n"
    "property float z\nelement face 4\nproperty list uchar int vertex_indices\n"
    "end_header\n7 0 0\n8 0 0\n7 1 0\n7 0 1\n3 0 2 1\n3 0 1 3\n3 0 3 2\n3 1 2 3\n");
  const tc::DeformingSequence sequence = tc::readSequence(Folder.string());
  expectWellFormed(sequence, 3);
  EXPECT_EQ(sequence.frames[1][3], 6.0f);
  EXPECT_EQ(sequence.frames[2][3], 8.0f);
}

TEST_F(SequenceFolder, ReadsASingleFrameAsASequenceOfOne)
{
  write("only.off", tetrahedronOff(0));
  const tc::DeformingSequence sequence = tc::readSequence(Folder.string());
  expectWellFormed(sequence, 1);
  EXPECT_EQ(sequence.soup.numPolygons(), 4);
}

TEST_F(SequenceFolder, RefusesAFrameWithAnotherPolygonNamingIt)
{
  write("f_0.off", tetrahedronOff(0));
  write("f_1.off", tetrahedronOff(1));
  write("f_2.off", tetrahedronOff(2, "3 0 2 1\n3 0 3 1\n3 0 3 2\n3 1 2 3\n"));
  const std::string error = sequenceError(Folder.string());
  EXPECT_NE(error.find("frame 2 (f_2.off) has polygon 1 with corners (0, 3, 1) where frame 0 "
                       "(f_0.off) has (0, 1, 3)"),
    std::string::npos)
    << error;
  EXPECT_NE(error.find("same connectivity"), std::string::npos) << error;
}

TEST_F(SequenceFolder, RefusesAFrameWithAnotherPointCountNamingIt)
{
  write("f_0.off", tetrahedronOff(0));
  write("f_1.off",
    "OFF\n5 4 0\n0 0 0\n1 0 0\n0 1 0\n0 0 1\n9 9 9\n"
    "3 0 2 1\n3 0 1 3\n3 0 3 2\n3 1 2 3\n");
  const std::string error = sequenceError(Folder.string());
  EXPECT_NE(
    error.find("frame 1 (f_1.off) has 5 points where frame 0 (f_0.off) has 4"), std::string::npos)
    << error;
}

TEST_F(SequenceFolder, NamesTheFrameItsReaderRefuses)
{
  write("f_0.off", tetrahedronOff(0));
  write("f_1.off", "OFF\n4 1 0\n0 0 0\n");
  const std::string error = sequenceError(Folder.string());
  EXPECT_NE(error.find("frame 1 (f_1.off)"), std::string::npos) << error;
}

TEST_F(SequenceFolder, RefusesAFolderWithoutFrameFiles)
{
  EXPECT_NE(sequenceError(Folder.string()).find("has no frame file"), std::string::npos);
  write("readme.txt", "no frame here");
  fs::create_directories(Folder / "sub.obj");
  EXPECT_NE(sequenceError(Folder.string()).find("has no frame file"), std::string::npos);
  EXPECT_FALSE(sequenceError(file("missing")).empty());
}

TEST_F(SequenceFolder, ReportsProgressPerFrameAndAborts)
{
  for (int k = 0; k < 4; ++k)
  {
    write("f_" + std::to_string(k) + ".off", tetrahedronOff(k));
  }
  tctest::expectProgressAndAbort([&](const tc::Progress& progress)
    { tc::readSequence(Folder.string(), progress); },
    5, [](double fraction) { return fraction < 0.5; });
}

TEST_F(SequenceFolder, TellsSequencePaths)
{
  EXPECT_TRUE(tc::isSequencePath(Folder.string()));
  EXPECT_TRUE(tc::isSequencePath("dir/f_*.obj"));
  EXPECT_TRUE(tc::isSequencePath("dir/f_000?.ply"));
  EXPECT_TRUE(tc::isSequencePath("model.MD2"));
  EXPECT_FALSE(tc::isSequencePath(write("mesh.obj", "v 0 0 0\n")));
  EXPECT_FALSE(tc::isSequencePath(".md2"));
}

TEST_F(SequencePattern, SelectsTheMatchingFramesOfTheSnake)
{
  const std::string folder = sharedSequence("snake_closed_21f", "f_0000.obj");
  if (folder.empty())
  {
    GTEST_SKIP() << "../shared/data/sequences/snake_closed_21f is absent";
  }
  const tc::DeformingSequence sequence = tc::readSequence(folder + "/f_000*.obj");
  expectWellFormed(sequence, 10);
  EXPECT_EQ(sequence.source, "pattern");
  EXPECT_EQ(sequence.frameNames.back(), "f_0009.obj");
  const tc::DeformingSequence some = tc::readSequence(folder + "/f_001?.obj");
  expectWellFormed(some, 10);
  EXPECT_EQ(some.frameNames.front(), "f_0010.obj");
  const tc::PolygonSoup tenth = tc::readOBJ(folder + "/f_0010.obj");
  EXPECT_EQ(some.frames[0], std::vector<float>(tenth.points.begin(), tenth.points.end()));
}

TEST_F(SequencePattern, SkipsMatchesOfAnotherFormatWithAWarning)
{
  write("f_1.off", tetrahedronOff(1));
  write("f_1.txt", "notes");
  const tc::DeformingSequence sequence = tc::readSequence(file("f_1.*"));
  expectWellFormed(sequence, 1);
  ASSERT_EQ(sequence.warnings.size(), 1u);
  EXPECT_NE(sequence.warnings[0].find("f_1.txt"), std::string::npos) << sequence.warnings[0];
}

TEST_F(SequencePattern, RefusesAWildcardInTheFolderAndAPatternWithoutMatch)
{
  write("f_1.off", tetrahedronOff(1));
  EXPECT_NE(
    sequenceError(Folder.string() + "*/f_1.off").find("wildcard in its folder"), std::string::npos);
  EXPECT_NE(sequenceError(file("g_*.off")).find("has no frame file"), std::string::npos);
  EXPECT_NE(sequenceError(file("nowhere/f_*.off")).find("does not exist"), std::string::npos);
}

namespace
{
/// An MD2 model to write: the fields that matter here, laid out by md2Bytes.
struct Md2Model
{
  uint32_t skinWidth = 64;
  uint32_t skinHeight = 32;
  std::string skin; ///< the first skin's name; none when empty
  std::vector<std::array<uint16_t, 2>> st;
  std::vector<std::array<uint16_t, 6>> triangles; ///< vertex[3], st[3]
  struct Frame
  {
    std::array<float, 3> scale;
    std::array<float, 3> translate;
    std::string name;
    std::vector<std::array<uint8_t, 3>> vertices;
  };
  std::vector<Frame> frames;
};

template <typename T>
void append(std::string& bytes, const T& value)
{
  bytes.append(reinterpret_cast<const char*>(&value), sizeof(T)); // the test machine is LE
}

/// The bytes of `model` as an MD2 file: header, skins, texture coordinates, triangles, frames.
std::string md2Bytes(const Md2Model& model)
{
  const uint32_t vertices = static_cast<uint32_t>(model.frames.at(0).vertices.size());
  const uint32_t frameSize = 40 + 4 * vertices, skins = model.skin.empty() ? 0 : 1;
  const uint32_t ofsSkins = 68, ofsSt = ofsSkins + 64 * skins;
  const uint32_t ofsTris = ofsSt + 4 * static_cast<uint32_t>(model.st.size());
  const uint32_t ofsFrames = ofsTris + 12 * static_cast<uint32_t>(model.triangles.size());
  const uint32_t ofsEnd = ofsFrames + frameSize * static_cast<uint32_t>(model.frames.size());
  std::string bytes = "IDP2";
  for (const uint32_t word : { 8u, model.skinWidth, model.skinHeight, frameSize, skins, vertices,
         static_cast<uint32_t>(model.st.size()), static_cast<uint32_t>(model.triangles.size()), 0u,
         static_cast<uint32_t>(model.frames.size()), ofsSkins, ofsSt, ofsTris, ofsFrames, ofsEnd,
         ofsEnd })
  {
    append(bytes, word);
  }
  if (skins)
  {
    bytes += model.skin + std::string(64 - model.skin.size(), '\0');
  }
  for (const auto& st : model.st)
  {
    append(bytes, st);
  }
  for (const auto& triangle : model.triangles)
  {
    append(bytes, triangle);
  }
  for (const Md2Model::Frame& frame : model.frames)
  {
    append(bytes, frame.scale);
    append(bytes, frame.translate);
    bytes += frame.name + std::string(16 - frame.name.size(), '\0');
    for (const auto& v : frame.vertices)
    {
      bytes += std::string(reinterpret_cast<const char*>(v.data()), 3) + '\0';
    }
  }
  return bytes;
}

/// Two triangles of a tetrahedron's 4 vertices; vertex 0 has two texture coordinates (a seam).
Md2Model seamModel()
{
  Md2Model model;
  model.st = { { 0, 0 }, { 64, 0 }, { 0, 32 }, { 32, 16 }, { 16, 8 } };
  model.triangles = { { 0, 1, 2, 0, 1, 2 }, { 0, 3, 1, 4, 3, 1 } };
  const std::vector<std::array<uint8_t, 3>> tetrahedron = { { 0, 0, 0 }, { 1, 0, 0 }, { 0, 1, 0 },
    { 0, 0, 1 } };
  model.frames = { { { 1, 2, 0.5f }, { 10, 20, 30 }, "stand01", tetrahedron },
    { { 1, 1, 1 }, { 0, 0, 0 }, "run02", tetrahedron } };
  return model;
}

std::string fileBytes(const std::string& path)
{
  std::ifstream in(path, std::ios::binary);
  return std::string((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
}

void putWord(std::string& bytes, size_t at, uint32_t value)
{
  std::memcpy(&bytes[at], &value, 4);
}

uint32_t getWord(const std::string& bytes, size_t at)
{
  uint32_t value;
  std::memcpy(&value, &bytes[at], 4);
  return value;
}

/// The length of the bounding box's diagonal of `points` (#V x 3).
double diagonal(const std::vector<double>& points)
{
  std::array<double, 3> low{ INFINITY, INFINITY, INFINITY },
    high{ -INFINITY, -INFINITY, -INFINITY };
  for (size_t i = 0; i < points.size(); ++i)
  {
    low[i % 3] = std::min(low[i % 3], points[i]);
    high[i % 3] = std::max(high[i % 3], points[i]);
  }
  return std::hypot(high[0] - low[0], high[1] - low[1], high[2] - low[2]);
}
} // namespace

TEST_F(SequenceMD2, ReadsEveryKeyframeWithAssimpsAxesWindingAndTextureCoordinates)
{
  const tc::DeformingSequence sequence = tc::readSequence(write("tet.md2", md2Bytes(seamModel())));
  expectWellFormed(sequence, 2);
  EXPECT_EQ(sequence.source, "md2");
  EXPECT_EQ(sequence.frameNames, (std::vector<std::string>{ "stand01", "run02" }));
  // Points in order of first use: (v0, st0), (v1, st1), (v2, st2), (v0, st4), (v3, st3); each
  // triangle's corners reversed.
  EXPECT_EQ(sequence.soup.connectivity, (std::vector<int64_t>{ 2, 1, 0, 1, 4, 3 }));
  // byte * scale + translate, then (x, z, -y).
  EXPECT_EQ(sequence.frames[0],
    (std::vector<float>{ 10, 30, -20, 11, 30, -20, 10, 30, -22, 10, 30, -20, 10, 30.5f, -20 }));
  EXPECT_EQ(sequence.frames[1],
    (std::vector<float>{ 0, 0, -0.0f, 1, 0, -0.0f, 0, 0, -1, 0, 0, -0.0f, 0, 1, -0.0f }));
  // u = s / 64, v = 1 - t / 32.
  EXPECT_EQ(sequence.attributes.textureCoordinates,
    (std::vector<float>{ 0, 1, 1, 1, 0, 0, 0.25f, 0.75f, 0.5f, 0.5f }));
  EXPECT_TRUE(sequence.warnings.empty());
}

TEST_F(SequenceMD2, LooksForTheSkinBesideTheModel)
{
  Md2Model model = seamModel();
  model.skin = "skin.pcx";
  write("skin.pcx", "texels");
  const tc::DeformingSequence sequence = tc::readSequence(write("tet.md2", md2Bytes(model)));
  EXPECT_EQ(sequence.texture.name, "skin.pcx");
  EXPECT_EQ(sequence.texture.encoded, "texels");
  fs::remove(file("skin.pcx"));
  const tc::DeformingSequence without = tc::readSequence(file("tet.md2"));
  EXPECT_FALSE(without.texture.hasImage());
  ASSERT_EQ(without.warnings.size(), 1u);
  EXPECT_NE(without.warnings[0].find("skin.pcx"), std::string::npos) << without.warnings[0];
}

TEST_F(SequenceMD2, SydneyHas198FramesOf679Triangles)
{
  const std::string path = tctest::sharedData("skinned/md2/sydney.md2");
  if (path.empty())
  {
    GTEST_SKIP() << "../shared/data/skinned/md2/sydney.md2 is absent";
  }
  const tc::DeformingSequence sequence = tc::readSequence(path);
  expectWellFormed(sequence, 198);
  EXPECT_EQ(sequence.soup.numPolygons(), 679);
  EXPECT_EQ(sequence.times.back(), 197.0);
  EXPECT_EQ(sequence.attributes.textureCoordinates.size(), 2 * size_t(sequence.soup.numPoints()));
  EXPECT_FALSE(sequence.frameNames[0].empty());
  EXPECT_GT(largestMove(sequence, 0, 100), 0.01 * diagonal(sequence.soup.points));
}

TEST_F(SequenceMD2, SydneysFrameZeroIsWhatAssimpReads)
{
  const std::string path = tctest::sharedData("skinned/md2/sydney.md2");
  if (path.empty())
  {
    GTEST_SKIP() << "../shared/data/skinned/md2/sydney.md2 is absent";
  }
  const tc::DeformingSequence sequence = tc::readSequence(path);
  const tc::Scene scene = tc::readScene(path);
  ASSERT_EQ(sequence.soup.numPolygons(), scene.soup.numPolygons());
  ASSERT_EQ(scene.attributes.textureCoordinates.size(), 2 * size_t(scene.soup.numPoints()));
  const double tolerance = 1e-5 * diagonal(scene.soup.points);
  // Triangle by triangle and corner by corner: the same position (hence the same points as a
  // set, every point being a corner), winding and texture coordinates.
  for (int64_t p = 0; p < scene.soup.numPolygons(); ++p)
  {
    ASSERT_EQ(scene.soup.offsets[p + 1] - scene.soup.offsets[p], 3);
    for (int64_t c = 0; c < 3; ++c)
    {
      const int64_t mine = sequence.soup.connectivity[3 * p + c];
      const int64_t theirs = scene.soup.connectivity[scene.soup.offsets[p] + c];
      for (int64_t a = 0; a < 3; ++a)
      {
        ASSERT_NEAR(
          sequence.soup.points[3 * mine + a], scene.soup.points[3 * theirs + a], tolerance)
          << "triangle " << p << " corner " << c;
      }
      for (int64_t a = 0; a < 2; ++a)
      {
        ASSERT_NEAR(sequence.attributes.textureCoordinates[2 * mine + a],
          scene.attributes.textureCoordinates[2 * theirs + a], 1e-6)
          << "triangle " << p << " corner " << c;
      }
    }
  }
  EXPECT_EQ(sequence.soup.numPoints(), scene.soup.numPoints());
}

TEST_F(SequenceMD2, ReportsProgressPerFrameAndAborts)
{
  const std::string path = write("tet.md2", md2Bytes(seamModel()));
  tctest::expectProgressAndAbort([&](const tc::Progress& progress)
    { tc::readSequence(path, progress); },
    3, [](double fraction) { return fraction < 0.4; });
}

TEST_F(SequenceMD2, RefusesDamagedHeadersAndData)
{
  const std::string path = tctest::sharedData("skinned/md2/sydney.md2");
  if (path.empty())
  {
    GTEST_SKIP() << "../shared/data/skinned/md2/sydney.md2 is absent";
  }
  const std::string bytes = fileBytes(path);
  const uint32_t ofsTris = getWord(bytes, 52), ofsFrames = getWord(bytes, 56);
  struct Damage
  {
    const char* what;
    size_t at;
    uint32_t value;
  };
  const float nan = std::numeric_limits<float>::quiet_NaN();
  uint32_t nanBits;
  std::memcpy(&nanBits, &nan, 4);
  const Damage damages[] = { { "signature", 0, 0x32504449u + 1 },
    { "num_frames huge", 40, 0xFFFFFFu }, { "num_frames 0", 40, 0 },
    { "ofs_frames past the end", 56, static_cast<uint32_t>(bytes.size()) - 10 },
    { "ofs_frames huge", 56, 0xFFFFFFF0u }, { "num_vertices huge", 24, 0x7FFFFFFFu },
    { "num_vertices 0", 24, 0 }, { "framesize small", 16, 39 },
    { "num_tris huge", 32, 0x40000000u }, { "num_st huge", 28, 0xFFFFFFFFu },
    { "ofs_end past the end", 64, 0xFFFFFFFFu }, { "vertex index out of range", ofsTris, 342 },
    { "st index out of range", ofsTris + 8, 456u << 16 },
    { "scale NaN", ofsFrames + 1408 * 5 + 4, nanBits } };
  for (const Damage& damage : damages)
  {
    SCOPED_TRACE(damage.what);
    std::string copy = bytes;
    putWord(copy, damage.at, damage.value);
    const std::string error = sequenceError(write("damaged.md2", copy));
    EXPECT_NE(error.find("as MD2"), std::string::npos) << error;
  }
}

TEST_F(SequenceMD2, RefusesTruncatedCopiesAndSurvivesFlippedBytes)
{
  const std::string path = tctest::sharedData("skinned/md2/sydney.md2");
  if (path.empty())
  {
    GTEST_SKIP() << "../shared/data/skinned/md2/sydney.md2 is absent";
  }
  const std::string bytes = fileBytes(path);
  for (const size_t length : { size_t(0), size_t(3), size_t(67), size_t(68), size_t(1000),
         bytes.size() / 2, bytes.size() - 1 })
  {
    SCOPED_TRACE(length);
    EXPECT_FALSE(sequenceError(write("cut.md2", bytes.substr(0, length))).empty());
  }
  for (const std::string& copy : tctest::damagedCopies(bytes, 7, 60))
  {
    try
    {
      const tc::DeformingSequence sequence = tc::readSequence(write("flipped.md2", copy));
      EXPECT_EQ(sequence.frames.size(), sequence.times.size());
    }
    catch (const tc::InputError&)
    {
    }
  }
}

TEST_F(SequenceMD2, RefusesAHeaderWhoseFramesWouldTakeFarMoreThanTheFile)
{
  // One vertex with 3000 texture coordinates makes 3000 points, over 3000 frames: 108 MB of
  // positions from a file of 160 kB.
  Md2Model model;
  for (uint16_t k = 0; k < 3000; ++k)
  {
    model.st.push_back({ k, k });
  }
  for (uint16_t t = 0; t < 1000; ++t)
  {
    model.triangles.push_back(
      { 0, 0, 0, uint16_t(3 * t), uint16_t(3 * t + 1), uint16_t(3 * t + 2) });
  }
  model.frames.assign(3000, { { 1, 1, 1 }, { 0, 0, 0 }, "f", { { 1, 2, 3 } } });
  const std::string error = sequenceError(write("blown.md2", md2Bytes(model)));
  EXPECT_NE(error.find("times the file's"), std::string::npos) << error;
}
