#include "core/kernel_source.h"

#include "core/error.h"

namespace arcus {

std::string kernel_text(const KernelSource& source) {
  std::string text;
  for (const char* file : source.files) {
    const std::string* body = embedded_kernel_file(file);
    if (!body) fail(ARCUS_ERROR_KERNEL_BUILD, std::string("kernel file ") + file + " is not embedded in the library");
    text += "\n#line 1 \"" + std::string(file) + "\"\n" + *body;
  }
  if (!source.text.empty()) text += "\n#line 1 \"" + std::string(source.name) + "\"\n" + source.text;
  return text;
}

uint64_t fnv1a64(const void* data, size_t size, uint64_t seed) {
  const unsigned char* p = static_cast<const unsigned char*>(data);
  uint64_t h = seed;
  for (size_t i = 0; i < size; ++i) {
    h ^= p[i];
    h *= 0x100000001b3ull;
  }
  return h;
}

}  // namespace arcus
