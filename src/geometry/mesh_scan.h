// What a mesh file declares, read before OpenMesh sees it.  OpenMesh's readers trust
// their input: the PLY reader loops for ever on a header without "end_header" (growing
// by 0.6 GB/s on some), the OBJ reader skips vertex lines it cannot parse (nan, inf,
// 1e+308) and so shifts every later index, and faces naming vertices that do not exist
// are dropped with a line on stderr.  So every file is scanned first: a header must be
// complete and bounded, every number a finite single-precision value (OpenMesh reads
// floats), every face index in range, and the counts a header declares must fit in the
// file's size.  The counts are then held against what OpenMesh handed over.
#pragma once

#include <cstddef>
#include <string>

namespace arcus::geometry {

struct Declared {
  size_t vertices = 0;  // vertices in the file
  size_t faces = 0;     // faces (polygons or STL triangles) in the file
  bool binary = false;  // a binary STL (OpenMesh cannot tell from a stream)
};

// Scans `bytes`, the contents of the mesh file `path` of extension `ext` (".obj",
// ".ply", ".off", ".stl").  Throws ARCUS_ERROR_INVALID_ARGUMENT "<path>: line 12: ..."
// (or "<path>: <what>" for binary files) for anything OpenMesh would misread.
Declared scan_mesh(const std::string& path, const std::string& ext, const std::string& bytes);

}  // namespace arcus::geometry
