// libFuzzer target for the mesh reader (src/geometry: the scan, then OpenMesh): the
// first byte picks the file's extension, the rest is the file.  Any input must give a
// mesh (finite positions, every triangle's vertices existing) or throw arcus::Error
// naming the file.  Any other exception, a sanitizer report, a hang or an out-of-memory
// is a finding.  Built and run by run_fuzz.sh.
#include <stdlib.h>
#include <unistd.h>

#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <fstream>
#include <string>

#include "core/error.h"
#include "geometry/mesh.h"

namespace {

const char* const kExtensions[] = {".obj", ".ply", ".off", ".stl"};

void check(bool ok, const char* what) {
  if (!ok) {
    std::fprintf(stderr, "fuzz_mesh: invariant broken: %s\n", what);
    std::abort();
  }
}

const std::string& directory() {
  static const std::string dir = [] {
    std::string pattern = "/tmp/arcus_fuzz_mesh_XXXXXX";
    return std::string(mkdtemp(&pattern[0]) ? pattern.c_str() : "/tmp");
  }();
  return dir;
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  if (size < 1) return 0;
  const std::string path = directory() + "/input" + kExtensions[data[0] % 4];
  {
    std::ofstream out(path, std::ios::binary | std::ios::trunc);
    out.write(reinterpret_cast<const char*>(data + 1), static_cast<std::streamsize>(size - 1));
  }
  try {
    const arcus::geometry::Mesh m = arcus::geometry::load_mesh(path);
    check(m.triangle_count() > 0, "a mesh has faces");
    for (double p : m.positions) check(std::isfinite(p), "finite positions");
    for (uint32_t v : m.triangles) check(v < m.vertex_count(), "triangles name existing vertices");
    check(m.uvs.empty() || m.uvs.size() == 2 * m.vertex_count(), "uvs: none or one pair per vertex");
  } catch (const arcus::Error& e) {
    check(std::strncmp(e.what(), path.c_str(), path.size()) == 0, "message starts with the file");
  }
  return 0;
}
