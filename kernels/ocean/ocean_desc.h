/* What the ocean engine's photon tracer and its host share, declared once for both (a
 * macro per precision, as curved/advance_desc.h does): the limits, the layouts of the
 * buffers and the description passed by value (thesis §4.2).
 *
 * Water tables (buffer `water`, reals), n = grid samples:
 *   [e·n + k]                 coefficient of active event e at sample k [1/m]
 *                             (events listed in `event_ids`: only those present)
 *   inelastic: for process p (ARCUS_OCEAN_PROCESS_*), at emission_offset + p·n·n:
 *   [(k·n + m)]               emission density h(λ_m | λ_k) [1/nm], then n·n reals of
 *                             its CDF, the same indices (src/ocean/water.h)
 *   phase tables, at phases.offset[s] for a tabulated scatterer s: phases.count[s]
 *   cosines, the density over cosines there (∫ dμ = 1, linear between them), its CDF
 * Lights (buffer `lights`, ARCUS_OCEAN_LIGHT_REALS reals each) and the emission CDF
 * (buffer `emission`: light_count·n reals, the cumulative share of (light, sample)
 * pairs in light-major order, last = 1).
 *
 * Tallies: `rows` rows of ARCUS_OCEAN_TALLY_REALS(limit) reals, each written by one
 * work-item only (so no atomics), summed by the host in row order; the depth tallies
 * (ARCUS_FEATURE_OCEAN_DEPTHS) `rows` rows of depth_count·n·3 reals (E_d, E_u, E_0
 * per depth and wavelength bin).                                                    */
#ifndef ARCUS_OCEAN_DESC_H
#define ARCUS_OCEAN_DESC_H

#ifndef __OPENCL_C_VERSION__
#include "common/real.h" /* the device source has it prepended */
#endif

#ifdef __OPENCL_C_VERSION__
#define REAL3 ARCUS_CAT(REAL, 3)
#define OCEAN_PI RC(3.14159265358979323846)
#endif

#define ARCUS_OCEAN_EVENTS 10
/* Interaction limit at most: images need 5 (§5.3), profiles of nearly white water
 * thousands (a photon then scatters ~1/(1 − albedo) times). */
#define ARCUS_OCEAN_MAX_INTERACTIONS 100000
/* Boundary events (surface reflections, bottom bounces) a photon may have before it is
 * counted as carried past the limit: keeps a photon trapped between a reflecting
 * bottom and total internal reflection from running forever. */
#define ARCUS_OCEAN_MAX_BOUNCES 256

/* Event ids: the thesis' roulette order (§4.2, eq. 4.4). */
#define ARCUS_OCEAN_ABSORB_WATER 0
#define ARCUS_OCEAN_RAMAN 1
#define ARCUS_OCEAN_ABSORB_DETRITUS 2
#define ARCUS_OCEAN_ABSORB_PHYTO 3
#define ARCUS_OCEAN_FLUORESCE_PHYTO 4
#define ARCUS_OCEAN_ABSORB_CDOM 5
#define ARCUS_OCEAN_FLUORESCE_CDOM 6
#define ARCUS_OCEAN_SCATTER_WATER 7
#define ARCUS_OCEAN_SCATTER_DETRITUS 8
#define ARCUS_OCEAN_SCATTER_PHYTO 9

/* Phase function kinds (src/ocean/water.h, Phase::Kind). */
#define ARCUS_OCEAN_PHASE_ISOTROPIC 0
#define ARCUS_OCEAN_PHASE_RAYLEIGH_LIKE 1
#define ARCUS_OCEAN_PHASE_HG 2
#define ARCUS_OCEAN_PHASE_TWO_TERM_HG 3
#define ARCUS_OCEAN_PHASE_TABLE 4

/* Light kinds; a light is ARCUS_OCEAN_LIGHT_REALS reals:
 *   kind, position xyz, direction xyz (unit), cos of the spot's half angle,
 *   the beam's radius (directional).                                               */
#define ARCUS_OCEAN_EMIT_POINT 0       /* isotropic from position                    */
#define ARCUS_OCEAN_EMIT_SPOT 1        /* uniform in the cone about direction        */
#define ARCUS_OCEAN_EMIT_DIRECTIONAL 2 /* a parallel beam along direction through a disc of
                                         * `radius` about position (plane-parallel: over
                                         * the surface, per square metre)           */
#define ARCUS_OCEAN_EMIT_SKY 3         /* plane-parallel only: uniform radiance from
                                         * the upper hemisphere, onto the surface    */
#define ARCUS_OCEAN_LIGHT_REALS 10

/* Per-row tallies: offsets in a row; per-interaction tallies have bins + 1 entries,
 * bins = min(limit, ARCUS_OCEAN_INTERACTION_BINS), the last one also holding every
 * later interaction. */
#define ARCUS_OCEAN_INTERACTION_BINS 64
#define ARCUS_OCEAN_T_COUNT 0                       /* events of each kind (10)       */
#define ARCUS_OCEAN_T_ARRIVING 10                   /* power arriving at each event   */
#define ARCUS_OCEAN_T_ABSORBED 20                   /* power each kind of event kept  */
#define ARCUS_OCEAN_T_EMITTED 30
#define ARCUS_OCEAN_T_PAST_LIMIT 31                 /* carried on past the limit       */
#define ARCUS_OCEAN_T_BOTTOM 32                     /* absorbed by the bottom          */
#define ARCUS_OCEAN_T_STORED 33                     /* photons stored for the map      */
#define ARCUS_OCEAN_T_PHOTONS 34                    /* photons traced                  */
#define ARCUS_OCEAN_T_INTERACTIONS 35               /* interactions in the medium      */
#define ARCUS_OCEAN_T_ABSORBED_R2 36                /* Σ power·(distance from emission)²
                                                     * where absorbed in the water      */
#define ARCUS_OCEAN_T_BY_INTERACTION 37             /* absorbed at interaction j (0..limit) */
#define ARCUS_OCEAN_T_ESCAPED(limit) (38 + (limit)) /* escaped after j interactions (0..limit) */
#define ARCUS_OCEAN_TALLY_REALS(limit) (39 + 2 * (limit))

/* Wavelengths a photon carries at most (hero-wavelength sampling, trace.cl): the
 * hero, which draws the path, and companions that share it until an inelastic event. */
#define ARCUS_OCEAN_MAX_HEROES 4

/* A stored photon (ARCUS_OCEAN_PHOTON_REALS reals per slot; slot = photon·limit + j):
 * where it scattered (3), the direction it arrived along (3, unit), the event
 * (ARCUS_OCEAN_SCATTER_*, or an inelastic one), then per carried wavelength its power
 * after the event [W] (ARCUS_OCEAN_MAX_HEROES, 0 where none) and its wavelength [nm]
 * (as many); a first power of 0 marks an empty slot. */
#define ARCUS_OCEAN_STORED_EVENT 6
#define ARCUS_OCEAN_STORED_POWER 7
#define ARCUS_OCEAN_STORED_NM (7 + ARCUS_OCEAN_MAX_HEROES)
#define ARCUS_OCEAN_PHOTON_REALS (7 + 2 * ARCUS_OCEAN_MAX_HEROES)

/* The three scatterers' phase functions (water, minerals and detritus, phytoplankton):
 * kind (ARCUS_OCEAN_PHASE_*), parameters, and for tables where in `water` they are. */
#define ARCUS_DECLARE_OCEAN_PHASES(NAME, R, I)                                 \
  typedef struct NAME {                                                        \
    R a[3], gf[3], gb[3], zeta[3];                                             \
    I kind[3], offset[3], count[3], pad;                                       \
  } NAME

#define ARCUS_DECLARE_OCEAN_DESC(NAME, PHASES, R, I, U64)                                                 \
  typedef struct NAME {                                                                           \
    R first_nm, step_nm;      /* the wavelength grid                                         */   \
    R power;                  /* each photon's power at emission [W]                         */   \
    R n_water;                /* the water's refractive index (surface)                      */   \
    R bottom_depth;           /* > 0: a Lambertian bottom at z = −bottom_depth; +inf: none   */   \
    R bottom_albedo;                                                                              \
    R box_lo[3], box_hi[3];   /* photons leaving the box escape (may be infinite)            */   \
    R layer;                  /* depth tallies: thickness of the E_0 track-length layer [m]  */   \
    R tile, tile_x, tile_y;   /* > 0: sun and sky enter through this periodic square tile [m] \
                               * about (tile_x, tile_y), photons stored folded into it     */   \
    PHASES phases;            /* the scatterers' phase functions                             */   \
    U64 seed;                                                                                     \
    U64 first_photon, end_photon; /* this launch traces photons [first, end)              */      \
    I count;                  /* grid samples n                                              */   \
    I heroes;                 /* wavelengths a stored photon carries: divides count          */   \
    I events;                 /* active events                                               */   \
    I event_ids[10];          /* their ids, roulette order                                   */   \
    I limit;                  /* interaction limit (thesis §5.3: 5)                          */   \
    I bins;                   /* per-interaction tallies: 0..bins, the last also all later   */   \
    I light_count;                                                                                \
    I surface;                /* 1: a flat air–water surface at z = 0, water below           */   \
    I store;                  /* 1: store scattered photons (photon map)                     */   \
    I rows;                   /* tally rows = work-items                                     */   \
    I depth_count;                                                                                \
    I emission_offset;        /* offset of the inelastic tables in `water`                   */   \
  } NAME

#ifdef __OPENCL_C_VERSION__
ARCUS_DECLARE_OCEAN_PHASES(ocean_phases, REAL, int);
ARCUS_DECLARE_OCEAN_DESC(ocean_desc, ocean_phases, REAL, int, ulong);
#else
ARCUS_DECLARE_OCEAN_PHASES(arcus_ocean_phases, double, int32_t);
ARCUS_DECLARE_OCEAN_DESC(arcus_ocean_desc, arcus_ocean_phases, double, int32_t, uint64_t);
#endif

/* The tracer's arguments, X(type, name) (ARCUS_PARAMS; src/core/launch.h). */
#define ARCUS_OCEAN_TRACE_ARGS(X)   \
  X(__global const REAL*, water)    \
  X(__global const REAL*, lights)   \
  X(__global const REAL*, emission) \
  X(__global const REAL*, depths)   \
  X(const ocean_desc, d)            \
  X(__global REAL*, tallies)        \
  X(__global REAL*, depth_tallies)  \
  X(__global REAL*, stored)

/* Ray marching (thesis §4.1.4, §4.2): the camera, the march and the estimate.  The
 * `optics` buffer holds, per grid sample m (n of them): σ_t, exp(−σ_t Δt),
 * exp(−σ_t Δt/2), the three scatterers' σ_s (3·n), then the phase tables.  Per light
 * l, `light_tables` holds g_samples distances' rows of n reals, E[l][d][m] = I_l(λ_m)
 * exp(−σ_t(λ_m) d) (the intensity that reaches distance d, elastic), then (inelastic)
 * as many rows of G[l][d][m] = Σ_i I_l(λ_i) exp(−σ_t(λ_i) d) μ_j(λ_i) h_j(λ_m | λ_i)
 * (λ_i/λ_m) Δλ / (4π) (eq. 4.5), d = g·g_step.  For the sun (a directional light above
 * the surface; its direction in `lights` is the refracted beam's in the water) I is
 * its irradiance normal to the beam just below the surface and d the slant path.
 * The sky above the surface (src/ocean/render.cpp, sky_tables): `sky` holds its
 * radiance L_s (n reals), n²T through the surface looking up at each of sky_cosines
 * view cosines v = −1 … 1 (0 outside Snell's window), then per depth row d = r ·
 * sky_d_step and view cosine the light its first elastic scattering sends toward the
 * camera per metre (sky_rows × sky_cosines × n), then per row the inelastic (sky_rows ×
 * n). */
#define ARCUS_DECLARE_OCEAN_RENDER_DESC(NAME, PHASES, R, I)                                       \
  typedef struct NAME {                                                                           \
    R eye[3], forward[3], right[3], up[3]; /* right/up scaled to the image plane at 1 */           \
    R step;                    /* Δt [m]                                                     */   \
    R band;                    /* Δλ of a grid sample [nm] (1 for one sample)                */   \
    R g_step;                  /* distance between light-table rows [m]                      */   \
    R sky_d_step;              /* depth between sky-table rows [m]                           */   \
    R n_water;                 /* the water's refractive index (surface)                     */   \
    R tile, tile_x, tile_y;    /* > 0: the photons' periodic tile [m] and its centre         */   \
    R r_max;                   /* the largest photon radius (beam)                           */   \
    PHASES phases;                                                                                \
    I width, height, count, steps, k, light_count, g_samples;                                     \
    I first_pixel, end_pixel;  /* this launch's pixels                                       */   \
    I single;                  /* 1: single scattering from the lights                       */   \
    I multiple;                /* 1: multiple scattering from the photon map                 */   \
    I stride;                  /* a pixel here is stride × stride of the image's              */   \
    I image_width, image_height; /* the image's pixels (width, height: this pass's)          */   \
    I sky_rows, sky_cosines;   /* the sky tables (0 rows: no sky)                            */   \
    I surface;                 /* 1: the flat sea surface at z = 0 reflects every ray
                                * reaching it (Fresnel; beyond Snell's window, wholly)      */   \
    I subsample;               /* per step: the estimate at one jittered step of every so many */ \
    I seed;                    /* the jitter's (the photons' seed)                           */   \
  } NAME

/* A stored photon in the map's power channels: its event, then per carried wavelength
 * its power (ARCUS_OCEAN_MAX_HEROES channels, 0 where none) and its grid sample. */
#define ARCUS_OCEAN_MAP_EVENT 0
#define ARCUS_OCEAN_MAP_POWER 1
#define ARCUS_OCEAN_MAP_BIN (1 + ARCUS_OCEAN_MAX_HEROES)
#define ARCUS_OCEAN_MAP_CHANNELS (1 + 2 * ARCUS_OCEAN_MAX_HEROES)

#ifdef __OPENCL_C_VERSION__
ARCUS_DECLARE_OCEAN_RENDER_DESC(ocean_render_desc, ocean_phases, REAL, int);
/* Which cell of the lattice of periodic photon tiles (width P, cell 0 centred on
 * `centre`) coordinate x lies in: trace.cl folds photons into cell 0, render.cl finds
 * the cells a ray crosses. */
ARCUS_INLINE REAL ocean_tile_cell(REAL x, REAL centre, REAL P) { return floor((x - centre) / P + RC(0.5)); }
#else
ARCUS_DECLARE_OCEAN_RENDER_DESC(arcus_ocean_render_desc, arcus_ocean_phases, double, int32_t);
#endif

/* The renderer's arguments, and those of the beam estimate's photon radii: the map
 * (photon/photon_desc.h), or its photons under a BVH of their spheres (render.cl). */
#define ARCUS_OCEAN_RENDER_ARGS(X)          \
  X(__global const REAL*, optics)           \
  X(__global const REAL*, lights)           \
  X(__global const REAL*, light_tables)     \
  X(__global const REAL*, sky)              \
  X(__global const bvh_node*, nodes)        \
  X(__global const REAL*, photons)          \
  X(const photon_map_desc, map)             \
  X(__global const REAL*, radii)            \
  X(const ocean_render_desc, rd)            \
  X(__global REAL*, radiance)               \
  X(__global REAL*, scratch)
#define ARCUS_OCEAN_RADII_ARGS(X)    \
  X(__global const bvh_node*, nodes) \
  X(__global const REAL*, photons)   \
  X(const photon_map_desc, map)      \
  X(const int, k)                    \
  X(const int, kr)                   \
  X(const int, chunk)                \
  X(__global REAL*, radii)

#endif /* ARCUS_OCEAN_DESC_H */
