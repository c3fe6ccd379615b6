// Kernel sources: one tree under kernels/, embedded into the library at build time
// (cmake/embed_kernels.cmake).  A program is built from an ordered list of those files
// (headers first), which each engine names once.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

namespace arcus {

struct KernelSource {
  const char* name;                // "curved/advance": part of the program-cache key
  std::vector<const char*> files;  // paths under kernels/, in include order
  std::string text;                // appended after the files (tests build small kernels so)
};

// The text of an embedded file, or null (generated at build time).
const std::string* embedded_kernel_file(const std::string& path);

// The files of `source` concatenated, each behind a #line directive so that compiler
// messages name the file and line, then its own text.  Throws if a file is not embedded.
std::string kernel_text(const KernelSource& source);

// FNV-1a, 64 bits: keys for the program cache (not cryptographic).
uint64_t fnv1a64(const void* data, size_t size, uint64_t seed = 0xcbf29ce484222325ull);

}  // namespace arcus
