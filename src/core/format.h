// Numbers in messages: the shortest text that reads back as the same double ("1e+308",
// "0.1", "288.15"), never std::to_string's fixed notation (310 digits for 1e308, "0.000000"
// for 1e-9).
#pragma once

#include <charconv>
#include <string>

namespace arcus {

inline std::string number(double v) {
  char buf[32];
  const auto r = std::to_chars(buf, buf + sizeof buf, v);
  return std::string(buf, r.ptr);
}

}  // namespace arcus
