// SPDX-License-Identifier: BSD-3-Clause
/// @file test_progress.h
/// The progress-and-abort check every core stage's tests share.
#pragma once

#include "tc/common/errors.h"
#include "tc/common/progress.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cstddef>
#include <functional>
#include <vector>

namespace tctest
{
/// Runs `stage(progress)` twice. First with a progress that records every report: there must
/// be at least `minReports`, rising from >= 0 and ending at exactly 1.0. Then with `stop` as the
/// callback, which asks to abort: the run must end with tc::Aborted.
inline void expectProgressAndAbort(const std::function<void(const tc::Progress&)>& stage,
  size_t minReports, const tc::Progress::Callback& stop)
{
  std::vector<double> seen;
  stage(tc::Progress(
    [&seen](double f)
    {
      seen.push_back(f);
      return true;
    }));
  ASSERT_GE(seen.size(), std::max<size_t>(minReports, 1));
  EXPECT_TRUE(std::is_sorted(seen.begin(), seen.end()));
  EXPECT_GE(seen.front(), 0.0);
  EXPECT_EQ(seen.back(), 1.0);
  EXPECT_THROW(stage(tc::Progress(stop)), tc::Aborted);
}
} // namespace tctest
