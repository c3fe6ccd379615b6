// Images in and out, all through OpenImageIO: EXR with every channel kept by name (the
// renderer's colour and its per-pixel data), sRGB PNG for viewing, and any format OIIO
// reads as linear RGB (textures, equirectangular skies).
#pragma once

#include <array>
#include <string>
#include <vector>

namespace arcus::image {

struct Image {
  int width = 0, height = 0;
  std::vector<std::string> channels;  // names: "R", "G", "B", "hit_distance", ...
  std::vector<float> pixels;          // width * height * channels.size(), row-major, top row first

  // Index of the channel called `name`, or -1.
  int channel_index(const std::string& name) const;
};

enum class ExrPixels { Float, Half };

// Writes an OpenEXR file with every channel by name (OpenEXR stores them sorted by
// name, so read them back by name, not position).  Float keeps values exactly; Half
// keeps 11 bits, enough for colour, not for distances or counts.
void write_exr(const std::string& path, const Image& image, ExrPixels pixels = ExrPixels::Float);

// Writes an 8-bit sRGB PNG of the channels named R, G and B, each scaled by `exposure`,
// encoded with the sRGB transfer function, clamped to [0, 1] and rounded.
void write_png(const std::string& path, const Image& linear_rgb, double exposure = 1.0);

// Writes linear RGB to a file whose format follows its extension: .exr and .hdr keep
// the floats (linear), .png and .jpg/.jpeg are 8-bit sRGB (as write_png, exposure 1).
// Another extension is ARCUS_ERROR_INVALID_ARGUMENT naming the path and the formats.
void write_by_extension(const std::string& path, const Image& linear_rgb);

// Reads the first image of any file OIIO reads as channels "R", "G", "B", linear float:
// integer files (PNG, JPEG, 8/16-bit TIFF) are taken as sRGB-encoded and decoded with
// the inverse transfer function unless they declare themselves linear; float files
// (EXR, HDR) are read as they are.  Colour comes from the channels named R, G, B, else
// the first three; one or two channels (grey, grey + alpha) give grey.  Alpha is
// dropped, and colour is not multiplied by it.  A file that is not a regular file is
// ARCUS_ERROR_IO, as is one of more than ARCUS_MAX_IMAGE_PIXELS (core/limits.h); a
// non-finite value is ARCUS_ERROR_INVALID_ARGUMENT naming the pixel.
Image read_image(const std::string& path);

// The width and height read_image would return, from the file's header alone.
std::array<int, 2> read_size(const std::string& path);

// Reads the first image of a file with every channel as stored, by name, no colour
// conversion: the counterpart of write_exr.
Image read_channels(const std::string& path);

// Every image job's last check: ARCUS_ERROR_NOT_FINITE unless every value of `pixels`
// (width x ... pixels of `channels` values, named by `channel_names`, e.g. "RGB") is
// finite: "<what>: 32 of 192 pixels are not finite; the first is (3, 5), whose G is nan".
// A NaN or infinite pixel is a numerical failure, never an image.
void require_finite_pixels(const std::vector<float>& pixels, int width, const char* channel_names,
                           const std::string& what);

// Bilinear sample of the first three channels at (u, v) in [0, 1]²: u = 0 is the left
// edge, v = 0 the top edge, texel (i, j) is centred at ((i + ½) / width, (j + ½) / height),
// so texel centres are returned exactly.  Across u the image wraps around when `wrap_u`
// (equirectangular skies: u is longitude) and is clamped to the edge texels otherwise;
// across v it is always clamped.  u and v must be finite.
std::array<float, 3> sample_bilinear(const Image& image, double u, double v, bool wrap_u);

// Where a unit direction (x, y, z) lands on an equirectangular map of the whole sphere
// (every sky image of every engine): y up, so v = acos(y)/π runs from the zenith (top
// row) to the nadir; u = ½ + atan2(x, −z)/2π puts −z at the centre column and +x at ¾.
std::array<double, 2> equirect_uv(double x, double y, double z);

}  // namespace arcus::image
