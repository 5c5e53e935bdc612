// SPDX-License-Identifier: BSD-3-Clause
/// @file temp_folder.h
/// A GoogleTest fixture for tests that write files: a fresh, empty folder per test.
#pragma once

#include <gtest/gtest.h>

#include <chrono>
#include <filesystem>
#include <fstream>
#include <string>

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
} // namespace tctest
