// SPDX-License-Identifier: BSD-3-Clause
#include "io/scene_textures.h"

#include <assimp/material.h>
#include <assimp/scene.h>
#include <assimp/texture.h>

#include <algorithm>

namespace tc
{
namespace
{
/// Texels an embedded raw image may have: 16384 x 16384. A damaged file's size is refused
/// rather than allocated.
constexpr uint64_t kMaxTexels = uint64_t(1) << 28;

/// The texture names of the scene's materials, in mesh order, each once: base colour first (glTF's
/// baseColorTexture), else diffuse (what older formats call it).
std::vector<std::string> textureNames(const aiScene& scene)
{
  std::vector<std::string> names;
  for (unsigned m = 0; m < scene.mNumMeshes; ++m)
  {
    const unsigned index = scene.mMeshes[m]->mMaterialIndex;
    if (index >= scene.mNumMaterials || !scene.mMaterials[index])
    {
      continue;
    }
    const aiMaterial& material = *scene.mMaterials[index];
    aiString name;
    if (material.GetTexture(aiTextureType_BASE_COLOR, 0, &name) != AI_SUCCESS &&
      material.GetTexture(aiTextureType_DIFFUSE, 0, &name) != AI_SUCCESS)
    {
      continue;
    }
    const std::string text = name.C_Str();
    if (!text.empty() && std::find(names.begin(), names.end(), text) == names.end())
    {
      names.push_back(text);
    }
  }
  return names;
}

/// An embedded image: its encoded bytes, or raw BGRA texels (top row first, as images are
/// stored) as RGBA with row 0 at the bottom.
BaseColorTexture embeddedTexture(
  const aiTexture& image, int index, std::vector<std::string>& warnings)
{
  BaseColorTexture texture;
  texture.name = "embedded:" + std::to_string(index);
  if (!image.pcData || image.mWidth == 0)
  {
    warnings.push_back("the embedded texture " + std::to_string(index) + " is empty");
    return texture;
  }
  if (image.mHeight == 0) // compressed: mWidth bytes of a PNG, JPEG, ... file
  {
    texture.encoded.assign(reinterpret_cast<const char*>(image.pcData), image.mWidth);
    return texture;
  }
  if (uint64_t(image.mWidth) * image.mHeight > kMaxTexels)
  {
    warnings.push_back("the embedded texture " + std::to_string(index) + " declares " +
      std::to_string(image.mWidth) + " x " + std::to_string(image.mHeight) +
      " texels, more than TriChart reads; the mesh is read without it");
    return texture;
  }
  texture.width = static_cast<int>(image.mWidth);
  texture.height = static_cast<int>(image.mHeight);
  texture.rgba.resize(4 * size_t(image.mWidth) * image.mHeight);
  for (unsigned y = 0; y < image.mHeight; ++y)
  {
    const aiTexel* row = image.pcData + size_t(image.mHeight - 1 - y) * image.mWidth;
    uint8_t* out = texture.rgba.data() + 4 * size_t(y) * image.mWidth;
    for (unsigned x = 0; x < image.mWidth; ++x, out += 4)
    {
      out[0] = row[x].r, out[1] = row[x].g, out[2] = row[x].b, out[3] = row[x].a;
    }
  }
  return texture;
}
} // namespace

BaseColorTexture sceneBaseColorTexture(
  const aiScene& scene, const std::string& path, std::vector<std::string>& warnings)
{
  const std::vector<std::string> names = textureNames(scene);
  if (names.empty())
  {
    return {};
  }
  const std::string& name = names.front();
  const auto [image, index] = scene.GetEmbeddedTextureAndIndex(name.c_str());
  BaseColorTexture texture;
  if (image)
  {
    texture = embeddedTexture(*image, index, warnings);
  }
  else if (name[0] == '*')
  {
    warnings.push_back("a material refers to the embedded texture '" + name +
      "', which the file does not have; the mesh is read without a texture");
    texture.name = name;
  }
  else
  {
    texture = readTextureFile(path, name, warnings);
  }
  texture.leftOut = static_cast<int64_t>(names.size()) - 1;
  return texture;
}
} // namespace tc
