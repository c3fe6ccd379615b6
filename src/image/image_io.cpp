#include "image/image_io.h"

#include <OpenImageIO/imageio.h>
#include <OpenImageIO/strutil.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <filesystem>
#include <memory>
#include <new>
#include <set>

#include "core/error.h"
#include "core/files.h"
#include "core/format.h"
#include "core/limits.h"
#include "spectral/srgb.h"

namespace arcus::image {

namespace {

// OIIO's own account of a failure, for the end of our message ("" becomes a note that
// there is none, so a message never ends in a dangling colon).
std::string detail(std::string message) {
  while (!message.empty() && std::isspace(static_cast<unsigned char>(message.back()))) message.pop_back();
  return message.empty() ? "OpenImageIO gave no reason" : message;
}

[[noreturn]] void fail_io(const std::string& path, const std::string& what, const std::string& oiio) {
  fail(ARCUS_ERROR_IO, path + ": " + what + ": " + detail(oiio));
}

void check(const Image& image, const std::string& path) {
  const std::string where = path + ": ";
  require(image.width > 0 && image.height > 0,
          where + "image is " + std::to_string(image.width) + " x " + std::to_string(image.height) + " pixels");
  require(!image.channels.empty(), where + "image has no channels");
  const size_t expected = static_cast<size_t>(image.width) * image.height * image.channels.size();
  require(image.pixels.size() == expected, where + "image has " + std::to_string(image.pixels.size()) +
                                               " values for " + std::to_string(expected) + " (width x height x " +
                                               std::to_string(image.channels.size()) + " channels)");
  std::set<std::string> seen;
  for (const std::string& name : image.channels) {
    require(!name.empty(), where + "a channel has no name");
    require(seen.insert(name).second, where + "two channels are called \"" + name + "\"");
  }
}

// Creates a writer of `format` (an OIIO format name, so the function decides the
// format, not the file's extension) and writes `data`, laid out as `spec` says.
void write(const std::string& path, const char* format, const OIIO::ImageSpec& spec, OIIO::TypeDesc data_type,
           const void* data) {
  auto out = OIIO::ImageOutput::create(format);
  if (!out) fail_io(path, std::string("no ") + format + " writer", OIIO::geterror());
  if (!out->open(path, spec)) fail_io(path, "cannot write", out->geterror());
  const bool wrote = out->write_image(data_type, data);
  const bool closed = out->close();
  if (!wrote || !closed) fail_io(path, "cannot write", out->geterror());
}

struct Read {
  Image image;
  bool encoded = false;  // integer pixels not declared linear: sRGB-encoded
};

// The file opened, its header read and checked (a flat image with pixels, within the
// pixel bound), no pixels.  Only a regular file is handed to OpenImageIO: a FIFO would
// block its open for ever and /dev/zero keep its format probe spinning.
std::unique_ptr<OIIO::ImageInput> open_file(const std::string& path) {
  files::require_regular(path);
  // Colour as stored: OIIO would otherwise multiply it by alpha, which for an encoded
  // file comes before decoding and darkens translucent texels twice.
  OIIO::ImageSpec config;
  config.attribute("oiio:UnassociatedAlpha", 1);
  auto in = OIIO::ImageInput::open(path, &config);
  if (!in) fail_io(path, "cannot read", OIIO::geterror());
  const OIIO::ImageSpec& spec = in->spec();
  if (spec.deep || spec.depth > 1) fail(ARCUS_ERROR_IO, path + ": deep and volume images are not read");
  if (spec.width <= 0 || spec.height <= 0 || spec.nchannels <= 0)
    fail(ARCUS_ERROR_IO, path + ": image is " + std::to_string(spec.width) + " x " + std::to_string(spec.height) +
                             " pixels of " + std::to_string(spec.nchannels) + " channels");
  const uint64_t pixels = uint64_t(spec.width) * uint64_t(spec.height);
  if (pixels > limits::image_pixels())
    fail(ARCUS_ERROR_IO, path + ": image is " + std::to_string(spec.width) + " x " + std::to_string(spec.height) +
                             " pixels, more than the " + std::to_string(limits::image_pixels()) +
                             " allowed (ARCUS_MAX_IMAGE_PIXELS raises the bound)");
  return in;
}

// Rows decoded at a time: memory grows with the rows a file actually holds, so a small
// file whose header claims a huge image fails at its first missing row, having used
// little (the whole buffer used to be zero-filled before decoding began).
constexpr int kRowsAtATime = 64;

Read read_file(const std::string& path) {
  const auto in = open_file(path);
  const OIIO::ImageSpec& spec = in->spec();
  Read read;
  Image& image = read.image;
  image.width = spec.width;
  image.height = spec.height;
  image.channels = spec.channelnames;
  image.channels.resize(spec.nchannels);
  const size_t row = static_cast<size_t>(spec.width) * spec.nchannels;
  // The pixels, and the RGB copy read_image makes of them.
  limits::require_host_memory(double(row) * spec.height * sizeof(float) + double(spec.width) * spec.height * 12.0,
                              path + ": a " + std::to_string(spec.width) + " x " + std::to_string(spec.height) +
                                  " image of " + std::to_string(spec.nchannels) + " channels");
  image.pixels.reserve(row * spec.height);  // address space only, until rows arrive
  for (int y = 0; y < spec.height; y += kRowsAtATime) {
    const int rows = std::min(kRowsAtATime, spec.height - y);
    image.pixels.resize(row * (y + rows));
    if (!in->read_scanlines(0, 0, spec.y + y, spec.y + y + rows, 0, 0, spec.nchannels, OIIO::TypeDesc::FLOAT,
                            image.pixels.data() + row * y))
      fail_io(path, "cannot read", in->geterror());
  }
  read.encoded = !spec.format.is_floating_point() &&
                 !OIIO::Strutil::iequals(spec.get_string_attribute("oiio:ColorSpace"), "Linear");
  return read;
}

}  // namespace

int Image::channel_index(const std::string& name) const {
  const auto it = std::find(channels.begin(), channels.end(), name);
  return it == channels.end() ? -1 : static_cast<int>(it - channels.begin());
}

void write_exr(const std::string& path, const Image& image, ExrPixels pixels) {
  check(image, path);
  const int n = static_cast<int>(image.channels.size());
  OIIO::ImageSpec spec(image.width, image.height, n,
                       pixels == ExrPixels::Half ? OIIO::TypeDesc::HALF : OIIO::TypeDesc::FLOAT);
  spec.channelnames = image.channels;
  // The constructor guessed alpha from the count (a 4th channel); only "A" is alpha.
  spec.alpha_channel = image.channel_index("A");
  spec.z_channel = -1;
  write(path, "openexr", spec, OIIO::TypeDesc::FLOAT, image.pixels.data());
}

namespace {

// 8-bit sRGB of the channels R, G, B times `exposure`, written by OIIO's `format` writer.
void write_8bit(const std::string& path, const char* format, const Image& linear_rgb, double exposure) {
  check(linear_rgb, path);
  require(std::isfinite(exposure) && exposure > 0.0, path + ": exposure " + number(exposure) + " is not positive");
  int source[3];
  for (int c = 0; c < 3; ++c) {
    source[c] = linear_rgb.channel_index(std::string(1, "RGB"[c]));
    require(source[c] >= 0, path + ": image has no " + std::string(1, "RGB"[c]) + " channel");
  }
  const size_t count = static_cast<size_t>(linear_rgb.width) * linear_rgb.height, n = linear_rgb.channels.size();
  std::vector<uint8_t> bytes(count * 3);
  for (size_t p = 0; p < count; ++p)
    for (int c = 0; c < 3; ++c)
      bytes[p * 3 + c] = spectral::srgb_encode_8bit(exposure * linear_rgb.pixels[p * n + source[c]]);
  OIIO::ImageSpec spec(linear_rgb.width, linear_rgb.height, 3, OIIO::TypeDesc::UINT8);
  spec.attribute("oiio:ColorSpace", "sRGB");
  if (std::string(format) == "jpeg") spec.attribute("Compression", "jpeg:92");
  write(path, format, spec, OIIO::TypeDesc::UINT8, bytes.data());
}

}  // namespace

void write_png(const std::string& path, const Image& linear_rgb, double exposure) {
  write_8bit(path, "png", linear_rgb, exposure);
}

void write_by_extension(const std::string& path, const Image& linear_rgb) {
  std::string ext = std::filesystem::path(path).extension().string();
  std::transform(ext.begin(), ext.end(), ext.begin(), [](unsigned char c) { return std::tolower(c); });
  if (ext == ".exr") return write_exr(path, linear_rgb);
  if (ext == ".png") return write_8bit(path, "png", linear_rgb, 1.0);
  if (ext == ".jpg" || ext == ".jpeg") return write_8bit(path, "jpeg", linear_rgb, 1.0);
  if (ext == ".hdr") {
    check(linear_rgb, path);
    require(linear_rgb.channels.size() == 3, path + ": expected 3 channels (R, G, B)");
    OIIO::ImageSpec spec(linear_rgb.width, linear_rgb.height, 3, OIIO::TypeDesc::FLOAT);
    return write(path, "hdr", spec, OIIO::TypeDesc::FLOAT, linear_rgb.pixels.data());
  }
  fail(ARCUS_ERROR_INVALID_ARGUMENT,
       "path: " + path + ": unknown image format \"" + ext + "\" (expected .exr, .hdr, .png, .jpg or .jpeg)");
}

Image read_channels(const std::string& path) { return read_file(path).image; }

std::array<int, 2> read_size(const std::string& path) {
  const auto in = open_file(path);
  return {in->spec().width, in->spec().height};
}

Image read_image(const std::string& path) {
  const Read read = read_file(path);
  const Image& raw = read.image;
  const int n = static_cast<int>(raw.channels.size());
  int source[3] = {raw.channel_index("R"), raw.channel_index("G"), raw.channel_index("B")};
  if (source[0] < 0 || source[1] < 0 || source[2] < 0) {
    for (int c = 0; c < 3; ++c) source[c] = n >= 3 ? c : 0;
  }
  Image rgb;
  rgb.width = raw.width;
  rgb.height = raw.height;
  rgb.channels = {"R", "G", "B"};
  const size_t count = static_cast<size_t>(raw.width) * raw.height;
  rgb.pixels.resize(count * 3);
  for (size_t p = 0; p < count; ++p)
    for (int c = 0; c < 3; ++c) {
      const float v = raw.pixels[p * n + source[c]];
      rgb.pixels[p * 3 + c] = read.encoded ? static_cast<float>(spectral::srgb_decode(v)) : v;
    }
  // A colour or radiance must be a number: a NaN or infinite texel would make NaN or
  // infinite pixels of every image it is seen in.  One pass, a message only on failure.
  const auto bad = std::find_if(rgb.pixels.begin(), rgb.pixels.end(), [](float v) { return !std::isfinite(v); });
  if (bad != rgb.pixels.end()) {
    const size_t at = static_cast<size_t>(bad - rgb.pixels.begin());
    fail(ARCUS_ERROR_INVALID_ARGUMENT, path + ": pixel (" + std::to_string(at / 3 % rgb.width) + ", " +
                                           std::to_string(at / 3 / rgb.width) + ") " + "RGB"[at % 3] + " = " +
                                           number(*bad) + " is not finite");
  }
  return rgb;
}

void require_finite_pixels(const std::vector<float>& pixels, int width, const char* channel_names,
                           const std::string& what) {
  const size_t channels = std::strlen(channel_names);
  size_t bad = 0, first = 0;
  for (size_t i = 0; i < pixels.size(); i += channels)
    for (size_t c = 0; c < channels; ++c)
      if (!std::isfinite(pixels[i + c])) {
        if (bad++ == 0) first = i + c;
        break;
      }
  if (!bad) return;
  const size_t pixel = first / channels;
  fail(ARCUS_ERROR_NOT_FINITE, what + ": " + std::to_string(bad) + " of " + std::to_string(pixels.size() / channels) +
                                   " pixels are not finite; the first is (" + std::to_string(pixel % width) + ", " +
                                   std::to_string(pixel / width) + "), whose " + channel_names[first % channels] +
                                   " is " + number(pixels[first]));
}

std::array<float, 3> sample_bilinear(const Image& image, double u, double v, bool wrap_u) {
  const size_t n = image.channels.size();
  // Checked with `if`, not require(), so that a sample builds no message strings.
  if (image.width <= 0 || image.height <= 0 || n < 3 ||
      image.pixels.size() != static_cast<size_t>(image.width) * image.height * n)
    fail(ARCUS_ERROR_INVALID_ARGUMENT, "sample_bilinear: image is not width x height pixels of at least 3 channels");
  if (!std::isfinite(u) || !std::isfinite(v))
    fail(ARCUS_ERROR_INVALID_ARGUMENT,
         "sample_bilinear: (u, v) = (" + number(u) + ", " + number(v) + ") is not finite");
  // Periodic in u when wrapping: only u's fractional part matters, which also keeps
  // huge u from overflowing the index.
  u = wrap_u ? u - std::floor(u) : std::clamp(u, 0.0, 1.0);
  v = std::clamp(v, 0.0, 1.0);
  const double x = u * image.width - 0.5, y = v * image.height - 0.5;
  const double fx0 = std::floor(x), fy0 = std::floor(y);
  const double fx = x - fx0, fy = y - fy0;
  auto column = [&](int i) {
    return wrap_u ? (i % image.width + image.width) % image.width : std::clamp(i, 0, image.width - 1);
  };
  const int x0 = column(static_cast<int>(fx0)), x1 = column(static_cast<int>(fx0) + 1);
  const int y0 = std::clamp(static_cast<int>(fy0), 0, image.height - 1);
  const int y1 = std::clamp(static_cast<int>(fy0) + 1, 0, image.height - 1);
  auto texel = [&](int i, int j, int c) { return image.pixels[(static_cast<size_t>(j) * image.width + i) * n + c]; };
  std::array<float, 3> out;
  for (int c = 0; c < 3; ++c) {
    const double top = (1.0 - fx) * texel(x0, y0, c) + fx * texel(x1, y0, c);
    const double bottom = (1.0 - fx) * texel(x0, y1, c) + fx * texel(x1, y1, c);
    out[c] = static_cast<float>((1.0 - fy) * top + fy * bottom);
  }
  return out;
}

std::array<double, 2> equirect_uv(double x, double y, double z) {
  constexpr double kPi = 3.14159265358979323846;
  return {0.5 + std::atan2(x, -z) / (2 * kPi), std::acos(std::clamp(y, -1.0, 1.0)) / kPi};
}

}  // namespace arcus::image
