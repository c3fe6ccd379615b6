/* Number types for code shared by the host (C++, one double at a time) and the device
 * (OpenCL C, ARCUS_LANES rays side by side in vector lanes).
 *
 * Why lanes: PoCL does not vectorise across work-items when the kernel body holds a
 * loop (a ray's step loop), so the CPU kernels hold several rays per work-item in
 * doubleN vectors; on a GPU ARCUS_LANES is 1 and the same code is one ray per
 * work-item (../shared/notes/opencl-on-pocl.md).
 *
 *   REAL   scalar real (double, or float with ARCUS_FEATURE_FLOAT)
 *   REALV  ARCUS_LANES reals;  MASKV the result of comparing two REALV;
 *   IDXV   an integer per lane, the same width as MASKV
 *   SEL(a, b, m)  b where m holds, else a;   ANY(m)  whether m holds in some lane
 *   RC(x)  a literal in REAL precision
 */
#ifndef ARCUS_REAL_H
#define ARCUS_REAL_H

#ifdef __OPENCL_C_VERSION__
/* ---------------------------------------------------------------- device */
#ifndef ARCUS_FEATURE_FLOAT
#pragma OPENCL EXTENSION cl_khr_fp64 : enable
#define REAL double
#define IDX long
#else
#define REAL float
#define IDX int
#endif
#define ARCUS_CAT_(a, b) a##b
#define ARCUS_CAT(a, b) ARCUS_CAT_(a, b)
#if ARCUS_LANES == 1
#define REALV REAL
#define IDXV IDX
#define MASKV int
#define SEL(a, b, m) ((m) ? (b) : (a))
#define ANY(m) (m)
#define ONE_IF(m) ((IDXV)(m))
#define VLOAD(i, p) ((p)[i])
#define VSTORE(v, i, p) ((p)[i] = (v))
#define VSTORE_IDX(v, i, p) ((p)[i] = (v))
#define FLOATV float
#define TO_FLOATV(x) ((float)(x))
#define TO_REALV(x) ((REAL)(x))
#else
#define REALV ARCUS_CAT(REAL, ARCUS_LANES)
#define IDXV ARCUS_CAT(IDX, ARCUS_LANES)
#define MASKV IDXV
#define SEL(a, b, m) select((a), (b), (m))
#define ANY(m) any(m)
#define ONE_IF(m) (-(m)) /* vector comparisons give -1 for true */
#define VLOAD(i, p) ARCUS_CAT(vload, ARCUS_LANES)((i), (p))
#define VSTORE(v, i, p) ARCUS_CAT(vstore, ARCUS_LANES)((v), (i), (p))
#define VSTORE_IDX(v, i, p) ARCUS_CAT(vstore, ARCUS_LANES)((v), (i), (p))
#define FLOATV ARCUS_CAT(float, ARCUS_LANES)
#define TO_FLOATV(x) ARCUS_CAT(convert_float, ARCUS_LANES)(x)
#define TO_REALV(x) ARCUS_CAT(ARCUS_CAT(convert_, REAL), ARCUS_LANES)(x)
#endif
#define RC(x) ((REAL)(x))
#define ARCUS_INLINE inline __attribute__((always_inline)) /* PoCL left big helpers out of line */
#define ARCUS_GLOBAL __global

#else
/* ---------------------------------------------------------------- host */
#include <math.h>
#include <stdint.h>
#define REAL double
#define REALV double
#define IDX int64_t
#define IDXV int64_t
#define MASKV int
#define SEL(a, b, m) ((m) ? (b) : (a))
#define ANY(m) (m)
#define RC(x) ((double)(x))
#define ARCUS_INLINE static inline
#define ARCUS_GLOBAL
#endif

#endif /* ARCUS_REAL_H */
