/* Intersecting recorded paths (thesis §4.3.2.2–4.3.2.4): a path recorded once (path
 * caching), the mirror image of one (symmetry) or one interpolated between two
 * (undersampling) is walked chord by chord through the same per-step hook as a traced
 * ray (render/hits.h), so walking a recorded path gives the traced hit bit for bit.
 * A net point is the whole state x y z vx vy vz s (ARCUS_USE_RECORD_STATE), so a hit is
 * moved onto the integrated path by the integrator's own step from the chord's start,
 * as when tracing.
 *
 * Path q's points are paths[(k·slots + q)·7 ...] for k < counts[q] (step by step:
 * neighbouring paths' points at a step are neighbours in memory), and
 * end_status[q] says how it ended.  Walked ray r follows ray_a[r], or with ray_b[r] >= 0
 * the path interpolated between the two at equal arc length along a's points as far as
 * both reach (it ends as the shorter one ended), mirrored in `plane` (normal·p = d) if
 * ray_mirror[r].  Results: `out` (x y z vx vy vz s, stride entries per component),
 * out_status and the hit record; a walk that hits nothing ends as its path ended.
 *
 * A cached path's chunks of ARCUS_SMART_CHUNK chords are proved once
 * (arcus_path_capsules: the radius of the capsule around each chunk's first-to-last
 * chord that holds its points), so a walk predicting its hit step (smart step
 * selection) proves the chunks before it with one test each without reading their
 * points, and starts at the first chunk not proved empty: the same proofs as the
 * trace's, made once for every later frame.   */
#if defined(ARCUS_USE_GEOMETRY) && defined(ARCUS_USE_BOX)

#define WALK_REALS 7
#define REAL4 ARCUS_CAT(REAL, 4)
#define WALK_POINT(q, k) (paths + ((size_t)(k) * (size_t)slots + (size_t)(q)) * WALK_REALS)

/* The state of path q at arc length s, linear between its net points; *j is a cursor
 * that only moves forward (s grows along a walk). */
ARCUS_INLINE void walk_state_at(__global const REAL* paths, int slots, int q, int n, REAL s, int* j, REAL* out) {
  while (*j + 2 < n && WALK_POINT(q, *j + 1)[6] <= s) ++*j;
  __global const REAL* a = WALK_POINT(q, *j);
  __global const REAL* b = WALK_POINT(q, min(*j + 1, n - 1));
  const REAL t = b[6] > a[6] ? clamp((s - a[6]) / (b[6] - a[6]), RC(0), RC(1)) : RC(0);
  for (int c = 0; c < 6; ++c) out[c] = a[c] + t * (b[c] - a[c]);
  out[6] = s;
}

/* Path caching's proofs (thesis §4.3.2.4): radii[q·chunks + c] is the radius of the
 * capsule around the chord from point c·ARCUS_SMART_CHUNK to point
 * (c + 1)·ARCUS_SMART_CHUNK of path q (or its last point: the last chunk may be short)
 * that holds the points between, or -1 where the chunk lies past the path's end.
 * `per_item` paths a work-item (it runs once per cache; few work-items keep PoCL's
 * per-group cost small). */
__kernel void arcus_path_capsules(ARCUS_PARAMS(ARCUS_PATH_CAPSULES_ARGS)) {
  const int q0 = (int)get_global_id(0) * per_item;
  for (int q = q0; q < min(count, q0 + per_item); ++q) {
    for (int c = 0; c < chunks; ++c) {
      const int i = c * ARCUS_SMART_CHUNK;
      const int j = min((c + 1) * ARCUS_SMART_CHUNK, counts[q] - 1);
      if (j <= i) {
        radii[(size_t)q * chunks + c] = RC(-1);
        continue;
      }
      __global const REAL* pa = WALK_POINT(q, i);
      __global const REAL* pb = WALK_POINT(q, j);
      const REAL a[3] = {pa[0], pa[1], pa[2]};
      const REAL d[3] = {pb[0] - a[0], pb[1] - a[1], pb[2] - a[2]};
      const REAL dd = d[0] * d[0] + d[1] * d[1] + d[2] * d[2];
      REAL r2 = RC(0);
      for (int k = i + 1; k < j; ++k) {
        __global const REAL* pk = WALK_POINT(q, k);
        const REAL p[3] = {pk[0], pk[1], pk[2]};
        r2 = fmax(r2, segment_distance2(a, d, dd, p));
      }
      radii[(size_t)q * chunks + c] = capsule_radius(r2, a, dd);
    }
  }
}

/* What a walked ray follows, per lane. */
typedef struct walk_lane {
  int a, b, mirror, points; /* points: of the walked path */
  int first;                /* the point it starts from: the chunks before are proved empty */
  int ja, jb;               /* cursors (interpolated paths) */
  REAL end;                 /* interpolated: where the shorter path ends */
} walk_lane;

/* Point k of the lane's walked path. */
ARCUS_INLINE void walk_point(__global const REAL* paths, int slots, __global const int* counts, walk_lane* w, int k,
                             const REAL plane[4], REAL* out) {
  if (w->b < 0) {
    __global const REAL* p = WALK_POINT(w->a, k);
    for (int c = 0; c < WALK_REALS; ++c) out[c] = p[c];
  } else {
    const REAL s = k + 1 < w->points ? WALK_POINT(w->a, k)[6] : w->end;
    REAL pa[WALK_REALS], pb[WALK_REALS];
    walk_state_at(paths, slots, w->a, counts[w->a], s, &w->ja, pa);
    walk_state_at(paths, slots, w->b, counts[w->b], s, &w->jb, pb);
    for (int c = 0; c < 6; ++c) out[c] = RC(0.5) * (pa[c] + pb[c]);
    out[6] = s;
  }
  if (w->mirror) {
    const REAL dx = plane[0] * out[0] + plane[1] * out[1] + plane[2] * out[2] - plane[3];
    const REAL dv = plane[0] * out[3] + plane[1] * out[4] + plane[2] * out[5];
    for (int c = 0; c < 3; ++c) {
      out[c] -= RC(2) * dx * plane[c];
      out[3 + c] -= RC(2) * dv * plane[c];
    }
  }
}

/* Point at[l] of each lane l's walked path into a lane group, for the lanes in `load`
 * (the others keep what they hold). */
ARCUS_INLINE void walk_load(__global const REAL* paths, int slots, __global const int* counts, walk_lane* w,
                            IDXV at, MASKV load, const REAL plane[4], ray6* y, REALV* s) {
  IDX k[ARCUS_LANES], on[ARCUS_LANES];
  VSTORE_IDX(at, 0, k);
  VSTORE_IDX((IDXV)load, 0, on);
  REAL c[WALK_REALS][ARCUS_LANES];
  VSTORE(y->x, 0, c[0]);
  VSTORE(y->y, 0, c[1]);
  VSTORE(y->z, 0, c[2]);
  VSTORE(y->vx, 0, c[3]);
  VSTORE(y->vy, 0, c[4]);
  VSTORE(y->vz, 0, c[5]);
  VSTORE(*s, 0, c[6]);
  for (int l = 0; l < ARCUS_LANES; ++l) {
    if (!on[l]) continue;
    REAL p[WALK_REALS];
    walk_point(paths, slots, counts, &w[l], (int)k[l], plane, p);
    for (int i = 0; i < WALK_REALS; ++i) c[i][l] = p[i];
  }
  y->x = VLOAD(0, c[0]);
  y->y = VLOAD(0, c[1]);
  y->z = VLOAD(0, c[2]);
  y->vx = VLOAD(0, c[3]);
  y->vy = VLOAD(0, c[4]);
  y->vz = VLOAD(0, c[5]);
  *s = VLOAD(0, c[6]);
}

__kernel void arcus_walk(ARCUS_PARAMS(ARCUS_WALK_ARGS)) {
  const size_t first_vector = get_global_id(0) * ARCUS_GROUPS;
  const size_t stride = (size_t)job.stride;
  const REAL plane[4] = {plane4.x, plane4.y, plane4.z, plane4.w};
  medium med[ARCUS_MEDIA];
  media_init(med, &field, field_data, wavelengths, first_vector);
  walk_lane lanes[ARCUS_GROUPS][ARCUS_LANES];
  ray6 y[ARCUS_GROUPS];
  REALV s[ARCUS_GROUPS];
  IDXV count[ARCUS_GROUPS], status[ARCUS_GROUPS];
  hit_state hs[ARCUS_GROUPS];
  smart_chunk chunk[ARCUS_GROUPS];
  IDXV at[ARCUS_GROUPS]; /* each lane's point: its own, so lanes need not wait for each other */
  FOR_GROUPS(g) {
    const size_t v = first_vector + g;
    IDX cs[ARCUS_LANES], es[ARCUS_LANES], fs[ARCUS_LANES], proofs[ARCUS_LANES];
    for (int l = 0; l < ARCUS_LANES; ++l) {
      const size_t r = v * ARCUS_LANES + l;
      walk_lane* w = &lanes[g][l];
      w->ja = w->jb = 0;
      w->end = RC(0);
      w->first = 0;
      fs[l] = proofs[l] = 0;
      if (r >= (size_t)ray_count) { /* padding: no path */
        w->a = 0, w->b = -1, w->mirror = 0, w->points = 0;
        cs[l] = 0;
        es[l] = ARCUS_STATUS_INVALID_INPUT;
        continue;
      }
      w->a = rays[r];
      w->b = rays[r + stride];
      w->mirror = rays[r + 2 * stride];
      const int na = counts[w->a];
      es[l] = end_status[w->a];
      w->points = na;
      if (w->b >= 0 && na >= 2 && counts[w->b] >= 2) {
        const int nb = counts[w->b];
        const REAL end_a = WALK_POINT(w->a, na - 1)[6], end_b = WALK_POINT(w->b, nb - 1)[6];
        w->end = fmin(end_a, end_b);
        if (end_b < end_a) es[l] = end_status[w->b];
        int m = 0;
        while (m < na && WALK_POINT(w->a, m)[6] < w->end) ++m;
        w->points = m + 1; /* a's points short of the end, and the end */
      } else {
        w->b = -1; /* a path of fewer than two points has nothing to interpolate */
      }
      /* A cached or mirrored path predicting its hit at step n: the chunks whose chords
       * all come before step n − 1 (those smart step selection skips) proved by their
       * capsules, as long as each proof holds.  A path predicted to hit nothing may be
       * proved to its end: nothing is left to walk, and it ends as its path ended. */
      const int predicted = predictions ? predictions[r] : -1;
      if (radii && w->b < 0 && predicted >= 0) {
        for (int c = 0; c < chunks && w->first + 1 < w->points; ++c) {
          const int j = min((c + 1) * ARCUS_SMART_CHUNK, w->points - 1);
          const REAL radius = radii[(size_t)w->a * chunks + c];
          if (j > predicted - 1 || !(radius >= RC(0))) break;
          REAL pa[WALK_REALS], pb[WALK_REALS];
          walk_point(paths, slots, counts, w, c * ARCUS_SMART_CHUNK, plane, pa);
          walk_point(paths, slots, counts, w, j, plane, pb);
          const REAL d[3] = {pb[0] - pa[0], pb[1] - pa[1], pb[2] - pa[2]};
          ++proofs[l];
          if (geometry_meets_capsule(&geo, nodes, tris, shapes, pa, d, radius, 0, 0, 0, 0)) break;
          w->first = j;
        }
      }
      fs[l] = w->first;
      cs[l] = w->points;
    }
    count[g] = VLOAD(0, cs);
    at[g] = VLOAD(0, fs);
    /* A path of one point (or none) has no chord: it ends as it was recorded (one that
     * hit at once stops short of where a walked ray goes). */
    IDXV start = VLOAD(0, es);
    start = SEL(start, (IDXV)ARCUS_STATUS_UNRESOLVED, start == (IDXV)ARCUS_STATUS_HIT);
    status[g] = SEL(start, (IDXV)ARCUS_STATUS_ACTIVE, count[g] > (IDXV)1);
    y[g].x = y[g].y = y[g].z = y[g].vx = y[g].vy = y[g].vz = (REALV)RC(0);
    s[g] = (REALV)RC(0);
    walk_load(paths, slots, counts, lanes[g], at[g], at[g] < count[g], plane, &y[g], &s[g]);
    hs[g].kind = (IDXV)ARCUS_HIT_NONE;
    hs[g].index = (IDXV)-1;
    hs[g].tests = VLOAD(0, proofs);
    hs[g].step = (IDXV)-1;
    hs[g].predict = predictions ? VLOAD_I(v, predictions) : (IDXV)-1;
    smart_chunk_start(&chunk[g], y[g], s[g]);
  }
  ray6 zero; /* no Kahan compensation: recorded points are exact states */
  zero.x = zero.y = zero.z = zero.vx = zero.vy = zero.vz = (REALV)RC(0);
  for (int walking = 1; walking;) {
    walking = 0;
    FOR_GROUPS(g) {
      const IDXV next = at[g] + (IDXV)1;
      const MASKV moved = (status[g] == (IDXV)ARCUS_STATUS_ACTIVE) & (next < count[g]);
      if (!ANY(moved)) continue;
      walking = 1;
      ray6 y1 = y[g], comp1 = zero;
      REALV s1 = s[g];
      walk_load(paths, slots, counts, lanes[g], next, moved, plane, &y1, &s1);
      geometry_step(GROUP_MEDIUM(med, g), &job, &geo, nodes, tris, shapes, y[g], zero, s[g], &y1, &comp1, &s1, next,
                    moved, moved & (next + (IDXV)1 >= count[g]), 0, &hs[g], &chunk[g], &status[g]);
      /* Lanes that moved stand at the chord's end now, or on the surface they hit. */
      y[g] = ray_select(y[g], y1, moved);
      s[g] = SEL(s[g], s1, moved);
      at[g] = SEL(at[g], next, moved);
    }
  }
  FOR_GROUPS(g) {
    const size_t v = first_vector + g;
    /* Walked to the end without a hit: the path's own ending, unless that was a hit
     * (the path stops short of where this ray goes). */
    IDX es[ARCUS_LANES];
    for (int l = 0; l < ARCUS_LANES; ++l) {
      const size_t r = v * ARCUS_LANES + l;
      const walk_lane* w = &lanes[g][l];
      es[l] = r >= (size_t)ray_count ? ARCUS_STATUS_INVALID_INPUT
              : w->b >= 0 && WALK_POINT(w->b, counts[w->b] - 1)[6] < WALK_POINT(w->a, counts[w->a] - 1)[6]
                  ? end_status[w->b]
                  : end_status[w->a];
    }
    IDXV ending = VLOAD(0, es);
    ending = SEL(ending, (IDXV)ARCUS_STATUS_UNRESOLVED, ending == (IDXV)ARCUS_STATUS_HIT);
    status[g] = SEL(status[g], ending, status[g] == (IDXV)ARCUS_STATUS_ACTIVE);
    VSTORE(y[g].x, v, out);
    VSTORE(y[g].y, v, out + stride);
    VSTORE(y[g].z, v, out + 2 * stride);
    VSTORE(y[g].vx, v, out + 3 * stride);
    VSTORE(y[g].vy, v, out + 4 * stride);
    VSTORE(y[g].vz, v, out + 5 * stride);
    VSTORE(s[g], v, out + 6 * stride);
    VSTORE_I(status[g], v, out_status);
    hit_state_store(hs[g], v, hit_ints, stride);
  }
}

#endif
