// Triangle meshes as the engines use them: positions and triangles in double, optional
// per-vertex texture coordinates, read from OBJ, PLY, OFF or STL through OpenMesh.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

namespace arcus::geometry {

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

// `mesh` with every position p replaced by M·(p, 1), M a 3×4 row-major affine matrix.
Mesh transformed(const Mesh& mesh, const double matrix[12]);

}  // namespace arcus::geometry
