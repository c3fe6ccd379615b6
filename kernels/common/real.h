/* Number types for code shared by the host (C++, one double at a time) and the device
 * (OpenCL C, ARCUS_LANES items side by side in vector lanes).
 *
 * Why lanes: PoCL does not vectorise across work-items when the kernel body holds a
 * loop (a ray's step loop): such a kernel runs scalar, only twice as fast as one C++
 * thread.  So the CPU kernels hold several items per work-item in doubleN vectors, and
 * each work-item several independent groups of them to hide latency; on a GPU
 * ARCUS_LANES is 1 and the same code is one item per work-item (README, "Kernels").
 *
 *   REAL   scalar real (double, or float with ARCUS_USE_FLOAT)
 *   REALV  ARCUS_LANES reals;  MASKV the result of comparing two REALV;
 *   IDXV   an integer per lane, the same width as MASKV
 *   SEL(a, b, m)  b where m holds, else a;   ANY(m)  whether m holds in some lane
 *   RC(x)  a literal in REAL precision
 *   VLOAD/VSTORE       REALV from/to a __global REAL array, lane group i
 *   VLOAD_I/VSTORE_I   IDXV from/to a __global int array, lane group i
 */
#ifndef ARCUS_REAL_H
#define ARCUS_REAL_H

#ifdef __OPENCL_C_VERSION__
/* ---------------------------------------------------------------- device */
#ifndef ARCUS_USE_FLOAT
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
#define VLOAD_I(i, p) ((IDXV)(p)[i])
#define VSTORE_I(v, i, p) ((p)[i] = (int)(v))
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
#define VLOAD_I(i, p) ARCUS_CAT(ARCUS_CAT(convert_, IDX), ARCUS_LANES)(ARCUS_CAT(vload, ARCUS_LANES)((i), (p)))
#define VSTORE_I(v, i, p) ARCUS_CAT(vstore, ARCUS_LANES)(ARCUS_CAT(convert_int, ARCUS_LANES)(v), (i), (p))
#define FLOATV ARCUS_CAT(float, ARCUS_LANES)
#define TO_FLOATV(x) ARCUS_CAT(convert_float, ARCUS_LANES)(x)
#define TO_REALV(x) ARCUS_CAT(ARCUS_CAT(convert_, REAL), ARCUS_LANES)(x)
#endif
#define RC(x) ((REAL)(x))
#define ARCUS_INLINE static inline __attribute__((always_inline)) /* PoCL left big helpers out of line */
#define ARCUS_GLOBAL __global

/* A kernel's parameters, "type name, ...", from its argument list: an X-macro of
 * X(type, name) in its *_desc.h, whose names the host binds by (src/core/launch.h). */
#define ARCUS_PARAM_(type, name) , type name
#define ARCUS_REST_(first, ...) __VA_ARGS__
#define ARCUS_REST(...) ARCUS_REST_(__VA_ARGS__)
#define ARCUS_PARAMS(LIST) ARCUS_REST(LIST(ARCUS_PARAM_))

/* The groups of a work-item advance in lockstep, one stage at a time for all of them,
 * so each stage offers ARCUS_GROUPS independent dependency chains to the core (a single
 * chain is latency-bound: measured 3× slower).  FOR_N loops over the first n groups
 * (n a constant after inlining, so fully unrolled). */
#define FOR_N(g, n) _Pragma("unroll") for (int g = 0; g < (n); ++g)
#define FOR_GROUPS(g) FOR_N(g, ARCUS_GROUPS)

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
