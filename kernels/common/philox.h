/* Counter-based random numbers: Philox4x32-10 (Salmon, Moraes, Dror & Shaw, "Parallel
 * random numbers: as easy as 1, 2, 3", SC11; the Random123 library).  A number is a pure
 * function of (seed, index, draw), with no state to carry or split, so a result cannot
 * depend on the lane/group layout, the device or how a batch is cut into launches.
 * Shared word for word by the host (C/C++, one item at a time: the reference) and the
 * kernels (ARCUS_LANES items side by side in uintN/ulongN lanes).
 *
 * Stream mapping, the contract (changing it changes every random result):
 *   key     = {seed lo, seed hi}                     the job
 *   counter = {index lo, index hi, draw / 2, 0}      the item (ray/photon), the block
 *   draw d is the 64-bit word w = out[2(d%2)]·2^32 + out[2(d%2)+1] of that block:
 *     double: (w >> 11)·2^-53   53 random bits, in [0, 1 − 2^-53]
 *     float:  (w >> 40)·2^-24   24 random bits, in [0, 1 − 2^-24]
 *   so a float draw is the double draw rounded down to 24 bits: float and double jobs
 *   with one seed make the same random choices up to the float's precision.
 *   Counter word 3 is 0, left free for sub-streams.                                   */
#ifndef ARCUS_PHILOX_H
#define ARCUS_PHILOX_H

#ifndef __OPENCL_C_VERSION__
#include "common/real.h" /* the device source has it prepended */
#endif

#ifdef __OPENCL_C_VERSION__
typedef uint arcus_u32;
typedef ulong arcus_u64;
#else
typedef uint32_t arcus_u32;
typedef uint64_t arcus_u64;
#endif
#define ARCUS_TO_U32(x) ((arcus_u32)(x))
#define ARCUS_TO_U64(x) ((arcus_u64)(x))

/* Salmon et al. 2011 and Random123's philox.h: the multipliers, and the Weyl key
 * increments (golden ratio, sqrt(3) − 1). */
#define ARCUS_PHILOX_M0 0xD2511F53u
#define ARCUS_PHILOX_M1 0xCD9E8D57u
#define ARCUS_PHILOX_W0 0x9E3779B9u
#define ARCUS_PHILOX_W1 0xBB67AE85u

/* `rounds` rounds on the counter c[4] of element type T (arcus_u32, or uintN lanes
 * sharing one key), in place; WIDEN and NARROW convert T to and from its 64-bit kind.
 * One text for every T, so the lanes compute exactly what the scalar reference computes.
 * Random123's round, with (hi, lo) the words of the 64-bit products M0·c0 and M1·c2:
 *   c' = {hi(M1·c2) ^ c1 ^ k0,  lo(M1·c2),  hi(M0·c0) ^ c3 ^ k1,  lo(M0·c0)},
 * the key bumped by (W0, W1) between rounds.  hi is the widened product shifted down,
 * not OpenCL's mul_hi: the same value, but PoCL 3.1's mul_hi measured 3-4x slower, in
 * lanes and in scalars (GPUs not measured).                                          */
#define ARCUS_DEFINE_PHILOX4X32(NAME, T, WIDEN, NARROW)                            \
  ARCUS_INLINE void NAME(int rounds, T* c, arcus_u32 k0, arcus_u32 k1) {           \
    for (int r = 0; r < rounds; ++r) {                                             \
      const T hi0 = NARROW((WIDEN(c[0]) * ARCUS_PHILOX_M0) >> 32);                 \
      const T hi1 = NARROW((WIDEN(c[2]) * ARCUS_PHILOX_M1) >> 32);                 \
      const T lo0 = c[0] * ARCUS_PHILOX_M0, lo1 = c[2] * ARCUS_PHILOX_M1;          \
      c[0] = hi1 ^ c[1] ^ k0;                                                      \
      c[1] = lo1;                                                                  \
      c[2] = hi0 ^ c[3] ^ k1;                                                      \
      c[3] = lo0;                                                                  \
      k0 += ARCUS_PHILOX_W0;                                                       \
      k1 += ARCUS_PHILOX_W1;                                                       \
    }                                                                              \
  }

ARCUS_DEFINE_PHILOX4X32(arcus_philox4x32_rounds, arcus_u32, ARCUS_TO_U64, ARCUS_TO_U32)

/* Philox4x32-R as Random123's philox4x32_R(R, ctr, key): out = f(ctr, key). */
ARCUS_INLINE void arcus_philox4x32_r(int rounds, const arcus_u32 ctr[4], const arcus_u32 key[2], arcus_u32 out[4]) {
  for (int i = 0; i < 4; ++i) out[i] = ctr[i];
  arcus_philox4x32_rounds(rounds, out, key[0], key[1]);
}

/* Philox4x32-10, the paper's and Random123's default: 7 rounds already pass BigCrush,
 * 10 keep a safety margin. */
ARCUS_INLINE void arcus_philox4x32_10(const arcus_u32 ctr[4], const arcus_u32 key[2], arcus_u32 out[4]) {
  arcus_philox4x32_r(10, ctr, key, out);
}

/* The block of four words holding draws 2·block and 2·block + 1 of item `index`. */
ARCUS_INLINE void arcus_rng_block(arcus_u64 seed, arcus_u64 index, arcus_u32 block, arcus_u32 out[4]) {
  out[0] = (arcus_u32)index;
  out[1] = (arcus_u32)(index >> 32);
  out[2] = block;
  out[3] = 0;
  arcus_philox4x32_rounds(10, out, (arcus_u32)seed, (arcus_u32)(seed >> 32));
}

/* Words to [0, 1): exact conversions (the integers are below 2^53 and 2^24), so host
 * and device agree bit for bit; all-ones words give 1 − 2^-53 and 1 − 2^-24, never 1. */
#if !defined(__OPENCL_C_VERSION__) || !defined(ARCUS_USE_FLOAT)
ARCUS_INLINE double arcus_u01_double(arcus_u32 hi, arcus_u32 lo) {
  return (double)(((arcus_u64)hi << 21) | (lo >> 11)) * 0x1.0p-53;
}

/* Draw `draw` of item `index` in job `seed`, as a double. */
ARCUS_INLINE double arcus_rng_uniform_double(arcus_u64 seed, arcus_u64 index, arcus_u32 draw) {
  arcus_u32 w[4];
  arcus_rng_block(seed, index, draw >> 1, w);
  return (draw & 1u) ? arcus_u01_double(w[2], w[3]) : arcus_u01_double(w[0], w[1]);
}
#endif

ARCUS_INLINE float arcus_u01_float(arcus_u32 hi) { return (float)(hi >> 8) * 0x1.0p-24f; }

/* The same draw as a float: the double's value rounded down to 24 bits. */
ARCUS_INLINE float arcus_rng_uniform_float(arcus_u64 seed, arcus_u64 index, arcus_u32 draw) {
  arcus_u32 w[4];
  arcus_rng_block(seed, index, draw >> 1, w);
  return arcus_u01_float((draw & 1u) ? w[2] : w[0]);
}

#ifdef __OPENCL_C_VERSION__
/* ---------------------------------------------------------------- device lanes */
/* A draw in the kernel's precision (REAL). */
ARCUS_INLINE REAL arcus_rng_uniform(ulong seed, ulong index, uint draw) {
#ifdef ARCUS_USE_FLOAT
  return arcus_rng_uniform_float(seed, index, draw);
#else
  return arcus_rng_uniform_double(seed, index, draw);
#endif
}

/* U32V/U64V: a uint/ulong per lane; LANE_OFFSETS: 0, 1, …, ARCUS_LANES − 1. */
#if ARCUS_LANES == 1
#define ARCUS_U32V uint
#define ARCUS_U64V ulong
#define ARCUS_TO_U32V(x) ((uint)(x))
#define ARCUS_TO_U64V(x) ((ulong)(x))
#define ARCUS_U64V_TO_REALV(x) ((REAL)(x))
#define ARCUS_U32V_TO_REALV(x) ((REAL)(x))
#define ARCUS_LANE_OFFSETS ((ulong)0)
#else
#define ARCUS_U32V ARCUS_CAT(uint, ARCUS_LANES)
#define ARCUS_U64V ARCUS_CAT(ulong, ARCUS_LANES)
#define ARCUS_TO_U32V(x) ARCUS_CAT(convert_uint, ARCUS_LANES)(x)
#define ARCUS_TO_U64V(x) ARCUS_CAT(convert_ulong, ARCUS_LANES)(x)
#define ARCUS_U64V_TO_REALV(x) ARCUS_CAT(ARCUS_CAT(convert_, REAL), ARCUS_LANES)(x)
#define ARCUS_U32V_TO_REALV(x) ARCUS_CAT(ARCUS_CAT(convert_, REAL), ARCUS_LANES)(x)
#if ARCUS_LANES == 2
#define ARCUS_LANE_OFFSETS ((ulong2)(0, 1))
#elif ARCUS_LANES == 4
#define ARCUS_LANE_OFFSETS ((ulong4)(0, 1, 2, 3))
#elif ARCUS_LANES == 8
#define ARCUS_LANE_OFFSETS ((ulong8)(0, 1, 2, 3, 4, 5, 6, 7))
#elif ARCUS_LANES == 16
#define ARCUS_LANE_OFFSETS ((ulong16)(0, 1, 2, 3, 4, 5, 6, 7, 8, 9, 10, 11, 12, 13, 14, 15))
#else
#error "ARCUS_LANES must be 1, 2, 4, 8 or 16"
#endif
#endif

ARCUS_DEFINE_PHILOX4X32(arcus_philox4x32_rounds_v, ARCUS_U32V, ARCUS_TO_U64V, ARCUS_TO_U32V)

/* arcus_rng_block for a lane vector of indices (one seed, one block for all lanes). */
ARCUS_INLINE void arcus_rng_block_v(ulong seed, ARCUS_U64V index, uint block, ARCUS_U32V out[4]) {
  out[0] = ARCUS_TO_U32V(index);
  out[1] = ARCUS_TO_U32V(index >> 32);
  out[2] = (ARCUS_U32V)block;
  out[3] = (ARCUS_U32V)0;
  arcus_philox4x32_rounds_v(10, out, (uint)seed, (uint)(seed >> 32));
}

/* Words to REALV in [0, 1), lane by lane the scalar arcus_u01_double/_float. */
ARCUS_INLINE REALV arcus_u01_v(ARCUS_U32V hi, ARCUS_U32V lo) {
#ifdef ARCUS_USE_FLOAT
  return ARCUS_U32V_TO_REALV(hi >> 8) * 0x1.0p-24f;
#else
  return ARCUS_U64V_TO_REALV((ARCUS_TO_U64V(hi) << 21) | ARCUS_TO_U64V(lo >> 11)) * 0x1.0p-53;
#endif
}

/* Draws 2·block and 2·block + 1 of the lanes' items: one Philox call for two numbers. */
ARCUS_INLINE void arcus_rng_uniform2_v(ulong seed, ARCUS_U64V index, uint block, REALV* u0, REALV* u1) {
  ARCUS_U32V w[4];
  arcus_rng_block_v(seed, index, block, w);
  *u0 = arcus_u01_v(w[0], w[1]);
  *u1 = arcus_u01_v(w[2], w[3]);
}

/* Draw `draw` of the lanes' items (half a block wasted: prefer arcus_rng_uniform2_v
 * where draws come in pairs). */
ARCUS_INLINE REALV arcus_rng_uniform_v(ulong seed, ARCUS_U64V index, uint draw) {
  ARCUS_U32V w[4];
  arcus_rng_block_v(seed, index, draw >> 1, w);
  return (draw & 1u) ? arcus_u01_v(w[2], w[3]) : arcus_u01_v(w[0], w[1]);
}
#endif /* __OPENCL_C_VERSION__ */

#endif /* ARCUS_PHILOX_H */
