// SPDX-License-Identifier: BSD-3-Clause
/// @file png_check.h
/// Whether a PNG is sound enough to hand to libpng through VTK: vtkPNGReader (VTK 9.2) crashes
/// while it cleans up after libpng reports an error (a damaged chunk of a texture did), so the
/// texture readers refuse a damaged PNG before it gets there.
#pragma once

#include <string>

namespace tc
{
/// What is wrong with the PNG `bytes`, or "" when it is sound: the signature, every chunk's
/// length, type and CRC, the IHDR (size at most 2^28 texels, a valid bit depth and colour
/// type), a PLTE for palette images, consecutive IDAT chunks whose zlib stream inflates to
/// exactly the image's filtered rows (each starting with a filter type 0..4, Adam7 passes
/// included), and IEND. Streams the inflation: memory stays small whatever the image's size.
std::string pngDamage(const std::string& bytes);
} // namespace tc
