// SPDX-License-Identifier: BSD-3-Clause
#include "tc/io/png_check.h"

#include <zlib.h>

#include <cstdint>
#include <cstring>
#include <vector>

namespace tc
{
namespace
{
/// Texels a texture may have: 16384 x 16384.
constexpr uint64_t kMaxTexels = uint64_t(1) << 28;

uint32_t bigEndian(const std::string& bytes, size_t at)
{
  const auto b = [&](size_t k)
  { return static_cast<uint32_t>(static_cast<uint8_t>(bytes[at + k])); };
  return b(0) << 24 | b(1) << 16 | b(2) << 8 | b(3);
}

/// The fields of an IHDR chunk that fix the layout of the image data.
struct PngLayout
{
  uint32_t width = 0;
  uint32_t height = 0;
  int depth = 0;
  int colorType = 0;
  bool interlaced = false;
};

/// What is wrong with the 13 bytes of an IHDR, or "".
std::string checkIhdr(const std::string& bytes, size_t at, PngLayout& layout)
{
  layout.width = bigEndian(bytes, at);
  layout.height = bigEndian(bytes, at + 4);
  layout.depth = static_cast<uint8_t>(bytes[at + 8]);
  layout.colorType = static_cast<uint8_t>(bytes[at + 9]);
  const int interlace = static_cast<uint8_t>(bytes[at + 12]);
  layout.interlaced = interlace == 1;
  if (layout.width == 0 || layout.height == 0 ||
    uint64_t(layout.width) * layout.height > kMaxTexels)
  {
    return "its size " + std::to_string(layout.width) + " x " + std::to_string(layout.height) +
      " is empty or more than 2^28 texels";
  }
  const int d = layout.depth;
  const bool depthOk = layout.colorType == 0 ? (d == 1 || d == 2 || d == 4 || d == 8 || d == 16)
    : layout.colorType == 3                  ? (d == 1 || d == 2 || d == 4 || d == 8)
    : (layout.colorType == 2 || layout.colorType == 4 || layout.colorType == 6)
    ? (d == 8 || d == 16)
    : false;
  if (!depthOk || bytes[at + 10] != 0 || bytes[at + 11] != 0 || interlace > 1)
  {
    return "its header has an invalid bit depth, colour type, compression, filter or interlace";
  }
  return "";
}

/// Bytes per row (without the filter byte) of `width` pixels, and the rows of each Adam7 pass
/// (one pass when not interlaced); passes of no pixel have no rows.
std::vector<std::pair<uint64_t, uint64_t>> passRows(const PngLayout& layout)
{
  static const int channels[7] = { 1, 0, 3, 1, 2, 0, 4 };
  const uint64_t bits = uint64_t(channels[layout.colorType]) * layout.depth;
  const auto rowBytes = [bits](uint64_t width) { return (width * bits + 7) / 8; };
  if (!layout.interlaced)
  {
    return { { rowBytes(layout.width), layout.height } };
  }
  static const int x0[7] = { 0, 4, 0, 2, 0, 1, 0 }, dx[7] = { 8, 8, 4, 4, 2, 2, 1 };
  static const int y0[7] = { 0, 0, 4, 0, 2, 0, 1 }, dy[7] = { 8, 8, 8, 4, 4, 2, 2 };
  std::vector<std::pair<uint64_t, uint64_t>> passes;
  for (int p = 0; p < 7; ++p)
  {
    const uint64_t w =
      layout.width > uint32_t(x0[p]) ? (layout.width - x0[p] + dx[p] - 1) / dx[p] : 0;
    const uint64_t h =
      layout.height > uint32_t(y0[p]) ? (layout.height - y0[p] + dy[p] - 1) / dy[p] : 0;
    if (w > 0 && h > 0)
    {
      passes.emplace_back(rowBytes(w), h);
    }
  }
  return passes;
}

/// Inflates the concatenated IDAT data and checks that it is exactly the filtered rows of
/// `layout`, each with a filter type 0..4; "" or what is wrong.
std::string checkImageData(const std::string& data, const PngLayout& layout)
{
  // The offsets in the inflated stream where rows start, walked as the stream goes.
  const std::vector<std::pair<uint64_t, uint64_t>> passes = passRows(layout);
  size_t pass = 0;
  uint64_t row = 0, nextRowAt = 0, total = 0;
  for (const auto& [bytes, rows] : passes)
  {
    total += (bytes + 1) * rows;
  }
  z_stream z;
  std::memset(&z, 0, sizeof(z));
  if (inflateInit(&z) != Z_OK)
  {
    return "zlib could not start";
  }
  z.next_in = reinterpret_cast<Bytef*>(const_cast<char*>(data.data()));
  z.avail_in = static_cast<uInt>(data.size());
  std::vector<unsigned char> buffer(1 << 16);
  uint64_t at = 0;
  int code = Z_OK;
  std::string problem;
  while (code == Z_OK && problem.empty())
  {
    z.next_out = buffer.data();
    z.avail_out = static_cast<uInt>(buffer.size());
    code = inflate(&z, Z_NO_FLUSH);
    const uint64_t produced = buffer.size() - z.avail_out;
    for (; problem.empty() && nextRowAt < at + produced && pass < passes.size();)
    {
      if (buffer[nextRowAt - at] > 4)
      {
        problem = "a row has the filter type " + std::to_string(buffer[nextRowAt - at]);
      }
      nextRowAt += passes[pass].first + 1;
      if (++row == passes[pass].second)
      {
        row = 0, ++pass;
      }
    }
    at += produced;
    if (at > total)
    {
      problem = "its image data inflate to more bytes than the image has";
    }
    if (code == Z_BUF_ERROR && z.avail_in == 0)
    {
      problem = "its image data end early";
    }
  }
  inflateEnd(&z);
  if (problem.empty() && code != Z_STREAM_END)
  {
    problem = "its image data do not inflate (" + std::string(z.msg ? z.msg : "zlib error") + ")";
  }
  if (problem.empty() && at != total)
  {
    problem = "its image data inflate to " + std::to_string(at) + " bytes, and the image has " +
      std::to_string(total);
  }
  return problem;
}
} // namespace

std::string pngDamage(const std::string& bytes)
{
  if (bytes.size() < 8 || bytes.compare(0, 8, "\x89PNG\r\n\x1a\n", 8) != 0)
  {
    return "it has no PNG signature";
  }
  PngLayout layout;
  std::string data;
  bool header = false, palette = false, end = false;
  int idatRun = 0; // 0 before the IDAT chunks, 1 in them, 2 after them
  for (size_t at = 8; !end;)
  {
    if (at + 12 > bytes.size())
    {
      return "it ends before its IEND chunk";
    }
    const uint32_t length = bigEndian(bytes, at);
    const std::string type = bytes.substr(at + 4, 4);
    if (length > bytes.size() - at - 12)
    {
      return "its " + type + " chunk runs past the end of the file";
    }
    for (const char c : type)
    {
      if (!((c >= 'A' && c <= 'Z') || (c >= 'a' && c <= 'z')))
      {
        return "it has a chunk whose type is no 4 letters";
      }
    }
    const uLong crc = crc32(0L, reinterpret_cast<const Bytef*>(bytes.data() + at + 4), length + 4);
    if (crc != bigEndian(bytes, at + 8 + length))
    {
      return "its " + type + " chunk fails its CRC";
    }
    const bool critical = type[0] >= 'A' && type[0] <= 'Z';
    if ((type == "IHDR") != !header || (type == "IHDR" && length != 13))
    {
      return "its first chunk is no 13-byte IHDR, or it has another";
    }
    if (type == "IHDR")
    {
      const std::string problem = checkIhdr(bytes, at + 8, layout);
      if (!problem.empty())
      {
        return problem;
      }
      header = true;
    }
    else if (type == "PLTE")
    {
      palette = length % 3 == 0 && length > 0 && length <= 768 && idatRun == 0;
      if (!palette)
      {
        return "its PLTE chunk is invalid or after the image data";
      }
    }
    else if (type == "IDAT")
    {
      if (idatRun == 2)
      {
        return "its IDAT chunks are not consecutive";
      }
      idatRun = 1;
      data.append(bytes, at + 8, length);
    }
    else if (type == "IEND")
    {
      end = true;
    }
    else if (critical)
    {
      return "it has the unknown critical chunk " + type;
    }
    idatRun = idatRun == 1 && type != "IDAT" ? 2 : idatRun;
    at += 12 + size_t(length);
  }
  if (idatRun == 0 || (layout.colorType == 3 && !palette))
  {
    return idatRun == 0 ? "it has no image data" : "its palette image has no PLTE chunk";
  }
  return checkImageData(data, layout);
}
} // namespace tc
