// libFuzzer target for the mesh reader (src/geometry: the scan, then OpenMesh): the
// first byte picks the file's extension, the rest is the file.  Any input must give a
// mesh (finite positions, every triangle's vertices existing) or throw arcus::Error
// naming the file.  Any other exception, a sanitizer report, a hang or an out-of-memory
// is a finding.  Built and run by run_fuzz.sh.
#include <cmath>
#include <cstdint>
#include <cstring>
#include <string>

#include "core/error.h"
#include "fuzz_file.h"
#include "geometry/mesh.h"

namespace {

using fuzz_file::check;
const char* const kExtensions[] = {".obj", ".ply", ".off", ".stl"};

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  if (size < 1) return 0;
  const std::string path = fuzz_file::write_input(data, size, kExtensions, sizeof kExtensions / sizeof *kExtensions);
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
