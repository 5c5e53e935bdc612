// SPDX-License-Identifier: BSD-3-Clause
/// @file octahedron_atlas.h
/// A small valid atlas with known geometry: one flat chart per face of the octahedron
/// (|x| + |y| + |z| = 1), at chosen finest levels, shared by the atlas and LOD tests.
#pragma once

#include "tc/common/array_names.h"
#include "tc/gim/atlas.h"

#include <algorithm>
#include <array>
#include <cstdint>
#include <vector>

namespace tctest
{
// Octahedron: 6 base vertices, 8 counter-clockwise faces.
inline const double kCorners[6][3] = { { 1, 0, 0 }, { -1, 0, 0 }, { 0, 1, 0 }, { 0, -1, 0 },
  { 0, 0, 1 }, { 0, 0, -1 } };
inline const int kFaces[8][3] = { { 0, 2, 4 }, { 2, 1, 4 }, { 1, 3, 4 }, { 3, 0, 4 }, { 2, 0, 5 },
  { 1, 2, 5 }, { 3, 1, 5 }, { 0, 3, 5 } };

// A flat atlas over the octahedron: sample (i, j) of face (a, b, c) at level d is
// a + i/N (b - a) + j/N (c - a). Side samples are computed from the lower-numbered end so
// neighbours agree bit for bit. Charts 2m and 2m + 1 share rectangles.
inline tc::Atlas octahedronAtlas(const std::array<int32_t, 8>& maxLevels)
{
  tc::Atlas atlas;
  atlas.attributes = { { tc::kAtlasPosition, 3 }, { tc::kAtlasNormal, 3 } };
  atlas.charts.resize(8);
  for (int f = 0; f < 8; ++f)
  {
    tc::AtlasChart& c = atlas.charts[static_cast<size_t>(f)];
    c.maxLevel = maxLevels[static_cast<size_t>(f)];
    c.partner = f ^ 1;
    c.rotated = static_cast<uint8_t>(f & 1);
    for (int k = 0; k < 3; ++k)
    {
      c.cornerVertex[static_cast<size_t>(k)] = kFaces[f][k];
      const int a = kFaces[f][k];
      const int b = kFaces[f][(k + 1) % 3];
      for (int g = 0; g < 8; ++g)
      {
        for (int s = 0; s < 3; ++s)
        {
          if (kFaces[g][s] == b && kFaces[g][(s + 1) % 3] == a)
          {
            c.neighborChart[static_cast<size_t>(k)] = g;
            c.neighborSide[static_cast<size_t>(k)] = s;
          }
        }
      }
    }
  }
  const int32_t top = *std::max_element(maxLevels.begin(), maxLevels.end());
  atlas.images.resize(static_cast<size_t>(top) + 1);
  for (int32_t k = 0; k <= top; ++k)
  {
    // Pair m's rectangle (2^dh + 2) x (2^dh + 1) at x = m * (2^(top - k) + 2).
    const int32_t width = 4 * ((1 << (top - k)) + 2);
    const int32_t height = (1 << (top - k)) + 1;
    tc::AtlasImage& image = atlas.images[static_cast<size_t>(k)];
    image.width = width;
    image.height = height;
    image.data.assign(2, std::vector<float>(static_cast<size_t>(width * height * 3), 0.0f));
    for (int pair = 0; pair < 4; ++pair)
    {
      const int32_t dh = std::max(maxLevels[static_cast<size_t>(2 * pair)],
                           maxLevels[static_cast<size_t>(2 * pair + 1)]) -
        k;
      const int32_t x0 = pair * ((1 << (top - k)) + 2);
      for (int member = 0; member < 2; ++member)
      {
        tc::AtlasChart& c = atlas.charts[static_cast<size_t>(2 * pair + member)];
        if (c.maxLevel - k < 0)
        {
          continue;
        }
        if (dh >= 0)
        {
          c.origin.push_back(member == 0 ? std::array<int32_t, 2>{ x0, 0 }
                                         : std::array<int32_t, 2>{ x0 + (1 << dh) + 1, 1 << dh });
        }
      }
    }
  }
  for (int f = 0; f < 8; ++f)
  {
    const tc::AtlasChart& c = atlas.charts[static_cast<size_t>(f)];
    for (int32_t d = 0; d <= c.maxLevel; ++d)
    {
      const int32_t n = 1 << d;
      tc::AtlasImage& image = atlas.images[static_cast<size_t>(c.maxLevel - d)];
      for (int32_t j = 0; j <= n; ++j)
      {
        for (int32_t i = 0; i + j <= n; ++i)
        {
          // The side (if any) the sample lies on, evaluated from its lower-numbered end.
          int from = kFaces[f][0];
          int to = kFaces[f][1];
          int other = kFaces[f][2];
          double s = static_cast<double>(i) / n;
          double r = static_cast<double>(j) / n;
          if (i + j == n && j > 0)
          {
            from = kFaces[f][1];
            to = kFaces[f][2];
            s = static_cast<double>(j) / n;
            r = 0;
          }
          else if (i == 0 && j > 0)
          {
            from = kFaces[f][2];
            to = kFaces[f][0];
            s = static_cast<double>(n - j) / n;
            r = 0;
          }
          if (r == 0 && from > to)
          {
            std::swap(from, to);
            s = 1.0 - s;
          }
          const std::array<int32_t, 2> xy = tc::atlasTexel(c, d, i, j);
          float* p = image.data[0].data() + 3 * (xy[1] * image.width + xy[0]);
          float* nrm = image.data[1].data() + 3 * (xy[1] * image.width + xy[0]);
          for (int x = 0; x < 3; ++x)
          {
            p[x] =
              static_cast<float>(kCorners[from][x] + s * (kCorners[to][x] - kCorners[from][x]) +
                r * (kCorners[other][x] - kCorners[from][x]));
          }
          nrm[0] = nrm[1] = nrm[2] = 0.57735f;
        }
      }
    }
  }
  return atlas;
}
} // namespace tctest
