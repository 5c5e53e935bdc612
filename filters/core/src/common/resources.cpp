// SPDX-License-Identifier: BSD-3-Clause
#include "tc/common/resources.h"

#include "tc/common/errors.h"

#include <tbb/global_control.h>

#include <fstream>
#include <mutex>
#include <sstream>
#include <string>

namespace tc
{
namespace
{
std::mutex controlMutex;
// Never destroyed at exit: TBB may already be torn down when static destructors run, and the
// cap no longer matters then.
tbb::global_control* control = nullptr;
} // namespace

void setMaxThreads(int n)
{
  if (n < 0 || n > 4096)
  {
    throw InputError(
      "setMaxThreads: " + std::to_string(n) + " threads; give 1 .. 4096, or 0 for one per core");
  }
  const std::lock_guard<std::mutex> lock(controlMutex);
  // The old control must go first: while two are alive, TBB applies the smaller value.
  delete control;
  control = nullptr;
  if (n > 0)
  {
    control =
      new tbb::global_control(tbb::global_control::max_allowed_parallelism, static_cast<size_t>(n));
  }
}

int maxThreads()
{
  return static_cast<int>(
    tbb::global_control::active_value(tbb::global_control::max_allowed_parallelism));
}

int64_t availableMemory()
{
  std::ifstream meminfo("/proc/meminfo");
  std::string line;
  while (std::getline(meminfo, line))
  {
    std::istringstream words(line);
    std::string key;
    long long kibibytes = 0;
    if (words >> key >> kibibytes && key == "MemAvailable:")
    {
      return static_cast<int64_t>(kibibytes) * 1024;
    }
  }
  return 0;
}
} // namespace tc
