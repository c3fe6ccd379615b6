// Triangle meshes as the engines use them: positions and triangles in double, optional
// per-vertex texture coordinates, read from OBJ, PLY, OFF or STL through OpenMesh or
// made from a caller's arrays (arcus_mesh_create); both pass the same checks.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

namespace arcus::geometry {

// The most vertices or faces a mesh may have, from a file or from arrays: beyond it
// indices overflow OpenMesh's ints.
constexpr uint64_t kMaxCount = (uint64_t(1) << 31) - 1;

struct Mesh {
  std::vector<double> positions;    // 3 per vertex
  std::vector<uint32_t> triangles;  // 3 vertex indices per triangle
  std::vector<double> uvs;          // 2 per vertex, or empty
  std::string source;               // the file it was read from ("" when built in code)

  size_t vertex_count() const { return positions.size() / 3; }
  size_t triangle_count() const { return triangles.size() / 3; }
};

// Reads `path` (by extension, case-insensitive: .obj .ply .off .stl; PLY and STL text or
// binary, OFF text only); polygons are triangulated as fans.  The file is scanned before
// OpenMesh parses it (geometry/mesh_scan.h): what OpenMesh would misread is refused with
// the line.  A missing, unreadable or not-regular file is ARCUS_ERROR_IO; an
// unknown extension, a file OpenMesh cannot parse, a mesh without faces or a
// non-finite vertex is ARCUS_ERROR_INVALID_ARGUMENT; every message names the file.
// Zero-area triangles are kept (the traversal never hits them), except faces that
// repeat a vertex index, and STL triangles two of whose corners coincide, which OpenMesh
// drops.  OpenMesh's readers (all four
// formats, PLY's double properties included) hand coordinates over as float, so
// positions read from files are float values; everything after reading is double.
Mesh load_mesh(const std::string& path);

// A mesh of `vertex_count` positions (`vertices`: x y z each) and `triangle_count`
// triangles (`indices`: 3 each), copied, with no source.  Counts above kMaxCount or
// beyond the host's memory are refused before anything is allocated; then check_mesh.
// Messages name the C API's arguments ("indices[7] = 12 is not below vertex_count 10").
Mesh mesh_from_arrays(size_t vertex_count, const double* vertices, size_t triangle_count, const uint32_t* indices);

// What every mesh must be, read from a file or made from arrays, checked once for both:
// at least one triangle, every coordinate finite, every index below the vertex count.
// ARCUS_ERROR_INVALID_ARGUMENT otherwise, naming the file ("cube.off: vertex 3 is not
// finite") or, for a mesh without a source, the arrays ("vertices[10] = nan is not
// finite").  How far from the origin a mesh may lie is checked where it is placed, in
// metres (bvh::kMaxCoordinate, when its BVH is built), for both alike.
void check_mesh(const Mesh& mesh);

// `mesh` with every position p replaced by M·(p, 1), M a 3×4 row-major affine matrix.
Mesh transformed(const Mesh& mesh, const double matrix[12]);

}  // namespace arcus::geometry
