// SPDX-License-Identifier: BSD-3-Clause
#include "io/height_field_georef.h"

#include "tc/common/errors.h"

#include <nlohmann/json.hpp>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <regex>
#include <sstream>

namespace tc::detail
{
namespace
{
/// "74.5", three significant digits.
std::string Short(double value)
{
  std::ostringstream text;
  text.precision(3);
  text << value;
  return text.str();
}

double Number(const nlohmann::json& side, const char* key, double fallback)
{
  const auto it = side.find(key);
  return it != side.end() && it->is_number() ? it->get<double>() : fallback;
}

std::string Text(const nlohmann::json& side, const char* key)
{
  const auto it = side.find(key);
  return it != side.end() && it->is_string() ? it->get<std::string>() : std::string();
}

std::string Lower(std::string s)
{
  for (char& c : s)
  {
    c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  }
  return s;
}

/// Whether the side file's spacing is in degrees: as `horizontal_units` says; else when its
/// free-text `units` mentions degrees, or when its corners lie in longitude / latitude range
/// with cells under 0.01 (a metric grid there would be a few metres wide, an unlikely DEM).
bool InDegrees(const nlohmann::json& side, double dx, double dy)
{
  const std::string stated = Lower(Text(side, "horizontal_units"));
  if (!stated.empty())
  {
    return stated.rfind("deg", 0) == 0;
  }
  if (Lower(Text(side, "units")).find("degree") != std::string::npos)
  {
    return true;
  }
  const double x0 = Number(side, "xmin", 1e9), x1 = Number(side, "xmax", x0);
  const double y0 = Number(side, "ymin", 1e9), y1 = Number(side, "ymax", y0);
  const auto inRange = [](double v, double limit) { return std::abs(v) <= limit; };
  return inRange(x0, 180) && inRange(x1, 180) && inRange(y0, 90) && inRange(y1, 90) && dx < 0.01 &&
    dy < 0.01;
}

/// How far the first cell's centre lies inside the bound a side file gives: half a cell when
/// the bounds span `cells` cells (the raster's outer edges, as GDAL and ESRI grids give them),
/// none when they span one fewer (the outer cells' centres).
double CentreOffset(double extent, double cell, int64_t cells)
{
  const double spanned = std::abs(extent) / cell;
  return std::abs(spanned - double(cells - 1)) < 0.01 ? 0.0 : 0.5 * cell;
}

nlohmann::json ParseSideFile(const std::string& sideFile)
{
  std::ifstream in(sideFile);
  nlohmann::json side = nlohmann::json::parse(in, nullptr, false);
  if (side.is_discarded() || !side.is_object())
  {
    throw InputError("the side file '" + sideFile +
      "' is not a JSON object; give dx, dy (cell size) and optionally xmin, ymin (first column "
      "and row), horizontal_units and height_units, or remove it");
  }
  return side;
}
} // namespace

std::string heightFieldSideFile(const std::string& rasterPath)
{
  namespace fs = std::filesystem;
  const fs::path raster(rasterPath);
  const std::string stem = raster.stem().string();
  std::smatch sized;
  const std::string base =
    std::regex_match(stem, sized, std::regex("(.+)_[0-9]+x[0-9]+")) ? sized[1].str() : stem;
  for (const std::string& name : { stem, base })
  {
    const fs::path candidate = raster.parent_path() / (name + ".json");
    std::error_code ec;
    if (fs::is_regular_file(candidate, ec))
    {
      return candidate.string();
    }
  }
  return "";
}

void readHeightFieldSideFile(const std::string& sideFile, HeightField& field)
{
  const nlohmann::json side = ParseSideFile(sideFile);
  const double dx = Number(side, "dx", 0.0), dy = Number(side, "dy", 0.0);
  if (!(dx > 0.0) || !(dy > 0.0))
  {
    throw InputError("the side file '" + sideFile +
      "' gives no positive dx and dy (the size of a cell); add them, or remove the file to read "
      "one unit per cell");
  }
  const double cols = Number(side, "cols", double(field.columns));
  const double rows = Number(side, "rows", double(field.rows));
  if (cols != double(field.columns) || rows != double(field.rows))
  {
    throw InputError("the side file '" + sideFile + "' describes " + Short(cols) + " x " +
      Short(rows) + " cells but the raster has " + std::to_string(field.columns) + " x " +
      std::to_string(field.rows) + "; it belongs to another raster");
  }
  // Columns run from xmin towards xmax, rows from ymin towards ymax (rows run south, as in a
  // north-up raster, when ymax is not given).
  const double x0 = Number(side, "xmin", 0.0), y0 = Number(side, "ymin", 0.0);
  const double x1 = Number(side, "xmax", x0 + dx * field.columns);
  const double y1 = Number(side, "ymax", y0 - dy * field.rows);
  const double xSign = x1 >= x0 ? 1.0 : -1.0, ySign = y1 >= y0 ? 1.0 : -1.0;
  field.origin = { x0 + xSign * CentreOffset(x1 - x0, dx, field.columns),
    y0 + ySign * CentreOffset(y1 - y0, dy, field.rows) };
  field.steps = { xSign * dx, 0.0, 0.0, ySign * dy };
  const std::string heightUnit = Text(side, "height_units");
  field.heightUnit = heightUnit.empty() ? field.heightUnit : heightUnit;
  field.notes.push_back("spacing from the side file '" + sideFile + "'");
  if (InDegrees(side, dx, dy))
  {
    degreesToMetres(field);
  }
}

void degreesToMetres(HeightField& field)
{
  const double pi = std::acos(-1.0);
  const double centreLatitude = field.origin[1] + 0.5 * (field.columns - 1) * field.steps[1] +
    0.5 * (field.rows - 1) * field.steps[3];
  const double phi = centreLatitude * pi / 180.0;
  // Metres per degree on the WGS 84 ellipsoid at latitude phi (the series of the meridian and
  // parallel arc lengths).
  const double perLatitude = 111132.954 - 559.822 * std::cos(2 * phi) + 1.175 * std::cos(4 * phi);
  const double perLongitude =
    111412.84 * std::cos(phi) - 93.5 * std::cos(3 * phi) + 0.118 * std::cos(5 * phi);
  for (int k : { 0, 2 })
  {
    field.steps[k] *= perLongitude;
    field.steps[k + 1] *= perLatitude;
  }
  field.notes.push_back("spacing in degrees, converted to metres at latitude " +
    Short(centreLatitude) + ": " + Short(std::hypot(field.steps[0], field.steps[1])) + " x " +
    Short(std::hypot(field.steps[2], field.steps[3])) + " m per cell");
}
} // namespace tc::detail
