// Bounds on what one input file or one request may make arcus allocate, each checked
// before anything is allocated, with a message naming the file or parameter, the size
// asked for and the bound.  docs/limits.md lists them with their defaults.
#pragma once

#include <cstdint>
#include <string>

namespace arcus::limits {

// A bound from the environment variable `name` (a positive integer, optionally with a
// K, M, G or T suffix of powers of 1024), else `fallback`.  A malformed value is
// ARCUS_ERROR_INVALID_ARGUMENT naming the variable.
uint64_t from_env(const char* name, uint64_t fallback);

// Scene and spec files (JSON): ARCUS_MAX_SCENE_BYTES, default 64 MiB.
uint64_t scene_file_bytes();
// Mesh files: ARCUS_MAX_MESH_BYTES, default 1 GiB.
uint64_t mesh_file_bytes();
// Input images (textures, skies): ARCUS_MAX_IMAGE_PIXELS, default 2^28 (16384²).
uint64_t image_pixels();
// What one call may allocate on the host: ARCUS_MEMORY_LIMIT, default the memory the
// system has available now (MemAvailable).
uint64_t host_memory();

// Throws ARCUS_ERROR_OUT_OF_MEMORY unless `bytes` fit host_memory(): "<what> needs
// 12.5 GiB of host memory; 8 GiB are available (ARCUS_MEMORY_LIMIT overrides this)".
void require_host_memory(double bytes, const std::string& what);

// "1.5 GiB", "640 KiB", "12 bytes": a size for a message.
std::string bytes_text(double bytes);

}  // namespace arcus::limits
