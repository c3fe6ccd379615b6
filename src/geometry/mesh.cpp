#include "geometry/mesh.h"

// OpenMesh's vectors leave their elements uninitialised on purpose (a default-made
// property value is always overwritten); GCC 12 flags every instantiation of that.
#pragma GCC diagnostic ignored "-Wmaybe-uninitialized"

#include <OpenMesh/Core/IO/IOManager.hh>
#include <OpenMesh/Core/IO/MeshIO.hh>
#include <OpenMesh/Core/IO/importer/ImporterT.hh>
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
#include "core/files.h"
#include "core/format.h"
#include "core/limits.h"
#include "geometry/mesh_scan.h"

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

// OpenMesh's importer, counting what the reader hands it: every vertex, every face, and
// the faces naming a vertex that does not exist (which the importer drops with a line
// on stderr).  Faces repeating a vertex are dropped too, harmlessly: they have no area.
struct CountingImporter : OpenMesh::IO::ImporterT<OmMesh> {
  using ImporterT::ImporterT;
  size_t vertices = 0, faces = 0, bad_faces = 0;
  OpenMesh::VertexHandle add_vertex(const OpenMesh::Vec3f& p) override { return counted(ImporterT::add_vertex(p)); }
  OpenMesh::VertexHandle add_vertex(const OpenMesh::Vec3d& p) override { return counted(ImporterT::add_vertex(p)); }
  OpenMesh::VertexHandle add_vertex() override { return counted(ImporterT::add_vertex()); }
  OpenMesh::FaceHandle add_face(const VHandles& corners) override {
    ++faces;
    for (const auto& v : corners)
      if (!v.is_valid() || static_cast<size_t>(v.idx()) >= vertices) {
        ++bad_faces;
        return OpenMesh::FaceHandle();
      }
    return ImporterT::add_face(corners);
  }

 private:
  OpenMesh::VertexHandle counted(OpenMesh::VertexHandle v) {
    ++vertices;
    return v;
  }
};

}  // namespace

Mesh load_mesh(const std::string& path) {
  const std::string ext = lower_extension(path);
  if (ext != ".obj" && ext != ".ply" && ext != ".off" && ext != ".stl")
    fail(ARCUS_ERROR_INVALID_ARGUMENT, path + ": unknown mesh format '" + ext + "' (expected .obj, .ply, .off or .stl)");
  // Read once, scanned, then parsed from memory: nothing OpenMesh opens itself (an OBJ's
  // material library, a path swapped for a FIFO meanwhile) can block or differ.
  const std::string bytes = files::read_all(path, limits::mesh_file_bytes(), "ARCUS_MAX_MESH_BYTES");
  const Declared declared = scan_mesh(path, ext, bytes);
  // OpenMesh's mesh and ours: a few hundred bytes a vertex and face at most.
  limits::require_host_memory(400.0 * (double(declared.vertices) + double(declared.faces)), path + ": the mesh");

  OmMesh om;
  om.request_vertex_texcoords2D();
  CountingImporter importer(om);
  OpenMesh::IO::Options options = OpenMesh::IO::Options::VertexTexCoord;
  if (declared.binary) options += OpenMesh::IO::Options::Binary;  // from a file OpenMesh sees it by the size
  std::istringstream in(bytes, std::ios::binary);
  if (!OpenMesh::IO::IOManager().read(in, ext.substr(1), importer, options))
    fail(ARCUS_ERROR_INVALID_ARGUMENT, path + ": not a readable " + ext.substr(1) + " mesh");
  if (importer.bad_faces)
    fail(ARCUS_ERROR_INVALID_ARGUMENT, path + ": " + std::to_string(importer.bad_faces) +
                                           " faces name vertices that do not exist");
  // STL vertices are merged as they are read, so only its triangles are counted, and a
  // triangle whose corners merged (no area) is never handed over: at most the file's.
  const bool stl = ext == ".stl";
  if ((!stl && (importer.vertices != declared.vertices || importer.faces != declared.faces)) ||
      (stl && importer.faces > declared.faces))
    fail(ARCUS_ERROR_INVALID_ARGUMENT, path + ": OpenMesh read " + std::to_string(importer.vertices) + " vertices and " +
                                           std::to_string(importer.faces) + " faces of the " +
                                           std::to_string(declared.vertices) + " and " +
                                           std::to_string(declared.faces) + " in the file");

  Mesh mesh;
  mesh.source = path;
  mesh.positions.reserve(3 * om.n_vertices());
  for (const auto v : om.vertices()) {
    const OpenMesh::Vec3d& p = om.point(v);
    mesh.positions.insert(mesh.positions.end(), {p[0], p[1], p[2]});
  }
  // STL has no texture coordinates, but OpenMesh leaves the option as asked.
  if (options.vertex_has_texcoord() && ext != ".stl") {
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
  check_mesh(mesh);
  return mesh;
}

Mesh mesh_from_arrays(size_t vertex_count, const double* vertices, size_t triangle_count, const uint32_t* indices) {
  require(vertex_count <= kMaxCount,
          "vertex_count " + std::to_string(vertex_count) + " is more than 2^31 - 1 vertices");
  require(triangle_count <= kMaxCount,
          "triangle_count " + std::to_string(triangle_count) + " is more than 2^31 - 1 triangles");
  if (vertex_count) require_pointer(vertices, "vertices");  // an empty array may be NULL
  if (triangle_count) require_pointer(indices, "indices");
  // The copy, and the particle or scene made of it: as a file's mesh, a few hundred
  // bytes a vertex and triangle at most.
  limits::require_host_memory(400.0 * (double(vertex_count) + double(triangle_count)),
                              "a mesh of " + std::to_string(vertex_count) + " vertices and " +
                                  std::to_string(triangle_count) + " triangles");
  Mesh mesh;
  mesh.positions.assign(vertices, vertices + 3 * vertex_count);
  mesh.triangles.assign(indices, indices + 3 * triangle_count);
  check_mesh(mesh);
  return mesh;
}

void check_mesh(const Mesh& mesh) {
  // A file's mesh is named by its file and counts; a caller's by the arrays it passed.
  auto refuse = [&](const std::string& in_file, const std::string& in_arrays) {
    fail(ARCUS_ERROR_INVALID_ARGUMENT, mesh.source.empty() ? in_arrays : mesh.source + ": " + in_file);
  };
  if (mesh.triangles.empty()) refuse("the mesh has no faces", "triangle_count is 0: a mesh needs a triangle");
  for (size_t i = 0; i < mesh.positions.size(); ++i)
    if (!std::isfinite(mesh.positions[i]))
      refuse("vertex " + std::to_string(i / 3) + " is not finite",
             "vertices[" + std::to_string(i) + "] = " + number(mesh.positions[i]) + " is not finite");
  const size_t count = mesh.vertex_count();
  for (size_t i = 0; i < mesh.triangles.size(); ++i)
    if (mesh.triangles[i] >= count)
      refuse("triangle " + std::to_string(i / 3) + " names vertex " + std::to_string(mesh.triangles[i]) + " of " +
                 std::to_string(count),
             "indices[" + std::to_string(i) + "] = " + std::to_string(mesh.triangles[i]) +
                 " is not below vertex_count " + std::to_string(count));
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
