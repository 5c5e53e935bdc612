// SPDX-License-Identifier: BSD-3-Clause
/// @file height_field_georef.h
/// Where a height field's cells lie (private to height_field_io): the spacing a JSON side file
/// gives, and the conversion of geographic spacing to metres.
#pragma once

#include "tc/io/height_field_io.h"

#include <string>

namespace tc::detail
{
/// The side file of a raster: `NAME.json`, or `BASE.json` where NAME is BASE_<c>x<r>; "" when
/// neither exists.
std::string heightFieldSideFile(const std::string& rasterPath);

/// Reads the side file's spacing, origin and units into `field` (whose columns and rows are
/// set), with a note on each; converts degrees to metres.
/// @throws tc::InputError  unparsable JSON, no positive dx / dy, or rows / cols that differ from
///   the raster's
void readHeightFieldSideFile(const std::string& sideFile, HeightField& field);

/// Turns steps given in degrees (x: longitude, y: latitude) into metres at the latitude of the
/// grid's centre, with a note saying so.
void degreesToMetres(HeightField& field);
} // namespace tc::detail
