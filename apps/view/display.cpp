#include "display.h"

#include <GLFW/glfw3.h>  // includes the system's GL/gl.h (legacy OpenGL 1.x)
#include <OpenImageIO/imageio.h>

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace arcus_view {
namespace {

// The library's 8-bit sRGB encoding (src/spectral/srgb.cpp, internal to libarcus),
// repeated operation for operation in double precision so that the window shows the
// very bytes of arcus_render's PNG.
uint8_t srgb_encode_8bit(double linear) {
  if (!(linear > 0.0)) return 0;  // NaN too
  const double encoded = linear <= 0.0031308 ? 12.92 * linear : 1.055 * std::pow(linear, 1.0 / 2.4) - 0.055;
  return static_cast<uint8_t>(std::lround(std::min(encoded, 1.0) * 255.0));
}

}  // namespace

Pixels to_srgb8(const std::vector<float>& linear_rgb, uint32_t width, uint32_t height, double exposure) {
  Pixels out{width, height, std::vector<uint8_t>(linear_rgb.size())};
  const size_t row = static_cast<size_t>(width) * 3;
  for (uint32_t y = 0; y < height; ++y) {
    const float* from = &linear_rgb[static_cast<size_t>(y) * row];
    uint8_t* to = &out.rgb[static_cast<size_t>(height - 1 - y) * row];  // OpenGL: bottom row first
    for (size_t i = 0; i < row; ++i) to[i] = srgb_encode_8bit(exposure * from[i]);
  }
  return out;
}

void draw(const Pixels& image, int framebuffer_width, int framebuffer_height) {
  glViewport(0, 0, framebuffer_width, framebuffer_height);
  glClearColor(0, 0, 0, 1);
  glClear(GL_COLOR_BUFFER_BIT);
  if (image.width == 0 || image.height == 0) return;
  glMatrixMode(GL_PROJECTION);
  glLoadIdentity();
  glMatrixMode(GL_MODELVIEW);
  glLoadIdentity();
  // Dithering may perturb colours on their way to the framebuffer; the screenshot must
  // hold the bytes given.
  glDisable(GL_DITHER);
  glPixelStorei(GL_UNPACK_ALIGNMENT, 1);
  glRasterPos2f(-1.0f, -1.0f);  // the framebuffer's bottom-left corner
  glPixelZoom(static_cast<float>(framebuffer_width) / image.width,
              static_cast<float>(framebuffer_height) / image.height);
  glDrawPixels(static_cast<GLsizei>(image.width), static_cast<GLsizei>(image.height), GL_RGB, GL_UNSIGNED_BYTE,
               image.rgb.data());
}

Pixels read_back(int framebuffer_width, int framebuffer_height) {
  Pixels out{static_cast<uint32_t>(framebuffer_width), static_cast<uint32_t>(framebuffer_height),
             std::vector<uint8_t>(static_cast<size_t>(framebuffer_width) * framebuffer_height * 3)};
  glFinish();
  glReadBuffer(GL_BACK);
  glPixelStorei(GL_PACK_ALIGNMENT, 1);
  glReadPixels(0, 0, framebuffer_width, framebuffer_height, GL_RGB, GL_UNSIGNED_BYTE, out.rgb.data());
  if (glGetError() != GL_NO_ERROR) throw std::runtime_error("glReadPixels failed");
  return out;
}

void write_png(const std::string& path, const Pixels& image) {
  auto out = OIIO::ImageOutput::create("png");
  if (!out) throw std::runtime_error(path + ": no PNG writer: " + OIIO::geterror());
  OIIO::ImageSpec spec(static_cast<int>(image.width), static_cast<int>(image.height), 3, OIIO::TypeDesc::UINT8);
  spec.attribute("oiio:ColorSpace", "sRGB");
  if (!out->open(path, spec)) throw std::runtime_error(path + ": cannot write: " + out->geterror());
  // Rows are stored bottom to top: start at the last and step backwards (the row flip).
  const OIIO::stride_t row = static_cast<OIIO::stride_t>(image.width) * 3;
  const bool wrote = out->write_image(OIIO::TypeDesc::UINT8, image.rgb.data() + (image.height - 1) * row,
                                      OIIO::AutoStride, -row);
  const bool closed = out->close();
  if (!wrote || !closed) throw std::runtime_error(path + ": cannot write: " + out->geterror());
}

}  // namespace arcus_view
