// SPDX-License-Identifier: BSD-3-Clause
/// @file parallel.h
/// The one parallel loop of the core (TBB underneath). Work runs in blocks; between blocks the
/// calling thread reports progress and honours abort, so callbacks never run on worker threads.
#pragma once

#include "tc/common/progress.h"

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <cstdint>

namespace tc
{
/// Calls body(i) for every i in [0, n), in parallel. `body` must be safe to call concurrently
/// for different i. Progress is reported (and abort checked) about `steps` times.
template <typename Body>
void parallel_for(
  int64_t n, const Body& body, const Progress& progress = Progress(), int steps = 32)
{
  if (n <= 0)
  {
    progress.report(1.0);
    return;
  }
  const int64_t block = std::max<int64_t>(1, (n + steps - 1) / steps);
  for (int64_t start = 0; start < n; start += block)
  {
    const int64_t stop = std::min(n, start + block);
    tbb::parallel_for(tbb::blocked_range<int64_t>(start, stop),
      [&](const tbb::blocked_range<int64_t>& r)
      {
        for (int64_t i = r.begin(); i != r.end(); ++i)
        {
          body(i);
        }
      });
    progress.report(static_cast<double>(stop) / static_cast<double>(n));
  }
}
} // namespace tc
