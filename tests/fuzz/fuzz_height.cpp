// SPDX-License-Identifier: BSD-3-Clause
// Fuzz target: tc::readHeightField (GDAL) and tc::triangulateHeightField on any bytes. GDAL
// picks its driver by the bytes, but some drivers also want the extension, so the input is
// written with the one its first bytes suggest (ESRI ASCII grid, PGM, BMP, PNG, TIFF).
#include "fuzz_support.h"
#include "tc/io/height_field_io.h"

#include <cmath>
#include <cstring>

namespace
{
bool startsWith(const uint8_t* data, size_t size, const char* magic)
{
  const size_t n = std::strlen(magic);
  return size >= n && std::memcmp(data, magic, n) == 0;
}

const tcfuzz::InputFile& fileFor(const uint8_t* data, size_t size)
{
  static const tcfuzz::InputFile asc(".asc"), pgm(".pgm"), bmp(".bmp"), png(".png"), tif(".tif");
  if (startsWith(data, size, "P2") || startsWith(data, size, "P5"))
  {
    return pgm;
  }
  if (startsWith(data, size, "BM"))
  {
    return bmp;
  }
  if (startsWith(data, size, "\x89PNG"))
  {
    return png;
  }
  return startsWith(data, size, "II*") || startsWith(data, size, "MM") ? tif : asc;
}

/// What the triangulation promises: ids in range, one height per point, finite positions.
void checkMesh(const tc::HeightFieldMesh& grid)
{
  const int64_t n = grid.mesh.numPoints();
  if (grid.heights.size() != static_cast<size_t>(n) || grid.mesh.triangles.empty())
  {
    tcfuzz::InputFile::fail("a height-field mesh whose heights and points differ in number");
  }
  for (const int32_t id : grid.mesh.triangles)
  {
    if (id < 0 || id >= n)
    {
      tcfuzz::InputFile::fail(
        "a triangle corner " + std::to_string(id) + " of " + std::to_string(n));
    }
  }
}
} // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size)
{
  const tcfuzz::InputFile& file = fileFor(data, size);
  const std::string& path = file.write(data, size);
  try
  {
    const tc::HeightField field = tc::readHeightField(path);
    if (field.heights.size() != static_cast<size_t>(field.columns * field.rows))
    {
      tcfuzz::InputFile::fail("a height field whose heights and cells differ in number");
    }
    checkMesh(tc::triangulateHeightField(field));
  }
  catch (const tc::InputError& error)
  {
    tcfuzz::checkRefusal(error, path, false);
  }
  return 0;
}
