// SPDX-License-Identifier: BSD-3-Clause
// Texture coordinates, colours and the base-colour texture of OBJ, PLY and glTF files
// (tc::readOBJFile, tc::readPLYFile, tc::readScene).
#include "tc/common/errors.h"
#include "tc/io/png_check.h"
#include "tc/io/scene_io.h"
#include "tc/io/soup_io.h"

#include "temp_folder.h"
#include "test_data.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <fstream>
#include <iostream>
#include <iterator>
#include <string>
#include <vector>

namespace
{
/// Mesh files with their materials and textures in a fresh folder per test.
class MeshFiles : public tctest::TempFolderTest
{
protected:
  /// The message of the tc::InputError readOBJFile throws for `text` ("" if it reads).
  std::string objError(const std::string& text) const
  {
    try
    {
      tc::readOBJFile(write("bad.obj", text));
    }
    catch (const tc::InputError& e)
    {
      return e.what();
    }
    return "";
  }
};

bool mentions(const std::string& message, const std::string& what)
{
  return message.find(what) != std::string::npos;
}

bool mentions(const std::vector<std::string>& warnings, const std::string& what)
{
  return std::any_of(
    warnings.begin(), warnings.end(), [&what](const std::string& w) { return mentions(w, what); });
}

/// The CRC-32 of PNG chunks (zlib's), computed bitwise.
uint32_t crc32Of(const std::string& bytes)
{
  uint32_t crc = 0xFFFFFFFFu;
  for (const char c : bytes)
  {
    crc ^= static_cast<uint8_t>(c);
    for (int k = 0; k < 8; ++k)
    {
      crc = crc & 1 ? (crc >> 1) ^ 0xEDB88320u : crc >> 1;
    }
  }
  return ~crc;
}

std::string fileBytes(const std::string& path)
{
  std::ifstream in(path, std::ios::binary);
  return std::string((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
}

/// Two triangles over a square whose diagonal is a UV seam at its end (0, 0): vertex 1 has
/// texture coordinate 1 in the first triangle and 4 in the second.
const char* kSeamSquare = "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\n"
                          "vt 0 0\nvt 0.5 0\nvt 0.5 0.5\nvt 1 1\nvt 0 0.5\n"
                          "f 1/1 2/2 3/3\nf 1/4 3/3 4/5\n";

/// The PNG signature and a few bytes: readers of the core do not decode images.
const std::string kFakePng = std::string("\x89PNG\r\n\x1a\n", 8) + "not decoded here";

/// A glTF tetrahedron whose buffer is the file "tet.bin" beside it: positions, then RGB colours
/// (COLOR_0) and texture coordinates (TEXCOORD_0, v from the image's top as glTF has it), and a
/// material whose base colour is the image file `image`.
std::string tetrahedronGltf(const std::string& image)
{
  return R"({
  "asset": { "version": "2.0" },
  "scene": 0, "scenes": [ { "nodes": [ 0 ] } ], "nodes": [ { "mesh": 0 } ],
  "meshes": [ { "primitives": [ { "attributes": { "POSITION": 0, "COLOR_0": 1, "TEXCOORD_0": 2 },
    "indices": 3, "material": 0 } ] } ],
  "materials": [ { "pbrMetallicRoughness": { "baseColorTexture": { "index": 0 } } } ],
  "textures": [ { "source": 0 } ], "images": [ { "uri": ")" +
    image + R"(" } ],
  "buffers": [ { "byteLength": 152, "uri": "tet.bin" } ],
  "bufferViews": [ { "buffer": 0, "byteOffset": 0, "byteLength": 48 },
                   { "buffer": 0, "byteOffset": 48, "byteLength": 48 },
                   { "buffer": 0, "byteOffset": 96, "byteLength": 32 },
                   { "buffer": 0, "byteOffset": 128, "byteLength": 24 } ],
  "accessors": [
    { "bufferView": 0, "componentType": 5126, "count": 4, "type": "VEC3",
      "min": [ 0, 0, 0 ], "max": [ 1, 1, 1 ] },
    { "bufferView": 1, "componentType": 5126, "count": 4, "type": "VEC3" },
    { "bufferView": 2, "componentType": 5126, "count": 4, "type": "VEC2" },
    { "bufferView": 3, "componentType": 5123, "count": 12, "type": "SCALAR" } ]
})";
}

std::string tetrahedronBuffer()
{
  std::string bytes;
  const auto put = [&bytes](const auto& values)
  {
    for (const auto value : values)
    {
      bytes.append(reinterpret_cast<const char*>(&value), sizeof(value));
    }
  };
  put(std::array<float, 12>{ 0, 0, 0, 1, 0, 0, 0, 1, 0, 0, 0, 1 });
  put(std::array<float, 12>{ 1, 0, 0, 0, 1, 0, 0, 0, 1, 1, 1, 1 });
  put(std::array<float, 8>{ 0, 0, 1, 0, 0, 0.25f, 0.5f, 1 });
  put(std::array<uint16_t, 12>{ 0, 2, 1, 0, 1, 3, 0, 3, 2, 1, 2, 3 });
  return bytes;
}

/// The points of `b` (with their texture coordinates) that match a point of `a` within 1e-4, each
/// matched once: two readings of the textured sphere compare whatever order their points come in
/// (the OBJ writes 5 digits).
int64_t matchingPoints(const tc::PolygonSoup& a, const std::vector<float>& uvA,
  const tc::PolygonSoup& b, const std::vector<float>& uvB)
{
  std::vector<bool> used(b.numPoints(), false);
  int64_t matches = 0;
  for (int64_t p = 0; p < a.numPoints(); ++p)
  {
    for (int64_t q = 0; q < b.numPoints(); ++q)
    {
      double d = 0.0;
      for (int c = 0; c < 3; ++c)
      {
        d = std::max(d, std::abs(a.points[3 * p + c] - b.points[3 * q + c]));
      }
      for (int c = 0; c < 2; ++c)
      {
        d = std::max(d, double(std::abs(uvA[2 * p + c] - uvB[2 * q + c])));
      }
      if (!used[q] && d < 1e-4)
      {
        used[q] = true;
        ++matches;
        break;
      }
    }
  }
  return matches;
}
} // namespace

TEST_F(MeshFiles, ObjCornersWithAnotherTextureCoordinateBecomeSeparatePoints)
{
  const tc::MeshFile mesh = tc::readOBJFile(write("square.obj", kSeamSquare));
  ASSERT_EQ(mesh.soup.numPoints(), 5); // the 4 vertices and vertex 1 with vt 4
  EXPECT_EQ(mesh.soup.connectivity, (std::vector<int64_t>{ 0, 1, 2, 4, 2, 3 }));
  EXPECT_EQ(std::vector<double>(mesh.soup.points.begin() + 12, mesh.soup.points.end()),
    (std::vector<double>{ 0, 0, 0 }));
  EXPECT_EQ(mesh.attributes.textureCoordinates,
    (std::vector<float>{ 0, 0, 0.5f, 0, 0.5f, 0.5f, 0, 0.5f, 1, 1 }));
  EXPECT_TRUE(mesh.attributes.colors.empty());
  EXPECT_TRUE(mesh.warnings.empty());
  EXPECT_EQ(tc::readOBJ(write("square.obj", kSeamSquare)).numPoints(), 5);
}

TEST_F(MeshFiles, ObjVertexColoursAreReadAsRGBAWithOpaqueAlpha)
{
  const tc::MeshFile mesh =
    tc::readOBJFile(write("rgb.obj", "v 0 0 0 1 0 0\nv 1 0 0 0 1 0\nv 0 1 0 0 0 0.5\nf 1 2 3\n"));
  EXPECT_EQ(mesh.attributes.colors,
    (std::vector<uint8_t>{ 255, 0, 0, 255, 0, 255, 0, 255, 0, 0, 128, 255 }));
  EXPECT_TRUE(mesh.attributes.textureCoordinates.empty());
  const tc::MeshFile partial =
    tc::readOBJFile(write("some.obj", "v 0 0 0 1 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n"));
  EXPECT_TRUE(partial.attributes.colors.empty());
  EXPECT_TRUE(mentions(partial.warnings, "2 of 3 vertices have no colour"));
}

TEST_F(MeshFiles, ObjCornersWithoutTextureCoordinatesDropThemForTheWholeMeshWithAWarning)
{
  const tc::MeshFile mesh = tc::readOBJFile(write("mixed.obj",
    "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nvt 0 0\nvt 1 0\nvt 1 1\n"
    "f 1/1 2/2 3/3\nf 1 3 4\n"));
  EXPECT_EQ(mesh.soup.numPoints(), 4);
  EXPECT_TRUE(mesh.attributes.textureCoordinates.empty());
  ASSERT_EQ(mesh.warnings.size(), 1u);
  EXPECT_TRUE(mentions(mesh.warnings[0],
    "3 of 6 face corners have no texture coordinate (the "
    "first on line 9)"))
    << mesh.warnings[0];
}

TEST_F(MeshFiles, BadObjTextureCoordinatesAreRefusedNamingTheLine)
{
  const std::string square = "v 0 0 0\nv 1 0 0\nv 1 1 0\nvt 0 0\nvt 1 0\n";
  const std::string outOfRange = objError(square + "f 1/1 2/2 3/9\n");
  EXPECT_TRUE(mentions(outOfRange,
    "line 6: face corner 3 refers to texture coordinate 9, and "
    "the file has 2"))
    << outOfRange;
  EXPECT_TRUE(mentions(objError(square + "f 1/1 2/2 3/0\n"),
    "line 6: face corner refers to "
    "texture coordinate 0"));
  EXPECT_TRUE(mentions(objError(square + "f 1/1 2/2 3/-3\n"), "before the first one"));
  EXPECT_TRUE(mentions(objError(square + "f 1/1 2/x 3/2\n"),
    "line 6: 'x' is no texture "
    "coordinate index"));
  EXPECT_TRUE(mentions(objError(square + "vt\nf 1/1 2/2 3/2\n"),
    "line 6: a texture coordinate "
    "needs u and v"));
  EXPECT_TRUE(mentions(objError(square + "vt 0.5 0.\x01\nf 1/1 2/2 3/2\n"), "line 6:"));
  EXPECT_TRUE(mentions(objError("v 0 0\n"), "line 1: a vertex needs x, y and z"));
  // "vt u" alone is the format's: v defaults to 0.
  const tc::MeshFile mesh = tc::readOBJFile(write("u.obj", square + "vt 0.25\nf 1/1 2/2 3/3\n"));
  EXPECT_EQ(mesh.attributes.textureCoordinates[4], 0.25f);
  EXPECT_EQ(mesh.attributes.textureCoordinates[5], 0.0f);
}

TEST_F(MeshFiles, ObjTakesTheMapKdOfTheFirstMaterialItsFacesUse)
{
  write("paint.mtl",
    "newmtl plain\nKd 1 0 0\nnewmtl skin\nmap_Kd -s 1 1 1 -clamp on "
    "skin tex.png\nnewmtl cloth\nmap_Kd cloth.png\n");
  write("skin tex.png", kFakePng);
  const std::string obj = std::string("mtllib paint.mtl\n") + kSeamSquare;
  const std::string faces = "usemtl plain\nf 1 2 3\nusemtl skin\nf 1 3 4\nusemtl cloth\nf 2 3 4\n";
  const tc::MeshFile mesh = tc::readOBJFile(write("painted.obj", obj + faces));
  EXPECT_EQ(mesh.texture.name, "skin tex.png");
  EXPECT_EQ(mesh.texture.encoded, kFakePng);
  EXPECT_EQ(mesh.texture.leftOut, 1); // cloth.png
  // cloth.png is no file, but only the kept texture is read.
  EXPECT_FALSE(mentions(mesh.warnings, "cloth.png"));
}

TEST_F(MeshFiles, AMissingMaterialLibraryOrTextureIsAWarningNotAnError)
{
  const tc::MeshFile noLibrary =
    tc::readOBJFile(write("a.obj", std::string("mtllib none.mtl\n") + kSeamSquare));
  EXPECT_EQ(noLibrary.soup.numPolygons(), 2);
  EXPECT_TRUE(mentions(noLibrary.warnings, "material library 'none.mtl' not found"));
  EXPECT_TRUE(noLibrary.texture.name.empty());
  write("m.mtl", "newmtl m\nmap_Kd textures\\gone.png\n");
  const tc::MeshFile noTexture =
    tc::readOBJFile(write("b.obj", std::string("mtllib m.mtl\nusemtl m\n") + kSeamSquare));
  EXPECT_EQ(noTexture.texture.name, "textures\\gone.png");
  EXPECT_FALSE(noTexture.texture.hasImage());
  EXPECT_TRUE(mentions(noTexture.warnings,
    "texture 'textures\\gone.png' not found at '" + (Folder / "textures/gone.png").string() + "'"));
}

TEST_F(MeshFiles, PlyVertexTextureCoordinatesColoursAndTextureFileAreRead)
{
  write("checker.png", kFakePng);
  const std::string header = "ply\nformat ascii 1.0\ncomment TextureFile checker.png\n"
                             "element vertex 3\nproperty float x\nproperty float y\n"
                             "property float z\nproperty float s\nproperty float t\n"
                             "property uchar red\nproperty uchar green\nproperty uchar blue\n"
                             "property uchar alpha\nelement face 1\n"
                             "property list uchar int vertex_indices\nend_header\n";
  const tc::MeshFile mesh = tc::readPLYFile(write("tri.ply",
    header + "0 0 0 0 0 255 0 0 10\n1 0 0 1 0 0 255 0 20\n0 1 0 0.5 1 0 0 255 30\n3 0 1 2\n"));
  EXPECT_EQ(mesh.attributes.textureCoordinates, (std::vector<float>{ 0, 0, 1, 0, 0.5f, 1 }));
  EXPECT_EQ(
    mesh.attributes.colors, (std::vector<uint8_t>{ 255, 0, 0, 10, 0, 255, 0, 20, 0, 0, 255, 30 }));
  EXPECT_EQ(mesh.texture.name, "checker.png");
  EXPECT_EQ(mesh.texture.encoded, kFakePng);

  // Binary, big-endian, float colours without alpha, a list element before the vertices.
  std::string binary = "ply\nformat binary_big_endian 1.0\nelement note 1\n"
                       "property list uchar int words\nelement vertex 3\nproperty float x\n"
                       "property float y\nproperty float z\nproperty float r\n"
                       "property float g\nproperty float b\nelement face 1\n"
                       "property list uchar int vertex_indices\nend_header\n";
  const auto put = [&binary](auto value)
  {
    char bytes[sizeof(value)];
    std::memcpy(bytes, &value, sizeof(value));
    std::reverse(bytes, bytes + sizeof(value));
    binary.append(bytes, sizeof(value));
  };
  put(uint8_t(2)), put(int32_t(7)), put(int32_t(8));
  for (int v = 0; v < 3; ++v)
  {
    for (const float c : { float(v == 1), float(v == 2), 0.0f, 1.0f, 0.5f, 0.0f })
    {
      put(c);
    }
  }
  put(uint8_t(3)), put(int32_t(0)), put(int32_t(1)), put(int32_t(2));
  const tc::MeshFile big = tc::readPLYFile(write("big.ply", binary));
  EXPECT_TRUE(big.attributes.textureCoordinates.empty());
  EXPECT_EQ(big.attributes.colors,
    (std::vector<uint8_t>{ 255, 128, 0, 255, 255, 128, 0, 255, 255, 128, 0, 255 }));
  EXPECT_EQ(big.soup.points[3], 1.0);
}

TEST_F(MeshFiles, GltfTextureCoordinatesAreFlippedToTheBottomOriginAndColoursRead)
{
  write("tet.bin", tetrahedronBuffer());
  write("checker.png", kFakePng);
  const tc::Scene scene = tc::readScene(write("tet.gltf", tetrahedronGltf("checker.png")));
  ASSERT_EQ(scene.soup.numPoints(), 4);
  // The file's v (origin at the image's top) 0, 0, 0.25, 1 read as 1 - v.
  EXPECT_EQ(
    scene.attributes.textureCoordinates, (std::vector<float>{ 0, 1, 1, 1, 0, 0.75f, 0.5f, 0 }));
  // RGB colours (VEC3): alpha 255.
  EXPECT_EQ(scene.attributes.colors,
    (std::vector<uint8_t>{ 255, 0, 0, 255, 0, 255, 0, 255, 0, 0, 255, 255, 255, 255, 255, 255 }));
  EXPECT_EQ(scene.texture.name, "checker.png");
  EXPECT_EQ(scene.texture.encoded, kFakePng);
  EXPECT_TRUE(scene.warnings.empty());

  const tc::Scene missing = tc::readScene(write("gone.gltf", tetrahedronGltf("gone.png")));
  EXPECT_FALSE(missing.texture.hasImage());
  EXPECT_TRUE(mentions(missing.warnings, "texture 'gone.png' not found"));
}

TEST(MeshFile, TheTexturedSphereReadsAlikeFromGlbAndObj)
{
  // testing-data/meshes/textured_sphere.* (scripts/make-textured-sphere.py): 32 segments, 16
  // rings, a seam at u = 0 / 1 and a vertex per segment at each pole: 559 (v, vt) pairs.
  const tc::Scene glb = tc::readScene(tctest::testingData("meshes/textured_sphere.glb"));
  const tc::MeshFile obj = tc::readOBJFile(tctest::testingData("meshes/textured_sphere.obj"));
  ASSERT_EQ(glb.soup.numPoints(), 559);
  ASSERT_EQ(obj.soup.numPoints(), 559);
  EXPECT_EQ(glb.soup.numPolygons(), 960);
  EXPECT_EQ(obj.soup.numPolygons(), 512); // quads between the pole rows
  // The same points with the same texture coordinates: the north pole (y = 1) at v = 1, the
  // image's top, in both, though the GLB stores v = 0 there.
  EXPECT_EQ(matchingPoints(glb.soup, glb.attributes.textureCoordinates, obj.soup,
              obj.attributes.textureCoordinates),
    559);
  for (int64_t p = 0; p < glb.soup.numPoints(); ++p)
  {
    if (glb.soup.points[3 * p + 1] > 0.9999)
    {
      EXPECT_EQ(glb.attributes.textureCoordinates[2 * p + 1], 1.0f) << p;
    }
  }
  const std::string png = fileBytes(tctest::testingData("meshes/textured_sphere.png"));
  EXPECT_EQ(glb.texture.name, "embedded:0");
  EXPECT_EQ(glb.texture.encoded, png);
  EXPECT_EQ(obj.texture.name, "textured_sphere.png");
  EXPECT_EQ(obj.texture.encoded, png);
  EXPECT_EQ(glb.texture.leftOut + obj.texture.leftOut, 0);
  EXPECT_TRUE(glb.warnings.empty() && obj.warnings.empty());
}

TEST_F(MeshFiles, DamagedCopiesOfTheTexturedSphereAreRefusedOrReadNeverCrash)
{
  // Every copy is read into attributes of one value per point, or refused with tc::InputError.
  int tried = 0, refused = 0;
  for (const char* name : { "textured_sphere.obj", "textured_sphere.glb" })
  {
    const std::string bytes = fileBytes(tctest::testingData(std::string("meshes/") + name));
    for (const std::string& copy : tctest::damagedCopies(bytes, 13, 45))
    {
      ++tried;
      try
      {
        const std::string path = write(name, copy);
        const bool isObj = mentions(name, ".obj");
        const tc::MeshFile mesh = isObj ? tc::readOBJFile(path) : tc::MeshFile{};
        const tc::Scene scene = isObj ? tc::Scene{} : tc::readScene(path);
        const tc::PolygonSoup& soup = isObj ? mesh.soup : scene.soup;
        const tc::PointAttributes& a = isObj ? mesh.attributes : scene.attributes;
        const size_t n = static_cast<size_t>(soup.numPoints());
        EXPECT_TRUE(a.textureCoordinates.empty() || a.textureCoordinates.size() == 2 * n);
        EXPECT_TRUE(a.colors.empty() || a.colors.size() == 4 * n);
        for (const int64_t id : soup.connectivity)
        {
          ASSERT_TRUE(id >= 0 && id < soup.numPoints());
        }
      }
      catch (const tc::InputError&)
      {
        ++refused;
      }
    }
  }
  std::cout << "[ figures  ] " << refused << " of " << tried << " damaged copies refused\n";
  EXPECT_GT(refused, 0);
}

TEST(MeshFile, DamagedPngsAreFoundBeforeTheyReachADecoder)
{
  // vtkPNGReader crashes on a PNG libpng reports; tcMeshReader asks tc::pngDamage first.
  const std::string png = fileBytes(tctest::testingData("meshes/textured_sphere.png"));
  EXPECT_EQ(tc::pngDamage(png), "");
  EXPECT_TRUE(mentions(tc::pngDamage(png.substr(0, png.size() - 5)), "ends before its IEND"));
  EXPECT_TRUE(mentions(tc::pngDamage("GIF89a"), "no PNG signature"));
  std::string flipped = png;
  flipped[png.find("IDAT") + 6] ^= 0x55;
  EXPECT_TRUE(mentions(tc::pngDamage(flipped), "IDAT chunk fails its CRC"));
  // A 64 x 33 header over 64 x 32 rows of 1 + 3 x 64 bytes (CRC made right).
  std::string taller = png;
  taller[16 + 7] = 33;
  const uint32_t crc = crc32Of(taller.substr(12, 17));
  for (int k = 0; k < 4; ++k)
  {
    taller[29 + k] = static_cast<char>(crc >> (24 - 8 * k));
  }
  EXPECT_TRUE(mentions(tc::pngDamage(taller), "inflate to 6176 bytes, and the image has 6369"))
    << tc::pngDamage(taller);
}
