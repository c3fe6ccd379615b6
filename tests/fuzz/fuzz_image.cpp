// libFuzzer target for the image reader (src/image/image_io, through OpenImageIO): the
// first byte picks the file's extension, the rest is the file.  Any input must give an
// image (within the pixel bound, every value finite) or throw arcus::Error naming the
// file.  Any other exception, a sanitizer report, a hang or an out-of-memory is a
// finding.  Built and run by run_fuzz.sh.
#include <stdlib.h>
#include <unistd.h>

#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <fstream>
#include <string>

#include "core/error.h"
#include "image/image_io.h"

namespace {

const char* const kExtensions[] = {".png", ".exr", ".hdr", ".pfm", ".tif", ".jpg", ".bmp", ".tga", ".ppm"};

void check(bool ok, const char* what) {
  if (!ok) {
    std::fprintf(stderr, "fuzz_image: invariant broken: %s\n", what);
    std::abort();
  }
}

// A directory of this process's own for the files (removed by the OS with /tmp).
const std::string& directory() {
  static const std::string dir = [] {
    std::string pattern = "/tmp/arcus_fuzz_image_XXXXXX";
    return std::string(mkdtemp(&pattern[0]) ? pattern.c_str() : "/tmp");
  }();
  return dir;
}

}  // namespace

extern "C" int LLVMFuzzerInitialize(int*, char***) {
  // Small images only: the bound itself is what is tested, and the fuzzer's memory is 2 GB.
  setenv("ARCUS_MAX_IMAGE_PIXELS", "1M", 1);
  return 0;
}

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  if (size < 1) return 0;
  const std::string path =
      directory() + "/input" + kExtensions[data[0] % (sizeof kExtensions / sizeof *kExtensions)];
  {
    std::ofstream out(path, std::ios::binary | std::ios::trunc);
    out.write(reinterpret_cast<const char*>(data + 1), static_cast<std::streamsize>(size - 1));
  }
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
