// SPDX-License-Identifier: BSD-3-Clause
#include "tc/io/png_write.h"

#include "tc/common/errors.h"

#include <png.h>

namespace tc
{
std::string encodePng(int32_t width, int32_t height, const std::vector<uint8_t>& rgba)
{
  if (width < 1 || height < 1 ||
    rgba.size() != static_cast<size_t>(width) * static_cast<size_t>(height) * 4)
  {
    throw InputError("cannot encode a PNG of " + std::to_string(width) + " x " +
      std::to_string(height) + " texels from " + std::to_string(rgba.size()) + " bytes");
  }
  png_image image{};
  image.version = PNG_IMAGE_VERSION;
  image.width = static_cast<png_uint_32>(width);
  image.height = static_cast<png_uint_32>(height);
  image.format = PNG_FORMAT_RGBA;
  // A negative stride: the first row in memory is the image's bottom.
  const png_int_32 stride = -static_cast<png_int_32>(4 * width);
  png_alloc_size_t size = 0;
  if (!png_image_write_to_memory(&image, nullptr, &size, 0, rgba.data(), stride, nullptr))
  {
    throw InputError(std::string("libpng cannot encode the texture: ") + image.message);
  }
  std::string bytes(size, '\0');
  if (!png_image_write_to_memory(&image, &bytes[0], &size, 0, rgba.data(), stride, nullptr))
  {
    throw InputError(std::string("libpng cannot encode the texture: ") + image.message);
  }
  bytes.resize(size);
  png_image_free(&image);
  return bytes;
}
} // namespace tc
