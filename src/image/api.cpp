// The image C API (include/arcus/arcus_image.h): input images, read through image_io.
#include <algorithm>

#include "arcus/arcus_image.h"
#include "core/call.h"
#include "image/image_io.h"

using namespace arcus;
using namespace arcus::api;

arcus_status arcus_image_read(const char* path, uint32_t* width, uint32_t* height, float* rgb, size_t rgb_count) {
  return without_context([&] {
    require_pointer(path, "path");
    if (!rgb) {  // the size query reads the header only, not the pixels twice
      const auto size = image::read_size(path);
      if (width) *width = static_cast<uint32_t>(size[0]);
      if (height) *height = static_cast<uint32_t>(size[1]);
      return;
    }
    const image::Image im = image::read_image(path);
    // The file may have changed since the caller learnt its size: never write past rgb.
    require(im.pixels.size() <= rgb_count, "rgb_count = " + std::to_string(rgb_count) + ": " + path + " now holds " +
                                               std::to_string(im.width) + " x " + std::to_string(im.height) +
                                               " pixels, which need " + std::to_string(im.pixels.size()) + " floats");
    if (width) *width = static_cast<uint32_t>(im.width);
    if (height) *height = static_cast<uint32_t>(im.height);
    std::copy(im.pixels.begin(), im.pixels.end(), rgb);
  });
}

arcus_status arcus_image_write(const char* path, uint32_t width, uint32_t height, const float* rgb) {
  return without_context([&] {
    require_pointer(path, "path");
    require_pointer(rgb, "rgb");
    require(width > 0 && height > 0, "width, height: " + std::to_string(width) + " x " + std::to_string(height) +
                                         " is not an image");
    image::Image im;
    im.width = static_cast<int>(width);
    im.height = static_cast<int>(height);
    im.channels = {"R", "G", "B"};
    im.pixels.assign(rgb, rgb + size_t(width) * height * 3);
    image::require_finite_pixels(im.pixels, im.width, "RGB", std::string("rgb (") + path + ")");
    image::write_by_extension(path, im);
  });
}
