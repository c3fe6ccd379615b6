// Meshes from memory (include/arcus/arcus_scene.h): arcus_mesh_create, arcus_mesh_load and
// the handle.
#include <memory>

#include "core/call.h"
#include "geometry/mesh_handle.h"

using namespace arcus;
using namespace arcus::api;

namespace arcus::geometry {
const HandleKind kMeshHandle("mesh");
}  // namespace arcus::geometry

extern "C" {

arcus_status arcus_mesh_create(arcus_context_t* ctx, size_t vertex_count, const double* vertices,
                               size_t triangle_count, const uint32_t* indices, arcus_mesh_t** out) {
  return simple<arcus_context_s>(ctx, kContextHandle, "ctx", [&](arcus_context_s*) {
    require_pointer(out, "out");
    *out = nullptr;
    auto mesh = std::make_unique<arcus_mesh_s>(
        ctx, geometry::mesh_from_arrays(vertex_count, vertices, triangle_count, indices));
    retain_context(ctx);  // the mesh's reference
    *out = mesh.release();
  });
}

arcus_status arcus_mesh_retain(arcus_mesh_t* mesh) { return retain(mesh, geometry::kMeshHandle, "mesh"); }

arcus_status arcus_mesh_release(arcus_mesh_t* mesh) { return release(mesh, geometry::kMeshHandle, "mesh"); }

arcus_status arcus_mesh_get_counts(arcus_mesh_t* mesh, size_t* vertex_count, size_t* triangle_count) {
  return simple<arcus_mesh_s>(mesh, geometry::kMeshHandle, "mesh", [&](arcus_mesh_s* m) {
    if (vertex_count) *vertex_count = m->mesh.vertex_count();
    if (triangle_count) *triangle_count = m->mesh.triangle_count();
  });
}

arcus_status arcus_mesh_load(arcus_context_t* ctx, const char* path, arcus_mesh_t** out) {
  return simple<arcus_context_s>(ctx, kContextHandle, "ctx", [&](arcus_context_s*) {
    require_pointer(out, "out");
    *out = nullptr;
    require_pointer(path, "path");
    auto mesh = std::make_unique<arcus_mesh_s>(ctx, geometry::load_mesh(path));
    retain_context(ctx);  // the mesh's reference
    *out = mesh.release();
  });
}

arcus_status arcus_mesh_get_arrays(arcus_mesh_t* mesh, double* vertices, uint32_t* indices) {
  return simple<arcus_mesh_s>(mesh, geometry::kMeshHandle, "mesh", [&](arcus_mesh_s* m) {
    copy_out(m->mesh.positions, vertices);
    copy_out(m->mesh.triangles, indices);
  });
}

}  // extern "C"
