// What the fuzzers of file readers share (fuzz_image.cpp, fuzz_mesh.cpp): the input
// written to a file whose extension its first byte picks, in a directory of the
// process's own, and invariants whose breach aborts (a finding for libFuzzer).
#pragma once

#include <stdlib.h>

#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <fstream>
#include <string>

namespace fuzz_file {

inline void check(bool ok, const char* what) {
  if (!ok) {
    std::fprintf(stderr, "fuzz: invariant broken: %s\n", what);
    std::abort();
  }
}

// The path of `data` (size >= 1) written as a file: its first byte picks one of the
// `count` extensions, the rest is the file.
inline std::string write_input(const uint8_t* data, size_t size, const char* const* extensions, size_t count) {
  static const std::string dir = [] {
    std::string pattern = "/tmp/arcus_fuzz_XXXXXX";
    return std::string(mkdtemp(&pattern[0]) ? pattern.c_str() : "/tmp");
  }();
  const std::string path = dir + "/input" + extensions[data[0] % count];
  std::ofstream out(path, std::ios::binary | std::ios::trunc);
  out.write(reinterpret_cast<const char*>(data + 1), static_cast<std::streamsize>(size - 1));
  return path;
}

}  // namespace fuzz_file
