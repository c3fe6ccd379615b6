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
  // The pixel's footprint: how u and v change to the next pixel across and down (0: a
  // point sample, as photons and lone pixels take).
  double du_x = 0, dv_x = 0, du_y = 0, dv_y = 0;
};

// The surface of hit primitive `index` of `kind` (ARCUS_HIT_*) at p, for a ray arriving
// along `arriving`.
Surface surface_at(const RenderScene& s, int32_t kind, int32_t index, Vec3 p, Vec3 arriving);

// The diffuse albedo of material `material` (of the scene's materials) there: its
// texture filtered over the surface's footprint.
Vec3 albedo(const RenderScene& s, size_t material, const Surface& surface);

// Each camera pixel's footprint (image `width` pixels wide, row by row) from its
// neighbours' texture coordinates: toward the neighbour, either side, on the same
// object whose coordinates change least (a neighbour across an edge or a mirage's
// fold would blur a whole tile in).  `object`: per pixel, the object hit or -1.
void set_footprints(const std::vector<int32_t>& object, int width, std::vector<Surface>* surfaces);

}  // namespace arcus::render
