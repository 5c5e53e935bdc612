// SPDX-License-Identifier: BSD-3-Clause
// The glTF export on the bundled bunny's atlas (built at the defaults): what Assimp reads back
// is, LOD by LOD, the mesh rebuildMesh draws at the same levels; the file keeps the glTF 2.0
// rules a validator checks (GLB chunks, buffer and accessor bounds, POSITION min and max,
// indices in range) and links the LODs by MSFT_lod.
#include "assimp_poser.h"
#include "pipeline_fixture.h"
#include "temp_folder.h"

#include "tc/common/errors.h"
#include "tc/gim/geometry_image_mesh.h"
#include "tc/gim/geometry_images.h"
#include "tc/gim/path_tracing.h"
#include "tc/io/gltf_export.h"

#include <assimp/Importer.hpp>
#include <assimp/anim.h>
#include <assimp/scene.h>
#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <cmath>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <map>

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
  return type == 5121 ? 1 : type == 5123 ? 2 : 4;
} // uint8, uint16, or uint32 / float

size_t componentsOf(const std::string& type)
{
  return type == "SCALAR" ? 1 : type == "VEC2" ? 2 : type == "VEC3" ? 3 : type == "MAT4" ? 16 : 4;
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

namespace
{
tc::Matrix4 translation(double x, double y, double z)
{
  tc::Matrix4 m = tc::identityMatrix();
  m[3] = x, m[7] = y, m[11] = z;
  return m;
}

/// A rotation by `angle` about z, as a matrix and as tc's quaternion (w, x, y, z).
tc::Matrix4 turn(double angle)
{
  tc::Matrix4 m = tc::identityMatrix();
  m[0] = m[5] = std::cos(angle), m[1] = -std::sin(angle), m[4] = std::sin(angle);
  return m;
}

std::array<double, 4> turnQuaternion(double angle)
{
  return { std::cos(angle / 2), 0.0, 0.0, std::sin(angle / 2) };
}

/// The bunny's x range: the rig's joints lie along it and the skin blends over it.
std::pair<double, double> xRange(const tc::Atlas& atlas)
{
  const tc::TriMesh m = tc::rebuildMesh(atlas, std::vector<int32_t>(atlas.charts.size(), 0)).mesh;
  double lo = m.points[0], hi = m.points[0];
  for (size_t v = 0; v < m.points.size(); v += 3)
  {
    lo = std::min(lo, m.points[v]), hi = std::max(hi, m.points[v]);
  }
  return { lo, hi };
}

/// "hip" (root) and "knee" (its child, halfway along x, turned), "knee" again as a second joint
/// of the knee's node (sameNodeAs, its own inverse bind); the animation "bend" moves the hip
/// and bends the knee (keys ending before the duration), and "sampled" is of sampled poses.
tc::Rig bunnyRig(double x0, double length)
{
  tc::Rig rig;
  tc::Joint hip{ "hip", -1, translation(x0, 0.0, 0.0), {}, -1 };
  hip.inverseBind = tc::inverseAffine(hip.restLocal);
  tc::Joint knee{ "knee", 0, tc::multiply(translation(length / 2, 0.0, 0.0), turn(0.2)), {}, -1 };
  knee.inverseBind = tc::inverseAffine(tc::multiply(hip.restLocal, knee.restLocal));
  tc::Joint second = knee;
  second.sameNodeAs = 1;
  second.inverseBind = tc::multiply(translation(0.0, 0.1 * length, 0.0), knee.inverseBind);
  rig.skeleton.joints = { hip, knee, second };
  tc::Animation bend;
  bend.name = "bend";
  bend.duration = 2.0;
  bend.ticksPerSecond = 25.0;
  tc::JointTrack moveHip;
  moveHip.joint = 0;
  moveHip.positionTimes = { 0.0, 2.0 };
  moveHip.positions = { { x0, 0.0, 0.0 }, { x0, 0.0, 0.2 * length } };
  tc::JointTrack bendKnee;
  bendKnee.joint = 1;
  bendKnee.rotationTimes = { 0.0, 1.0, 1.5 };
  bendKnee.rotations = { turnQuaternion(0.2), turnQuaternion(0.8), turnQuaternion(-0.3) };
  bendKnee.positionTimes = { 0.5, 1.5 };
  bendKnee.positions = { { length / 2, 0.0, 0.0 }, { length / 2, 0.1 * length, 0.0 } };
  bend.tracks = { moveHip, bendKnee };
  tc::Animation sampled;
  sampled.name = "sampled";
  sampled.duration = 1.0;
  sampled.frameTimes = { 0.0, 1.0 };
  sampled.frameGlobals.assign(2, std::vector<tc::Matrix4>(3, tc::identityMatrix()));
  rig.animations = { bend, sampled };
  return rig;
}

/// The skin of a sample at x: a function of the position, so that shared sides agree; weights
/// summing to 0.9 (not 1), as a file may give them.
void skinAt(double x, double x0, double length, float* skin)
{
  const float t = float(std::clamp((x - x0) / length, 0.0, 1.0));
  const float values[tc::kSkinValues] = { 0, 1, 2, 0, 0.9f * (1 - t), 0.54f * t, 0.36f * t, 0 };
  std::copy(values, values + tc::kSkinValues, skin);
}

const tc::Atlas& skinnedAtlas()
{
  static const tc::Atlas atlas = []
  {
    tc::Atlas a = bunnyAtlas();
    const auto [x0, x1] = xRange(a);
    a.rig = bunnyRig(x0, x1 - x0);
    a.attributes.push_back({ tc::kAtlasSkin, tc::kSkinValues });
    for (tc::AtlasImage& image : a.images)
    {
      const size_t texels = size_t(image.width) * size_t(image.height);
      std::vector<float> skin(texels * tc::kSkinValues);
      for (size_t t = 0; t < texels; ++t)
      {
        skinAt(image.data[0][3 * t], x0, x1 - x0, skin.data() + tc::kSkinValues * t);
      }
      image.data.push_back(std::move(skin));
    }
    tc::validateAtlas(a);
    return a;
  }();
  return atlas;
}

/// The rebuilt mesh's Skin values as tc::SkinWeights, the weights divided by their sum as the
/// file holds them.
tc::SkinWeights normalizedSkin(const tc::RebuiltMesh& rebuilt, int32_t skinAttribute)
{
  const std::vector<float>& values = rebuilt.attributes[size_t(skinAttribute) - 1];
  tc::SkinWeights skin;
  for (size_t v = 0; v < values.size(); v += tc::kSkinValues)
  {
    const float* w = values.data() + v + tc::kMaxInfluences;
    const float sum = w[0] + w[1] + w[2] + w[3];
    for (int k = 0; k < tc::kMaxInfluences; ++k)
    {
      skin.joints.push_back(int32_t(std::lround(values[v + size_t(k)])));
      skin.weights.push_back(w[k] / sum);
    }
  }
  return skin;
}

/// The largest distance between two point lists, relative to the bunny's diagonal.
double relativeDistance(const std::vector<double>& a, const std::vector<double>& b)
{
  EXPECT_EQ(a.size(), b.size());
  double worst = 0.0;
  for (size_t i = 0; i < std::min(a.size(), b.size()); ++i)
  {
    worst = std::max(worst, std::abs(a[i] - b[i]));
  }
  return worst / bunnyAtlas().inputDiagonal;
}
} // namespace

TEST_F(GltfExport, SkinnedAtlasKeepsItsSkinJointsAndKeyframedAnimation)
{
  const tc::Atlas& atlas = skinnedAtlas();
  const std::string path = file("skinned.glb");
  const std::vector<tc::GltfLod> lods = tc::writeGltf(path, atlas);
  // The file: JOINTS_0 as bytes, WEIGHTS_0 summing to 1, one skin on every LOD, 5 channels (the
  // hip's translation, the knee's rotation and translation on its node and on its copy).
  const auto [gltf, bin] = glbChunks(readBytes(path));
  expectBoundsHold(gltf, bin);
  const auto& attributes = gltf["meshes"][0]["primitives"][0]["attributes"];
  EXPECT_EQ(gltf["accessors"][size_t(attributes["JOINTS_0"])]["componentType"], 5121);
  const auto& weights = gltf["accessors"][size_t(attributes["WEIGHTS_0"])];
  const float* w = reinterpret_cast<const float*>(
    bin.data() + size_t(gltf["bufferViews"][size_t(weights["bufferView"])].value("byteOffset", 0)));
  for (size_t v = 0; v < size_t(weights["count"]); ++v)
  {
    ASSERT_NEAR(w[4 * v] + w[4 * v + 1] + w[4 * v + 2] + w[4 * v + 3], 1.0f, 1e-6f) << v;
  }
  ASSERT_EQ(gltf["skins"].size(), 1u);
  EXPECT_EQ(gltf["skins"][0]["joints"].size(), 3u);
  EXPECT_EQ(gltf["accessors"][size_t(gltf["skins"][0]["inverseBindMatrices"])]["type"], "MAT4");
  for (size_t k = 0; k < lods.size(); ++k)
  {
    EXPECT_EQ(gltf["nodes"][k]["skin"], 0) << "LOD " << k;
  }
  ASSERT_EQ(gltf["animations"].size(), 1u);
  EXPECT_EQ(gltf["animations"][0]["name"], "bend");
  EXPECT_EQ(gltf["animations"][0]["channels"].size(), 5u);
  for (const auto& sampler : gltf["animations"][0]["samplers"])
  {
    const auto& input = gltf["accessors"][size_t(sampler["input"])];
    EXPECT_EQ(double(input["max"][0]), 2.0); // held to the duration
    EXPECT_TRUE(input.contains("min"));
  }
  const std::vector<std::string> notes = tc::gltfExportNotes(atlas);
  ASSERT_EQ(notes.size(), 1u);
  EXPECT_NE(notes[0].find("sampled"), std::string::npos);
  EXPECT_TRUE(tc::gltfExportNotes(bunnyAtlas()).empty());
}

TEST_F(GltfExport, AssimpPosesTheSkinnedFileAsJointGlobalsAndSkinPointsDo)
{
  const tc::Atlas& atlas = skinnedAtlas();
  const std::string path = file("skinned.glb");
  const std::vector<tc::GltfLod> lods = tc::writeGltf(path, atlas);
  Assimp::Importer importer;
  const aiScene* scene = importer.ReadFile(path, 0);
  ASSERT_NE(scene, nullptr) << importer.GetErrorString();
  ASSERT_EQ(scene->mNumMeshes, 1u);
  const aiMesh& mesh = *scene->mMeshes[0];
  ASSERT_EQ(mesh.mNumBones, 3u);
  for (unsigned b = 0; b < mesh.mNumBones; ++b)
  {
    EXPECT_GT(mesh.mBones[b]->mNumWeights, 0u) << mesh.mBones[b]->mName.C_Str();
  }
  const aiNode* hip = scene->mRootNode->FindNode("hip");
  ASSERT_NE(hip, nullptr);
  ASSERT_NE(hip->FindNode("knee"), nullptr);
  ASSERT_NE(hip->FindNode("knee.bind2"), nullptr);
  ASSERT_EQ(scene->mNumAnimations, 1u);
  const aiAnimation& animation = *scene->mAnimations[0];
  EXPECT_STREQ(animation.mName.C_Str(), "bend");
  EXPECT_EQ(animation.mNumChannels, 3u); // one per animated node
  const double ticksPerSecond = animation.mTicksPerSecond > 0 ? animation.mTicksPerSecond : 1.0;
  EXPECT_NEAR(animation.mDuration / ticksPerSecond, 2.0, 1e-6);
  // Posed by Assimp's data and by tc at the rest pose and two times, the second after the
  // knee's last key.
  const tc::RebuiltMesh rebuilt = tc::rebuildMesh(atlas, lods[0].chartLevels);
  const tc::SkinWeights skin = normalizedSkin(rebuilt, tc::findAttribute(atlas, tc::kAtlasSkin));
  const tc::Skeleton& skeleton = atlas.rig.skeleton;
  const auto tcPose = [&](const tc::Animation* a, double seconds)
  {
    return tc::skinPoints(rebuilt.mesh.points, skin,
      tc::skinningMatrices(skeleton, tc::jointGlobals(skeleton, a, seconds)));
  };
  EXPECT_LE(
    relativeDistance(tctest::AssimpPoser(*scene, nullptr).pose(mesh, 0.0), tcPose(nullptr, 0)),
    1e-5);
  for (const double seconds : { 0.75, 1.8 })
  {
    const std::vector<double> read =
      tctest::AssimpPoser(*scene, &animation).pose(mesh, seconds * ticksPerSecond);
    EXPECT_LE(relativeDistance(read, tcPose(&atlas.rig.animations[0], seconds)), 1e-5)
      << seconds << " s";
    EXPECT_GT(relativeDistance(read, tcPose(nullptr, 0)), 1e-2) << "the animation moves it";
  }
}

TEST_F(GltfExport, EveryLodOfASkinnedAtlasReadsBackAsRebuildMeshDrawsIt)
{
  // Issue 22's line for a skinned character: every level's triangles and rest positions.
  const tc::Atlas& atlas = skinnedAtlas();
  const std::string path = file("skinned_lods.glb");
  tc::GltfExportOptions options;
  options.layout = tc::GltfLayout::NamedNodes;
  const std::vector<tc::GltfLod> lods = tc::writeGltf(path, atlas, options);
  ASSERT_GE(lods.size(), 3u);
  Assimp::Importer importer;
  const aiScene* scene = importer.ReadFile(path, 0);
  ASSERT_NE(scene, nullptr) << importer.GetErrorString();
  for (size_t k = 0; k < lods.size(); ++k)
  {
    const aiNode* node = scene->mRootNode->FindNode(("TriChart_LOD" + std::to_string(k)).c_str());
    ASSERT_NE(node, nullptr) << "LOD " << k;
    ASSERT_EQ(node->mNumMeshes, 1u);
    const aiMesh* mesh = scene->mMeshes[node->mMeshes[0]];
    EXPECT_EQ(mesh->mNumBones, 3u) << "LOD " << k;
    expectSameMesh(
      mesh, tc::rebuildMesh(atlas, lods[k].chartLevels).mesh, "LOD " + std::to_string(k));
  }
}
