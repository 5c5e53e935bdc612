// SPDX-License-Identifier: BSD-3-Clause
#include "tc/io/scene_io.h"

#include "io/scene_skin.h"
#include "io/scene_textures.h"
#include "tc/common/errors.h"
#include "tc/common/file_names.h"

#include <assimp/Importer.hpp>
#include <assimp/ProgressHandler.hpp>
#include <assimp/importerdesc.h>
#include <assimp/postprocess.h>
#include <assimp/scene.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <fstream>
#include <iterator>
#include <map>
#include <set>
#include <sstream>
#include <vector>

namespace tc
{
namespace
{
// The formats whose Assimp 5.2 importer survived 508 truncated and byte-flipped copies of the
// shared data's wuson.glb, Testwuson.X, snake .fbx and sydney.md2 without crashing. Not offered:
// MD5, whose importer crashes on a truncated ffflag.md5mesh or a misspelled keyword in it; 3DS
// and COLLADA, which no file here tests.
constexpr const char* kExtensions = "glb gltf fbx x md2";

/// Forwards Assimp's progress to a tc::Progress; an abort becomes Assimp's "stop reading"
/// (an exception must not cross Assimp's code).
class ForwardProgress : public Assimp::ProgressHandler
{
public:
  ForwardProgress(const Progress& progress, bool& aborted)
    : Progress_(progress)
    , Aborted_(aborted)
  {
  }
  bool Update(float fraction) override
  {
    try
    {
      Progress_.report(std::clamp(static_cast<double>(fraction), 0.0, 1.0));
    }
    catch (const Aborted&)
    {
      Aborted_ = true;
    }
    return !Aborted_;
  }

private:
  Progress Progress_;
  bool& Aborted_;
};

/// Points whose mesh has no texture coordinates, and no colours: a per-point attribute is kept
/// only when every placed mesh has it.
struct AttributeGaps
{
  int64_t withoutUV = 0;
  int64_t withoutColor = 0;
};

uint8_t colorByte(float value)
{
  return static_cast<uint8_t>(std::lround(std::clamp(value, 0.0f, 1.0f) * 255.0f));
}

/// Appends the texture coordinates (set 0; v as Assimp gives it, origin at the image's bottom)
/// and colours (set 0) of `mesh`'s points, (0, 0) and white where the mesh has none.
void addPointAttributes(const aiMesh& mesh, Scene& out, AttributeGaps& gaps)
{
  std::vector<float>& uv = out.attributes.textureCoordinates;
  std::vector<uint8_t>& rgba = out.attributes.colors;
  const aiVector3D* coordinates = mesh.mTextureCoords[0];
  const aiColor4D* colors = mesh.mColors[0];
  gaps.withoutUV += coordinates ? 0 : mesh.mNumVertices;
  gaps.withoutColor += colors ? 0 : mesh.mNumVertices;
  // Assimp 5.2's glTF importer copies RGB colours (COLOR_0 of type VEC3) into RGBA and leaves
  // alpha 0; a mesh whose every colour has alpha 0 is taken as RGB, hence opaque.
  const bool rgbOnly = colors &&
    std::all_of(colors, colors + mesh.mNumVertices, [](const aiColor4D& c) { return c.a == 0; });
  for (unsigned v = 0; v < mesh.mNumVertices; ++v)
  {
    uv.push_back(coordinates ? coordinates[v].x : 0.0f);
    uv.push_back(coordinates && mesh.mNumUVComponents[0] > 1 ? coordinates[v].y : 0.0f);
    const aiColor4D c = colors ? colors[v] : aiColor4D(1, 1, 1, 1);
    rgba.insert(rgba.end(),
      { colorByte(c.r), colorByte(c.g), colorByte(c.b), rgbOnly ? uint8_t(255) : colorByte(c.a) });
  }
}

/// Drops the attributes some placed meshes lack, with a warning; those none has, silently.
void keepCompleteAttributes(Scene& out, const AttributeGaps& gaps)
{
  const int64_t points = out.soup.numPoints();
  const auto keep = [&](auto& values, int64_t missing, const char* what)
  {
    if (missing > 0 && missing < points)
    {
      out.warnings.push_back(std::to_string(missing) + " of " + std::to_string(points) +
        " points have no " + what + " (their meshes lack them): the scene is read without " + what);
    }
    if (missing > 0)
    {
      values.clear();
    }
  };
  keep(out.attributes.textureCoordinates, gaps.withoutUV, "texture coordinates");
  keep(out.attributes.colors, gaps.withoutColor, "colours");
}

/// What addNode gathers besides the scene's polygons.
struct Gathering
{
  AttributeGaps gaps;
  SceneSkinBuilder skin;
};

/// Appends the meshes of `node` and of its children, each placed with the transform
/// accumulated from the root.
void addNode(
  const aiScene& scene, const aiNode& node, const aiMatrix4x4& parent, Scene& out, Gathering& more)
{
  const aiMatrix4x4 transform = parent * node.mTransformation;
  // A mirroring transform reverses the winding; put it back so faces keep their side.
  const bool mirrored = transform.Determinant() < 0.0f;
  for (unsigned k = 0; k < node.mNumMeshes; ++k)
  {
    if (node.mMeshes[k] >= scene.mNumMeshes)
    {
      throw InputError("the node '" + std::string(node.mName.C_Str()) +
        "' refers to a mesh the file does not have");
    }
    const aiMesh& mesh = *scene.mMeshes[node.mMeshes[k]];
    const int64_t first = out.soup.numPoints();
    for (unsigned v = 0; v < mesh.mNumVertices; ++v)
    {
      const aiVector3D p = transform * mesh.mVertices[v];
      out.soup.points.insert(out.soup.points.end(), { p.x, p.y, p.z });
    }
    addPointAttributes(mesh, out, more.gaps);
    if (more.skin.active())
    {
      more.skin.addMesh(mesh, node, transform, out.skin);
    }
    std::vector<int64_t> ids;
    for (unsigned f = 0; f < mesh.mNumFaces; ++f)
    {
      const aiFace& face = mesh.mFaces[f];
      if (face.mNumIndices < 3)
      {
        ++out.skippedPrimitives;
        continue;
      }
      ids.resize(face.mNumIndices);
      for (unsigned c = 0; c < face.mNumIndices; ++c)
      {
        if (face.mIndices[c] >= mesh.mNumVertices)
        {
          throw InputError("a face of the mesh '" + std::string(mesh.mName.C_Str()) +
            "' refers to vertex " + std::to_string(face.mIndices[c]) + " of " +
            std::to_string(mesh.mNumVertices));
        }
        ids[c] = first + face.mIndices[c];
      }
      if (mirrored)
      {
        std::reverse(ids.begin(), ids.end());
      }
      out.soup.addPolygon(ids.data(), static_cast<int64_t>(ids.size()));
      out.meshId.push_back(static_cast<int32_t>(node.mMeshes[k]));
    }
    ++out.meshInstances;
  }
  for (unsigned c = 0; c < node.mNumChildren; ++c)
  {
    addNode(scene, *node.mChildren[c], transform, out, more);
  }
}

/// The warnings on what the skin's 4 influences per point and a bone-less point leave out, and
/// on weights that do not sum to 1.
void addSkinWarnings(Scene& out)
{
  if (out.skin.pointsOverLimit > 0)
  {
    out.warnings.push_back(std::to_string(out.skin.pointsOverLimit) + " points have more than " +
      std::to_string(kMaxInfluences) +
      " bone influences: the largest 4 are kept and renormalized (largest weight dropped " +
      std::to_string(out.skin.largestDropped) + ")");
  }
  if (out.skin.pointsOffUnitSum > 0)
  {
    std::ostringstream range;
    range << out.skin.smallestSum << " to " << out.skin.largestSum;
    out.warnings.push_back(std::to_string(out.skin.pointsOffUnitSum) +
      " points have bone weights that do not sum to 1 (" + range.str() +
      "): kept as the file gives them, so they pose as Assimp poses them");
  }
  if (out.unweightedPoints > 0)
  {
    out.warnings.push_back(std::to_string(out.unweightedPoints) +
      " points of skinned meshes have no bone weight: they move with their mesh's node");
  }
}

/// Whether the object-to-object connections (C: "OO",child,parent) of an ASCII FBX file form
/// a cycle: Assimp 5.2's FBX converter follows them depth first without marks, and a model
/// connected to itself (from the scene fuzz target) overflowed the stack. Binary FBX stores
/// connections as records, which this does not read.
bool fbxConnectionsCycle(const std::string& bytes)
{
  std::map<int64_t, std::vector<int64_t>> children;
  for (size_t at = bytes.find("\"OO\","); at != std::string::npos;
       at = bytes.find("\"OO\",", at + 5))
  {
    char* end = nullptr;
    const int64_t child = std::strtoll(bytes.c_str() + at + 5, &end, 10);
    if (end && *end == ',')
    {
      children[std::strtoll(end + 1, nullptr, 10)].push_back(child);
    }
  }
  // Depth-first, iterative, with marks: 1 on the current path, 2 done.
  std::map<int64_t, int> mark;
  for (const auto& [start, unused] : children)
  {
    std::vector<std::pair<int64_t, size_t>> path{ { start, 0 } };
    while (!path.empty() && mark[start] != 2)
    {
      auto& [node, next] = path.back();
      mark[node] = 1;
      const auto it = children.find(node);
      if (it == children.end() || next == it->second.size())
      {
        mark[node] = 2;
        path.pop_back();
        continue;
      }
      const int64_t child = it->second[next++];
      if (mark[child] == 1)
      {
        return true;
      }
      if (mark[child] == 0)
      {
        path.emplace_back(child, 0);
      }
    }
  }
  return false;
}

/// The little-endian 32-bit word at `at` of `bytes` (MD2 and binary glTF are little-endian).
uint32_t word(const std::string& bytes, size_t at)
{
  uint32_t value = 0;
  for (int k = 3; k >= 0; --k)
  {
    value = value << 8 | static_cast<unsigned char>(bytes[at + static_cast<size_t>(k)]);
  }
  return value;
}

/// Refuses, by signature (Assimp also tries a file's content on importers of other extensions),
/// the damaged files Assimp 5.2 mishandles before it can refuse them:
/// - an MD2 model whose skin names run past the file's end (the importer takes each 64-byte
///   name with strlen and overran its buffer) or whose triangles have no vertices to index
///   (found by the scene fuzz target under AddressSanitizer);
/// - a binary glTF whose header or chunks declare more bytes than the file has: the importer
///   allocates what they declare (2 GB for a 672-byte file the fuzz target made);
/// - an ASCII FBX whose connections form a cycle (fbxConnectionsCycle).
void checkSignatures(const std::string& path)
{
  std::ifstream in(path, std::ios::binary);
  const std::string bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  const auto refuse = [&path](const std::string& what)
  { throw InputError("cannot read '" + path + "': " + what + " (a damaged file?)"); };
  if (bytes.size() >= 68 && bytes.compare(0, 4, "IDP2") == 0)
  {
    // The first frame's vertices (those the importer reads) must exist and lie in the file:
    // it clamps a triangle's vertex index to the vertex count less one, which for no vertex
    // read far outside the file.
    const uint64_t vertices = word(bytes, 24), frameSize = word(bytes, 16);
    if (word(bytes, 32) > 0 &&
      (vertices == 0 || frameSize < 40 + 4 * vertices || word(bytes, 40) == 0 ||
        uint64_t(word(bytes, 56)) + frameSize > bytes.size()))
    {
      refuse("its MD2 header declares triangles without a first frame of vertices in the file");
    }
    const uint64_t skins = word(bytes, 20), offset = word(bytes, 44);
    for (uint64_t k = 0; k < skins; ++k)
    {
      const uint64_t at = offset + 64 * k;
      if (at + 64 > bytes.size() || std::memchr(bytes.data() + at, 0, 64) == nullptr)
      {
        refuse("its MD2 skin name " + std::to_string(k) + " is outside the file or has no end");
      }
    }
  }
  if (bytes.compare(0, 18, "Kaydara FBX Binary") != 0 && fbxConnectionsCycle(bytes))
  {
    refuse("its FBX connections form a cycle (an object is its own ancestor)");
  }
  if (bytes.size() >= 12 && bytes.compare(0, 4, "glTF") == 0)
  {
    // Version 1: the scene's length at byte 12; version 2: chunks of length, type, data.
    const uint64_t declared = word(bytes, 4) == 1
      ? (bytes.size() >= 20 ? 20 + uint64_t(word(bytes, 12)) : bytes.size() + 1)
      : 12;
    uint64_t at = declared;
    for (int chunk = 0; word(bytes, 4) != 1 && chunk < 2 && at + 8 <= bytes.size(); ++chunk)
    {
      at += 8 + uint64_t(word(bytes, at));
    }
    if (at > bytes.size())
    {
      refuse("its binary glTF header declares more bytes than the file's " +
        std::to_string(bytes.size()));
    }
  }
}
} // namespace

const char* sceneExtensions()
{
  return kExtensions;
}

bool isSceneFile(const std::string& path)
{
  return hasOneOfExtensions(path, kExtensions);
}

Scene readScene(const std::string& path, const Progress& progress)
{
  if (!isSceneFile(path))
  {
    throw InputError("'" + path + "' is no scene file; the scene formats are: " + kExtensions);
  }
  if (!std::ifstream(path).good())
  {
    throw InputError("cannot open '" + path + "': the file does not exist or is not readable");
  }
  checkSignatures(path);
  Assimp::Importer importer;
  bool aborted = false;
  // The importer owns and deletes its progress handler.
  importer.SetProgressHandler(new ForwardProgress(progress, aborted));
  const aiScene* scene =
    importer.ReadFile(path, aiProcess_JoinIdenticalVertices | aiProcess_ValidateDataStructure);
  if (aborted)
  {
    throw Aborted();
  }
  if (!scene || !scene->mRootNode)
  {
    throw InputError("cannot read '" + path + "': " +
      (scene ? std::string("the scene has no nodes") : std::string(importer.GetErrorString())));
  }

  Scene out;
  const int index = importer.GetPropertyInteger("importerIndex", -1);
  if (const aiImporterDesc* desc = index >= 0 ? importer.GetImporterInfo(index) : nullptr)
  {
    out.importer = desc->mName;
  }
  std::set<std::string> bones;
  for (unsigned m = 0; m < scene->mNumMeshes; ++m)
  {
    const aiMesh& mesh = *scene->mMeshes[m];
    out.meshNames.emplace_back(mesh.mName.C_Str());
    out.skinnedMeshes += mesh.mNumBones > 0 ? 1 : 0;
    out.morphTargets += mesh.mNumAnimMeshes;
    for (unsigned b = 0; b < mesh.mNumBones; ++b)
    {
      bones.insert(mesh.mBones[b]->mName.C_Str());
    }
  }
  out.bones = static_cast<int64_t>(bones.size());
  Gathering more{ {}, SceneSkinBuilder(*scene) };
  addNode(*scene, *scene->mRootNode, aiMatrix4x4(), out, more);
  if (out.soup.numPolygons() == 0)
  {
    throw InputError("'" + path + "' has no polygons (" + std::to_string(scene->mNumMeshes) +
      " meshes, " + std::to_string(out.skippedPrimitives) + " points and lines)");
  }
  keepCompleteAttributes(out, more.gaps);
  out.skeleton = more.skin.skeleton();
  out.animations = more.skin.animations(*scene, out.warnings);
  out.unweightedPoints = more.skin.unweightedPoints();
  addSkinWarnings(out);
  out.texture = sceneBaseColorTexture(*scene, path, out.warnings);
  return out;
}
} // namespace tc
