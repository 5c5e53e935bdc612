// SPDX-License-Identifier: BSD-3-Clause
#include "tc/io/height_field_io.h"

#include "io/height_field_georef.h"
#include "tc/common/errors.h"
#include "tc/common/file_names.h"
#include "tc/common/resources.h"

#include <cpl_error.h>
#include <gdal_priv.h>
#include <ogr_spatialref.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <mutex>
#include <sstream>

namespace tc
{
namespace
{
constexpr const char* kExtensions = "tif tiff asc hgt dem pgm png bmp";

/// GDAL's messages while it is in scope, instead of on stderr, so that a failed open can say
/// what GDAL found wrong.
class GdalMessages
{
public:
  GdalMessages() { CPLPushErrorHandlerEx(&GdalMessages::Collect, this); }
  ~GdalMessages() { CPLPopErrorHandler(); }
  GdalMessages(const GdalMessages&) = delete;
  GdalMessages& operator=(const GdalMessages&) = delete;
  std::string text() const { return Text.empty() ? "GDAL gave no reason" : Text; }

private:
  static void CPL_STDCALL Collect(CPLErr level, CPLErrorNum, const char* message)
  {
    auto* self = static_cast<GdalMessages*>(CPLGetErrorHandlerUserData());
    if (self && level >= CE_Failure && self->Text.empty())
    {
      self->Text = message;
    }
  }
  std::string Text;
};

void RegisterDrivers()
{
  static std::once_flag once;
  std::call_once(once, [] { GDALAllRegister(); });
}

/// Metres per unit of a height unit GDAL names ("m", "ft", "US survey foot"); 0 if unknown.
double MetresPerHeightUnit(std::string unit)
{
  std::transform(
    unit.begin(), unit.end(), unit.begin(), [](unsigned char c) { return std::tolower(c); });
  if (unit == "m" || unit == "metre" || unit == "meter" || unit == "metres" || unit == "meters")
  {
    return 1.0;
  }
  if (unit == "ft" || unit == "foot" || unit == "feet")
  {
    return 0.3048;
  }
  return unit.find("us survey") != std::string::npos ? 1200.0 / 3937.0 : 0.0;
}

/// The steps and origin of the file's geotransform, in metres; false when it has none.
bool ReadGeotransform(GDALDataset& dataset, HeightField& field)
{
  double gt[6];
  if (dataset.GetGeoTransform(gt) != CE_None)
  {
    return false;
  }
  // The geotransform gives the first cell's outer corner; a cell's height is at its centre.
  field.origin = { gt[0] + 0.5 * gt[1] + 0.5 * gt[2], gt[3] + 0.5 * gt[4] + 0.5 * gt[5] };
  field.steps = { gt[1], gt[4], gt[2], gt[5] };
  const OGRSpatialReference* srs = dataset.GetSpatialRef();
  if (srs)
  {
    char* wkt = nullptr;
    srs->exportToWkt(&wkt);
    field.crs = wkt ? wkt : "";
    CPLFree(wkt);
  }
  field.notes.push_back(std::string("spacing from the file's geotransform") +
    (srs && srs->GetName() ? std::string(" (") + srs->GetName() + ")" : std::string()));
  if (srs && srs->IsGeographic())
  {
    detail::degreesToMetres(field);
  }
  else if (srs && srs->IsProjected() && srs->GetLinearUnits() != 1.0)
  {
    for (double& step : field.steps)
    {
      step *= srs->GetLinearUnits();
    }
    field.notes.push_back("spacing converted to metres (" + std::to_string(srs->GetLinearUnits()) +
      " m per coordinate unit)");
  }
  return true;
}

/// The first band's values, row by row, with no data (the band's no-data value, NaN) as NaN
/// and the band's scale and offset applied.
void ReadHeights(GDALRasterBand& band, HeightField& field, const Progress& progress)
{
  int hasNoData = 0, hasScale = 0, hasOffset = 0;
  const double noData = band.GetNoDataValue(&hasNoData);
  const double scale = band.GetScale(&hasScale), offset = band.GetOffset(&hasOffset);
  field.heights.resize(static_cast<size_t>(field.columns * field.rows));
  const int64_t chunk = std::max<int64_t>(1, (1 << 20) / field.columns);
  for (int64_t r = 0; r < field.rows; r += chunk)
  {
    const int64_t n = std::min(chunk, field.rows - r);
    double* rows = field.heights.data() + r * field.columns;
    if (band.RasterIO(GF_Read, 0, int(r), int(field.columns), int(n), rows, int(field.columns),
          int(n), GDT_Float64, 0, 0) != CE_None)
    {
      throw InputError("rows " + std::to_string(r) + " to " + std::to_string(r + n - 1) +
        " cannot be read: " + CPLGetLastErrorMsg() + " (the file is damaged or truncated)");
    }
    for (double* h = rows; h != rows + n * field.columns; ++h)
    {
      *h = (hasNoData && *h == noData) || !std::isfinite(*h)
        ? std::numeric_limits<double>::quiet_NaN()
        : *h * (hasScale ? scale : 1.0) + (hasOffset ? offset : 0.0);
    }
    progress.report(double(r + n) / double(field.rows));
  }
}

/// Heights in metres where the unit is known and not metres (feet), so that they match the
/// metric spacing.
void HeightsToMetres(HeightField& field)
{
  const double perUnit = MetresPerHeightUnit(field.heightUnit);
  if (field.heightUnit.empty() || perUnit == 0.0)
  {
    field.notes.push_back(field.heightUnit.empty()
        ? "heights as stored (no unit given; VerticalScale scales them)"
        : "heights in '" + field.heightUnit + "', as stored");
    return;
  }
  if (perUnit != 1.0)
  {
    for (double& h : field.heights)
    {
      h *= perUnit;
    }
    field.notes.push_back("heights converted from " + field.heightUnit + " to metres");
  }
  field.heightUnit = "m";
}
/// Refuses a raster whose grid would not fit in the memory the system can give: a damaged or
/// mistaken header must not make the reader allocate until the process is killed.
void CheckMemory(const std::string& path, int64_t cells)
{
  // Per cell: the height read (8 bytes), its point id (4), its point (24 + 4 for Elevation)
  // and two triangles (24).
  const int64_t bytes = cells * 64;
  const int64_t available = availableMemory();
  if (available > 0 && bytes > available)
  {
    throw InputError("'" + path + "' has " + std::to_string(cells) + " cells, whose grid needs " +
      std::to_string(bytes >> 20) + " MB but " + std::to_string(available >> 20) +
      " MB are available; crop or resample it first (gdal_translate -outsize)");
  }
}
} // namespace

const char* heightFieldExtensions()
{
  return kExtensions;
}

bool isHeightFieldFile(const std::string& path)
{
  return hasOneOfExtensions(path, kExtensions);
}

HeightField readHeightField(const std::string& path, const Progress& progress)
{
  RegisterDrivers();
  GdalMessages messages;
  GDALDatasetUniquePtr dataset(GDALDataset::Open(path.c_str(), GDAL_OF_RASTER | GDAL_OF_READONLY));
  if (!dataset)
  {
    throw InputError("cannot read '" + path + "' as a raster of heights: " + messages.text());
  }
  HeightField field;
  field.columns = dataset->GetRasterXSize();
  field.rows = dataset->GetRasterYSize();
  if (dataset->GetRasterCount() < 1 || field.columns < 2 || field.rows < 2)
  {
    throw InputError("'" + path + "' holds no raster of at least 2 x 2 cells (" +
      std::to_string(field.columns) + " x " + std::to_string(field.rows) + ", " +
      std::to_string(dataset->GetRasterCount()) + " bands)");
  }
  if (field.columns * field.rows > std::numeric_limits<int32_t>::max())
  {
    throw InputError("'" + path + "' has " + std::to_string(field.columns * field.rows) +
      " cells, more than a mesh can index (2^31 - 1); crop or resample it (gdal_translate)");
  }
  CheckMemory(path, field.columns * field.rows);
  GDALRasterBand& band = *dataset->GetRasterBand(1);
  if (dataset->GetRasterCount() > 1)
  {
    field.notes.push_back(
      "band 1 of " + std::to_string(dataset->GetRasterCount()) + " read as heights");
  }
  field.heightUnit = band.GetUnitType();
  const std::string sideFile = detail::heightFieldSideFile(path);
  if (!ReadGeotransform(*dataset, field) && !sideFile.empty())
  {
    detail::readHeightFieldSideFile(sideFile, field);
  }
  else if (field.notes.empty())
  {
    field.notes.push_back("not georeferenced (no geotransform, no side file): one unit per cell");
  }
  ReadHeights(band, field, progress);
  if (std::none_of(
        field.heights.begin(), field.heights.end(), [](double h) { return std::isfinite(h); }))
  {
    throw InputError("'" + path + "' has no cell of data (every cell is the no-data value)");
  }
  HeightsToMetres(field);
  return field;
}
} // namespace tc
