// What arcus_view puts on screen and reads back: the 8-bit sRGB image, drawn with
// legacy OpenGL, the window's pixels and the PNG screenshot.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

namespace arcus_view {

// An 8-bit RGB image, rows bottom to top as OpenGL stores them.
struct Pixels {
  uint32_t width = 0, height = 0;
  std::vector<uint8_t> rgb;
};

// The library's linear RGB image (top row first) scaled by `exposure`, encoded with the
// sRGB transfer function, clamped and rounded exactly as arcus_job_write_render_image's PNG.
Pixels to_srgb8(const std::vector<float>& linear_rgb, uint32_t width, uint32_t height, double exposure);

// Draws `image` stretched over the framebuffer (nearest pixel, so a coarse frame shows
// as blocks); 1:1 when the sizes agree, where glDrawPixels copies the bytes unchanged.
void draw(const Pixels& image, int framebuffer_width, int framebuffer_height);

// The current back buffer's pixels (call after draw, before the buffers are swapped).
Pixels read_back(int framebuffer_width, int framebuffer_height);

// Writes the pixels as a PNG through OpenImageIO, top row first; throws
// std::runtime_error with OIIO's message on failure.
void write_png(const std::string& path, const Pixels& image);

}  // namespace arcus_view
