// SPDX-License-Identifier: BSD-3-Clause
/// @file input_files.h
/// The inputs a fuzz target replays, named as libFuzzer takes them: files, and folders of them.
#pragma once

#include <algorithm>
#include <filesystem>
#include <string>
#include <vector>

namespace tcfuzz
{
/// The files named: a file itself, a folder's regular files in name order.
inline std::vector<std::filesystem::path> inputFiles(const std::vector<std::string>& paths)
{
  namespace fs = std::filesystem;
  std::vector<fs::path> files;
  for (const std::string& path : paths)
  {
    if (!fs::is_directory(path))
    {
      files.emplace_back(path);
      continue;
    }
    std::vector<fs::path> inFolder;
    for (const fs::directory_entry& entry : fs::directory_iterator(path))
    {
      if (entry.is_regular_file())
      {
        inFolder.push_back(entry.path());
      }
    }
    std::sort(inFolder.begin(), inFolder.end());
    files.insert(files.end(), inFolder.begin(), inFolder.end());
  }
  return files;
}
} // namespace tcfuzz
