// libFuzzer target for the scene reader: any input must parse or throw arcus::Error with
// a message "fuzz.json: $...: ..." (or "fuzz.json: not valid JSON (after $...)") in valid UTF-8.  Any other exception (std::terminate),
// a sanitizer report, a hang or a broken invariant of the parsed scene is a finding.
// Built and run by run_fuzz.sh.
#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <cstring>
#include <string>

#include "core/error.h"
#include "curved/scene_desc.h"

namespace {

// RFC 3629 UTF-8 (no overlongs, surrogates or code points above U+10FFFF).
bool valid_utf8(const char* s) {
  const auto* p = reinterpret_cast<const unsigned char*>(s);
  while (*p) {
    unsigned c = *p, n = 0, lo = 0x80, hi = 0xBF;
    if (c < 0x80) n = 0;
    else if (c >= 0xC2 && c <= 0xDF) n = 1;
    else if (c >= 0xE0 && c <= 0xEF) n = 2, lo = c == 0xE0 ? 0xA0 : 0x80, hi = c == 0xED ? 0x9F : 0xBF;
    else if (c >= 0xF0 && c <= 0xF4) n = 3, lo = c == 0xF0 ? 0x90 : 0x80, hi = c == 0xF4 ? 0x8F : 0xBF;
    else return false;
    ++p;
    for (unsigned k = 0; k < n; ++k, ++p) {
      if (k == 0 ? (*p < lo || *p > hi) : ((*p & 0xC0) != 0x80)) return false;
    }
  }
  return true;
}

bool all_finite(const std::vector<double>& v) {
  for (double x : v)
    if (!std::isfinite(x)) return false;
  return true;
}

void check(bool ok, const char* what) {
  if (!ok) {
    fprintf(stderr, "fuzz_scene: invariant broken: %s\n", what);
    abort();
  }
}

void check_scene(const arcus::curved::SceneDesc& s, const arcus::curved::SceneLimits& limits) {
  const size_t n = s.ray_count();
  check(n >= 1 && n <= limits.max_rays, "ray count within 1..max_rays");
  check(s.origins.size() == 3 * n && s.directions.size() == 3 * n, "origins and directions are count x 3");
  check(s.wavelengths.empty() || s.wavelengths.size() == n, "wavelengths: none or one per ray");
  check(all_finite(s.origins) && all_finite(s.directions) && all_finite(s.wavelengths), "finite rays");
  for (size_t i = 0; i < n; ++i) {
    const double* d = &s.directions[3 * i];
    check(d[0] != 0 || d[1] != 0 || d[2] != 0, "no zero direction");
  }
  check(!s.name.empty() && s.name != "." && s.name != ".." && s.name.find('/') == std::string::npos, "plain name");
  check(s.params.progress == nullptr, "no progress callback");
  check(s.medium.kind != ARCUS_FIELD_GRID || (!s.medium.grid.file.empty() && s.medium.grid.file[0] == '/'),
        "grid file absolute");
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  const std::string text(reinterpret_cast<const char*>(data), size);
  // Small enough that a 60-byte fan of 2^26 rays cannot exhaust the fuzzer's memory.
  arcus::curved::SceneLimits limits;
  limits.max_rays = 1 << 12;
  try {
    const arcus::curved::SceneDesc s = arcus::curved::parse_scene_text(text, "fuzz.json", "/fuzz", limits);
    check_scene(s, limits);
    // The document as printed reads back as the same scene.
    const arcus::curved::SceneDesc again = arcus::curved::parse_scene_text(s.document, "fuzz.json", "/fuzz", limits);
    check(again.document == s.document, "document round trip");
    check(again.origins == s.origins && again.directions == s.directions && again.wavelengths == s.wavelengths,
          "rays round trip");
  } catch (const arcus::Error& e) {
    check(e.status() == ARCUS_ERROR_INVALID_ARGUMENT, "status INVALID_ARGUMENT");
    // "fuzz.json: $.path: ..." or, for text that is no JSON, "fuzz.json: not valid JSON (after $...)".
    check(std::strncmp(e.what(), "fuzz.json: $", 12) == 0 || std::strncmp(e.what(), "fuzz.json: not valid JSON (after $", 34) == 0,
          "message starts with the file and a path");
    check(valid_utf8(e.what()), "message is valid UTF-8");
    check(std::strlen(e.what()) < 65536, "message is bounded");
  }
  return 0;
}
