/* The job description the advance kernel receives by value; declared once for host
 * and device (see ARCUS_DECLARE_FIELD_DESC for why it is a macro).                   */
#ifndef ARCUS_ADVANCE_H
#define ARCUS_ADVANCE_H

#ifndef __OPENCL_C_VERSION__
#include "arcus_real.h" /* the device source has it prepended */
#endif

/* Per-ray status codes: the values of arcus_ray_status in arcus.h. */
#define ARCUS_STATUS_DONE 0
#define ARCUS_STATUS_LEFT_BOX 1
#define ARCUS_STATUS_STEP_LIMIT 2
#define ARCUS_STATUS_FAILED 3
#define ARCUS_STATUS_INVALID_INPUT 4
#define ARCUS_STATUS_ACTIVE 5 /* device only: still advancing */

/* Ray buffers are structures of arrays, `stride` entries per component, so a lane
 * group loads with one vector load. */
#define ARCUS_IN_COMPONENTS 6  /* x y z dx dy dz        */
#define ARCUS_OUT_COMPONENTS 7 /* x y z dx dy dz length */

#define ARCUS_DECLARE_ADVANCE_DESC(NAME, R, I) \
  typedef struct NAME {                        \
    R length;                                  \
    R step;                                    \
    R rtol;                                    \
    R atol;                                    \
    R min_step;                                \
    R max_step;                                \
    R box_min[3];                              \
    R box_max[3];                              \
    R last_step;                               \
    I fixed_steps;                             \
    I max_steps;                               \
    I max_rejections;                          \
    I path_capacity;                           \
    I stride;                                  \
  } NAME

#ifdef __OPENCL_C_VERSION__
ARCUS_DECLARE_ADVANCE_DESC(advance_desc, REAL, int);
#else
ARCUS_DECLARE_ADVANCE_DESC(arcus_advance_desc_d, double, int32_t);
ARCUS_DECLARE_ADVANCE_DESC(arcus_advance_desc_f, float, int32_t);
#endif

#endif /* ARCUS_ADVANCE_H */
