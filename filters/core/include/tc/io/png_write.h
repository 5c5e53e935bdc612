// SPDX-License-Identifier: BSD-3-Clause
/// @file png_write.h
/// An RGBA image as PNG bytes (libpng's simplified API), for the textures the glTF export
/// embeds.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

namespace tc
{
/// The 8-bit RGBA image of `width` x `height` texels in `rgba` (row 0 the image's bottom, as
/// the atlas stores textures) as a PNG file's bytes, rows top to bottom as PNG stores them.
/// @throws InputError when the sizes disagree or libpng fails (its message)
std::string encodePng(int32_t width, int32_t height, const std::vector<uint8_t>& rgba);
} // namespace tc
