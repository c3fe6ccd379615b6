/*
 * arcus rainbows (thesis §2.1.1, §2.2.3, §4.4, §5.5; Sadeghi et al., ACM TOG 31(1),
 * 2012): phase functions of single particles (spheres, the thesis' raindrop, any closed
 * triangle mesh) from rays cast on a grid over the particle's projection, each carrying
 * the phasors of two incident polarisations and its optical path through every
 * reflection and refraction, collected on a sphere of patches that are queried through
 * the shared BVH and summed with their phases (interference); and, for spheres, our own
 * Lorenz–Mie with its Debye-series terms.  Include arcus.h.
 *
 * Units (arcus_core.h): metres for sizes, nanometres in vacuum for wavelengths, kelvin
 * for temperatures, degrees for angles; the air around a particle has n = 1.  Frame: the
 * light travels along +z, its "horizontal" polarisation along x and "vertical" along y;
 * a scattering direction is (θ, φ) with θ from +z and φ from +x toward +y.  "Parallel"
 * and "perpendicular" are the scattered light's components along e_θ (in the
 * scattering plane) and e_φ (normal to it), for unpolarised incident light.
 */
#ifndef ARCUS_RAINBOW_H
#define ARCUS_RAINBOW_H

#include "arcus_core.h"
#include "arcus_scene.h"

#ifdef __cplusplus
extern "C" {
#endif

/* Kernel features of rainbow jobs: bits 40-47 of arcus_features.  A sphere is traced in
 * closed form and compiles neither. */
#define ARCUS_FEATURE_RAINBOW_IMPLICIT (UINT64_C(1) << 40) /* the raindrop's implicit surface (eq. 4.21) */
#define ARCUS_FEATURE_RAINBOW_MESH (UINT64_C(1) << 41)     /* triangle meshes through the shared BVH     */
/* Sky renders: a table that depends on the azimuth too (non-spherical drops, oriented
 * crystals); a table of spheres or randomly oriented particles compiles without it. */
#define ARCUS_FEATURE_RAINBOW_AZIMUTH (UINT64_C(1) << 42)

/* ---- refractive index --------------------------------------------------------- */
typedef enum arcus_material {
  ARCUS_MATERIAL_WATER = 0, /* IAPWS R9-97 at 1 atm; temperature_k applies            */
  ARCUS_MATERIAL_ICE = 1,   /* ice Ih (data/rainbow/README.md gives the source)        */
  ARCUS_MATERIAL_FIXED = 2  /* refractive_index as given, at every wavelength          */
} arcus_material;

/* The real refractive index of `material` at the vacuum wavelength `wavelength_nm` and
 * `temperature_k` kelvin (water: 253.15-383.15 K), relative to the surrounding air,
 * taken as 1 as the thesis does (§4.4.1.1; data/rainbow/README.md).  A wavelength or
 * temperature outside the formulation's range is an error that names it. */
ARCUS_API arcus_status arcus_rainbow_refractive_index(int32_t material, double wavelength_nm, double temperature_k,
                                                      double* n);

/* ---- particles ---------------------------------------------------------------- */
typedef struct arcus_particle_s arcus_particle_t;

typedef enum arcus_particle_kind {
  ARCUS_PARTICLE_SPHERE = 0,
  ARCUS_PARTICLE_RAINDROP = 1, /* thesis eq. 4.21 with Table 4.4 (1-6 mm)  */
  ARCUS_PARTICLE_MESH = 2
} arcus_particle_kind;

/* A sphere of `radius` metres. */
ARCUS_API arcus_status arcus_particle_create_sphere(arcus_context_t* ctx, double radius, arcus_particle_t** out);
/* The thesis' falling raindrop of equivalent diameter 1-6 mm (`diameter` in metres):
 * an ellipsoid deformed by eq. 4.21 with Table 4.4's a, b, k (interpolated linearly
 * between the tabulated diameters).  Its symmetry axis is its own y (up); it is
 * flattened underneath. */
ARCUS_API arcus_status arcus_particle_create_raindrop(arcus_context_t* ctx, double diameter, arcus_particle_t** out);
/* A closed triangle mesh read with OpenMesh (OBJ, PLY, OFF, STL), its coordinates
 * multiplied by `scale` (to metres).  A mesh with an edge not shared by exactly two
 * triangles is an error that says how many such edges it has.
 *   smooth = 1: the triangles approximate a smooth surface (a measured drop): normals
 *     and their curvature are interpolated from the vertices, and the phase function is
 *     the surface's;
 *   smooth = 0: the faces are flat (a crystal).  In one orientation each sequence of
 *     faces sends its light into a single direction, a peak no patch can hold: the
 *     cast reports these glints (arcus_job_get_rainbow_glints), and the phase function
 *     holds only what falls between them (averaging over orientations spreads the
 *     glints into a phase function). */
ARCUS_API arcus_status arcus_particle_create_mesh(arcus_context_t* ctx, const char* path, double scale,
                                                  int32_t smooth, arcus_particle_t** out);
/* As arcus_particle_create_mesh, of a mesh made from memory (arcus_mesh_create,
 * arcus_scene.h), on the mesh's context: the same vertices and triangles give the same
 * particle and the same casts as from a file.  The particle keeps its own copy: the
 * mesh may be released at once. */
ARCUS_API arcus_status arcus_particle_create_from_mesh(arcus_mesh_t* mesh, double scale, int32_t smooth,
                                                       arcus_particle_t** out);
ARCUS_API arcus_status arcus_particle_retain(arcus_particle_t* particle);
ARCUS_API arcus_status arcus_particle_release(arcus_particle_t* particle);

typedef struct arcus_particle_info {
  int32_t kind;             /* arcus_particle_kind                          */
  double equivalent_radius; /* of the sphere of equal volume [m]            */
  double volume;            /* [m³]                                         */
  double bound_radius;      /* of a sphere about the origin holding it [m]  */
  uint32_t triangles;       /* meshes                                       */
} arcus_particle_info;
ARCUS_API arcus_status arcus_particle_get_info(arcus_particle_t* particle, arcus_particle_info* info);

/* ---- casting (thesis §4.4.2-4.4.3.1) ------------------------------------------ */
typedef struct arcus_rainbow_params {
  double wavelength_nm;    /* in vacuum (the air around the drops is taken as n = 1)    */
  int32_t material;        /* arcus_material (water)                                    */
  double temperature_k;    /* water's, kelvin (293.15)                                  */
  double refractive_index; /* ARCUS_MATERIAL_FIXED                                      */
  uint32_t grid;           /* rays per side of the cast grid (1000)                     */
  double alpha;            /* the grid's warp, eq. 4.27-4.28 (0.3; 1: uniform)           */
  uint32_t max_bounces;    /* P: terms p = 0..P, p − 1 internal reflections (3; ≤ 15)   */
  int32_t edge_rays;       /* 1: grid points just outside move onto the projected edge,
                            *    found by bisection (§4.4.3.1); 0: the grid as it is   */
  double rotation[9];      /* the particle's orientation: particle → world, row-major   */
  double query_phi_deg;    /* finite: only patches reaching the half-plane of azimuth φ
                            * are kept (a table p(θ) at that φ, much faster); NaN: all  */
  arcus_progress_callback progress;
  void* progress_user;
  /* Deprecated (0.9's °C field, removed in 0.11): NaN after arcus_rainbow_params_init;
   * a finite value is used instead of temperature_k, converted (+273.15). */
  double temperature_c;
} arcus_rainbow_params;

/* wavelength 550 nm, water at 293.15 K (20 °C), grid 1000, α 0.3, P = 3, edge rays, identity
 * rotation, every azimuth. */
ARCUS_API arcus_status arcus_rainbow_params_init(arcus_rainbow_params* params);

/* Casts the grid at the particle, traces every ray through p = 0..P and builds the
 * collecting sphere's patches and their BVH: the job answers queries afterwards. */
ARCUS_API arcus_status arcus_rainbow_cast(arcus_context_t* ctx, arcus_particle_t* particle,
                                          const arcus_rainbow_params* params, arcus_job_t** job);

typedef struct arcus_rainbow_stats {
  double refractive_index;
  uint64_t rays, hits, edge_rays;
  uint64_t patches;            /* patches in the BVH                                   */
  uint64_t patches_rejected;   /* spanning more than 60°: unresolved, left out          */
  uint64_t patches_folded;     /* across a caustic (corners on two branches): left out  */
  double intercepted;          /* geometric cross-section hit by the cast [m²]          */
  double scattered[16];        /* power leaving in term p, as a fraction of intercepted */
  double remaining;            /* still inside after P (the same fraction)              */
  double cast_seconds, patch_seconds, bvh_seconds, query_seconds;
} arcus_rainbow_stats;
ARCUS_API arcus_status arcus_job_get_rainbow_stats(arcus_job_t* job, arcus_rainbow_stats* stats);

/* The phase function at `count` directions (θ_i, φ_i in degrees; phi may be NULL for
 * φ = query_phi_deg, or 0), per steradian, normalised so that the scattered light of
 * p = 0..P integrates to 1 over the sphere:
 *   parallel, perpendicular [count]  for unpolarised incident light (either may be NULL)
 *   per_bounce [count × (P+1)]       unpolarised, term p alone (may be NULL)
 * coherent = 1 adds the patches' phasors with their optical-path and focal-line phases
 * (interference, eq. 4.31), except where the two rays of one term meet at a fold caustic
 * (a rainbow angle): there their sum is the uniform (Airy) approximation of the same two
 * rays, which stays finite and peaks where the wave does; 2 adds them by eq. 4.31 alone,
 * as the thesis does (the rays' intensity then peaks at the geometric caustic); 0 adds
 * their intensities (geometric optics). */
ARCUS_API arcus_status arcus_job_get_rainbow_phase(arcus_job_t* job, size_t count, const double* theta_deg,
                                                   const double* phi_deg, int32_t coherent, double* parallel,
                                                   double* perpendicular, double* per_bounce);
/* The raw sums behind it (coherent = 1), per direction and term p: the four phasors
 * E_hθ, E_hφ, E_vθ, E_vφ (re, im) with their phases applied, summed over the patches
 * holding the direction, unnormalised [count × (P+1) × 8]. */
ARCUS_API arcus_status arcus_job_get_rainbow_phasors(arcus_job_t* job, size_t count, const double* theta_deg,
                                                     const double* phi_deg, double* phasors);

/* The glints of a flat-faced mesh (smooth = 0): in one orientation every ray of one
 * sequence of faces leaves in one direction, so the light of such a particle is a set of
 * glints rather than a phase function.  Per glint: its term p [count], its direction
 * (world, unit) [3 × count], the cast area whose rays feed it [m², count] and the power
 * it carries per unit irradiance, unpolarised [m², count].  Call with NULL arrays to
 * learn *count (0 for other particles), then with arrays of that size. */
ARCUS_API arcus_status arcus_job_get_rainbow_glints(arcus_job_t* job, size_t* count, uint32_t* terms,
                                                    double* directions, double* areas, double* cross_sections);

/* The glints of a convex flat-faced particle (arcus_particle_create_mesh with smooth = 0:
 * an ice crystal) in each of `count` orientations, traced as beams instead of a grid of
 * rays: each face the light enters is followed as a polygon and cut exactly among the
 * faces it reaches at every internal reflection, so each glint's area and power are
 * exact, not a grid's count of rays, and an orientation costs a few hundred polygon
 * clips.  rotations [count × 9]: particle → world, row-major, as
 * arcus_rainbow_params.rotation; the light travels along +z.  From params:
 * wavelength_nm, material, temperature_k, refractive_index, max_bounces and progress;
 * the grid's fields are not used.  The job answers arcus_job_get_rainbow_glints (every
 * orientation's glints, orientation by orientation) and arcus_job_get_rainbow_stats:
 * intercepted, the shadows' mean area [m²]; scattered[p] and remaining, fractions of
 * all the shadows' light; rays, the beam pieces traced; cast_seconds; the rest 0.
 * Runs on the host's cores.  count is 1 to 65536 per call; a particle that is not
 * convex is refused. */
ARCUS_API arcus_status arcus_rainbow_trace_beams(arcus_context_t* ctx, arcus_particle_t* particle,
                                                 const arcus_rainbow_params* params, size_t count,
                                                 const double* rotations, arcus_job_t** job);

/* ---- rainbow skies (thesis §4.1.4, §5.5.2) --------------------------------------- */
/* The rain's single scattering as a table: the volume scattering function
 * β(λ, φ, θ) = Σ_sizes N·C_sca·p(θ, φ) [1/(m·sr)] of the drops (or crystals) per unit
 * volume, and their extinction σ_e(λ) [1/m], in the frame of the rainbow header with the
 * light along +z and +y the world's up as seen across the light (so φ = 90° is up).
 *   theta: theta_count ≥ 2 uniform samples from theta_first to theta_last [deg]; β is 0
 *     outside them (a table of the sky behind the camera need not hold the forward peak)
 *   phi: phi_count samples at 360°·j/phi_count, periodic; 1: β does not depend on φ
 *   scattering: [wavelength_count × phi_count × theta_count], θ fastest
 *   extinction: [wavelength_count] */
typedef struct arcus_rainbow_table {
  uint32_t wavelength_count;
  const double* wavelengths_nm; /* strictly increasing */
  uint32_t theta_count;
  double theta_first_deg, theta_last_deg;
  uint32_t phi_count;
  const double* scattering;
  const double* extinction;
} arcus_rainbow_table;

/* What the camera sees: a box of rain lit by the sun, over a sky and a ground (y = 0).
 * World frame: y up, +x to the right of a camera looking along +z.  The camera sits at `camera_position` looking along
 * `camera_forward` with `camera_up` roughly up (a pinhole, horizontal field of view
 * fov_deg).  The sun is at elevation/azimuth (azimuth from +z toward +x), a disc of
 * sun_diameter_deg averaged over sun_samples points; its irradiance at each wavelength
 * [W/(m²·nm)] arrives unattenuated at the box.  Per view ray, the rain's single
 * scattering is marched (march_steps midpoints across the box, each attenuated toward
 * the camera and toward the sun by σ_e), then the sky (above the horizon: a spectrum or
 * an image) or the ground behind it, attenuated through the rain, is added. */
typedef struct arcus_rainbow_sky {
  uint32_t width, height;
  double camera_position[3], camera_forward[3], camera_up[3];
  double fov_deg;
  double sun_elevation_deg, sun_azimuth_deg, sun_diameter_deg;
  uint32_t sun_samples;
  const double* sun_irradiance; /* [wavelength_count] */
  const double* sky_radiance;   /* [wavelength_count] W/(m²·sr·nm), NULL: black */
  const double* ground_radiance;/* [wavelength_count], NULL: black */
  /* The sky as an image (NULL: sky_radiance): sky_image_width × sky_image_height linear
   * sRGB, 3 floats a pixel (finite, ≥ 0), top row first, an equirectangular panorama of
   * the whole sphere: a direction at azimuth a (from +z toward +x, as the sun's) and
   * elevation e lands at column u = a/360° and row v = (90° − e)/180°, read bilinearly
   * (wrapping in u).  So the centre column faces −z and, turning right, u grows: the
   * panorama is seen as it was taken, as the renderer's skies are.
   * Above the horizon it replaces sky_radiance: a pixel (r, g, b) times sky_image_scale
   * becomes the spectrum r·S_r(λ) + g·S_g(λ) + b·S_b(λ), three fixed smooth spectra whose
   * colours at the table's wavelengths are the sRGB primaries, so where no rain is in
   * the way the image comes out as it went in, times the scale; through rain each
   * wavelength is attenuated by its own σ_e.  Needs ≥ 3 wavelengths across 440–640 nm. */
  const float* sky_image;
  uint32_t sky_image_width, sky_image_height;
  double sky_image_scale;       /* the radiance of a pixel value of 1 [W/(m²·sr·nm)] */
  double rain_min[3], rain_max[3]; /* the box of drops [m] */
  uint32_t march_steps;
  double exposure;              /* the PNG's scale; 0: Y's 99.5th percentile → 0.9 */
  arcus_progress_callback progress;
  void* progress_user;
} arcus_rainbow_sky;

/* 320 × 240, camera at 1.7 m looking along +z, 90° field of view, sun at 10° behind the
 * camera (azimuth 180°), 0.53° wide, 16 samples, no spectra (set them), rain in
 * x ∈ [−2000, 2000], y ∈ [0, 2000], z ∈ [500, 1500] m, 32 steps, automatic exposure, no
 * sky image (scale 1). */
ARCUS_API arcus_status arcus_rainbow_sky_init(arcus_rainbow_sky* sky);
/* Renders the sky: an error (with a message) for a table or sky out of range, and for a
 * sun below the horizon (no rainbow forms from a sun that does not light the rain). */
ARCUS_API arcus_status arcus_rainbow_render(arcus_context_t* ctx, const arcus_rainbow_table* table,
                                            const arcus_rainbow_sky* sky, arcus_job_t** job);
/* The rendered image, top row first: CIE XYZ and linear sRGB (Y = 1 for a flat spectrum
 * of 1 W/(m²·sr·nm)), 3 floats a pixel each (either may be NULL); the per-pixel
 * scattering angle θ from the sun's centre [deg] (may be NULL). */
ARCUS_API arcus_status arcus_job_get_rainbow_image(arcus_job_t* job, uint32_t* width, uint32_t* height,
                                                   float* xyz, float* rgb, float* theta_deg);
/* Writes the image: EXR (R, G, B linear, X, Y, Z, theta) and/or an sRGB PNG scaled by
 * the exposure; either path may be NULL. */
ARCUS_API arcus_status arcus_job_write_rainbow_image(arcus_job_t* job, const char* exr_path, const char* png_path);

/* ---- Lorenz–Mie and the Debye series (spheres; host code, no context) ----------- */
typedef struct arcus_mie_efficiencies {
  double q_ext, q_sca, q_back, g;
} arcus_mie_efficiencies;

/* Lorenz–Mie for a sphere of `radius` metres at wavelength_nm with relative refractive
 * index n_re + i·n_im: the amplitudes S1, S2 (re, im pairs) at each θ [2 × count each,
 * either may be NULL], the phase function's parallel (|S2|²) and perpendicular (|S1|²)
 * halves for unpolarised light, whose sum integrates to 1 over the sphere [count each,
 * may be NULL], and the efficiencies (may be NULL). */
ARCUS_API arcus_status arcus_rainbow_mie(double radius, double wavelength_nm, double n_re, double n_im, size_t count,
                                         const double* theta_deg, double* s1, double* s2, double* parallel,
                                         double* perpendicular, arcus_mie_efficiencies* efficiencies);
/* The Debye-series terms p = 0..max_p of the same amplitudes [count × (max_p + 1) × 2
 * each], and each term's phase function in Mie's normalisation (parallel and
 * perpendicular, count × (max_p + 1)); p = 0 is external reflection without
 * diffraction. */
ARCUS_API arcus_status arcus_rainbow_mie_debye(double radius, double wavelength_nm, double n_re, double n_im,
                                               uint32_t max_p, size_t count, const double* theta_deg, double* s1,
                                               double* s2, double* parallel, double* perpendicular);

/* ---- spellings before arcus 0.10 (removed in 0.11; arcus_core.h, "Names") ----------- */
#ifndef ARCUS_NO_DEPRECATED
/* temperature_c in °C (the old unit); converted to kelvin. */
ARCUS_DEPRECATED("arcus_rainbow_refractive_index (temperature in kelvin)")
ARCUS_API arcus_status arcus_refractive_index(int32_t material, double wavelength_nm, double temperature_c,
                                              double* n);
ARCUS_DEPRECATED("arcus_job_get_rainbow_phase")
ARCUS_API arcus_status arcus_job_rainbow_phase(arcus_job_t* job, size_t count, const double* theta_deg,
                                               const double* phi_deg, int32_t coherent, double* parallel,
                                               double* perpendicular, double* per_bounce);
ARCUS_DEPRECATED("arcus_job_get_rainbow_phasors")
ARCUS_API arcus_status arcus_job_rainbow_phasors(arcus_job_t* job, size_t count, const double* theta_deg,
                                                 const double* phi_deg, double* phasors);
ARCUS_DEPRECATED("arcus_rainbow_mie")
ARCUS_API arcus_status arcus_mie(double radius, double wavelength_nm, double n_re, double n_im, size_t count,
                                 const double* theta_deg, double* s1, double* s2, double* parallel,
                                 double* perpendicular, arcus_mie_efficiencies* efficiencies);
ARCUS_DEPRECATED("arcus_rainbow_mie_debye")
ARCUS_API arcus_status arcus_mie_debye(double radius, double wavelength_nm, double n_re, double n_im,
                                       uint32_t max_p, size_t count, const double* theta_deg, double* s1,
                                       double* s2, double* parallel, double* perpendicular);
#endif

#ifdef __cplusplus
}
#endif
#endif /* ARCUS_RAINBOW_H */
