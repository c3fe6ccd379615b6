#include "core/layout.h"

#include <cstdlib>
#include <string>

#include "core/error.h"

namespace arcus {
namespace {

const uint32_t kLanes[] = {1, 2, 4, 8, 16};                   // OpenCL vector widths
const uint32_t kGroups[] = {1, 2, 3, 4, 6, 8, 12, 16};

template <int N>
uint32_t from_environment(const char* variable, uint32_t fallback, const uint32_t (&allowed)[N]) {
  const char* text = std::getenv(variable);
  return text && *text ? parse_layout_value(variable, text, allowed, N) : fallback;
}

}  // namespace

uint32_t parse_layout_value(const char* variable, const char* text, const uint32_t* allowed, int allowed_count) {
  std::string list;
  for (int i = 0; i < allowed_count; ++i) list += (i ? ", " : "") + std::to_string(allowed[i]);
  const std::string what = std::string(variable) + "=\"" + text + "\"";
  uint64_t value = 0;
  bool digits = *text != '\0';
  for (const char* c = text; *c && digits; ++c) {
    digits = *c >= '0' && *c <= '9';
    value = value * 10 + static_cast<uint64_t>(*c - '0');
    if (value > 0xffffffffull) fail(ARCUS_ERROR_INVALID_ARGUMENT, what + " is out of range; use one of " + list);
  }
  if (!digits) fail(ARCUS_ERROR_INVALID_ARGUMENT, what + " is not a number; use one of " + list);
  for (int i = 0; i < allowed_count; ++i)
    if (allowed[i] == value) return static_cast<uint32_t>(value);
  fail(ARCUS_ERROR_INVALID_ARGUMENT, what + " is not supported; use one of " + list);
}

Layout choose_layout(const DeviceEntry& device, uint32_t cpu_groups) {
  Layout l;
  l.lanes = from_environment("ARCUS_LANES", device.info.lanes, kLanes);
  l.groups = from_environment("ARCUS_GROUPS", device.info.is_gpu ? 1 : cpu_groups, kGroups);
  return l;
}

}  // namespace arcus
