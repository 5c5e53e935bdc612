// SPDX-License-Identifier: BSD-3-Clause
#include "gim/atlas_packing.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <numeric>

namespace tc::detail::geometry_images
{
namespace
{
/// A rectangle of the packing: one chart pair (or a lone chart) in one image.
struct PackUnit
{
  int32_t first = -1;  ///< higher d_max, lower-left
  int32_t second = -1; ///< upper-right, turned by 180 degrees (-1: none)
};

/// The rectangle of a unit in one image.
struct Rect
{
  int32_t unit, w, h;
};

/// Charts sorted by d_max (stable: ascending ids on a tie), each paired with the next one;
/// sets AtlasChart::partner and rotated.
std::vector<PackUnit> pairCharts(const std::vector<int32_t>& level, std::vector<AtlasChart>& charts)
{
  std::vector<int32_t> order(level.size());
  std::iota(order.begin(), order.end(), 0);
  std::stable_sort(
    order.begin(), order.end(), [&level](int32_t a, int32_t b) { return level[a] > level[b]; });
  std::vector<PackUnit> units;
  for (size_t i = 0; i < order.size(); i += 2)
  {
    PackUnit u;
    u.first = order[i];
    u.second = i + 1 < order.size() ? order[i + 1] : -1;
    units.push_back(u);
    if (u.second >= 0)
    {
      charts[u.first].partner = u.second;
      charts[u.second].partner = u.first;
      charts[u.second].rotated = 1;
    }
  }
  return units;
}

/// The rectangles of the units that image k holds, tallest first (stable), their total area and
/// the widest one's width.
std::vector<Rect> imageRects(const std::vector<PackUnit>& units, const std::vector<int32_t>& level,
  int32_t k, double& area, int32_t& widest)
{
  std::vector<Rect> rects;
  area = 0.0;
  widest = 0;
  for (size_t u = 0; u < units.size(); ++u)
  {
    const int32_t d = level[units[u].first] - k;
    if (d < 0)
    {
      continue;
    }
    const int32_t n = int32_t(1) << d;
    // (2^dh + 2) x (2^dh + 1) for a pair: the two diagonals are separate texel rows.
    const Rect r{ static_cast<int32_t>(u), units[u].second >= 0 ? n + 2 : n + 1, n + 1 };
    rects.push_back(r);
    area += double(r.w) * double(r.h);
    widest = std::max(widest, r.w);
  }
  std::stable_sort(
    rects.begin(), rects.end(), [](const Rect& a, const Rect& b) { return a.h > b.h; });
  return rects;
}

/// Shelf packing at width w (left to right, rows bottom to top); returns the height and, with
/// `at`, the lower-left corner of each unit.
int32_t shelfPack(
  const std::vector<Rect>& rects, int32_t w, std::vector<std::array<int32_t, 2>>* at)
{
  int32_t x = 0, y = 0, shelf = 0;
  for (const Rect& r : rects)
  {
    if (x + r.w > w)
    {
      y += shelf;
      x = 0;
      shelf = 0;
    }
    if (at)
    {
      (*at)[r.unit] = { x, y };
    }
    x += r.w;
    shelf = std::max(shelf, r.h);
  }
  return y + shelf;
}

/// Shelf packing of the rectangles of image k; returns the lower-left corner of each unit
/// present (x = -1 for a unit absent from this image) and the image size. The width is a
/// multiple of 4 from the widest rectangle up to twice sqrt(total area): the one that gives the
/// shortest longer side (GPU textures are limited in width and height, not area), the smaller
/// image on a tie.
void packImage(const std::vector<PackUnit>& units, const std::vector<int32_t>& level, int32_t k,
  std::vector<std::array<int32_t, 2>>& corner, int32_t& width, int32_t& height)
{
  double area = 0.0;
  int32_t widest = 0;
  const std::vector<Rect> rects = imageRects(units, level, k, area, widest);
  const int32_t first = (widest + 3) / 4 * 4;
  const int32_t last = std::max(first, static_cast<int32_t>(std::ceil(2.0 * std::sqrt(area))));
  width = first;
  height = shelfPack(rects, first, nullptr);
  for (int32_t w = first + 4; w <= last; w += 4)
  {
    const int32_t h = shelfPack(rects, w, nullptr);
    const int32_t side = std::max(w, h), bestSide = std::max(width, height);
    const int64_t size = int64_t(w) * h, best = int64_t(width) * height;
    if (side < bestSide || (side == bestSide && size < best))
    {
      width = w;
      height = h;
    }
  }
  corner.assign(units.size(), { -1, -1 });
  shelfPack(rects, width, &corner);
}
} // namespace

void packAtlas(const std::vector<int32_t>& level, const SampleLayout& S, Atlas& atlas)
{
  const std::vector<PackUnit> units = pairCharts(level, atlas.charts);
  const int32_t numImages = atlas.maxLevel() + 1;
  const int32_t numAttributes = static_cast<int32_t>(S.components.size());
  atlas.images.resize(numImages);
  for (AtlasChart& ch : atlas.charts)
  {
    ch.origin.assign(static_cast<size_t>(ch.maxLevel) + 1, { 0, 0 });
  }
  for (int32_t k = 0; k < numImages; ++k)
  {
    std::vector<std::array<int32_t, 2>> corner;
    AtlasImage& image = atlas.images[k];
    packImage(units, level, k, corner, image.width, image.height);
    for (size_t u = 0; u < units.size(); ++u)
    {
      if (corner[u][0] < 0)
      {
        continue;
      }
      const int32_t n = int32_t(1) << (level[units[u].first] - k);
      atlas.charts[units[u].first].origin[k] = corner[u];
      const int32_t second = units[u].second;
      if (second >= 0 && level[second] >= k)
      {
        atlas.charts[second].origin[k] = { corner[u][0] + n + 1, corner[u][1] + n };
      }
    }
    image.data.resize(numAttributes);
    for (int32_t a = 0; a < numAttributes; ++a)
    {
      image.data[a].assign(static_cast<size_t>(image.width) * static_cast<size_t>(image.height) *
          static_cast<size_t>(S.components[a]),
        0.0f);
    }
  }
}

void writeChartImages(const ChartGrid& g, const SampleLayout& S, int32_t c, Atlas& atlas)
{
  const int32_t numAttributes = static_cast<int32_t>(S.components.size());
  const AtlasChart& ch = atlas.charts[c];
  for (int32_t k = 0; k <= ch.maxLevel; ++k)
  {
    const int32_t d = ch.maxLevel - k;
    const int64_t nd = int64_t(1) << d;
    AtlasImage& image = atlas.images[k];
    for (int64_t j = 0; j <= nd; ++j)
    {
      for (int64_t i = 0; i + j <= nd; ++i)
      {
        // Level d is the sampled grid at stride 2^(sampled - d): the point-sampled pyramid.
        const float* src = g.at(d, i, j);
        const std::array<int32_t, 2> xy =
          atlasTexel(ch, d, static_cast<int32_t>(i), static_cast<int32_t>(j));
        const size_t texel = static_cast<size_t>(xy[1]) * image.width + xy[0];
        for (int32_t a = 0; a < numAttributes; ++a)
        {
          std::copy(src + S.offset[a], src + S.offset[a] + S.components[a],
            image.data[a].data() + texel * S.components[a]);
        }
      }
    }
  }
}
} // namespace tc::detail::geometry_images
