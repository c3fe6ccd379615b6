// Meshes from memory (arcus_mesh_create, arcus_scene.h) through the public C API: the
// same vertices and triangles from memory and from a file are the same particle and
// cast the same light, bit for bit; bad arrays are refused with the argument named;
// the handle is checked like every other.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <fstream>
#include <limits>
#include <string>
#include <vector>

#include "arcus/arcus.h"
#include "test_util.h"

namespace {

using arcus_test::ArcusTest;
using arcus_test::ContextPtr;
using arcus_test::JobPtr;
using arcus_test::MeshPtr;
using arcus_test::ParticlePtr;

class MeshesApi : public ArcusTest {};

// A box of half-sides 1, 0.75 and 0.5 (every coordinate exact in single precision, as
// file readers hand them over), two triangles a face, wound outward.
const std::vector<double> kBoxVertices = [] {
  std::vector<double> v;
  for (int i = 0; i < 8; ++i) v.insert(v.end(), {i & 1 ? 1.0 : -1.0, i & 2 ? 0.75 : -0.75, i & 4 ? 0.5 : -0.5});
  return v;
}();
const std::vector<uint32_t> kBoxIndices = {0, 2, 3, 0, 3, 1, 4, 5, 7, 4, 7, 6, 0, 1, 5, 0, 5, 4,
                                           2, 6, 7, 2, 7, 3, 0, 4, 6, 0, 6, 2, 1, 3, 7, 1, 7, 5};

// The box as an OFF file.
std::string write_box_off() {
  const std::string path = testing::TempDir() + "arcus_meshes_api_box.off";
  std::ofstream f(path);
  f << "OFF\n8 12 0\n";
  for (size_t v = 0; v < 8; ++v)
    f << kBoxVertices[3 * v] << " " << kBoxVertices[3 * v + 1] << " " << kBoxVertices[3 * v + 2] << "\n";
  for (size_t t = 0; t < 12; ++t)
    f << "3 " << kBoxIndices[3 * t] << " " << kBoxIndices[3 * t + 1] << " " << kBoxIndices[3 * t + 2] << "\n";
  return path;
}

// A mesh of `ctx` (null when refused).
MeshPtr make_mesh(arcus_context_t* ctx, const std::vector<double>& vertices, const std::vector<uint32_t>& indices,
                  arcus_status* status = nullptr) {
  arcus_mesh_t* m = nullptr;
  const arcus_status st =
      arcus_mesh_create(ctx, vertices.size() / 3, vertices.data(), indices.size() / 3, indices.data(), &m);
  if (status) {
    *status = st;
  } else {
    EXPECT_EQ(st, ARCUS_SUCCESS) << arcus_context_last_error(ctx);
  }
  return MeshPtr(m);
}

// A particle of `mesh` (null when refused).
ParticlePtr from_mesh(arcus_mesh_t* mesh, double scale, int smooth) {
  arcus_particle_t* p = nullptr;
  EXPECT_EQ(arcus_particle_create_from_mesh(mesh, scale, smooth, &p), ARCUS_SUCCESS) << arcus_last_error();
  return ParticlePtr(p);
}

arcus_rainbow_params small_cast() {
  arcus_rainbow_params params;
  EXPECT_EQ(arcus_rainbow_params_init(&params), ARCUS_SUCCESS);
  params.grid = 8;
  return params;
}

// What a cast of `particle` gives: its stats, its phase function at a few angles and
// its glints.
struct Cast {
  arcus_rainbow_stats stats{};
  std::vector<double> parallel, perpendicular, per_bounce;
  std::vector<uint32_t> terms;
  std::vector<double> directions, cross_sections;
};

Cast cast(arcus_context_t* ctx, arcus_particle_t* particle) {
  arcus_rainbow_params params = small_cast();
  params.grid = 48;
  params.query_phi_deg = 0;
  const double s = std::sqrt(0.5);  // 45° about x, then the light meets edges and faces
  const double rotation[9] = {1, 0, 0, 0, s, -s, 0, s, s};
  std::copy(rotation, rotation + 9, params.rotation);
  arcus_job_t* raw = nullptr;
  Cast r;
  EXPECT_EQ(arcus_rainbow_cast(ctx, particle, &params, &raw), ARCUS_SUCCESS) << arcus_context_last_error(ctx);
  const JobPtr job(raw);
  if (!job) return r;
  EXPECT_EQ(arcus_job_get_rainbow_stats(job.get(), &r.stats), ARCUS_SUCCESS);
  const std::vector<double> theta = {10, 45, 90, 120, 138, 150, 179};
  r.parallel.resize(theta.size());
  r.perpendicular.resize(theta.size());
  r.per_bounce.resize(theta.size() * (params.max_bounces + 1));
  EXPECT_EQ(arcus_job_get_rainbow_phase(job.get(), theta.size(), theta.data(), nullptr, 1, r.parallel.data(),
                                        r.perpendicular.data(), r.per_bounce.data()),
            ARCUS_SUCCESS)
      << arcus_context_last_error(ctx);
  size_t count = 0;
  EXPECT_EQ(arcus_job_get_rainbow_glints(job.get(), &count, nullptr, nullptr, nullptr, nullptr), ARCUS_SUCCESS);
  r.terms.resize(count);
  r.directions.resize(3 * count);
  r.cross_sections.resize(count);
  EXPECT_EQ(arcus_job_get_rainbow_glints(job.get(), &count, r.terms.data(), r.directions.data(), nullptr,
                                         r.cross_sections.data()),
            ARCUS_SUCCESS);
  return r;
}

// Equal bit for bit (NaN equal to NaN).
void expect_identical(const std::vector<double>& a, const std::vector<double>& b, const char* what) {
  ASSERT_EQ(a.size(), b.size()) << what;
  for (size_t i = 0; i < a.size(); ++i)
    EXPECT_TRUE(a[i] == b[i] || (std::isnan(a[i]) && std::isnan(b[i])))
        << what << "[" << i << "]: " << a[i] << " vs " << b[i];
}

// Determinism: the box from memory and from an OFF file is one mesh downstream; for a
// smooth and a flat surface, particle info, cast stats, phase values and glints agree
// exactly.
TEST_F(MeshesApi, DeterminismMemoryMeshCastsAsTheSameFileMesh) {
  const std::string path = write_box_off();
  const MeshPtr m = make_mesh(ctx(), kBoxVertices, kBoxIndices);
  ASSERT_TRUE(m);
  size_t nv = 0, nt = 0;
  ASSERT_EQ(arcus_mesh_get_counts(m.get(), &nv, &nt), ARCUS_SUCCESS);
  EXPECT_EQ(nv, 8u);
  EXPECT_EQ(nt, 12u);
  for (const int smooth : {0, 1}) {
    arcus_particle_t* raw = nullptr;
    ASSERT_EQ(arcus_particle_create_mesh(ctx(), path.c_str(), 1e-4, smooth, &raw), ARCUS_SUCCESS) << last_error();
    const ParticlePtr from_file(raw), from_memory = from_mesh(m.get(), 1e-4, smooth);
    ASSERT_TRUE(from_memory);
    arcus_particle_info a, b;
    ASSERT_EQ(arcus_particle_get_info(from_file.get(), &a), ARCUS_SUCCESS);
    ASSERT_EQ(arcus_particle_get_info(from_memory.get(), &b), ARCUS_SUCCESS);
    EXPECT_EQ(a.kind, ARCUS_PARTICLE_MESH);
    EXPECT_EQ(b.kind, a.kind);
    EXPECT_EQ(b.equivalent_radius, a.equivalent_radius);
    EXPECT_EQ(b.volume, a.volume);
    EXPECT_NEAR(a.volume, 8 * 0.75 * 0.5 * 1e-12, 1e-24);
    EXPECT_EQ(b.bound_radius, a.bound_radius);
    EXPECT_EQ(b.triangles, a.triangles);
    const Cast x = cast(ctx(), from_file.get()), y = cast(ctx(), from_memory.get());
    EXPECT_GT(x.stats.hits, 0u);
    EXPECT_EQ(y.stats.rays, x.stats.rays);
    EXPECT_EQ(y.stats.hits, x.stats.hits);
    EXPECT_EQ(y.stats.patches, x.stats.patches);
    EXPECT_EQ(y.stats.intercepted, x.stats.intercepted);
    expect_identical(std::vector<double>(x.stats.scattered, x.stats.scattered + 4),
                     std::vector<double>(y.stats.scattered, y.stats.scattered + 4), "scattered");
    expect_identical(x.parallel, y.parallel, "parallel");
    expect_identical(x.perpendicular, y.perpendicular, "perpendicular");
    expect_identical(x.per_bounce, y.per_bounce, "per_bounce");
    EXPECT_EQ(x.terms, y.terms);
    expect_identical(x.directions, y.directions, "glint directions");
    expect_identical(x.cross_sections, y.cross_sections, "glint cross-sections");
    if (!smooth) {
      EXPECT_GT(x.terms.size(), 0u);
    }
  }
  std::remove(path.c_str());
}

// The mesh's arrays are copied: changing or freeing them afterwards changes nothing,
// and a particle outlives the mesh it was made from.
TEST_F(MeshesApi, ArraysAreCopiedAndParticlesOutliveTheMesh) {
  std::vector<double> vertices = kBoxVertices;
  MeshPtr m = make_mesh(ctx(), vertices, kBoxIndices);
  ASSERT_TRUE(m);
  vertices.assign(vertices.size(), std::numeric_limits<double>::quiet_NaN());
  const ParticlePtr p = from_mesh(m.get(), 1e-4, 0);
  ASSERT_TRUE(p);
  m.reset();
  arcus_particle_info info;
  ASSERT_EQ(arcus_particle_get_info(p.get(), &info), ARCUS_SUCCESS);
  EXPECT_EQ(info.triangles, 12u);
  EXPECT_NEAR(info.volume, 8 * 0.75 * 0.5 * 1e-12, 1e-24);
}

// Bad arrays are refused, nothing is made, and the message names the argument.
TEST_F(MeshesApi, BadInputIsRefusedWithTheArgumentNamed) {
  auto refused = [&](const std::vector<double>& v, const std::vector<uint32_t>& t, const std::string& words) {
    arcus_status st;
    EXPECT_FALSE(make_mesh(ctx(), v, t, &st)) << words;
    EXPECT_EQ(st, ARCUS_ERROR_INVALID_ARGUMENT) << words;
    EXPECT_NE(last_error().find(words), std::string::npos) << last_error();
  };
  std::vector<double> v = kBoxVertices;
  v[10] = std::numeric_limits<double>::quiet_NaN();
  refused(v, kBoxIndices, "vertices[10] = nan is not finite");
  v[10] = -std::numeric_limits<double>::infinity();
  refused(v, kBoxIndices, "vertices[10] = -inf is not finite");
  std::vector<uint32_t> t = kBoxIndices;
  t[7] = 12;
  refused(kBoxVertices, t, "indices[7] = 12 is not below vertex_count 8");
  refused(kBoxVertices, {}, "triangle_count is 0");  // indices NULL: an empty array may be
  refused({}, kBoxIndices, "indices[0] = 0 is not below vertex_count 0");

  arcus_mesh_t* m = nullptr;
  EXPECT_EQ(arcus_mesh_create(ctx(), 8, nullptr, 12, kBoxIndices.data(), &m), ARCUS_ERROR_INVALID_ARGUMENT);
  EXPECT_EQ(last_error(), "vertices is NULL");
  EXPECT_EQ(arcus_mesh_create(ctx(), 8, kBoxVertices.data(), 12, nullptr, &m), ARCUS_ERROR_INVALID_ARGUMENT);
  EXPECT_EQ(last_error(), "indices is NULL");
  EXPECT_EQ(arcus_mesh_create(ctx(), 8, kBoxVertices.data(), 12, kBoxIndices.data(), nullptr),
            ARCUS_ERROR_INVALID_ARGUMENT);
  EXPECT_EQ(last_error(), "out is NULL");
  EXPECT_EQ(arcus_mesh_create(nullptr, 8, kBoxVertices.data(), 12, kBoxIndices.data(), &m),
            ARCUS_ERROR_INVALID_ARGUMENT);
  EXPECT_NE(std::string(arcus_last_error()).find("ctx"), std::string::npos) << arcus_last_error();
  // Counts beyond the file reader's 2^31 - 1 are refused before the arrays are read.
  EXPECT_EQ(arcus_mesh_create(ctx(), size_t(1) << 31, kBoxVertices.data(), 12, kBoxIndices.data(), &m),
            ARCUS_ERROR_INVALID_ARGUMENT);
  EXPECT_NE(last_error().find("vertex_count 2147483648"), std::string::npos) << last_error();
  EXPECT_EQ(arcus_mesh_create(ctx(), 8, kBoxVertices.data(), SIZE_MAX, kBoxIndices.data(), &m),
            ARCUS_ERROR_INVALID_ARGUMENT);
  EXPECT_NE(last_error().find("triangle_count"), std::string::npos) << last_error();
  EXPECT_EQ(m, nullptr);

  // What the particle adds, named as for a file: scale, and a mesh that is not closed.
  const MeshPtr box = make_mesh(ctx(), kBoxVertices, kBoxIndices);
  ASSERT_TRUE(box);
  arcus_particle_t* p = nullptr;
  EXPECT_EQ(arcus_particle_create_from_mesh(box.get(), -1, 0, &p), ARCUS_ERROR_INVALID_ARGUMENT);
  EXPECT_NE(last_error().find("scale"), std::string::npos) << last_error();
  EXPECT_EQ(arcus_particle_create_from_mesh(box.get(), 1, 0, nullptr), ARCUS_ERROR_INVALID_ARGUMENT);
  EXPECT_EQ(last_error(), "out is NULL");
  const MeshPtr open =
      make_mesh(ctx(), kBoxVertices, std::vector<uint32_t>(kBoxIndices.begin(), kBoxIndices.end() - 3));
  ASSERT_TRUE(open);
  EXPECT_EQ(arcus_particle_create_from_mesh(open.get(), 1, 0, &p), ARCUS_ERROR_INVALID_ARGUMENT);
  EXPECT_NE(last_error().find("the mesh is not closed: 3 of its 18 edges"), std::string::npos) << last_error();
  EXPECT_EQ(p, nullptr);

  // Beyond the 1e18 m the BVH can represent, once scaled to metres: refused at the cast,
  // as for a file.
  const ParticlePtr far = from_mesh(box.get(), 3e18, 0);
  ASSERT_TRUE(far);
  const arcus_rainbow_params params = small_cast();
  arcus_job_t* job = nullptr;
  EXPECT_EQ(arcus_rainbow_cast(ctx(), far.get(), &params, &job), ARCUS_ERROR_INVALID_ARGUMENT);
  EXPECT_EQ(job, nullptr);
  EXPECT_NE(last_error().find("beyond the 1e+18 m"), std::string::npos) << last_error();
}

// The handle is checked as every handle is: NULL, another kind, a released one; and a
// particle made from a mesh belongs to the mesh's context, not another one.
TEST_F(MeshesApi, HandlesAreChecked) {
  arcus_context_t* raw = nullptr;
  ASSERT_EQ(arcus_context_create(ARCUS_DEVICE_DEFAULT, &raw), ARCUS_SUCCESS) << arcus_last_error();
  const ContextPtr other(raw);
  arcus_particle_t* p = nullptr;
  EXPECT_EQ(arcus_particle_create_from_mesh(nullptr, 1, 0, &p), ARCUS_ERROR_INVALID_ARGUMENT);
  EXPECT_EQ(std::string(arcus_last_error()), "mesh is NULL");
  EXPECT_EQ(arcus_mesh_retain(nullptr), ARCUS_ERROR_INVALID_ARGUMENT);
  EXPECT_EQ(arcus_mesh_release(nullptr), ARCUS_ERROR_INVALID_ARGUMENT);

  // A job passed as a mesh, and a mesh passed as a particle.
  arcus_particle_t* sphere_raw = nullptr;
  ASSERT_EQ(arcus_particle_create_sphere(ctx(), 1e-4, &sphere_raw), ARCUS_SUCCESS);
  const ParticlePtr sphere(sphere_raw);
  const arcus_rainbow_params params = small_cast();
  arcus_job_t* job_raw = nullptr;
  ASSERT_EQ(arcus_rainbow_cast(ctx(), sphere.get(), &params, &job_raw), ARCUS_SUCCESS) << last_error();
  const JobPtr job(job_raw);
  auto* job_as_mesh = reinterpret_cast<arcus_mesh_t*>(job.get());
  EXPECT_EQ(arcus_particle_create_from_mesh(job_as_mesh, 1, 0, &p), ARCUS_ERROR_INVALID_ARGUMENT);
  EXPECT_EQ(last_error(), "mesh is a job, not a mesh");
  EXPECT_EQ(arcus_mesh_retain(job_as_mesh), ARCUS_ERROR_INVALID_ARGUMENT);
  EXPECT_EQ(arcus_mesh_get_counts(job_as_mesh, nullptr, nullptr), ARCUS_ERROR_INVALID_ARGUMENT);
  EXPECT_EQ(last_error(), "mesh is a job, not a mesh");
  EXPECT_EQ(p, nullptr);
  MeshPtr m = make_mesh(other.get(), kBoxVertices, kBoxIndices);
  ASSERT_TRUE(m);
  EXPECT_EQ(arcus_particle_retain(reinterpret_cast<arcus_particle_t*>(m.get())), ARCUS_ERROR_INVALID_ARGUMENT);
  EXPECT_EQ(std::string(arcus_context_last_error(other.get())), "particle is a mesh, not a particle");

  // A mesh of another context: its particle is that context's, and a cast on this one
  // refuses it.
  const ParticlePtr theirs = from_mesh(m.get(), 1e-4, 0);
  ASSERT_TRUE(theirs);
  arcus_job_t* cast_job = nullptr;
  EXPECT_EQ(arcus_rainbow_cast(ctx(), theirs.get(), &params, &cast_job), ARCUS_ERROR_INVALID_ARGUMENT);
  EXPECT_EQ(last_error(), "particle belongs to another context");
  ASSERT_EQ(arcus_rainbow_cast(other.get(), theirs.get(), &params, &cast_job), ARCUS_SUCCESS);
  JobPtr fine(cast_job);

  // Retain and release count; a released mesh is no longer a handle.
  ASSERT_EQ(arcus_mesh_retain(m.get()), ARCUS_SUCCESS);
  ASSERT_EQ(arcus_mesh_release(m.get()), ARCUS_SUCCESS);
  size_t nt = 0;
  EXPECT_EQ(arcus_mesh_get_counts(m.get(), nullptr, &nt), ARCUS_SUCCESS);
  EXPECT_EQ(nt, 12u);
  arcus_mesh_t* gone = m.release();
  ASSERT_EQ(arcus_mesh_release(gone), ARCUS_SUCCESS);
  EXPECT_EQ(arcus_particle_create_from_mesh(gone, 1, 0, &p), ARCUS_ERROR_INVALID_ARGUMENT);
  EXPECT_NE(std::string(arcus_last_error()).find("mesh"), std::string::npos) << arcus_last_error();
}

}  // namespace
