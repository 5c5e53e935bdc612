// SPDX-License-Identifier: BSD-3-Clause
#include "io/md2_frames.h"

#include "tc/common/errors.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <fstream>
#include <iterator>
#include <unordered_map>
#include <vector>

namespace tc
{
namespace
{
// The layout of an MD2 file (id Software's Quake II format), all little-endian.
constexpr uint64_t kHeaderBytes = 17 * 4;
constexpr uint64_t kSkinBytes = 64;        // char name[64]
constexpr uint64_t kTexCoordBytes = 4;     // 16-bit s, t
constexpr uint64_t kTriangleBytes = 12;    // uint16 vertex[3], st[3]
constexpr uint64_t kFrameHeaderBytes = 40; // float scale[3], translate[3]; char name[16]
constexpr uint64_t kFrameVertexBytes = 4;  // uint8 x, y, z, normal index
constexpr uint64_t kFrameNameBytes = 16;
// The frames read here take 12 bytes per point where the file stores 4 per vertex, and a model
// has rarely more than 2 points (texture seams) per vertex: a header whose frames would take
// over this many times the file's size is a damaged one whose counts multiply into gigabytes.
constexpr uint64_t kMaxExpansion = 64;

/// The file's bytes, with reads that never pass its end.
struct Md2Bytes
{
  std::string path;
  std::string bytes;

  [[noreturn]] void fail(const std::string& what) const
  {
    throw InputError("cannot read '" + path + "' as MD2: " + what);
  }
  /// Whether `count` items of `size` bytes from byte `at` lie in the file (no overflow: every
  /// argument is below 2^32).
  bool holds(uint64_t at, uint64_t count, uint64_t size) const
  {
    return at <= bytes.size() && count * size <= bytes.size() - at;
  }
  /// The little-endian unsigned integer of `size` bytes at `at`.
  uint32_t word(uint64_t at, int size) const
  {
    if (!holds(at, 1, static_cast<uint64_t>(size)))
    {
      fail("a read at byte " + std::to_string(at) + " passes the file's end (a damaged file?)");
    }
    uint32_t value = 0;
    for (int k = size - 1; k >= 0; --k)
    {
      value = value << 8 | static_cast<unsigned char>(bytes[at + static_cast<uint64_t>(k)]);
    }
    return value;
  }
  uint32_t u32(uint64_t at) const { return word(at, 4); }
  uint16_t u16(uint64_t at) const { return static_cast<uint16_t>(word(at, 2)); }
  uint8_t u8(uint64_t at) const { return static_cast<uint8_t>(word(at, 1)); }
  float f32(uint64_t at) const
  {
    const uint32_t bits = u32(at);
    float value;
    std::memcpy(&value, &bits, sizeof value);
    return value;
  }
  /// The text of the char[size] at `at`, up to its first NUL.
  std::string name(uint64_t at, uint64_t size) const
  {
    if (!holds(at, 1, size))
    {
      fail("a name at byte " + std::to_string(at) + " passes the file's end (a damaged file?)");
    }
    const char* begin = bytes.data() + at;
    const void* nul = std::memchr(begin, 0, size);
    return std::string(begin, nul ? static_cast<const char*>(nul) : begin + size);
  }
};

/// The 17 words of the header, after "IDP2".
struct Md2Header
{
  uint32_t version, skinWidth, skinHeight, frameSize, skins, vertices, texCoords, triangles,
    glCommands, frames, ofsSkins, ofsTexCoords, ofsTriangles, ofsFrames, ofsGlCommands, ofsEnd;
};

Md2Bytes readBytes(const std::string& path)
{
  std::ifstream in(path, std::ios::binary);
  if (!in.good())
  {
    throw InputError("cannot open '" + path + "': the file does not exist or is not readable");
  }
  return { path,
    std::string((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>()) };
}

Md2Header readHeader(const Md2Bytes& file)
{
  if (file.bytes.size() < kHeaderBytes)
  {
    file.fail("the file has " + std::to_string(file.bytes.size()) + " bytes, fewer than the " +
      std::to_string(kHeaderBytes) + " of an MD2 header (a truncated file?)");
  }
  if (file.bytes.compare(0, 4, "IDP2") != 0)
  {
    file.fail("it does not start with the MD2 signature IDP2");
  }
  uint32_t words[16];
  for (uint64_t k = 0; k < 16; ++k)
  {
    words[k] = file.u32(4 + 4 * k);
  }
  return { words[0], words[1], words[2], words[3], words[4], words[5], words[6], words[7], words[8],
    words[9], words[10], words[11], words[12], words[13], words[14], words[15] };
}

/// Refuses a header that declares what the file does not hold; every later read stays in the
/// blocks checked here.
void checkHeader(const Md2Bytes& file, const Md2Header& h, std::vector<std::string>& warnings)
{
  const std::string size = std::to_string(file.bytes.size());
  if (h.version != 8)
  {
    warnings.push_back("the MD2 header gives version " + std::to_string(h.version) +
      ", not 8; the file is read as version 8");
  }
  if (h.frames == 0 || h.vertices == 0 || h.triangles == 0)
  {
    file.fail("its header declares " + std::to_string(h.frames) + " frames, " +
      std::to_string(h.vertices) + " vertices and " + std::to_string(h.triangles) +
      " triangles; a sequence needs at least one of each");
  }
  if (h.frameSize < kFrameHeaderBytes + kFrameVertexBytes * uint64_t(h.vertices))
  {
    file.fail("its frame size " + std::to_string(h.frameSize) + " is under the " +
      std::to_string(kFrameHeaderBytes + kFrameVertexBytes * uint64_t(h.vertices)) +
      " bytes that 40 + 4 x its " + std::to_string(h.vertices) +
      " vertices take (a damaged file?)");
  }
  if (h.ofsEnd > file.bytes.size())
  {
    file.fail("its header says the file ends at byte " + std::to_string(h.ofsEnd) +
      ", and it has " + size + " bytes (a truncated file?)");
  }
  const auto block = [&](const char* what, uint32_t at, uint32_t count, uint64_t bytes)
  {
    if (!file.holds(at, count, bytes))
    {
      file.fail("its " + std::to_string(count) + " " + what + " of " + std::to_string(bytes) +
        " bytes from byte " + std::to_string(at) + " pass the file's end at byte " + size +
        " (a damaged file?)");
    }
  };
  block("skins", h.ofsSkins, h.skins, kSkinBytes);
  block("texture coordinates", h.ofsTexCoords, h.texCoords, kTexCoordBytes);
  block("triangles", h.ofsTriangles, h.triangles, kTriangleBytes);
  block("frames", h.ofsFrames, h.frames, h.frameSize);
}

/// Per point of the sequence, the MD2 vertex and texture coordinate it stands for.
struct Md2Points
{
  std::vector<uint32_t> vertex;
  std::vector<uint32_t> texCoord; ///< 0 when the file has no texture coordinates
};

/// The triangles, as polygons of points, one point per distinct (vertex, texture coordinate)
/// pair in order of first use, as Assimp's per-corner vertices joined by identical position
/// and uv give. Each triangle's corners are reversed, as Assimp reverses them.
Md2Points readTriangles(const Md2Bytes& file, const Md2Header& h, PolygonSoup& soup)
{
  const uint64_t stCount = std::max<uint64_t>(h.texCoords, 1);
  std::unordered_map<uint64_t, int64_t> pointOf;
  pointOf.reserve(3 * uint64_t(h.triangles));
  Md2Points points;
  soup.connectivity.reserve(3 * uint64_t(h.triangles));
  soup.offsets.reserve(uint64_t(h.triangles) + 1);
  for (uint64_t t = 0; t < h.triangles; ++t)
  {
    int64_t ids[3];
    for (uint64_t c = 0; c < 3; ++c)
    {
      const uint64_t at = h.ofsTriangles + kTriangleBytes * t;
      const uint32_t v = file.u16(at + 2 * c), st = file.u16(at + 6 + 2 * c);
      if (v >= h.vertices)
      {
        file.fail("triangle " + std::to_string(t) + " refers to vertex " + std::to_string(v) +
          ", and the file has " + std::to_string(h.vertices) + " (a damaged file?)");
      }
      if (h.texCoords > 0 && st >= h.texCoords)
      {
        file.fail("triangle " + std::to_string(t) + " refers to texture coordinate " +
          std::to_string(st) + ", and the file has " + std::to_string(h.texCoords) +
          " (a damaged file?)");
      }
      const uint64_t key = v * stCount + (h.texCoords > 0 ? st : 0);
      const auto [it, added] = pointOf.emplace(key, static_cast<int64_t>(points.vertex.size()));
      if (added)
      {
        points.vertex.push_back(v);
        points.texCoord.push_back(h.texCoords > 0 ? st : 0);
      }
      ids[2 - c] = it->second;
    }
    soup.addPolygon(ids, 3);
  }
  return points;
}

/// Per point, u = s / skinwidth and v = 1 - t / skinheight, as Assimp gives them (a zero skin
/// size divides by 1, as there); empty when the file has no texture coordinates.
std::vector<float> readTexCoords(const Md2Bytes& file, const Md2Header& h, const Md2Points& points,
  std::vector<std::string>& warnings)
{
  std::vector<float> uv;
  if (h.texCoords == 0)
  {
    return uv;
  }
  if (h.skinWidth == 0 || h.skinHeight == 0)
  {
    warnings.push_back("the MD2 header gives a skin of " + std::to_string(h.skinWidth) + " x " +
      std::to_string(h.skinHeight) + " texels: texture coordinates are divided by 1 where 0");
  }
  // In float, as Assimp computes them, so that frame 0 matches tc::readScene bit for bit.
  const float width = h.skinWidth ? static_cast<float>(h.skinWidth) : 1.0f;
  const float height = h.skinHeight ? static_cast<float>(h.skinHeight) : 1.0f;
  uv.reserve(2 * points.texCoord.size());
  for (const uint32_t st : points.texCoord)
  {
    const uint64_t at = h.ofsTexCoords + kTexCoordBytes * uint64_t(st);
    // Unsigned, as Assimp 5.2 reads them (the Quake II sources declare short).
    uv.push_back(static_cast<float>(file.u16(at)) / width);
    uv.push_back(1.0f - static_cast<float>(file.u16(at + 2)) / height);
  }
  return uv;
}

/// The positions of frame `k`, and its name: byte * scale + translate, in float as Assimp
/// computes them, then turned to Assimp's axes (x, z, -y): the root transform of its MD2
/// importer, which rotates Quake's z-up to y-up.
std::vector<float> readFrame(
  const Md2Bytes& file, const Md2Header& h, uint64_t k, const Md2Points& points, std::string& name)
{
  const uint64_t at = h.ofsFrames + uint64_t(h.frameSize) * k;
  float scale[3], translate[3];
  for (uint64_t a = 0; a < 3; ++a)
  {
    scale[a] = file.f32(at + 4 * a);
    translate[a] = file.f32(at + 12 + 4 * a);
    if (!std::isfinite(scale[a]) || !std::isfinite(translate[a]))
    {
      file.fail("frame " + std::to_string(k) + " has a scale or translation that is not a " +
        "finite number (a damaged file?)");
    }
  }
  name = file.name(at + 24, kFrameNameBytes);
  std::vector<float> positions;
  positions.reserve(3 * points.vertex.size());
  for (const uint32_t v : points.vertex)
  {
    const uint64_t vertexAt = at + kFrameHeaderBytes + kFrameVertexBytes * uint64_t(v);
    float p[3];
    for (uint64_t a = 0; a < 3; ++a)
    {
      p[a] = static_cast<float>(file.u8(vertexAt + a)) * scale[a];
      p[a] += translate[a];
    }
    positions.insert(positions.end(), { p[0], p[2], -p[1] });
  }
  return positions;
}

/// The first skin, the file beside the model it names, when the model has texture coordinates
/// (Assimp's MD2 importer uses it only then).
BaseColorTexture readSkin(
  const Md2Bytes& file, const Md2Header& h, std::vector<std::string>& warnings)
{
  if (h.skins == 0 || h.texCoords == 0)
  {
    return {};
  }
  const std::string skin = file.name(h.ofsSkins, kSkinBytes);
  if (skin.size() == kSkinBytes)
  {
    file.fail("its first skin name has no end within its 64 bytes (a damaged file?)");
  }
  if (skin.empty())
  {
    warnings.push_back("the MD2 file's first skin has an empty name: it is read without a texture");
    return {};
  }
  return readTextureFile(file.path, skin, warnings);
}
} // namespace

DeformingSequence readMD2Sequence(const std::string& path, const Progress& progress)
{
  const Md2Bytes file = readBytes(path);
  const Md2Header header = readHeader(file);
  DeformingSequence out;
  out.source = "md2";
  checkHeader(file, header, out.warnings);
  const Md2Points points = readTriangles(file, header, out.soup);
  const uint64_t frameBytes = 3 * sizeof(float) * uint64_t(points.vertex.size());
  if (frameBytes * header.frames > kMaxExpansion * file.bytes.size())
  {
    file.fail(std::to_string(header.frames) + " frames of " + std::to_string(points.vertex.size()) +
      " points would take over " + std::to_string(kMaxExpansion) + " times the file's " +
      std::to_string(file.bytes.size()) + " bytes (a damaged header?)");
  }
  out.attributes.textureCoordinates = readTexCoords(file, header, points, out.warnings);
  out.texture = readSkin(file, header, out.warnings);
  out.frames.reserve(header.frames);
  for (uint64_t k = 0; k < header.frames; ++k)
  {
    progress.report(static_cast<double>(k) / header.frames);
    std::string name;
    out.frames.push_back(readFrame(file, header, k, points, name));
    out.frameNames.push_back(name);
    out.times.push_back(static_cast<double>(k));
  }
  out.soup.points.assign(out.frames.front().begin(), out.frames.front().end());
  progress.report(1.0);
  return out;
}
} // namespace tc
