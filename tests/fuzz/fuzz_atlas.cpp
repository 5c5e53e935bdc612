// SPDX-License-Identifier: BSD-3-Clause
// Fuzz target: tc::isAtlasFile and tc::readAtlas (OpenEXR, zlib-compressed JSON) on any bytes,
// as an .exr file. What readAtlas returns must pass tc::validateAtlas, as it promises.
#include "fuzz_support.h"
#include "tc/gim/atlas.h"
#include "tc/io/atlas_io.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size)
{
  static const tcfuzz::InputFile file(".exr");
  const std::string& path = file.write(data, size);
  tc::isAtlasFile(path); // never throws
  try
  {
    const tc::Atlas atlas = tc::readAtlas(path);
    try
    {
      tc::validateAtlas(atlas);
    }
    catch (const tc::InputError& error)
    {
      tcfuzz::InputFile::fail(std::string("readAtlas returned an invalid atlas: ") + error.what());
    }
  }
  catch (const tc::InputError& error)
  {
    tcfuzz::checkRefusal(error, path, true);
  }
  return 0;
}
