#include "geometry/mesh.h"

// OpenMesh's vectors leave their elements uninitialised on purpose (a default-made
// property value is always overwritten); GCC 12 flags every instantiation of that.
#pragma GCC diagnostic ignored "-Wmaybe-uninitialized"

#include <OpenMesh/Core/IO/MeshIO.hh>
#include <OpenMesh/Core/Mesh/PolyMesh_ArrayKernelT.hh>

#include <algorithm>
#include <cctype>
#include <cmath>
#include <filesystem>
#include <cstring>
#include <fstream>
#include <iterator>
#include <sstream>

#include "core/error.h"

namespace arcus::geometry {
namespace {

// Double positions and texture coordinates: OpenMesh's defaults are float, which would
// round every scene coordinate before the double kernels ever see it.
struct DoubleTraits : OpenMesh::DefaultTraits {
  typedef OpenMesh::Vec3d Point;
  typedef OpenMesh::Vec3d Normal;
  typedef OpenMesh::Vec2d TexCoord2D;
};
using OmMesh = OpenMesh::PolyMesh_ArrayKernelT<DoubleTraits>;

std::string lower_extension(const std::string& path) {
  std::string ext = std::filesystem::path(path).extension().string();
  std::transform(ext.begin(), ext.end(), ext.begin(), [](unsigned char c) { return std::tolower(c); });
  return ext;
}

// The checks OpenMesh does not make (it reports all of them as one `false`).
void check_readable(const std::string& path) {
  namespace fs = std::filesystem;
  std::error_code ec;
  const fs::file_status st = fs::status(path, ec);
  if (ec || !fs::exists(st)) fail(ARCUS_ERROR_IO, path + ": no such file");
  if (!fs::is_regular_file(st)) fail(ARCUS_ERROR_IO, path + ": not a regular file");
  if (!std::ifstream(path, std::ios::binary)) fail(ARCUS_ERROR_IO, path + ": cannot be opened for reading");
}

// OpenMesh's STL reader merges equal vertices through an ordered map, where a NaN is
// "equal" to whatever it is compared with: a NaN vertex silently becomes another
// vertex.  So STL files are scanned for non-finite coordinates before OpenMesh reads them.
void check_stl_finite(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  const std::string bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  uint32_t count = 0;
  if (bytes.size() >= 84) std::memcpy(&count, bytes.data() + 80, 4);
  const bool binary = bytes.size() >= 84 && bytes.size() == 84 + 50 * static_cast<uint64_t>(count);
  auto bad = [&](size_t triangle) {
    fail(ARCUS_ERROR_INVALID_ARGUMENT, path + ": triangle " + std::to_string(triangle) + " has a non-finite vertex");
  };
  if (binary) {
    for (uint32_t t = 0; t < count; ++t)
      for (int k = 0; k < 9; ++k) {
        float x;
        std::memcpy(&x, bytes.data() + 84 + 50 * static_cast<size_t>(t) + 12 + 4 * k, 4);
        if (!std::isfinite(x)) bad(t);
      }
    return;
  }
  std::istringstream text(bytes);
  size_t vertices = 0;
  for (std::string word; text >> word;) {
    if (word != "vertex") continue;
    for (int k = 0; k < 3; ++k) {
      std::string number;
      text >> number;
      if (!std::isfinite(std::strtod(number.c_str(), nullptr))) bad(vertices / 3);
    }
    ++vertices;
  }
}

}  // namespace

Mesh load_mesh(const std::string& path) {
  const std::string ext = lower_extension(path);
  if (ext != ".obj" && ext != ".ply" && ext != ".off" && ext != ".stl")
    fail(ARCUS_ERROR_INVALID_ARGUMENT, path + ": unknown mesh format '" + ext + "' (expected .obj, .ply, .off or .stl)");
  check_readable(path);
  if (ext == ".stl") check_stl_finite(path);

  OmMesh om;
  om.request_vertex_texcoords2D();
  OpenMesh::IO::Options options = OpenMesh::IO::Options::VertexTexCoord;
  if (!OpenMesh::IO::read_mesh(om, path, options))
    fail(ARCUS_ERROR_INVALID_ARGUMENT, path + ": not a readable " + ext.substr(1) + " mesh");

  Mesh mesh;
  mesh.source = path;
  mesh.positions.reserve(3 * om.n_vertices());
  for (const auto v : om.vertices()) {
    const OpenMesh::Vec3d& p = om.point(v);
    for (int k = 0; k < 3; ++k) {
      if (!std::isfinite(p[k]))
        fail(ARCUS_ERROR_INVALID_ARGUMENT, path + ": vertex " + std::to_string(v.idx()) + " is not finite");
      mesh.positions.push_back(p[k]);
    }
  }
  if (options.vertex_has_texcoord()) {
    mesh.uvs.reserve(2 * om.n_vertices());
    for (const auto v : om.vertices()) {
      const OpenMesh::Vec2d& t = om.texcoord2D(v);
      mesh.uvs.push_back(t[0]);
      mesh.uvs.push_back(t[1]);
    }
  }
  for (const auto f : om.faces()) {
    std::vector<uint32_t> ring;
    for (const auto v : om.fv_range(f)) ring.push_back(static_cast<uint32_t>(v.idx()));
    for (size_t i = 1; i + 1 < ring.size(); ++i) mesh.triangles.insert(mesh.triangles.end(), {ring[0], ring[i], ring[i + 1]});
  }
  if (mesh.triangles.empty()) fail(ARCUS_ERROR_INVALID_ARGUMENT, path + ": the mesh has no faces");
  return mesh;
}

Mesh transformed(const Mesh& mesh, const double m[12]) {
  for (int i = 0; i < 12; ++i) require(std::isfinite(m[i]), "transformed: the matrix is not finite");
  Mesh out = mesh;
  for (size_t v = 0; v < mesh.vertex_count(); ++v) {
    const double* p = &mesh.positions[3 * v];
    for (int r = 0; r < 3; ++r)
      out.positions[3 * v + r] = m[4 * r] * p[0] + m[4 * r + 1] * p[1] + m[4 * r + 2] * p[2] + m[4 * r + 3];
  }
  return out;
}

}  // namespace arcus::geometry
