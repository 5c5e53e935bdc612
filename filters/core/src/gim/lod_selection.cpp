// SPDX-License-Identifier: BSD-3-Clause
#include "tc/gim/lod_selection.h"

#include "tc/common/errors.h"
#include "tc/common/parallel.h"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <limits>
#include <string>

namespace tc
{
namespace
{
/// Charts per block: the unit of vectorized work and of parallel scheduling. The block's scratch
/// arrays live on the stack (selectLevels allocates nothing).
constexpr int32_t kBlock = 256;
/// From this many charts on, blocks run in parallel; below it a fork-join costs more than it saves.
constexpr int32_t kParallelCharts = 16384;

constexpr float kInf = std::numeric_limits<float>::infinity();

/// What one call needs per chart, in float, computed once per call.
struct Frame
{
  float column[4][4];  ///< worldToClip by columns: column[k][r] = M(r, k)
  float levelScale;    ///< 2^(2 bias - 1): eq. (7)'s bias, its +1/2 rounding and log4(1/4) (below)
  float pixelsPerNdc2; ///< width * height / 4: pixels^2 per unit of area in normalized device
                       ///< coordinates
  float errorPixels2;  ///< errorPixels^2, 0 when the error mode is off
  int32_t roundedBias; ///< the bias in error mode
  int32_t cullMask;    ///< -1 (all bits) when culling, else 0
  bool errorMode;
};

/// Homogeneous clip coordinates of a block: per chart 16 floats, M c0 (x, y, z, w) with the
/// translation, then M a_k for k = 1, 2, 3 without it (corner k is M c0 + M a_k). Written per
/// chart as four 4-vectors so that the compiler vectorizes it; the box's 12 floats per chart are
/// a group it cannot load as lanes.
void transformBlock(const float* boxes, const Frame& frame, int32_t count, float* clip)
{
  const float(&col)[4][4] = frame.column;
  for (int32_t i = 0; i < count; ++i)
  {
    const float* b = boxes + static_cast<size_t>(i) * 12;
    float* o = clip + static_cast<size_t>(i) * 16;
    for (int r = 0; r < 4; ++r)
    {
      o[r] = col[0][r] * b[0] + col[1][r] * b[1] + col[2][r] * b[2] + col[3][r];
    }
    for (int k = 0; k < 3; ++k)
    {
      for (int r = 0; r < 4; ++r)
      {
        o[4 + 4 * k + r] =
          col[0][r] * b[3 + 3 * k] + col[1][r] * b[4 + 3 * k] + col[2][r] * b[5 + 3 * k];
      }
    }
  }
}

/// The rules of lod_selection.h for a block, from its clip coordinates. Writes the level of each
/// chart by rules 1 to 3 and the area mode, and, for the error mode, the projected area in
/// normalized device coordinates and whether the chart may be refined by it (no rule 1 to 3
/// applied).
/// Every choice is a mask or a select on values computed unconditionally: the compiler
/// if-converts and vectorizes the loop only when no arm is evaluated conditionally.
void rulesBlock(const float* clip, const float* worldAreas, const int32_t* maxLevels,
  const Frame& frame, int32_t count, int32_t* levels, float* projectedArea, int32_t* refinable)
{
  for (int32_t i = 0; i < count; ++i)
  {
    const float* t = clip + static_cast<size_t>(i) * 16;
    const float x0 = t[0], y0 = t[1], z0 = t[2], w0 = t[3];
    float xa[3], ya[3], za[3], wa[3];
    for (int k = 0; k < 3; ++k)
    {
      xa[k] = t[4 + 4 * k];
      ya[k] = t[5 + 4 * k];
      za[k] = t[6 + 4 * k];
      wa[k] = t[7 + 4 * k];
    }

    // Rule 1: the largest value over the 8 corners of g = w +- x, w +- y, w +- z is g(c0) plus
    // the positive parts of g(a_k); the box is outside a plane when that is negative.
    float px = w0 + x0, nx = w0 - x0, py = w0 + y0, ny = w0 - y0, pz = w0 + z0, nz = w0 - z0;
    for (int k = 0; k < 3; ++k)
    {
      px += std::max(0.0f, wa[k] + xa[k]);
      nx += std::max(0.0f, wa[k] - xa[k]);
      py += std::max(0.0f, wa[k] + ya[k]);
      ny += std::max(0.0f, wa[k] - ya[k]);
      pz += std::max(0.0f, wa[k] + za[k]);
      nz += std::max(0.0f, wa[k] - za[k]);
    }
    const float lowest = std::min(std::min(std::min(px, nx), std::min(py, ny)), std::min(pz, nz));
    const int32_t culledMask = -static_cast<int32_t>(lowest < 0.0f) & frame.cullMask;

    // Rule 2: the smallest w over the corners, against a threshold relative to the box's extent.
    const float minW = w0 + std::min(0.0f, wa[0]) + std::min(0.0f, wa[1]) + std::min(0.0f, wa[2]);
    const float wScale = std::fabs(w0) + std::fabs(wa[0]) + std::fabs(wa[1]) + std::fabs(wa[2]);
    const int32_t nearMask = -static_cast<int32_t>(minW <= kLodNearEpsilon * wScale);

    // Rule 3.
    const float worldArea = worldAreas[i];
    const int32_t degenerateMask = -static_cast<int32_t>(!(worldArea > 0.0f));

    // Eq. (6) in normalized device coordinates: ĉ_k - ĉ_0 = (x_a w0 - x0 w_a) / (w0 w_k), free
    // of the cancellation of subtracting two projected points. Where rule 2 applies these are
    // meaningless (even inf or NaN); the masks discard them.
    const float inv0 = 1.0f / w0;
    float dx[3], dy[3];
    for (int k = 0; k < 3; ++k)
    {
      const float scale = inv0 / (w0 + wa[k]);
      dx[k] = (xa[k] * w0 - x0 * wa[k]) * scale;
      dy[k] = (ya[k] * w0 - y0 * wa[k]) * scale;
    }
    const float areaNdc = std::fabs(dx[0] * dy[1] - dy[0] * dx[1]) +
      std::fabs(dx[0] * dy[2] - dy[0] * dx[2]) + std::fabs(dx[1] * dy[2] - dy[1] * dx[2]);

    // Eq. (7) with min. A / (width height) = areaNdc / 4, so the unclamped level is
    //   floor(maxLevel + log2(areaNdc) / 2 - 1 + bias + 1/2) = floor(log2(u) / 2),
    //   u = areaNdc 4^maxLevel 2^(2 bias - 1),
    // and floor(log2(u) / 2) = floor(floor(log2(u)) / 2): half the binary exponent of u, rounded
    // down (an arithmetic shift). No logarithm is evaluated, and the level boundaries are exact
    // powers of 4 of u. Zero and denormal u have exponent
    // -127 and go to level 0; an overflow to inf has exponent 128 and goes to maxLevel; NaN
    // (areaNdc > 0 fails) goes to 0.
    const int32_t maxLevel = maxLevels[i];
    // 4^maxLevel built from its exponent bits (a per-lane variable shift would not vectorize).
    const int32_t powerBits = (127 + 2 * maxLevel) << 23;
    float power;
    std::memcpy(&power, &powerBits, sizeof power);
    const float u = areaNdc * frame.levelScale * power;
    int32_t bits;
    std::memcpy(&bits, &u, sizeof bits);
    const int32_t exponent = ((bits >> 23) & 0xff) - 127;
    const int32_t positiveMask = -static_cast<int32_t>(areaNdc > 0.0f);
    const int32_t areaLevel = std::min(std::max(exponent >> 1, 0), maxLevel) & positiveMask;

    // Rules in order: culled (-1, all bits), else near (maxLevel), else degenerate (0).
    int32_t chosen = areaLevel & ~degenerateMask;
    chosen = (chosen & ~nearMask) | (maxLevel & nearMask);
    levels[i] = chosen | culledMask;
    projectedArea[i] = areaNdc;
    refinable[i] = ~(culledMask | nearMask | degenerateMask);
  }
}

/// Error mode for a block: the smallest d with levelError[d] s <= errorPixels, compared as
/// levelError[d]^2 s^2 <= errorPixels^2 (both sides are non-negative) so that no square root is
/// taken. Levels beyond maxLevel hold +inf and never pass (inf * 0 is NaN and fails too).
/// Charts without measured errors (levelError[0] = +inf) keep their area-mode level.
void errorBlock(const float* errors, int32_t stride, const float* worldAreas,
  const int32_t* maxLevels, const float* projectedArea, const int32_t* refinable,
  const Frame& frame, int32_t count, int32_t* levels)
{
  // s^2 = A / worldArea in pixels^2 per world unit^2 (inf or NaN where worldArea is 0: those
  // charts are not refinable).
  float magnification2[kBlock];
  for (int32_t i = 0; i < count; ++i)
  {
    magnification2[i] = projectedArea[i] * frame.pixelsPerNdc2 / worldAreas[i];
  }
  // Level by level, from the finest down, over the whole block: the loop over charts vectorizes
  // (one strided load per chart and level), where a loop over one chart's few levels would not.
  int32_t smallest[kBlock];
  for (int32_t i = 0; i < count; ++i)
  {
    smallest[i] = maxLevels[i];
  }
  const float target2 = frame.errorPixels2;
  for (int32_t d = stride - 1; d >= 0; --d)
  {
    for (int32_t i = 0; i < count; ++i)
    {
      const float e = errors[i * stride + d];
      smallest[i] = e * e * magnification2[i] <= target2 ? d : smallest[i];
    }
  }
  for (int32_t i = 0; i < count; ++i)
  {
    const int32_t biased = std::min(std::max(smallest[i] + frame.roundedBias, 0), maxLevels[i]);
    const int32_t measuredMask = -static_cast<int32_t>(errors[i * stride] < kInf);
    const int32_t keepMask = ~(measuredMask & refinable[i]);
    levels[i] = (levels[i] & keepMask) | (biased & ~keepMask);
  }
}

/// Levels of charts [begin, end), end - begin <= kBlock. Scratch on the stack (about 22 KB).
void selectBlock(const LodCharts& charts, const float* box, const float* worldArea,
  const Frame& frame, int32_t begin, int32_t end, int32_t* levels)
{
  alignas(16) float clip[kBlock * 16];
  float projectedArea[kBlock];
  int32_t refinable[kBlock];
  const int32_t count = end - begin;
  transformBlock(box + static_cast<size_t>(begin) * 12, frame, count, clip);
  rulesBlock(clip, worldArea + begin, charts.maxLevel.data() + begin, frame, count, levels + begin,
    projectedArea, refinable);
  if (frame.errorMode && charts.stride > 0)
  {
    errorBlock(
      charts.levelError.data() + static_cast<size_t>(begin) * static_cast<size_t>(charts.stride),
      charts.stride, worldArea + begin, charts.maxLevel.data() + begin, projectedArea, refinable,
      frame, count, levels + begin);
  }
}

/// Throws unless the arrays of `charts` agree on #C and stride.
void checkCharts(const LodCharts& charts)
{
  const size_t n = charts.maxLevel.size();
  if (n > static_cast<size_t>(std::numeric_limits<int32_t>::max()) || charts.box.size() != 12 * n ||
    charts.worldArea.size() != n || charts.neighbor.size() != 3 * n || charts.stride < 0 ||
    charts.levelError.size() != static_cast<size_t>(charts.stride) * n)
  {
    throw InputError("LOD selection: the chart arrays disagree (want box #C x 12, worldArea #C, "
                     "neighbor #C x 3, levelError #C x stride for #C = maxLevel.size() = " +
      std::to_string(n) + "); build them with LodCharts::fromAtlas");
  }
}
} // namespace

LodCharts LodCharts::fromAtlas(const Atlas& atlas)
{
  const size_t n = atlas.charts.size();
  LodCharts out;
  out.stride = std::max(atlas.maxLevel(), -1) + 1;
  out.box.resize(12 * n);
  out.worldArea.resize(n);
  out.maxLevel.resize(n);
  out.levelError.assign(static_cast<size_t>(out.stride) * n, kInf);
  out.neighbor.resize(3 * n);
  for (size_t c = 0; c < n; ++c)
  {
    const AtlasChart& chart = atlas.charts[c];
    if (chart.maxLevel < 0 || chart.maxLevel > kLodMaxLevel)
    {
      throw InputError("LOD selection: chart " + std::to_string(c) + " has maxLevel " +
        std::to_string(chart.maxLevel) + "; levels must lie in [0, " +
        std::to_string(kLodMaxLevel) + "] (4 bits each in the draw list)");
    }
    if (!chart.levelError.empty() &&
      chart.levelError.size() != static_cast<size_t>(chart.maxLevel) + 1)
    {
      throw InputError("LOD selection: chart " + std::to_string(c) + " has " +
        std::to_string(chart.levelError.size()) + " level errors for maxLevel " +
        std::to_string(chart.maxLevel) + "; want maxLevel + 1 of them, or none");
    }
    out.maxLevel[c] = chart.maxLevel;
    // Axes in double before rounding, so that a box far from the origin keeps its size.
    double axes[3][3];
    float* b = out.box.data() + 12 * c;
    for (int i = 0; i < 3; ++i)
    {
      b[i] = static_cast<float>(chart.box[static_cast<size_t>(i)]);
    }
    for (int k = 0; k < 3; ++k)
    {
      for (int i = 0; i < 3; ++i)
      {
        axes[k][i] =
          chart.box[static_cast<size_t>(3 * (k + 1) + i)] - chart.box[static_cast<size_t>(i)];
        b[3 + 3 * k + i] = static_cast<float>(axes[k][i]);
      }
    }
    // Eq. (6) before projection: the areas of the three faces at c0.
    double area = 0.0;
    for (int p = 0; p < 3; ++p)
    {
      const double* u = axes[p == 2 ? 1 : 0];
      const double* v = axes[p == 0 ? 1 : 2];
      const double cx = u[1] * v[2] - u[2] * v[1];
      const double cy = u[2] * v[0] - u[0] * v[2];
      const double cz = u[0] * v[1] - u[1] * v[0];
      area += std::sqrt(cx * cx + cy * cy + cz * cz);
    }
    out.worldArea[c] = static_cast<float>(area);
    for (size_t d = 0; d < chart.levelError.size(); ++d)
    {
      out.levelError[c * static_cast<size_t>(out.stride) + d] =
        static_cast<float>(chart.levelError[d]);
    }
    for (int k = 0; k < 3; ++k)
    {
      const int32_t nb = chart.neighborChart[static_cast<size_t>(k)];
      if (nb < -1 || nb >= static_cast<int32_t>(n))
      {
        throw InputError("LOD selection: chart " + std::to_string(c) + " names chart " +
          std::to_string(nb) + " across side " + std::to_string(k) + ", but the atlas has " +
          std::to_string(n) + " charts");
      }
      out.neighbor[3 * c + static_cast<size_t>(k)] = nb;
    }
  }
  return out;
}

void selectLevels(
  const LodCharts& charts, const LodView& view, const LodOptions& options, int32_t* levels)
{
  selectLevels(charts, charts.box.data(), charts.worldArea.data(), view, options, levels);
}

void selectLevels(const LodCharts& charts, const float* box, const float* worldArea,
  const LodView& view, const LodOptions& options, int32_t* levels)
{
  checkCharts(charts);
  if (!(view.width > 0.0) || !(view.height > 0.0))
  {
    throw InputError("LOD selection: the viewport is " + std::to_string(view.width) + " x " +
      std::to_string(view.height) + " pixels; set LodView::width and height to its size");
  }
  Frame frame{};
  for (int r = 0; r < 4; ++r)
  {
    for (int k = 0; k < 4; ++k)
    {
      frame.column[k][r] = static_cast<float>(view.worldToClip[static_cast<size_t>(4 * r + k)]);
    }
  }
  frame.levelScale = static_cast<float>(std::exp2(2.0 * options.bias - 1.0));
  frame.pixelsPerNdc2 = static_cast<float>(view.width * view.height / 4.0);
  frame.errorMode = options.errorPixels > 0.0;
  frame.errorPixels2 =
    frame.errorMode ? static_cast<float>(options.errorPixels * options.errorPixels) : 0.0f;
  frame.roundedBias = static_cast<int32_t>(std::lround(options.bias));
  frame.cullMask = options.cull ? -1 : 0;

  const int32_t n = charts.size();
  const int32_t blocks = (n + kBlock - 1) / kBlock;
  const auto block = [&](int64_t b)
  {
    const int32_t begin = static_cast<int32_t>(b) * kBlock;
    selectBlock(charts, box, worldArea, frame, begin, std::min(n, begin + kBlock), levels);
  };
  if (n >= kParallelCharts)
  {
    // One fork-join over all blocks (steps = 1): nothing to report between them.
    parallel_for(blocks, block, Progress(), 1);
  }
  else
  {
    for (int32_t b = 0; b < blocks; ++b)
    {
      block(b);
    }
  }
}

namespace
{
/// Per-entry cursor of the counting sort, one slot per level and one for culled charts.
using LevelCursor = std::array<int64_t, kLodMaxLevel + 2>;

/// The chart arrays a draw list reads: a stride that packs in 4 bits, neighbours that are -1
/// or charts, maxLevel in [0, stride).
void checkDrawListCharts(const LodCharts& charts, int32_t instances)
{
  checkCharts(charts);
  if (instances < 0)
  {
    throw InputError("LOD draw list: " + std::to_string(instances) + " instances");
  }
  const int32_t n = charts.size();
  const int32_t stride = charts.stride;
  if (stride > kLodMaxLevel + 1)
  {
    throw InputError("LOD draw list: stride " + std::to_string(stride) +
      " exceeds the 4 bits of a packed level (at most " + std::to_string(kLodMaxLevel + 1) + ")");
  }
  for (int32_t c = 0; c < n; ++c)
  {
    const int32_t nb[3] = { charts.neighbor[3 * static_cast<size_t>(c)],
      charts.neighbor[3 * static_cast<size_t>(c) + 1],
      charts.neighbor[3 * static_cast<size_t>(c) + 2] };
    for (int k = 0; k < 3; ++k)
    {
      if (nb[k] < -1 || nb[k] >= n)
      {
        throw InputError("LOD draw list: chart " + std::to_string(c) + " names neighbour " +
          std::to_string(nb[k]) + " on side " + std::to_string(k) + "; want -1 or a chart < " +
          std::to_string(n));
      }
    }
    if (charts.maxLevel[static_cast<size_t>(c)] < 0 ||
      charts.maxLevel[static_cast<size_t>(c)] >= stride)
    {
      throw InputError("LOD draw list: chart " + std::to_string(c) + " has maxLevel " +
        std::to_string(charts.maxLevel[static_cast<size_t>(c)]) + " outside [0, stride)");
    }
  }
}

/// Counting sort, pass 1: entries per level (and the level range check), the list's level
/// starts, counts and triangles; returns the cursor of each level at its start.
LevelCursor countLevels(
  const LodCharts& charts, const int32_t* levels, int32_t instances, LodDrawList& list)
{
  const int32_t n = charts.size();
  const int32_t stride = charts.stride;
  LevelCursor cursor{};
  list.chartsPerLevel.assign(static_cast<size_t>(stride), 0);
  for (int64_t r = 0; r < instances; ++r)
  {
    const int32_t* row = levels + r * n;
    for (int32_t c = 0; c < n; ++c)
    {
      const int32_t level = row[c];
      if (level < -1 || level > charts.maxLevel[static_cast<size_t>(c)])
      {
        throw InputError("LOD draw list: instance " + std::to_string(r) + " has chart " +
          std::to_string(c) + " at level " + std::to_string(level) + "; want -1 (culled) .. " +
          std::to_string(charts.maxLevel[static_cast<size_t>(c)]));
      }
      cursor[static_cast<size_t>(level + 1)] += 1;
    }
  }
  list.levelStart.assign(static_cast<size_t>(stride) + 1, 0);
  list.triangles = 0;
  for (int32_t d = 0; d < stride; ++d)
  {
    const int64_t inLevel = cursor[static_cast<size_t>(d + 1)];
    list.chartsPerLevel[static_cast<size_t>(d)] = inLevel;
    list.levelStart[static_cast<size_t>(d + 1)] = list.levelStart[static_cast<size_t>(d)] + inLevel;
    // 4^d grid triangles per chart at level d.
    list.triangles += inLevel << (2 * d);
  }
  for (int32_t d = 0; d < stride; ++d)
  {
    cursor[static_cast<size_t>(d)] = list.levelStart[static_cast<size_t>(d)];
  }
  return cursor;
}

/// Pass 2: place every drawn chart with its own and its neighbours' levels (eq. (8)'s inputs).
void placeEntries(const LodCharts& charts, const int32_t* levels, int32_t instances,
  LevelCursor& cursor, LodDrawList& list)
{
  const int32_t n = charts.size();
  int32_t* entries = list.entries.data();
  const int32_t* neighbor = charts.neighbor.data();
  int64_t firstId = 0;
  for (int32_t r = 0; r < instances; ++r)
  {
    const int32_t* row = levels + static_cast<int64_t>(r) * n;
    for (int32_t c = 0; c < n; ++c)
    {
      const int32_t level = row[c];
      if (level < 0)
      {
        continue;
      }
      int32_t packed = level;
      for (int k = 0; k < 3; ++k)
      {
        const int32_t nb = neighbor[3 * static_cast<size_t>(c) + static_cast<size_t>(k)];
        const int32_t across = nb >= 0 ? row[nb] : -1;
        packed |= (across >= 0 ? across : level) << (4 + 4 * k);
      }
      int32_t* e = entries + 4 * cursor[static_cast<size_t>(level)]++;
      e[0] = c;
      e[1] = r;
      e[2] = packed;
      // Cell ids run instance by instance, chart by chart (lod_selection.h).
      e[3] = firstId <= std::numeric_limits<int32_t>::max() ? static_cast<int32_t>(firstId) : -1;
      firstId += int64_t(1) << (2 * level);
    }
  }
}

/// The finest samples of every chart (image 0), xyz each, and their bounds.
std::vector<float> finestSamples(const Atlas& atlas, std::array<double, 6>& bounds)
{
  validateAtlasLayout(atlas);
  const AtlasImage& image = atlas.images[0];
  const size_t texels = static_cast<size_t>(image.width) * static_cast<size_t>(image.height);
  if (image.data.empty() || image.data[0].size() < 3 * texels)
  {
    throw InputError("LOD bounds: image 0 holds " +
      std::to_string(image.data.empty() ? 0 : image.data[0].size()) + " position values for " +
      std::to_string(texels) + " texels; want 3 per texel");
  }
  std::vector<float> points;
  bounds = { kInf, -kInf, kInf, -kInf, kInf, -kInf };
  forEachImageSample(atlas, 0,
    [&](int32_t, int32_t, int32_t, int32_t, size_t texel)
    {
      for (size_t x = 0; x < 3; ++x)
      {
        const float v = image.data[0][3 * texel + x];
        points.push_back(v);
        bounds[2 * x] = std::min(bounds[2 * x], double(v));
        bounds[2 * x + 1] = std::max(bounds[2 * x + 1], double(v));
      }
    });
  return points;
}

/// Bounds of the samples under one affine row-major 4 x 4 matrix `t`, each coordinate of each
/// sample evaluated as t[r][0] x + t[r][1] y + t[r][2] z + t[r][3] in double.
std::array<double, 6> transformedBounds(
  const std::vector<float>& points, const std::array<double, 6>& model, const double* t)
{
  std::array<double, 6> out{};
  for (int r = 0; r < 3; ++r)
  {
    const double* row = t + 4 * r;
    const int nonzero = (row[0] != 0.0) + (row[1] != 0.0) + (row[2] != 0.0);
    if (nonzero <= 1)
    {
      // One axis (or none) feeds this row: rounding is monotone, so the extremes of the samples'
      // coordinate give the extremes of the row, bit for bit as the loop below would.
      const int k = row[0] != 0.0 ? 0 : row[1] != 0.0 ? 1 : 2;
      const double a = row[k] * model[2 * static_cast<size_t>(k)] + row[3];
      const double b = row[k] * model[2 * static_cast<size_t>(k) + 1] + row[3];
      out[2 * static_cast<size_t>(r)] = std::min(a, b);
      out[2 * static_cast<size_t>(r) + 1] = std::max(a, b);
      continue;
    }
    double lo = kInf, hi = -kInf;
    for (size_t p = 0; p < points.size(); p += 3)
    {
      const double v =
        row[0] * points[p] + row[1] * points[p + 1] + row[2] * points[p + 2] + row[3];
      lo = std::min(lo, v);
      hi = std::max(hi, v);
    }
    out[2 * static_cast<size_t>(r)] = lo;
    out[2 * static_cast<size_t>(r) + 1] = hi;
  }
  return out;
}
} // namespace

void buildDrawList(
  const LodCharts& charts, const int32_t* levels, int32_t instances, LodDrawList& list)
{
  checkDrawListCharts(charts, instances);
  LevelCursor cursor = countLevels(charts, levels, instances, list);
  list.entries.resize(static_cast<size_t>(list.levelStart[static_cast<size_t>(charts.stride)]) * 4);
  placeEntries(charts, levels, instances, cursor, list);
}

LodTriangle locateTriangle(const LodDrawList& list, int64_t cell)
{
  LodTriangle found;
  if (cell < 0 || list.levelStart.empty())
  {
    return found;
  }
  const int32_t* e = list.entries.data();
  for (size_t d = 0; d + 1 < list.levelStart.size(); ++d)
  {
    // The entries of level d ascend in first id (instance, then chart); -1 only at their end.
    int64_t lo = list.levelStart[d], hi = list.levelStart[d + 1];
    while (lo < hi)
    {
      const int64_t mid = lo + (hi - lo) / 2;
      const int32_t first = e[4 * mid + 3];
      if (first >= 0 && first <= cell)
      {
        lo = mid + 1;
      }
      else
      {
        hi = mid;
      }
    }
    if (lo == list.levelStart[d])
    {
      continue;
    }
    const int32_t* hit = e + 4 * (lo - 1);
    const int64_t triangle = cell - hit[3];
    if (triangle < (int64_t(1) << (2 * d)))
    {
      found.chart = hit[0];
      found.instance = hit[1];
      found.level = static_cast<int32_t>(d);
      found.triangle = triangle;
      return found;
    }
  }
  return found;
}

std::array<double, 6> drawnBounds(const Atlas& atlas, const std::vector<double>& instances)
{
  std::array<double, 6> bounds{ 1, -1, 1, -1, 1, -1 };
  const int64_t count = static_cast<int64_t>(instances.size() / 16);
  if (atlas.charts.empty() || count == 0)
  {
    return bounds;
  }
  std::array<double, 6> model{};
  const std::vector<float> points = finestSamples(atlas, model);
  std::vector<std::array<double, 6>> each(static_cast<size_t>(count));
  // Instances in parallel: a crowd turned off the axes loops over every sample once per instance.
  parallel_for(count,
    [&](int64_t i) {
      each[static_cast<size_t>(i)] = transformedBounds(points, model, instances.data() + 16 * i);
    });
  bounds = { kInf, -kInf, kInf, -kInf, kInf, -kInf };
  for (const std::array<double, 6>& b : each)
  {
    for (size_t x = 0; x < 3; ++x)
    {
      bounds[2 * x] = std::min(bounds[2 * x], b[2 * x]);
      bounds[2 * x + 1] = std::max(bounds[2 * x + 1], b[2 * x + 1]);
    }
  }
  return bounds;
}
} // namespace tc
