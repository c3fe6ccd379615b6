/*
 * arcus translucency: subsurface light transport by the dipole diffusion model (thesis
 * §3.1.4; Jensen, Marschner, Levoy & Hanrahan, SIGGRAPH 2001), its measured materials,
 * the inversion from what a photograph shows (total diffuse reflectance and diffuse
 * mean free path) to coefficients, and rendering through it (Jensen & Buhler, TOG
 * 2002).  docs/translucency.md.
 * Include arcus.h.
 *
 * Units: coefficients in mm⁻¹ and distances in mm (as the measured tables give them);
 * R_d(r) per mm²; three channels R, G, B.  η is the medium's refractive index relative
 * to its surroundings.
 *
 * Two misprints of the thesis are corrected here (docs/translucency.md says why):
 * eq. 3.7's virtual source lies at z_v = z_r(1 + 4A/3) and R_d carries no extra
 * 1/σ′_t; eq. 3.5's Henyey–Greenstein is the standard, normalised one.
 *
 * The model's calls are host code and take no context: errors go to arcus_last_error()
 * (thread-local), naming the argument.  Rendering (below) is a job on a context.
 */
#ifndef ARCUS_TRANSLUCENCY_H
#define ARCUS_TRANSLUCENCY_H

#include "arcus_core.h"
#include "arcus_scene.h"

#ifdef __cplusplus
extern "C" {
#endif

/* A homogeneous translucent medium for the dipole: per channel the absorption σ_a >= 0
 * and the reduced scattering σ_s′ = (1 − g)σ_s > 0 [mm⁻¹], and η > 0. */
typedef struct arcus_dipole {
  double sigma_a[3];
  double sigma_s_prime[3];
  double eta;
} arcus_dipole;

/* What follows from a dipole (thesis §3.1.4, corrected), per channel unless scalar. */
typedef struct arcus_dipole_terms {
  double albedo[3];            /* reduced albedo α′ = σ_s′/σ_t′                       */
  double sigma_t_prime[3];     /* σ_t′ = σ_a + σ_s′ [mm⁻¹]                            */
  double sigma_tr[3];          /* effective extinction sqrt(3σ_a σ_t′) [mm⁻¹]         */
  double diffuse_length[3];    /* ℓ_d = 1/σ_tr [mm]; infinite when σ_a = 0             */
  double z_r[3], z_v[3];       /* depths of the real and virtual sources [mm]         */
  double total_reflectance[3]; /* R_total = ∫ 2πr R_d(r) dr, in closed form           */
  int32_t diffusive[3];        /* 1 where α′ >= 0.5; below, diffusion is a poor model   */
                               /* (e.g. ketchup's G and B): warn, the numbers still hold */
  double f_dr;                 /* diffuse Fresnel reflectance inside (Egan & Hilgeman)  */
  double a;                    /* A = (1 + F_dr)/(1 − F_dr)                            */
  double exit_transmittance;   /* ∫ (1/π)F_t(η, ω_o) cos θ_o dω_o = 1 − 2·FM1, by the  */
                               /* exact Fresnel equations (0.939 at η = 1.3)           */
} arcus_dipole_terms;

ARCUS_API arcus_status arcus_translucency_dipole_get_terms(const arcus_dipole* dipole, arcus_dipole_terms* terms);

/* How a profile is stretched by a factor s > 0 (thesis §5.2's edits). */
typedef enum arcus_profile_scaling {
  ARCUS_PROFILE_SCALE_ENERGY = 0, /* R_d(r/s)/s²: the same total reflectance (default)  */
  ARCUS_PROFILE_SCALE_THESIS = 1  /* R_d(r/s), as the thesis writes it: s² times more   */
} arcus_profile_scaling;

/* R_d at `count` distances r_mm[i] >= 0 (finite) from where light enters, stretched by
 * `scale` (1: none) as `scaling` says: rd[3 i + c] per mm², channel c. */
ARCUS_API arcus_status arcus_translucency_dipole_profile(const arcus_dipole* dipole, double scale, int32_t scaling,
                                                         size_t count, const double* r_mm, double* rd);

/* Jensen et al. 2001's measured materials by name (lower case): "apple", "chicken1",
 * "chicken2", "cream", "ketchup", "marble", "potato", "skimmilk", "skin1", "skin2",
 * "spectralon", "wholemilk"; η = 1.3, marble 1.5 (data/translucency/README.md gives the
 * source).  arcus_translucency_material_name(i, &name) lists them: i from 0 until it
 * returns ARCUS_ERROR_INVALID_ARGUMENT. */
ARCUS_API arcus_status arcus_translucency_dipole_from_material(const char* name, arcus_dipole* out);
ARCUS_API arcus_status arcus_translucency_material_name(uint32_t index, const char** name);

/* The dipole with the given total diffuse reflectance 0 < R_total < 1 and diffuse mean
 * free path ℓ_d = 1/σ_tr > 0 [mm] per channel, at η (Jensen & Buhler 2002: α′ from
 * R_total by bisection, R_total rising with α′; then σ_t′ = 1/(ℓ_d sqrt(3(1 − α′)))). */
ARCUS_API arcus_status arcus_translucency_dipole_from_reflectance(const double total_reflectance[3],
                                                                  const double diffuse_length[3], double eta,
                                                                  arcus_dipole* out);

/* The Henyey–Greenstein phase function of asymmetry g (−1 < g < 1) at `count` cosines
 * of the scattering angle: (1 − g²)/(4π(1 + g² − 2g cos θ)^{3/2}) per steradian. */
ARCUS_API arcus_status arcus_translucency_henyey_greenstein(double g, size_t count, const double* cos_theta,
                                                            double* phase);

/* Unpolarised Fresnel reflectance of light arriving at cos θ = cos_i (0..1) from a
 * medium of index n1 on one of n2 (exact, 1 under total internal reflection): the
 * formulas the rainbow engine's amplitudes use (kernels/common/fresnel.h). */
ARCUS_API arcus_status arcus_translucency_fresnel_reflectance(double cos_i, double n1, double n2,
                                                              double* reflectance);


/* ---- rendering (thesis eq. 3.6–3.8; Jensen & Buhler 2002) ----------------------------
 * A closed triangle mesh of one homogeneous medium, lit by directional lights, seen by a
 * camera: irradiance E at area samples spread evenly over the surface (eq. 3.8, each
 * light through the boundary's Fresnel transmittance, shadow rays through the shared
 * BVH), then per pixel the light leaving where the camera ray meets the surface,
 *   L = (1/π) F_t(η, ω_o) Σ_i R_d(|x_o − x_i|) E_i ΔA_i          (eq. 3.6)
 * plus a Fresnel-weighted Phong highlight.  docs/translucency.md.
 *
 * Feature bits 48–55 are the translucency engine's. */
#define ARCUS_FEATURE_TRANSLUCENCY_DIPOLE (UINT64_C(1) << 48)       /* R_d as the dipole           */
#define ARCUS_FEATURE_TRANSLUCENCY_HIERARCHICAL (UINT64_C(1) << 49) /* the tree gather; else all pairs */

/* A light at infinity: `direction` points toward it (any length > 0, the mesh's frame),
 * `irradiance` (RGB, >= 0) is what it gives a surface facing it, in any unit the image
 * then shares. */
typedef struct arcus_directional_light {
  double direction[3];
  double irradiance[3];
} arcus_directional_light;

/* Eq. 3.6's exit term (1/π)F_t(η, ω_o) sends only 1 − 2·FM1 (exit_transmittance,
 * 0.939 at η = 1.3) of what reaches the boundary out of it; NORMALIZED divides by that,
 * as pbrt's separable BSSRDF does, so that a diffusing medium conserves energy. */
typedef enum arcus_exit_term { ARCUS_EXIT_THESIS = 0, ARCUS_EXIT_NORMALIZED = 1 } arcus_exit_term;

/* How the irradiance samples are gathered per pixel. */
typedef enum arcus_gather {
  ARCUS_GATHER_HIERARCHICAL = 0, /* a BVH over the samples, far nodes as one (default)  */
  ARCUS_GATHER_BRUTE_FORCE = 1   /* every sample for every pixel: the reference         */
} arcus_gather;

typedef struct arcus_translucency_render_params {
  arcus_camera camera;       /* positions in mesh units                                   */
  double ortho_height;       /* > 0: an orthographic view this tall (mesh units), rays along
                                the camera's view; 0: the pinhole camera                    */
  double mm_per_unit;        /* how long a mesh unit is, in mm (> 0)                        */
  int32_t exit;              /* arcus_exit_term                                            */
  double profile_scale;      /* §5.2's stretch of the profile (1: none) ...                 */
  int32_t profile_scaling;   /* ... as arcus_profile_scaling says                          */
  double sample_spacing_mm;  /* the samples' spacing; 0: the smallest channel's mean free
                                path 1/σ′_t, coarsened if the samples would exceed 2^22      */
  int32_t gather;            /* arcus_gather                                               */
  double max_solid_angle;    /* hierarchical: a node seen under less (its area, and 6× its
                                samples' variance, over d²; sr) is taken whole; 0 (the
                                default): 0.1 for the dipole, 0.005 for a table             */
  double highlight_deg;      /* the Phong highlight's angle b, degrees (eq. 3.3: exponent
                                −ln 2/ln cos b; reflectance F_r(η)); 0: no highlight       */
  arcus_progress_callback progress; /* called after each slice of pixels; may be NULL       */
  void* progress_user;
} arcus_translucency_render_params;

/* A tabulated profile: §5.2's blends, §3.4's fits, measured data.  R_d per mm² at
 * r_k = reach_mm · (k / (count − 1))², k = 0 .. count − 1 (dense near 0, where
 * profiles peak), linear in √r between samples, 0 beyond reach_mm. */
typedef struct arcus_profile_table {
  uint32_t count;        /* 2..65536                                                 */
  double reach_mm;       /* > 0                                                     */
  const double* values;  /* count × 3: row k is R, G, B at r_k; finite and >= 0       */
  double eta;            /* the medium's index, for the boundary's Fresnel terms (1..3) */
} arcus_profile_table;

#define ARCUS_FEATURE_TRANSLUCENCY_TABLE (UINT64_C(1) << 51) /* R_d from a table         */

/* Defaults: a 256 × 256 pinhole camera at (0, 0, 5) looking at the origin, y up, 30°;
 * 1 mm per unit, the thesis' exit term, no stretch, automatic spacing, hierarchical
 * gather at 0.005 sr, a 10° highlight (Table 3.1's b). */
ARCUS_API arcus_status arcus_translucency_render_params_init(arcus_translucency_render_params* params);

/* Renders `mesh` (closed, its triangles wound either way: the normals are turned
 * outwards by the sign of its volume) made of `dipole` under `light_count` (1..64)
 * lights.  Errors name the parameter (params->camera.width, lights[2].irradiance[1],
 * params->sample_spacing_mm when the samples would exceed 2^22, ...); a cancelled
 * render returns ARCUS_ERROR_CANCELLED with the job (pixels not reached are 0). */
ARCUS_API arcus_status arcus_translucency_render(arcus_context_t* ctx, arcus_mesh_t* mesh, const arcus_dipole* dipole,
                                                 size_t light_count, const arcus_directional_light* lights,
                                                 const arcus_translucency_render_params* params, arcus_job_t** job);

/* As arcus_translucency_render, through a tabulated profile (feature
 * TRANSLUCENCY_TABLE; the brute-force gather one point a work-item).  The automatic
 * sample spacing is 1.3 × the smallest channel's half-width (where R falls to half of
 * R(0)): the dipole's 1/σ′_t in those terms.  profile_scale stretches the table as it
 * stretches a dipole. */
ARCUS_API arcus_status arcus_translucency_render_table(arcus_context_t* ctx, arcus_mesh_t* mesh,
                                                       const arcus_profile_table* profile, size_t light_count,
                                                       const arcus_directional_light* lights,
                                                       const arcus_translucency_render_params* params,
                                                       arcus_job_t** job);

typedef struct arcus_translucency_render_stats {
  uint32_t width, height;
  uint64_t samples;            /* irradiance samples on the surface                       */
  double sample_spacing_mm;    /* their spacing, as chosen                                */
  double surface_area_mm2;     /* the mesh's area                                         */
  uint64_t covered_pixels;     /* pixels that see the mesh                                */
  uint64_t tree_nodes;         /* hierarchical: nodes of the samples' BVH (else 0)        */
  double mean_visits;          /* hierarchical: nodes visited per covered pixel            */
  double irradiance_seconds;   /* samples, their irradiance and the camera rays            */
  double gather_seconds;       /* the gather kernel (its launches' wall time)              */
} arcus_translucency_render_stats;

ARCUS_API arcus_status arcus_job_get_translucency_stats(arcus_job_t* job, arcus_translucency_render_stats* stats);
/* Linear RGB radiance, width × height × 3 floats, top row first (0 where no surface is
 * seen); any pointer may be NULL.  `subsurface` is eq. 3.6's part alone, `covered` 1
 * where the pixel sees the mesh. */
ARCUS_API arcus_status arcus_job_get_translucency_image(arcus_job_t* job, float* rgb, float* subsurface,
                                                        uint8_t* covered);


/* ---- estimation from one HDR photograph (thesis §3.3.1; Muñoz et al. 2011) -----------
 * Given a photograph of a closed mesh of one homogeneous medium, its camera and its
 * directional lights, the profile R_d as m basis functions: per pixel i of the
 * equations (the object's pixels less the highlights and the matte's rim),
 *   L_i / ((1/π) F_t(η, c·n_i)) = Σ_h w_h Σ_j [E_j ΔA_j B_h(r_ij) + E_b,j ΔA_b,j B_h(r_b,ij)]
 * over the sources j (every object pixel's front and back point, eq. 3.10–3.12), solved
 * in the least-squares sense per channel (QMR on the normal equations, Jacobi
 * preconditioned, near-empty columns dropped), then fitted by a dipole. */
#define ARCUS_FEATURE_TRANSLUCENCY_HISTOGRAM (UINT64_C(1) << 50) /* the distance histograms of eq. 3.16 */

/* The basis functions B_h of eq. 3.14 over x = r / r_max in [0, 1) (Table 3.2's
 * families), each scaled to a largest |value| of 1 (src/translucency/basis.h). */
typedef enum arcus_profile_basis {
  ARCUS_BASIS_PIECEWISE_CONSTANT = 0, /* m equal bins: the thesis' choice (default)       */
  ARCUS_BASIS_HAAR = 1,               /* the box, then Haar wavelets level by level       */
  ARCUS_BASIS_GAUSSIAN = 2,           /* zero-mean, widths geometric from r_max/m to r_max */
  ARCUS_BASIS_HERMITE = 3,            /* Hermite polynomials H_h(2x − 1)                  */
  ARCUS_BASIS_LEGENDRE = 4            /* Legendre polynomials P_h(2x − 1)                 */
} arcus_profile_basis;

/* What the dipole is fitted to, per channel, by Levenberg–Marquardt (src/translucency/fit.h). */
typedef enum arcus_profile_fit {
  ARCUS_FIT_IMAGE = 0,  /* the pixels it predicts through the cached histograms (default)  */
  ARCUS_FIT_PROFILE = 1 /* the piecewise-constant profile's bins, as the thesis does        */
} arcus_profile_fit;

typedef struct arcus_translucency_estimate_params {
  arcus_camera camera;       /* as for a render: mesh units; the photo's size is its own */
  double ortho_height;       /* > 0: orthographic (the thesis' photographs); 0: pinhole   */
  double mm_per_unit;        /* > 0                                                     */
  double eta;                /* the medium's assumed index (1.3, as the thesis)           */
  int32_t exit;              /* arcus_exit_term the photo is taken to follow (THESIS)      */
  uint32_t basis_count;      /* m, 2..64 (24)                                            */
  int32_t basis;             /* arcus_profile_basis                                     */
  double r_max_mm;           /* the profile's reach; 0: the object's bounding diagonal     */
  uint32_t max_side;         /* the photo is box-filtered down by whole factors until its
                                longer side is at most this (200, as the thesis)          */
  int32_t remove_highlights; /* 1: drop pixels above the histogram's cut (default 1)      */
  int32_t subtract_minimum;  /* 1: subtract the darkest object pixel from all (default 1) */
  int32_t fit;               /* arcus_profile_fit                                        */
  arcus_progress_callback progress; /* after each slice of the histograms; may be NULL   */
  void* progress_user;
  double tikhonov;           /* λ >= 0: adds λ × the mean diagonal of AᵀA to its diagonal
                                (0: off, as the thesis)                                  */
  int32_t nonnegative;       /* 1: weights >= 0 (Lawson–Hanson over QMR; 0: off, as the thesis) */
} arcus_translucency_estimate_params;

/* Defaults: the render defaults' camera, 1 mm per unit, η 1.3, 24 piecewise-constant
 * functions up to the object's diagonal, 200 pixels a side, highlights removed and the
 * minimum subtracted (§3.3.1). */
ARCUS_API arcus_status arcus_translucency_estimate_params_init(arcus_translucency_estimate_params* params);

/* Estimates from `photo` (width × height × 3 floats, linear RGB radiance, top row first:
 * an HDR photograph's pixels) of `mesh` under `lights`; `matte` (width × height bytes,
 * non-zero: the object) may be NULL, when the mesh's projection is the matte.  Refused,
 * naming the reason: a NaN, infinite or negative pixel; an object whose pixels have no
 * light; a matte that covers no pixel of the mesh. */
ARCUS_API arcus_status arcus_translucency_estimate(arcus_context_t* ctx, arcus_mesh_t* mesh, uint32_t width,
                                                   uint32_t height, const float* photo, const uint8_t* matte,
                                                   size_t light_count, const arcus_directional_light* lights,
                                                   const arcus_translucency_estimate_params* params,
                                                   arcus_job_t** job);

typedef struct arcus_translucency_estimate_result {
  uint32_t width, height;        /* the downscaled photo's size                            */
  uint32_t object_pixels;        /* |𝕆|: sources                                          */
  uint32_t equation_pixels;      /* |𝕀|: equations                                        */
  double highlight_cut;          /* the luminance above which pixels were dropped (inf: none) */
  double minimum_subtracted[3];  /* what was subtracted (0 when not asked)                */
  double r_max_mm;               /* the profile's reach                                   */
  uint32_t basis_count;
  arcus_dipole dipole;           /* the dipole fitted to the profile                      */
  arcus_dipole_terms terms;      /* and what follows from it                              */
  int32_t iterations[3];         /* QMR, per channel                                     */
  double residual[3];            /* QMR's relative residual of the normal equations       */
  double condition_a[3];         /* 2-norm condition number of A's kept columns           */
  double condition_normal[3];    /* of AᵀA                                                */
  uint32_t dropped_columns[3];   /* columns left out as near-empty                         */
  double fit_error[3];           /* the fit's RMS residual over the data's RMS              */
  double geometry_seconds;       /* camera rays, back points, irradiance maps             */
  double histogram_seconds;      /* the kernel of eq. 3.16                                 */
  double solve_seconds;          /* normal equations, QMR, condition numbers, the fit      */
  int32_t basis;                 /* arcus_profile_basis                                     */
  double near_radius_mm;         /* ρ: within it a row's own irradiance over a flat disc
                                    stands for the sources (docs/translucency.md)           */
  double image_error[3];         /* Σ|A x − b| / Σ b: the solve's re-render of the equation
                                    pixels against them (Table 3.2's "error")              */
  double refined_radius_mm;      /* from ρ to this, the front sources are counted by their
                                    sub-pixels (arcus_job_get_translucency_sub_sources)    */
  uint32_t sub_source_count;     /* how many sub-pixel points                               */
} arcus_translucency_estimate_result;

ARCUS_API arcus_status arcus_job_get_translucency_estimate(arcus_job_t* job,
                                                           arcus_translucency_estimate_result* result);
/* The estimated profile: edges (basis_count + 1 distances, mm) and weights (basis_count
 * × 3: R_d per mm², Σ_h w_h B_h averaged over each bin's area, per channel); either
 * pointer may be NULL. */
ARCUS_API arcus_status arcus_job_get_translucency_profile(arcus_job_t* job, double* edges, double* weights);
/* §3.4's plausible profile fitted to the estimate (src/translucency/hermite.h): the
 * bins made non-increasing (area-weighted, energy kept) and >= 0, a monotone cubic
 * Hermite curve through them, scaled to their ∫2πr R dr.  `values`: count (2..65536) × 3,
 * R per mm² at r_k = r_max_mm (k / (count − 1))² — an arcus_profile_table with reach
 * r_max_mm and the estimate's η, for arcus_translucency_render_table. */
ARCUS_API arcus_status arcus_job_get_translucency_hermite(arcus_job_t* job, uint32_t count, double* values);
/* One channel's linear system (eq. 3.16–3.18), for checking it: `a` equation_pixels ×
 * basis_count (row-major, per mm²), `b` equation_pixels (the pixels over the exit term),
 * `x` basis_count (the weights solved for); any pointer may be NULL. */
ARCUS_API arcus_status arcus_job_get_translucency_system(arcus_job_t* job, uint32_t channel, double* a, double* b,
                                                         double* x);
/* What the system is assembled from, in mm: `rows` equation_pixels × 3 (the equation
 * pixels' front points), `sources` 2·object_pixels × 3 (every object pixel's front point,
 * then its back point), `source_weights` 2·object_pixels × 3 (E·ΔA, per channel),
 * `near_irradiance` equation_pixels × 3 (E_i, the disc within near_radius_mm); any
 * pointer may be NULL. */
ARCUS_API arcus_status arcus_job_get_translucency_sources(arcus_job_t* job, double* rows, double* sources,
                                                          double* source_weights, double* near_irradiance);
/* The front sources' sub-pixel points, for checking: `points` and `weights` (E·ΔA per
 * channel) sub_source_count × 3 each.  Between near_radius_mm and refined_radius_mm of a
 * row, the system counts these and the back points; beyond, every source; either
 * pointer may be NULL. */
ARCUS_API arcus_status arcus_job_get_translucency_sub_sources(arcus_job_t* job, double* points, double* weights);

/* ---- light directions from the photograph alone (thesis §3.4; Lopez-Moreno et al. 2009)
 * For an uncontrolled photograph, neither lights nor shape known.  The object is the
 * matte's pixels, or else segmented from the photo (the object brighter than its
 * background, which the photo's frame shows: above the frame's levels, the largest
 * region, its small holes filled).
 * At its contour the surface faces across the view, so the contour's luminance against
 * its normals' image-plane azimuths shows the lights: k-means on the luminance-weighted
 * normals gives each light's azimuth θ, and the number of lights is the fewest whose
 * clamped-cosine model explains the contour (docs/translucency.md).  Each light's zenith
 * φ is then fitted to the luminance gradients inside the object, with the normals of a
 * globally convex stand-in inflated from the contour (Johnston 2002).  A photo larger
 * than 512 pixels a side is box-filtered by a whole factor first.
 * Angles in the camera's frame: x right, y up, z toward the camera. */
#define ARCUS_MAX_DETECTED_LIGHTS 4

typedef struct arcus_detected_light {
  double azimuth_deg;        /* θ: in the image plane, counter-clockwise from +x, 0..360      */
  double zenith_deg;         /* φ: from the camera's axis, 0 (from the camera's side) .. 90 (in the
                                image plane)                                                 */
  double direction[3];       /* the unit vector toward the light, (sinφ cosθ, sinφ sinθ, cosφ) */
  double intensity;          /* relative: the lights' intensities sum to 1                   */
  double azimuth_spread_deg; /* the angles whose fit's misfit stays within 5% of the best's:  */
  double zenith_spread_deg;  /* half their range, an uncertainty from the data alone (the
                                stand-in shape's own error is not in it)                     */
} arcus_detected_light;

typedef struct arcus_light_detection {
  uint32_t count;            /* lights found, 1..ARCUS_MAX_DETECTED_LIGHTS                  */
  arcus_detected_light lights[ARCUS_MAX_DETECTED_LIGHTS]; /* strongest first               */
  uint32_t object_pixels;    /* the object's pixels                                        */
  uint32_t contour_pixels;   /* its outer contour's                                        */
  int32_t segmented;         /* 1: segmented from the photo; 0: the matte's                */
  double contour_misfit;     /* the contour model's RMS residual over the contour's RMS     */
  double seconds;
} arcus_light_detection;

/* Finds the lights of `photo` (width × height × 3 floats, linear RGB radiance, top row
 * first); `matte` (width × height bytes, non-zero: the object) may be NULL.  Refused,
 * naming the reason: a NaN, infinite or negative pixel; no object; an object touching the
 * photo's border (its contour is cut); more than ARCUS_MAX_DETECTED_LIGHTS lights. */
ARCUS_API arcus_status arcus_translucency_detect_lights(arcus_context_t* ctx, uint32_t width, uint32_t height,
                                                        const float* photo, const uint8_t* matte,
                                                        arcus_light_detection* result);

/* ---- shape from the photograph alone (thesis §3.4; Khan et al. 2006) -----------------
 * A depth map Z of the object (the same object as arcus_translucency_detect_lights finds)
 * as base_weight × a base layer + detail_weight × a detail layer:
 *   base:   global convexity.  The contour at Z = 0 and a sphere's profile from the
 *           distance d to it, R·sqrt(1 − (1 − d/R)²) (R: the largest d), scaled by the
 *           bilateral-filtered luminance B through the "inflation" spline, a monotone
 *           cubic from 1 − inflation at B = 0 to 1 at B = 1 ("dark is deep");
 *   detail: the filter's high-frequency residual, (luminance − B) · R;
 * the luminance over the object's 99th percentile.  The bilateral filter's spatial σ is
 * sigma_spatial × the object's diameter and its range σ is sigma_intensity (§3.4: 0.08–0.1
 * and 0.3–0.5).  The bas-relief ambiguity leaves Z's scale unknown: `relief` multiplies
 * it (1: a sphere's depth for a round object).  ARCUS_DEPTH_LUMINANCE is the simplest
 * method, Z = R × luminance (Fig. 3.9's "simplest", for comparison).  Normals from Z's
 * central differences.  Like the lights, it works at most 512 pixels a side (a larger
 * photo box-filtered by a whole factor) and is read back at the photo's size, depth in
 * the photo's pixels.  docs/translucency-photo.md. */
typedef enum arcus_depth_method {
  ARCUS_DEPTH_BASE_DETAIL = 0, /* base and detail layers (the thesis' choice; default)        */
  ARCUS_DEPTH_BASE = 1,        /* the base layer alone                                          */
  ARCUS_DEPTH_LUMINANCE = 2    /* the luminance as depth                                        */
} arcus_depth_method;

typedef struct arcus_photo_shape_params {
  int32_t method;          /* arcus_depth_method                                               */
  double sigma_spatial;    /* the bilateral filter's spatial σ over the object's diameter (0.09) */
  double sigma_intensity;  /* its range σ, luminance over its 99th percentile (0.4)              */
  double base_weight;      /* (0.8)                                                             */
  double detail_weight;    /* (0.2)                                                             */
  double inflation;        /* the spline's drop at B = 0, 0..1 (0: off; Khan et al.'s is ~0.3)  */
  double relief;           /* Z's scale, the bas-relief parameter, > 0 (1)                      */
} arcus_photo_shape_params;

ARCUS_API arcus_status arcus_translucency_photo_shape_params_init(arcus_photo_shape_params* params);

/* The object's depth (width × height doubles, pixels toward the camera, 0 outside it) and
 * normals (width × height × 3, unit, the camera's frame; 0 outside); `matte` may be NULL
 * (the object segmented as for the lights); `mask` (width × height bytes, 1: the object)
 * may be NULL.  Refused as arcus_translucency_detect_lights refuses, and for parameters
 * out of range, naming them. */
ARCUS_API arcus_status arcus_translucency_estimate_shape(arcus_context_t* ctx, uint32_t width, uint32_t height,
                                                         const float* photo, const uint8_t* matte,
                                                         const arcus_photo_shape_params* params, double* depth,
                                                         double* normals, uint8_t* mask);

/* ---- the BSSRDF from an uncontrolled photograph (thesis §3.4, §5.2) -------------------
 * No mesh and no lights: the lights (arcus_translucency_detect_lights) and the depth
 * (arcus_translucency_estimate_shape) from the photo, a closed mesh from the depth (the
 * back mirrors the front, as §3.4 assumes; a unit per pixel), then
 * arcus_translucency_estimate on it, seen orthographically pixel for pixel: the dipole,
 * flagged approximate, and §3.4's plausible Hermite profile
 * (arcus_job_get_translucency_hermite).  The photo does not give the lights' absolute
 * irradiance, which the profile's scale shares with it (an albedo–light ambiguity):
 * `irradiance` states it. */
typedef struct arcus_translucency_auto_params {
  arcus_translucency_estimate_params estimate; /* its camera, ortho_height and mm_per_unit
                                                  are the pipeline's own and not read;
                                                  by default here nonnegative is 1 and
                                                  remove_highlights 0 (docs say why)       */
  arcus_photo_shape_params shape;
  double mm_per_pixel;   /* the photo's scale at the object, mm (> 0; 1)                   */
  double irradiance[3];  /* the lights' summed irradiance on a surface facing them, RGB, in
                            the photo's units (>= 0, not all 0; 1, 1, 1)                  */
} arcus_translucency_auto_params;

ARCUS_API arcus_status arcus_translucency_auto_params_init(arcus_translucency_auto_params* params);

/* Estimates from `photo` alone (as arcus_translucency_estimate; `matte` may be NULL: the
 * object segmented).  The job holds the estimate (arcus_job_get_translucency_estimate and
 * the rest) and what the photo gave (arcus_job_get_translucency_auto). */
ARCUS_API arcus_status arcus_translucency_estimate_auto(arcus_context_t* ctx, uint32_t width, uint32_t height,
                                                        const float* photo, const uint8_t* matte,
                                                        const arcus_translucency_auto_params* params,
                                                        arcus_job_t** job);

/* What an automatic estimate found: `lights`, `depth` and `normals` (as
 * arcus_translucency_estimate_shape), `mask` (1: the object the mesh covers), the mesh's
 * counts and arrays (`positions` vertex_count × 3 in pixels, `triangles` triangle_count ×
 * 3); any pointer may be NULL (the counts first, then arrays that long). */
ARCUS_API arcus_status arcus_job_get_translucency_auto(arcus_job_t* job, arcus_light_detection* lights,
                                                       double* depth, double* normals, uint8_t* mask,
                                                       size_t* vertex_count, size_t* triangle_count,
                                                       double* positions, uint32_t* triangles);

/* ---- genetic inverse rendering (thesis §3.2, §5.1) ------------------------------------
 * The genes of a model whose render best matches a target image of a known mesh under
 * known directional lights and camera: per-pixel least squares in YCbCr (the thesis'
 * main text) or RGB (its footnote), as the relative RMS difference over the object's
 * pixels.  Each individual is a matrix–vector product over a cache of what does not
 * depend on the genes (src/translucency/appearance.h), not a render.  The same
 * parameters, seed and device give the same history bit for bit. */
typedef enum arcus_genetic_model {
  ARCUS_GENETIC_DIPOLE = 0, /* nine genes: σ_a R G B, σ_s R G B (mm⁻¹), g, η, b (degrees):
                               the renderer's dipole with its Fresnel-weighted highlight  */
  ARCUS_GENETIC_PHONG = 1   /* five genes: k_d R G B, k_s, b (degrees): eq. 3.2–3.3, opaque */
} arcus_genetic_model;

typedef enum arcus_fitness_space { ARCUS_FITNESS_YCBCR = 0, ARCUS_FITNESS_RGB = 1 } arcus_fitness_space;

#define ARCUS_GENETIC_MAX_GENES 9

/* After each generation (0: the seeded population) with the best individual so far; a
 * non-zero return stops the search (ARCUS_ERROR_CANCELLED, the history so far kept). */
typedef int32_t (*arcus_generation_callback)(void* user, uint32_t generation, double best_fitness,
                                             const double* best_genes);

typedef struct arcus_genetic_params {
  arcus_camera camera;       /* as for a render; the target's size is its own          */
  double ortho_height;       /* > 0: orthographic; 0: pinhole                            */
  double mm_per_unit;        /* > 0                                                     */
  int32_t model;             /* arcus_genetic_model                                      */
  uint32_t population;       /* 2..10000 (40, §5.1)                                      */
  uint32_t generations;      /* 0..100000 (50, §5.1)                                     */
  double replacement;        /* the fraction replaced each generation, the best kept (0.8) */
  double crossover;          /* the probability a child is a one-point crossover (0.8)    */
  double mutation;           /* the probability each gene of a child mutates (0.8)        */
  double mutation_range;     /* ± this × max(|x|, 10% of the gene's range) at most (0.3)   */
  double fitness_threshold;  /* stop once the best fitness is at most this (0: never)      */
  int32_t fitness_space;     /* arcus_fitness_space (YCBCR)                               */
  uint64_t seed;
  double initial[ARCUS_GENETIC_MAX_GENES]; /* the seeded individual (Table 3.1)            */
  double lower[ARCUS_GENETIC_MAX_GENES];   /* bounds per gene                             */
  double upper[ARCUS_GENETIC_MAX_GENES];
  arcus_progress_callback progress;        /* the cache's slices, then the generations    */
  void* progress_user;
  arcus_generation_callback on_generation; /* may be NULL                                 */
  void* generation_user;
  uint32_t polish_steps;     /* then at most this many Levenberg–Marquardt steps through the
                                same cache from each of the last population's 4 best, the best
                                kept: the dipole in σ_a, σ′_s, η, b (g held), in ln of the genes
                                bounded above 0 (20; 0: the thesis' search alone); 0..1000    */
} arcus_genetic_params;

/* Defaults for `model`: Table 3.1's initial genes (dipole: σ_a = σ_s = 1, g = 0, η = 1.3,
 * b = 10°; Phong: k_d = 0.5, k_s = 0.5, b = 10°), bounds (dipole: σ_a [1e-4, 5], σ_s
 * [0.01, 10], g [−0.9, 0.95], η [1.05, 2], b [1, 45]; Phong: k_d, k_s [0, 1], b [1, 45]),
 * §5.1's 40 individuals, 50 generations, 0.8 / 0.8 / 0.8, ±30%, YCbCr, seed 0, the
 * render defaults' camera, 1 mm per unit, 20 polish steps. */
ARCUS_API arcus_status arcus_translucency_genetic_params_init(int32_t model, arcus_genetic_params* params);

/* Searches for the genes whose render of `mesh` under `lights` best matches `target`
 * (width × height × 3 floats, linear RGB radiance, top row first; its pixels where the
 * mesh is seen are compared). */
ARCUS_API arcus_status arcus_translucency_genetic(arcus_context_t* ctx, arcus_mesh_t* mesh, uint32_t width,
                                                  uint32_t height, const float* target, size_t light_count,
                                                  const arcus_directional_light* lights,
                                                  const arcus_genetic_params* params, arcus_job_t** job);

typedef struct arcus_genetic_result {
  int32_t model;
  uint32_t gene_count;
  uint32_t generations_run;
  uint64_t evaluations;                  /* individuals whose fitness was computed        */
  double best[ARCUS_GENETIC_MAX_GENES];  /* the best genes                                */
  double best_fitness;                   /* their relative RMS difference from the target  */
  double sigma_s_prime[3];               /* dipole: (1 − g)σ_s, what multiple scattering sees:
                                            σ_s and g alone are not identifiable          */
  uint32_t pixels;                       /* the target's pixels compared                  */
  uint64_t samples;                      /* the cache's irradiance samples                */
  double cache_seconds;                  /* the cache (geometry, irradiance, histograms)  */
  double search_seconds;                 /* the generations                              */
  double search_fitness;                 /* the search's best, before the polish          */
  uint32_t polish_steps;                 /* the kept polish's accepted steps              */
  uint64_t polish_evaluations;           /* the images the polishes computed              */
  double polish_seconds;
} arcus_genetic_result;

ARCUS_API arcus_status arcus_job_get_translucency_genetic(arcus_job_t* job, arcus_genetic_result* result);
/* Per generation run (generations_run + 1 values, the first the seeded population):
 * the best and mean fitness and the best genes (gene_count each); any pointer may be NULL. */
ARCUS_API arcus_status arcus_job_get_translucency_genetic_history(arcus_job_t* job, double* best_fitness,
                                                                  double* mean_fitness, double* best_genes);
/* The best individual's image through the cache (width × height × 3 floats; 0 where the
 * mesh is not seen). */
ARCUS_API arcus_status arcus_job_get_translucency_genetic_image(arcus_job_t* job, float* rgb);

#ifdef __cplusplus
}
#endif
#endif /* ARCUS_TRANSLUCENCY_H */
