// Images in and out (src/image/image_io) through OpenImageIO: EXR keeps every channel
// exactly and by name, PNG is 8-bit sRGB and decodes back to the quantised linear value,
// read_image gives linear RGB whatever the file, errors name the file and carry OIIO's
// reason, and bilinear sampling is exact at texel centres, wrapping or clamping at edges.
// Hostile input: special files, headers claiming huge images, NaN and infinite texels.
#include <OpenImageIO/imageio.h>
#include <sys/resource.h>
#include <sys/stat.h>
#include <unistd.h>

#include <gtest/gtest.h>

#include <chrono>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <functional>
#include <string>
#include <vector>

#include "core/error.h"
#include "image/image_io.h"
#include "spectral/srgb.h"
#include "unit_util.h"

namespace {

using arcus::image::ExrPixels;
using arcus::image::Image;
using arcus::image::read_channels;
using arcus::image::read_image;
using arcus::image::sample_bilinear;
using arcus::image::write_exr;
using arcus::image::write_png;
using arcus::spectral::srgb_decode;
using arcus::spectral::srgb_encode;
using arcus::spectral::srgb_encode_8bit;
using arcus_unit::TempDir;

Image make(int w, int h, std::vector<std::string> channels, const std::function<float(int, int, int)>& value) {
  Image image;
  image.width = w;
  image.height = h;
  image.channels = std::move(channels);
  const int n = static_cast<int>(image.channels.size());
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x)
      for (int c = 0; c < n; ++c) image.pixels.push_back(value(x, y, c));
  return image;
}

float at(const Image& image, int x, int y, const std::string& channel) {
  const int c = image.channel_index(channel);
  EXPECT_GE(c, 0) << channel;
  return image.pixels[(static_cast<size_t>(y) * image.width + x) * image.channels.size() + c];
}

// The error `f` throws; fails the test if there is none.
arcus::Error error_of(const std::function<void()>& f) {
  try {
    f();
  } catch (const arcus::Error& e) {
    return e;
  }
  ADD_FAILURE() << "no error";
  return arcus::Error(ARCUS_SUCCESS, "");
}

bool contains(const std::string& s, const std::string& part) { return s.find(part) != std::string::npos; }

TEST(ImageIo, ExrRoundTripIsExactWithChannelsByName) {
  TempDir dir;
  const std::string path = dir.path() + "/render.exr";
  // Values a half or a colour-managed path would change: big, tiny, negative, counts.
  const std::vector<std::string> names = {"R", "G", "B", "hit_distance", "steps", "tests"};
  const Image image = make(7, 5, names, [](int x, int y, int c) {
    switch (c) {
      case 3: return 1234.5678f * (x + 1) + 1e-3f * y;
      case 4: return static_cast<float>(16777216 - x * 977 - y);
      case 5: return static_cast<float>(x * y);
      default: return std::ldexp(1.0f + 0.1234567f * c, x - y) * (y % 2 ? -1.0f : 1.0f) + 1e-30f * x;
    }
  });
  write_exr(path, image);
  const Image back = read_channels(path);
  ASSERT_EQ(back.width, 7);
  ASSERT_EQ(back.height, 5);
  ASSERT_EQ(back.channels.size(), names.size());
  for (const std::string& name : names)
    for (int y = 0; y < 5; ++y)
      for (int x = 0; x < 7; ++x)
        ASSERT_EQ(at(back, x, y, name), at(image, x, y, name)) << name << " " << x << "," << y;
  // read_image takes R, G, B of an EXR as they are.
  const Image rgb = read_image(path);
  ASSERT_EQ(rgb.channels, (std::vector<std::string>{"R", "G", "B"}));
  for (int y = 0; y < 5; ++y)
    for (int x = 0; x < 7; ++x)
      for (const char* c : {"R", "G", "B"}) ASSERT_EQ(at(rgb, x, y, c), at(image, x, y, c));
}

TEST(ImageIo, ExrFourChannelsAreNotTakenForAlpha) {
  // OIIO guesses the 4th channel of 4 is alpha; only one called "A" is.
  TempDir dir;
  const std::string path = dir.path() + "/depth.exr";
  const Image image =
      make(3, 2, {"R", "G", "B", "depth"}, [](int x, int y, int c) { return c == 3 ? 0.0f : x + y + 0.5f; });
  write_exr(path, image);
  const Image back = read_channels(path);
  for (int y = 0; y < 2; ++y)
    for (int x = 0; x < 3; ++x) {
      EXPECT_EQ(at(back, x, y, "depth"), 0.0f);
      EXPECT_EQ(at(back, x, y, "R"), x + y + 0.5f);
    }
}

TEST(ImageIo, ExrHalfKeepsElevenBits) {
  TempDir dir;
  const std::string path = dir.path() + "/half.exr";
  const Image image = make(4, 4, {"R", "G", "B"}, [](int x, int y, int c) { return 0.1f * (x + 4 * y + c) + 0.25f; });
  write_exr(path, image, ExrPixels::Half);
  auto in = OIIO::ImageInput::open(path);
  ASSERT_TRUE(in);
  EXPECT_EQ(in->spec().format, OIIO::TypeDesc::HALF);
  in.reset();
  const Image back = read_channels(path);
  for (size_t i = 0; i < image.pixels.size(); ++i) EXPECT_NEAR(back.pixels[i], image.pixels[i], image.pixels[i] / 1024);
}

TEST(ImageIo, PngRoundTripIsTheQuantisedValue) {
  TempDir dir;
  const std::string path = dir.path() + "/view.png";
  // A ramp past both ends plus an extra channel that write_png must ignore.
  const Image image = make(64, 3, {"steps", "B", "G", "R"}, [](int x, int y, int c) {
    return c == 0 ? 99.0f : static_cast<float>((x - 4) / 56.0 * std::pow(0.8, y + c));
  });
  write_png(path, image);
  const Image back = read_image(path);
  ASSERT_EQ(back.width, 64);
  ASSERT_EQ(back.height, 3);
  for (int y = 0; y < 3; ++y)
    for (int x = 0; x < 64; ++x)
      for (const char* c : {"R", "G", "B"}) {
        const double linear = at(image, x, y, c), read = at(back, x, y, c);
        EXPECT_NEAR(read, srgb_decode(srgb_encode_8bit(linear) / 255.0), 1e-6) << c << " " << x << "," << y;
        // Within half a code of the original, in the encoded (display) scale.
        const double clamped = std::min(std::max(linear, 0.0), 1.0);
        EXPECT_LE(std::fabs(srgb_encode(read) - srgb_encode(clamped)), 0.5 / 255 + 1e-6) << c << " " << x << "," << y;
      }
}

TEST(ImageIo, PngExposureScalesBeforeEncoding) {
  TempDir dir;
  const Image image = make(2, 2, {"R", "G", "B"}, [](int x, int y, int c) { return 0.1f * (1 + x + 2 * y + c); });
  Image doubled = image;
  for (float& v : doubled.pixels) v *= 2;
  write_png(dir.path() + "/a.png", image, 2.0);
  write_png(dir.path() + "/b.png", doubled);
  EXPECT_EQ(read_image(dir.path() + "/a.png").pixels, read_image(dir.path() + "/b.png").pixels);
}

TEST(ImageIo, GreyAlphaPngIsGreyAndNotPremultiplied) {
  TempDir dir;
  const std::string path = dir.path() + "/grey.png";
  const unsigned char pixels[] = {128, 64, 255, 0};  // (grey, alpha) x 2
  auto out = OIIO::ImageOutput::create(path);
  ASSERT_TRUE(out);
  OIIO::ImageSpec spec(2, 1, 2, OIIO::TypeDesc::UINT8);
  spec.alpha_channel = 1;
  spec.attribute("oiio:UnassociatedAlpha", 1);  // as given, not divided by alpha
  ASSERT_TRUE(out->open(path, spec));
  ASSERT_TRUE(out->write_image(OIIO::TypeDesc::UINT8, pixels));
  ASSERT_TRUE(out->close());
  const Image back = read_image(path);
  for (const char* c : {"R", "G", "B"}) {
    EXPECT_NEAR(at(back, 0, 0, c), srgb_decode(128 / 255.0), 1e-6) << c;
    EXPECT_NEAR(at(back, 1, 0, c), 1.0, 1e-6) << c;
  }
}

TEST(ImageIo, MissingFileIsAnIoErrorNamingIt) {
  TempDir dir;
  const std::string path = dir.path() + "/no_such_sky.exr";
  const arcus::Error e = error_of([&] { read_image(path); });
  EXPECT_EQ(e.status(), ARCUS_ERROR_IO);
  EXPECT_TRUE(contains(e.what(), path + ": cannot read: ")) << e.what();
  EXPECT_FALSE(contains(e.what(), "gave no reason")) << e.what();
}

TEST(ImageIo, TextFileNamedPngIsAnIoErrorWithOiiosReason) {
  TempDir dir;
  const std::string path = dir.path() + "/texture.png";
  std::ofstream(path) << "this is not an image\n";
  const arcus::Error e = error_of([&] { read_image(path); });
  EXPECT_EQ(e.status(), ARCUS_ERROR_IO);
  EXPECT_TRUE(contains(e.what(), path + ": cannot read: ")) << e.what();
  EXPECT_FALSE(contains(e.what(), "gave no reason")) << e.what();
}

TEST(ImageIo, UnwritablePathIsAnIoErrorNamingIt) {
  TempDir dir;
  const Image image = make(2, 2, {"R", "G", "B"}, [](int, int, int) { return 0.5f; });
  for (const std::string& path : {dir.path() + "/missing_dir/out.exr", dir.path() + "/missing_dir/out.png"}) {
    const arcus::Error e = error_of([&] {
      if (path.back() == 'r')
        write_exr(path, image);
      else
        write_png(path, image);
    });
    EXPECT_EQ(e.status(), ARCUS_ERROR_IO) << e.what();
    EXPECT_TRUE(contains(e.what(), path + ": cannot write: ")) << e.what();
  }
}

TEST(ImageIo, BadImagesAreInvalidArguments) {
  TempDir dir;
  const std::string path = dir.path() + "/x.exr";
  const Image good = make(2, 2, {"R", "G", "B"}, [](int, int, int) { return 0.5f; });
  auto expect_invalid = [&](const Image& image, const std::string& what) {
    for (bool png : {false, true}) {
      const arcus::Error e = error_of([&] { png ? write_png(path, image) : write_exr(path, image); });
      EXPECT_EQ(e.status(), ARCUS_ERROR_INVALID_ARGUMENT) << e.what();
      EXPECT_TRUE(contains(e.what(), path + ": ") && contains(e.what(), what)) << e.what();
    }
  };
  Image zero = good;
  zero.width = 0;
  zero.pixels.clear();
  expect_invalid(zero, "0 x 2 pixels");
  Image short_of_pixels = good;
  short_of_pixels.pixels.pop_back();
  expect_invalid(short_of_pixels, "11 values for 12");
  Image twice = good;
  twice.channels[2] = "R";
  expect_invalid(twice, "two channels are called \"R\"");
  Image no_channels = good;
  no_channels.channels.clear();
  expect_invalid(no_channels, "no channels");
  Image no_blue = make(2, 2, {"R", "G", "Z"}, [](int, int, int) { return 0.5f; });
  EXPECT_EQ(error_of([&] { write_png(path, no_blue); }).status(), ARCUS_ERROR_INVALID_ARGUMENT);
  EXPECT_EQ(error_of([&] { write_png(path, good, 0.0); }).status(), ARCUS_ERROR_INVALID_ARGUMENT);
  EXPECT_EQ(error_of([&] { write_png(path, good, NAN); }).status(), ARCUS_ERROR_INVALID_ARGUMENT);
}

// 4 x 3 texels, each channel a different plane so every texel is distinct.
Image grid() {
  return make(4, 3, {"R", "G", "B"}, [](int x, int y, int c) { return 10.0f * x + 100.0f * y + c; });
}

TEST(Bilinear, TexelCentresAreExact) {
  const Image image = grid();
  for (bool wrap : {false, true})
    for (int y = 0; y < 3; ++y)
      for (int x = 0; x < 4; ++x) {
        const auto s = sample_bilinear(image, (x + 0.5) / 4, (y + 0.5) / 3, wrap);
        for (int c = 0; c < 3; ++c) EXPECT_EQ(s[c], 10.0f * x + 100.0f * y + c) << x << "," << y << " wrap " << wrap;
      }
}

TEST(Bilinear, InterpolatesBetweenCentres) {
  const Image image = grid();
  // Halfway between texels (1, 0) and (2, 1), a quarter of the way across.
  const auto mid = sample_bilinear(image, 2.0 / 4, 1.0 / 3, false);
  EXPECT_FLOAT_EQ(mid[0], 15.0f + 50.0f);
  const auto quarter = sample_bilinear(image, (1.5 + 0.25) / 4, 0.5 / 3, false);
  EXPECT_FLOAT_EQ(quarter[1], 12.5f + 1.0f);
}

TEST(Bilinear, WrapsOrClampsAcrossUAndClampsAcrossV) {
  const Image image = grid();
  // u = 0 lies halfway between the last column and the first when wrapping.
  EXPECT_FLOAT_EQ(sample_bilinear(image, 0.0, 0.5 / 3, true)[0], 15.0f);
  EXPECT_FLOAT_EQ(sample_bilinear(image, 1.0, 0.5 / 3, true)[0], 15.0f);
  EXPECT_FLOAT_EQ(sample_bilinear(image, 0.0, 0.5 / 3, false)[0], 0.0f);
  EXPECT_FLOAT_EQ(sample_bilinear(image, 1.0, 0.5 / 3, false)[0], 30.0f);
  // Periodic in u when wrapping, for any u; clamped otherwise.
  for (double u : {0.1, 0.37, 0.9}) {
    for (double shift : {-3.0, 1.0, 1e6}) {
      EXPECT_NEAR(sample_bilinear(image, u + shift, 0.5, true)[0], sample_bilinear(image, u, 0.5, true)[0], 1e-3)
          << u << " + " << shift;
    }
  }
  EXPECT_EQ(sample_bilinear(image, -5.0, 0.5 / 3, false)[0], 0.0f);
  EXPECT_EQ(sample_bilinear(image, 7.0, 0.5 / 3, false)[0], 30.0f);
  // v = 0 is the top row, v = 1 the bottom, both clamped even when u wraps.
  for (bool wrap : {false, true}) {
    EXPECT_EQ(sample_bilinear(image, 1.5 / 4, 0.0, wrap)[0], 10.0f);
    EXPECT_EQ(sample_bilinear(image, 1.5 / 4, -2.0, wrap)[0], 10.0f);
    EXPECT_EQ(sample_bilinear(image, 1.5 / 4, 1.0, wrap)[0], 210.0f);
    EXPECT_EQ(sample_bilinear(image, 1.5 / 4, 9.0, wrap)[0], 210.0f);
  }
}

TEST(Bilinear, RejectsNonFiniteCoordinatesAndBadImages) {
  const Image image = grid();
  EXPECT_EQ(error_of([&] { sample_bilinear(image, NAN, 0.5, true); }).status(), ARCUS_ERROR_INVALID_ARGUMENT);
  EXPECT_EQ(error_of([&] { sample_bilinear(image, 0.5, INFINITY, false); }).status(), ARCUS_ERROR_INVALID_ARGUMENT);
  Image grey = make(2, 2, {"Y"}, [](int, int, int) { return 1.0f; });
  EXPECT_EQ(error_of([&] { sample_bilinear(grey, 0.5, 0.5, false); }).status(), ARCUS_ERROR_INVALID_ARGUMENT);
  EXPECT_EQ(error_of([&] { sample_bilinear(Image(), 0.5, 0.5, false); }).status(), ARCUS_ERROR_INVALID_ARGUMENT);
}

// ---- hostile input ---------------------------------------------------------------------

// A PFM of one colour per pixel, rows bottom-up as the format stores them.
void write_pfm(const std::string& path, int w, int h, const std::function<float(int, int, int)>& value) {
  std::ofstream out(path, std::ios::binary);
  out << "PF\n" << w << " " << h << "\n-1.0\n";
  for (int y = h - 1; y >= 0; --y)
    for (int x = 0; x < w; ++x)
      for (int c = 0; c < 3; ++c) {
        const float v = value(x, y, c);
        out.write(reinterpret_cast<const char*>(&v), sizeof v);
      }
}

// The CRC-32 of PNG chunks (ISO 3309), for hand-made PNG files.
uint32_t crc32(const std::string& bytes) {
  uint32_t c = 0xffffffffu;
  for (unsigned char b : bytes) {
    c ^= b;
    for (int k = 0; k < 8; ++k) c = (c >> 1) ^ (0xedb88320u & (0u - (c & 1u)));
  }
  return ~c;
}

std::string be32(uint32_t v) {
  return {char(v >> 24), char(v >> 16), char(v >> 8), char(v)};
}

std::string chunk(const std::string& type, const std::string& data) {
  return be32(uint32_t(data.size())) + type + data + be32(crc32(type + data));
}

// A PNG whose header claims width x height RGB pixels, holding a few bytes of data.
std::string lying_png(uint32_t width, uint32_t height) {
  const std::string ihdr = be32(width) + be32(height) + std::string("\x08\x02\x00\x00\x00", 5);
  const std::string idat("\x78\x9c\x63\x00\x00\x00\x01\x00\x01", 9);  // zlib of one zero byte
  return std::string("\x89PNG\r\n\x1a\n", 8) + chunk("IHDR", ihdr) + chunk("IDAT", idat) + chunk("IEND", "");
}

long peak_rss_mib() {
  struct rusage u {};
  getrusage(RUSAGE_SELF, &u);
  return u.ru_maxrss / 1024;
}

TEST(ImageIoHostile, SpecialFilesAreRefusedWithoutBlocking) {
  // A FIFO blocked OpenImageIO's open for ever; /dev/zero kept its format probe spinning.
  TempDir dir;
  const std::string fifo = dir.path() + "/sky.exr";
  ASSERT_EQ(::mkfifo(fifo.c_str(), 0600), 0);
  const auto start = std::chrono::steady_clock::now();
  arcus::Error e = error_of([&] { read_image(fifo); });
  EXPECT_EQ(e.status(), ARCUS_ERROR_IO);
  EXPECT_TRUE(contains(e.what(), fifo + ": is a FIFO, not a regular file")) << e.what();
  const std::string zero = dir.path() + "/zero.png";
  ASSERT_EQ(::symlink("/dev/zero", zero.c_str()), 0);
  e = error_of([&] { read_image(zero); });
  EXPECT_TRUE(contains(e.what(), "character device")) << e.what();
  e = error_of([&] { read_image(dir.path()); });
  EXPECT_TRUE(contains(e.what(), "is a directory")) << e.what();
  EXPECT_LT(std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count(), 5.0);
}

TEST(ImageIoHostile, AHeaderClaimingAHugeImageCostsOnlyWhatTheFileHolds) {
  // 149 bytes claiming 12000 x 12000 took 1.8 GB: the pixels were zero-filled before
  // decoding began.  Now rows are allocated as they are decoded.
  TempDir dir;
  const std::string path = dir.path() + "/liar.png";
  std::ofstream(path, std::ios::binary) << lying_png(12000, 12000);
  // Past the memory check whatever this machine has free: the rows are what is tested.
  ScopedEnv room("ARCUS_MEMORY_LIMIT", "1T");
  const long before = peak_rss_mib();
  const arcus::Error e = error_of([&] { read_image(path); });
  EXPECT_EQ(e.status(), ARCUS_ERROR_IO) << e.what();
  EXPECT_TRUE(contains(e.what(), path)) << e.what();
  // The whole image would be 1.6 GiB of float pixels (zero-filled, it took 1.65 GiB); a
  // few rows are a few MiB.  Under AddressSanitizer the reserved (untouched) buffer still
  // costs its shadow, an eighth of it: 200 MiB.  So the bound is 400 MiB.
  EXPECT_LT(peak_rss_mib() - before, 400) << "peak RSS before " << before << " MiB, after " << peak_rss_mib();
  // Beyond the pixel bound (2^28) it is refused from the header alone.
  std::ofstream(path, std::ios::binary | std::ios::trunc) << lying_png(30000, 30000);
  const arcus::Error big = error_of([&] { read_image(path); });
  EXPECT_TRUE(contains(big.what(), "30000 x 30000 pixels, more than the 268435456 allowed (ARCUS_MAX_IMAGE_PIXELS"))
      << big.what();
  ScopedEnv raised("ARCUS_MAX_IMAGE_PIXELS", "1G");
  EXPECT_FALSE(contains(error_of([&] { read_image(path); }).what(), "allowed")) << "the bound is raised";
}

TEST(ImageIoHostile, NanAndInfiniteTexelsAreRefusedNamingThePixel) {
  TempDir dir;
  const std::string path = dir.path() + "/texture.pfm";
  for (const float bad : {NAN, INFINITY, -INFINITY}) {
    write_pfm(path, 4, 3, [&](int x, int y, int c) { return x == 2 && y == 1 && c == 1 ? bad : 0.5f; });
    const arcus::Error e = error_of([&] { read_image(path); });
    EXPECT_EQ(e.status(), ARCUS_ERROR_INVALID_ARGUMENT);
    EXPECT_TRUE(contains(e.what(), path + ": pixel (2, 1) G = ")) << e.what();
    EXPECT_TRUE(contains(e.what(), "is not finite")) << e.what();
  }
  // The largest finite float is a colour like any other.
  write_pfm(path, 2, 2, [](int, int, int) { return 3.0e38f; });
  EXPECT_EQ(read_image(path).pixels[0], 3.0e38f);
}

TEST(ImageIoHostile, TheFuzzersRegressionInputsReadOrFailCleanly) {
  // tests/fuzz/image/regressions (the first byte picks the extension: fuzz_image.cpp).
  const char* const extensions[] = {".png", ".exr", ".hdr", ".pfm", ".tif", ".jpg", ".bmp", ".tga", ".ppm"};
  TempDir dir;
  int n = 0;
  for (const auto& entry : std::filesystem::directory_iterator(ARCUS_SOURCE_DIR "/tests/fuzz/image/regressions")) {
    std::ifstream in(entry.path(), std::ios::binary);
    const std::string data((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    ASSERT_FALSE(data.empty()) << entry.path();
    const std::string path = dir.path() + "/input" + extensions[static_cast<unsigned char>(data[0]) % 9];
    std::ofstream(path, std::ios::binary | std::ios::trunc) << data.substr(1);
    try {
      const Image im = read_image(path);
      for (float v : im.pixels) EXPECT_TRUE(std::isfinite(v)) << entry.path();
    } catch (const arcus::Error& e) {
      EXPECT_TRUE(contains(e.what(), path)) << e.what();
    }
    ++n;
  }
  EXPECT_GE(n, 4);
}

}  // namespace
