// SPDX-License-Identifier: BSD-3-Clause
// The glTF export on the bundled bunny's atlas (built at the defaults): what Assimp reads back
// is, LOD by LOD, the mesh rebuildMesh draws at the same levels; the file keeps the glTF 2.0
// rules a validator checks (GLB chunks, buffer and accessor bounds, POSITION min and max,
// indices in range) and links the LODs by MSFT_lod.
#include "pipeline_fixture.h"
#include "temp_folder.h"

#include "tc/common/errors.h"
#include "tc/gim/geometry_image_mesh.h"
#include "tc/gim/geometry_images.h"
#include "tc/gim/path_tracing.h"
#include "tc/io/gltf_export.h"

#include <assimp/Importer.hpp>
#include <assimp/scene.h>
#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <cmath>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iterator>

namespace
{
const tc::Atlas& bunnyAtlas()
{
  static const tc::Atlas atlas = []
  {
    const tctest::PipelineCase& c = *tctest::pipelineCase(tctest::pipelineMeshPath("bunny_npm"));
    return tc::buildGeometryImages(tc::tracePaths(c.mesh, c.result), c.result, {}, {}, {});
  }();
  return atlas;
}

std::string readBytes(const std::string& path)
{
  std::ifstream in(path, std::ios::binary);
  return { std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>() };
}

uint32_t word(const std::string& bytes, size_t at)
{
  uint32_t w = 0;
  std::memcpy(&w, bytes.data() + at, 4);
  return w;
}

/// The JSON and BIN chunks of a GLB, checking its header and chunk framing.
std::pair<nlohmann::json, std::string> glbChunks(const std::string& bytes)
{
  EXPECT_GE(bytes.size(), 28u);
  EXPECT_EQ(bytes.substr(0, 4), "glTF");
  EXPECT_EQ(word(bytes, 4), 2u);
  EXPECT_EQ(word(bytes, 8), bytes.size());
  const uint32_t jsonLength = word(bytes, 12);
  EXPECT_EQ(bytes.substr(16, 4), "JSON");
  EXPECT_EQ(jsonLength % 4, 0u);
  const size_t bin = 20 + jsonLength;
  EXPECT_EQ(bytes.substr(bin + 4, 4), std::string("BIN\0", 4));
  const uint32_t binLength = word(bytes, bin);
  EXPECT_EQ(binLength % 4, 0u);
  EXPECT_EQ(bin + 8 + binLength, bytes.size());
  return { nlohmann::json::parse(bytes.substr(20, jsonLength)), bytes.substr(bin + 8, binLength) };
}

size_t componentBytes(int type)
{
  return type == 5123 ? 2 : 4;
} // uint16, or uint32 / float

size_t componentsOf(const std::string& type)
{
  return type == "SCALAR" ? 1 : type == "VEC2" ? 2 : type == "VEC3" ? 3 : 4;
}

/// Buffer views inside the buffer, accessors inside their views, POSITION bounds exact.
void expectBoundsHold(const nlohmann::json& gltf, const std::string& bin)
{
  const size_t bufferLength = gltf["buffers"][0]["byteLength"];
  EXPECT_LE(bufferLength, bin.size());
  for (const auto& view : gltf["bufferViews"])
  {
    EXPECT_LE(size_t(view.value("byteOffset", 0)) + size_t(view["byteLength"]), bufferLength);
  }
  for (const auto& a : gltf["accessors"])
  {
    const auto& view = gltf["bufferViews"][size_t(a["bufferView"])];
    const size_t n =
      size_t(a["count"]) * componentsOf(a["type"]) * componentBytes(a["componentType"]);
    EXPECT_LE(size_t(a.value("byteOffset", 0)) + n, size_t(view["byteLength"]));
  }
  for (const auto& mesh : gltf["meshes"])
  {
    const auto& a = gltf["accessors"][size_t(mesh["primitives"][0]["attributes"]["POSITION"])];
    const auto& view = gltf["bufferViews"][size_t(a["bufferView"])];
    const float* p =
      reinterpret_cast<const float*>(bin.data() + size_t(view.value("byteOffset", 0)));
    for (size_t k = 0; k < 3; ++k)
    {
      float lo = p[k], hi = p[k];
      for (size_t v = 0; v < size_t(a["count"]); ++v)
      {
        lo = std::min(lo, p[3 * v + k]), hi = std::max(hi, p[3 * v + k]);
      }
      EXPECT_EQ(double(a["min"][k]), double(lo));
      EXPECT_EQ(double(a["max"][k]), double(hi));
    }
  }
}

class GltfExport : public tctest::TempFolderTest
{
};
} // namespace

namespace
{
/// `read` is `m`: the same points (within float rounding of the diagonal) and triangles.
void expectSameMesh(const aiMesh* read, const tc::TriMesh& m, const std::string& what)
{
  ASSERT_EQ(int64_t(read->mNumVertices), m.numPoints()) << what;
  ASSERT_EQ(int64_t(read->mNumFaces), m.numTriangles()) << what;
  ASSERT_TRUE(read->HasNormals()) << what;
  double worst = 0.0;
  for (int64_t v = 0; v < m.numPoints(); ++v)
  {
    const aiVector3D& p = read->mVertices[v];
    worst = std::max({ worst, std::abs(p.x - m.points[3 * v]), std::abs(p.y - m.points[3 * v + 1]),
      std::abs(p.z - m.points[3 * v + 2]) });
  }
  EXPECT_LE(worst, 1e-6 * bunnyAtlas().inputDiagonal) << what;
  for (int64_t f = 0; f < m.numTriangles(); ++f)
  {
    ASSERT_EQ(read->mFaces[f].mNumIndices, 3u) << what;
    for (int i = 0; i < 3; ++i)
    {
      ASSERT_EQ(int64_t(read->mFaces[f].mIndices[i]), m.triangles[3 * f + i]) << what;
    }
  }
}
} // namespace

TEST_F(GltfExport, AssimpReadsBackEachLodAsRebuildMeshDrawsIt)
{
  // Named nodes: Assimp, which ignores MSFT_lod, sees every LOD; as .glb and as .gltf.
  for (const bool binary : { true, false })
  {
    const std::string path = file(binary ? "bunny.glb" : "bunny.gltf");
    tc::GltfExportOptions options;
    options.layout = tc::GltfLayout::NamedNodes;
    const std::vector<tc::GltfLod> lods = tc::writeGltf(path, bunnyAtlas(), options);
    ASSERT_GE(lods.size(), 3u);
    Assimp::Importer importer;
    const aiScene* scene = importer.ReadFile(path, 0);
    ASSERT_NE(scene, nullptr) << importer.GetErrorString();
    const aiNode* group = scene->mRootNode->FindNode("TriChart");
    ASSERT_NE(group, nullptr);
    ASSERT_EQ(group->mNumChildren, lods.size());
    for (size_t k = 0; k < lods.size(); ++k)
    {
      const aiNode* node = group->FindNode(("TriChart_LOD" + std::to_string(k)).c_str());
      ASSERT_NE(node, nullptr) << "LOD " << k;
      ASSERT_EQ(node->mNumMeshes, 1u);
      const tc::TriMesh m = tc::rebuildMesh(bunnyAtlas(), lods[k].chartLevels).mesh;
      EXPECT_EQ(lods[k].triangles, m.numTriangles());
      expectSameMesh(scene->mMeshes[node->mMeshes[0]], m, "LOD " + std::to_string(k));
    }
  }
  // MSFT_lod: Assimp shows LOD 0 alone.
  const std::string path = file("lod.glb");
  const std::vector<tc::GltfLod> lods = tc::writeGltf(path, bunnyAtlas());
  Assimp::Importer importer;
  const aiScene* scene = importer.ReadFile(path, 0);
  ASSERT_NE(scene, nullptr) << importer.GetErrorString();
  ASSERT_EQ(scene->mNumMeshes, 1u);
  expectSameMesh(
    scene->mMeshes[0], tc::rebuildMesh(bunnyAtlas(), lods[0].chartLevels).mesh, "LOD 0");
}

TEST_F(GltfExport, GlbKeepsTheRulesAndLinksTheLodsFinestFirst)
{
  const std::string path = file("bunny.glb");
  const std::vector<tc::GltfLod> lods = tc::writeGltf(path, bunnyAtlas());
  const auto [gltf, bin] = glbChunks(readBytes(path));
  expectBoundsHold(gltf, bin);
  EXPECT_EQ(gltf["asset"]["version"], "2.0");
  EXPECT_EQ(gltf["extensionsUsed"], nlohmann::json::array({ "MSFT_lod" }));
  EXPECT_FALSE(gltf.contains("extensionsRequired"));
  EXPECT_EQ(gltf["scenes"][0]["nodes"], nlohmann::json::array({ 0 }));
  const auto& first = gltf["nodes"][0];
  ASSERT_EQ(first["extensions"]["MSFT_lod"]["ids"].size(), lods.size() - 1);
  const auto& coverage = first["extras"]["MSFT_screencoverage"];
  ASSERT_EQ(coverage.size(), lods.size());
  for (size_t k = 0; k < lods.size(); ++k)
  {
    if (k > 0)
    {
      EXPECT_EQ(first["extensions"]["MSFT_lod"]["ids"][k - 1], k);
      EXPECT_LT(double(coverage[k]), double(coverage[k - 1]));
      EXPECT_LT(lods[k].triangles, lods[k - 1].triangles);
      EXPECT_GT(lods[k].error, lods[k - 1].error);
    }
    EXPECT_EQ(gltf["nodes"][k]["extras"]["triangles"], lods[k].triangles);
    const auto& primitive = gltf["meshes"][k]["primitives"][0];
    const auto& indices = gltf["accessors"][size_t(primitive["indices"])];
    EXPECT_EQ(indices["count"], 3 * lods[k].triangles);
    EXPECT_EQ(indices["componentType"], lods[k].points <= 65535 ? 5123 : 5125);
    // Every LOD's positions are those rebuildMesh gives, in float.
    const tc::TriMesh m = tc::rebuildMesh(bunnyAtlas(), lods[k].chartLevels).mesh;
    const auto& position = gltf["accessors"][size_t(primitive["attributes"]["POSITION"])];
    ASSERT_EQ(position["count"], m.numPoints());
    const auto& view = gltf["bufferViews"][size_t(position["bufferView"])];
    const float* p =
      reinterpret_cast<const float*>(bin.data() + size_t(view.value("byteOffset", 0)));
    for (size_t i = 0; i < m.points.size(); ++i)
    {
      ASSERT_EQ(p[i], float(m.points[i])) << "LOD " << k;
    }
  }
  EXPECT_EQ(double(coverage.back()), 0.0);
  // The chain runs from every chart at its finest level to the base complex.
  for (size_t c = 0; c < bunnyAtlas().charts.size(); ++c)
  {
    EXPECT_EQ(lods.front().chartLevels[c], bunnyAtlas().charts[c].maxLevel);
    EXPECT_EQ(lods.back().chartLevels[c], 0);
  }
}

TEST_F(GltfExport, UniformChainTakesOneLevelPerLod)
{
  tc::GltfExportOptions options;
  options.chain = tc::GltfChain::Uniform;
  const std::vector<tc::GltfLod> lods = tc::gltfLodChain(bunnyAtlas(), options);
  const int32_t top = bunnyAtlas().maxLevel();
  ASSERT_EQ(lods.size(), size_t(top + 1));
  for (size_t k = 0; k < lods.size(); ++k)
  {
    for (size_t c = 0; c < bunnyAtlas().charts.size(); ++c)
    {
      EXPECT_EQ(
        lods[k].chartLevels[c], std::min(top - int32_t(k), bunnyAtlas().charts[c].maxLevel));
    }
  }
  options.maxLods = 2;
  EXPECT_EQ(tc::gltfLodChain(bunnyAtlas(), options).size(), 2u);
}

TEST_F(GltfExport, RefusesBadOptionsAndLeavesNoFileOnAFailedWrite)
{
  tc::GltfExportOptions bad;
  bad.errorRatio = 1.0;
  EXPECT_THROW(tc::gltfLodChain(bunnyAtlas(), bad), tc::InputError);
  bad = {};
  bad.viewportHeight = 0.0;
  EXPECT_THROW(tc::gltfLodChain(bunnyAtlas(), bad), tc::InputError);
  tc::Atlas unmeasured = bunnyAtlas();
  unmeasured.charts[0].levelError.clear();
  EXPECT_THROW(tc::writeGltf(file("a.glb"), unmeasured), tc::InputError);
  EXPECT_THROW(tc::writeGltf(file("missing/a.glb"), bunnyAtlas()), tc::InputError);
  EXPECT_THROW(tc::writeGltf(file("a.obj"), bunnyAtlas()), tc::InputError);
  EXPECT_TRUE(std::filesystem::is_empty(Folder));
}
