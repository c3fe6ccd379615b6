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
//
// Optimizations (thesis §4.3.4), each switched by the renderer's ARCUS_TECHNIQUE_* bits
// (PhotonOptions::techniques), all applied to the FIRST generation — the photons as they
// leave the lights, the one generation that is the same every frame and whose photons
// have neighbours in a low-dimensional sampling coordinate; bounced photons (which start
// anywhere, in any direction) are always traced.
//
// The sampling coordinate ("direction" in the thesis).  A point light's photons differ
// by their direction: the coordinate is the unit direction, and an angle t is the chord
// 2 sin(t/2) between unit vectors.  A sun's photons all share one direction (a parallel
// beam), so their direction cannot tell them apart: the coordinate is the photon's start
// point on the sun's portal (the window) projected across the beam (two coordinates in
// the plane perpendicular to the sun: the distance between the parallel rays), and t
// becomes a distance t·D, D the largest side of the scene's bounds: two rays from a
// point t apart in angle are about t·D apart where they cross the scene, so parallel
// rays t·D apart are "as close" as those.  Cross room (D = 5.1 m): t = 2° ↔ 0.178 m,
// 3° ↔ 0.267 m.  Neighbours are found with a grid hash over these coordinates.
//
//   SMART_STEP   (threshold t = 3°, smart_step_deg) trace() is given each photon's
//                predicted hit step: temporally the same photon's end step in the
//                previous frame (PhotonCache, same seed: the same photons); else
//                spatially, a first pass traces a "coarse" set (photons with no earlier
//                coarse photon within t) and every other photon predicts the end step of
//                its nearest coarse photon within t.  Exact: trace() proves the skipped
//                steps empty, so the photon map is bit for bit the one without it.
//   SYMMETRY     the mid-planes of the scene's bounds (x, y, z, in that order) are tried
//                as mirror planes: the first one the medium (medium_asymmetry, the
//                renderer's test for its camera plane made plane-generic), every light
//                (a sun's direction parallel to it, a point light on it) and every sun's
//                portal (its triangles' corners, edge midpoints and centroids mirrored
//                land on the portal) are symmetric about is used; none: the shot is
//                refused (ARCUS_ERROR_UNSUPPORTED, photon_asymmetry's reason).  Photons
//                then come in pairs (ids 2k, 2k+1 of each light's share): the first is
//                drawn as usual and folded onto the plane's positive side, the second is
//                its mirror image.  The first is traced with its path recorded up to
//                its hit (record_paths; in chunks of 32 768 to bound the memory); the
//                second walks that path mirrored (walk(), mirror = 1): the geometry need
//                not be symmetric, the mirrored path meets the real scene.  The bounds are symmetric about
//                their mid-plane, so a mirrored path ends where a traced one would.
//   UNDERSAMPLE  (t = 2°, n = 3: undersample_deg, undersample_n) photons are visited in
//                order; one with ≥ n stored (computed) photons of its light within t is
//                interpolated from the n closest of them, the others are computed and
//                stored.  An interpolated photon's hit is the affine combination of its
//                neighbours' hits whose weights reproduce its sampling coordinate (in the
//                plane across the beam / tangent to the sphere): exact where the hit
//                moves affinely with the start, as on a plane lit by a parallel beam
//                through a medium varying along it; its direction is the same
//                combination, normalized.  When the n closest would extrapolate far
//                (a weight beyond ±3, or nearly collinear) the closest in each of n equal
//                angular sectors around it are tried (they mostly surround it); failing
//                that it is computed and stored.  Interpolation needs all n neighbours on
//                one plane (coplanar triangles of one object, or one disc; not spheres),
//                else the photon is traced after all ("fallback", counted in `traced`).
//                A symmetric pair's mirror is interpolated from its neighbours' mirrors.
//                Cross room, 500 000 photons: ~190 computed, hit error mean 3e-8 m, max
//                1.4e-6 m (the crossing's own tolerance) against tracing them.
//   PATH_CACHE   the first generation's results (the photons as emitted, their powers,
//                hits, directions, statuses) are kept in the PhotonCache while the scene,
//                the integrator, the photon count, the seed and the result-changing
//                techniques (SYMMETRY, UNDERSAMPLE) are unchanged; the next frame takes
//                them instead of tracing (the renderer drops the cache with its frames).
//   SYMMETRY's mirrors whose walk is unresolved (walk(): the mirrored path ended on a hit
//   its mirror does not have — asymmetric geometry) are traced after all ("fallback").
//   Smart step applies to every computed first-generation path (traced, recorded, the
//   mirrors' walks: a mirror predicts its twin's end step, which is its own).
#pragma once

#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "arcus/arcus_render.h"
#include "photon/photon_map.h"
#include "render/scene.h"
#include "render/trace.h"

namespace arcus::render {

constexpr int kMaxPhotonBounces = 16;  // diffuse bounces after the first hit
constexpr const char* kWindowMaterial = "window";

struct PhotonStats {
  uint64_t shot = 0, stored = 0;
  uint64_t traced = 0;        // photon paths integrated, every generation (undersampling's fallbacks too)
  uint64_t mirrored = 0;      // SYMMETRY: first-generation photons that walked a mirrored path
  uint64_t interpolated = 0;  // UNDERSAMPLE: first-generation hits interpolated
  uint64_t cached = 0;        // PATH_CACHE: first-generation results taken from the cache
  uint64_t tests = 0;         // intersection tests, every trace and walk
  uint64_t steps = 0;         // integrator steps of the paths integrated
  // PhotonOptions::measure_interpolation: the interpolated hits against the same photons
  // traced (those whose traced photon hits something), metres.
  uint64_t interpolation_measured = 0;
  double interpolation_error_mean = 0, interpolation_error_max = 0;
  double seconds = 0;
};

// What one frame's photons leave to the next (a renderer holds one): the first
// generation for PATH_CACHE, its end steps for SMART_STEP's temporal prediction.
struct PhotonCache {
  PhotonCache();
  ~PhotonCache();
  struct Data;
  std::unique_ptr<Data> data;
  size_t bytes() const;  // host memory held
};

struct PhotonOptions {
  uint32_t techniques = 0;        // ARCUS_TECHNIQUE_* bits
  PhotonCache* cache = nullptr;   // may be null: no path cache, no temporal prediction
  double smart_step_deg = 3;      // t of smart step selection
  double undersample_deg = 2;     // t of undersampling
  uint32_t undersample_n = 3;     // n of undersampling (≥ 1)
  bool measure_interpolation = false;  // trace the interpolated photons too (stats)
};

// The plane of symmetry SYMMETRY uses for the scene's photons ("" and *plane), or why
// there is none (the reason for each mid-plane of the bounds).
std::string photon_asymmetry(const RenderScene& scene, MirrorPlane* plane);

// Why the medium is not symmetric about `plane` ("" if it is): a constant medium always
// is; a linear one when its gradient is parallel to the plane; a Luneburg lens or fish
// eye when its centre lies on it; a flat atmosphere when the plane is vertical, a
// spherical one when the Earth's centre (the origin) lies on it; a grid never (unchecked).
std::string medium_asymmetry(const arcus_field_desc_d& medium, const MirrorPlane& plane);

// The first generation as shot (tests, diagnostics): per photon its start, direction,
// id, how its hit was found (kFirst*) and the hit (NaN where none), status and object.
enum : int32_t { kFirstTraced = 0, kFirstMirrored = 1, kFirstInterpolated = 2, kFirstFallback = 3, kFirstCached = 4 };
struct FirstGeneration {
  std::vector<double> origins, directions, hits;  // 3 per photon
  std::vector<uint64_t> ids;
  std::vector<int32_t> how, status, object;
};
FirstGeneration first_generation(arcus_context_t* ctx, RenderScene* scene, const arcus_advance_params& params,
                                 uint64_t count, uint64_t seed, PhotonStats* stats, const PhotonOptions& options = {});

// Shoots `count` photons (1..2^26) from the scene's lights through its medium (trace(),
// curved) with `params` as the integrator (the box is the scene's bounds), stores them
// at diffuse hits with Russian roulette (survival = the albedo's mean), bounces them
// diffusely (cosine-weighted) until absorbed or the bounce limit; returns the photons
// (RGB powers, W) as stored, in the order they were stored.  Bad arguments (count 0,
// null pointers) are INVALID_ARGUMENT.  A scene without lights gives no photons.
photon::Photons shoot_photon_list(arcus_context_t* ctx, RenderScene* scene, const arcus_advance_params& params,
                                  uint64_t count, uint64_t seed, PhotonStats* stats, const PhotonOptions& options = {});

// The same, built into a photon map on ctx's device (stats->seconds includes the build).
std::unique_ptr<photon::PhotonMap> shoot_photons(arcus_context_t* ctx, RenderScene* scene,
                                                 const arcus_advance_params& params, uint64_t count, uint64_t seed,
                                                 PhotonStats* stats, const PhotonOptions& options = {});

// Irradiance (3 per point, W/m²) at hit points with their normals (facing the arriving
// ray: only photons that arrived from that side count), from the k nearest photons
// within max_radius (scene.desc.photons: estimate, max_radius).  Radiance of a diffuse
// surface there: albedo / π · irradiance.
std::vector<double> photon_irradiance(arcus_context_t* ctx, const photon::PhotonMap& map, const RenderScene& scene,
                                      const std::vector<double>& points, const std::vector<double>& normals);

}  // namespace arcus::render
