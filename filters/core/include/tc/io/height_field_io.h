// SPDX-License-Identifier: BSD-3-Clause
/// @file height_field_io.h
/// Terrain input: a raster of heights (GeoTIFF, ESRI ASCII grid, SRTM .hgt, PGM/PNG/BMP height
/// maps, anything GDAL reads as a raster) read through GDAL, and its triangulation as a regular
/// grid. The grid lies in a local metric frame whose origin is the first cell's centre; where
/// that centre is on the earth is kept apart, in double precision (`HeightField::origin`), because
/// the later stages store positions as float32 texels.
#pragma once

#include "tc/common/mesh.h"
#include "tc/common/progress.h"

#include <array>
#include <cstdint>
#include <string>
#include <vector>

namespace tc
{
/// The extensions read as height fields, for messages and file dialogs: "tif tiff ...".
const char* heightFieldExtensions();

/// True if `path` ends (case-insensitively) with one of heightFieldExtensions().
bool isHeightFieldFile(const std::string& path);

/// A raster of heights as read, before triangulation.
struct HeightField
{
  int64_t columns = 0;
  int64_t rows = 0;
  /// rows x columns heights in metres (or the file's own height unit, see heightUnit), row-major
  /// from the raster's first row; NaN where the file marks no data.
  std::vector<double> heights;
  /// The first cell's centre in the file's coordinates (its CRS units, or degrees for geographic
  /// data); (0, 0) when the file is not georeferenced.
  std::array<double, 2> origin{ 0.0, 0.0 };
  /// The ground step of one column (x, y) and of one row (x, y), in metres (in cells when the
  /// file is not georeferenced).
  std::array<double, 4> steps{ 1.0, 0.0, 0.0, -1.0 };
  std::string crs;        ///< the file's coordinate system as WKT; "" when it has none
  std::string heightUnit; ///< "m", "ft", ... as the file or side file states; "" when unknown
  /// How spacing and heights were read, one sentence each ("spacing in degrees, converted to
  /// metres at latitude 36.6: 74.5 x 92.6 m per cell").
  std::vector<std::string> notes;
};

/// Reads the first band of a raster through GDAL. Spacing comes from, in this order: the
/// file's geotransform; a JSON side file (`NAME.json`, or `NAME.json` without a trailing
/// `_<columns>x<rows>` in the name) with `dx`, `dy` and optionally `xmin`, `ymin` (where the
/// first column and row lie), `xmax`, `ymax` (the far ones: their direction, and whether the
/// bounds are the raster's outer edges or its outer cells' centres; edges without them),
/// `horizontal_units` ("degrees" or "metres") and `height_units`; else one unit per cell.
/// Geographic spacing (degrees) is converted to metres at the grid's centre latitude (an
/// equirectangular frame: exact east-west scale at that latitude, off by tan(latitude) times the
/// half-height in radians at the north and south edges, 0.2% for a 0.3-degree grid at 37
/// degrees; reproject a larger grid to a metric CRS first, e.g. with gdalwarp).
///
/// @throws tc::InputError  a file GDAL cannot open as a raster (its message), an empty raster, a
///   raster with no cell of data, a damaged side file, or more cells than the mesh can index
/// @throws tc::Aborted     when the progress callback aborts
HeightField readHeightField(const std::string& path, const Progress& progress = {});

struct HeightFieldOptions
{
  /// Heights are multiplied by this (vertical exaggeration, or a unit conversion); > 0.
  double verticalScale = 1.0;
};

/// A height field as a triangle mesh.
struct HeightFieldMesh
{
  TriMesh mesh;               ///< a point per cell with data, two triangles per square of data
  std::vector<float> heights; ///< #V: the height read (before verticalScale), for colouring
  int64_t noDataCells = 0;    ///< cells without data, left out as holes
};

/// Triangulates a height field as a regular grid: a point per cell centre at (column step,
/// row step, height x verticalScale), two triangles per square whose 4 corners have data, split
/// along the diagonal whose ends differ less in height; triangles face up (+z).
///
/// @throws tc::InputError  verticalScale not > 0, or no square of data (nothing to triangulate)
HeightFieldMesh triangulateHeightField(
  const HeightField& field, const HeightFieldOptions& options = {}, const Progress& progress = {});
} // namespace tc
