// Curved photon mapping's emission (photons.h): the photons as they leave the lights,
// each light's share of them, a sun's portal, and with SYMMETRY the pairs mirrored about
// a plane of symmetry of the scene (photon_asymmetry: the check that one exists).
#pragma once

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <vector>

#include "common/philox.h"  // kernels/common/philox.h: the same generator on host and device
#include "geometry/vec3.h"
#include "render/scene.h"
#include "render/trace.h"

namespace arcus::render {

// Photon `id`'s draws: 0..3 at emission, then 3 per generation (roulette, direction).
constexpr uint32_t kEmissionDraws = 4;
inline double photon_draw(uint64_t seed, uint64_t id, uint32_t d) { return arcus_rng_uniform_double(seed, id, d); }
inline uint32_t generation_draw(int generation, uint32_t k) {
  return kEmissionDraws + 3u * static_cast<uint32_t>(generation) + k;
}

// An orthonormal pair perpendicular to the unit vector n.
inline void photon_basis(Vec3 n, Vec3* t, Vec3* b) {
  *t = normalized(std::fabs(n.x) < 0.9 ? cross(n, Vec3{1, 0, 0}) : cross(n, Vec3{0, 1, 0}));
  *b = cross(n, *t);
}

// A photon in flight.
struct Live {
  Vec3 origin, direction;
  double power[3];
  uint64_t id;
  int bounces;
};

// The photons as they leave the lights, with what the techniques need of each.
struct Emission {
  std::vector<Live> live;
  std::vector<Vec3> key;              // the sampling coordinate (photons.h)
  std::vector<uint32_t> light;      // the light's index
  std::vector<int32_t> mirror_of;   // SYMMETRY: the photon this one mirrors (its index), -1
};

// Mirror images about a plane.
inline Vec3 reflect_point(const MirrorPlane& m, Vec3 p) {
  const Vec3 n = vec3(m.normal);
  return p - (2 * (dot(n, p) - m.offset)) * n;
}
inline Vec3 reflect_vector(const MirrorPlane& m, Vec3 d) {
  const Vec3 n = vec3(m.normal);
  return d - (2 * dot(n, d)) * n;
}

// `count` photons of seed `seed` shared among the scene's lights in proportion to their
// flux, each starting `offset` past its light's portal; with `plane` (SYMMETRY) in pairs,
// the second the first's mirror image.
Emission emit(const RenderScene& s, uint64_t count, uint64_t seed, double offset, const MirrorPlane* plane);

}  // namespace arcus::render
