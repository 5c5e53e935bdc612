// SPDX-License-Identifier: BSD-3-Clause
// Fuzz target: tc::readPLY on any bytes, as a .ply file (ASCII and both binary byte orders:
// the seeds hold all three, and a mutated format line switches between them).
#include "fuzz_support.h"
#include "tc/io/soup_io.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size)
{
  static const tcfuzz::InputFile file(".ply");
  tcfuzz::readSoup(file, data, size, tc::readPLY);
  return 0;
}
