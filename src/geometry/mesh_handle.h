// The object behind arcus_mesh_t (arcus_scene.h): a mesh made from a caller's arrays,
// shared by every engine that takes meshes (rainbow: arcus_particle_create_from_mesh).
// It holds the same geometry::Mesh a mesh file gives, so downstream the two are one.
#pragma once

#include <utility>

#include "arcus/arcus_scene.h"
#include "core/handle.h"
#include "geometry/mesh.h"

namespace arcus::geometry {
extern const HandleKind kMeshHandle;  // "mesh"
}  // namespace arcus::geometry

struct arcus_mesh_s : arcus::Handle {
  arcus_mesh_s(arcus_context_t* ctx, arcus::geometry::Mesh m)
      : Handle(arcus::geometry::kMeshHandle, ctx), mesh(std::move(m)) {}
  const arcus::geometry::Mesh mesh;  // never changed once made: users copy it
};
