// SPDX-License-Identifier: BSD-3-Clause
#include "tc/lod_selection.h"

#include "tc/errors.h"

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <string>

namespace tc
{
namespace
{
float crossNorm(const float* a, const float* b)
{
  const float x = a[1] * b[2] - a[2] * b[1];
  const float y = a[2] * b[0] - a[0] * b[2];
  const float z = a[0] * b[1] - a[1] * b[0];
  return std::sqrt(x * x + y * y + z * z);
}

/// The level of one chart; see the header for the rules.
int32_t chartLevel(const LodCharts& charts, size_t c, const float m[16], float halfWidth,
  float halfHeight, float screenArea, const LodOptions& options)
{
  const float* b = charts.box.data() + 12 * c;
  const int32_t finest = charts.maxLevel[c];
  // Clip coordinates of c0 (p) and of the axes (q[k]), rows x, y, z, w.
  float p[4], q[3][4];
  for (int r = 0; r < 4; ++r)
  {
    const float* row = m + 4 * r;
    p[r] = row[0] * b[0] + row[1] * b[1] + row[2] * b[2] + row[3];
    for (int k = 0; k < 3; ++k)
    {
      const float* a = b + 3 + 3 * k;
      q[k][r] = row[0] * a[0] + row[1] * a[1] + row[2] * a[2];
    }
  }
  // The smallest value over the eight corners of a linear function with value v0 at c0 and
  // v[k] on axis k.
  auto lowest = [&](float v0, float v1, float v2, float v3)
  { return v0 + std::min(0.0f, v1) + std::min(0.0f, v2) + std::min(0.0f, v3); };
  if (options.cull)
  {
    for (int r = 0; r < 3; ++r)
    {
      // Outside r <= w: every corner has r - w > 0; outside -w <= r: every corner -r - w > 0.
      if (lowest(p[r] - p[3], q[0][r] - q[0][3], q[1][r] - q[1][3], q[2][r] - q[2][3]) > 0.0f ||
        lowest(-p[r] - p[3], -q[0][r] - q[0][3], -q[1][r] - q[1][3], -q[2][r] - q[2][3]) > 0.0f)
      {
        return -1;
      }
    }
  }
  if (lowest(p[3], q[0][3], q[1][3], q[2][3]) <= 1e-6f)
  {
    return finest;
  }
  // Eq. (6): the three visible faces of the projected box, in pixels.
  float s[4][2];
  s[0][0] = p[0] / p[3] * halfWidth;
  s[0][1] = p[1] / p[3] * halfHeight;
  for (int k = 0; k < 3; ++k)
  {
    const float w = p[3] + q[k][3];
    s[k + 1][0] = (p[0] + q[k][0]) / w * halfWidth - s[0][0];
    s[k + 1][1] = (p[1] + q[k][1]) / w * halfHeight - s[0][1];
  }
  const float area = std::fabs(s[1][0] * s[2][1] - s[1][1] * s[2][0]) +
    std::fabs(s[1][0] * s[3][1] - s[1][1] * s[3][0]) +
    std::fabs(s[2][0] * s[3][1] - s[2][1] * s[3][0]);
  if (!(area > 0.0f))
  {
    return 0;
  }
  const float* errors = charts.levelError.data() + static_cast<size_t>(charts.stride) * c;
  if (options.errorPixels > 0.0 && std::isfinite(errors[0]) && charts.worldArea[c] > 0.0f)
  {
    const float pixelsPerUnit = std::sqrt(area / charts.worldArea[c]);
    const float allowed = static_cast<float>(options.errorPixels) / pixelsPerUnit;
    int32_t level = finest;
    for (int32_t d = 0; d < finest; ++d)
    {
      if (errors[d] <= allowed)
      {
        level = d;
        break;
      }
    }
    level += static_cast<int32_t>(std::lround(options.bias));
    return std::clamp(level, 0, finest);
  }
  // Eq. (7): d = d_max + log4(A / A_0).
  const float d = static_cast<float>(finest) + 0.5f * std::log2(area / screenArea) +
    static_cast<float>(options.bias);
  return static_cast<int32_t>(std::clamp(std::floor(d + 0.5f), 0.0f, static_cast<float>(finest)));
}
} // namespace

LodCharts LodCharts::fromAtlas(const Atlas& atlas)
{
  LodCharts charts;
  const size_t nc = atlas.charts.size();
  charts.stride = std::max(0, atlas.maxLevel()) + 1;
  charts.box.resize(12 * nc);
  charts.worldArea.resize(nc);
  charts.maxLevel.resize(nc);
  charts.levelError.assign(
    static_cast<size_t>(charts.stride) * nc, std::numeric_limits<float>::infinity());
  charts.neighbor.resize(3 * nc);
  for (size_t c = 0; c < nc; ++c)
  {
    const AtlasChart& chart = atlas.charts[c];
    float* b = charts.box.data() + 12 * c;
    for (int x = 0; x < 3; ++x)
    {
      b[x] = static_cast<float>(chart.box[static_cast<size_t>(x)]);
      for (int k = 0; k < 3; ++k)
      {
        b[3 + 3 * k + x] = static_cast<float>(
          chart.box[static_cast<size_t>(3 + 3 * k + x)] - chart.box[static_cast<size_t>(x)]);
      }
    }
    charts.worldArea[c] =
      crossNorm(b + 3, b + 6) + crossNorm(b + 3, b + 9) + crossNorm(b + 6, b + 9);
    charts.maxLevel[c] = chart.maxLevel;
    if (chart.levelError.size() == static_cast<size_t>(chart.maxLevel) + 1)
    {
      for (size_t d = 0; d < chart.levelError.size(); ++d)
      {
        charts.levelError[static_cast<size_t>(charts.stride) * c + d] =
          static_cast<float>(chart.levelError[d]);
      }
    }
    for (int k = 0; k < 3; ++k)
    {
      charts.neighbor[3 * c + static_cast<size_t>(k)] = chart.neighborChart[static_cast<size_t>(k)];
    }
  }
  return charts;
}

void selectLevels(
  const LodCharts& charts, const LodView& view, const LodOptions& options, int32_t* levels)
{
  float m[16];
  for (int e = 0; e < 16; ++e)
  {
    m[e] = static_cast<float>(view.worldToClip[static_cast<size_t>(e)]);
  }
  const float halfWidth = static_cast<float>(0.5 * view.width);
  const float halfHeight = static_cast<float>(0.5 * view.height);
  const float screenArea = static_cast<float>(std::max(1.0, view.width * view.height));
  const size_t nc = charts.maxLevel.size();
  auto run = [&](size_t begin, size_t end)
  {
    for (size_t c = begin; c < end; ++c)
    {
      levels[c] = chartLevel(charts, c, m, halfWidth, halfHeight, screenArea, options);
    }
  };
  // Small scenes cost less than a parallel launch.
  constexpr size_t kBlock = 8192;
  if (nc <= kBlock)
  {
    run(0, nc);
    return;
  }
  tbb::parallel_for(tbb::blocked_range<size_t>(0, nc, kBlock),
    [&](const tbb::blocked_range<size_t>& r) { run(r.begin(), r.end()); });
}

void buildDrawList(
  const LodCharts& charts, const int32_t* levels, int32_t instances, LodDrawList& list)
{
  const size_t nc = charts.maxLevel.size();
  const size_t stride = static_cast<size_t>(std::max(1, charts.stride));
  list.chartsPerLevel.assign(stride, 0);
  list.levelStart.assign(stride + 1, 0);
  list.triangles = 0;
  const size_t total = nc * static_cast<size_t>(std::max(0, instances));
  for (size_t e = 0; e < total; ++e)
  {
    const int32_t n = levels[e];
    if (n < 0)
    {
      continue;
    }
    if (n >= static_cast<int32_t>(stride) || n > 15)
    {
      throw InputError("buildDrawList: level " + std::to_string(n) + " of chart " +
        std::to_string(e % nc) + " is above the atlas's finest level " +
        std::to_string(stride - 1) + " (or above 15); clamp the levels first");
    }
    ++list.chartsPerLevel[static_cast<size_t>(n)];
    list.triangles += int64_t(1) << (2 * n);
  }
  for (size_t d = 0; d < stride; ++d)
  {
    list.levelStart[d + 1] = list.levelStart[d] + list.chartsPerLevel[d];
  }
  list.entries.resize(4 * static_cast<size_t>(list.levelStart[stride]));
  std::vector<int64_t>& next = list.chartsPerLevel; // reused as the fill cursor, restored below
  for (size_t d = 0; d < stride; ++d)
  {
    next[d] = list.levelStart[d];
  }
  for (int32_t i = 0; i < instances; ++i)
  {
    const int32_t* row = levels + static_cast<size_t>(i) * nc;
    for (size_t c = 0; c < nc; ++c)
    {
      const int32_t n = row[c];
      if (n < 0)
      {
        continue;
      }
      int32_t packed = n;
      for (int k = 0; k < 3; ++k)
      {
        const int32_t nb = charts.neighbor[3 * c + static_cast<size_t>(k)];
        const int32_t m = nb >= 0 && row[nb] >= 0 ? row[nb] : n;
        packed |= m << (4 * (k + 1));
      }
      int32_t* entry = list.entries.data() + 4 * next[static_cast<size_t>(n)]++;
      entry[0] = static_cast<int32_t>(c);
      entry[1] = i;
      entry[2] = packed;
      entry[3] = 0;
    }
  }
  for (size_t d = 0; d < stride; ++d)
  {
    next[d] = list.levelStart[d + 1] - list.levelStart[d];
  }
}
} // namespace tc
