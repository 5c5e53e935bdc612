// SPDX-License-Identifier: BSD-3-Clause
// Fuzz target: tc::readOBJ on any bytes, as an .obj file.
#include "fuzz_support.h"
#include "tc/io/soup_io.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size)
{
  static const tcfuzz::InputFile file(".obj");
  tcfuzz::readSoup(file, data, size, tc::readOBJ);
  return 0;
}
