// SPDX-License-Identifier: BSD-3-Clause
// Fuzz target: tc::readPLY on any bytes as a .ply.gz file, the way a damaged download reaches
// it: the gzip header, the deflate stream and its trailer are what the mutations hit (the PLY
// inside is the ply target's; its seeds compressed are this one's).
#include "fuzz_support.h"
#include "tc/io/soup_io.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size)
{
  static const tcfuzz::InputFile file(".ply.gz");
  tcfuzz::readSoup(file, data, size, tc::readPLY);
  return 0;
}
