// Curved photon mapping (thesis §4.3.4; Gutierrez et al., GMAS05): photons
// are shot from the scene's lights along curved paths through its medium (trace(), the
// same per-step hit test as camera rays), stored at every diffuse surface they reach,
// and bounced diffusely until Russian roulette absorbs them; the radiance at a camera
// ray's hit is then albedo/π times the irradiance estimated from the k nearest photons,
// E ≈ Σ Φ / (π r_k²) (photon/photon_map.h).
//
// Emission.
//   Point light (intensity I per channel): isotropic from its position, each photon
//     carrying 4π·I / N_light.
//   Sun (irradiance E per channel on a surface facing it, direction s toward the sun):
//     a parallel beam along −s through a "portal" made of triangles:
//       - the triangles of the material named "window", when the scene has any: the
//         opening the light comes in through (the room's window).  A window is an
//         opening, so photons cross "window" primitives as if they were not there, at
//         emission and whenever a bounced photon reaches one (it leaves through it);
//         camera rays still see it (give it an emission: the bright sky outside);
//       - else the faces of the scene's bounds that face the sun (two triangles each).
//     A point is drawn uniformly over the portal's area as seen from the sun (a
//     triangle with probability ∝ its area × |n·s|, then uniformly within it), and the
//     photon starts just past the portal, inside the bounds, travelling along −s; each
//     carries E·A/N_light, A = Σ area·|n·s| (the portal's area projected perpendicular
//     to the sun).  The sun's light is thus taken to arrive parallel at the portal: the
//     medium bends it from there on.  The portal's triangles must not overlap as seen
//     from the sun (a flat opening, or the convex bounds, never do).
//   The photons are shared among the lights in proportion to their flux (summed over
//   the channels).  Emissive materials do not shoot photons.
//
// Transport: each generation is one trace() over the photons still alive.  At a
// diffuse hit the photon is stored (position, arriving direction, power: RGB), then
// survives with probability P = mean of the albedo (diffuse × texture, clamped to 1)
// and leaves cosine-weighted about the normal on the side it came from, its power
// scaled by albedo / P; photons that leave the bounds, fail or exceed the bounce limit
// (kMaxPhotonBounces diffuse bounces) are dropped.  Spectral scenes: photons carry the
// three RGB channels and use the medium's own wavelength.
//
// Randomness: the project's Philox 4x32-10 (kernels/common/philox.h) on the host, draw
// (generation, purpose) of photon i of job `seed`: counter-based, so every photon's
// path depends only on (seed, i) — not on the batch it travels in, on how many survive
// around it, on the thread count or the device — and the map is reproducible bit for
// bit on every machine (a sequential std::mt19937_64 would tie photon i's numbers to
// the order in which the surviving photons are visited).
#pragma once

#include <cstdint>
#include <memory>
#include <vector>

#include "arcus/arcus_render.h"
#include "photon/photon_map.h"
#include "render/scene.h"

namespace arcus::render {

constexpr int kMaxPhotonBounces = 16;  // diffuse bounces after the first hit
constexpr const char* kWindowMaterial = "window";

struct PhotonStats {
  uint64_t shot = 0, stored = 0;
  double seconds = 0;
};

// Shoots `count` photons (1..2^26) from the scene's lights through its medium (trace(),
// curved) with `params` as the integrator (the box is the scene's bounds), stores them
// at diffuse hits with Russian roulette (survival = the albedo's mean), bounces them
// diffusely (cosine-weighted) until absorbed or the bounce limit; returns the photons
// (RGB powers, W) as stored, in the order they were stored.  Bad arguments (count 0,
// null pointers) are INVALID_ARGUMENT.  A scene without lights gives no photons.
photon::Photons shoot_photon_list(arcus_context_t* ctx, RenderScene* scene, const arcus_advance_params& params,
                                  uint64_t count, uint64_t seed, PhotonStats* stats);

// The same, built into a photon map on ctx's device (stats->seconds includes the build).
std::unique_ptr<photon::PhotonMap> shoot_photons(arcus_context_t* ctx, RenderScene* scene,
                                                 const arcus_advance_params& params, uint64_t count, uint64_t seed,
                                                 PhotonStats* stats);

// Irradiance (3 per point, W/m²) at hit points with their normals (facing the arriving
// ray: only photons that arrived from that side count), from the k nearest photons
// within max_radius (scene.desc.photons: estimate, max_radius).  Radiance of a diffuse
// surface there: albedo / π · irradiance.
std::vector<double> photon_irradiance(arcus_context_t* ctx, const photon::PhotonMap& map, const RenderScene& scene,
                                      const std::vector<double>& points, const std::vector<double>& normals);

}  // namespace arcus::render
