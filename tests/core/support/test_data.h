// SPDX-License-Identifier: BSD-3-Clause
/// @file test_data.h
/// Where core tests find meshes: small ones in testing-data/, larger ones in ../shared/data/
/// (tests that need the latter call GTEST_SKIP when it is absent).
#pragma once

#include <fstream>
#include <string>

namespace tctest
{
inline std::string testingData(const std::string& relative)
{
  return std::string(TC_TESTING_DATA_DIR) + "/" + relative;
}

/// Path of a file under ../shared/data, or "" when it is not there.
inline std::string sharedData(const std::string& relative)
{
  const std::string path = std::string(TC_SHARED_DATA_DIR) + "/" + relative;
  return std::ifstream(path).good() ? path : std::string();
}
} // namespace tctest
