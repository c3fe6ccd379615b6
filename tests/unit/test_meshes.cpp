// Mesh loading: the bundled meshes, each format written by OpenMesh and read back, and
// every way a file can be wrong (status and a message naming the file), including the
// inputs OpenMesh's readers misread: they are refused before OpenMesh sees them, or
// caught by counting what it handed over (geometry/mesh_scan.h).

// OpenMesh's vectors leave their elements uninitialised on purpose; GCC 12 flags it.
#pragma GCC diagnostic ignored "-Wmaybe-uninitialized"
#include <OpenMesh/Core/IO/MeshIO.hh>
#include <OpenMesh/Core/Mesh/PolyMesh_ArrayKernelT.hh>
#include <gtest/gtest.h>

#include <sys/stat.h>

#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <fstream>

#include "core/error.h"
#include "geometry/mesh.h"
#include "unit_util.h"

namespace {

using arcus::geometry::load_mesh;
using arcus::geometry::Mesh;
using arcus_unit::TempDir;

using Triangle = std::array<double, 9>;

// The triangles as coordinates, each rotated to start at its smallest vertex (so the
// winding is kept but the starting vertex does not matter), sorted.
std::vector<Triangle> triangles_of(const Mesh& m) {
  std::vector<Triangle> out;
  for (size_t t = 0; t < m.triangle_count(); ++t) {
    std::array<std::array<double, 3>, 3> v;
    for (int c = 0; c < 3; ++c)
      for (int k = 0; k < 3; ++k) v[c][k] = m.positions[3 * m.triangles[3 * t + c] + k];
    std::rotate(v.begin(), std::min_element(v.begin(), v.end()), v.end());
    Triangle tri;
    for (int c = 0; c < 3; ++c)
      for (int k = 0; k < 3; ++k) tri[3 * c + k] = v[c][k];
    out.push_back(tri);
  }
  std::sort(out.begin(), out.end());
  return out;
}

// A square pyramid: one quad and four triangles, coordinates exact in float.
OpenMesh::PolyMesh_ArrayKernelT<> pyramid() {
  OpenMesh::PolyMesh_ArrayKernelT<> m;
  using P = OpenMesh::Vec3f;
  auto a = m.add_vertex(P(0, 0, 0)), b = m.add_vertex(P(1, 0, 0)), c = m.add_vertex(P(1, 0, 1)),
       d = m.add_vertex(P(0, 0, 1)), top = m.add_vertex(P(0.5f, 1.25f, 0.5f));
  m.add_face(std::vector<decltype(a)>{a, b, c, d});
  m.add_face(std::vector<decltype(a)>{b, a, top});
  m.add_face(std::vector<decltype(a)>{c, b, top});
  m.add_face(std::vector<decltype(a)>{d, c, top});
  m.add_face(std::vector<decltype(a)>{a, d, top});
  return m;
}

// Runs load_mesh(path) expecting `status` and a message naming the file.
// Returns the message.
std::string expect_error(const std::string& path, arcus_status status) {
  try {
    load_mesh(path);
    ADD_FAILURE() << path << ": no error";
  } catch (const arcus::Error& e) {
    EXPECT_EQ(e.status(), status) << e.what();
    EXPECT_NE(std::string(e.what()).find(path), std::string::npos) << e.what();
    return e.what();
  }
  return "";
}

void write_text(const std::string& path, const std::string& text) { std::ofstream(path) << text; }

TEST(Meshes, BundledMeshesLoad) {
  const std::string dir = ARCUS_SOURCE_DIR "/data/meshes/";
  const struct {
    const char* file;
    size_t triangles;
    bool uvs;
  } cases[] = {{"icosphere.obj", 1280, false}, {"torus.obj", 1024, true}, {"tower.ply", 528, false}};
  for (const auto& c : cases) {
    const Mesh m = load_mesh(dir + c.file);
    EXPECT_EQ(m.triangle_count(), c.triangles) << c.file;
    EXPECT_EQ(m.source, dir + c.file);
    EXPECT_EQ(m.uvs.size(), c.uvs ? 2 * m.vertex_count() : 0u) << c.file;
    for (double x : m.positions) ASSERT_TRUE(std::isfinite(x)) << c.file;
    for (uint32_t i : m.triangles) ASSERT_LT(i, m.vertex_count()) << c.file;
  }
  // The icosphere's vertices lie on the unit sphere, to float's precision (OpenMesh
  // reads coordinates as float).
  const Mesh ico = load_mesh(dir + "icosphere.obj");
  for (size_t v = 0; v < ico.vertex_count(); ++v) {
    const double* p = &ico.positions[3 * v];
    EXPECT_NEAR(std::sqrt(p[0] * p[0] + p[1] * p[1] + p[2] * p[2]), 1.0, 1e-7);
  }
  // The torus' texture coordinates span [0, 1]².
  const Mesh torus = load_mesh(dir + "torus.obj");
  EXPECT_EQ(*std::min_element(torus.uvs.begin(), torus.uvs.end()), 0.0);
  EXPECT_EQ(*std::max_element(torus.uvs.begin(), torus.uvs.end()), 1.0);
}

TEST(Meshes, EveryFormatRoundTripsAndPolygonsAreTriangulated) {
  TempDir dir;
  auto poly = pyramid();
  auto tri = pyramid();
  tri.triangulate();
  // The pyramid as load_mesh should give it: polygons as fans from their first vertex.
  auto expected = [](const auto& om) {
    Mesh m;
    for (auto v : om.vertices())
      for (int k = 0; k < 3; ++k) m.positions.push_back(om.point(v)[k]);
    for (auto f : om.faces()) {
      std::vector<uint32_t> ring;
      for (auto v : om.fv_range(f)) ring.push_back(static_cast<uint32_t>(v.idx()));
      for (size_t i = 1; i + 1 < ring.size(); ++i) m.triangles.insert(m.triangles.end(), {ring[0], ring[i], ring[i + 1]});
    }
    return triangles_of(m);
  };
  ASSERT_EQ(expected(poly).size(), 6u);
  for (const char* ext : {"obj", "ply", "off", "stl", "OBJ"})
    for (const bool binary : {false, true}) {
      if (binary && std::string(ext) != "ply" && std::string(ext) != "stl") continue;  // binary OFF is refused
      const std::string path = dir.path() + "/pyramid." + ext;
      const bool stl = std::string(ext) == "stl";  // STL holds triangles only
      ASSERT_TRUE(OpenMesh::IO::write_mesh(stl ? tri : poly, path,
                                           binary ? OpenMesh::IO::Options::Binary : OpenMesh::IO::Options::Default))
          << path;
      const Mesh got = load_mesh(path);
      EXPECT_EQ(got.source, path);
      EXPECT_EQ(triangles_of(got), expected(stl ? tri : poly)) << ext << (binary ? " binary" : " text");
      if (stl) EXPECT_TRUE(got.uvs.empty()) << "STL has no texture coordinates";
    }
}

TEST(Meshes, BadFilesNameTheFile) {
  TempDir dir;
  const std::string d = dir.path();
  expect_error(d + "/missing.obj", ARCUS_ERROR_IO);
  std::filesystem::create_directory(d + "/folder.obj");
  expect_error(d + "/folder.obj", ARCUS_ERROR_IO);
  write_text(d + "/empty.obj", "");
  expect_error(d + "/empty.obj", ARCUS_ERROR_INVALID_ARGUMENT);
  write_text(d + "/points.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\n");
  expect_error(d + "/points.obj", ARCUS_ERROR_INVALID_ARGUMENT);
  write_text(d + "/points.off", "OFF\n3 0 0\n0 0 0\n1 0 0\n0 1 0\n");
  expect_error(d + "/points.off", ARCUS_ERROR_INVALID_ARGUMENT);
  write_text(d + "/mesh.xyz", "v 0 0 0\n");
  expect_error(d + "/mesh.xyz", ARCUS_ERROR_INVALID_ARGUMENT);
  write_text(d + "/noext", "v 0 0 0\n");
  expect_error(d + "/noext", ARCUS_ERROR_INVALID_ARGUMENT);
  write_text(d + "/garbage.ply", "this is not a ply file\n");
  expect_error(d + "/garbage.ply", ARCUS_ERROR_INVALID_ARGUMENT);
  // Non-finite vertices, in a text format and in binary ones (where they are plain bits).
  write_text(d + "/nan.off", "OFF\n3 1 0\n0 0 0\n1 nan 0\n0 1 0\n3 0 1 2\n");
  expect_error(d + "/nan.off", ARCUS_ERROR_INVALID_ARGUMENT);
  auto m = pyramid();
  m.triangulate();
  m.set_point(m.vertex_handle(2), OpenMesh::Vec3f(1, std::nanf(""), 1));
  for (const char* ext : {"stl", "ply"}) {
    const std::string path = d + "/nan." + ext;
    ASSERT_TRUE(OpenMesh::IO::write_mesh(m, path, OpenMesh::IO::Options::Binary)) << path;
    expect_error(path, ARCUS_ERROR_INVALID_ARGUMENT);
  }
  m.set_point(m.vertex_handle(2), OpenMesh::Vec3f(1, INFINITY, 1));
  ASSERT_TRUE(OpenMesh::IO::write_mesh(m, d + "/inf.stl", OpenMesh::IO::Options::Binary));
  expect_error(d + "/inf.stl", ARCUS_ERROR_INVALID_ARGUMENT);
}

TEST(Meshes, ZeroAreaTrianglesAreKept) {
  TempDir dir;
  const std::string path = dir.path() + "/flat.obj";
  // A proper triangle, one with two coincident vertices and one with collinear ones.
  write_text(path, "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 1 0 0\nv 2 0 0\nv 3 0 0\nf 1 2 3\nf 1 2 4\nf 1 5 6\n");
  EXPECT_EQ(load_mesh(path).triangle_count(), 3u);
}

TEST(Meshes, TransformedAppliesTheAffineMatrix) {
  Mesh m;
  m.positions = {1, 2, 3, -1, 0, 0.5};
  m.triangles = {0, 1, 1};
  // x' = 2y + 1, y' = -x, z' = 3z - 2
  const double M[12] = {0, 2, 0, 1, -1, 0, 0, 0, 0, 0, 3, -2};
  const Mesh t = arcus::geometry::transformed(m, M);
  EXPECT_EQ(t.positions, (std::vector<double>{5, -1, 7, 1, 1, -0.5}));
  EXPECT_EQ(t.triangles, m.triangles);
  const double bad[12] = {NAN, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0};
  EXPECT_THROW(arcus::geometry::transformed(m, bad), arcus::Error);
}

// ---- what OpenMesh misreads: refused, with the line -------------------------------------

void expect_refused(const std::string& path, const std::string& text, const char* says) {
  write_text(path, text);
  const auto start = std::chrono::steady_clock::now();
  const std::string message = expect_error(path, ARCUS_ERROR_INVALID_ARGUMENT);
  EXPECT_NE(message.find(says), std::string::npos) << path << ": " << message;
  EXPECT_LT(std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count(), 5.0) << path;
}

TEST(MeshesHostile, APlyHeaderWithoutEndIsRefusedNotLoopedOn) {
  // OpenMesh looped for ever on the first (21 bytes) and grew by 0.6 GB/s on the second.
  TempDir dir;
  expect_refused(dir.path() + "/short.ply", "ply\nformat ascii 1.0\n", "end_header");
  std::string long_header = "ply\nformat ascii 1.0\n";
  for (int i = 0; i < 5000; ++i) long_header += "comment padding padding padding\n";
  expect_refused(dir.path() + "/long.ply", long_header + "element vertex 3\n", "end_header");
  expect_refused(dir.path() + "/keyword.ply", "ply\nformat ascii 1.0\nelement vertex 1\nproperty float x\nbogus\nend_header\n0\n",
                 "line 5: unknown header keyword");
}

TEST(MeshesHostile, CountsAPlyHeaderDeclaresMustFitTheFile) {
  TempDir dir;
  const std::string header = "ply\nformat binary_little_endian 1.0\nelement vertex 1000000000\nproperty float x\n"
                             "property float y\nproperty float z\nelement face 1\nproperty list uchar int vertex_indices\n"
                             "end_header\n";
  expect_refused(dir.path() + "/huge.ply", header + std::string(64, '\0'), "need at least 12000000001 bytes");
  expect_refused(dir.path() + "/text.ply",
                 "ply\nformat ascii 1.0\nelement vertex 100\nproperty float x\nproperty float y\nproperty float z\n"
                 "end_header\n0 0 0\n",
                 "declares 100 vertices");
}

TEST(MeshesHostile, ObjVerticesOpenMeshWouldSkipAreRefusedWithTheirLine) {
  // OpenMesh skipped each of these lines, so "f 1 2 3" below named other vertices.
  TempDir dir;
  const char* bad[] = {"nan 0 0", "0 inf 0", "0 0 1e+308", "1 2", "0x10 0 0", "1.5.5 0 0"};
  for (const char* v : bad)
    expect_refused(dir.path() + "/bad.obj", std::string("v 0 0 0\nv 1 0 0\nv ") + v + "\nv 0 1 0\nf 1 2 4\n",
                   "line 3: vertex");
  expect_refused(dir.path() + "/vt.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nvt 0 nan\nf 1/1 2/1 3/1\n", "line 4: texture");
  // Tiny values are fine: they read as (denormal or zero) floats.
  write_text(dir.path() + "/tiny.obj", "v 0 0 0\nv 1e-50 1 0\nv 0 0 1\nf 1 2 3\n");
  EXPECT_EQ(load_mesh(dir.path() + "/tiny.obj").triangle_count(), 1u);
}

TEST(MeshesHostile, FacesNamingMissingVerticesOrCoordinatesAreRefused) {
  // OpenMesh dropped such faces with a line on stderr, and the render went on without them.
  TempDir dir;
  const std::string three = "v 0 0 0\nv 1 0 0\nv 0 1 0\n";
  expect_refused(dir.path() + "/far.obj", three + "f 1 2 3\nf 1 2 9\n", "line 5: face: vertex index 9");
  expect_refused(dir.path() + "/back.obj", three + "f -1 -2 -4\n", "vertex index -4");
  expect_refused(dir.path() + "/zero.obj", three + "f 0 1 2\n", "is not a vertex index");
  expect_refused(dir.path() + "/vt.obj", three + "vt 0 0\nf 1/1 2/2 3/1\n", "texture coordinate index 2");
  expect_refused(dir.path() + "/two.obj", three + "f 1 2\n", "at least three corners");
  expect_refused(dir.path() + "/off.off", "OFF\n3 1 0\n0 0 0\n1 0 0\n0 1 0\n3 0 1 3\n", "line 6: face");
  expect_refused(dir.path() + "/few.off", "OFF\n4 1 0\n0 0 0\n1 0 0\n0 1 0\n", "declares 4 vertices");
  // A binary PLY face naming vertex 7 of 3: only OpenMesh's count of what it took shows it.
  std::string ply = "ply\nformat binary_little_endian 1.0\nelement vertex 3\nproperty float x\nproperty float y\n"
                    "property float z\nelement face 1\nproperty list uchar int vertex_indices\nend_header\n";
  const float xyz[9] = {0, 0, 0, 1, 0, 0, 0, 1, 0};
  ply.append(reinterpret_cast<const char*>(xyz), sizeof xyz);
  const int32_t face[3] = {0, 1, 7};
  ply += '\3';
  ply.append(reinterpret_cast<const char*>(face), sizeof face);
  expect_refused(dir.path() + "/index.ply", ply, "faces name vertices that do not exist");
}

TEST(MeshesHostile, AnStlTriangleWithCoincidentCornersIsDroppedNotAnError) {
  // OpenMesh's STL reader never hands over a triangle whose corners merge: it has no
  // area, so the file is read with the others (CAD exports have them).
  TempDir dir;
  for (const bool binary : {false, true}) {
    const float tris[2][9] = {{0, 0, 0, 1, 0, 0, 0, 1, 0}, {0, 0, 0, 1, 0, 0, 1, 0, 0}};
    std::string bytes;
    if (binary) {
      bytes = std::string(80, '\0');
      const uint32_t n = 2;
      bytes.append(reinterpret_cast<const char*>(&n), 4);
      for (const auto& t : tris) {
        bytes.append(12, '\0');
        bytes.append(reinterpret_cast<const char*>(t), sizeof t);
        bytes.append(2, '\0');
      }
    } else {
      bytes = "solid s\n";
      for (const auto& t : tris) {
        bytes += "facet normal 0 0 1\nouter loop\n";
        for (int c = 0; c < 3; ++c)
          bytes += "vertex " + std::to_string(t[3 * c]) + " " + std::to_string(t[3 * c + 1]) + " " +
                   std::to_string(t[3 * c + 2]) + "\n";
        bytes += "endloop\nendfacet\n";
      }
      bytes += "endsolid s\n";
    }
    const std::string path = dir.path() + "/cad.stl";
    std::ofstream(path, std::ios::binary | std::ios::trunc) << bytes;
    EXPECT_EQ(load_mesh(path).triangle_count(), 1u) << (binary ? "binary" : "text");
  }
}

TEST(MeshesHostile, NonManifoldFacesAreKeptWhole) {
  // Three triangles on one edge: OpenMesh's importer adds the third with copies of its
  // vertices; no face is lost.
  TempDir dir;
  write_text(dir.path() + "/fin.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 0 -1 0\nv 0 0 1\nf 1 2 3\nf 2 1 4\nf 1 2 5\n");
  EXPECT_EQ(load_mesh(dir.path() + "/fin.obj").triangle_count(), 3u);
}

TEST(MeshesHostile, AMaterialLibraryIsNeverOpened) {
  // OpenMesh opened an OBJ's mtllib itself: a FIFO there blocked the load for ever.
  TempDir dir;
  const std::string fifo = dir.path() + "/materials.mtl";
  ASSERT_EQ(::mkfifo(fifo.c_str(), 0600), 0);
  write_text(dir.path() + "/m.obj", "mtllib materials.mtl\nv 0 0 0\nv 1 0 0\nv 0 1 0\nusemtl a\nf 1 2 3\n");
  EXPECT_EQ(load_mesh(dir.path() + "/m.obj").triangle_count(), 1u);
}

TEST(MeshesHostile, SpecialFilesAreRefusedWithoutBlocking) {
  TempDir dir;
  const std::string fifo = dir.path() + "/pipe.obj";
  ASSERT_EQ(::mkfifo(fifo.c_str(), 0600), 0);
  EXPECT_NE(expect_error(fifo, ARCUS_ERROR_IO).find("is a FIFO"), std::string::npos);
  ::symlink("/dev/zero", (dir.path() + "/zero.ply").c_str());
  EXPECT_NE(expect_error(dir.path() + "/zero.ply", ARCUS_ERROR_IO).find("character device"), std::string::npos);
}

TEST(MeshesHostile, TheFuzzersRegressionInputsLoadOrFailCleanlyAndQuickly) {
  // tests/fuzz/mesh/regressions: each once hung OpenMesh, exhausted memory or was
  // misread.  The first byte picks the extension, as in fuzz_mesh.cpp.
  const char* const extensions[] = {".obj", ".ply", ".off", ".stl"};
  TempDir dir;
  int n = 0;
  for (const auto& entry : std::filesystem::directory_iterator(ARCUS_SOURCE_DIR "/tests/fuzz/mesh/regressions")) {
    std::ifstream in(entry.path(), std::ios::binary);
    const std::string data((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    ASSERT_FALSE(data.empty()) << entry.path();
    const std::string path = dir.path() + "/input" + extensions[static_cast<unsigned char>(data[0]) % 4];
    std::ofstream(path, std::ios::binary | std::ios::trunc) << data.substr(1);
    const auto start = std::chrono::steady_clock::now();
    try {
      const Mesh m = load_mesh(path);
      for (uint32_t v : m.triangles) EXPECT_LT(v, m.vertex_count()) << entry.path();
    } catch (const arcus::Error& e) {
      EXPECT_EQ(std::string(e.what()).rfind(path, 0), 0u) << e.what();
    }
    EXPECT_LT(std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count(), 5.0) << entry.path();
    ++n;
  }
  EXPECT_GE(n, 10);
}

}  // namespace
