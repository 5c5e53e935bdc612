// SPDX-License-Identifier: BSD-3-Clause
/// @file chart_grid.h
/// Private to buildGeometryImages: the float samples of a chart's grid and of a shared path, and
/// the grid triangle that holds a parameter (Feng et al. 2010, section 5.2).
#pragma once

#include "tc/gim/atlas.h"
#include "tc/gim/geometry_images.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <vector>

namespace tc::detail::geometry_images
{
/// Float values of one sample: position, normal, then every extra attribute.
struct SampleLayout
{
  std::vector<int32_t> components; ///< per atlas attribute
  std::vector<int32_t> offset;     ///< of each attribute in a sample
  int32_t size = 0;
};

/// The layout of Position (3), Normal (3), then the extra attributes in order.
inline SampleLayout sampleLayout(const std::vector<GeometryImageAttribute>& extra)
{
  SampleLayout S;
  S.components = { 3, 3 };
  for (const GeometryImageAttribute& x : extra)
  {
    S.components.push_back(x.components);
  }
  for (int32_t c : S.components)
  {
    S.offset.push_back(S.size);
    S.size += c;
  }
  return S;
}

/// Sample values of a whole chart at its finest sampled level (n = 2^level per side). Level
/// d <= level is the finest grid at stride 2^(level - d): a point-sampled pyramid.
struct ChartGrid
{
  int32_t level = 0;
  int64_t n = 0;
  int32_t size = 0;          ///< SampleLayout::size
  std::vector<float> values; ///< gridVertexCount(level) x size
  /// Sample (i, j) of level d (2^d samples per side): the finest sample at stride n / 2^d.
  float* at(int32_t d, int64_t i, int64_t j)
  {
    const int64_t stride = n >> d;
    return &values[gridVertexIndex(
                     level, static_cast<int32_t>(i * stride), static_cast<int32_t>(j * stride)) *
      size];
  }
  const float* at(int32_t d, int64_t i, int64_t j) const
  {
    return const_cast<ChartGrid*>(this)->at(d, i, j);
  }
};

/// One path sampled by arc length from its lower base vertex to its higher one.
struct PathSamples
{
  int32_t level = 0;            ///< finer level of its two charts
  std::vector<int32_t> segment; ///< per sample: piece (point i to i + 1) of the path
  std::vector<double> tau;      ///< per sample: fraction along that piece
  std::vector<float> values;    ///< per sample: SampleLayout::size floats (shared normal)
};

/// The grid triangle of level nd (samples per side) holding parameter (u, v), clamped into the
/// right triangle, and the barycentric weights of its corners (i[k], j[k]).
struct GridHit
{
  int64_t i[3], j[3];
  double w[3];
};

inline GridHit gridHit(double u, double v, int64_t nd)
{
  const double x = std::clamp(u, 0.0, 1.0) * nd;
  const double y = std::clamp(v, 0.0, 1.0) * nd;
  const int64_t i = std::clamp<int64_t>(static_cast<int64_t>(std::floor(x)), 0, nd - 1);
  const int64_t j = std::clamp<int64_t>(static_cast<int64_t>(std::floor(y)), 0, nd - 1 - i);
  double fx = x - i, fy = y - j;
  if (fx + fy <= 1.0 || i + j + 1 >= nd)
  {
    // Lower triangle (i, j), (i + 1, j), (i, j + 1); clamped onto it at the hypotenuse.
    const double s = fx + fy;
    if (s > 1.0)
    {
      fx /= s;
      fy /= s;
    }
    return { { i, i + 1, i }, { j, j, j + 1 }, { 1.0 - fx - fy, fx, fy } };
  }
  // Upper triangle (i + 1, j + 1), (i, j + 1), (i + 1, j).
  return { { i + 1, i, i + 1 }, { j + 1, j + 1, j }, { fx + fy - 1.0, 1.0 - fx, 1.0 - fy } };
}
} // namespace tc::detail::geometry_images
