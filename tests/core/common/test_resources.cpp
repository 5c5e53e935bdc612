// SPDX-License-Identifier: BSD-3-Clause
#include "tc/common/errors.h"
#include "tc/common/parallel.h"
#include "tc/common/resources.h"

#include <gtest/gtest.h>

#include <tbb/info.h>

#include <chrono>
#include <fstream>
#include <mutex>
#include <set>
#include <string>
#include <thread>

namespace
{
/// The distinct threads that run the bodies of a parallel loop long enough to spread.
size_t threadsOfALoop()
{
  std::mutex mutex;
  std::set<std::thread::id> ids;
  tc::parallel_for(
    256,
    [&](int64_t)
    {
      std::this_thread::sleep_for(std::chrono::milliseconds(1));
      const std::lock_guard<std::mutex> lock(mutex);
      ids.insert(std::this_thread::get_id());
    },
    {}, 4);
  return ids.size();
}

/// Lifts the cap at the end of each test, so that the other tests run on every core.
class ThreadCap : public ::testing::Test
{
protected:
  void TearDown() override { tc::setMaxThreads(0); }
};
} // namespace

TEST_F(ThreadCap, OneThreadRunsEveryLoopOnOneThread)
{
  tc::setMaxThreads(1);
  EXPECT_EQ(tc::maxThreads(), 1);
  EXPECT_EQ(threadsOfALoop(), 1u);
}

TEST_F(ThreadCap, TwoThreadsRunLoopsOnAtMostTwo)
{
  tc::setMaxThreads(2);
  EXPECT_EQ(tc::maxThreads(), 2);
  EXPECT_LE(threadsOfALoop(), 2u);
}

TEST_F(ThreadCap, ZeroLiftsTheCapAndALaterCapReplacesAnEarlierOne)
{
  tc::setMaxThreads(1);
  tc::setMaxThreads(3);
  EXPECT_EQ(tc::maxThreads(), 3); // not the smaller of the two: the first is gone
  tc::setMaxThreads(0);
  EXPECT_EQ(tc::maxThreads(), tbb::info::default_concurrency());
  if (tbb::info::default_concurrency() > 1)
  {
    EXPECT_GT(threadsOfALoop(), 1u);
  }
}

TEST_F(ThreadCap, CountsOutsideTheRangeAreRefusedAndChangeNothing)
{
  tc::setMaxThreads(2);
  EXPECT_THROW(tc::setMaxThreads(-1), tc::InputError);
  EXPECT_THROW(tc::setMaxThreads(4097), tc::InputError);
  EXPECT_EQ(tc::maxThreads(), 2);
}

TEST(AvailableMemory, IsWhatLinuxSaysAndBelowTheTotal)
{
  const int64_t available = tc::availableMemory();
  std::ifstream meminfo("/proc/meminfo");
  if (!meminfo)
  {
    EXPECT_EQ(available, 0);
    return;
  }
  std::string key;
  long long total = 0;
  meminfo >> key >> total; // MemTotal: first line
  ASSERT_EQ(key, "MemTotal:");
  EXPECT_GT(available, 0);
  EXPECT_LE(available, total * 1024);
}
