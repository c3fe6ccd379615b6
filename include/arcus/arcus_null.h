/*
 * arcus null engine: a constant-colour engine that exists only to show, and test, that
 * an engine plugs into the core alone (docs/adding-an-engine.md).  Built with
 * -DARCUS_WITH_NULL_ENGINE=ON; tests/test_null_engine.cpp is its only user.  Include
 * this header itself: arcus.h does not, and it is not installed.
 */
#ifndef ARCUS_NULL_H
#define ARCUS_NULL_H

#include "arcus_core.h"

#ifdef __cplusplus
extern "C" {
#endif

/* Its one kernel feature (bits 56-63 are the null engine's). */
#define ARCUS_FEATURE_NULL_FILL (UINT64_C(1) << 56)

/* A swatch: one linear RGB colour (finite, >= 0), the engine's only object. */
typedef struct arcus_swatch_s arcus_swatch_t;
ARCUS_API arcus_status arcus_swatch_create(arcus_context_t* ctx, const float rgb[3], arcus_swatch_t** out);
ARCUS_API arcus_status arcus_swatch_retain(arcus_swatch_t* swatch);
ARCUS_API arcus_status arcus_swatch_release(arcus_swatch_t* swatch);

/* An image of width × height pixels (each 1..4096), every one the swatch's colour,
 * filled on the device. */
ARCUS_API arcus_status arcus_null_fill(arcus_swatch_t* swatch, uint32_t width, uint32_t height, arcus_job_t** job);
/* The image: width × height × 3 floats, top row first. */
ARCUS_API arcus_status arcus_job_get_null_image(arcus_job_t* job, float* rgb);

#ifdef __cplusplus
}
#endif
#endif /* ARCUS_NULL_H */
