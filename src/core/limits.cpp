#include "core/limits.h"

#include <unistd.h>

#include <cctype>
#include <cstdio>
#include <cstdlib>
#include <fstream>

#include "core/error.h"
#include "core/format.h"

namespace arcus::limits {

uint64_t from_env(const char* name, uint64_t fallback) {
  const char* text = std::getenv(name);
  if (!text || !*text) return fallback;
  char* end = nullptr;
  const unsigned long long value = std::strtoull(text, &end, 10);
  uint64_t scale = 1;
  if (*end) {
    switch (std::toupper(static_cast<unsigned char>(*end))) {
      case 'K': scale = uint64_t(1) << 10; break;
      case 'M': scale = uint64_t(1) << 20; break;
      case 'G': scale = uint64_t(1) << 30; break;
      case 'T': scale = uint64_t(1) << 40; break;
      default: scale = 0;
    }
    ++end;
  }
  if (!std::isdigit(static_cast<unsigned char>(text[0])) || *end || scale == 0 || value == 0 ||
      value > UINT64_MAX / scale)
    fail(ARCUS_ERROR_INVALID_ARGUMENT, std::string("the environment variable ") + name + " = '" + text +
                                           "' is not a positive size (an integer, optionally with K, M, G or T)");
  return value * scale;
}

uint64_t scene_file_bytes() { return from_env("ARCUS_MAX_SCENE_BYTES", uint64_t(64) << 20); }

uint64_t mesh_file_bytes() { return from_env("ARCUS_MAX_MESH_BYTES", uint64_t(1) << 30); }

uint64_t image_pixels() { return from_env("ARCUS_MAX_IMAGE_PIXELS", uint64_t(1) << 28); }

namespace {
// MemAvailable of /proc/meminfo (what can be allocated without swapping), else the
// physical pages free now.
uint64_t available_memory() {
  std::ifstream meminfo("/proc/meminfo");
  std::string key;
  uint64_t kib = 0;
  std::string unit;
  while (meminfo >> key >> kib >> unit)
    if (key == "MemAvailable:") return kib * 1024;
  const long pages = ::sysconf(_SC_AVPHYS_PAGES), page = ::sysconf(_SC_PAGESIZE);
  return pages > 0 && page > 0 ? uint64_t(pages) * uint64_t(page) : UINT64_MAX;
}
}  // namespace

uint64_t host_memory() { return from_env("ARCUS_MEMORY_LIMIT", available_memory()); }

std::string bytes_text(double bytes) {
  static const char* units[] = {"bytes", "KiB", "MiB", "GiB", "TiB", "PiB", "EiB"};
  int u = 0;
  while (bytes >= 1024 && u < 6) bytes /= 1024, ++u;
  char buf[48];
  std::snprintf(buf, sizeof buf, u ? "%.4g %s" : "%.0f %s", bytes, units[u]);
  return buf;
}

void require_host_memory(double bytes, const std::string& what) {
  const uint64_t limit = host_memory();
  if (bytes > static_cast<double>(limit))
    fail(ARCUS_ERROR_OUT_OF_MEMORY, what + " needs " + bytes_text(bytes) + " of host memory; " + bytes_text(double(limit)) +
                                        (std::getenv("ARCUS_MEMORY_LIMIT") ? " are allowed (ARCUS_MEMORY_LIMIT)"
                                                                           : " are available (ARCUS_MEMORY_LIMIT overrides this)"));
}

}  // namespace arcus::limits
