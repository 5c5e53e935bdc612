// SPDX-License-Identifier: BSD-3-Clause
/// @file resources.h
/// The machine's resources the core uses: the threads of its parallel loops (tc/common/parallel.h)
/// and the memory available to a computation.
#pragma once

#include <cstdint>

namespace tc
{
/// Caps the threads of every parallel loop of the process (TBB's max_allowed_parallelism, which
/// also holds for TBB's other users in the process) at `n` until the next call; 0 lifts the cap
/// (TBB's default: one thread per core). The results of the stages do not depend on it: every
/// loop writes per-index results and reduces in index order.
/// @param[in] n  threads, 0 .. 4096
/// @throws InputError for a negative or larger n
void setMaxThreads(int n);

/// The threads a parallel loop may use now: the cap of setMaxThreads, else TBB's default.
int maxThreads();

/// The memory the system can give a new computation without swapping, in bytes: MemAvailable
/// of /proc/meminfo (Linux's estimate, page cache that can be dropped included); 0 when the
/// system does not say.
int64_t availableMemory();
} // namespace tc
