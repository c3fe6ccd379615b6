/*
 * arcus underwater light (thesis §2.4.3, §3.5, §4.2, §5.3): water described by the
 * bio-optical model (chlorophyll, minerals and detritus, CDOM, pure water with Raman
 * scattering and two fluorescences) or by its inherent optical properties, and
 * spectral photon tracing through it with the thesis' Russian roulette over ten event
 * types, tallies of where the energy went, irradiance profiles of a plane-parallel
 * column, and the scattered photons for a photon map.  Include arcus.h.
 *
 * Units: metres, nanometres, watts.  Coordinates: z up; a plane-parallel column's
 * surface is z = 0 with water below.
 */
#ifndef ARCUS_OCEAN_H
#define ARCUS_OCEAN_H

#include "arcus_core.h"
#include "arcus_scene.h"

#ifdef __cplusplus
extern "C" {
#endif

/* Kernel features of ocean jobs: bits 32-39 of arcus_features.  A water without
 * inelastic constituents compiles no inelastic code, an unbounded medium no boundary
 * tests, a trace without depths no irradiance tallies. */
#define ARCUS_FEATURE_OCEAN_INELASTIC (UINT64_C(1) << 32) /* Raman and fluorescence re-emission */
#define ARCUS_FEATURE_OCEAN_BOUNDARIES (UINT64_C(1) << 33) /* surface, bottom, box */
#define ARCUS_FEATURE_OCEAN_DEPTHS (UINT64_C(1) << 34)     /* irradiance tallies at depths */
#define ARCUS_FEATURE_OCEAN_PHOTON_MAP (UINT64_C(1) << 35) /* images: multiple scattering from the map */
#define ARCUS_FEATURE_OCEAN_BEAM (UINT64_C(1) << 36)       /* images: the beam radiance estimate */

/* The ten events of the thesis' roulette (§4.2), in its order. */
#define ARCUS_OCEAN_EVENT_COUNT 10
typedef enum arcus_ocean_event {
  ARCUS_EVENT_ABSORB_WATER = 0,
  ARCUS_EVENT_RAMAN = 1,
  ARCUS_EVENT_ABSORB_DETRITUS = 2, /* minerals and detritus */
  ARCUS_EVENT_ABSORB_PHYTO = 3,
  ARCUS_EVENT_FLUORESCE_PHYTO = 4,
  ARCUS_EVENT_ABSORB_CDOM = 5,
  ARCUS_EVENT_FLUORESCE_CDOM = 6,
  ARCUS_EVENT_SCATTER_WATER = 7,
  ARCUS_EVENT_SCATTER_DETRITUS = 8,
  ARCUS_EVENT_SCATTER_PHYTO = 9
} arcus_ocean_event;

/* A uniform wavelength grid: first_nm + k·step_nm, k < count (300-1000 nm). */
typedef struct arcus_wavelength_grid {
  double first_nm, step_nm;
  uint32_t count;
} arcus_wavelength_grid;

/* A spectrum: count strictly increasing wavelengths and values (one entry: a constant). */
typedef struct arcus_spectrum {
  uint32_t count;
  const double* nm;
  const double* values;
} arcus_spectrum;

typedef enum arcus_phase_kind {
  ARCUS_PHASE_ISOTROPIC = 0,
  ARCUS_PHASE_RAYLEIGH_LIKE = 1, /* ∝ 1 + a cos²θ (pure water: a = 0.835, thesis eq. 3.26) */
  ARCUS_PHASE_HG = 2,            /* Henyey–Greenstein, g_forward                         */
  ARCUS_PHASE_TWO_TERM_HG = 3,   /* ζ HG(g_forward) + (1 − ζ) HG(g_backward) (eq. 3.28)   */
  ARCUS_PHASE_TABLE = 4          /* values at cosines spanning [−1, 1], linear between   */
} arcus_phase_kind;

typedef struct arcus_phase_function {
  int32_t kind; /* arcus_phase_kind */
  double a, g_forward, g_backward, forward_weight;
  uint32_t table_count;
  const double* table_cosines;
  const double* table_values;
} arcus_phase_function;

/* ---- water ----------------------------------------------------------------------- */
typedef struct arcus_water_s arcus_water_t;

/* The bio-optical model (thesis §3.5, Table 4.3); data/ocean/README.md gives every
 * value's source. */
typedef struct arcus_bio_optical {
  double chlorophyll;        /* C [mg/m³]                                          */
  double a_d400;             /* minerals and detritus absorption at 400 nm [1/m]   */
  double a_y440;             /* CDOM absorption at 440 nm [1/m]                    */
  double s_d, s_y;           /* their spectral slopes [1/nm]                       */
  double chlorophyll_yield;  /* Γ_p                                                */
  double cdom_yield_scale;   /* × Hawes' A0 (0: no CDOM fluorescence)              */
  double raman_scale;        /* × the Raman coefficient (0: no Raman)              */
  double detritus_scattering_reference_a_d400;
  arcus_phase_function detritus_phase;
  int32_t stokes_only;       /* 1: inelastic re-emission only toward longer
                              * wavelengths, no anti-Stokes (the thesis' Fig. 5.11
                              * ablation); 0: both ways (default)                  */
} arcus_bio_optical;

/* The thesis' values. */
ARCUS_API arcus_status arcus_bio_optical_init(arcus_bio_optical* bio);
/* A named preset: "atlantic", "mediterranean", "baltic", "north_sea", "cdom_coastal". */
ARCUS_API arcus_status arcus_bio_optical_preset(const char* name, arcus_bio_optical* bio);

/* Water by its inherent optical properties, optionally with inelastic constituents. */
typedef struct arcus_water_iops {
  arcus_spectrum absorption, scattering; /* [1/m] */
  arcus_phase_function phase;
  int32_t raman;                         /* 1: Raman by the water (taken out of absorption) */
  double chlorophyll, chlorophyll_yield; /* adds phytoplankton absorption and fluorescence  */
  double a_y440, s_y;                    /* adds CDOM absorption and fluorescence           */
  int32_t stokes_only;                   /* as in arcus_bio_optical                         */
} arcus_water_iops;

ARCUS_API arcus_status arcus_water_create(arcus_context_t* ctx, const arcus_bio_optical* bio, arcus_water_t** out);
ARCUS_API arcus_status arcus_water_create_iops(arcus_context_t* ctx, const arcus_water_iops* iops,
                                               arcus_water_t** out);
ARCUS_API arcus_status arcus_water_retain(arcus_water_t* water);
ARCUS_API arcus_status arcus_water_release(arcus_water_t* water);

/* The water on a grid (any pointer may be NULL): the coefficient of each event
 * [ARCUS_OCEAN_EVENT_COUNT × count, 1/m], and per constituent (water, minerals and
 * detritus, phytoplankton, CDOM) the whole absorption and scattering [4 × count]. */
ARCUS_API arcus_status arcus_water_get_coefficients(arcus_water_t* water, const arcus_wavelength_grid* grid,
                                                    double* events, double* absorption, double* scattering);

/* ---- photon tracing -------------------------------------------------------------- */
typedef enum arcus_ocean_light_kind {
  ARCUS_OCEAN_LIGHT_POINT = 0,       /* isotropic; spectrum in W/nm                        */
  ARCUS_OCEAN_LIGHT_SPOT = 1,        /* uniform within half_angle_deg of direction; W/nm    */
  ARCUS_OCEAN_LIGHT_DIRECTIONAL = 2, /* a parallel beam along direction; W/m²/nm over a disc
                                      * of `radius` about position, or (surface) per m² of
                                      * the surface                                        */
  ARCUS_OCEAN_LIGHT_SKY = 3          /* uniform sky radiance onto the surface; W/m²/nm      */
} arcus_ocean_light_kind;

typedef struct arcus_ocean_light {
  int32_t kind;
  double position[3];
  double direction[3];
  double half_angle_deg;
  double radius;
  arcus_spectrum spectrum;
} arcus_ocean_light;

typedef struct arcus_ocean_setup {
  arcus_wavelength_grid grid;
  uint32_t light_count;
  const arcus_ocean_light* lights;
  int32_t surface;                  /* 1: flat air–water surface at z = 0 (Fresnel), water below */
  double n_water;                   /* its refractive index (1.34)                               */
  double bottom_depth;              /* a Lambertian bottom at z = −depth; +inf: none             */
  double bottom_albedo;
  double box_lo[3], box_hi[3];      /* photons leaving the box escape; ±inf: unbounded           */
  uint32_t depth_count;             /* irradiance tallies at these depths (m, ≥ 0)               */
  const double* depths;
  double layer;                     /* the scalar irradiance's track-length layer [m]            */
} arcus_ocean_setup;

typedef struct arcus_ocean_trace_params {
  uint64_t photons;
  uint32_t max_interactions; /* 1..100000; the thesis: 5 (images)        */
  uint64_t seed;
  int32_t store_photons;     /* 1: keep scattered photons (photon map)   */
  int32_t force_inelastic;   /* 1: compile the inelastic code anyway     */
  /* Wavelengths each stored photon carries, 1..4 (4): hero-wavelength sampling, the
   * largest divisor of the grid's sample count not above this (81 samples: 3);
   * 1: the thesis' one wavelength per photon.  The tallies follow the hero alone. */
  uint32_t wavelengths_per_photon;
  arcus_progress_callback progress;
  void* progress_user;
} arcus_ocean_trace_params;

/* Grid 380-780 nm at 5 nm, no lights, unbounded water, n 1.34; 400 000 photons, 5
 * interactions, seed 1, 4 wavelengths per photon. */
ARCUS_API arcus_status arcus_ocean_setup_init(arcus_ocean_setup* setup);
ARCUS_API arcus_status arcus_ocean_trace_params_init(arcus_ocean_trace_params* params);

ARCUS_API arcus_status arcus_ocean_trace(arcus_context_t* ctx, arcus_water_t* water, const arcus_ocean_setup* setup,
                                         const arcus_ocean_trace_params* params, arcus_job_t** job);

/* Where the energy went [W]: emitted = Σ absorbed + Σ escaped + past_limit + bottom. */
typedef struct arcus_ocean_tallies {
  uint64_t photons, interactions, stored;
  double emitted, past_limit, bottom, escaped, absorbed;
  double count[ARCUS_OCEAN_EVENT_COUNT];    /* events of each kind                       */
  double arriving[ARCUS_OCEAN_EVENT_COUNT]; /* power arriving at them                   */
  double absorbed_by[ARCUS_OCEAN_EVENT_COUNT]; /* power each kept (inelastic: the energy
                                             * difference, negative for anti-Stokes)    */
  uint32_t max_interactions;
  uint32_t interaction_bins;
} arcus_ocean_tallies;
ARCUS_API arcus_status arcus_job_get_ocean_tallies(arcus_job_t* job, arcus_ocean_tallies* tallies);
/* Per interaction number j = 0..interaction_bins: absorbed at the j-th interaction,
 * escaped after j interactions (thesis Fig. 5.9); arrays of interaction_bins + 1,
 * interaction_bins = min(max_interactions, 64), the last entry also holding every
 * later interaction. */
ARCUS_API arcus_status arcus_job_get_ocean_by_interaction(arcus_job_t* job, double* absorbed, double* escaped);
/* Irradiances at the setup's depths per grid sample [W/m²/nm], depth-major
 * (depth_count × count): downward and upward plane irradiance, scalar irradiance. */
ARCUS_API arcus_status arcus_job_get_ocean_irradiance(arcus_job_t* job, double* ed, double* eu, double* e0);
/* The stored photons: *count, then (any pointer may be NULL) positions (× 3), the
 * directions they arrived along (× 3), powers [W], wavelengths [nm], events.  A photon
 * carrying several wavelengths is listed once per wavelength, at the same place. */
ARCUS_API arcus_status arcus_job_get_ocean_photons(arcus_job_t* job, size_t* count, double* positions,
                                                   double* directions, double* powers, double* wavelengths,
                                                   int32_t* events);

/* ---- images ---------------------------------------------------------------------
 * Camera rays marched through the water (thesis §4.1.4, §4.2): single scattering from
 * the lights (elastic and inelastic, eq. 4.5) and multiple scattering from a photon map
 * of the photons stored from their second interaction on (eq. 4.6), per grid sample,
 * then CIE 1931 XYZ and linear sRGB.  Point and spot lamps in the water; the sun and
 * the sky over a flat surface (setup.surface), which reflects the rays reaching it by
 * Fresnel's R, wholly outside Snell's window. */
#define ARCUS_OCEAN_ESTIMATE_PER_STEP 0 /* the thesis': k nearest photons at each step */
#define ARCUS_OCEAN_ESTIMATE_BEAM 1     /* Jarosz, Zwicker & Jensen 2008: photons along the ray */

typedef struct arcus_ocean_march {
  uint32_t steps;             /* 200 */
  double distance;            /* how far rays are marched [m]: 20 */
  uint32_t k;                 /* photons per estimate: 250 (per step ≤ 512; beam: each
                               * photon's radius holds k, ≤ 65536) */
  int32_t estimator;          /* ARCUS_OCEAN_ESTIMATE_* */
  int32_t single_scattering;  /* 1 */
  int32_t multiple_scattering;/* 1 (0: no photons are traced) */
  double exposure;            /* PNG: linear sRGB × exposure: 1 */
  uint32_t estimate_stride;   /* the photon estimate at every n-th pixel across and down,
                               * bilinear between: 1 (every pixel, the thesis'), ≤ 64 */
  double photon_tile;         /* > 0 [m]: lit only by the sun and the sky over a surface, the
                               * scene is the same at every horizontal place: its photons
                               * enter through one square tile this wide about the camera,
                               * standing for every copy of it (beam estimate only).
                               * 0 (default): through the lights' discs */
  uint32_t step_subsample;    /* m: the per-step estimate at one step of every m, jittered
                               * per pixel and weighted by m: unbiased, m× fewer searches,
                               * noisier.  1 (default): every step, the thesis' */
} arcus_ocean_march;
ARCUS_API arcus_status arcus_ocean_march_init(arcus_ocean_march* march);

/* Renders an image (params: the photon trace's; setup: its grid, lights, medium). */
ARCUS_API arcus_status arcus_ocean_render(arcus_context_t* ctx, arcus_water_t* water, const arcus_ocean_setup* setup,
                                          const arcus_ocean_trace_params* params, const arcus_camera* camera,
                                          const arcus_ocean_march* march, arcus_job_t** job);
/* The same from an ocean scene file (arcus_scene_load; scenes/README.md): its view. */
ARCUS_API arcus_status arcus_ocean_render_scene(arcus_scene_t* scene, arcus_progress_callback progress, void* user,
                                                arcus_job_t** job);

typedef struct arcus_ocean_render_stats {
  double trace_seconds;    /* tracing photons                         */
  double map_seconds;      /* building the photon map (beam: its radii, too) */
  double estimate_seconds; /* marching the camera rays                */
  double total_seconds;
  uint64_t photons_stored;
} arcus_ocean_render_stats;
ARCUS_API arcus_status arcus_job_get_ocean_render_stats(arcus_job_t* job, arcus_ocean_render_stats* stats);
/* The image (any pointer may be NULL): width, height, grid samples and their
 * wavelengths [nm]; rgb (width × height × 3 floats, linear sRGB, top row first) and
 * spectral radiance (width × height × samples doubles, W/m²/sr/nm). */
ARCUS_API arcus_status arcus_job_get_ocean_image(arcus_job_t* job, uint32_t* width, uint32_t* height,
                                                 uint32_t* samples, double* wavelengths, float* rgb, double* spectral);
/* Writes an OpenEXR file (linear RGB; with spectral_bands, one channel per sample
 * named "L<nm>") and/or a PNG (sRGB, the march's exposure); either path may be NULL. */
ARCUS_API arcus_status arcus_job_write_ocean_image(arcus_job_t* job, const char* exr_path, const char* png_path,
                                                   int32_t spectral_bands);

#ifdef __cplusplus
}
#endif
#endif /* ARCUS_OCEAN_H */
