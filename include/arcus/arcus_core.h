/*
 * arcus core: status codes, version, devices, contexts, errors, and what every engine's
 * jobs share (features, statistics, progress and cancellation).  Include arcus.h.
 *
 * Conventions
 *   - Every function returns an arcus_status; results come back through out-pointers.
 *   - Objects are opaque handles, created by arcus_*_create (or a job-making call) and
 *     reference counted with arcus_*_retain / arcus_*_release.  A handle is freed when
 *     its count reaches zero; every object keeps its context alive.
 *   - Every call checks its handles: NULL, a released handle, a handle of the wrong
 *     type (a job passed where a field is expected) or an object of another context
 *     gives ARCUS_ERROR_INVALID_ARGUMENT with a message, never undefined behaviour.
 *   - Units, in every engine: lengths in metres, wavelengths in nanometres in vacuum,
 *     temperatures in kelvin, angles in degrees where a name ends in _deg (else
 *     radians).  Arrays of 3-vectors are tightly packed doubles, x y z per element.
 *   - Names: arcus_<object>_<verb>[_<what>], where <object> is the handle a call acts
 *     on (context, field, scene, renderer, water, particle, job) or, for a call that
 *     makes a job, its engine (arcus_curved_advance, arcus_render_frame,
 *     arcus_ocean_trace, arcus_rainbow_cast).  What only one engine's jobs hold is
 *     arcus_job_get_<engine>_<what> (arcus_job_get_ocean_image); what every job has is
 *     arcus_job_get_<what> (count, features, stats).  Feature bits are
 *     ARCUS_FEATURE_<ENGINE>_<NAME> and report as "<ENGINE>_<NAME>"; the core's have
 *     no engine (ARCUS_FEATURE_FLOAT).
 *   - Renamed calls keep their old spelling for one release, declared ARCUS_DEPRECATED
 *     (the compiler names the new one); define ARCUS_NO_DEPRECATED to hide them.
 *
 * Errors
 *   Each context keeps the message of the last failed call made with it (what was
 *   wrong and which argument): arcus_context_last_error().  Calls that fail before a
 *   context exists (device queries, arcus_context_create) keep theirs per thread:
 *   arcus_last_error().  An optional callback sees every error as it happens.
 *
 * Thread safety
 *   Contexts and their objects may be used from several threads at once: every call
 *   that touches a context serialises on that context's lock, so calls are safe but do
 *   not run concurrently on one context.  Contexts are independent: use one context per
 *   thread to run jobs in parallel.  The last-error message is per context (shared by
 *   its threads); read it from the thread that saw the failure before making another
 *   call.  Retain and release are atomic, and a call keeps the objects it was handed
 *   alive until it returns, even when another thread releases their last reference
 *   meanwhile.  A progress callback runs on the calling thread with the context's lock
 *   held: a call it makes on that context or any of its objects (retain and release
 *   included) returns ARCUS_ERROR_REENTRANT and does nothing (the error callback is not
 *   called for it); calls on other contexts work.
 *
 * Environment
 *   ARCUS_DEVICE     the default device: an index, or part of the device/platform name
 *   ARCUS_CACHE_DIR  where compiled kernels are kept between processes ("off": nowhere;
 *                    default $XDG_CACHE_HOME/arcus, else ~/.cache/arcus)
 *   ARCUS_LANES, ARCUS_GROUPS  override the kernel layout (rays per SIMD group, groups
 *                    per work-item) for experiments; a bad value is an error
 */
#ifndef ARCUS_CORE_H
#define ARCUS_CORE_H

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

/* A spelling kept for one release after a rename: calling it warns with the new name. */
#if defined(__GNUC__) || defined(__clang__)
#  define ARCUS_DEPRECATED(replacement) __attribute__((deprecated("use " replacement)))
#elif defined(_MSC_VER)
#  define ARCUS_DEPRECATED(replacement) __declspec(deprecated("use " replacement))
#else
#  define ARCUS_DEPRECATED(replacement)
#endif

#ifdef __cplusplus
extern "C" {
#endif

/* ---- version ------------------------------------------------------------------ */
#define ARCUS_VERSION_MAJOR 0
#define ARCUS_VERSION_MINOR 10
#define ARCUS_VERSION_PATCH 0
#define ARCUS_VERSION (ARCUS_VERSION_MAJOR * 10000 + ARCUS_VERSION_MINOR * 100 + ARCUS_VERSION_PATCH)

typedef enum arcus_status {
  ARCUS_SUCCESS = 0,
  ARCUS_ERROR_INVALID_ARGUMENT = 1, /* a null or wrong handle, a bad number, a mismatched size */
  ARCUS_ERROR_OUT_OF_MEMORY = 2,    /* host or device memory; the message names what needed it */
  ARCUS_ERROR_DEVICE_NOT_FOUND = 3, /* no OpenCL device, or none matches the request          */
  ARCUS_ERROR_UNSUPPORTED = 4,      /* double precision on a device without cl_khr_fp64       */
  ARCUS_ERROR_KERNEL_BUILD = 5,     /* the message holds the OpenCL compiler's log            */
  ARCUS_ERROR_OPENCL = 6,           /* an OpenCL call failed; the message names it            */
  ARCUS_ERROR_IO = 7,               /* a file could not be read: missing, not a regular file,
                                     * the wrong size, unreadable                             */
  /* Partial results: the job was created and holds every ray's result; some rays are
   * flagged (ARCUS_RAY_INVALID_INPUT, paths longer than the capacity, or not finished
   * because the progress callback cancelled the job: ARCUS_RAY_CANCELLED).            */
  ARCUS_ERROR_INVALID_RAYS = 8,
  ARCUS_ERROR_PATH_OVERFLOW = 9,
  ARCUS_ERROR_CANCELLED = 10,
  /* A call on a context (or one of its objects) made from inside a progress callback of
   * a call on that same context: refused, nothing done (the context is busy with the
   * job that runs the callback).  Make the call after the job returns.               */
  ARCUS_ERROR_REENTRANT = 11,
  /* A result came out NaN or infinite (an image's pixel, ...): no job is returned; the
   * message says which result and where.                                              */
  ARCUS_ERROR_NOT_FINITE = 12
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

/* ---- kernel features -----------------------------------------------------------
 * Every job compiles only the kernel features its scene calls for (Cycles-style
 * coarse bits, one 64-bit word shared by all engines: bits 0-7 are the core's, each
 * engine owns a range, see its header).  arcus_job_get_features tells which.       */
typedef uint64_t arcus_features;
#define ARCUS_FEATURE_FLOAT (UINT64_C(1) << 0) /* single precision; absent: double */

/* Writes the names of the bits in `features` ("DP45 FIELD_LINEAR BOX"), space
 * separated, NUL-terminated.  A bit no engine defines is an error. */
ARCUS_API arcus_status arcus_features_to_string(arcus_features features, char* buffer, size_t size);

/* ---- progress and cancellation ---------------------------------------------------
 * Long jobs run in slices.  After each slice the job's progress callback (if any) is
 * called with the fraction done (0..1, non-decreasing); a non-zero return cancels the
 * job: the call returns ARCUS_ERROR_CANCELLED with a job holding the results so far,
 * the unfinished items flagged ARCUS_RAY_CANCELLED.                                  */
typedef int32_t (*arcus_progress_callback)(void* user, double fraction);

/* ---- jobs ----------------------------------------------------------------------
 * A job is the result of one engine call (arcus_curved_advance, ...): it holds its items'
 * results and how it ran.  Each engine's header has the getters of its results; they
 * reject a job of another engine with ARCUS_ERROR_INVALID_ARGUMENT.                 */
typedef struct arcus_job_s arcus_job_t;

/* Where a job's compiled kernel came from. */
typedef enum arcus_program_origin {
  ARCUS_PROGRAM_BUILT = 0,       /* compiled from source by this call          */
  ARCUS_PROGRAM_MEMORY_CACHE = 1,/* already built in this process              */
  ARCUS_PROGRAM_DISK_CACHE = 2   /* loaded from ARCUS_CACHE_DIR (an earlier process) */
} arcus_program_origin;

typedef struct arcus_job_stats {
  double build_seconds;   /* getting the program: build, or load from the disk cache  */
  double kernel_seconds;  /* device time of the job's kernel launches                 */
  double total_seconds;   /* wall time of the call that made the job                  */
  int32_t program_origin; /* arcus_program_origin                                     */
  uint32_t lanes;         /* items per SIMD group                                     */
  uint32_t groups;        /* independent lane groups per work-item                    */
  uint32_t launches;      /* kernel launches (slices) the job took                    */
} arcus_job_stats;

ARCUS_API arcus_status arcus_job_retain(arcus_job_t* job);
ARCUS_API arcus_status arcus_job_release(arcus_job_t* job);
/* Items (rays, photons, ...) in the job. */
ARCUS_API arcus_status arcus_job_get_count(arcus_job_t* job, size_t* count);
ARCUS_API arcus_status arcus_job_get_features(arcus_job_t* job, arcus_features* features);
ARCUS_API arcus_status arcus_job_get_stats(arcus_job_t* job, arcus_job_stats* stats);

#ifdef __cplusplus
}
#endif
#endif /* ARCUS_CORE_H */
