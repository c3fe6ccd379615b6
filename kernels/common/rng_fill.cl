/* Test and benchmark kernel for common/philox.h: fills out[(index − first_index)·draws + d]
 * with draw d of item index, for the `count` items from first_index, in REAL precision.
 * Layout as in advance.cl: work-item i holds ARCUS_GROUPS groups of ARCUS_LANES
 * consecutive items, items first_index + (i·ARCUS_GROUPS + g)·ARCUS_LANES + lane; the
 * groups compute side by side so the core has independent multiply chains to overlap.
 * The host prepends common/real.h and common/philox.h.                                  */


/* Writes draw d of the lanes' items, items rel.. of the batch, skipping those past count.
 * The output is item-major, so lanes are `draws` apart: one lane at a time. */
ARCUS_INLINE void rng_store(__global REAL* out, ulong rel, uint count, uint draws, uint d, REALV u) {
  REAL s[ARCUS_LANES];
  VSTORE(u, 0, s);
  for (int l = 0; l < ARCUS_LANES; ++l)
    if (rel + l < count) out[(rel + l) * draws + d] = s[l];
}

__kernel void arcus_rng_fill(ulong seed, ulong first_index, uint draws, uint count, __global REAL* out) {
  ulong rel[ARCUS_GROUPS]; /* the group's first item, counted from first_index */
  ARCUS_U64V index[ARCUS_GROUPS];
  FOR_GROUPS(g) {
    rel[g] = ((ulong)get_global_id(0) * ARCUS_GROUPS + g) * ARCUS_LANES;
    index[g] = first_index + rel[g] + ARCUS_LANE_OFFSETS; /* mod 2^64, as on the host */
  }
  if (rel[0] >= count) return;
  const uint blocks = draws / 2 + (draws & 1u); /* two draws per Philox block */
  for (uint b = 0; b < blocks; ++b) {
    REALV u0[ARCUS_GROUPS], u1[ARCUS_GROUPS];
    FOR_GROUPS(g) arcus_rng_uniform2_v(seed, index[g], b, &u0[g], &u1[g]);
    FOR_GROUPS(g) {
      rng_store(out, rel[g], count, draws, 2 * b, u0[g]);
      if (2 * b + 1 < draws) rng_store(out, rel[g], count, draws, 2 * b + 1, u1[g]);
    }
  }
}
