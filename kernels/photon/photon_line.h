/* The k nearest photons of points marching along a straight line, one search shared by
 * many steps (the ocean engine's per-step estimate, thesis eq. 4.6).
 *
 * A march asks for the k nearest photons at points g apart on a line, and consecutive
 * points' k-sets are nearly the same (about 1 − 3g/4r_k of them).  So the photons within
 * a reach R of a stretch of the line (a capsule about it) are gathered once into a
 * private pool, and each step updates the last step's k-set:
 *  - every photon's distance moves by at most g between steps, and so does r_k, the
 *    k-th smallest.  At the new point a photon nearer than r_last − g is in, and was;
 *    one farther than r_last + g is out, and was; only those in the shell between can
 *    have entered or left.  So the shell keeps as many of the k as it held, and the
 *    step finds the shell's photons, selects that many, and reports which changed.
 *  - while r_last + g ≤ R, the ball that holds the new k nearest lies inside the
 *    capsule, so the step's answer is photon_knn's: the k smallest distances², their
 *    ties (of probability zero for photons at distinct points) broken by pool order.
 * The caller keeps what its k photons add up to and adds or removes those reported.
 *
 * A photon's distance from a point of the line depends only on how far along the line
 * it lies (a) and how far off it (h): the pool is sorted by a into columns as wide as a
 * step and by h² into bands, and a step looks only at the bands of each column that
 * its shell crosses.  r_k moves little from step to step, so the k-th is a few places
 * from r_last in the shell: a short sorted list finds it, not a selection.
 *
 * The pool lives in the caller's private memory (ARCUS_PHOTON_LINE_CAPACITY photons,
 * ~190 kB in double precision: the stack of a CPU device's work-item; a GPU would want
 * it in a work-group's local memory, shared by neighbouring rays, not measured: no GPU
 * was at hand).  A stretch that holds more is refused, and the caller gathers a shorter
 * one or falls back on photon_knn.  Needs photon/photon_map.h before it.             */
#ifndef ARCUS_PHOTON_LINE_H
#define ARCUS_PHOTON_LINE_H

#ifndef ARCUS_PHOTON_LINE_CAPACITY
#define ARCUS_PHOTON_LINE_CAPACITY 4096
#endif
#define ARCUS_PHOTON_LINE_COLUMNS 128
/* Bands of h² per column: equal volumes of a column's disc. */
#define ARCUS_PHOTON_LINE_BANDS 16
#define ARCUS_PHOTON_LINE_BUCKETS (ARCUS_PHOTON_LINE_COLUMNS * ARCUS_PHOTON_LINE_BANDS)
/* The furthest in rank from r_last that a step finds its k-th with a short sorted list. */
#define ARCUS_PHOTON_LINE_RANK 24
/* A new stretch's reach, as a multiple of the bound r_last + g (the room r_k has to grow
 * along it before the pool must be gathered anew), and the share of the pool its
 * photons are expected to fill (more fill: longer stretches, more refused); measured
 * best on the thesis' Mediterranean view (docs/benchmarks_ocean.md). */
#define ARCUS_PHOTON_LINE_REACH RC(1.25)
#define ARCUS_PHOTON_LINE_FILL RC(0.7)
/* Points farther apart than this many k-th distances share too little (their shell
 * holds most of the k): each is searched alone (a march at one step in several). */
#define ARCUS_PHOTON_LINE_MOVE RC(0.3)

typedef struct photon_line {
  REAL ax, ay, az;    /* the stretch a + t u, t in [0, length] */
  REAL ux, uy, uz;    /* unit (any unit vector when length is 0) */
  REAL inv_ux, inv_uy, inv_uz; /* 1/u (±∞ where 0) */
  REAL length, reach; /* every photon within `reach` of the stretch is in the pool */
  REAL width;         /* of a column: column c holds t in [c·width − reach, (c+1)·width − reach) */
  int count;          /* photons in the pool; −1: none gathered */
  int columns;
  /* bucket (column c, band b) = c·BANDS + b: entries first[bucket] .. first[bucket + 1) */
  int first[ARCUS_PHOTON_LINE_BUCKETS + 1];
  /* the pool, by bucket */
  REAL x[ARCUS_PHOTON_LINE_CAPACITY], y[ARCUS_PHOTON_LINE_CAPACITY], z[ARCUS_PHOTON_LINE_CAPACITY];
  REAL weight[ARCUS_PHOTON_LINE_CAPACITY]; /* the caller's, per photon (NaN: not yet known) */
  int slot[ARCUS_PHOTON_LINE_CAPACITY];
  uchar in[ARCUS_PHOTON_LINE_CAPACITY]; /* in the last step's k-set */
  /* the gather's photons in slot order: slot and bucket */
  int gathered[ARCUS_PHOTON_LINE_CAPACITY];
  short bucket[ARCUS_PHOTON_LINE_CAPACITY];
} photon_line;

/* Whether the stretch may come within `reach` of a node's box: the stretch against the
 * box grown by `reach` on every side (a superset: the grown box's corners count). */
ARCUS_INLINE int photon_line_meets(__global const bvh_node* n, const photon_line* l, REAL reach) {
  const REAL a[3] = {l->ax, l->ay, l->az}, inv[3] = {l->inv_ux, l->inv_uy, l->inv_uz};
  REAL enter = RC(0), leave = l->length;
  for (int i = 0; i < 3; ++i) {
    const REAL lo = n->lo[i] - reach, hi = n->hi[i] + reach;
    if (isinf(inv[i])) { /* the stretch runs across this axis */
      if (a[i] < lo || a[i] > hi) return 0;
      continue;
    }
    const REAL t0 = (lo - a[i]) * inv[i], t1 = (hi - a[i]) * inv[i];
    enter = fmax(enter, fmin(t0, t1));
    leave = fmin(leave, fmax(t0, t1));
  }
  return enter <= leave;
}

/* Photon (px, py, pz)'s place about the line: how far along it (returned) and its
 * distance² off it (*h2). */
ARCUS_INLINE REAL photon_line_along(const photon_line* l, REAL px, REAL py, REAL pz, REAL* h2) {
  const REAL vx = px - l->ax, vy = py - l->ay, vz = pz - l->az;
  const REAL t = vx * l->ux + vy * l->uy + vz * l->uz;
  const REAL ox = vx - t * l->ux, oy = vy - t * l->uy, oz = vz - t * l->uz;
  *h2 = ox * ox + oy * oy + oz * oz;
  return t;
}

/* Gathers every photon within `reach` of the stretch from a to b into the pool, columns
 * `width` wide, the k-set emptied.  Returns 0, with no pool (count −1), when the photons
 * or the columns are more than the pool holds. */
ARCUS_INLINE int photon_line_gather(__global const bvh_node* nodes, __global const REAL* photons,
                                    const photon_map_desc map, photon_line* l, REAL ax, REAL ay, REAL az, REAL bx,
                                    REAL by, REAL bz, REAL reach, REAL width) {
  const REAL length = sqrt((bx - ax) * (bx - ax) + (by - ay) * (by - ay) + (bz - az) * (bz - az));
  l->ax = ax, l->ay = ay, l->az = az;
  l->ux = length > RC(0) ? (bx - ax) / length : RC(1);
  l->uy = length > RC(0) ? (by - ay) / length : RC(0);
  l->uz = length > RC(0) ? (bz - az) / length : RC(0);
  l->inv_ux = RC(1) / l->ux, l->inv_uy = RC(1) / l->uy, l->inv_uz = RC(1) / l->uz;
  l->length = length;
  l->reach = reach;
  l->width = width;
  l->count = -1;
  l->columns = (int)ceil((length + RC(2) * reach) / width) + 1;
  if (map.count == 0 || !(l->columns <= ARCUS_PHOTON_LINE_COLUMNS)) return 0;
  const int buckets = l->columns * ARCUS_PHOTON_LINE_BANDS;
  for (int b = 0; b <= buckets; ++b) l->first[b] = 0;
  const REAL reach2 = reach * reach, bands = (REAL)ARCUS_PHOTON_LINE_BANDS / reach2, inv_width = RC(1) / width;
  int n = 0, top = 0, node = 0;
  int stack[ARCUS_BVH_MAX_DEPTH];
  for (;;) {
    __global const bvh_node* nd = nodes + node;
    if (photon_line_meets(nd, l, reach)) {
      if (nd->count == 0) {
        stack[top++] = nd->first + 1;
        node = nd->first;
        continue;
      }
      if (n + nd->count > ARCUS_PHOTON_LINE_CAPACITY) return 0;
      for (int s = nd->first; s < nd->first + nd->count; ++s) { /* without branches: about half are kept */
        REAL h2;
        const REAL t = photon_line_along(l, PHOTON(photons, map, ARCUS_PHOTON_POSITION, s),
                                         PHOTON(photons, map, ARCUS_PHOTON_POSITION + 1, s),
                                         PHOTON(photons, map, ARCUS_PHOTON_POSITION + 2, s), &h2);
        const REAL beyond = fmax(fmax(-t, t - length), RC(0)); /* past the stretch's ends */
        const int keep = h2 + beyond * beyond <= reach2;
        const int c = (int)clamp((t + reach) * inv_width, RC(0), (REAL)(l->columns - 1));
        const int b = c * ARCUS_PHOTON_LINE_BANDS + (int)fmin(h2 * bands, (REAL)(ARCUS_PHOTON_LINE_BANDS - 1));
        l->gathered[n] = s;
        l->bucket[n] = (short)b;
        l->first[b + 1] += keep;
        n += keep;
      }
    }
    if (top == 0) break;
    node = stack[--top];
  }
  /* by bucket (counting sort; first[b] counts on through bucket b, shifted back after) */
  for (int b = 0; b < buckets; ++b) l->first[b + 1] += l->first[b];
  for (int i = 0; i < n; ++i) {
    const int s = l->gathered[i], j = l->first[l->bucket[i]]++;
    l->x[j] = PHOTON(photons, map, ARCUS_PHOTON_POSITION, s);
    l->y[j] = PHOTON(photons, map, ARCUS_PHOTON_POSITION + 1, s);
    l->z[j] = PHOTON(photons, map, ARCUS_PHOTON_POSITION + 2, s);
    l->slot[j] = s;
    l->weight[j] = (REAL)NAN;
    l->in[j] = 0;
  }
  for (int b = buckets; b > 0; --b) l->first[b] = l->first[b - 1];
  l->first[0] = 0;
  l->count = n;
  return 1;
}

/* One step of the march, at (x, y, z) near the stretch: the k nearest, given the last
 * step's k-th distance r_last and the distance moved since, at most g (the caller's
 * bound, rounding allowed for); with `fresh` the pool holds no k-set yet and every
 * photon within r_last + g is a candidate.  Returns the new k-th distance r_k, or −1
 * where the pool cannot answer exactly (the ball r_last + g reaches past the pool, or
 * the shell overflows d2[]/idx[], ARCUS_PHOTON_SEARCH_CAPACITY entries).  Then
 * idx[0..*changes) names the photons that entered (pool entry i as i + 1) or left
 * (as −(i + 1)). */
ARCUS_INLINE REAL photon_line_step(photon_line* l, REAL x, REAL y, REAL z, int k, REAL r_last, REAL g, int fresh,
                                   REAL* d2, int* idx, int* changes) {
  *changes = 0;
  if (l->count < 0) return RC(-1);
  /* the point's place about the line: off it by `off` (rounding; the march's points lie
   * on it), which widens the shell each column is searched for */
  REAL off2;
  const REAL t = photon_line_along(l, x, y, z, &off2);
  const REAL off = sqrt(off2) + RC(1e-9) * (r_last + g);
  const REAL hi = r_last + g, lo = fresh ? RC(0) : fmax(r_last - g, RC(0));
  if (!(hi + off <= l->reach) || t < RC(0) || t > l->length + off) return RC(-1);
  const REAL lo2 = lo * lo, hi2 = hi * hi;
  const REAL wlo = fmax(lo - off, RC(0)), whi = hi + off; /* the shell, widened */
  const REAL wlo2 = wlo * wlo, whi2 = whi * whi;
  const REAL bands = (REAL)ARCUS_PHOTON_LINE_BANDS / (l->reach * l->reach); /* as the gather has them */
  int n = 0, members = 0; /* the shell's photons; how many of them were in */
  const int c0 = max((int)((t - whi + l->reach) / l->width), 0);
  const int c1 = min((int)((t + whi + l->reach) / l->width), l->columns - 1);
  for (int c = c0; c <= c1; ++c) {
    /* the column's distances along the line from the point, nearest and farthest */
    const REAL a0 = (REAL)c * l->width - l->reach - t, a1 = a0 + l->width;
    const REAL near = a0 > RC(0) ? a0 : a1 < RC(0) ? -a1 : RC(0), far = fmax(fabs(a0), fabs(a1));
    const REAL h2_lo = wlo2 - far * far, h2_hi = whi2 - near * near;
    if (h2_hi < RC(0)) continue;
    /* the bands that h2_lo .. h2_hi falls in */
    const int b0 = min((int)(fmax(h2_lo, RC(0)) * bands), ARCUS_PHOTON_LINE_BANDS - 1);
    const int b1 = min((int)(h2_hi * bands), ARCUS_PHOTON_LINE_BANDS - 1);
    int i = l->first[c * ARCUS_PHOTON_LINE_BANDS + b0];
    const int stop = l->first[c * ARCUS_PHOTON_LINE_BANDS + b1 + 1];
    if (n + (stop - i) > ARCUS_PHOTON_SEARCH_CAPACITY) return RC(-1);
    for (; i < stop; ++i) { /* without branches: the shell's photons are a fraction of these */
      const REAL dx = l->x[i] - x;
      const REAL dy = l->y[i] - y;
      const REAL dz = l->z[i] - z;
      const REAL d = dx * dx + dy * dy + dz * dz;
      const int keep = (d >= lo2) & (d <= hi2);
      d2[n] = d;
      idx[n] = i;
      members += keep & (int)l->in[i];
      n += keep;
    }
  }
  /* Nearer than lo: in, and in before; beyond hi: out, and out before.  So the shell
   * keeps as many members as it had (fresh: all k). */
  const int need = fresh ? k : members;
  if (need < 1 || need > n) return RC(-1);
  REAL r2;
  int at; /* the k-th: distance², pool entry */
  const REAL last2 = r_last * r_last;
  int below = 0; /* the shell's photons nearer than r_last */
  for (int j = 0; j < n; ++j) below += d2[j] < last2;
  /* the k-th: the more-th nearest beyond r_last, or (more ≤ 0) the (1 − more)-th
   * farthest within */
  const int more = need - below;
  if (!fresh && more > -ARCUS_PHOTON_LINE_RANK && more <= ARCUS_PHOTON_LINE_RANK) {
    /* r_k moves little from step to step: the k-th is a few places from r_last, found
     * with a short sorted list instead of a selection over the whole shell.  Within,
     * distance² and entry are negated, so that the list ascends either way. */
    const int beyond = more > 0, q = beyond ? more : 1 - more;
    const REAL sign = beyond ? RC(1) : RC(-1);
    REAL best[ARCUS_PHOTON_LINE_RANK];
    int best_i[ARCUS_PHOTON_LINE_RANK];
    int m = 0;
    for (int j = 0; j < n; ++j) {
      if ((d2[j] < last2) == beyond) continue;
      const REAL key = sign * d2[j];
      const int key_i = beyond ? idx[j] : -idx[j];
      if (m == q && !photon_after(best[q - 1], best_i[q - 1], key, key_i)) continue;
      int p = m < q ? m++ : q - 1;
      for (; p > 0 && photon_after(best[p - 1], best_i[p - 1], key, key_i); --p) {
        best[p] = best[p - 1];
        best_i[p] = best_i[p - 1];
      }
      best[p] = key;
      best_i[p] = key_i;
    }
    if (m < q) return RC(-1);
    r2 = sign * best[q - 1];
    at = beyond ? best_i[q - 1] : -best_i[q - 1];
  } else {
    photon_select(d2, idx, n, need - 1);
    r2 = d2[need - 1];
    at = idx[need - 1];
  }
  int c = 0;
  for (int j = 0; j < n; ++j) {
    const int i = idx[j];
    const uchar now = d2[j] < r2 || (d2[j] == r2 && i <= at);
    if (now != l->in[i]) {
      l->in[i] = now;
      idx[c++] = now ? i + 1 : -(i + 1);
    }
  }
  *changes = c;
  return sqrt(r2);
}

/* The march's query at (x, y, z), moving along the unit (ux, uy, uz) with `room` more
 * to go on this line: the step from the pool when it can answer, else from a new
 * stretch gathered here (*fresh = 1: the caller's sums start again from the changes
 * reported, all k entering).  r_last and g as for photon_line_step; r_last = ∞ (no k-th
 * known) gathers nothing.  Returns r_k, or −1 with no pool where the stretch cannot
 * answer (too many photons even for a stretch of one step; fewer than k within reach):
 * then the caller searches alone (photon_knn).  The pool's cached weights are the
 * caller's to keep: gather anew (count = −1) when what they depend on changes. */
ARCUS_INLINE REAL photon_line_query(__global const bvh_node* nodes, __global const REAL* photons,
                                    const photon_map_desc map, photon_line* l, REAL x, REAL y, REAL z, REAL ux, REAL uy,
                                    REAL uz, REAL room, int k, REAL r_last, REAL g, REAL* d2, int* idx, int* changes,
                                    int* fresh) {
  *fresh = 0;
  if (!isfinite(r_last) || !(r_last > RC(0)) || !(g > RC(0)) || g > ARCUS_PHOTON_LINE_MOVE * r_last) {
    l->count = -1;
    return RC(-1);
  }
  const REAL r = photon_line_step(l, x, y, z, k, r_last, g, 0, d2, idx, changes);
  if (r >= RC(0)) return r;
  /* A capsule of length L and radius reach = q r_last, at the density that puts k within
   * r_last, holds k (q³ + ¾ q² L / r_last) photons: L such that they fill FILL of the
   * pool, halved while they overflow it. */
  const REAL reach = (r_last + g) * ARCUS_PHOTON_LINE_REACH, q = reach / r_last;
  const REAL fill = ARCUS_PHOTON_LINE_FILL * (REAL)ARCUS_PHOTON_LINE_CAPACITY / (REAL)k;
  REAL length = fmin(fmax(fill - q * q * q, RC(0)) / (RC(0.75) * q * q) * r_last, fmax(room, RC(0)));
  while (!photon_line_gather(nodes, photons, map, l, x, y, z, x + length * ux, y + length * uy, z + length * uz, reach,
                             g)) {
    if (length == RC(0)) return RC(-1);
    length = length > g ? RC(0.5) * length : RC(0);
  }
  *fresh = 1;
  const REAL first = photon_line_step(l, x, y, z, k, r_last, g, 1, d2, idx, changes);
  if (first < RC(0)) l->count = -1;
  return first;
}

#endif /* ARCUS_PHOTON_LINE_H */
