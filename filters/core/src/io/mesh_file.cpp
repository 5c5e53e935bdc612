// SPDX-License-Identifier: BSD-3-Clause
#include "tc/io/mesh_file.h"

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <iterator>

namespace tc
{
BaseColorTexture readTextureFile(
  const std::string& meshPath, const std::string& name, std::vector<std::string>& warnings)
{
  namespace fs = std::filesystem;
  BaseColorTexture texture;
  texture.name = name;
  // Windows exporters write "textures\\skin.png"; the folder separator is all that differs.
  std::string relative = name;
  std::replace(relative.begin(), relative.end(), '\\', '/');
  const fs::path file(relative);
  texture.path =
    (file.is_absolute() ? file : fs::path(meshPath).parent_path() / file).lexically_normal();
  std::error_code ec;
  std::ifstream in(texture.path, std::ios::binary);
  if (!fs::is_regular_file(texture.path, ec) || !in.good())
  {
    warnings.push_back("texture '" + name + "' not found at '" + texture.path +
      "'; the mesh is read without a texture");
    return texture;
  }
  texture.encoded.assign(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
  if (texture.encoded.empty())
  {
    warnings.push_back(
      "texture '" + name + "' ('" + texture.path + "') is empty; the mesh is read without it");
  }
  return texture;
}
} // namespace tc
