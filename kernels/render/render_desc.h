/* What the rendering engine's per-step hook (render/hits.h) and the host share: the
 * analytic shapes, the geometry description passed by value, and the per-ray hit
 * record kept on the device between slices (see field.h for why structs are macros). */
#ifndef ARCUS_RENDER_DESC_H
#define ARCUS_RENDER_DESC_H

#ifndef __OPENCL_C_VERSION__
#include "common/real.h" /* the device source has it prepended */
#endif

/* Internal ray status codes beyond advance_desc.h's (render jobs only). */
#define ARCUS_STATUS_HIT 7        /* stopped on a primitive: the end state is the hit   */
#define ARCUS_STATUS_UNRESOLVED 8 /* a walk reached the end of a path that ended on a
                                   * hit, without a hit of its own: trace it instead  */

/* Kinds of hit. */
#define ARCUS_HIT_NONE 0
#define ARCUS_HIT_TRIANGLE 1 /* index: the triangle's slot in the BVH's leaf order     */
#define ARCUS_HIT_SHAPE 2    /* index: the shape's position in the shape array         */

/* Analytic shapes: spheres (the Earth, a sun 1.5e11 m away) and discs (ground). */
#define ARCUS_SHAPE_SPHERE 0
#define ARCUS_SHAPE_DISC 1
#define ARCUS_MAX_SHAPES 64

#define ARCUS_DECLARE_SHAPE(NAME, R, I)                                             \
  typedef struct NAME {                                                             \
    R center[3];                                                                    \
    R normal[3]; /* disc: unit normal                                           */ \
    R radius;                                                                       \
    I kind;      /* ARCUS_SHAPE_*                                               */  \
    I pad;                                                                          \
  } NAME

#define ARCUS_DECLARE_GEOMETRY_DESC(NAME, R, I)                                     \
  typedef struct NAME {                                                             \
    I shape_count;                                                                  \
    I triangle_count; /* 0: no BVH to traverse                                   */ \
    I max_tests;      /* bound on the tests counter (saturates)                  */ \
    I occlusion;      /* 1: a hit only stops the ray, where its chord hit (shadow \
                       * rays toward a sun ask "blocked?", not where)           */ \
    I from_surface;   /* 1: the rays leave a surface (shadow rays): smart step   \
                       * selection tests their first chord alone (hits.h, peel) */ \
    I pad;                                                                          \
  } NAME

/* The hit record, integers (stride entries per component, like the ray state): */
#define ARCUS_HIT_KIND 0    /* ARCUS_HIT_*                                           */
#define ARCUS_HIT_INDEX 1   /* triangle slot or shape index                          */
#define ARCUS_HIT_TESTS 2   /* intersection tests (segments and proofs) this ray made */
#define ARCUS_HIT_PREDICT 3 /* smart step selection: the predicted hit step, -1: none;
                             * set to -1 once the skipped steps are proved empty      */
#define ARCUS_HIT_STEP 4    /* the step (segment index) that hit                      */
#define ARCUS_HIT_INTS 5

#ifdef __OPENCL_C_VERSION__
ARCUS_DECLARE_SHAPE(shape, REAL, int);
ARCUS_DECLARE_GEOMETRY_DESC(geometry_desc, REAL, int);
#else
ARCUS_DECLARE_SHAPE(arcus_shape_d, double, int32_t);
ARCUS_DECLARE_SHAPE(arcus_shape_f, float, int32_t);
ARCUS_DECLARE_GEOMETRY_DESC(arcus_geometry_desc, double, int32_t);
#endif

/* The walk's arguments, X(type, name) (ARCUS_PARAMS; src/core/launch.h; walk.cl says
 * what they hold), and those of the capsules' proofs. */
#define ARCUS_WALK_ARGS(X)                \
  X(__global const REAL*, paths)          \
  X(const int, slots)                     \
  X(__global const int*, counts)          \
  X(__global const int*, end_status)      \
  X(__global const int*, rays)            \
  X(const int, ray_count)                 \
  X(const REAL4, plane4)                  \
  X(__global const REAL*, wavelengths)    \
  X(__global REAL*, out)                  \
  X(__global int*, out_status)            \
  X(__global const REAL*, radii)          \
  X(const int, chunks)                    \
  ARCUS_FIELD_JOB_ARGS(X)                 \
  ARCUS_GEOMETRY_ARGS(X)
#define ARCUS_PATH_CAPSULES_ARGS(X) \
  X(__global const REAL*, paths)    \
  X(const int, slots)               \
  X(__global const int*, counts)    \
  X(const int, count)               \
  X(const int, chunks)              \
  X(const int, per_item)            \
  X(__global REAL*, radii)

#endif /* ARCUS_RENDER_DESC_H */
