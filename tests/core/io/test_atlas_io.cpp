// SPDX-License-Identifier: BSD-3-Clause
// The atlas file: writeAtlas then readAtlas is bit-exact, a failed write changes nothing, and
// every kind of damaged or foreign file is refused with a message that names it.
#include "tc/common/errors.h"
#include "tc/gim/atlas.h"
#include "tc/gim/geometry_images.h"
#include "tc/gim/path_tracing.h"
#include "tc/io/atlas_io.h"
#include "temp_folder.h"

#include "pipeline_fixture.h"
#include "test_progress.h"

#include <ImfChannelList.h>
#include <ImfFrameBuffer.h>
#include <ImfHeader.h>
#include <ImfInputPart.h>
#include <ImfIntAttribute.h>
#include <ImfMultiPartInputFile.h>
#include <ImfMultiPartOutputFile.h>
#include <ImfOutputPart.h>
#include <ImfPartType.h>
#include <ImfStringAttribute.h>
#include <gtest/gtest.h>
#include <half.h>
#include <nlohmann/json.hpp>
#include <sys/resource.h>
#include <zlib.h>

#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <functional>
#include <iostream>
#include <iterator>
#include <limits>
#include <map>
#include <string>
#include <vector>

namespace
{
namespace fs = std::filesystem;
using Json = nlohmann::ordered_json;

// ------------------------------------------------------------------------------------------
// A synthetic atlas over the 4 faces of a tetrahedron (each face counter-clockwise seen from
// outside, each edge used once in each direction), charts 0 + 1 and 2 + 3 packed in pairs.

const double kTetCorners[4][3] = { { 1, 1, 1 }, { 1, -1, -1 }, { -1, 1, -1 }, { -1, -1, 1 } };
const int kTetFaces[4][3] = { { 0, 1, 2 }, { 1, 0, 3 }, { 0, 2, 3 }, { 1, 3, 2 } };

uint64_t mix(uint64_t x)
{
  x += 0x9e3779b97f4a7c15ull;
  x = (x ^ (x >> 30)) * 0xbf58476d1ce4e5b9ull;
  x = (x ^ (x >> 27)) * 0x94d049bb133111ebull;
  return x ^ (x >> 31);
}

uint64_t hashOf(std::initializer_list<int64_t> values)
{
  uint64_t h = 0x1234567ull;
  for (int64_t v : values)
  {
    h = mix(h ^ static_cast<uint64_t>(v));
  }
  return h;
}

float floatFromBits(uint32_t bits)
{
  float f;
  std::memcpy(&f, &bits, sizeof f);
  return f;
}

uint32_t bitsOf(float f)
{
  uint32_t bits;
  std::memcpy(&bits, &f, sizeof bits);
  return bits;
}

/// A float for hash h: often one of the awkward ones (signed zeros, denormals, huge values and,
/// unless `finite`, NaNs with payloads and infinities), otherwise any finite bit pattern.
float awkwardFloat(uint64_t h, bool finite)
{
  const uint32_t sign = static_cast<uint32_t>(h >> 63) << 31;
  const uint32_t mantissa = static_cast<uint32_t>(h >> 20) & 0x7fffffu;
  switch (h % 16)
  {
    case 0:
      return -0.0f;
    case 1:
      return 0.0f;
    case 2:
      return floatFromBits(sign | mantissa | 1u); // denormal
    case 3:
      return floatFromBits(sign | (254u << 23) | mantissa); // up to FLT_MAX
    case 4:
      return floatFromBits(sign | 1u); // +-denorm_min
    case 5:
      if (!finite)
      {
        return floatFromBits(sign | 0x7f800000u | mantissa | 1u); // NaN, quiet or signalling
      }
      break;
    case 6:
      if (!finite)
      {
        return floatFromBits(sign | 0x7f800000u); // +-inf
      }
      break;
    default:
      break;
  }
  const uint32_t exponent = 1u + static_cast<uint32_t>((h >> 8) % 254u);
  return floatFromBits(sign | (exponent << 23) | mantissa);
}

/// Doubles that do not survive a careless text round trip.
double awkwardDouble(uint64_t h)
{
  switch (h % 10)
  {
    case 0:
      return -0.0;
    case 1:
      return std::numeric_limits<double>::denorm_min();
    case 2:
      return 0.1;
    case 3:
      return 1.0 / 3.0;
    case 4:
      return -std::numeric_limits<double>::max();
    case 5:
      return 4.9406564584124654e-322 * static_cast<double>(h % 1000 + 1); // denormal
    default:
    {
      const uint64_t bits = (h & 0x800fffffffffffffull) | ((1 + (h >> 12) % 2046) << 52);
      double d;
      std::memcpy(&d, &bits, sizeof d);
      return d;
    }
  }
}

/// Identifies sample (i, j) of chart c at level d (N = 2^d) so that copies of one surface point
/// get one key: a base vertex for corners, the base edge (low end first) and the reduced dyadic
/// fraction along it for side samples, the chart and the reduced dyadic grid position (i, j) / N
/// otherwise, so that every level is the next finer one at every other sample, like the
/// pipeline's point-sampled pyramid.
uint64_t sampleKey(int c, int32_t d, int32_t i, int32_t j)
{
  const int32_t n = 1 << d;
  const int* corner = kTetFaces[c];
  if (i == 0 && j == 0)
  {
    return hashOf({ 1, corner[0] });
  }
  if (i == n && j == 0)
  {
    return hashOf({ 1, corner[1] });
  }
  if (i == 0 && j == n)
  {
    return hashOf({ 1, corner[2] });
  }
  int side = -1;
  int32_t t = 0;
  if (j == 0)
  {
    side = 0;
    t = i;
  }
  else if (i + j == n)
  {
    side = 1;
    t = j;
  }
  else if (i == 0)
  {
    side = 2;
    t = n - j;
  }
  if (side < 0)
  {
    int32_t m = n;
    while (i % 2 == 0 && j % 2 == 0 && m > 1)
    {
      i /= 2;
      j /= 2;
      m /= 2;
    }
    return hashOf({ 3, c, m, i, j });
  }
  int a = corner[side];
  int b = corner[(side + 1) % 3];
  int32_t m = n;
  if (a > b)
  {
    std::swap(a, b);
    t = m - t;
  }
  while (t % 2 == 0 && m > 1)
  {
    t /= 2;
    m /= 2;
  }
  return hashOf({ 2, a, b, t, m });
}

/// Point of the tetrahedron at sample (i, j) of chart c at level d, projected onto the unit
/// sphere; side samples are interpolated from the edge's lower-numbered end so both charts
/// compute the same bits.
std::array<float, 3> spherePoint(int c, int32_t d, int32_t i, int32_t j)
{
  const int32_t n = 1 << d;
  const int* corner = kTetFaces[c];
  int from = corner[0];
  int to = corner[1];
  int other = corner[2];
  double s = static_cast<double>(i) / n;
  double r = static_cast<double>(j) / n;
  if (i + j == n && j > 0)
  {
    from = corner[1];
    to = corner[2];
    s = static_cast<double>(j) / n;
    r = 0;
  }
  else if (i == 0 && j > 0)
  {
    from = corner[2];
    to = corner[0];
    s = static_cast<double>(n - j) / n;
    r = 0;
  }
  if (r == 0 && from > to)
  {
    std::swap(from, to);
    s = 1.0 - s;
  }
  double p[3];
  for (int x = 0; x < 3; ++x)
  {
    p[x] = kTetCorners[from][x] + s * (kTetCorners[to][x] - kTetCorners[from][x]) +
      r * (kTetCorners[other][x] - kTetCorners[from][x]);
  }
  const double length = std::sqrt(p[0] * p[0] + p[1] * p[1] + p[2] * p[2]);
  return { static_cast<float>(p[0] / length), static_cast<float>(p[1] / length),
    static_cast<float>(p[2] / length) };
}

/// The tetrahedron atlas with charts of level maxLevel (so maxLevel + 1 images). `awkward`:
/// Position, Normal, Curvature (1), Color (4), Tensor (6) full of awkward values (finite
/// positions, as validateAtlas asks); otherwise Position and Normal of the unit sphere, the
/// smooth data a real atlas holds.
tc::Atlas tetrahedronAtlas(int32_t maxLevel, bool awkward)
{
  tc::Atlas atlas;
  atlas.attributes = { { tc::kAtlasPosition, 3 }, { tc::kAtlasNormal, 3 } };
  if (awkward)
  {
    atlas.attributes.push_back({ "Curvature", 1 });
    atlas.attributes.push_back({ "Color", 4 });
    atlas.attributes.push_back({ "Tensor", 6 });
  }
  atlas.inputPoints = (int64_t(1) << 53) + 1; // not a double: must stay an integer in the JSON
  atlas.inputTriangles = 4;
  atlas.inputDiagonal = awkward ? 0.1 + 0.2 : std::sqrt(48.0);
  atlas.source = "t\xc3\xa9tra\xe2\x98\x83 \"hedron\".off"; // UTF-8 and a quote

  for (int32_t k = 0; k <= maxLevel; ++k)
  {
    const int32_t n = 1 << (maxLevel - k);
    tc::AtlasImage image;
    image.width = 2 * (n + 2);
    image.height = n + 1;
    for (const tc::AtlasAttribute& attribute : atlas.attributes)
    {
      image.data.emplace_back(
        static_cast<size_t>(image.width * image.height * attribute.components), 0.0f);
    }
    atlas.images.push_back(std::move(image));
  }

  atlas.charts.resize(4);
  for (int c = 0; c < 4; ++c)
  {
    tc::AtlasChart& chart = atlas.charts[static_cast<size_t>(c)];
    chart.maxLevel = maxLevel;
    chart.partner = c ^ 1;
    chart.rotated = static_cast<uint8_t>(c & 1);
    for (int k = 0; k < 3; ++k)
    {
      const int a = kTetFaces[c][k];
      const int b = kTetFaces[c][(k + 1) % 3];
      chart.cornerVertex[static_cast<size_t>(k)] = a;
      // Edge 0-1 is a feature curve, seen from both of its charts.
      chart.featureSide[static_cast<size_t>(k)] =
        static_cast<uint8_t>(std::min(a, b) == 0 && std::max(a, b) == 1);
      for (int g = 0; g < 4; ++g)
      {
        for (int s = 0; s < 3; ++s)
        {
          if (kTetFaces[g][s] == b && kTetFaces[g][(s + 1) % 3] == a)
          {
            chart.neighborChart[static_cast<size_t>(k)] = g;
            chart.neighborSide[static_cast<size_t>(k)] = s;
          }
        }
      }
    }
    // Pair c / 2 fills the (N + 2) x (N + 1) rectangle at x = (c / 2) (N + 2) of every image.
    for (int32_t k = 0; k <= maxLevel; ++k)
    {
      const int32_t n = 1 << (maxLevel - k);
      const int32_t x0 = (c / 2) * (n + 2);
      chart.origin.push_back(
        chart.rotated ? std::array<int32_t, 2>{ x0 + n + 1, n } : std::array<int32_t, 2>{ x0, 0 });
    }
    if (awkward)
    {
      for (size_t i = 0; i < 12; ++i)
      {
        // Every kind of awkwardDouble in every chart.
        chart.box[i] = awkwardDouble(hashOf({ 4, c, static_cast<int64_t>(i) }) / 10 * 10 + i % 10);
      }
      chart.levelError = { 1.0 / 3.0, 0.1, std::numeric_limits<double>::denorm_min() };
      chart.levelError.resize(static_cast<size_t>(maxLevel) + 1, 1e-300);
      chart.levelError[0] = c == 0 ? std::numeric_limits<double>::infinity() : 1e308;
    }
    else
    {
      // Axis-aligned box of the face, as c0 and its three neighbours.
      std::array<double, 3> lo{ 1e9, 1e9, 1e9 };
      std::array<double, 3> hi{ -1e9, -1e9, -1e9 };
      for (int k = 0; k < 3; ++k)
      {
        for (int x = 0; x < 3; ++x)
        {
          lo[static_cast<size_t>(x)] =
            std::min(lo[static_cast<size_t>(x)], kTetCorners[kTetFaces[c][k]][x]);
          hi[static_cast<size_t>(x)] =
            std::max(hi[static_cast<size_t>(x)], kTetCorners[kTetFaces[c][k]][x]);
        }
      }
      for (int q = 0; q < 4; ++q)
      {
        for (int x = 0; x < 3; ++x)
        {
          chart.box[static_cast<size_t>(3 * q + x)] =
            (q == x + 1) ? hi[static_cast<size_t>(x)] : lo[static_cast<size_t>(x)];
        }
      }
    }
  }

  for (int c = 0; c < 4; ++c)
  {
    const tc::AtlasChart& chart = atlas.charts[static_cast<size_t>(c)];
    for (int32_t d = 0; d <= maxLevel; ++d)
    {
      const int32_t n = 1 << d;
      tc::AtlasImage& image = atlas.images[static_cast<size_t>(maxLevel - d)];
      for (int32_t j = 0; j <= n; ++j)
      {
        for (int32_t i = 0; i + j <= n; ++i)
        {
          const std::array<int32_t, 2> xy = tc::atlasTexel(chart, d, i, j);
          const size_t texel = static_cast<size_t>(xy[1] * image.width + xy[0]);
          const uint64_t key = sampleKey(c, d, i, j);
          const std::array<float, 3> p = spherePoint(c, d, i, j);
          for (size_t a = 0; a < atlas.attributes.size(); ++a)
          {
            const size_t comps = static_cast<size_t>(atlas.attributes[a].components);
            for (size_t x = 0; x < comps; ++x)
            {
              image.data[a][texel * comps + x] = awkward
                ? awkwardFloat(hashOf({ static_cast<int64_t>(key), static_cast<int64_t>(a),
                                 static_cast<int64_t>(x) }),
                    a == 0)
                : p[x];
            }
          }
        }
      }
    }
  }
  return atlas;
}

// ------------------------------------------------------------------------------------------
// Comparisons

template <typename T>
bool sameBits(const std::vector<T>& a, const std::vector<T>& b)
{
  return a.size() == b.size() &&
    (a.empty() || std::memcmp(a.data(), b.data(), a.size() * sizeof(T)) == 0);
}

template <typename T, size_t N>
bool sameBits(const std::array<T, N>& a, const std::array<T, N>& b)
{
  return std::memcmp(a.data(), b.data(), N * sizeof(T)) == 0;
}

bool sameBits(double a, double b)
{
  return std::memcmp(&a, &b, sizeof a) == 0;
}

/// Every field, floats and doubles compared bit for bit (so -0 differs from 0, NaN equals itself).
void expectBitIdentical(const tc::Atlas& expected, const tc::Atlas& actual)
{
  EXPECT_EQ(actual.source, expected.source);
  EXPECT_EQ(actual.inputPoints, expected.inputPoints);
  EXPECT_EQ(actual.inputTriangles, expected.inputTriangles);
  EXPECT_TRUE(sameBits(actual.inputDiagonal, expected.inputDiagonal));
  ASSERT_EQ(actual.attributes.size(), expected.attributes.size());
  for (size_t a = 0; a < expected.attributes.size(); ++a)
  {
    EXPECT_EQ(actual.attributes[a].name, expected.attributes[a].name);
    EXPECT_EQ(actual.attributes[a].components, expected.attributes[a].components);
  }
  ASSERT_EQ(actual.images.size(), expected.images.size());
  for (size_t k = 0; k < expected.images.size(); ++k)
  {
    EXPECT_EQ(actual.images[k].width, expected.images[k].width);
    EXPECT_EQ(actual.images[k].height, expected.images[k].height);
    ASSERT_EQ(actual.images[k].data.size(), expected.images[k].data.size());
    for (size_t a = 0; a < expected.images[k].data.size(); ++a)
    {
      EXPECT_TRUE(sameBits(actual.images[k].data[a], expected.images[k].data[a]))
        << "image " << k << " attribute " << a;
    }
  }
  ASSERT_EQ(actual.charts.size(), expected.charts.size());
  for (size_t c = 0; c < expected.charts.size(); ++c)
  {
    const tc::AtlasChart& e = expected.charts[c];
    const tc::AtlasChart& r = actual.charts[c];
    EXPECT_EQ(r.maxLevel, e.maxLevel);
    EXPECT_EQ(r.cornerVertex, e.cornerVertex);
    EXPECT_EQ(r.neighborChart, e.neighborChart);
    EXPECT_EQ(r.neighborSide, e.neighborSide);
    EXPECT_EQ(r.featureSide, e.featureSide);
    EXPECT_EQ(r.partner, e.partner);
    EXPECT_EQ(r.rotated, e.rotated);
    EXPECT_EQ(r.origin, e.origin);
    EXPECT_TRUE(sameBits(r.box, e.box)) << "chart " << c;
    EXPECT_TRUE(sameBits(r.levelError, e.levelError)) << "chart " << c;
  }
  // The rig's text writes every double in its shortest exact form: equal text, equal bits.
  EXPECT_EQ(tc::encodeRig(actual.rig), tc::encodeRig(expected.rig));
  ASSERT_EQ(actual.textures.size(), expected.textures.size());
  for (size_t t = 0; t < expected.textures.size(); ++t)
  {
    EXPECT_EQ(actual.textures[t].name, expected.textures[t].name);
    EXPECT_EQ(actual.textures[t].source, expected.textures[t].source);
    EXPECT_EQ(actual.textures[t].width, expected.textures[t].width);
    EXPECT_EQ(actual.textures[t].height, expected.textures[t].height);
    EXPECT_TRUE(actual.textures[t].rgba == expected.textures[t].rgba) << "texture " << t;
  }
}

std::string fileBytes(const std::string& path)
{
  std::ifstream in(path, std::ios::binary);
  return std::string(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
}

void writeBytes(const std::string& path, const std::string& bytes)
{
  std::ofstream(path, std::ios::binary | std::ios::trunc) << bytes;
}

// ------------------------------------------------------------------------------------------
// Damaged files: the parts of an atlas file loaded with OpenEXR, edited, and written again.

struct ExrPart
{
  Imf::Header header;
  std::map<std::string, std::vector<float>> channels; ///< per channel: height x width
  std::map<std::string, std::vector<uint32_t>> codes; ///< UINT channels (version 4), the same
};

std::vector<ExrPart> loadParts(const std::string& path)
{
  Imf::MultiPartInputFile file(path.c_str());
  std::vector<ExrPart> parts;
  for (int p = 0; p < file.parts(); ++p)
  {
    ExrPart part{ file.header(p), {} };
    const Imath::Box2i window = part.header.dataWindow();
    const size_t width = static_cast<size_t>(window.max.x - window.min.x + 1);
    const size_t height = static_cast<size_t>(window.max.y - window.min.y + 1);
    Imf::FrameBuffer buffer;
    for (auto it = part.header.channels().begin(); it != part.header.channels().end(); ++it)
    {
      if (it.channel().type == Imf::UINT)
      {
        std::vector<uint32_t>& codes = part.codes[it.name()];
        codes.assign(width * height, 0u);
        buffer.insert(it.name(),
          Imf::Slice(Imf::UINT, reinterpret_cast<char*>(codes.data()), sizeof(uint32_t),
            sizeof(uint32_t) * width));
        continue;
      }
      std::vector<float>& data = part.channels[it.name()];
      data.assign(width * height, 0.0f);
      buffer.insert(it.name(),
        Imf::Slice(
          Imf::FLOAT, reinterpret_cast<char*>(data.data()), sizeof(float), sizeof(float) * width));
    }
    Imf::InputPart in(file, p);
    in.setFrameBuffer(buffer);
    in.readPixels(window.min.y, window.max.y);
    parts.push_back(std::move(part));
  }
  return parts;
}

void saveParts(const std::string& path, std::vector<ExrPart>& parts)
{
  std::vector<Imf::Header> headers;
  for (const ExrPart& part : parts)
  {
    headers.push_back(part.header);
  }
  Imf::MultiPartOutputFile file(path.c_str(), headers.data(), static_cast<int>(headers.size()));
  for (size_t p = 0; p < parts.size(); ++p)
  {
    const Imath::Box2i window = parts[p].header.dataWindow();
    const size_t width = static_cast<size_t>(window.max.x - window.min.x + 1);
    Imf::FrameBuffer buffer;
    std::vector<std::vector<half>> halves; // OpenEXR does not convert float to half on output
    halves.reserve(parts[p].channels.size());
    for (auto& [name, data] : parts[p].channels)
    {
      if (parts[p].header.channels().findChannel(name)->type == Imf::HALF)
      {
        halves.emplace_back(data.begin(), data.end());
        buffer.insert(name,
          Imf::Slice(Imf::HALF, reinterpret_cast<char*>(halves.back().data()), sizeof(half),
            sizeof(half) * width));
        continue;
      }
      buffer.insert(name,
        Imf::Slice(
          Imf::FLOAT, reinterpret_cast<char*>(data.data()), sizeof(float), sizeof(float) * width));
    }
    for (auto& [name, codes] : parts[p].codes)
    {
      buffer.insert(name,
        Imf::Slice(Imf::UINT, reinterpret_cast<char*>(codes.data()), sizeof(uint32_t),
          sizeof(uint32_t) * width));
    }
    Imf::OutputPart out(file, static_cast<int>(p));
    out.setFrameBuffer(buffer);
    out.writePixels(window.max.y - window.min.y + 1);
  }
}

ExrPart& partNamed(std::vector<ExrPart>& parts, const std::string& name)
{
  for (ExrPart& part : parts)
  {
    if (part.header.name() == name)
    {
      return part;
    }
  }
  throw std::runtime_error("no part " + name);
}

int crc32Of(const std::string& text)
{
  return static_cast<int>(crc32(crc32(0L, Z_NULL, 0), reinterpret_cast<const Bytef*>(text.data()),
    static_cast<uInt>(text.size())));
}

std::string deflated(const std::string& text)
{
  uLongf size = compressBound(static_cast<uLong>(text.size()));
  std::string packed(size, '\0');
  if (compress2(reinterpret_cast<Bytef*>(&packed[0]), &size,
        reinterpret_cast<const Bytef*>(text.data()), static_cast<uLong>(text.size()),
        Z_BEST_COMPRESSION) != Z_OK)
  {
    throw std::runtime_error("compress2 failed");
  }
  packed.resize(size);
  return packed;
}

/// Removes attribute `name` from `header`. Not with Header::erase: OpenEXR 3.1 (Debian 12's)
/// drops the attribute from its map without deleting it (fixed upstream in 2023, openexr#1520),
/// a leak the sanitizer build reports. A header of every other attribute replaces it instead.
void eraseAttribute(Imf::Header& header, const char* name)
{
  Imf::Header rebuilt;
  for (Imf::Header::ConstIterator it = header.begin(); it != header.end(); ++it)
  {
    if (std::strcmp(it.name(), name) != 0)
    {
      rebuilt.insert(it.name(), it.attribute());
    }
  }
  header = std::move(rebuilt);
}

/// Replaces the metadata of part 0 by `text` as version 2 stores it (deflated, with its length),
/// with a matching checksum when `fixChecksum`.
void setMetadata(std::vector<ExrPart>& parts, const std::string& text, bool fixChecksum = true)
{
  eraseAttribute(parts[0].header, "trichartAtlas");
  parts[0].header.insert("trichartAtlasZ", Imf::StringAttribute(deflated(text)));
  parts[0].header.insert("trichartAtlasLength", Imf::IntAttribute(static_cast<int>(text.size())));
  if (fixChecksum)
  {
    parts[0].header.insert("trichartAtlasCrc32", Imf::IntAttribute(crc32Of(text)));
  }
}

/// Replaces the metadata of part 0 by `text` as version 1 stored it: plain, with its checksum.
void setPlainMetadata(std::vector<ExrPart>& parts, const std::string& text)
{
  eraseAttribute(parts[0].header, "trichartAtlasZ");
  eraseAttribute(parts[0].header, "trichartAtlasLength");
  parts[0].header.insert("trichartAtlas", Imf::StringAttribute(text));
  parts[0].header.insert("trichartAtlasCrc32", Imf::IntAttribute(crc32Of(text)));
}

/// The JSON text of the version-2 metadata of part 0.
std::string metadataTextOf(const std::vector<ExrPart>& parts)
{
  const Imf::Header& header = parts[0].header;
  const std::string& packed = header.typedAttribute<Imf::StringAttribute>("trichartAtlasZ").value();
  std::string text(
    static_cast<size_t>(header.typedAttribute<Imf::IntAttribute>("trichartAtlasLength").value()),
    '\0');
  uLongf size = text.size();
  if (uncompress(reinterpret_cast<Bytef*>(&text[0]), &size,
        reinterpret_cast<const Bytef*>(packed.data()), static_cast<uLong>(packed.size())) != Z_OK ||
    size != text.size())
  {
    throw std::runtime_error("the metadata does not inflate to its length");
  }
  return text;
}

Json metadataOf(const std::vector<ExrPart>& parts)
{
  return Json::parse(metadataTextOf(parts));
}

/// Writes `atlas` to `to` as version 1 or 2 wrote it, from `from`, the same atlas written by
/// writeAtlas: the same headers and metadata, but every part holds its whole image as floats
/// (no compact parts, no "texels" entries, no lattice) and the metadata says `version`, stored
/// plainly for version 1.
void writeOldVersion(
  const tc::Atlas& atlas, const std::string& from, const std::string& to, int version)
{
  std::vector<ExrPart> parts = loadParts(from);
  for (ExrPart& part : parts)
  {
    if (!part.codes.empty())
    {
      // A version-4 part of codes: the float channels of its 3 components instead.
      part.codes.clear();
      part.header.channels() = Imf::ChannelList();
      for (const char* name : { "X", "Y", "Z" })
      {
        part.header.channels().insert(name, Imf::Channel(Imf::FLOAT));
      }
    }
    const std::string name = part.header.name();
    const size_t dot = name.rfind('.');
    const size_t k = std::stoul(name.substr(dot + 1));
    size_t a = 0;
    while (atlas.attributes[a].name != name.substr(0, dot))
    {
      ++a;
    }
    const tc::AtlasImage& image = atlas.images[k];
    part.header.dataWindow() =
      Imath::Box2i(Imath::V2i(0, 0), Imath::V2i(image.width - 1, image.height - 1));
    const size_t comps = static_cast<size_t>(atlas.attributes[a].components);
    size_t c = 0;
    for (auto it = part.header.channels().begin(); it != part.header.channels().end(); ++it, ++c)
    {
      std::vector<float>& data = part.channels[it.name()];
      data.assign(static_cast<size_t>(image.width * image.height), 0.0f);
      // Channels are listed by name; components in the order channelNames gives them.
      const std::map<std::string, size_t> component = { { "X", 0 }, { "Y", 1 }, { "Z", 2 },
        { "R", 0 }, { "G", 1 }, { "B", 2 }, { "A", 3 } };
      const auto found = component.find(it.name());
      const size_t x =
        found != component.end() ? found->second : std::stoul(std::string(it.name()).substr(1));
      for (size_t t = 0; t < data.size(); ++t)
      {
        data[t] = image.data[a][t * comps + x];
      }
    }
  }
  Json metadata = metadataOf(parts);
  metadata["version"] = version;
  metadata.erase("lattice");
  for (Json& image : metadata["images"])
  {
    image.erase("texels");
  }
  if (version == 1)
  {
    setPlainMetadata(parts, metadata.dump());
  }
  else
  {
    setMetadata(parts, metadata.dump());
  }
  saveParts(to, parts);
}

/// An edit of the parts that makes `edit` on the metadata JSON (checksum kept valid).
std::function<void(std::vector<ExrPart>&)> metadataEdit(const std::function<void(Json&)>& edit)
{
  return [edit](std::vector<ExrPart>& parts)
  {
    Json metadata = metadataOf(parts);
    edit(metadata);
    setMetadata(parts, metadata.dump());
  };
}

/// Atlas files in a fresh folder per test.
class AtlasIo : public tctest::TempFolderTest
{
protected:
  /// Names in the folder (to see that no temporary file is left behind).
  std::vector<std::string> listing() const
  {
    std::vector<std::string> names;
    for (const auto& entry : fs::directory_iterator(Folder))
    {
      names.push_back(entry.path().filename().string());
    }
    std::sort(names.begin(), names.end());
    return names;
  }

  /// The message of the tc::InputError readAtlas throws for `path` ("" if it reads).
  static std::string readError(const std::string& path)
  {
    try
    {
      tc::readAtlas(path);
    }
    catch (const tc::InputError& error)
    {
      return error.what();
    }
    return "";
  }

  /// Applies `edit` to the parts of the atlas file `good`, saves them as "bad.exr" and returns
  /// the refusal message.
  std::string damagedCopyError(
    const std::string& good, const std::function<void(std::vector<ExrPart>&)>& edit)
  {
    const std::string bad = file("bad.exr");
    std::vector<ExrPart> parts = loadParts(good);
    edit(parts);
    saveParts(bad, parts);
    return readError(bad);
  }

  /// Writes the awkward atlas, applies `edit` to its parts and returns the refusal message.
  std::string damagedError(const std::function<void(std::vector<ExrPart>&)>& edit)
  {
    const std::string good = file("good.exr");
    tc::writeAtlas(tetrahedronAtlas(2, true), good);
    return damagedCopyError(good, edit);
  }

  /// damagedError for an edit of the metadata JSON (checksum kept valid).
  std::string metadataError(const std::function<void(Json&)>& edit)
  {
    return damagedError(metadataEdit(edit));
  }
};

bool mentions(const std::string& message, const std::string& what)
{
  return message.find(what) != std::string::npos;
}
} // namespace

// ------------------------------------------------------------------------------------------

TEST_F(AtlasIo, RoundTripIsBitExact)
{
  const tc::Atlas atlas = tetrahedronAtlas(2, true);
  ASSERT_NO_THROW(tc::validateAtlas(atlas));
  ASSERT_EQ(atlas.images.size(), 3u);

  // The data must hold the awkward values for the comparison to mean anything.
  size_t negativeZeros = 0, denormals = 0, huge = 0, nans = 0, infinities = 0;
  for (const tc::AtlasImage& image : atlas.images)
  {
    for (const std::vector<float>& data : image.data)
    {
      for (float v : data)
      {
        negativeZeros += bitsOf(v) == 0x80000000u;
        denormals += std::fpclassify(v) == FP_SUBNORMAL;
        huge += std::isfinite(v) && std::fabs(v) > 1e30f;
        nans += std::isnan(v);
        infinities += std::isinf(v);
      }
    }
  }
  EXPECT_GT(negativeZeros, 10u);
  EXPECT_GT(denormals, 10u);
  EXPECT_GT(huge, 10u);
  EXPECT_GT(nans, 5u);
  EXPECT_GT(infinities, 5u);

  const std::string path = file("tetrahedron.exr");
  tc::writeAtlas(atlas, path);
  expectBitIdentical(atlas, tc::readAtlas(path));

  // Replacing an existing file works the same way.
  tc::Atlas other = atlas;
  other.source = "second";
  tc::writeAtlas(other, path);
  expectBitIdentical(other, tc::readAtlas(path));
  EXPECT_EQ(listing(), std::vector<std::string>{ "tetrahedron.exr" });
}

TEST_F(AtlasIo, FileFollowsTheDocumentedLayout)
{
  const tc::Atlas atlas = tetrahedronAtlas(2, true);
  const std::string path = file("layout.exr");
  tc::writeAtlas(atlas, path);

  // Coarsest image first. Image k is 2 (N + 2) x (N + 1) with N = 2^(2 - k), all of it charts;
  // its part holds the texels that image k + 1 does not: all 12 of image 2 (2 rows of 6), the
  // 24 - 12 = 12 of image 1 (2 rows of 8), the 60 - 24 = 36 of image 0 (3 rows of 12).
  const std::array<int32_t, 3> rows = { 3, 2, 2 };
  const std::array<size_t, 3> stored = { 36, 12, 12 };
  Imf::MultiPartInputFile exr(path.c_str());
  ASSERT_EQ(exr.parts(), 15);
  const std::map<int, std::vector<std::string>> channels = { { 1, { "R" } },
    { 3, { "X", "Y", "Z" } }, { 4, { "A", "B", "G", "R" } },
    { 6, { "C0", "C1", "C2", "C3", "C4", "C5" } } };
  int p = 0;
  for (size_t k = 3; k-- > 0;)
  {
    for (const tc::AtlasAttribute& attribute : atlas.attributes)
    {
      const Imf::Header& header = exr.header(p++);
      EXPECT_EQ(header.name(), attribute.name + "." + std::to_string(k));
      EXPECT_EQ(header.type(), Imf::SCANLINEIMAGE);
      EXPECT_EQ(header.compression(), Imf::ZIP_COMPRESSION);
      EXPECT_EQ(header.dataWindow().min.x, 0);
      EXPECT_EQ(header.dataWindow().min.y, 0);
      EXPECT_EQ(header.dataWindow().max.x, atlas.images[k].width - 1);
      EXPECT_EQ(header.dataWindow().max.y, rows[k] - 1);
      std::vector<std::string> names;
      for (auto it = header.channels().begin(); it != header.channels().end(); ++it)
      {
        names.push_back(it.name());
        EXPECT_EQ(it.channel().type, Imf::FLOAT);
      }
      EXPECT_EQ(names, channels.at(attribute.components));
    }
  }

  // A part lists its image's new texels in texel order (row y, then x), row after row of the
  // part, then zeros. New: every sample of a chart's coarsest level, and every sample (i, j) of
  // a finer level with i or j odd.
  const std::vector<ExrPart> parts = loadParts(path);
  for (size_t k = 0; k < 3; ++k)
  {
    const tc::AtlasImage& image = atlas.images[k];
    const int32_t d = 2 - static_cast<int32_t>(k);
    std::vector<bool> fresh(static_cast<size_t>(image.width * image.height), false);
    for (const tc::AtlasChart& chart : atlas.charts)
    {
      for (int32_t j = 0; j <= (1 << d); ++j)
      {
        for (int32_t i = 0; i + j <= (1 << d); ++i)
        {
          const std::array<int32_t, 2> xy = tc::atlasTexel(chart, d, i, j);
          fresh[static_cast<size_t>(xy[1] * image.width + xy[0])] = d == 0 || i % 2 || j % 2;
        }
      }
    }
    const std::vector<float>& z = parts[3 * 5 - 5 * (k + 1)].channels.at("Z");
    ASSERT_EQ(z.size(), static_cast<size_t>(image.width * rows[k]));
    size_t n = 0;
    for (size_t t = 0; t < fresh.size(); ++t)
    {
      if (fresh[t])
      {
        EXPECT_EQ(bitsOf(z[n++]), bitsOf(image.data[0][3 * t + 2])) << "image " << k;
      }
    }
    EXPECT_EQ(n, stored[k]);
    for (; n < z.size(); ++n)
    {
      EXPECT_EQ(bitsOf(z[n]), 0u) << "image " << k;
    }
  }

  // The metadata: deflated JSON with its length and the checksum of the text, in part 0 only.
  const Imf::Header& first = parts[0].header;
  ASSERT_TRUE(first.findTypedAttribute<Imf::StringAttribute>("trichartAtlasZ"));
  ASSERT_TRUE(first.findTypedAttribute<Imf::IntAttribute>("trichartAtlasLength"));
  ASSERT_TRUE(first.findTypedAttribute<Imf::IntAttribute>("trichartAtlasCrc32"));
  EXPECT_FALSE(first.findTypedAttribute<Imf::StringAttribute>("trichartAtlas"));
  const std::string text = metadataTextOf(parts);
  EXPECT_EQ(first.typedAttribute<Imf::IntAttribute>("trichartAtlasLength").value(),
    static_cast<int>(text.size()));
  EXPECT_EQ(first.typedAttribute<Imf::IntAttribute>("trichartAtlasCrc32").value(), crc32Of(text));
  EXPECT_EQ(tc::kAtlasTextureVersion, 5);
  const Json metadata = Json::parse(text);
  for (const Json& image : metadata["images"])
  {
    EXPECT_EQ(image["texels"], "new");
  }
  EXPECT_EQ(metadata["format"], "TriChart atlas");
  // Its floats lie on no lattice: every attribute is stored as floats.
  EXPECT_EQ(metadata["version"], tc::kAtlasFloatVersion);
  EXPECT_EQ(metadata.count("lattice"), 0u);
  EXPECT_EQ(metadata["charts"].size(), 4u);
  EXPECT_EQ(metadata["charts"][0]["levelError"][0], "inf");
  EXPECT_TRUE(metadata["inputPoints"].is_number_integer());
  for (const char* name : { "trichartAtlasZ", "trichartAtlasLength", "trichartAtlasCrc32" })
  {
    EXPECT_FALSE(parts[1].header.find(name) != parts[1].header.end()) << name;
  }
}

TEST_F(AtlasIo, CompressedMetadataSurvivesEveryByteValue)
{
  // The deflated metadata is binary (NULs included); OpenEXR's string attribute must carry it
  // unchanged, through OpenEXRCore's header check too.
  const std::string path = file("bytes.exr");
  tc::writeAtlas(tetrahedronAtlas(2, true), path);
  const std::string packed =
    loadParts(path)[0].header.typedAttribute<Imf::StringAttribute>("trichartAtlasZ").value();
  std::vector<bool> seen(256, false);
  for (const char c : packed)
  {
    seen[static_cast<unsigned char>(c)] = true;
  }
  EXPECT_TRUE(seen[0]) << "no NUL in the " << packed.size() << " compressed bytes";
  EXPECT_GT(std::count(seen.begin(), seen.end(), true), 200);
  expectBitIdentical(tetrahedronAtlas(2, true), tc::readAtlas(path));
}

TEST_F(AtlasIo, SmoothAtlasSizeAndBytesPerTexel)
{
  const tc::Atlas atlas = tetrahedronAtlas(7, false);
  ASSERT_NO_THROW(tc::validateAtlas(atlas));
  const std::string path = file("sphere.exr");
  tc::writeAtlas(atlas, path);
  expectBitIdentical(atlas, tc::readAtlas(path));

  size_t texels = 0;
  for (const tc::AtlasImage& image : atlas.images)
  {
    texels += static_cast<size_t>(image.width * image.height);
  }
  const double bytes = static_cast<double>(fs::file_size(path));
  const double raw = 6.0 * sizeof(float) * static_cast<double>(texels);
  std::cout << "[ figures  ] tetrahedron on the unit sphere, 4 charts of level 7, Position + "
               "Normal: "
            << atlas.images.size() << " images, " << texels << " texels, file " << bytes
            << " bytes = " << bytes / static_cast<double>(texels) << " bytes per texel (raw "
            << raw / static_cast<double>(texels) << ", ratio " << raw / bytes << ")\n";
  // ZIP must be on: smooth float data shrinks.
  EXPECT_LT(bytes, raw);
}

TEST_F(AtlasIo, FailedWriteLeavesNoFileAndKeepsTheOldOne)
{
  const tc::Atlas atlas = tetrahedronAtlas(2, true);

  // A folder that does not exist: a clear error and nothing created.
  const std::string nowhere = file("missing/atlas.exr");
  try
  {
    tc::writeAtlas(atlas, nowhere);
    ADD_FAILURE() << "writing into a missing folder succeeded";
  }
  catch (const tc::InputError& error)
  {
    EXPECT_TRUE(mentions(error.what(), nowhere)) << error.what();
    EXPECT_TRUE(mentions(error.what(), "No such file or directory")) << error.what();
  }
  EXPECT_FALSE(fs::exists(Folder / "missing"));

  const std::string path = file("atlas.exr");
  tc::writeAtlas(atlas, path);
  const std::string before = fileBytes(path);

  // An atlas validateAtlas refuses.
  tc::Atlas broken = atlas;
  broken.charts[1].neighborSide[0] = (broken.charts[1].neighborSide[0] + 1) % 3;
  try
  {
    tc::writeAtlas(broken, path);
    ADD_FAILURE() << "an invalid atlas was written";
  }
  catch (const tc::InputError& error)
  {
    EXPECT_TRUE(mentions(error.what(), path)) << error.what();
    EXPECT_TRUE(mentions(error.what(), "chart 1")) << error.what();
  }

  // A double the file cannot hold.
  broken = atlas;
  broken.charts[2].box[5] = std::numeric_limits<double>::quiet_NaN();
  try
  {
    tc::writeAtlas(broken, path);
    ADD_FAILURE() << "a NaN box was written";
  }
  catch (const tc::InputError& error)
  {
    EXPECT_TRUE(mentions(error.what(), "chart 2 box[5] is NaN")) << error.what();
  }

  // An attribute name that is not UTF-8.
  broken = atlas;
  broken.attributes[2].name = "Curv\xff";
  EXPECT_THROW(tc::writeAtlas(broken, path), tc::InputError);

  // An abort half-way through the texels.
  EXPECT_THROW(
    tc::writeAtlas(atlas, path, tc::Progress([](double f) { return f < 0.5; })), tc::Aborted);

  // The target is a folder: the rename fails.
  fs::create_directories(Folder / "folder.exr");
  try
  {
    tc::writeAtlas(atlas, file("folder.exr"));
    ADD_FAILURE() << "an atlas replaced a folder";
  }
  catch (const tc::InputError& error)
  {
    EXPECT_TRUE(mentions(error.what(), file("folder.exr"))) << error.what();
  }

  EXPECT_EQ(fileBytes(path), before);
  EXPECT_EQ(listing(), (std::vector<std::string>{ "atlas.exr", "folder.exr" }));
  expectBitIdentical(atlas, tc::readAtlas(path));
}

TEST_F(AtlasIo, SourceThatIsNotUtf8IsWrittenWithReplacementCharacters)
{
  tc::Atlas atlas = tetrahedronAtlas(1, true);
  atlas.source = "caf\xe9.off"; // Latin-1
  const std::string path = file("latin1.exr");
  tc::writeAtlas(atlas, path);
  EXPECT_EQ(tc::readAtlas(path).source, "caf\xef\xbf\xbd.off");
}

TEST_F(AtlasIo, RefusesMissingFoldersAndFilesThatAreNotExr)
{
  const std::string missing = file("missing.exr");
  EXPECT_TRUE(mentions(readError(missing), missing)) << readError(missing);
  EXPECT_TRUE(mentions(readError(missing), "No such file")) << readError(missing);

  EXPECT_TRUE(mentions(readError(Folder.string()), "is a folder")) << readError(Folder.string());

  const std::string text = file("text.exr");
  writeBytes(text, "OFF\n3 1 0\n0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n");
  EXPECT_TRUE(mentions(readError(text), text + ": it is not an OpenEXR file")) << readError(text);

  const std::string empty = file("empty.exr");
  writeBytes(empty, "");
  EXPECT_TRUE(mentions(readError(empty), "not an OpenEXR file")) << readError(empty);
}

TEST_F(AtlasIo, RefusesExrFilesThatAreNotTriChartAtlases)
{
  // A plain OpenEXR image.
  const std::string plain = file("plain.exr");
  {
    Imf::Header header(4, 3);
    header.channels().insert("Y", Imf::Channel(Imf::FLOAT));
    std::vector<ExrPart> parts{ { header, { { "Y", std::vector<float>(12, 0.5f) } } } };
    parts[0].header.setName("image");
    parts[0].header.setType(Imf::SCANLINEIMAGE);
    saveParts(plain, parts);
  }
  const std::string message = readError(plain);
  EXPECT_TRUE(mentions(message, plain)) << message;
  EXPECT_TRUE(mentions(message, "not a TriChart atlas")) << message;
  EXPECT_FALSE(tc::isAtlasFile(plain));
  EXPECT_FALSE(tc::isAtlasFile(file("missing.exr")));
  const std::string atlas = file("atlas.exr");
  tc::writeAtlas(tetrahedronAtlas(1, false), atlas);
  EXPECT_TRUE(tc::isAtlasFile(atlas));

  std::string error = damagedError([](std::vector<ExrPart>& parts)
    { setMetadata(parts, "{\"format\": \"TriChart atlas\", \"version\": 1,"); });
  EXPECT_TRUE(mentions(error, "not valid JSON")) << error;
  EXPECT_TRUE(mentions(error, file("bad.exr"))) << error;

  error = metadataError([](Json& metadata) { metadata["format"] = "Other atlas"; });
  EXPECT_TRUE(mentions(error, "does not name the format")) << error;

  error = metadataError([](Json& metadata) { metadata["version"] = tc::kAtlasFileVersion + 1; });
  EXPECT_TRUE(mentions(error, "update TriChart")) << error;
  EXPECT_TRUE(mentions(error, file("bad.exr"))) << error;
}

TEST_F(AtlasIo, RefusesDamagedMetadata)
{
  // A changed digit with the checksum left as written.
  std::string error = damagedError(
    [](std::vector<ExrPart>& parts)
    {
      Json metadata = metadataOf(parts);
      metadata["charts"][1]["box"][3] = 0.25;
      setMetadata(parts, metadata.dump(), false);
    });
  EXPECT_TRUE(mentions(error, "metadata does not match its checksum")) << error;

  const std::vector<std::pair<std::function<void(Json&)>, std::string>> edits = {
    { [](Json& m) { m["charts"][0]["box"].erase(11); }, "charts[0].box" },
    { [](Json& m) { m["charts"][2]["rotated"] = 300; }, "charts[2].rotated" },
    { [](Json& m) { m["charts"][3]["maxLevel"] = "2"; }, "charts[3].maxLevel" },
    { [](Json& m) { m["charts"][0]["origin"][1] = Json::array({ 1 }); }, "charts[0].origin[1]" },
    { [](Json& m) { m["charts"][1]["levelError"][0] = "large"; }, "charts[1].levelError[0]" },
    { [](Json& m) { m["images"][1].erase("height"); }, "images[1].height" },
    { [](Json& m) { m["images"][0]["width"] = 1 << 20; }, "images[0].width" },
    { [](Json& m) { m["attributes"][3]["components"] = 0; }, "attributes[3].components" },
    { [](Json& m) { m["inputPoints"] = 1.5; }, "inputPoints" },
    { [](Json& m) { m.erase("charts"); }, "charts" },
  };
  for (const auto& [edit, field] : edits)
  {
    error = metadataError(edit);
    EXPECT_TRUE(mentions(error, field)) << field << ": " << error;
    EXPECT_TRUE(mentions(error, file("bad.exr"))) << error;
  }

  // Consistent sizes and checksums but neighbours that do not name each other.
  error = metadataError([](Json& m) { m["charts"][1]["neighborSide"][0] = 2; });
  EXPECT_TRUE(mentions(error, "invalid atlas")) << error;
  EXPECT_TRUE(mentions(error, file("bad.exr"))) << error;
}

TEST_F(AtlasIo, ReadsVersion1And2FilesBitExactly)
{
  const tc::Atlas atlas = tetrahedronAtlas(2, true);
  const std::string current = file("version3.exr");
  tc::writeAtlas(atlas, current);
  const std::string old = file("version1.exr");
  writeOldVersion(atlas, current, old, 1);
  const std::string second = file("version2.exr");
  writeOldVersion(atlas, current, second, 2);
  EXPECT_TRUE(tc::isAtlasFile(second));
  expectBitIdentical(atlas, tc::readAtlas(second));
  EXPECT_EQ(metadataOf(loadParts(second))["version"], 2);

  // The file really has the old layout: plain JSON, no compressed block.
  const std::vector<ExrPart> parts = loadParts(old);
  ASSERT_TRUE(parts[0].header.findTypedAttribute<Imf::StringAttribute>("trichartAtlas"));
  EXPECT_FALSE(parts[0].header.findTypedAttribute<Imf::StringAttribute>("trichartAtlasZ"));
  EXPECT_FALSE(parts[0].header.findTypedAttribute<Imf::IntAttribute>("trichartAtlasLength"));
  EXPECT_EQ(
    Json::parse(
      parts[0].header.typedAttribute<Imf::StringAttribute>("trichartAtlas").value())["version"],
    1);

  EXPECT_TRUE(tc::isAtlasFile(old));
  expectBitIdentical(atlas, tc::readAtlas(old));

  // Version 1's checksum still guards its plain text.
  std::string error = damagedError(
    [](std::vector<ExrPart>& edited)
    {
      Json metadata = metadataOf(edited);
      metadata["version"] = 1;
      setPlainMetadata(edited, metadata.dump());
      metadata["charts"][1]["box"][3] = 0.25;
      edited[0].header.insert("trichartAtlas", Imf::StringAttribute(metadata.dump()));
    });
  EXPECT_TRUE(mentions(error, "metadata does not match its checksum")) << error;
}

TEST_F(AtlasIo, RefusesMetadataStoredUnlikeItsVersion)
{
  // Version 1 text in the compressed block, version 3 text stored plainly.
  std::string error = metadataError([](Json& metadata) { metadata["version"] = 1; });
  EXPECT_TRUE(mentions(error, "says format version 1 but is stored compressed")) << error;
  EXPECT_TRUE(mentions(error, file("bad.exr"))) << error;
  error = damagedError(
    [](std::vector<ExrPart>& parts) { setPlainMetadata(parts, metadataTextOf(parts)); });
  EXPECT_TRUE(mentions(error, "says format version 3 but is stored as plain text")) << error;
  EXPECT_TRUE(mentions(error, file("bad.exr"))) << error;
}

TEST_F(AtlasIo, RefusesDamagedCompressedMetadata)
{
  const std::string damaged = "the file is damaged (write the atlas again)";
  const auto withPacked = [this](const std::function<std::string(const std::string&)>& edit)
  {
    return damagedError(
      [&edit](std::vector<ExrPart>& parts)
      {
        Imf::Header& header = parts[0].header;
        const std::string packed =
          header.typedAttribute<Imf::StringAttribute>("trichartAtlasZ").value();
        header.insert("trichartAtlasZ", Imf::StringAttribute(edit(packed)));
      });
  };
  const auto withLength = [this](const std::function<int(int)>& edit)
  {
    return damagedError(
      [&edit](std::vector<ExrPart>& parts)
      {
        Imf::Header& header = parts[0].header;
        const int length = header.typedAttribute<Imf::IntAttribute>("trichartAtlasLength").value();
        header.insert("trichartAtlasLength", Imf::IntAttribute(edit(length)));
      });
  };

  // A flipped byte in the middle of the deflate data (the checksum of the text left valid):
  // refused by zlib, by the declared length or by the checksum, never read.
  std::string error = withPacked(
    [](std::string packed)
    {
      packed[packed.size() / 2] = static_cast<char>(packed[packed.size() / 2] ^ 0x5a);
      return packed;
    });
  EXPECT_TRUE(mentions(error, file("bad.exr"))) << error;
  EXPECT_TRUE(mentions(error, "damaged")) << error;

  // Cut short, at its end (the Adler-32 of zlib's stream) and in its middle.
  for (const size_t cut : { size_t(1), size_t(4), size_t(300) })
  {
    error = withPacked(
      [cut](const std::string& packed) { return packed.substr(0, packed.size() - cut); });
    EXPECT_TRUE(mentions(error, "its compressed metadata is cut short; " + damaged))
      << cut << ": " << error;
    EXPECT_TRUE(mentions(error, file("bad.exr"))) << error;
  }
  error = withPacked([](const std::string&) { return std::string(); });
  EXPECT_TRUE(mentions(error, "which deflate cannot give")) << error;

  // Bytes after the end of the stream.
  error = withPacked([](const std::string& packed) { return packed + "xy"; });
  EXPECT_TRUE(mentions(error, "has 2 stray bytes after its end")) << error;

  // Not zlib data at all.
  error = withPacked([](const std::string& packed) { return std::string(packed.size(), 'x'); });
  EXPECT_TRUE(mentions(error, "its compressed metadata is corrupt (zlib: ")) << error;

  // Declared lengths: one byte short, one byte long, more than deflate can give, negative,
  // missing.
  error = withLength([](int length) { return length - 1; });
  EXPECT_TRUE(mentions(error, "bytes, not the")) << error;
  error = withLength([](int length) { return length + 1; });
  EXPECT_TRUE(mentions(error, "bytes, not the")) << error;
  error = withLength([](int length) { return length / 2; });
  EXPECT_TRUE(mentions(error, "inflates to more than the")) << error;
  const auto peakMiB = []
  {
    rusage usage{};
    getrusage(RUSAGE_SELF, &usage);
    return usage.ru_maxrss / 1024; // KiB on Linux
  };
  const long before = peakMiB();
  error = withLength([](int) { return std::numeric_limits<int>::max(); });
  EXPECT_TRUE(
    mentions(error, "declares a length of 2147483647 bytes, which deflate cannot give; " + damaged))
    << error;
  EXPECT_TRUE(mentions(error, file("bad.exr"))) << error;
  EXPECT_LT(peakMiB() - before, 64) << "the declared length was allocated";
  error = withLength([](int) { return -5; });
  EXPECT_TRUE(mentions(error, "declares a length of -5 bytes")) << error;
  error = damagedError(
    [](std::vector<ExrPart>& parts) { eraseAttribute(parts[0].header, "trichartAtlasLength"); });
  EXPECT_TRUE(mentions(error, "has no 'trichartAtlasLength' attribute")) << error;
}

TEST_F(AtlasIo, FlippedBytesInTheCompressedMetadataAreRefusedOrHarmless)
{
  // Every byte of the deflate data flipped in place in the file (its CRC-32 of the text, its
  // length and every OpenEXR size unchanged).
  const tc::Atlas atlas = tetrahedronAtlas(2, true);
  const std::string good = file("good.exr");
  tc::writeAtlas(atlas, good);
  const std::string bytes = fileBytes(good);
  const std::string key("trichartAtlasZ\0string\0", 22);
  const size_t sizeAt = bytes.find(key) + key.size();
  ASSERT_LT(sizeAt + 4, bytes.size());
  uint32_t size = 0;
  std::memcpy(&size, bytes.data() + sizeAt, 4);
  const size_t begin = sizeAt + 4;
  ASSERT_LE(begin + size, bytes.size());
  const std::string bad = file("flipped.exr");
  size_t refused = 0;
  for (size_t at = begin; at < begin + size; ++at)
  {
    std::string damaged = bytes;
    damaged[at] = static_cast<char>(damaged[at] ^ 0x5a);
    writeBytes(bad, damaged);
    try
    {
      const tc::Atlas read = tc::readAtlas(bad);
      // Only bits that deflate ignores (the padding of its last byte) can change harmlessly.
      SCOPED_TRACE("byte " + std::to_string(at - begin) + " of the block flipped and read");
      expectBitIdentical(atlas, read);
    }
    catch (const tc::InputError& error)
    {
      ++refused;
      EXPECT_TRUE(mentions(error.what(), bad)) << error.what();
    }
  }
  std::cout << "[ figures  ] " << refused << " of " << size
            << " single-byte flips in the compressed metadata refused\n";
  EXPECT_GE(refused + 1, size);
}

TEST_F(AtlasIo, EachVersionMakesTheFileSmaller)
{
  // The atlas of the bundled bunny with default options, 100+ charts: a chart table and images
  // like a real one's, not the tetrahedron's four full rectangles.
  const tctest::PipelineCase* bunny = tctest::pipelineCase(tctest::pipelineMeshPath("bunny_npm"));
  ASSERT_TRUE(bunny);
  const tc::Atlas atlas =
    tc::buildGeometryImages(tc::tracePaths(bunny->mesh, bunny->result), bunny->result, {}, {}, {});
  ASSERT_GE(atlas.charts.size(), 100u);
  const std::string current = file("version4.exr");
  tc::writeAtlas(atlas, current);
  const std::string first = file("version1.exr");
  writeOldVersion(atlas, current, first, 1);
  const std::string second = file("version2.exr");
  writeOldVersion(atlas, current, second, 2);
  // Version 3, the floats: the same atlas but for one interior sample of chart 0's finest
  // level moved off the lattice.
  tc::Atlas floats = atlas;
  const int32_t top = floats.charts[0].maxLevel;
  float* moved = const_cast<float*>(tc::atlasSample(floats, 0, 0, top, 1, 1));
  moved[0] = std::nextafter(moved[0], HUGE_VALF);
  const std::string third = file("version3.exr");
  tc::writeAtlas(floats, third);
  expectBitIdentical(atlas, tc::readAtlas(first));
  expectBitIdentical(atlas, tc::readAtlas(second));
  expectBitIdentical(floats, tc::readAtlas(third));
  expectBitIdentical(atlas, tc::readAtlas(current));

  // The pipeline's pyramid is point-sampled: every image is stored compactly.
  const std::vector<ExrPart> parts = loadParts(current);
  const Json metadata = metadataOf(parts);
  EXPECT_EQ(metadata["version"], 4);
  EXPECT_EQ(metadataOf(loadParts(third))["version"], 3);
  for (const Json& image : metadata["images"])
  {
    EXPECT_EQ(image["texels"], "new");
  }
  const double text = static_cast<double>(metadataTextOf(parts).size());
  const double packed = static_cast<double>(
    parts[0].header.typedAttribute<Imf::StringAttribute>("trichartAtlasZ").value().size());
  const double v1 = static_cast<double>(fs::file_size(first));
  const double v2 = static_cast<double>(fs::file_size(second));
  const double v3 = static_cast<double>(fs::file_size(third));
  const double v4 = static_cast<double>(fs::file_size(current));
  const double triangles = static_cast<double>(bunny->mesh.numTriangles());
  std::cout << "[ figures  ] bunny_npm, " << atlas.charts.size() << " charts: metadata " << text
            << " -> " << packed << " bytes (" << text / packed << "x); file version 1 " << v1
            << ", version 2 " << v2 << ", version 3 " << v3 << ", version 4 " << v4
            << " bytes = " << v1 / triangles << ", " << v2 / triangles << ", " << v3 / triangles
            << ", " << v4 / triangles << " bytes per input triangle\n";
  // Deflate shrinks JSON text by more than 2x; the file must lose at least half the text.
  EXPECT_GT(text / packed, 2.0);
  EXPECT_LT(v2, v1 - text / 2);
  // The coarser images are a third of the finest one's texels, which compact parts no longer
  // repeat.
  EXPECT_LT(v3, 0.85 * v2);
  // Codes predicted from the coarser image take a fraction of the floats' bytes.
  EXPECT_LT(v4, 0.6 * v3);
}

TEST_F(AtlasIo, ImagesThatAreNoPointSampledPyramidAreStoredWhole)
{
  // One texel of image 0 that is not its coarser copy, and one texel of image 1 no chart covers
  // that is not 0: those images are written whole, the others compactly, all bit-exact.
  tc::Atlas atlas = tetrahedronAtlas(3, true);
  const std::array<int32_t, 2> inherited = tc::atlasTexel(atlas.charts[2], 3, 2, 4);
  float& v =
    atlas.images[0]
      .data[3][4 * static_cast<size_t>(inherited[1] * atlas.images[0].width + inherited[0]) + 1];
  v = floatFromBits(bitsOf(v) ^ 0x10u);
  // Image 1 gains a column no chart covers.
  tc::AtlasImage& image = atlas.images[1];
  for (size_t a = 0; a < atlas.attributes.size(); ++a)
  {
    const size_t comps = static_cast<size_t>(atlas.attributes[a].components);
    std::vector<float> wider;
    for (int32_t y = 0; y < image.height; ++y)
    {
      const auto row = image.data[a].begin() + static_cast<std::ptrdiff_t>(y * image.width * comps);
      wider.insert(wider.end(), row, row + static_cast<std::ptrdiff_t>(image.width * comps));
      for (size_t x = 0; x < comps; ++x)
      {
        wider.push_back(y == 1 ? -0.0f : 0.0f);
      }
    }
    image.data[a] = wider;
  }
  ++image.width;
  ASSERT_NO_THROW(tc::validateAtlas(atlas));

  const std::string path = file("mixed.exr");
  tc::writeAtlas(atlas, path);
  expectBitIdentical(atlas, tc::readAtlas(path));
  const std::vector<ExrPart> parts = loadParts(path);
  const Json metadata = metadataOf(parts);
  EXPECT_EQ(metadata["images"][0]["texels"], "all");
  EXPECT_EQ(metadata["images"][1]["texels"], "all");
  EXPECT_EQ(metadata["images"][2]["texels"], "new");
  EXPECT_EQ(metadata["images"][3]["texels"], "new");
  EXPECT_EQ(
    partNamed(const_cast<std::vector<ExrPart>&>(parts), "Color.0").header.dataWindow().max.x,
    atlas.images[0].width - 1);

  // With the empty column all zero, image 1 is compact again.
  for (size_t a = 0; a < atlas.attributes.size(); ++a)
  {
    const size_t comps = static_cast<size_t>(atlas.attributes[a].components);
    const size_t x = static_cast<size_t>(image.width - 1);
    std::fill_n(
      image.data[a].begin() + static_cast<std::ptrdiff_t>((image.width + x) * comps), comps, 0.0f);
  }
  tc::writeAtlas(atlas, path);
  expectBitIdentical(atlas, tc::readAtlas(path));
  EXPECT_EQ(metadataOf(loadParts(path))["images"][1]["texels"], "new");
}

TEST_F(AtlasIo, RefusesMissingPartsWrongSizesAndChannels)
{
  std::string error =
    damagedError([](std::vector<ExrPart>& parts) { parts.erase(parts.begin() + 6); });
  EXPECT_TRUE(mentions(error, "has 14 parts")) << error;

  error = damagedError(
    [](std::vector<ExrPart>& parts) { partNamed(parts, "Normal.1").header.setName("Normals.1"); });
  EXPECT_TRUE(mentions(error, "part 'Normal.1' is missing")) << error;

  // A part one pixel wider than its image.
  error = damagedError(
    [](std::vector<ExrPart>& parts)
    {
      ExrPart& part = partNamed(parts, "Tensor.2");
      part.header.dataWindow().max.x += 1;
      const Imath::Box2i w = part.header.dataWindow();
      for (auto& [name, data] : part.channels)
      {
        data.assign(static_cast<size_t>((w.max.x + 1) * (w.max.y + 1)), 1.0f);
      }
    });
  EXPECT_TRUE(mentions(error, "part 'Tensor.2' covers pixels")) << error;

  // The metadata says the image is taller than its part, or whole where the part is compact.
  // (A compact part's size follows from the chart layout: a wrong image size there shows as a
  // checksum mismatch.)
  error = metadataError(
    [](Json& m)
    {
      m["images"][2]["height"] = 3;
      m["images"][2]["texels"] = "all";
    });
  EXPECT_TRUE(mentions(
    error, "part 'Position.2' covers pixels (0, 0) .. (5, 1) but the metadata makes it 6 x 3"))
    << error;
  error = metadataError([](Json& m) { m["images"][1]["texels"] = "all"; });
  EXPECT_TRUE(mentions(error, "but the metadata makes it 8 x 3")) << error;
  error = metadataError([](Json& m) { m["images"][1]["texels"] = "some"; });
  EXPECT_TRUE(mentions(error, "images[1].texels that is neither \"new\" nor \"all\"")) << error;
  error = metadataError([](Json& m) { m["images"][1].erase("texels"); });
  EXPECT_TRUE(mentions(error, "lacks images[1].texels")) << error;

  error = damagedError(
    [](std::vector<ExrPart>& parts)
    {
      ExrPart& part = partNamed(parts, "Position.0");
      part.channels["W"] = part.channels["Z"];
      part.channels.erase("Z");
      part.header.channels() = Imf::ChannelList();
      for (const char* name : { "X", "Y", "W" })
      {
        part.header.channels().insert(name, Imf::Channel(Imf::FLOAT));
      }
    });
  EXPECT_TRUE(mentions(error, "part 'Position.0' does not have exactly the channels X, Y, Z"))
    << error;

  error = damagedError(
    [](std::vector<ExrPart>& parts)
    {
      ExrPart& part = partNamed(parts, "Curvature.1");
      part.channels["G"] = part.channels["R"];
      part.header.channels().insert("G", Imf::Channel(Imf::FLOAT));
    });
  EXPECT_TRUE(mentions(error, "part 'Curvature.1' does not have exactly the channels R")) << error;

  error = damagedError([](std::vector<ExrPart>& parts)
    { partNamed(parts, "Color.0").header.channels().findChannel("B")->type = Imf::HALF; });
  EXPECT_TRUE(mentions(error, "channel 'B' is not full-resolution 32-bit float")) << error;

  // One texel changed, which OpenEXR cannot notice: the part checksum does.
  error = damagedError(
    [](std::vector<ExrPart>& parts)
    {
      float& v = partNamed(parts, "Normal.1").channels["Y"][0];
      v = floatFromBits(bitsOf(v) ^ 1u);
    });
  EXPECT_TRUE(mentions(error, "the texels of part 'Normal.1' do not match their checksum"))
    << error;
  EXPECT_TRUE(mentions(error, file("bad.exr"))) << error;
}

TEST_F(AtlasIo, RefusesTruncatedFiles)
{
  const tc::Atlas atlas = tetrahedronAtlas(2, true);
  const std::string good = file("good.exr");
  tc::writeAtlas(atlas, good);
  const std::string bytes = fileBytes(good);
  const std::string cut = file("cut.exr");
  std::vector<size_t> lengths = { 0, 1, 3, 4, 7, 8, 9, 16, 40, 200, bytes.size() - 1,
    bytes.size() - 2, bytes.size() - 17 };
  for (size_t length = 300; length < bytes.size(); length += bytes.size() / 61)
  {
    lengths.push_back(length);
  }
  for (size_t length : lengths)
  {
    writeBytes(cut, bytes.substr(0, length));
    const std::string error = readError(cut);
    EXPECT_TRUE(mentions(error, cut))
      << "cut at " << length << " of " << bytes.size() << ": '" << error << "'";
  }
}

TEST_F(AtlasIo, RefusesHugeSizesInDamagedHeadersWithoutAllocatingThem)
{
  const std::string good = file("good.exr");
  tc::writeAtlas(tetrahedronAtlas(2, true), good);
  const std::string bytes = fileBytes(good);
  const std::string bad = file("huge.exr");
  const auto peakMiB = []
  {
    rusage usage{};
    getrusage(RUSAGE_SELF, &usage);
    return usage.ru_maxrss / 1024; // KiB on Linux
  };
  const long before = peakMiB();

  // The size of the compressed metadata string, then the data window of part 1, made 2^31 - 1.
  const std::string metadataKey("trichartAtlasZ\0string\0", 22);
  const size_t metadataSize = bytes.find(metadataKey) + metadataKey.size();
  const std::string windowKey("dataWindow\0box2i\0", 17);
  const size_t window1 = bytes.find(windowKey, bytes.find(windowKey) + 1) + windowKey.size() + 4;
  for (const size_t at : { metadataSize, window1 + 8, window1 + 12 })
  {
    ASSERT_LT(at + 4, bytes.size());
    std::string damaged = bytes;
    damaged.replace(at, 4, "\xff\xff\xff\x7f", 4);
    writeBytes(bad, damaged);
    const std::string error = readError(bad);
    EXPECT_TRUE(mentions(error, bad)) << "at " << at << ": '" << error << "'";
  }
  EXPECT_LT(peakMiB() - before, 256) << "reading the damaged files took that much memory";
}

TEST_F(AtlasIo, FlippedBytesAreRefusedOrHarmless)
{
  const tc::Atlas atlas = tetrahedronAtlas(2, true);
  const std::string good = file("good.exr");
  tc::writeAtlas(atlas, good);
  const std::string bytes = fileBytes(good);
  const std::string bad = file("flipped.exr");
  size_t refused = 0;
  size_t tried = 0;
  for (size_t at = 0; at < bytes.size(); at += 1 + bytes.size() / 251, ++tried)
  {
    std::string damaged = bytes;
    damaged[at] = static_cast<char>(damaged[at] ^ 0x5a);
    writeBytes(bad, damaged);
    // Never silently different: either a refusal naming the file or the very same atlas.
    bool wasRefused = false;
    try
    {
      const tc::Atlas read = tc::readAtlas(bad);
      SCOPED_TRACE("byte " + std::to_string(at) + " flipped and read");
      expectBitIdentical(atlas, read);
    }
    catch (const tc::InputError& error)
    {
      wasRefused = true;
      ++refused;
      EXPECT_TRUE(mentions(error.what(), bad)) << error.what();
    }
    // The file ends with the texel chunks (the headers, with the metadata, and the offset
    // tables take its first 52 %): every flip in its last third is refused.
    if (at >= 2 * bytes.size() / 3)
    {
      EXPECT_TRUE(wasRefused) << "byte " << at << " of " << bytes.size();
    }
  }
  std::cout << "[ figures  ] " << refused << " of " << tried << " single-byte flips refused ("
            << bytes.size() << "-byte file)\n";
}

TEST_F(AtlasIo, ReportsProgressAndHonoursAbort)
{
  const tc::Atlas atlas = tetrahedronAtlas(2, true);
  const std::string path = file("progress.exr");
  const auto stopHalfWay = [](double f) { return f < 0.5; };
  tctest::expectProgressAndAbort(
    [&](const tc::Progress& progress) { tc::writeAtlas(atlas, path, progress); }, 10, stopHalfWay);
  // The aborted write left the complete file of the first run and no temporary.
  EXPECT_EQ(listing(), std::vector<std::string>{ "progress.exr" });
  tctest::expectProgressAndAbort([&](const tc::Progress& progress)
    { expectBitIdentical(atlas, tc::readAtlas(path, progress)); },
    10, stopHalfWay);
}

// ------------------------------------------------------------------------------------------
// Version 4: Position and Normal as lattice codes

namespace
{
/// The bundled bunny's atlas with default options: its positions and normals on the lattice.
const tc::Atlas& latticeAtlas()
{
  static const tc::Atlas atlas = []
  {
    const tctest::PipelineCase* bunny = tctest::pipelineCase(tctest::pipelineMeshPath("bunny_npm"));
    return tc::buildGeometryImages(
      tc::tracePaths(bunny->mesh, bunny->result), bunny->result, {}, {}, {});
  }();
  return atlas;
}

/// Coordinate a of position code q, by the decode rule of docs/atlas-format.md section 2.1.
float documentedCoordinate(const Json& lattice, int a, int64_t q)
{
  return static_cast<float>(std::ldexp(static_cast<double>(lattice["origin"][a].get<int64_t>() + q),
    lattice["stepExponent"].get<int>()));
}

/// The normal of octahedral code (u, v), by the decode rule of section 2.1.
std::array<float, 3> documentedNormal(int bits, int64_t u, int64_t v)
{
  const double limit = static_cast<double>((int64_t(1) << (bits - 1)) - 1);
  const auto s = [](double t) { return t >= 0.0 ? 1.0 : -1.0; };
  double x = static_cast<double>(u) / limit, y = static_cast<double>(v) / limit;
  const double z = 1.0 - std::abs(x) - std::abs(y);
  if (z < 0.0)
  {
    const double fx = (1.0 - std::abs(y)) * s(x);
    y = (1.0 - std::abs(x)) * s(y);
    x = fx;
  }
  const double length = std::sqrt(x * x + y * y + z * z);
  return { static_cast<float>(x / length) + 0.0f, static_cast<float>(y / length) + 0.0f,
    static_cast<float>(z / length) + 0.0f };
}

/// The residuals of a coded part, per channel (in texel order), from its stored values by the
/// byte planes of section 2.1: per block of 16 rows, B -> t -> P -> residual bytes.
std::vector<std::vector<uint32_t>> documentedResiduals(const ExrPart& part)
{
  const Imath::Box2i window = part.header.dataWindow();
  const size_t width = static_cast<size_t>(window.max.x + 1);
  const size_t height = static_cast<size_t>(window.max.y + 1);
  std::vector<const std::vector<uint32_t>*> channels; // sorted by name, as the map is
  for (const auto& [name, codes] : part.codes)
  {
    channels.push_back(&codes);
  }
  std::vector<std::vector<uint32_t>> residuals(
    channels.size(), std::vector<uint32_t>(width * height));
  for (size_t y0 = 0; y0 < height; y0 += 16)
  {
    const size_t y1 = std::min(height, y0 + 16);
    std::vector<uint8_t> b;
    for (size_t y = y0; y < y1; ++y)
    {
      for (const std::vector<uint32_t>* channel : channels)
      {
        for (size_t x = 0; x < width; ++x)
        {
          for (int byte = 0; byte < 4; ++byte)
          {
            b.push_back(static_cast<uint8_t>((*channel)[y * width + x] >> (8 * byte)));
          }
        }
      }
    }
    const size_t half = (b.size() + 1) / 2;
    std::vector<uint8_t> t(b.size()), p(b.size());
    for (size_t m = 0; m < b.size(); ++m)
    {
      t[m % 2 == 0 ? m / 2 : half + m / 2] = b[m];
    }
    p[0] = t[0];
    for (size_t m = 1; m < t.size(); ++m)
    {
      p[m] = static_cast<uint8_t>(t[m] - t[m - 1] + 128);
    }
    const size_t texels = (y1 - y0) * width;
    for (size_t c = 0; c < channels.size(); ++c)
    {
      for (int byte = 0; byte < 4; ++byte)
      {
        for (size_t n = 0; n < texels; ++n)
        {
          residuals[c][y0 * width + n] |= static_cast<uint32_t>(p[(4 * c + byte) * texels + n])
            << (8 * byte);
        }
      }
    }
  }
  return residuals;
}

/// The decoded codes of every chart sample of attribute a (0 Position, 1 Normal) of every image
/// by the order, prediction and zigzag of section 2.1, keyed by (chart, level, i, j).
std::map<std::array<int32_t, 4>, std::array<int64_t, 3>> documentedCodes(
  const tc::Atlas& atlas, const std::vector<ExrPart>& parts, size_t a)
{
  std::map<std::array<int32_t, 4>, std::array<int64_t, 3>> codes;
  const size_t comps = a == 0 ? 3 : 2;
  size_t twins = 0;
  for (size_t k = atlas.images.size(); k-- > 0;)
  {
    const ExrPart& part = partNamed(
      const_cast<std::vector<ExrPart>&>(parts), atlas.attributes[a].name + "." + std::to_string(k));
    const std::vector<std::vector<uint32_t>> residuals = documentedResiduals(part);
    size_t n = 0;
    std::array<int64_t, 3> previous{ 0, 0, 0 };
    for (size_t c = 0; c < atlas.charts.size(); ++c)
    {
      const int32_t d = atlas.charts[c].maxLevel - static_cast<int32_t>(k),
                    big = d >= 0 ? 1 << d : 0;
      for (int32_t j = 0; d >= 0 && j <= big; ++j)
      {
        for (int32_t i = 0; i + j <= big; ++i)
        {
          const int32_t ci = static_cast<int32_t>(c);
          std::array<int64_t, 3>& code = codes[{ ci, d, i, j }];
          if (d > 0 && i % 2 == 0 && j % 2 == 0)
          {
            code = codes.at({ ci, d - 1, i / 2, j / 2 });
            continue;
          }
          if (a == 0)
          {
            // A position whose twin on the chart across its side came first is not stored.
            const std::array<int32_t, 2> side = tc::gridSide(i, j, big);
            if (side[0] >= 0)
            {
              const tc::AtlasChart& chart = atlas.charts[c];
              const std::array<int32_t, 2> ij =
                tc::sidePoint(chart.neighborSide[side[0]], big - side[1], big);
              const auto twin = codes.find({ chart.neighborChart[side[0]], d, ij[0], ij[1] });
              if (twin != codes.end())
              {
                code = twin->second;
                previous = code;
                ++twins;
                continue;
              }
            }
          }
          std::array<int32_t, 4> ends = j % 2 == 0 ? std::array<int32_t, 4>{ i - 1, j, i + 1, j }
            : i % 2 == 0                           ? std::array<int32_t, 4>{ i, j - 1, i, j + 1 }
                         : std::array<int32_t, 4>{ i - 1, j + 1, i + 1, j - 1 };
          for (size_t x = 0; x < comps; ++x)
          {
            int64_t predicted = previous[x];
            if (d > 0)
            {
              const int64_t sum = codes.at({ ci, d - 1, ends[0] / 2, ends[1] / 2 })[x] +
                codes.at({ ci, d - 1, ends[2] / 2, ends[3] / 2 })[x];
              predicted = static_cast<int64_t>(std::floor(static_cast<double>(sum) / 2.0));
            }
            const uint32_t z = residuals[x][n];
            code[x] = predicted + ((z & 1u) ? -static_cast<int64_t>(z / 2) - 1 : int64_t(z / 2));
            previous[x] = code[x];
          }
          ++n;
        }
      }
    }
  }
  // Shared sides: every position sample on one has a twin, stored once.
  EXPECT_EQ(twins > 0, a == 0);
  return codes;
}
} // namespace

TEST_F(AtlasIo, Version4FollowsTheDocumentedLayout)
{
  const tc::Atlas& atlas = latticeAtlas();
  const std::string path = file("lattice.exr");
  tc::writeAtlas(atlas, path);
  expectBitIdentical(atlas, tc::readAtlas(path));

  const std::vector<ExrPart> parts = loadParts(path);
  const Json metadata = metadataOf(parts);
  EXPECT_EQ(metadata["version"], 4);
  const Json& lattice = metadata["lattice"];
  // The step: the largest power of two <= the diagonal * 2^-16; 12-bit normals.
  EXPECT_EQ(lattice["stepExponent"], std::ilogb(atlas.inputDiagonal) - 16);
  EXPECT_EQ(lattice["normalBits"], 12);
  for (const ExrPart& part : parts)
  {
    const std::string name = part.header.name();
    const bool position = name.rfind("Position.", 0) == 0;
    const bool normal = name.rfind("Normal.", 0) == 0;
    std::vector<std::string> channels;
    for (auto it = part.header.channels().begin(); it != part.header.channels().end(); ++it)
    {
      channels.push_back(it.name());
      EXPECT_EQ(it.channel().type, position || normal ? Imf::UINT : Imf::FLOAT) << name;
    }
    if (position || normal)
    {
      const std::vector<std::string> expected =
        position ? std::vector<std::string>{ "X", "Y", "Z" } : std::vector<std::string>{ "U", "V" };
      EXPECT_EQ(channels, expected) << name;
    }
  }

  // Every sample's codes, decoded by the document alone, give the atlas's floats bit for bit
  // and lie in the lattice's range.
  for (size_t a = 0; a < 2; ++a)
  {
    const auto codes = documentedCodes(atlas, parts, a);
    size_t checked = 0;
    for (const auto& [sample, code] : codes)
    {
      const float* expected =
        tc::atlasSample(atlas, sample[0], static_cast<int32_t>(a), sample[1], sample[2], sample[3]);
      std::array<float, 3> decoded{};
      if (a == 0)
      {
        for (int x = 0; x < 3; ++x)
        {
          EXPECT_GE(code[x], 0);
          EXPECT_LE(code[x], lattice["extent"][x].get<int64_t>());
          decoded[x] = documentedCoordinate(lattice, x, code[x]);
        }
      }
      else
      {
        EXPECT_LE(std::abs(code[0]), 2047);
        EXPECT_LE(std::abs(code[1]), 2047);
        decoded = documentedNormal(12, code[0], code[1]);
      }
      for (int x = 0; x < 3; ++x)
      {
        ASSERT_EQ(bitsOf(decoded[x]), bitsOf(expected[x]))
          << "attribute " << a << " chart " << sample[0] << " level " << sample[1] << " ("
          << sample[2] << ", " << sample[3] << ")";
      }
      ++checked;
    }
    // Every sample of every level of every chart.
    size_t samples = 0;
    for (const tc::AtlasChart& chart : atlas.charts)
    {
      for (int32_t d = 0; d <= chart.maxLevel; ++d)
      {
        samples += static_cast<size_t>(tc::gridVertexCount(d));
      }
    }
    EXPECT_EQ(checked, samples);
  }
}

TEST_F(AtlasIo, AnyNormalOfTheLatticeIsStoredAsItsCode)
{
  // Normals from all over the code square (its edges and corners, where the octahedral map
  // folds, the axes, and codes at random), a function of the position so that shared samples
  // stay identical: the writer finds the code of each, so the file is version 4 and exact.
  tc::Atlas atlas = latticeAtlas();
  const int32_t limit = 2047;
  const int32_t special[] = { -limit, -limit + 1, -1, 0, 1, limit - 1, limit };
  for (tc::AtlasImage& image : atlas.images)
  {
    for (size_t t = 0; t < image.data[0].size() / 3; ++t)
    {
      const float* p = &image.data[0][3 * t];
      const uint64_t h = hashOf({ bitsOf(p[0]), bitsOf(p[1]), bitsOf(p[2]) });
      int32_t u = static_cast<int32_t>(h % (2 * limit + 1)) - limit;
      int32_t v = static_cast<int32_t>((h >> 20) % (2 * limit + 1)) - limit;
      if ((h >> 40) % 2 == 0)
      {
        u = special[(h >> 41) % 7];
      }
      if ((h >> 44) % 2 == 0)
      {
        v =
          (h >> 45) % 2 ? special[(h >> 46) % 7] : (limit - std::abs(u)) * ((h >> 49) % 2 ? 1 : -1);
      }
      const std::array<float, 3> n = documentedNormal(12, u, v);
      if (bitsOf(p[0]) | bitsOf(p[1]) | bitsOf(p[2]))
      {
        std::copy(n.begin(), n.end(), &image.data[1][3 * t]);
      }
    }
  }
  ASSERT_NO_THROW(tc::validateAtlas(atlas));
  const std::string path = file("normals.exr");
  tc::writeAtlas(atlas, path);
  EXPECT_EQ(metadataOf(loadParts(path))["version"], 4);
  expectBitIdentical(atlas, tc::readAtlas(path));

  // One normal a float step off its code, or one position off the lattice: version 3, exact.
  for (size_t a = 0; a < 2; ++a)
  {
    tc::Atlas off = latticeAtlas();
    float* value = const_cast<float*>(
      tc::atlasSample(off, 0, static_cast<int32_t>(a), off.charts[0].maxLevel, 1, 1));
    value[1] = std::nextafter(value[1], HUGE_VALF);
    tc::writeAtlas(off, path);
    EXPECT_EQ(metadataOf(loadParts(path))["version"], 3) << "attribute " << a;
    expectBitIdentical(off, tc::readAtlas(path));
  }
}

TEST_F(AtlasIo, RefusesDamagedVersion4Files)
{
  const std::string good = file("good4.exr");
  const std::string bad = file("bad.exr");
  tc::writeAtlas(latticeAtlas(), good);
  const auto damaged = [&](const std::function<void(std::vector<ExrPart>&)>& edit)
  { return damagedCopyError(good, edit); };
  const auto metadataDamaged = [&](const std::function<void(Json&)>& edit)
  { return damagedCopyError(good, metadataEdit(edit)); };
  // A bad frame.
  std::string error = metadataDamaged([](Json& m) { m.erase("lattice"); });
  EXPECT_TRUE(mentions(error, "lacks the root.lattice")) << error;
  EXPECT_TRUE(mentions(error, bad)) << error;
  error = metadataDamaged([](Json& m) { m["lattice"]["extent"][1] = -1; });
  EXPECT_TRUE(mentions(error, "lattice.extent[1] = -1, out of range")) << error;
  error = metadataDamaged([](Json& m) { m["lattice"]["stepExponent"] = 5000; });
  EXPECT_TRUE(mentions(error, "lattice.stepExponent = 5000, out of range")) << error;
  error = metadataDamaged([](Json& m) { m["lattice"]["normalBits"] = 40; });
  EXPECT_TRUE(mentions(error, "lattice.normalBits = 40, out of range")) << error;
  error = metadataDamaged([](Json& m) { m["lattice"]["origin"] = { 1, 2 }; });
  EXPECT_TRUE(mentions(error, "lattice.origin that is not an array of 3 elements")) << error;
  // A smaller frame than the codes need: they decode outside it.
  error = metadataDamaged([](Json& m) { m["lattice"]["extent"][0] = 10; });
  EXPECT_TRUE(mentions(error, "outside the lattice's 0 .. 10")) << error;
  error = metadataDamaged([](Json& m) { m["images"][0]["texels"] = "all"; });
  EXPECT_TRUE(mentions(error, "which a file with a lattice does not have")) << error;

  // Damaged parts: codes as floats, residuals that leave the lattice, a changed residual.
  error = damaged(
    [](std::vector<ExrPart>& parts)
    {
      ExrPart& part = partNamed(parts, "Normal.0");
      part.header.channels() = Imf::ChannelList();
      for (const auto& [name, codes] : part.codes)
      {
        part.header.channels().insert(name, Imf::Channel(Imf::FLOAT));
        part.channels[name].assign(codes.size(), 0.0f);
      }
      part.codes.clear();
    });
  EXPECT_TRUE(
    mentions(error, "part 'Normal.0' channel 'U' is not full-resolution 32-bit unsigned integer"))
    << error;
  for (const char* name : { "Position.1", "Normal.2" })
  {
    error = damaged(
      [name](std::vector<ExrPart>& parts)
      {
        for (auto& [channel, codes] : partNamed(parts, name).codes)
        {
          std::fill(codes.begin(), codes.end(), 0xffffffffu);
        }
      });
    EXPECT_TRUE(mentions(error, std::string("part '") + name + "' holds a code of")) << error;
    EXPECT_TRUE(mentions(error, "outside the lattice")) << error;
  }
  error = damaged(
    [](std::vector<ExrPart>& parts) { partNamed(parts, "Position.0").codes["Y"][3] ^= 1u; });
  EXPECT_TRUE(mentions(error, "the texels of part 'Position.0' do not match their checksum"))
    << error;
}

TEST_F(AtlasIo, FlippedBytesOfVersion4AreRefusedOrHarmless)
{
  const tc::Atlas& atlas = latticeAtlas();
  const std::string good = file("good4.exr");
  tc::writeAtlas(atlas, good);
  ASSERT_EQ(metadataOf(loadParts(good))["version"], 4);
  const std::string bytes = fileBytes(good);
  const std::string bad = file("flipped4.exr");
  size_t refused = 0, tried = 0;
  for (size_t at = 0; at < bytes.size(); at += 1 + bytes.size() / 151, ++tried)
  {
    std::string damaged = bytes;
    damaged[at] = static_cast<char>(damaged[at] ^ 0x5a);
    writeBytes(bad, damaged);
    // Never silently different (nor a crash): a refusal naming the file or the same atlas.
    try
    {
      const tc::Atlas read = tc::readAtlas(bad);
      SCOPED_TRACE("byte " + std::to_string(at) + " flipped and read");
      expectBitIdentical(atlas, read);
    }
    catch (const tc::InputError& error)
    {
      ++refused;
      EXPECT_TRUE(mentions(error.what(), bad)) << error.what();
    }
  }
  std::cout << "[ figures  ] version 4: " << refused << " of " << tried
            << " single-byte flips refused (" << bytes.size() << "-byte file)\n";
  EXPECT_GT(refused, tried / 2);
}

TEST_F(AtlasIo, Version4ReportsProgressAndHonoursAbort)
{
  const tc::Atlas& atlas = latticeAtlas();
  const std::string path = file("progress4.exr");
  const auto stopHalfWay = [](double f) { return f < 0.5; };
  // One report per part at least: 2 attributes x 4 or more images.
  tctest::expectProgressAndAbort(
    [&](const tc::Progress& progress) { tc::writeAtlas(atlas, path, progress); }, 8, stopHalfWay);
  EXPECT_EQ(listing(), std::vector<std::string>{ "progress4.exr" });
  tctest::expectProgressAndAbort([&](const tc::Progress& progress)
    { expectBitIdentical(atlas, tc::readAtlas(path, progress)); },
    8, stopHalfWay);
}

TEST_F(AtlasIo, RefusesToWriteAnAtlasUnderAnotherExtension)
{
  // An atlas named like a mesh would be an OpenEXR file that mesh tools cannot open.
  for (const char* name : { "atlas.glb", "atlas.obj", "atlas", "atlas.exr.tmp" })
  {
    try
    {
      tc::writeAtlas(tetrahedronAtlas(1, true), file(name));
      ADD_FAILURE() << name << " was written";
    }
    catch (const tc::InputError& error)
    {
      EXPECT_NE(std::string(error.what()).find("named .exr"), std::string::npos) << error.what();
    }
  }
  EXPECT_TRUE(std::filesystem::is_empty(Folder));
  tc::writeAtlas(tetrahedronAtlas(1, true), file("UPPER.EXR"));
  EXPECT_TRUE(std::filesystem::exists(file("UPPER.EXR")));
}

// ------------------------------------------------------------------------------------------
// Version 5: textures

namespace
{
/// `atlas` with a TextureCoordinates attribute (every texel's first two position values) and
/// two textures of hashed bytes, one of 37 x 19 texels, one of a single texel.
tc::Atlas withTextures(tc::Atlas atlas)
{
  atlas.attributes.push_back({ tc::kAtlasTextureCoordinates, 2 });
  for (tc::AtlasImage& image : atlas.images)
  {
    std::vector<float> uv;
    for (size_t t = 0; t < image.data[0].size(); t += 3)
    {
      uv.push_back(image.data[0][t]);
      uv.push_back(image.data[0][t + 1]);
    }
    image.data.push_back(std::move(uv));
  }
  const auto texture = [](const char* name, const char* source, int32_t w, int32_t h)
  {
    tc::AtlasTexture out{ name, source, w, h, {} };
    for (int64_t b = 0; b < int64_t(w) * h * 4; ++b)
    {
      out.rgba.push_back(static_cast<uint8_t>(hashOf({ w, h, b }) >> 17));
    }
    return out;
  };
  atlas.textures.push_back(texture(tc::kAtlasBaseColorTexture, "checker.png", 37, 19));
  atlas.textures.push_back(texture("Extra", "embedded:1", 1, 1));
  return atlas;
}
} // namespace

TEST_F(AtlasIo, TexturesRoundTripBitExactWithAndWithoutALattice)
{
  for (const bool lattice : { true, false })
  {
    const tc::Atlas atlas = withTextures(lattice ? latticeAtlas() : tetrahedronAtlas(2, true));
    ASSERT_NO_THROW(tc::validateAtlas(atlas));
    const std::string path = file(lattice ? "lattice5.exr" : "float5.exr");
    tc::writeAtlas(atlas, path);
    expectBitIdentical(atlas, tc::readAtlas(path));
    const Json metadata = metadataOf(loadParts(path));
    EXPECT_EQ(metadata["version"], 5);
    EXPECT_EQ(metadata.contains("lattice"), lattice);
  }
  // Without textures the writer still writes version 4, which older readers read.
  tc::writeAtlas(latticeAtlas(), file("lattice4.exr"));
  EXPECT_EQ(metadataOf(loadParts(file("lattice4.exr")))["version"], 4);
}

TEST_F(AtlasIo, Version5FollowsTheDocumentedLayout)
{
  const tc::Atlas atlas = withTextures(latticeAtlas());
  const std::string path = file("textures.exr");
  tc::writeAtlas(atlas, path);
  std::vector<ExrPart> parts = loadParts(path);
  ASSERT_EQ(parts.size(), atlas.attributes.size() * atlas.images.size() + 2);
  // The texture parts come last, in the order of the metadata's list.
  EXPECT_EQ(parts[parts.size() - 2].header.name(), "BaseColor.texture");
  EXPECT_EQ(parts.back().header.name(), "Extra.texture");
  const Json metadata = metadataOf(parts);
  ASSERT_EQ(metadata["textures"].size(), 2u);
  for (size_t t = 0; t < 2; ++t)
  {
    const tc::AtlasTexture& texture = atlas.textures[t];
    const Json& entry = metadata["textures"][t];
    EXPECT_EQ(entry["name"], texture.name);
    EXPECT_EQ(entry["source"], texture.source);
    EXPECT_EQ(entry["width"], texture.width);
    EXPECT_EQ(entry["height"], texture.height);
    EXPECT_EQ(entry["crc32"],
      static_cast<uint32_t>(crc32(0L, reinterpret_cast<const Bytef*>(texture.rgba.data()),
        static_cast<uInt>(texture.rgba.size()))));
    ExrPart& part = partNamed(parts, texture.name + ".texture");
    const Imath::Box2i window = part.header.dataWindow();
    EXPECT_EQ(window.max.x + 1, texture.width);
    EXPECT_EQ(window.max.y + 1, texture.height);
    ASSERT_EQ(part.codes.size(), 1u);
    ASSERT_TRUE(part.channels.empty());
    // One UINT channel: R in the lowest byte, then G, B, A; pixel (x, y) is texel (x, y), row 0
    // the texture's bottom.
    const std::vector<uint32_t>& rgba = part.codes.at("RGBA");
    for (size_t i = 0; i < rgba.size(); ++i)
    {
      const uint8_t* b = texture.rgba.data() + 4 * i;
      ASSERT_EQ(rgba[i], b[0] | uint32_t(b[1]) << 8 | uint32_t(b[2]) << 16 | uint32_t(b[3]) << 24)
        << texture.name << " texel " << i;
    }
  }
}

TEST_F(AtlasIo, RefusesDamagedTextures)
{
  const std::string good = file("good5.exr");
  tc::writeAtlas(withTextures(tetrahedronAtlas(2, true)), good);
  const auto damaged = [&](const std::function<void(std::vector<ExrPart>&)>& edit)
  { return damagedCopyError(good, edit); };
  const auto metadataDamaged = [&](const std::function<void(Json&)>& edit)
  { return damagedCopyError(good, metadataEdit(edit)); };
  std::string error = damaged([](std::vector<ExrPart>& parts)
    { partNamed(parts, "BaseColor.texture").codes.at("RGBA")[40] ^= 0x100u; });
  EXPECT_TRUE(mentions(error, "'BaseColor.texture' do not match their checksum")) << error;
  error = damaged([](std::vector<ExrPart>& parts) { parts.pop_back(); });
  EXPECT_TRUE(mentions(error, "2 textures")) << error;
  error = metadataDamaged([](Json& m) { m["textures"][1]["name"] = "Other"; });
  EXPECT_TRUE(mentions(error, "part 'Other.texture' is missing")) << error;
  error = metadataDamaged([](Json& m) { m["textures"][0]["width"] = 38; });
  EXPECT_TRUE(mentions(error, "part 'BaseColor.texture' covers pixels (0, 0) .. (36, 18)"))
    << error;
  error = metadataDamaged([](Json& m) { m["textures"][0]["height"] = 0; });
  EXPECT_TRUE(mentions(error, "textures[0].height = 0, out of range")) << error;
  error = metadataDamaged([](Json& m) { m.erase("textures"); });
  EXPECT_TRUE(mentions(error, "lacks the root.textures")) << error;
  error = metadataDamaged([](Json& m) { m["textures"][1]["name"] = "BaseColor"; });
  EXPECT_FALSE(error.empty());
  error = metadataDamaged([](Json& m) { m["textures"][0]["source"] = 3; });
  EXPECT_TRUE(mentions(error, "textures[0].source that is not a string")) << error;
  // A texture part whose channel is float.
  error = damaged(
    [](std::vector<ExrPart>& parts)
    {
      ExrPart& part = partNamed(parts, "Extra.texture");
      part.codes.clear();
      part.header.channels() = Imf::ChannelList();
      part.header.channels().insert("RGBA", Imf::Channel(Imf::FLOAT));
      part.channels["RGBA"] = { 1.0f };
    });
  EXPECT_TRUE(mentions(error, "channel 'RGBA' is not full-resolution 32-bit unsigned integer"))
    << error;
}

// ------------------------------------------------------------------------------------------
// Version 6: the rig of a skinned atlas

namespace
{
/// `atlas` with a Skin attribute (joints of a 3-joint skeleton and weights hashed from the
/// sample's position, so that the copies of a shared side agree) and a rig whose
/// doubles have every bit set somewhere (hashed), with one animation of each kind of key.
tc::Atlas withRig(tc::Atlas atlas)
{
  atlas.attributes.push_back({ tc::kAtlasSkin, tc::kSkinValues });
  for (tc::AtlasImage& image : atlas.images)
  {
    std::vector<float> skin;
    for (size_t t = 0; t < image.data[0].size() / 3; ++t)
    {
      uint32_t bits[3];
      std::memcpy(bits, &image.data[0][3 * t], sizeof bits);
      const uint64_t h = hashOf({ bits[0], bits[1], bits[2] });
      for (int k = 0; k < tc::kMaxInfluences; ++k)
      {
        skin.push_back(static_cast<float>((h + k) % 3));
      }
      for (int k = 0; k < tc::kMaxInfluences; ++k)
      {
        skin.push_back(static_cast<float>((h >> (8 * k)) % 1000) / 1000.0f);
      }
    }
    image.data.push_back(std::move(skin));
  }
  const auto number = [](int64_t a, int64_t b) {
    return static_cast<double>(hashOf({ a, b })) / 3.0e18 - 1.7;
  };
  for (int32_t j = 0; j < 3; ++j)
  {
    tc::Joint joint;
    joint.name = "joint " + std::to_string(j);
    joint.parent = j - 1;
    for (int k = 0; k < 16; ++k)
    {
      joint.restLocal[k] = number(j, k);
      joint.inverseBind[k] = number(j, 100 + k);
    }
    atlas.rig.skeleton.joints.push_back(joint);
  }
  tc::Animation animation;
  animation.name = "wave";
  animation.duration = number(7, 7) + 3.0;
  animation.ticksPerSecond = 24;
  tc::JointTrack track;
  track.joint = 2;
  track.positionTimes = { 0.0, 0.1 + number(1, 1) / 10 };
  track.positions = { { number(2, 1), number(2, 2), number(2, 3) }, { 1, 2, 3 } };
  track.rotationTimes = { 0.25 };
  track.rotations = { { number(3, 0), number(3, 1), number(3, 2), number(3, 3) } };
  animation.tracks.push_back(track);
  atlas.rig.animations.push_back(animation);
  return atlas;
}
} // namespace

TEST_F(AtlasIo, ARigRoundTripsBitExactlyAsVersion6)
{
  const tc::Atlas atlas = withRig(latticeAtlas());
  ASSERT_NO_THROW(tc::validateAtlas(atlas));
  const std::string path = file("rig.exr");
  tc::writeAtlas(atlas, path);
  const tc::Atlas back = tc::readAtlas(path);
  expectBitIdentical(atlas, back);
  ASSERT_EQ(back.rig.skeleton.joints.size(), 3u);
  EXPECT_EQ(std::memcmp(back.rig.skeleton.joints[2].inverseBind.data(),
              atlas.rig.skeleton.joints[2].inverseBind.data(), 16 * sizeof(double)),
    0);
  const Json metadata = metadataOf(loadParts(path));
  EXPECT_EQ(metadata["version"], 6);
  EXPECT_FALSE(metadata.contains("textures"));
  // With textures too, still version 6.
  tc::writeAtlas(withTextures(atlas), file("rig_textures.exr"));
  expectBitIdentical(withTextures(atlas), tc::readAtlas(file("rig_textures.exr")));
}

TEST_F(AtlasIo, ItsRigReadsFromTheHeadersAlone)
{
  const tc::Atlas atlas = withRig(latticeAtlas());
  const std::string path = file("rig.exr");
  tc::writeAtlas(atlas, path);
  EXPECT_EQ(tc::encodeRig(tc::readAtlasRig(path)), tc::encodeRig(atlas.rig));
  tc::writeAtlas(latticeAtlas(), file("bare.exr"));
  EXPECT_TRUE(tc::readAtlasRig(file("bare.exr")).empty());
  const std::string text = file("not_an_atlas.exr");
  std::ofstream(text) << "not an atlas";
  EXPECT_THROW(tc::readAtlasRig(text), tc::InputError);
  EXPECT_THROW(tc::readAtlasRig(file("missing.exr")), tc::InputError);
}

TEST_F(AtlasIo, RefusesADamagedRig)
{
  const std::string good = file("rig.exr");
  tc::writeAtlas(withRig(latticeAtlas()), good);
  const std::string parent = damagedCopyError(
    good, metadataEdit([](Json& metadata) { metadata["rig"]["joints"][1]["parent"] = 2; }));
  EXPECT_TRUE(mentions(parent, "joints[1].parent")) << parent;
  const std::string track = damagedCopyError(good,
    metadataEdit(
      [](Json& metadata) { metadata["rig"]["animations"][0]["tracks"][0]["joint"] = 9; }));
  EXPECT_TRUE(mentions(track, "joint")) << track;
  const std::string gone =
    damagedCopyError(good, metadataEdit([](Json& metadata) { metadata.erase("rig"); }));
  EXPECT_TRUE(mentions(gone, "rig")) << gone;
}

TEST(AtlasSkin, ValidationNamesWhatIsWrong)
{
  tc::Atlas atlas = withRig(latticeAtlas());
  ASSERT_NO_THROW(tc::validateAtlas(atlas));
  tc::Atlas noRig = atlas;
  noRig.rig = {};
  EXPECT_THROW(tc::validateAtlas(noRig), tc::InputError);
  tc::Atlas badJoint = atlas;
  badJoint.images[0].data.back()[0] = 3.0f; // a skeleton of 3 joints: 0 .. 2
  EXPECT_THROW(tc::validateAtlas(badJoint), tc::InputError);
  tc::Atlas oneSide = atlas;
  // A shared side whose two copies of the skin differ: the corner of chart 0 is shared.
  const float* corner = tc::atlasSample(oneSide, 0,
    static_cast<int32_t>(atlas.attributes.size() - 1), oneSide.charts[0].maxLevel, 0, 0);
  const size_t at = static_cast<size_t>(corner - oneSide.images[0].data.back().data());
  oneSide.images[0].data.back()[at + 4] += 0.25f;
  EXPECT_THROW(tc::validateAtlas(oneSide), tc::InputError);
}

TEST(AtlasTextures, ValidationNamesWhatIsWrong)
{
  const tc::Atlas good = withTextures(tetrahedronAtlas(1, false));
  ASSERT_NO_THROW(tc::validateAtlas(good));
  const auto invalid = [&good](const std::function<void(tc::Atlas&)>& edit)
  {
    tc::Atlas atlas = good;
    edit(atlas);
    try
    {
      tc::validateAtlas(atlas);
    }
    catch (const tc::InputError& error)
    {
      return std::string(error.what());
    }
    return std::string();
  };
  std::string error = invalid([](tc::Atlas& a) { a.textures[0].rgba.pop_back(); });
  EXPECT_TRUE(mentions(error, "texture 0 ('BaseColor') holds 2811 bytes, not the 2812")) << error;
  error = invalid([](tc::Atlas& a) { a.textures[1].name = "BaseColor"; });
  EXPECT_TRUE(mentions(error, "has the name of texture 0")) << error;
  error = invalid([](tc::Atlas& a) { a.textures[1].name.clear(); });
  EXPECT_TRUE(mentions(error, "texture 1 has no name")) << error;
  error = invalid([](tc::Atlas& a) { a.textures[1].width = 70000; });
  EXPECT_TRUE(mentions(error, "size 70000 x 1")) << error;
  error = invalid([](tc::Atlas& a) { a.attributes.back().name = "UV"; });
  EXPECT_TRUE(mentions(error, "no attribute TextureCoordinates with 2 components")) << error;
  EXPECT_EQ(tc::findAttribute(good, tc::kAtlasTextureCoordinates), 2);
  EXPECT_EQ(tc::findAttribute(good, "Missing"), -1);
}
