/* What the advance kernel and the host share, declared once for both: the job
 * description passed by value, the per-ray status and failure codes, and the layout
 * of the ray state kept on the device between slices (see ARCUS_DECLARE_FIELD_DESC in
 * field.h for why the structs are macros).                                           */
#ifndef ARCUS_ADVANCE_DESC_H
#define ARCUS_ADVANCE_DESC_H

#ifndef __OPENCL_C_VERSION__
#include "common/real.h" /* the device source has it prepended */
#endif

/* Per-ray status codes: the values of arcus_ray_status in arcus_curved.h. */
#define ARCUS_STATUS_DONE 0
#define ARCUS_STATUS_LEFT_BOX 1
#define ARCUS_STATUS_STEP_LIMIT 2
#define ARCUS_STATUS_FAILED 3
#define ARCUS_STATUS_INVALID_INPUT 4
#define ARCUS_STATUS_CANCELLED 5 /* host only: set on the rays a cancelled job left     */
#define ARCUS_STATUS_ACTIVE 6    /* still advancing                                      */

/* Why a ray failed: the values of arcus_ray_failure. */
#define ARCUS_FAIL_NONE 0
#define ARCUS_FAIL_TOLERANCE 1
#define ARCUS_FAIL_NOT_FINITE 2
#define ARCUS_FAIL_INDEX_NOT_POSITIVE 3

/* Ray buffers are structures of arrays, `stride` entries per component, so a lane
 * group loads with one vector load.  The input: */
#define ARCUS_IN_COMPONENTS 6 /* x y z dx dy dz (wavelengths are a buffer of their own) */
/* The state, kept on the device from slice to slice and read back at the end.  Reals: */
#define ARCUS_STATE_X 0       /* x y z vx vy vz: r and v = n·dr/ds                       */
#define ARCUS_STATE_S 6       /* arc length travelled                                   */
#define ARCUS_STATE_H 7       /* DP45: the next trial step                              */
#define ARCUS_STATE_COMP 8    /* float only: 6 Kahan compensations of x..vz             */
#define ARCUS_STATE_REALS_DOUBLE 8
#define ARCUS_STATE_REALS_FLOAT 14
/* ... and integers: */
#define ARCUS_STATE_STEPS 0      /* accepted steps                                      */
#define ARCUS_STATE_STATUS 1     /* status | failure << 8                               */
#define ARCUS_STATE_REJECTIONS 2 /* DP45: consecutive rejections                        */
#define ARCUS_STATE_POINTS 3     /* path points so far (more than kept on overflow)     */
#define ARCUS_STATE_INTS 4
#define ARCUS_FAILURE_SHIFT 8

#define ARCUS_DECLARE_ADVANCE_DESC(NAME, R, I)                                           \
  typedef struct NAME {                                                                  \
    R length;                                                                            \
    R step;        /* fixed step, or DP45's first trial step (0: automatic)     */       \
    R rtol;                                                                              \
    R atol;                                                                              \
    R min_step;                                                                          \
    R max_step;                                                                          \
    R box_min[3];                                                                        \
    R box_max[3];                                                                        \
    R cross_tol;   /* how close to the box a crossing must end (metres)          */       \
    R last_step;   /* the fixed-step path's last, shortened step                */       \
    I fixed_steps; /* steps of a fixed-step path (then the status is final)      */       \
    I max_steps;                                                                         \
    I max_rejections;                                                                    \
    I path_capacity;                                                                     \
    I stride;      /* entries per component of the ray buffers               */          \
    I first_slice; /* 1: start the rays from the input; 0: resume the state  */          \
    I slice_begin; /* fixed steps: the steps [slice_begin, slice_end) of this slice */   \
    I slice_end;   /* DP45: at most slice_end attempts in this slice           */        \
  } NAME

#ifdef __OPENCL_C_VERSION__
ARCUS_DECLARE_ADVANCE_DESC(advance_desc, REAL, int);
#else
ARCUS_DECLARE_ADVANCE_DESC(arcus_advance_desc_d, double, int32_t);
ARCUS_DECLARE_ADVANCE_DESC(arcus_advance_desc_f, float, int32_t);
#endif

/* The advance kernel's arguments, X(type, name) (ARCUS_PARAMS; src/core/launch.h): the
 * rays, their wavelengths (NULL: none), the state and the recorded paths, then the
 * field and the job, as the renderer's walk takes them too, then the geometry. */
#define ARCUS_ADVANCE_ARGS(X)          \
  X(__global const REAL*, rays_in)     \
  X(__global const REAL*, wavelengths) \
  X(__global REAL*, state)             \
  X(__global int*, istate)             \
  X(__global REAL*, path)              \
  ARCUS_FIELD_JOB_ARGS(X)              \
  ARCUS_GEOMETRY_ARGS(X)
#define ARCUS_FIELD_JOB_ARGS(X)          \
  X(const field_desc, field)             \
  X(__global const REAL*, field_data)    \
  X(const advance_desc, job)
/* The renderer's per-step hook (ARCUS_USE_GEOMETRY, render/hits.h): the scene
 * (bvh/bvh_desc.h, render/render_desc.h), each ray's hit record, and the predicted hit
 * steps of smart step selection (NULL: none).  The host knows them always. */
#if defined(ARCUS_USE_GEOMETRY) || !defined(__OPENCL_C_VERSION__)
#define ARCUS_GEOMETRY_ARGS(X)         \
  X(__global const bvh_node*, nodes)   \
  X(__global const REAL*, tris)        \
  X(__global const shape*, shapes)     \
  X(const geometry_desc, geo)          \
  X(__global int*, hit_ints)           \
  X(__global const int*, predictions)
#else
#define ARCUS_GEOMETRY_ARGS(X)
#endif

#endif /* ARCUS_ADVANCE_DESC_H */
