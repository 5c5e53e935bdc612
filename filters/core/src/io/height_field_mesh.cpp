// SPDX-License-Identifier: BSD-3-Clause
#include "tc/common/errors.h"
#include "tc/io/height_field_io.h"

#include <cmath>
#include <limits>
#include <string>

namespace tc
{
namespace
{
/// The point ids of the cells with data (-1 without), and their positions and heights.
std::vector<int32_t> AddGridPoints(
  const HeightField& field, double verticalScale, HeightFieldMesh& out)
{
  std::vector<int32_t> ids(field.heights.size(), -1);
  for (int64_t r = 0; r < field.rows; ++r)
  {
    for (int64_t c = 0; c < field.columns; ++c)
    {
      const double h = field.heights[r * field.columns + c];
      if (!std::isfinite(h))
      {
        ++out.noDataCells;
        continue;
      }
      ids[r * field.columns + c] = static_cast<int32_t>(out.heights.size());
      out.mesh.points.insert(out.mesh.points.end(),
        { c * field.steps[0] + r * field.steps[2], c * field.steps[1] + r * field.steps[3],
          h * verticalScale });
      out.heights.push_back(static_cast<float>(h));
    }
  }
  return ids;
}

/// Appends triangle (a, b, c), reversed when the grid's columns and rows make a clockwise frame
/// seen from above, so that every triangle faces up.
void AddTriangle(std::vector<int32_t>& triangles, bool flip, int32_t a, int32_t b, int32_t c)
{
  triangles.insert(triangles.end(), { a, flip ? c : b, flip ? b : c });
}
} // namespace

// A regular grid rather than an adaptive triangulation: every cell is a sample of the data, so
// errors are measured against the raster itself, and the later stages already decide where
// fewer triangles do (a flat region becomes coarse levels of its charts).
HeightFieldMesh triangulateHeightField(
  const HeightField& field, const HeightFieldOptions& options, const Progress& progress)
{
  if (!(options.verticalScale > 0.0) || !std::isfinite(options.verticalScale))
  {
    throw InputError("the vertical scale must be a positive number (got " +
      std::to_string(options.verticalScale) + "); 1 keeps the heights as read");
  }
  HeightFieldMesh out;
  const std::vector<int32_t> ids = AddGridPoints(field, options.verticalScale, out);
  // In a frame where columns turn counter-clockwise into rows, (a, d, e) below is clockwise.
  const bool flip = field.steps[0] * field.steps[3] - field.steps[1] * field.steps[2] > 0.0;
  const auto height = [&](int64_t k) { return field.heights[k]; };
  for (int64_t r = 0; r + 1 < field.rows; ++r)
  {
    for (int64_t c = 0; c + 1 < field.columns; ++c)
    {
      const int64_t ka = r * field.columns + c, kb = ka + 1, kd = ka + field.columns, ke = kd + 1;
      const int32_t a = ids[ka], b = ids[kb], d = ids[kd], e = ids[ke];
      // The diagonal whose ends differ less in height follows the terrain's ridges and valleys
      // instead of cutting across them.
      const bool alongAE = a < 0 || e < 0 ? false
        : b < 0 || d < 0                  ? true
                         : std::abs(height(ka) - height(ke)) <= std::abs(height(kb) - height(kd));
      if (alongAE)
      {
        if (d >= 0)
          AddTriangle(out.mesh.triangles, flip, a, d, e);
        if (b >= 0)
          AddTriangle(out.mesh.triangles, flip, a, e, b);
      }
      else if (b >= 0 && d >= 0)
      {
        if (a >= 0)
          AddTriangle(out.mesh.triangles, flip, a, d, b);
        if (e >= 0)
          AddTriangle(out.mesh.triangles, flip, b, d, e);
      }
    }
    if ((r & 255) == 0)
    {
      progress.report(double(r) / double(field.rows));
    }
  }
  if (out.mesh.triangles.empty())
  {
    throw InputError("the height field has no 3 neighbouring cells with data; there is no "
                     "surface to triangulate");
  }
  progress.report(1.0);
  return out;
}
} // namespace tc
