// SPDX-License-Identifier: BSD-3-Clause
#include "tc/common/file_names.h"

#include <cctype>
#include <sstream>

namespace tc
{
bool hasExtension(const std::string& path, const std::string& extension)
{
  if (path.size() < extension.size())
  {
    return false;
  }
  const size_t start = path.size() - extension.size();
  for (size_t i = 0; i < extension.size(); ++i)
  {
    if (std::tolower(static_cast<unsigned char>(path[start + i])) !=
      std::tolower(static_cast<unsigned char>(extension[i])))
    {
      return false;
    }
  }
  return true;
}

bool hasOneOfExtensions(const std::string& path, const char* extensions)
{
  std::istringstream list(extensions);
  std::string ext;
  while (list >> ext)
  {
    ext = "." + ext;
    if (path.size() > ext.size() && hasExtension(path, ext))
    {
      return true;
    }
  }
  return false;
}
} // namespace tc
