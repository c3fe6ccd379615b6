/* Batch queries on a triangle BVH (bvh/traverse.h): the closest hit of each segment
 * (tests, benchmarks), and every (query, triangle) pair the rainbow engine asks for.
 * Scalar: one query per work-item, whatever ARCUS_LANES says.  The host prepends
 * common/real.h, bvh/bvh_desc.h and bvh/traverse.h.
 *
 * Segments are 7 REALs each: origin, direction, t_max (the segment o + t·d, t in
 * [0, t_max]); points are 3 REALs. */

__kernel void arcus_bvh_closest(__global const bvh_node* nodes, __global const REAL* tris,
                                __global const REAL* segments, uint count, __global int* slot,
                                __global REAL* tuv /* 3 per segment */, __global int* tests) {
  const size_t i = get_global_id(0);
  if (i >= count) return;
  __global const REAL* s = segments + 7 * i;
  REAL t = 0, u = 0, v = 0;
  int n = 0;
  slot[i] = bvh_segment_closest(nodes, tris, s[0], s[1], s[2], s[3], s[4], s[5], s[6], &t, &u, &v, &n);
  tuv[3 * i] = t;
  tuv[3 * i + 1] = u;
  tuv[3 * i + 2] = v;
  tests[i] = n;
}

ARCUS_INLINE void bvh_emit(__global int* pairs, uint capacity, __global volatile uint* counter, int query,
                           int primitive) {
  const uint k = atomic_inc(counter);
  if (k < capacity) {
    pairs[2 * (size_t)k] = query;
    pairs[2 * (size_t)k + 1] = primitive;
  }
}

/* Writes (query, order[slot]) for every triangle the segment hits (points == 0) or whose
 * bounding box contains the point (points != 0) into pairs[2·k], k from the atomic
 * counter.  Pairs past `capacity` are not written but still counted, so the host sees
 * an overflow and the size it needs. */
__kernel void arcus_bvh_all_hits(__global const bvh_node* nodes, __global const REAL* tris,
                                 __global const int* order, __global const REAL* queries, uint count, int points,
                                 __global int* pairs, uint capacity, __global volatile uint* counter) {
  const size_t i = get_global_id(0);
  if (i >= count) return;
  bvh_walk w;
  int s;
  if (points) {
    const REAL p[3] = {queries[3 * i], queries[3 * i + 1], queries[3 * i + 2]};
    bvh_walk_start(&w, nodes, bvh_node_overlaps(nodes, p, p));
    while ((s = bvh_box_next(nodes, tris, p, p, &w)) >= 0) bvh_emit(pairs, capacity, counter, (int)i, order[s]);
  } else {
    __global const REAL* q = queries + 7 * i;
    bvh_ray r;
    bvh_ray_init(&r, q[0], q[1], q[2], q[3], q[4], q[5]);
    REAL near, t, u, v;
    int tests = 0;
    bvh_walk_start(&w, nodes, bvh_ray_box(&r, nodes, q[6], &near));
    while ((s = bvh_segment_next(nodes, tris, &r, q[6], &w, &t, &u, &v, &tests)) >= 0)
      bvh_emit(pairs, capacity, counter, (int)i, order[s]);
  }
}
