// SPDX-License-Identifier: BSD-3-Clause
/// @file fuzz_support.h
/// What the fuzz targets share: the readers take paths, so each input is written to one file
/// per process with the extension the reader dispatches on; and the checks that every input
/// read gives a soup whose polygons exist, or a refusal that says what is wrong.
#pragma once

#include "tc/common/errors.h"
#include "tc/common/mesh.h"

#include <unistd.h>

#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <string>

namespace tcfuzz
{
/// One file per process (the process id in its name, so that libFuzzer's -jobs and -fork
/// workers do not share it), in /dev/shm where there is one: each input is a file write, and
/// there it costs a memory copy. Removed when the process ends normally.
class InputFile
{
public:
  explicit InputFile(const std::string& extension)
  {
    const std::filesystem::path folder = std::filesystem::is_directory("/dev/shm")
      ? std::filesystem::path("/dev/shm")
      : std::filesystem::temp_directory_path();
    Path = (folder / ("tc_fuzz_" + std::to_string(getpid()) + extension)).string();
  }
  ~InputFile() { std::remove(Path.c_str()); }
  InputFile(const InputFile&) = delete;
  InputFile& operator=(const InputFile&) = delete;

  /// Replaces the file's bytes with `size` bytes at `data`; returns its path.
  const std::string& write(const uint8_t* data, size_t size) const
  {
    std::ofstream out(Path, std::ios::binary | std::ios::trunc);
    out.write(reinterpret_cast<const char*>(data), static_cast<std::streamsize>(size));
    out.close();
    if (!out)
    {
      fail("cannot write the input to " + Path);
    }
    return Path;
  }

  const std::string& path() const { return Path; }

  /// Reports a broken contract and aborts, which libFuzzer (and the replay main) count as a
  /// crash, saving the input.
  [[noreturn]] static void fail(const std::string& what)
  {
    std::fprintf(stderr, "tc_fuzz: %s\n", what.c_str());
    std::abort();
  }

private:
  std::string Path;
};

/// A soup a reader returned must be what PolygonSoup promises: whole points, offsets rising
/// from 0 to the connectivity's size, `minCorners` or more corners per polygon, every corner a
/// point. readPLY, readOBJ and readScene promise 3 corners; readOFF passes on a face of 1 or 2
/// (tc::prepareMesh drops and reports it), so 1 for it.
inline void checkSoup(const tc::PolygonSoup& soup, int64_t minCorners = 3)
{
  if (soup.points.size() % 3 != 0 || soup.offsets.empty() || soup.offsets.front() != 0 ||
    soup.offsets.back() != static_cast<int64_t>(soup.connectivity.size()))
  {
    InputFile::fail("the soup's points or offsets are inconsistent");
  }
  for (int64_t p = 0; p < soup.numPolygons(); ++p)
  {
    if (soup.offsets[p + 1] - soup.offsets[p] < minCorners)
    {
      InputFile::fail("polygon " + std::to_string(p) + " has fewer than " +
        std::to_string(minCorners) + " corners");
    }
  }
  for (const int64_t id : soup.connectivity)
  {
    if (id < 0 || id >= soup.numPoints())
    {
      InputFile::fail("a corner refers to point " + std::to_string(id) + " of " +
        std::to_string(soup.numPoints()));
    }
  }
}

/// A refusal must say what is wrong; `path` must be named in it where the reader promises so.
inline void checkRefusal(const tc::InputError& error, const std::string& path, bool namesFile)
{
  const std::string message = error.what();
  if (message.empty() || (namesFile && message.find(path) == std::string::npos))
  {
    InputFile::fail("a refusal that does not name the file: '" + message + "'");
  }
}

/// Reads the input as the file `file` with `read` (a reader returning a PolygonSoup) and checks
/// the result (polygons of `minCorners` or more) or the refusal. Any other exception escapes:
/// libFuzzer reports it as a crash.
template <typename Read>
void readSoup(
  const InputFile& file, const uint8_t* data, size_t size, Read read, int64_t minCorners = 3)
{
  const std::string& path = file.write(data, size);
  try
  {
    checkSoup(read(path), minCorners);
  }
  catch (const tc::InputError& error)
  {
    checkRefusal(error, path, true);
  }
}
} // namespace tcfuzz
