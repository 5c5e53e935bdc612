// SPDX-License-Identifier: BSD-3-Clause
#include "tc/io/mesh_header.h"

#include "tc/common/file_names.h"

#include <zlib.h>

#include <cstdio>
#include <cstdlib>
#include <sstream>
#include <string>
#include <vector>

namespace tc
{
namespace
{
constexpr size_t kHeaderBytes = 64 * 1024;

bool endsWith(const std::string& s, const std::string& suffix)
{
  return s.size() >= suffix.size() &&
    s.compare(s.size() - suffix.size(), suffix.size(), suffix) == 0;
}

/// The first kHeaderBytes of `path`, inflated when it is gzip (zlib reads a plain file as is).
std::string headerBytes(const std::string& path)
{
  gzFile file = gzopen(path.c_str(), "rb");
  if (!file)
  {
    return {};
  }
  std::string text(kHeaderBytes, '\0');
  const int n = gzread(file, text.data(), static_cast<unsigned>(text.size()));
  gzclose(file);
  text.resize(n > 0 ? static_cast<size_t>(n) : 0);
  return text;
}

MeshFileCounts plyCounts(const std::string& path)
{
  std::istringstream header(headerBytes(path));
  std::string line;
  if (!std::getline(header, line) || line.rfind("ply", 0) != 0)
  {
    return {};
  }
  MeshFileCounts counts;
  while (std::getline(header, line) && line.rfind("end_header", 0) != 0)
  {
    std::istringstream words(line);
    std::string keyword, element;
    long long n = -1;
    if (words >> keyword >> element >> n && keyword == "element" && n >= 0)
    {
      if (element == "vertex")
      {
        counts.points = n;
      }
      else if (element == "face")
      {
        counts.triangles = n;
      }
    }
  }
  return counts;
}

MeshFileCounts offCounts(const std::string& path)
{
  std::istringstream text(headerBytes(path));
  std::vector<long long> numbers;
  std::string line;
  bool keyword = false;
  while (numbers.size() < 2 && std::getline(text, line))
  {
    std::istringstream words(line.substr(0, line.find('#')));
    std::string word;
    while (numbers.size() < 2 && words >> word)
    {
      if (!keyword && endsWith(word, "OFF"))
      {
        keyword = true;
        continue;
      }
      char* end = nullptr;
      const long long n = std::strtoll(word.c_str(), &end, 10);
      if (!keyword || *end != '\0' || n < 0)
      {
        return {};
      }
      numbers.push_back(n);
    }
  }
  return numbers.size() == 2 ? MeshFileCounts{ numbers[0], numbers[1] } : MeshFileCounts{};
}

MeshFileCounts stlCounts(const std::string& path)
{
  std::FILE* file = std::fopen(path.c_str(), "rb");
  if (!file)
  {
    return {};
  }
  unsigned char head[84] = {};
  const bool complete = std::fread(head, 1, sizeof(head), file) == sizeof(head);
  std::fseek(file, 0, SEEK_END);
  const long long size = std::ftell(file);
  std::fclose(file);
  const long long facets = static_cast<long long>(head[80]) |
    (static_cast<long long>(head[81]) << 8) | (static_cast<long long>(head[82]) << 16) |
    (static_cast<long long>(head[83]) << 24);
  if (!complete || size != 84 + 50 * facets)
  {
    return {};
  }
  return { facets / 2, facets };
}

MeshFileCounts objCounts(const std::string& path)
{
  std::FILE* file = std::fopen(path.c_str(), "rb");
  if (!file)
  {
    return {};
  }
  MeshFileCounts counts{ 0, 0 };
  std::vector<char> buffer(1 << 20);
  // The two characters that open the line being read ('\n' before the file's first line).
  char first = '\n', second = '\0';
  bool lineStart = true;
  size_t n = 0;
  while ((n = std::fread(buffer.data(), 1, buffer.size(), file)) > 0)
  {
    for (size_t i = 0; i < n; ++i)
    {
      const char c = buffer[i];
      if (lineStart)
      {
        first = c, second = '\0', lineStart = c == '\n';
        continue;
      }
      if (second == '\0')
      {
        second = c;
        const bool blank = c == ' ' || c == '\t';
        counts.points += first == 'v' && blank;
        counts.triangles += first == 'f' && blank;
      }
      lineStart = c == '\n';
    }
  }
  std::fclose(file);
  return counts;
}
} // namespace

MeshFileCounts readMeshFileCounts(const std::string& path)
{
  if (hasExtension(path, ".ply") || hasExtension(path, ".ply.gz"))
  {
    return plyCounts(path);
  }
  if (hasExtension(path, ".off"))
  {
    return offCounts(path);
  }
  if (hasExtension(path, ".stl"))
  {
    return stlCounts(path);
  }
  if (hasExtension(path, ".obj"))
  {
    return objCounts(path);
  }
  return {};
}
} // namespace tc
