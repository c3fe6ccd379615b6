// The surface at a hit, as camera rays and photons both see it: the normal facing the
// arriving ray, texture coordinates, and the diffuse albedo (colour × texture).
#pragma once

#include <cstdint>

#include "render/scene.h"
#include "geometry/vec3.h"

namespace arcus::render {

struct Surface {
  Vec3 normal;
  double u = 0, v = 0;
  bool has_uv = false;
};

// The surface of hit primitive `index` of `kind` (ARCUS_HIT_*) at p, for a ray arriving
// along `arriving`.
Surface surface_at(const RenderScene& s, int32_t kind, int32_t index, Vec3 p, Vec3 arriving);

// The diffuse albedo of material `material` (of the scene's materials) there.
Vec3 albedo(const RenderScene& s, size_t material, const Surface& surface);

}  // namespace arcus::render
