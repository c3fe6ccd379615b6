/*
 * arcus curved light (thesis §2.2, §4.1.6, §4.3.5): index-of-refraction fields, and
 * rays advanced through them along the ray equation d/ds(n dr/ds) = ∇n with Euler,
 * RK2, RK4 or Dormand–Prince 5(4).  Include arcus.h.
 *
 * A flat layered atmosphere measures height along +y (y = 0 at sea level); a
 * spherical one is centred on the origin with the Earth's radius ARCUS_EARTH_RADIUS.
 */
#ifndef ARCUS_CURVED_H
#define ARCUS_CURVED_H

#include "arcus_core.h"
#include "arcus_scene.h"

#ifdef __cplusplus
extern "C" {
#endif

#define ARCUS_EARTH_RADIUS 6371000.0 /* metres */
/* Vacuum wavelengths (nm) Ciddor's dispersion of air covers: the range of per-ray and
 * atmosphere wavelengths. */
#define ARCUS_MIN_WAVELENGTH 300.0
#define ARCUS_MAX_WAVELENGTH 1690.0

/* ---- index-of-refraction fields -------------------------------------------------
 * Each field gives n and its gradient at any point; analytic where the form allows
 * (thesis §2.2.2, §4.1.6).  Parameters are checked together with what the kernels
 * derive from them (1/radius², 1/spacing): both must be finite and non-zero.        */
typedef struct arcus_field_s arcus_field_t;

typedef enum arcus_field_kind {
  ARCUS_FIELD_CONSTANT = 0,
  ARCUS_FIELD_LINEAR = 1,      /* n  = n0 + g·x                                        */
  ARCUS_FIELD_LINEAR_N2 = 2,   /* n² = a + k·x   (parabolic paths)                     */
  ARCUS_FIELD_LUNEBURG = 3,    /* n  = sqrt(2 − (r/R)²) inside R, 1 outside           */
  ARCUS_FIELD_FISHEYE = 4,     /* n  = n0 / (1 + (r/R)²)   (Maxwell's fish-eye)        */
  ARCUS_FIELD_ATMOSPHERE = 5,  /* layered air, flat (height = y) or spherical; dispersive */
  ARCUS_FIELD_GRID = 6         /* 3D voxel grid, trilinear                             */
} arcus_field_kind;

ARCUS_API arcus_status arcus_field_create_constant(arcus_context_t* ctx, double n, arcus_field_t** out);
ARCUS_API arcus_status arcus_field_create_linear(arcus_context_t* ctx, double n0, const double gradient[3],
                                                 arcus_field_t** out);
ARCUS_API arcus_status arcus_field_create_linear_n2(arcus_context_t* ctx, double a, const double k[3],
                                                    arcus_field_t** out);
ARCUS_API arcus_status arcus_field_create_luneburg(arcus_context_t* ctx, const double center[3], double radius,
                                                   arcus_field_t** out);
ARCUS_API arcus_status arcus_field_create_fisheye(arcus_context_t* ctx, const double center[3], double radius,
                                                  double n0, arcus_field_t** out);

/* An inversion layer of the atmospheric profile manager (thesis §3.1.1): the
 * temperature is offset by delta_t below `base`, the offset fades linearly to zero at
 * `top`, and the standard profile holds above.  delta_t < 0 makes cold air under warm
 * (an inversion: superior mirages, Novaya Zemlya); delta_t > 0 with base = 0 makes a
 * hot ground layer (inferior mirages).  Heights are geometric, in metres.           */
typedef struct arcus_inversion {
  double base;
  double top;
  double delta_t;
} arcus_inversion;

#define ARCUS_MAX_INVERSIONS 1024 /* the kernels scan the layers at every evaluation */

typedef struct arcus_atmosphere_desc {
  int32_t spherical;                  /* 0: flat, height = y; 1: Earth-centred sphere  */
  double wavelength;                  /* nm, 300..1690 (Ciddor's dispersion range); per-ray
                                       * wavelengths given to arcus_curved_advance
                                       * replace it                                      */
  double sea_level_temperature;       /* K   (US Standard Atmosphere 1976: 288.15)     */
  double sea_level_pressure;          /* Pa  (101325)                                  */
  uint32_t inversion_count;           /* at most ARCUS_MAX_INVERSIONS                  */
  const arcus_inversion* inversions;  /* copied at creation                            */
} arcus_atmosphere_desc;

/* Fills desc with the US Standard Atmosphere 1976, flat, 550 nm, no inversions. */
ARCUS_API arcus_status arcus_atmosphere_desc_init(arcus_atmosphere_desc* desc);
ARCUS_API arcus_status arcus_field_create_atmosphere(arcus_context_t* ctx, const arcus_atmosphere_desc* desc,
                                                     arcus_field_t** out);

/* values[(k*ny + j)*nx + i] is n at origin + (i, j, k)·spacing; each of dims is 2..65536
 * and every value a positive finite n.  Outside the grid the values at its faces extend
 * outwards (clamped), with zero gradient across the face. */
ARCUS_API arcus_status arcus_field_create_grid(arcus_context_t* ctx, const double* values, const uint32_t dims[3],
                                               const double origin[3], const double spacing[3], arcus_field_t** out);

typedef enum arcus_scalar_type { ARCUS_FLOAT32 = 0, ARCUS_FLOAT64 = 1 } arcus_scalar_type;
/* A raw little-endian file of nx·ny·nz values in the order of arcus_field_create_grid.
 * `type` is an arcus_scalar_type.  A path that is not a regular file (a directory, a
 * FIFO, a device), or a file of the wrong size, is ARCUS_ERROR_IO. */
ARCUS_API arcus_status arcus_field_create_grid_from_file(arcus_context_t* ctx, const char* path, int32_t type,
                                                         const uint32_t dims[3], const double origin[3],
                                                         const double spacing[3], arcus_field_t** out);

ARCUS_API arcus_status arcus_field_retain(arcus_field_t* field);
ARCUS_API arcus_status arcus_field_release(arcus_field_t* field);
ARCUS_API arcus_status arcus_field_get_kind(arcus_field_t* field, arcus_field_kind* kind);
/* Evaluates n (and, if gradient != NULL, ∇n) at count points on the host, in double
 * precision, with the same formulas the kernels use (at the field's own wavelength). */
ARCUS_API arcus_status arcus_field_evaluate(arcus_field_t* field, size_t count, const double* positions,
                                            double* n, double* gradient);

/* ---- advancing rays (thesis §4.1.6 eq. 4.2, §4.3.5) ---------------------------------
 * The ray equation d/ds(n dr/ds) = ∇n is integrated in the state (r, v = n·dr/ds) over
 * arc length s.  A ray stops at `length`, on leaving the box (if use_box: where its
 * integrated path crosses the box, to the job's tolerance), after max_steps accepted
 * steps, or when it fails.                                                           */
typedef enum arcus_method {
  ARCUS_METHOD_EULER = 0,
  ARCUS_METHOD_RK2 = 1,   /* explicit midpoint */
  ARCUS_METHOD_RK4 = 2,
  ARCUS_METHOD_DP45 = 3   /* Dormand–Prince 5(4), FSAL, adaptive per ray */
} arcus_method;

/* Float resolves positions to about 6e-8 of their magnitude: ~0.5 m in Earth-centred
 * coordinates of a spherical atmosphere, too coarse for mirages there.  Parameters and
 * field values must fit in float (ARCUS_ERROR_INVALID_ARGUMENT otherwise). */
typedef enum arcus_precision { ARCUS_PRECISION_DOUBLE = 0, ARCUS_PRECISION_FLOAT = 1 } arcus_precision;

/* Enumerations are held in int32_t members: a value outside the enumeration is an
 * error, never undefined behaviour. */
typedef struct arcus_advance_params {
  int32_t method;         /* arcus_method                                              */
  int32_t precision;      /* arcus_precision                                           */
  double length;          /* arc length to advance, metres (> 0)                       */
  double step;            /* fixed step (Euler/RK2/RK4); DP45: first trial step (0: auto),
                           * kept within max_step and [min_step, length]                */
  double rtol, atol;      /* DP45 tolerances on position and v, per step (> 0); also the
                           * tolerance of box crossings (fixed steps: 1e-12 relative)   */
  double min_step;        /* DP45: a step this small that still fails ends the ray     */
  double max_step;        /* DP45: upper bound on the step (0: unbounded).  For a Luneburg
                           * lens or a grid arcus also caps it at half the radius / the
                           * grid's smallest extent, so no step jumps over the medium. */
  uint32_t max_rejections;/* DP45: consecutive rejections before the ray fails         */
  uint64_t max_steps;     /* accepted steps before the ray stops (ARCUS_RAY_STEP_LIMIT);
                           * values above 2^31 − 1 count as 2^31 − 1                   */
  int32_t use_box;        /* stop on leaving [box_min, box_max]                        */
  double box_min[3], box_max[3];
  int32_t record_path;    /* keep every net point of every path                        */
  uint32_t path_capacity; /* points kept per ray; 0: enough for fixed steps, 4096 for DP45 */
  arcus_progress_callback progress; /* optional (arcus_core.h); NULL: none              */
  void* progress_user;    /* passed to progress                                        */
} arcus_advance_params;

/* Defaults: DP45, double, length 1, rtol 1e-9, atol 1e-12, min_step 1e-12,
 * max_step 0, max_rejections 64, max_steps 10 000 000, no box, no path, no progress. */
ARCUS_API arcus_status arcus_advance_params_init(arcus_advance_params* params);

/* Per-ray status. */
typedef enum arcus_ray_status {
  ARCUS_RAY_DONE = 0,          /* reached `length`                                      */
  ARCUS_RAY_LEFT_BOX = 1,      /* end state is where the path crossed the box           */
  ARCUS_RAY_STEP_LIMIT = 2,    /* max_steps reached before `length`                     */
  ARCUS_RAY_FAILED = 3,        /* see arcus_ray_failure
                                * (arcus_job_get_curved_failures)                        */
  ARCUS_RAY_INVALID_INPUT = 4, /* NaN/Inf origin or direction, a zero direction, or a
                                * wavelength outside 300..1690 nm                       */
  ARCUS_RAY_CANCELLED = 5      /* the job was cancelled before the ray finished         */
} arcus_ray_status;

/* Why a ray failed; its end state is the last one known good (DP45 and box jobs) or
 * where the fixed-step integration stopped. */
typedef enum arcus_ray_failure {
  ARCUS_FAILURE_NONE = 0,              /* the ray did not fail                          */
  ARCUS_FAILURE_TOLERANCE = 1,         /* DP45: no step >= min_step met the tolerance
                                        * within max_rejections tries                   */
  ARCUS_FAILURE_NOT_FINITE = 2,        /* the state became NaN or infinite (overflow)   */
  ARCUS_FAILURE_INDEX_NOT_POSITIVE = 3 /* the ray reached a point where n <= 0          */
} arcus_ray_failure;

/* Kernel features of curved jobs: bits 8-23 of arcus_features.  A constant field
 * compiles ARCUS_FEATURE_CURVED_STRAIGHT and no integrator at all; each field kind has its
 * own bit, as it has its own program. */
#define ARCUS_FEATURE_CURVED_STRAIGHT (UINT64_C(1) << 8)
#define ARCUS_FEATURE_CURVED_EULER (UINT64_C(1) << 9)
#define ARCUS_FEATURE_CURVED_RK2 (UINT64_C(1) << 10)
#define ARCUS_FEATURE_CURVED_RK4 (UINT64_C(1) << 11)
#define ARCUS_FEATURE_CURVED_DP45 (UINT64_C(1) << 12)
#define ARCUS_FEATURE_CURVED_FIELD_LINEAR (UINT64_C(1) << 13)
#define ARCUS_FEATURE_CURVED_FIELD_LINEAR_N2 (UINT64_C(1) << 14)
#define ARCUS_FEATURE_CURVED_FIELD_LUNEBURG (UINT64_C(1) << 15)
#define ARCUS_FEATURE_CURVED_FIELD_FISHEYE (UINT64_C(1) << 16)
#define ARCUS_FEATURE_CURVED_FIELD_ATMOSPHERE (UINT64_C(1) << 17)
#define ARCUS_FEATURE_CURVED_FIELD_GRID (UINT64_C(1) << 18)
#define ARCUS_FEATURE_CURVED_BOX (UINT64_C(1) << 19)
#define ARCUS_FEATURE_CURVED_RECORD_PATH (UINT64_C(1) << 20)
#define ARCUS_FEATURE_CURVED_DISPERSION (UINT64_C(1) << 21) /* per-ray wavelengths, dispersive field */

/* Advances count rays (origins, directions: count×3 doubles; directions need not be
 * unit length) through field.  wavelengths (count doubles, nm; may be NULL) gives each
 * ray its own wavelength: a dispersive field (the atmosphere) evaluates n at each ray's
 * wavelength in the same job; other fields ignore it.  On ARCUS_SUCCESS,
 * ARCUS_ERROR_INVALID_RAYS, ARCUS_ERROR_PATH_OVERFLOW and ARCUS_ERROR_CANCELLED *job
 * holds every ray's result (the flagged rays are marked and the others are unharmed);
 * on any other status *job is NULL.                                                  */
ARCUS_API arcus_status arcus_curved_advance(arcus_context_t* ctx, arcus_field_t* field, const arcus_advance_params* params,
                                            size_t count, const double* origins, const double* directions,
                                            const double* wavelengths, arcus_job_t** job);

/* The results of an advance job (another engine's job is ARCUS_ERROR_INVALID_ARGUMENT).
 * Any pointer may be NULL.  positions, directions: count×3 (unit directions);
 * steps: accepted steps; status: arcus_ray_status; lengths: arc length travelled.    */
ARCUS_API arcus_status arcus_job_get_curved_end_states(arcus_job_t* job, double* positions, double* directions,
                                                       uint64_t* steps, int32_t* status, double* lengths);
/* failures: count entries of arcus_ray_failure. */
ARCUS_API arcus_status arcus_job_get_curved_failures(arcus_job_t* job, int32_t* failures);
/* Paths (record_path): total_points is the number of points kept for all rays.  Both
 * path calls return ARCUS_ERROR_INVALID_ARGUMENT for a job advanced without record_path. */
ARCUS_API arcus_status arcus_job_get_curved_path_size(arcus_job_t* job, size_t* total_points);
/* offsets: count+1 entries; ray i's points are points[offsets[i] .. offsets[i+1]) (×3).
 * needed: count entries, the points each ray's full path has (> kept on overflow);
 * either may be NULL. */
ARCUS_API arcus_status arcus_job_get_curved_paths(arcus_job_t* job, uint64_t* offsets, double* points, uint64_t* needed);

/* ---- curved scenes (arcus_scene.h; engine "curved") --------------------------------
 * A new reference to the scene's field (release it). */
ARCUS_API arcus_status arcus_scene_get_field(arcus_scene_t* scene, arcus_field_t** field);
/* The scene's integrator settings, box and path options (progress: none). */
ARCUS_API arcus_status arcus_scene_get_advance_params(arcus_scene_t* scene, arcus_advance_params* params);
/* The scene's rays: count, then (any pointer may be NULL) count×3 origins and
 * directions and count wavelengths; *has_wavelengths says whether the scene gives
 * them (else wavelengths is left untouched). */
ARCUS_API arcus_status arcus_scene_get_ray_count(arcus_scene_t* scene, size_t* count);
ARCUS_API arcus_status arcus_scene_get_rays(arcus_scene_t* scene, double* origins, double* directions,
                                            double* wavelengths, int32_t* has_wavelengths);
/* Advances the scene's rays through its field with its settings (arcus_curved_advance),
 * reporting to `progress` (may be NULL). */
ARCUS_API arcus_status arcus_curved_advance_scene(arcus_scene_t* scene, arcus_progress_callback progress, void* user,
                                                  arcus_job_t** job);

/* ---- spellings before arcus 0.10 (removed in 0.11; arcus_core.h, "Names") ----------- */
#ifndef ARCUS_NO_DEPRECATED
#define ARCUS_FEATURE_STRAIGHT ARCUS_FEATURE_CURVED_STRAIGHT
#define ARCUS_FEATURE_EULER ARCUS_FEATURE_CURVED_EULER
#define ARCUS_FEATURE_RK2 ARCUS_FEATURE_CURVED_RK2
#define ARCUS_FEATURE_RK4 ARCUS_FEATURE_CURVED_RK4
#define ARCUS_FEATURE_DP45 ARCUS_FEATURE_CURVED_DP45
#define ARCUS_FEATURE_FIELD_LINEAR ARCUS_FEATURE_CURVED_FIELD_LINEAR
#define ARCUS_FEATURE_FIELD_LINEAR_N2 ARCUS_FEATURE_CURVED_FIELD_LINEAR_N2
#define ARCUS_FEATURE_FIELD_LUNEBURG ARCUS_FEATURE_CURVED_FIELD_LUNEBURG
#define ARCUS_FEATURE_FIELD_FISHEYE ARCUS_FEATURE_CURVED_FIELD_FISHEYE
#define ARCUS_FEATURE_FIELD_ATMOSPHERE ARCUS_FEATURE_CURVED_FIELD_ATMOSPHERE
#define ARCUS_FEATURE_FIELD_GRID ARCUS_FEATURE_CURVED_FIELD_GRID
#define ARCUS_FEATURE_BOX ARCUS_FEATURE_CURVED_BOX
#define ARCUS_FEATURE_RECORD_PATH ARCUS_FEATURE_CURVED_RECORD_PATH
#define ARCUS_FEATURE_DISPERSION ARCUS_FEATURE_CURVED_DISPERSION
ARCUS_DEPRECATED("arcus_curved_advance")
ARCUS_API arcus_status arcus_advance(arcus_context_t* ctx, arcus_field_t* field, const arcus_advance_params* params,
                                     size_t count, const double* origins, const double* directions,
                                     const double* wavelengths, arcus_job_t** job);
ARCUS_DEPRECATED("arcus_curved_advance_scene")
ARCUS_API arcus_status arcus_scene_advance(arcus_scene_t* scene, arcus_progress_callback progress, void* user,
                                           arcus_job_t** job);
ARCUS_DEPRECATED("arcus_job_get_curved_end_states")
ARCUS_API arcus_status arcus_job_get_end_states(arcus_job_t* job, double* positions, double* directions,
                                                uint64_t* steps, int32_t* status, double* lengths);
ARCUS_DEPRECATED("arcus_job_get_curved_failures")
ARCUS_API arcus_status arcus_job_get_failures(arcus_job_t* job, int32_t* failures);
ARCUS_DEPRECATED("arcus_job_get_curved_path_size")
ARCUS_API arcus_status arcus_job_get_path_size(arcus_job_t* job, size_t* total_points);
ARCUS_DEPRECATED("arcus_job_get_curved_paths")
ARCUS_API arcus_status arcus_job_get_paths(arcus_job_t* job, uint64_t* offsets, double* points, uint64_t* needed);
#endif

#ifdef __cplusplus
}
#endif
#endif /* ARCUS_CURVED_H */
