// SPDX-License-Identifier: BSD-3-Clause
// Fuzz target: tc::readOFF on any bytes, as an .off file.
#include "fuzz_support.h"
#include "tc/io/off_io.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size)
{
  static const tcfuzz::InputFile file(".off");
  tcfuzz::readSoup(file, data, size, tc::readOFF, 1);
  return 0;
}
