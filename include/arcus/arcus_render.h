/*
 * arcus rendering through curved light (thesis §4.1.6, §4.3, §5.4.2): scenes of
 * triangle meshes, spheres and discs seen by a pinhole camera through a medium whose
 * index of refraction bends every ray, lit by suns and point lights (shadow rays are
 * curved too), optionally by a curved photon map, in RGB or over wavelengths.
 * Include arcus.h.
 *
 * Render scenes are scene files with a "camera" (scenes/README.md, "Render scenes"),
 * loaded with arcus_scene_load (engine "render").  A renderer draws frames of a scene;
 * it keeps what one frame leaves for the next (cached paths, the hit steps smart step
 * selection predicts from), so it belongs to one thread at a time like every object of
 * its context (arcus_core.h).
 */
#ifndef ARCUS_RENDER_H
#define ARCUS_RENDER_H

#include "arcus_core.h"
#include "arcus_curved.h"
#include "arcus_scene.h"

#ifdef __cplusplus
extern "C" {
#endif

/* The thesis' optimizations (§4.3.2–4.3.4), any set of them; parallel execution is the
 * OpenCL execution itself and always on.
 *   SMART_STEP   predict each ray's hit step from its neighbours and from the previous
 *                frame; the skipped steps are proved empty, so the hits are exactly
 *                the exhaustive scan's (photons: the angular form, t = 3°)
 *   SYMMETRY     trace half the image and mirror the paths for a medium symmetric
 *                about the camera's vertical plane (refused, with the reason, otherwise)
 *   UNDERSAMPLE  interpolate a fraction of the paths (α = ½) from traced neighbours
 *   PATH_CACHE   keep every path's net points while the camera rests; later frames
 *                only intersect them again                                          */
#define ARCUS_TECHNIQUE_SMART_STEP (1u << 0)
#define ARCUS_TECHNIQUE_SYMMETRY (1u << 1)
#define ARCUS_TECHNIQUE_UNDERSAMPLE (1u << 2)
#define ARCUS_TECHNIQUE_PATH_CACHE (1u << 3)
#define ARCUS_TECHNIQUE_ALL (ARCUS_TECHNIQUE_SMART_STEP | ARCUS_TECHNIQUE_SYMMETRY | \
                             ARCUS_TECHNIQUE_UNDERSAMPLE | ARCUS_TECHNIQUE_PATH_CACHE)

/* Kernel features of render jobs: bits 24-31 of arcus_features. */
#define ARCUS_FEATURE_RENDER_GEOMETRY (UINT64_C(1) << 24)     /* rays stop on the scene's primitives */
#define ARCUS_FEATURE_RENDER_RECORD_STATE (UINT64_C(1) << 25) /* paths keep the whole state (cache) */

typedef struct arcus_renderer_s arcus_renderer_t;

/* A renderer of `scene` (which it keeps a reference to), with the scene's camera,
 * integrator and default techniques. */
ARCUS_API arcus_status arcus_renderer_create(arcus_scene_t* scene, arcus_renderer_t** out);
ARCUS_API arcus_status arcus_renderer_retain(arcus_renderer_t* renderer);
ARCUS_API arcus_status arcus_renderer_release(arcus_renderer_t* renderer);

/* A set of ARCUS_TECHNIQUE_* bits.  SYMMETRY for a scene whose medium is not symmetric
 * about the camera's vertical plane is ARCUS_ERROR_UNSUPPORTED with the reason. */
ARCUS_API arcus_status arcus_renderer_set_techniques(arcus_renderer_t* renderer, uint32_t techniques);
ARCUS_API arcus_status arcus_renderer_get_techniques(arcus_renderer_t* renderer, uint32_t* techniques);
/* Moving the camera drops the path cache and the previous frame. */
ARCUS_API arcus_status arcus_renderer_set_camera(arcus_renderer_t* renderer, const arcus_camera* camera);
ARCUS_API arcus_status arcus_renderer_get_camera(arcus_renderer_t* renderer, arcus_camera* camera);
/* The integrator of primary and shadow rays (method, tolerances, steps; the box and
 * the length are the scene's); changing it drops the cache and the previous frame. */
ARCUS_API arcus_status arcus_renderer_set_integrator(arcus_renderer_t* renderer, const arcus_advance_params* params);
ARCUS_API arcus_status arcus_renderer_get_integrator(arcus_renderer_t* renderer, arcus_advance_params* params);

/* Renders one frame into a new job (arcus_job_get_stats: its device time; the calls
 * below: its image and figures).  `progress` (may be NULL) sees the frame's fraction
 * done and may cancel it (ARCUS_ERROR_CANCELLED, no job). */
ARCUS_API arcus_status arcus_render_frame(arcus_renderer_t* renderer, arcus_progress_callback progress, void* user,
                                          arcus_job_t** job);

/* Per-stage figures of a render job. */
typedef struct arcus_render_stats {
  double trace_seconds;   /* integrating paths (with their per-step tests) */
  double walk_seconds;    /* intersecting cached, mirrored and interpolated paths */
  double photon_seconds;  /* shooting photons and building the photon map */
  double shade_seconds;   /* shadow rays, sky, radiance estimates, the image */
  double total_seconds;
  uint64_t pixels;
  uint64_t rays_traced;       /* paths integrated (primary rays) */
  uint64_t rays_mirrored;     /* SYMMETRY */
  uint64_t rays_interpolated; /* UNDERSAMPLE */
  uint64_t rays_cached;       /* PATH_CACHE: paths reused from the last frame */
  uint64_t rays_unresolved;   /* walked past a path cut short by a hit: traced instead */
  uint64_t steps;             /* integrator steps of primary rays */
  uint64_t tests;             /* intersection tests of primary rays */
  uint64_t shadow_rays;
  uint64_t photons;           /* stored in the photon map */
  uint64_t cache_bytes;       /* device memory the path cache holds */
  uint32_t techniques;        /* what this frame used */
} arcus_render_stats;
ARCUS_API arcus_status arcus_job_get_render_stats(arcus_job_t* job, arcus_render_stats* stats);

ARCUS_API arcus_status arcus_job_get_render_image_size(arcus_job_t* job, uint32_t* width, uint32_t* height);
/* Linear RGB radiance, width × height × 3 floats, top row first (spectral scenes:
 * converted through the CIE 1931 colour-matching functions to linear sRGB). */
ARCUS_API arcus_status arcus_job_get_render_image(arcus_job_t* job, float* rgb);
/* Per pixel (any pointer may be NULL): the primary ray's hit point (× 3; NaN for
 * none), the object hit (its index in the scene's "objects", -1 for none) and the
 * primitive within it (triangle index, 0 for a sphere or disc), the arc length to the
 * hit (or to where the ray left the scene), its integrator steps and intersection
 * tests.  Spectral scenes: the figures of the first wavelength. */
ARCUS_API arcus_status arcus_job_get_render_hits(arcus_job_t* job, double* points, int32_t* objects, int32_t* primitives,
                                                 double* distances, uint32_t* steps, uint32_t* tests);
/* Writes the image: an OpenEXR file (linear RGB, plus the channels "distance",
 * "steps" and "tests") and/or a PNG (sRGB, the scene's exposure); either path may be
 * NULL. */
ARCUS_API arcus_status arcus_job_write_render_image(arcus_job_t* job, const char* exr_path, const char* png_path);

/* ---- spellings before arcus 0.10 (removed in 0.11; arcus_core.h, "Names") ----------- */
#ifndef ARCUS_NO_DEPRECATED
#define ARCUS_FEATURE_GEOMETRY ARCUS_FEATURE_RENDER_GEOMETRY
#define ARCUS_FEATURE_RECORD_STATE ARCUS_FEATURE_RENDER_RECORD_STATE
ARCUS_DEPRECATED("arcus_job_get_render_image_size")
ARCUS_API arcus_status arcus_job_get_image_size(arcus_job_t* job, uint32_t* width, uint32_t* height);
ARCUS_DEPRECATED("arcus_job_get_render_image")
ARCUS_API arcus_status arcus_job_get_image(arcus_job_t* job, float* rgb);
ARCUS_DEPRECATED("arcus_job_get_render_hits")
ARCUS_API arcus_status arcus_job_get_hits(arcus_job_t* job, double* points, int32_t* objects, int32_t* primitives,
                                          double* distances, uint32_t* steps, uint32_t* tests);
ARCUS_DEPRECATED("arcus_job_write_render_image")
ARCUS_API arcus_status arcus_job_write_image(arcus_job_t* job, const char* exr_path, const char* png_path);
#endif

#ifdef __cplusplus
}
#endif
#endif /* ARCUS_RENDER_H */
