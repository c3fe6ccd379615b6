/* The photon map on the device: k-nearest-neighbour search over the map's BVH and the
 * radiance estimate built on it (Jensen's photon map; thesis §4.3.4 for the curved
 * variant, where photons are stored along bent paths but gathered the same way).
 *
 * One query per work-item, scalar: a traversal's branches differ from query to query,
 * so lanes would mostly idle.  The photons within the search radius are collected in
 * the caller's private arrays and the k nearest selected from them (photon_knn);
 * subtrees whose box lies farther are skipped.  Ties are broken by slot, so the result
 * is "the k smallest (distance², slot)" whatever the traversal order.
 *
 * Another kernel uses it by prepending common/real.h, bvh/bvh_desc.h,
 * photon/photon_desc.h and this file, taking the map's nodes, photons and
 * photon_map_desc as arguments (src/photon/photon_map.h says in which order the host
 * wrapper passes them), and calling photon_knn or photon_estimate.                    */
#ifndef ARCUS_PHOTON_MAP_H
#define ARCUS_PHOTON_MAP_H

/* Component c (ARCUS_PHOTON_*) of the photon in `slot`. */
#define PHOTON(photons, map, c, slot) ((photons)[(size_t)(c) * (size_t)(map).count + (size_t)(slot)])

/* Distance² from (x, y, z) to a node's box: 0 inside. */
ARCUS_INLINE REAL photon_box_d2(__global const bvh_node* n, REAL x, REAL y, REAL z) {
  const REAL dx = fmax(fmax(n->lo[0] - x, x - n->hi[0]), RC(0));
  const REAL dy = fmax(fmax(n->lo[1] - y, y - n->hi[1]), RC(0));
  const REAL dz = fmax(fmax(n->lo[2] - z, z - n->hi[2]), RC(0));
  return dx * dx + dy * dy + dz * dz;
}

/* Whether (da, sa) comes after (db, sb): the order of the search's results. */
ARCUS_INLINE int photon_after(REAL da, int sa, REAL db, int sb) { return da > db || (da == db && sa > sb); }

/* Adds (d, s) to the max-heap of n entries. */
ARCUS_INLINE void photon_heap_push(REAL* d2, int* slot, int n, REAL d, int s) {
  int i = n;
  while (i > 0) {
    const int parent = (i - 1) / 2;
    if (!photon_after(d, s, d2[parent], slot[parent])) break;
    d2[i] = d2[parent];
    slot[i] = slot[parent];
    i = parent;
  }
  d2[i] = d;
  slot[i] = s;
}

/* Replaces the top of the max-heap of n entries with (d, s), which comes before it. */
ARCUS_INLINE void photon_heap_replace_top(REAL* d2, int* slot, int n, REAL d, int s) {
  int i = 0;
  for (;;) {
    const int l = 2 * i + 1, r = l + 1;
    if (l >= n) break;
    int c = l;
    if (r < n && photon_after(d2[r], slot[r], d2[l], slot[l])) c = r;
    if (!photon_after(d2[c], slot[c], d, s)) break;
    d2[i] = d2[c];
    slot[i] = slot[c];
    i = c;
  }
  d2[i] = d;
  slot[i] = s;
}

/* Sorts n entries into ascending (distance², slot) order, in place (heap sort). */
ARCUS_INLINE void photon_sort(REAL* d2, int* slot, int n) {
  for (int i = 1; i < n; ++i) photon_heap_push(d2, slot, i, d2[i], slot[i]);
  for (int m = n - 1; m > 0; --m) {
    const REAL d = d2[m];
    const int s = slot[m];
    d2[m] = d2[0];
    slot[m] = slot[0];
    photon_heap_replace_top(d2, slot, m, d, s);
  }
}

/* Reorders d2[]/slot[] (n entries) so that entry `at` holds the (at+1)-th smallest
 * (distance², slot), the ones before it smaller and the ones after it larger
 * (Hoare's selection, the middle entry as pivot; expected O(n)). */
ARCUS_INLINE void photon_select(REAL* d2, int* slot, int n, int at) {
  int lo = 0, hi = n - 1;
  while (hi > lo) {
    const int mid = lo + (hi - lo) / 2;
    const REAL pd = d2[mid];
    const int ps = slot[mid];
    int i = lo, j = hi;
    while (i <= j) {
      while (photon_after(pd, ps, d2[i], slot[i])) ++i;
      while (photon_after(d2[j], slot[j], pd, ps)) --j;
      if (i <= j) {
        const REAL td = d2[i];
        d2[i] = d2[j];
        d2[j] = td;
        const int ts = slot[i];
        slot[i] = slot[j];
        slot[j] = ts;
        ++i;
        --j;
      }
    }
    if (at <= j) hi = j;
    else if (at >= i) lo = i;
    else break;
  }
}

/* The up to k (1..ARCUS_PHOTON_MAX_K) photons nearest to (x, y, z) within distance²
 * max_r2 (inclusive; may be +inf): the k smallest (distance², slot), whatever the
 * traversal order.  With a non-zero normal (nx, ny, nz) only photons arriving from its
 * side count: dot(normal, −dir) > 0.  Returns how many were found and leaves them in
 * d2[]/slot[] (ARCUS_PHOTON_SEARCH_CAPACITY entries) in no particular order except that
 * d2[0] is the farthest.
 *
 * Every photon within the bound is collected and the k smallest selected at the end;
 * when the arrays fill, the k smallest are kept and the bound shrinks to the k-th.
 * Given a bound that holds little more than k photons (a march's last r_k + Δt), that
 * is a constant amount of work per photon where a heap of the k best does log k. */
ARCUS_INLINE int photon_knn(__global const bvh_node* nodes, __global const REAL* photons, const photon_map_desc map,
                            REAL x, REAL y, REAL z, REAL nx, REAL ny, REAL nz, int k, REAL max_r2, REAL* d2,
                            int* slot) {
  if (map.count == 0 || k < 1) return 0;
  const int oriented = nx != RC(0) || ny != RC(0) || nz != RC(0);
  int n = 0;
  REAL bound = max_r2; /* farthest distance² still of interest */
  /* The nearer child is visited first and the farther one pushed with its distance²,
   * so at most one node per level waits: the builder keeps depth ≤ ARCUS_BVH_MAX_DEPTH. */
  int stack[ARCUS_BVH_MAX_DEPTH];
  REAL stack_d2[ARCUS_BVH_MAX_DEPTH];
  int top = 0, node = 0;
  if (photon_box_d2(nodes, x, y, z) > bound) return 0;
  for (;;) {
    __global const bvh_node* nd = nodes + node;
    if (nd->count > 0) {
      for (int s = nd->first; s < nd->first + nd->count; ++s) {
        const REAL dx = PHOTON(photons, map, ARCUS_PHOTON_POSITION, s) - x;
        const REAL dy = PHOTON(photons, map, ARCUS_PHOTON_POSITION + 1, s) - y;
        const REAL dz = PHOTON(photons, map, ARCUS_PHOTON_POSITION + 2, s) - z;
        const REAL d = dx * dx + dy * dy + dz * dz;
        if (d > bound) continue;
        if (oriented && nx * PHOTON(photons, map, ARCUS_PHOTON_DIRECTION, s) +
                                ny * PHOTON(photons, map, ARCUS_PHOTON_DIRECTION + 1, s) +
                                nz * PHOTON(photons, map, ARCUS_PHOTON_DIRECTION + 2, s) >=
                            RC(0))
          continue; /* travelling along the normal: it arrived from behind */
        if (n == ARCUS_PHOTON_SEARCH_CAPACITY) { /* full: keep the k smallest, search no farther than the k-th */
          photon_select(d2, slot, n, k - 1);
          n = k;
          bound = d2[k - 1];
          if (!photon_after(bound, slot[k - 1], d, s)) continue;
        }
        d2[n] = d;
        slot[n++] = s;
      }
    } else {
      int a = nd->first, b = nd->first + 1;
      REAL da = photon_box_d2(nodes + a, x, y, z), db = photon_box_d2(nodes + b, x, y, z);
      if (db < da) {
        const int t = a;
        a = b;
        b = t;
        const REAL td = da;
        da = db;
        db = td;
      }
      if (db <= bound) {
        stack[top] = b;
        stack_d2[top++] = db;
      }
      if (da <= bound) {
        node = a;
        continue;
      }
    }
    /* Next: the latest pushed node still within the (possibly shrunk) bound. */
    do {
      if (top == 0) {
        if (n > k) {
          photon_select(d2, slot, n, k - 1);
          n = k;
        }
        int far = 0; /* the farthest first */
        for (int i = 1; i < n; ++i)
          if (photon_after(d2[i], slot[i], d2[far], slot[far])) far = i;
        const REAL td = d2[0];
        d2[0] = d2[far];
        d2[far] = td;
        const int ts = slot[0];
        slot[0] = slot[far];
        slot[far] = ts;
        return n;
      }
      --top;
      node = stack[top];
    } while (stack_d2[top] > bound);
  }
}

/* The photon map's radiance estimate at (x, y, z) from the k nearest photons within
 * max_radius, per channel into out[0..map.channels):
 *   surface (ARCUS_PHOTON_SURFACE; unit normal n, front-side photons only):
 *     Σ Φ_p / (π r²), the irradiance (the caller multiplies by the BRDF);
 *   volume (ARCUS_PHOTON_VOLUME; the normal is ignored):
 *     Σ Φ_p / (4/3 π r³) (the caller multiplies by the phase function).
 * r is r_k, the distance of the k-th photon, when k were found; else the whole search
 * sphere max_radius was searched and r = max_radius (or, with max_radius = +inf, the
 * farthest photon's distance).  With cone > 0 (Jensen's cone filter, constant ≥ 1) each
 * photon is weighted 1 − d/(cone·r) and the sum normalised by the filter's integral:
 * 1 − 2/(3 cone) on a disc, 1 − 3/(4 cone) in a ball.  k photons exactly at the query
 * point give r = 0 and an infinite estimate, as the density is.  Returns the count
 * found; *radius = r.  d2[]/slot[] are photon_knn's scratch arrays. */
ARCUS_INLINE int photon_estimate(__global const bvh_node* nodes, __global const REAL* photons,
                                 const photon_map_desc map, REAL x, REAL y, REAL z, REAL nx, REAL ny, REAL nz,
                                 const photon_query_desc* q, REAL* d2, int* slot, REAL* out, REAL* radius) {
  const int volume = q->mode == ARCUS_PHOTON_VOLUME;
  const REAL side = volume ? RC(0) : RC(1); /* a zero normal: every direction counts */
  const int found = photon_knn(nodes, photons, map, x, y, z, side * nx, side * ny, side * nz, q->k,
                               q->max_radius * q->max_radius, d2, slot);
  REAL r = RC(0);
  if (found == q->k || (found > 0 && isinf(q->max_radius)))
    r = sqrt(d2[0]);
  else if (found > 0)
    r = q->max_radius;
  *radius = r;
  for (int c = 0; c < map.channels; ++c) out[c] = RC(0);
  if (found == 0) return 0;
  for (int i = 0; i < found; ++i) {
    const REAL w = q->cone > RC(0) && r > RC(0) ? RC(1) - sqrt(d2[i]) / (q->cone * r) : RC(1);
    for (int c = 0; c < map.channels; ++c) out[c] += w * PHOTON(photons, map, ARCUS_PHOTON_POWER + c, slot[i]);
  }
  const REAL pi = RC(3.14159265358979323846);
  REAL norm = volume ? RC(4) / RC(3) * pi * r * r * r : pi * r * r;
  if (q->cone > RC(0)) norm *= volume ? RC(1) - RC(0.75) / q->cone : RC(1) - RC(2) / (RC(3) * q->cone);
  for (int c = 0; c < map.channels; ++c) out[c] /= norm;
  return found;
}

#endif /* ARCUS_PHOTON_MAP_H */
