// libFuzzer target for the image reader (src/image/image_io, through OpenImageIO): the
// first byte picks the file's extension, the rest is the file.  Any input must give an
// image (within the pixel bound, every value finite) or throw arcus::Error naming the
// file.  Any other exception, a sanitizer report, a hang or an out-of-memory is a
// finding.  Built and run by run_fuzz.sh.
#include <cmath>
#include <cstdint>
#include <cstring>
#include <string>

#include "core/error.h"
#include "fuzz_file.h"
#include "image/image_io.h"

namespace {

using fuzz_file::check;
const char* const kExtensions[] = {".png", ".exr", ".hdr", ".pfm", ".tif", ".jpg", ".bmp", ".tga", ".ppm"};

}  // namespace

extern "C" int LLVMFuzzerInitialize(int*, char***) {
  // Small images only: the bound itself is what is tested, and the fuzzer's memory is 2 GB.
  setenv("ARCUS_MAX_IMAGE_PIXELS", "1M", 1);
  return 0;
}

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  if (size < 1) return 0;
  const std::string path = fuzz_file::write_input(data, size, kExtensions, sizeof kExtensions / sizeof *kExtensions);
  try {
    const arcus::image::Image im = arcus::image::read_image(path);
    check(im.width > 0 && im.height > 0 && uint64_t(im.width) * im.height <= (uint64_t(1) << 20), "size in bounds");
    check(im.channels.size() == 3 && im.pixels.size() == size_t(im.width) * im.height * 3, "RGB pixels");
    for (float v : im.pixels) check(std::isfinite(v), "finite pixels");
  } catch (const arcus::Error& e) {
    check(std::strncmp(e.what(), path.c_str(), path.size()) == 0, "message starts with the file");
  }
  return 0;
}
