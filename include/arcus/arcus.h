/*
 * arcus — light transport in participating media, over OpenCL.
 * The one public C API (C99, usable from C++).
 *
 * Conventions
 *   - Every function returns an arcus_status; results come back through out-pointers.
 *   - Objects are opaque handles, created by arcus_*_create / arcus_advance and
 *     reference counted with arcus_*_retain / arcus_*_release.  A handle is freed when
 *     its count reaches zero; a field or job keeps its context alive.
 *   - Units: lengths in metres, wavelengths in nanometres, temperatures in kelvin.
 *     A flat layered atmosphere measures height along +y (y = 0 at sea level); a
 *     spherical one is centred on the origin with the Earth's radius ARCUS_EARTH_RADIUS.
 *   - Arrays of 3-vectors are tightly packed doubles, x y z per element.
 *
 * Errors
 *   Each context keeps the message of the last failed call made with it (what was
 *   wrong and which argument): arcus_context_last_error().  Calls that fail before a
 *   context exists (device queries, arcus_context_create) keep theirs per thread:
 *   arcus_last_error().  An optional callback sees every error as it happens.
 *
 * Thread safety
 *   Contexts, fields and jobs may be used from several threads at once: every call
 *   that touches a context serialises on that context's lock, so calls are safe but do
 *   not run concurrently on one context.  Use one context per thread for parallel
 *   submission.  The last-error message is per context (shared by its threads); read
 *   it from the thread that saw the failure before making another call.  Retain and
 *   release are atomic.  A handle must not be released while another thread uses it.
 */
#ifndef ARCUS_ARCUS_H
#define ARCUS_ARCUS_H

#include <stddef.h>
#include <stdint.h>

#if defined(_WIN32)
#  if defined(ARCUS_BUILDING_LIBRARY)
#    define ARCUS_API __declspec(dllexport)
#  else
#    define ARCUS_API __declspec(dllimport)
#  endif
#else
#  define ARCUS_API __attribute__((visibility("default")))
#endif

#ifdef __cplusplus
extern "C" {
#endif

/* ---- version ------------------------------------------------------------------ */
#define ARCUS_VERSION_MAJOR 0
#define ARCUS_VERSION_MINOR 1
#define ARCUS_VERSION_PATCH 0
#define ARCUS_VERSION (ARCUS_VERSION_MAJOR * 10000 + ARCUS_VERSION_MINOR * 100 + ARCUS_VERSION_PATCH)

#define ARCUS_EARTH_RADIUS 6371000.0 /* metres */

typedef enum arcus_status {
  ARCUS_SUCCESS = 0,
  ARCUS_ERROR_INVALID_ARGUMENT = 1, /* a null pointer, a bad number, a mismatched size  */
  ARCUS_ERROR_OUT_OF_MEMORY = 2,
  ARCUS_ERROR_DEVICE_NOT_FOUND = 3, /* no OpenCL device, or none matches the request    */
  ARCUS_ERROR_UNSUPPORTED = 4,      /* double precision on a device without cl_khr_fp64 */
  ARCUS_ERROR_KERNEL_BUILD = 5,     /* the message holds the OpenCL compiler's log      */
  ARCUS_ERROR_OPENCL = 6,           /* an OpenCL call failed; the message names it      */
  ARCUS_ERROR_IO = 7,               /* a file could not be read                         */
  /* Partial results: the job was created and holds every ray's result; some rays are
   * flagged (ARCUS_RAY_INVALID_INPUT, or paths longer than the capacity).           */
  ARCUS_ERROR_INVALID_RAYS = 8,
  ARCUS_ERROR_PATH_OVERFLOW = 9
} arcus_status;

/* Human-readable name of a status ("ARCUS_ERROR_INVALID_ARGUMENT"). Never NULL. */
ARCUS_API const char* arcus_status_string(arcus_status status);

/* Runtime version of the loaded library (compare with the ARCUS_VERSION_* macros). */
ARCUS_API arcus_status arcus_get_version(int* major, int* minor, int* patch);

/* Message of the last failed call on this thread that had no context ("" if none). */
ARCUS_API const char* arcus_last_error(void);

/* ---- devices ------------------------------------------------------------------ */
typedef struct arcus_device_info {
  uint32_t index;           /* position in arcus' enumeration (all platforms)      */
  char name[256];
  char platform[256];
  char version[128];        /* OpenCL version string of the device                 */
  int32_t is_gpu;
  int32_t fp64;             /* 1 when the device supports double precision         */
  uint32_t compute_units;
  uint64_t global_memory;   /* bytes */
  uint32_t lanes;           /* SIMD lanes per work-item arcus compiles for (doubleN) */
} arcus_device_info;

ARCUS_API arcus_status arcus_device_count(uint32_t* count);
ARCUS_API arcus_status arcus_device_get_info(uint32_t index, arcus_device_info* info);

/* ---- context ------------------------------------------------------------------ */
typedef struct arcus_context_s arcus_context_t;

/* Which device to use when creating a context: ARCUS_DEVICE_DEFAULT means the
 * ARCUS_DEVICE environment variable (an index, or a case-insensitive part of the
 * device or platform name) if set, else the first GPU, else the first CPU.         */
#define ARCUS_DEVICE_DEFAULT (-1)

typedef void (*arcus_error_callback)(void* user, arcus_status status, const char* message);

ARCUS_API arcus_status arcus_context_create(int32_t device, arcus_context_t** out);
ARCUS_API arcus_status arcus_context_retain(arcus_context_t* ctx);
ARCUS_API arcus_status arcus_context_release(arcus_context_t* ctx);
ARCUS_API arcus_status arcus_context_get_device(arcus_context_t* ctx, arcus_device_info* info);
/* Message of the last failed call on ctx ("" if none).  Valid until the next call. */
ARCUS_API const char* arcus_context_last_error(arcus_context_t* ctx);
/* Called (on the failing thread, after the context's lock is released, so it may call
 * arcus) for every error on ctx; NULL removes it. */
ARCUS_API arcus_status arcus_context_set_error_callback(arcus_context_t* ctx,
                                                        arcus_error_callback callback, void* user);

/* ---- index-of-refraction fields -------------------------------------------------
 * Each field gives n and its gradient at any point; analytic where the form allows
 * (thesis §2.2.2, §4.1.6).                                                           */
typedef struct arcus_field_s arcus_field_t;

typedef enum arcus_field_kind {
  ARCUS_FIELD_CONSTANT = 0,
  ARCUS_FIELD_LINEAR = 1,      /* n  = n0 + g·x                                        */
  ARCUS_FIELD_LINEAR_N2 = 2,   /* n² = a + k·x   (parabolic paths)                     */
  ARCUS_FIELD_LUNEBURG = 3,    /* n  = sqrt(2 − (r/R)²) inside R, 1 outside           */
  ARCUS_FIELD_FISHEYE = 4,     /* n  = n0 / (1 + (r/R)²)   (Maxwell's fish-eye)        */
  ARCUS_FIELD_ATMOSPHERE = 5,  /* layered air, flat (height = y) or spherical         */
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

typedef struct arcus_atmosphere_desc {
  int32_t spherical;                  /* 0: flat, height = y; 1: Earth-centred sphere  */
  double wavelength;                  /* nm, 300..1690 (Ciddor's dispersion range)     */
  double sea_level_temperature;       /* K   (US Standard Atmosphere 1976: 288.15)     */
  double sea_level_pressure;          /* Pa  (101325)                                  */
  uint32_t inversion_count;
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
/* A raw little-endian file of nx·ny·nz values in the order of arcus_field_create_grid. */
ARCUS_API arcus_status arcus_field_create_grid_from_file(arcus_context_t* ctx, const char* path,
                                                         arcus_scalar_type type, const uint32_t dims[3],
                                                         const double origin[3], const double spacing[3],
                                                         arcus_field_t** out);

ARCUS_API arcus_status arcus_field_retain(arcus_field_t* field);
ARCUS_API arcus_status arcus_field_release(arcus_field_t* field);
ARCUS_API arcus_status arcus_field_get_kind(arcus_field_t* field, arcus_field_kind* kind);
/* Evaluates n (and, if gradient != NULL, ∇n) at count points on the host, in double
 * precision, with the same formulas the kernels use. */
ARCUS_API arcus_status arcus_field_evaluate(arcus_field_t* field, size_t count, const double* positions,
                                            double* n, double* gradient);

/* ---- advancing rays (thesis §4.1.6 eq. 4.2, §4.3.5) ---------------------------------
 * The ray equation d/ds(n dr/ds) = ∇n is integrated in the state (r, v = n·dr/ds) over
 * arc length s.  A ray stops at `length`, on leaving the box (if use_box), or after
 * max_steps accepted steps.                                                          */
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

typedef struct arcus_advance_params {
  arcus_method method;
  arcus_precision precision;
  double length;          /* arc length to advance, metres (> 0)                       */
  double step;            /* fixed step (Euler/RK2/RK4); DP45: first trial step (0: auto),
                           * kept within max_step and [min_step, length]                */
  double rtol, atol;      /* DP45 tolerances on position and v, per step (> 0)         */
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
} arcus_advance_params;

/* Defaults: DP45, double, length 1, rtol 1e-9, atol 1e-12, min_step 1e-12,
 * max_step 0, max_rejections 64, max_steps 10 000 000, no box, no path. */
ARCUS_API arcus_status arcus_advance_params_init(arcus_advance_params* params);

/* Per-ray status. */
typedef enum arcus_ray_status {
  ARCUS_RAY_DONE = 0,          /* reached `length`                                      */
  ARCUS_RAY_LEFT_BOX = 1,      /* end state is where the path crossed the box           */
  ARCUS_RAY_STEP_LIMIT = 2,    /* max_steps reached before `length`                     */
  ARCUS_RAY_FAILED = 3,        /* DP45 could not meet the tolerance, or a non-finite state */
  ARCUS_RAY_INVALID_INPUT = 4  /* NaN/Inf origin or direction, or a zero direction     */
} arcus_ray_status;

/* Kernel features a job compiled with (Cycles-style coarse bits).  A constant field
 * compiles ARCUS_FEATURE_STRAIGHT and no integrator at all.                          */
#define ARCUS_FEATURE_STRAIGHT (1u << 0)
#define ARCUS_FEATURE_EULER (1u << 1)
#define ARCUS_FEATURE_RK2 (1u << 2)
#define ARCUS_FEATURE_RK4 (1u << 3)
#define ARCUS_FEATURE_DP45 (1u << 4)
#define ARCUS_FEATURE_ANALYTIC_FIELD (1u << 5) /* linear, linear n², Luneburg, fish-eye */
#define ARCUS_FEATURE_ATMOSPHERE (1u << 6)
#define ARCUS_FEATURE_GRID (1u << 7)
#define ARCUS_FEATURE_BOX (1u << 8)
#define ARCUS_FEATURE_RECORD_PATH (1u << 9)
#define ARCUS_FEATURE_FLOAT (1u << 10)         /* absent: double precision              */

/* Writes the names of the bits in `features` ("STRAIGHT BOX ..."), NUL-terminated. */
ARCUS_API arcus_status arcus_features_to_string(uint32_t features, char* buffer, size_t size);

typedef struct arcus_job_s arcus_job_t;

/* Advances count rays (origins, directions: count×3 doubles; directions need not be
 * unit length) through field.  On ARCUS_SUCCESS, ARCUS_ERROR_INVALID_RAYS and
 * ARCUS_ERROR_PATH_OVERFLOW *job holds every ray's result (the flagged rays are marked
 * and the others are unharmed); on any other status *job is NULL.                   */
ARCUS_API arcus_status arcus_advance(arcus_context_t* ctx, arcus_field_t* field, const arcus_advance_params* params,
                                     size_t count, const double* origins, const double* directions,
                                     arcus_job_t** job);

ARCUS_API arcus_status arcus_job_retain(arcus_job_t* job);
ARCUS_API arcus_status arcus_job_release(arcus_job_t* job);
ARCUS_API arcus_status arcus_job_get_count(arcus_job_t* job, size_t* count);
/* Any pointer may be NULL.  positions, directions: count×3 (unit directions);
 * steps: accepted steps; status: arcus_ray_status; lengths: arc length travelled.    */
ARCUS_API arcus_status arcus_job_get_end_states(arcus_job_t* job, double* positions, double* directions,
                                                uint64_t* steps, int32_t* status, double* lengths);
/* Paths (record_path): total_points is the number of points kept for all rays.  Both
 * path calls return ARCUS_ERROR_INVALID_ARGUMENT for a job advanced without record_path. */
ARCUS_API arcus_status arcus_job_get_path_size(arcus_job_t* job, size_t* total_points);
/* offsets: count+1 entries; ray i's points are points[offsets[i] .. offsets[i+1]) (×3).
 * needed: count entries, the points each ray's full path has (> kept on overflow);
 * either may be NULL. */
ARCUS_API arcus_status arcus_job_get_paths(arcus_job_t* job, uint64_t* offsets, double* points, uint64_t* needed);
ARCUS_API arcus_status arcus_job_get_features(arcus_job_t* job, uint32_t* features);

typedef struct arcus_job_stats {
  double build_seconds;   /* program build (0 when the program cache had it)          */
  double kernel_seconds;  /* device time of the advance kernel                         */
  double total_seconds;   /* wall time of arcus_advance                                */
  int32_t cache_hit;      /* 1 when the program came from the cache                    */
  uint32_t lanes;         /* rays per SIMD group                                       */
  uint32_t groups;        /* independent lane groups per work-item                     */
} arcus_job_stats;
ARCUS_API arcus_status arcus_job_get_stats(arcus_job_t* job, arcus_job_stats* stats);

#ifdef __cplusplus
}
#endif
#endif /* ARCUS_ARCUS_H */
