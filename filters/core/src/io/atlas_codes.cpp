// SPDX-License-Identifier: BSD-3-Clause
#include "io/atlas_codes.h"

#include "tc/common/errors.h"

#include <algorithm>
#include <cstring>
#include <stdexcept>

namespace tc::detail
{
namespace
{
/// floor(s / 2): the rounded mean of two codes, the same for negative sums (normals).
int64_t floorHalf(int64_t s)
{
  return s >= 0 ? s / 2 : -((1 - s) / 2);
}

uint32_t zigzag(int64_t r)
{
  return static_cast<uint32_t>(r >= 0 ? 2 * r : -2 * r - 1);
}

int64_t unzigzag(uint32_t z)
{
  return (z & 1u) ? -static_cast<int64_t>(z / 2) - 1 : static_cast<int64_t>(z / 2);
}

/// Calls f(c, d, i, j, texel) for every new sample of image k (every sample of a chart's level
/// 0, the samples with i or j odd of a finer level), chart by chart, each level's samples row by
/// row: the order of a coded part.
template <class F>
void forEachNewSample(const Atlas& atlas, size_t k, F&& f)
{
  forEachImageSample(atlas, k,
    [&](int32_t c, int32_t d, int32_t i, int32_t j, size_t texel)
    {
      if (d == 0 || i % 2 != 0 || j % 2 != 0)
      {
        f(c, d, i, j, texel);
      }
    });
}

/// The prediction of a new sample's codes from the codes of the coarser image k + 1.
class Predictor
{
public:
  Predictor(const Atlas& atlas, size_t k, const std::vector<int32_t>& coarse, size_t comps)
    : Source(atlas)
    , Coarse(coarse)
    , CoarseWidth(k + 1 < atlas.images.size() ? atlas.images[k + 1].width : 0)
    , Comps(comps)
  {
  }

  /// Component x of the prediction of sample (i, j) of level d >= 1 of chart c: the rounded
  /// mean of the codes of the ends of the edge of level d - 1 whose middle it is, in the grid
  /// triangulation (rows j, diagonals from (i + 1, j) to (i, j + 1), as rebuildMesh draws them):
  /// i odd, j even: (i - 1, j), (i + 1, j); i even, j odd: (i, j - 1), (i, j + 1); both odd: the
  /// diagonal (i - 1, j + 1), (i + 1, j - 1). (The butterfly scheme's 8-point stencil predicts no
  /// better: at the finest levels the samples resolve the input's flat triangles.)
  int64_t operator()(int32_t c, int32_t d, int32_t i, int32_t j, size_t x) const
  {
    const AtlasChart& chart = Source.charts[static_cast<size_t>(c)];
    const bool iOdd = i % 2 != 0;
    const bool jOdd = j % 2 != 0;
    const std::array<int32_t, 4> ends = !jOdd ? std::array<int32_t, 4>{ i - 1, j, i + 1, j }
      : !iOdd                                 ? std::array<int32_t, 4>{ i, j - 1, i, j + 1 }
              : std::array<int32_t, 4>{ i - 1, j + 1, i + 1, j - 1 };
    int64_t sum = 0;
    for (int e = 0; e < 2; ++e)
    {
      const std::array<int32_t, 2> xy =
        atlasTexel(chart, d - 1, ends[2 * e] / 2, ends[2 * e + 1] / 2);
      sum +=
        Coarse[(static_cast<size_t>(xy[1]) * CoarseWidth + static_cast<size_t>(xy[0])) * Comps + x];
    }
    return floorHalf(sum);
  }

private:
  const Atlas& Source;
  const std::vector<int32_t>& Coarse;
  size_t CoarseWidth;
  size_t Comps;
};

/// The bytes of the values of rows [y0, y1) of a part `width` texels wide, `comps` values each,
/// as OpenEXR lays out a scan-line block: row by row, channel by channel (the channels' names
/// are sorted like their components), value by value, little-endian.
std::vector<uint8_t> blockBytes(
  const std::vector<uint32_t>& values, size_t width, size_t comps, size_t y0, size_t y1)
{
  std::vector<uint8_t> bytes(4 * (y1 - y0) * comps * width);
  size_t o = 0;
  for (size_t y = y0; y < y1; ++y)
  {
    for (size_t c = 0; c < comps; ++c)
    {
      for (size_t x = 0; x < width; ++x, o += 4)
      {
        std::memcpy(&bytes[o], &values[(y * width + x) * comps + c], 4);
      }
    }
  }
  return bytes;
}

/// The inverse of blockBytes: the block's bytes back into `values`.
void setBlockBytes(const std::vector<uint8_t>& bytes, size_t width, size_t comps, size_t y0,
  size_t y1, std::vector<uint32_t>& values)
{
  size_t o = 0;
  for (size_t y = y0; y < y1; ++y)
  {
    for (size_t c = 0; c < comps; ++c)
    {
      for (size_t x = 0; x < width; ++x, o += 4)
      {
        std::memcpy(&values[(y * width + x) * comps + c], &bytes[o], 4);
      }
    }
  }
}

/// The byte planes of rows [y0, y1): per channel, byte b = 0 .. 3 of every value of the block
/// (row by row).
std::vector<uint8_t> blockPlanes(
  const std::vector<uint32_t>& values, size_t width, size_t comps, size_t y0, size_t y1)
{
  std::vector<uint8_t> planes(4 * (y1 - y0) * comps * width);
  size_t o = 0;
  for (size_t c = 0; c < comps; ++c)
  {
    for (int b = 0; b < 4; ++b)
    {
      for (size_t t = y0 * width; t < y1 * width; ++t)
      {
        planes[o++] = static_cast<uint8_t>(values[t * comps + c] >> (8 * b));
      }
    }
  }
  return planes;
}

/// The inverse of blockPlanes.
void setBlockPlanes(const std::vector<uint8_t>& planes, size_t width, size_t comps, size_t y0,
  size_t y1, std::vector<uint32_t>& values)
{
  size_t o = 0;
  for (size_t c = 0; c < comps; ++c)
  {
    for (size_t t = y0 * width; t < y1 * width; ++t)
    {
      values[t * comps + c] = 0;
    }
    for (int b = 0; b < 4; ++b)
    {
      for (size_t t = y0 * width; t < y1 * width; ++t)
      {
        values[t * comps + c] |= static_cast<uint32_t>(planes[o++]) << (8 * b);
      }
    }
  }
}

/// OpenEXR's ZIP predictor on a block: the bytes interleaved (even offsets first, then odd),
/// then each byte replaced by its difference to the one before, + 128 (mod 256).
std::vector<uint8_t> zipPredicted(const std::vector<uint8_t>& bytes)
{
  const size_t half = (bytes.size() + 1) / 2;
  std::vector<uint8_t> t(bytes.size());
  for (size_t m = 0; m < bytes.size(); ++m)
  {
    t[m % 2 == 0 ? m / 2 : half + m / 2] = bytes[m];
  }
  for (size_t m = t.size(); m-- > 1;)
  {
    t[m] = static_cast<uint8_t>(t[m] - t[m - 1] + 128);
  }
  return t;
}

/// The inverse of zipPredicted.
std::vector<uint8_t> zipUnpredicted(std::vector<uint8_t> t)
{
  for (size_t m = 1; m < t.size(); ++m)
  {
    t[m] = static_cast<uint8_t>(t[m] + t[m - 1] - 128);
  }
  const size_t half = (t.size() + 1) / 2;
  std::vector<uint8_t> bytes(t.size());
  for (size_t m = 0; m < bytes.size(); ++m)
  {
    bytes[m] = t[m % 2 == 0 ? m / 2 : half + m / 2];
  }
  return bytes;
}

/// The codes of the twin of sample (i, j) of level d of chart c in image k, the same sample of the
/// chart across the side that holds it (gridSide's side; a corner's first), when the stream
/// reaches the twin first: that chart has level d in a coarser image, or in image k with a lower
/// index. Null otherwise. Positions only: validateAtlas makes shared sides' positions
/// bit-identical, whereas a feature side's normals differ between its charts. `codes` holds
/// the position codes of the images before k, `current` those of image k so far.
const int32_t* earlierTwin(const Atlas& atlas, const std::vector<std::vector<int32_t>>& codes,
  const std::vector<int32_t>& current, size_t k, int32_t c, int32_t d, int32_t i, int32_t j)
{
  const int32_t n = int32_t(1) << d;
  const std::array<int32_t, 2> side = gridSide(i, j, n);
  if (side[0] < 0)
  {
    return nullptr;
  }
  const AtlasChart& chart = atlas.charts[static_cast<size_t>(c)];
  const int32_t nb = chart.neighborChart[static_cast<size_t>(side[0])];
  const AtlasChart& other = atlas.charts[static_cast<size_t>(nb)];
  if (other.maxLevel < d)
  {
    return nullptr;
  }
  const size_t kk = static_cast<size_t>(other.maxLevel - d);
  if (kk < k || (kk == k && nb >= c))
  {
    return nullptr;
  }
  const std::array<int32_t, 2> ij =
    sidePoint(chart.neighborSide[static_cast<size_t>(side[0])], n - side[1], n);
  const std::array<int32_t, 2> xy = atlasTexel(other, d, ij[0], ij[1]);
  const size_t texel = static_cast<size_t>(xy[1]) * static_cast<size_t>(atlas.images[kk].width) +
    static_cast<size_t>(xy[0]);
  return (kk == k ? current : codes[kk]).data() + 3 * texel;
}

/// Stores the codes of attribute a of image k in `store` (per attribute, per image) for the
/// images after it: a finer image predicts from them, a finer position may be a twin of one of
/// any coarser image. Normals are needed by image k - 1 only: those of image k + 1 go.
void keepCodes(std::vector<std::vector<std::vector<int32_t>>>& store, size_t a, size_t k,
  std::vector<int32_t> codes)
{
  store[a][k] = std::move(codes);
  if (a != 0 && k + 1 < store[a].size())
  {
    std::vector<int32_t>().swap(store[a][k + 1]);
  }
}

/// The codes of attribute a (< kCodedAttributes) of the chart samples of image k, 0 elsewhere;
/// false when one does not decode back to its float exactly.
bool imageCodes(
  const Atlas& atlas, const AtlasLattice& lattice, size_t k, size_t a, std::vector<int32_t>& codes)
{
  const AtlasImage& image = atlas.images[k];
  const size_t comps = static_cast<size_t>(codeComponents(a));
  codes.assign(static_cast<size_t>(image.width) * static_cast<size_t>(image.height) * comps, 0);
  const float* data = image.data[a].data();
  bool exact = true;
  forEachImageSample(atlas, k,
    [&](int32_t, int32_t, int32_t, int32_t, size_t texel)
    {
      const float* value = data + 3 * texel;
      float decoded[3] = { 0.0f, 0.0f, 0.0f };
      int32_t* code = codes.data() + comps * texel;
      if (a == 0)
      {
        std::array<int64_t, 3> q{};
        if (!exact || !encodePosition(lattice.frame, value, q))
        {
          exact = false;
          return;
        }
        for (int x = 0; x < 3; ++x)
        {
          code[x] = static_cast<int32_t>(q[static_cast<size_t>(x)]);
          decoded[x] = decodeCoordinate(lattice.frame, x, q[static_cast<size_t>(x)]);
        }
      }
      else
      {
        std::array<int32_t, 2> uv{};
        if (!exact || !encodeNormal(lattice.normalBits, value, uv))
        {
          exact = false;
          return;
        }
        code[0] = uv[0];
        code[1] = uv[1];
        decodeNormal(lattice.normalBits, uv[0], uv[1], decoded);
      }
      exact = std::memcmp(decoded, value, sizeof(decoded)) == 0;
    });
  return exact;
}
} // namespace

int32_t codeComponents(size_t a)
{
  return a == 0 ? 3 : 2;
}

std::vector<std::string> codeChannelNames(size_t a)
{
  return a == 0 ? std::vector<std::string>{ "X", "Y", "Z" } : std::vector<std::string>{ "U", "V" };
}

std::optional<AtlasLattice> exactLattice(
  const Atlas& atlas, const std::vector<ImageLayout>& layouts)
{
  for (const ImageLayout& layout : layouts)
  {
    if (!layout.compact)
    {
      return std::nullopt;
    }
  }
  const std::optional<PositionFrame> frame = positionFrame(atlas);
  if (!frame)
  {
    return std::nullopt;
  }
  const AtlasLattice lattice{ *frame, kNormalBits };
  std::vector<int32_t> codes;
  for (size_t k = 0; k < atlas.images.size(); ++k)
  {
    for (size_t a = 0; a < kCodedAttributes; ++a)
    {
      if (!imageCodes(atlas, lattice, k, a, codes))
      {
        return std::nullopt;
      }
    }
  }
  return lattice;
}

std::vector<uint32_t> planeValues(std::vector<uint32_t> residuals, int32_t width, size_t comps)
{
  const size_t w = static_cast<size_t>(width);
  const size_t rows = residuals.size() / (w * comps);
  for (size_t y0 = 0; y0 < rows; y0 += kPlaneBlockRows)
  {
    const size_t y1 = std::min(rows, y0 + kPlaneBlockRows);
    setBlockBytes(
      zipUnpredicted(blockPlanes(residuals, w, comps, y0, y1)), w, comps, y0, y1, residuals);
  }
  return residuals;
}

std::vector<uint32_t> planeResiduals(std::vector<uint32_t> values, int32_t width, size_t comps)
{
  const size_t w = static_cast<size_t>(width);
  const size_t rows = values.size() / (w * comps);
  for (size_t y0 = 0; y0 < rows; y0 += kPlaneBlockRows)
  {
    const size_t y1 = std::min(rows, y0 + kPlaneBlockRows);
    setBlockPlanes(zipPredicted(blockBytes(values, w, comps, y0, y1)), w, comps, y0, y1, values);
  }
  return values;
}

CodeWriter::CodeWriter(const Atlas& atlas, const AtlasLattice& lattice)
  : Source(atlas)
  , Lattice(lattice)
  , Codes(kCodedAttributes, std::vector<std::vector<int32_t>>(atlas.images.size()))
{
}

std::vector<uint32_t> CodeWriter::residuals(size_t k, size_t a, const ImageLayout& layout)
{
  const AtlasImage& image = Source.images[k];
  const size_t comps = static_cast<size_t>(codeComponents(a));
  std::vector<int32_t> codes;
  if (!imageCodes(Source, Lattice, k, a, codes))
  {
    throw std::logic_error("atlas_codes: a texel does not decode exactly from its code");
  }
  std::vector<uint32_t> out(
    static_cast<size_t>(image.width) * static_cast<size_t>(layout.partHeight) * comps, 0);
  static const std::vector<int32_t> none;
  const Predictor predict(Source, k, k + 1 < Codes[a].size() ? Codes[a][k + 1] : none, comps);
  std::array<int64_t, 3> previous{ 0, 0, 0 };
  size_t o = 0;
  forEachNewSample(Source, k,
    [&](int32_t c, int32_t d, int32_t i, int32_t j, size_t texel)
    {
      const bool twin = a == 0 && earlierTwin(Source, Codes[0], codes, k, c, d, i, j);
      for (size_t x = 0; x < comps; ++x)
      {
        const int64_t code = codes[texel * comps + x];
        if (!twin)
        {
          out[o++] = zigzag(code - (d == 0 ? previous[x] : predict(c, d, i, j, x)));
        }
        previous[x] = code;
      }
    });
  keepCodes(Codes, a, k, std::move(codes));
  return out;
}

CodeReader::CodeReader(const Atlas& atlas, const AtlasLattice& lattice)
  : Source(atlas)
  , Lattice(lattice)
  , Codes(kCodedAttributes, std::vector<std::vector<int32_t>>(atlas.images.size()))
{
}

void CodeReader::decode(size_t k, size_t a, const ImageLayout& layout,
  const std::vector<uint32_t>& residuals, const std::string& path, const std::string& part,
  std::vector<float>& data)
{
  const size_t comps = static_cast<size_t>(codeComponents(a));
  std::vector<int32_t> codes(layout.roles.size() * comps, 0);
  static const std::vector<int32_t> none;
  const std::vector<int32_t>& coarse = k + 1 < Codes[a].size() ? Codes[a][k + 1] : none;
  const int64_t limit = normalLimit(Lattice.normalBits);
  const Predictor predict(Source, k, coarse, comps);
  std::array<int64_t, 3> previous{ 0, 0, 0 };
  size_t o = 0;
  forEachNewSample(Source, k,
    [&](int32_t c, int32_t d, int32_t i, int32_t j, size_t texel)
    {
      const int32_t* twin = a == 0 ? earlierTwin(Source, Codes[0], codes, k, c, d, i, j) : nullptr;
      for (size_t x = 0; x < comps; ++x)
      {
        if (twin)
        {
          codes[texel * comps + x] = twin[x];
          previous[x] = twin[x];
          continue;
        }
        const int64_t code =
          (d == 0 ? previous[x] : predict(c, d, i, j, x)) + unzigzag(residuals[o++]);
        const int64_t low = a == 0 ? 0 : -limit;
        const int64_t high = a == 0 ? Lattice.frame.extent[x] : limit;
        if (code < low || code > high)
        {
          throw InputError("cannot read atlas " + path + ": part '" + part + "' holds a code of " +
            std::to_string(code) + ", outside the lattice's " + std::to_string(low) + " .. " +
            std::to_string(high) + "; the file is damaged (write the atlas again)");
        }
        codes[texel * comps + x] = static_cast<int32_t>(code);
        previous[x] = code;
      }
    });
  // Inherited samples repeat their coarser copy; then every chart sample's floats.
  const size_t coarseWidth = k + 1 < Source.images.size() ? Source.images[k + 1].width : 0;
  forEachImageSample(Source, k,
    [&](int32_t c, int32_t d, int32_t i, int32_t j, size_t texel)
    {
      if (d >= 1 && i % 2 == 0 && j % 2 == 0)
      {
        const std::array<int32_t, 2> xy =
          atlasTexel(Source.charts[static_cast<size_t>(c)], d - 1, i / 2, j / 2);
        const size_t from = static_cast<size_t>(xy[1]) * coarseWidth + static_cast<size_t>(xy[0]);
        std::copy_n(coarse.begin() + static_cast<std::ptrdiff_t>(from * comps), comps,
          codes.begin() + static_cast<std::ptrdiff_t>(texel * comps));
      }
      const int32_t* code = codes.data() + texel * comps;
      float* value = data.data() + 3 * texel;
      if (a == 0)
      {
        for (int x = 0; x < 3; ++x)
        {
          value[x] = decodeCoordinate(Lattice.frame, x, code[x]);
        }
      }
      else
      {
        decodeNormal(Lattice.normalBits, code[0], code[1], value);
      }
    });
  keepCodes(Codes, a, k, std::move(codes));
}
} // namespace tc::detail
