// SPDX-License-Identifier: BSD-3-Clause
#include "io/obj_materials.h"

#include <algorithm>
#include <cctype>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <utility>

namespace tc
{
namespace
{
/// A material of a library: its name and its map_Kd file name ("" when it has none).
using Material = std::pair<std::string, std::string>;

std::string lower(std::string s)
{
  std::transform(s.begin(), s.end(), s.begin(), [](unsigned char c) { return std::tolower(c); });
  return s;
}

/// The file name of a map statement's arguments: the words after the options (-o 0 0, -clamp on,
/// ...), joined by one space, as a name may hold spaces.
std::string mapFileName(std::istringstream& words)
{
  // Options and how many words follow them; -o, -s and -t take 1 to 3 numbers.
  static const std::pair<const char*, int> options[] = { { "-blendu", 1 }, { "-blendv", 1 },
    { "-boost", 1 }, { "-cc", 1 }, { "-clamp", 1 }, { "-bm", 1 }, { "-imfchan", 1 },
    { "-texres", 1 }, { "-type", 1 }, { "-mm", 2 }, { "-o", -3 }, { "-s", -3 }, { "-t", -3 } };
  std::vector<std::string> rest;
  for (std::string word; words >> word;)
  {
    rest.push_back(word);
  }
  size_t at = 0;
  while (at < rest.size())
  {
    const auto option = std::find_if(
      std::begin(options), std::end(options), [&](const auto& o) { return rest[at] == o.first; });
    if (option == std::end(options))
    {
      break;
    }
    ++at;
    const int n = std::abs(option->second);
    for (int k = 0; k < n && at < rest.size(); ++k, ++at)
    {
      char* end = nullptr;
      std::strtod(rest[at].c_str(), &end);
      if (option->second < 0 && *end != '\0')
      {
        break; // fewer than 3 numbers
      }
    }
  }
  std::string name;
  for (; at < rest.size(); ++at)
  {
    name += (name.empty() ? "" : " ") + rest[at];
  }
  return name;
}

/// The materials of one library, in file order; empty (and a warning) when it is missing.
std::vector<Material> readLibrary(
  const std::string& objPath, const std::string& name, std::vector<std::string>& warnings)
{
  std::string relative = name;
  std::replace(relative.begin(), relative.end(), '\\', '/');
  const std::filesystem::path file =
    std::filesystem::path(objPath).parent_path() / std::filesystem::path(relative);
  std::ifstream in(file);
  if (name.empty() || !in.good())
  {
    warnings.push_back("material library '" + name + "' not found at '" + file.string() +
      "'; the mesh is read without its materials");
    return {};
  }
  std::vector<Material> materials;
  for (std::string line; std::getline(in, line);)
  {
    std::istringstream words(line.substr(0, line.find('#')));
    std::string keyword;
    words >> keyword;
    if (keyword == "newmtl")
    {
      std::string material;
      std::getline(words >> std::ws, material);
      while (!material.empty() && std::isspace(static_cast<unsigned char>(material.back())))
      {
        material.pop_back();
      }
      materials.emplace_back(material, "");
    }
    else if (lower(keyword) == "map_kd" && !materials.empty() && materials.back().second.empty())
    {
      materials.back().second = mapFileName(words);
    }
  }
  return materials;
}
} // namespace

BaseColorTexture objBaseColorTexture(const std::string& objPath,
  const std::vector<std::string>& libraries, const std::vector<std::string>& used,
  std::vector<std::string>& warnings)
{
  std::vector<Material> all;
  for (const std::string& library : libraries)
  {
    const std::vector<Material> materials = readLibrary(objPath, library, warnings);
    all.insert(all.end(), materials.begin(), materials.end());
  }
  // The textures in the order that counts: of the materials faces use, else of all.
  std::vector<std::string> maps;
  const auto add = [&maps](const std::string& map)
  {
    if (!map.empty() && std::find(maps.begin(), maps.end(), map) == maps.end())
    {
      maps.push_back(map);
    }
  };
  for (const std::string& name : used)
  {
    const auto it =
      std::find_if(all.begin(), all.end(), [&name](const Material& m) { return m.first == name; });
    add(it == all.end() ? std::string() : it->second);
  }
  for (size_t m = 0; used.empty() && m < all.size(); ++m)
  {
    add(all[m].second);
  }
  if (maps.empty())
  {
    return {};
  }
  BaseColorTexture texture = readTextureFile(objPath, maps.front(), warnings);
  texture.leftOut = static_cast<int64_t>(maps.size()) - 1;
  return texture;
}
} // namespace tc
