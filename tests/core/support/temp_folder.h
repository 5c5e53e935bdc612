// SPDX-License-Identifier: BSD-3-Clause
/// @file temp_folder.h
/// For tests that write files: a GoogleTest fixture with a fresh, empty folder per test, and
/// damaged copies of a file's bytes for the readers' robustness tests.
#pragma once

#include <gtest/gtest.h>

#include <chrono>
#include <filesystem>
#include <fstream>
#include <random>
#include <string>
#include <vector>

namespace tctest
{
/// A fresh, empty folder per test (named after the suite and the test), removed afterwards.
class TempFolderTest : public ::testing::Test
{
protected:
  void SetUp() override
  {
    const auto* info = ::testing::UnitTest::GetInstance()->current_test_info();
    Folder = std::filesystem::temp_directory_path() /
      (std::string("tc_") + info->test_suite_name() + "_" + info->name() + "_" +
        std::to_string(std::chrono::steady_clock::now().time_since_epoch().count()));
    std::filesystem::create_directories(Folder);
  }
  void TearDown() override { std::filesystem::remove_all(Folder); }

  /// The path of `name` in the folder.
  std::string file(const std::string& name) const { return (Folder / name).string(); }

  /// Writes `bytes` to `name` in the folder; returns its path.
  std::string write(const std::string& name, const std::string& bytes) const
  {
    const std::string path = file(name);
    std::ofstream(path, std::ios::binary) << bytes;
    return path;
  }

  std::filesystem::path Folder;
};

/// Damaged copies of `bytes`: cut at 5, 30, 50, 77 and 99% of their length, and `flipped`
/// copies with 1, 4 or 32 bytes replaced at random (seeded: the same copies every run).
inline std::vector<std::string> damagedCopies(const std::string& bytes, unsigned seed, int flipped)
{
  std::vector<std::string> copies;
  for (const double fraction : { 0.05, 0.3, 0.5, 0.77, 0.99 })
  {
    copies.push_back(bytes.substr(0, static_cast<size_t>(fraction * bytes.size())));
  }
  std::mt19937 random(seed);
  for (int k = 0; k < flipped; ++k)
  {
    std::string copy = bytes;
    for (int i = 0; i < (k % 3 == 0 ? 1 : k % 3 == 1 ? 4 : 32); ++i)
    {
      copy[random() % copy.size()] = static_cast<char>(random() % 256);
    }
    copies.push_back(copy);
  }
  return copies;
}
} // namespace tctest
