/* The rendering engine's per-step hook (ARCUS_USE_GEOMETRY; thesis §4.1.6, §4.3):
 * every step a ray takes is a chord between two net points of its integrated path,
 * tested against the scene's triangles (through the BVH, bvh/traverse.h) and analytic
 * shapes.  The first chord that hits stops the ray, and its end is moved, with the
 * integrator's own step (curved/crossing.h), to where the integrated path crosses the
 * hit primitive's surface: a hit lies on the path, not on its chord.
 *
 * Smart step selection (thesis §4.3.3): a ray given a predicted hit step n (from its
 * neighbours or from the previous frame) skips the tests of its steps before n − 1 and
 * keeps only the box of the chords skipped since the last proof.  Every
 * ARCUS_SMART_CHUNK skipped steps, when it reaches step n − 1, and when it ends, one
 * test proves that box empty of primitives, so the skipped steps cannot have hit
 * anything: the hit found from there on is exactly the exhaustive scan's.  (One box for
 * all skipped steps would be too coarse: every path starts at the camera, so its box
 * spans everything between the camera and the path's end.)  If a proof fails the ray
 * stops as RETRY and the host traces it again without a prediction.  (The thesis tests n, then n − 1, then n + 1 and takes the first hit
 * found; along a path computed step by step n − 1 comes first, and the proof makes
 * the order irrelevant to the result.)
 *
 * Tests count one per chord query and one per proof: the thesis' t_intersection.   */
#ifdef ARCUS_USE_GEOMETRY

#define ARCUS_SMART_CHUNK 8 /* skipped steps per emptiness proof */

/* A ray's hit record while it is traced (render_desc.h has the device layout). */
typedef struct hit_state {
  IDXV kind, index, tests, predict, step;
  REALV lo[3], hi[3]; /* box of the skipped chords */
} hit_state;

/* The closest shape hit by the chord o + t·d, t in [0, *t_best): its index, or -1;
 * *t_best becomes its t.  Spheres by the closest-approach form of the quadratic, which
 * stays exact for a sphere 1.5e11 m away whose radius is 1/200 of its distance. */
ARCUS_INLINE int shapes_segment(__global const shape* shapes, int count, const REAL o[3], const REAL d[3],
                                REAL* t_best) {
  int best = -1;
  const REAL dd = d[0] * d[0] + d[1] * d[1] + d[2] * d[2];
  if (!(dd > RC(0))) return -1;
  for (int i = 0; i < count; ++i) {
    __global const shape* sh = &shapes[i];
    const REAL oc[3] = {o[0] - sh->center[0], o[1] - sh->center[1], o[2] - sh->center[2]};
    REAL t = INFINITY;
    if (sh->kind == ARCUS_SHAPE_SPHERE) {
      const REAL b = (oc[0] * d[0] + oc[1] * d[1] + oc[2] * d[2]) / dd; /* closest approach at t = -b */
      const REAL f[3] = {oc[0] - b * d[0], oc[1] - b * d[1], oc[2] - b * d[2]};
      const REAL r2 = sh->radius * sh->radius;
      const REAL disc = r2 - (f[0] * f[0] + f[1] * f[1] + f[2] * f[2]); /* r² − (miss distance)² */
      if (disc < RC(0)) continue;
      const REAL spread = sqrt(disc / dd);
      const REAL t0 = -b - spread, t1 = -b + spread;
      t = t0 >= RC(0) ? t0 : t1; /* from inside (the Earth seen from below?) the far side */
    } else {
      const REAL denom = sh->normal[0] * d[0] + sh->normal[1] * d[1] + sh->normal[2] * d[2];
      if (denom == RC(0)) continue; /* parallel: a grazing chord never hits a disc */
      t = -(sh->normal[0] * oc[0] + sh->normal[1] * oc[1] + sh->normal[2] * oc[2]) / denom;
      const REAL p[3] = {oc[0] + t * d[0], oc[1] + t * d[1], oc[2] + t * d[2]};
      if (p[0] * p[0] + p[1] * p[1] + p[2] * p[2] > sh->radius * sh->radius) continue;
    }
    if (t >= RC(0) && t < *t_best) {
      *t_best = t;
      best = i;
    }
  }
  return best;
}

/* Whether some shape may reach into the box [lo, hi] (conservative: a sphere by its
 * distance from the box, a disc by its own bounding box). */
ARCUS_INLINE int shapes_overlap_box(__global const shape* shapes, int count, const REAL lo[3], const REAL hi[3]) {
  for (int i = 0; i < count; ++i) {
    __global const shape* sh = &shapes[i];
    if (sh->kind == ARCUS_SHAPE_SPHERE) {
      REAL dist2 = RC(0);
      for (int a = 0; a < 3; ++a) {
        const REAL c = sh->center[a], gap = fmax(lo[a] - c, c - hi[a]);
        if (gap > RC(0)) dist2 += gap * gap;
      }
      if (dist2 <= sh->radius * sh->radius) return 1;
    } else {
      int overlap = 1;
      for (int a = 0; a < 3; ++a) {
        const REAL n = sh->normal[a];
        const REAL extent = sh->radius * sqrt(fmax(RC(0), RC(1) - n * n));
        overlap &= (sh->center[a] - extent <= hi[a]) & (sh->center[a] + extent >= lo[a]);
      }
      if (overlap) return 1;
    }
  }
  return 0;
}

/* Whether any primitive may lie in the box: the smart-step proof. */
ARCUS_INLINE int geometry_overlaps_box(const geometry_desc* geo, __global const bvh_node* nodes,
                                       __global const REAL* tris, __global const shape* shapes, const REAL lo[3],
                                       const REAL hi[3]) {
  if (geo->triangle_count > 0 && bvh_box_overlaps(nodes, tris, lo, hi)) return 1;
  return shapes_overlap_box(shapes, geo->shape_count, lo, hi);
}

/* Lanes in `moved` took the step y0 → *y1 (from arc s0; `steps` already counts it);
 * `ending`: the lanes stop after it anyway (left the box, reached the length).
 * Tests the step's chord, stops the lanes that hit (HIT, end moved onto the surface)
 * and those whose skipped steps cannot be proved empty (RETRY). */
ARCUS_INLINE void geometry_step(const medium* m, const advance_desc* job, const geometry_desc* geo,
                                __global const bvh_node* nodes, __global const REAL* tris,
                                __global const shape* shapes, ray6 y0, ray6 comp0, REALV s0, ray6* y1, ray6* comp1,
                                REALV* s1, IDXV steps, MASKV moved, MASKV ending, hit_state* hs, IDXV* status) {
  REAL a0[3][ARCUS_LANES], a1[3][ARCUS_LANES], lo[3][ARCUS_LANES], hi[3][ARCUS_LANES];
  REAL q[8][ARCUS_LANES]; /* the hit surface's quadric per lane (crossing.h) */
  REAL t_hit[ARCUS_LANES];
  IDX k[ARCUS_LANES], mv[ARCUS_LANES], en[ARCUS_LANES], kind[ARCUS_LANES], index[ARCUS_LANES], tests[ARCUS_LANES],
      predict[ARCUS_LANES], hstep[ARCUS_LANES], hit[ARCUS_LANES], retry[ARCUS_LANES];
  VSTORE(y0.x, 0, a0[0]);
  VSTORE(y0.y, 0, a0[1]);
  VSTORE(y0.z, 0, a0[2]);
  VSTORE(y1->x, 0, a1[0]);
  VSTORE(y1->y, 0, a1[1]);
  VSTORE(y1->z, 0, a1[2]);
  for (int a = 0; a < 3; ++a) {
    VSTORE(hs->lo[a], 0, lo[a]);
    VSTORE(hs->hi[a], 0, hi[a]);
  }
  VSTORE_IDX(steps, 0, k);
  VSTORE_IDX((IDXV)moved, 0, mv);
  VSTORE_IDX((IDXV)ending, 0, en);
  VSTORE_IDX(hs->kind, 0, kind);
  VSTORE_IDX(hs->index, 0, index);
  VSTORE_IDX(hs->tests, 0, tests);
  VSTORE_IDX(hs->predict, 0, predict);
  VSTORE_IDX(hs->step, 0, hstep);

  for (int l = 0; l < ARCUS_LANES; ++l) {
    hit[l] = 0;
    retry[l] = 0;
    t_hit[l] = RC(1);
    for (int c = 0; c < 8; ++c) q[c][l] = RC(0);
    if (!mv[l]) continue;
    const IDX seg = k[l] - 1; /* this step's index along the path */
    const REAL o[3] = {a0[0][l], a0[1][l], a0[2][l]};
    const REAL d[3] = {a1[0][l] - o[0], a1[1][l] - o[1], a1[2][l] - o[2]};
    const IDX predicted = predict[l];
    if (predicted >= 0) {
      if (seg < predicted - 1) {
        /* Skipped: only its box is kept (the start point is in it already). */
        for (int a = 0; a < 3; ++a) {
          lo[a][l] = fmin(lo[a][l], a1[a][l]);
          hi[a][l] = fmax(hi[a][l], a1[a][l]);
        }
        if (!en[l] && (seg + 1) % ARCUS_SMART_CHUNK != 0) continue;
      }
      /* A chunk is full, the tested range begins, or the ray ends: prove the chords
       * skipped since the last proof empty. */
      tests[l] += 1;
      const REAL blo[3] = {lo[0][l], lo[1][l], lo[2][l]}, bhi[3] = {hi[0][l], hi[1][l], hi[2][l]};
      if (geometry_overlaps_box(geo, nodes, tris, shapes, blo, bhi)) {
        retry[l] = 1;
        continue;
      }
      if (seg < predicted - 1) {
        if (en[l]) continue; /* the ray ended within the skipped, now empty, steps */
        for (int a = 0; a < 3; ++a) lo[a][l] = hi[a][l] = a1[a][l]; /* the next chunk starts here */
        continue;
      }
      predict[l] = -1;
    }
    tests[l] += 1;
    REAL best = RC(1);
    int found_kind = ARCUS_HIT_NONE, found = -1;
    if (geo->triangle_count > 0) {
      REAL t, u, v;
      int visits = 0;
      const int slot = bvh_segment_closest(nodes, tris, o[0], o[1], o[2], d[0], d[1], d[2], best, &t, &u, &v, &visits);
      if (slot >= 0) {
        best = t;
        found_kind = ARCUS_HIT_TRIANGLE;
        found = slot;
      }
    }
    const int si = shapes_segment(shapes, geo->shape_count, o, d, &best);
    if (si >= 0) {
      found_kind = ARCUS_HIT_SHAPE;
      found = si;
    }
    if (found_kind == ARCUS_HIT_NONE) continue;
    hit[l] = 1;
    kind[l] = found_kind;
    index[l] = found;
    hstep[l] = seg;
    t_hit[l] = best;
    /* The surface for crossing.h: the triangle's or disc's plane, or the sphere. */
    REAL qa = RC(0), c[3], n[3] = {RC(0), RC(0), RC(0)}, qd = RC(0);
    if (found_kind == ARCUS_HIT_TRIANGLE) {
      __global const REAL* tri = tris + 9 * (size_t)found;
      const REAL e1[3] = {tri[3] - tri[0], tri[4] - tri[1], tri[5] - tri[2]};
      const REAL e2[3] = {tri[6] - tri[0], tri[7] - tri[1], tri[8] - tri[2]};
      n[0] = e1[1] * e2[2] - e1[2] * e2[1];
      n[1] = e1[2] * e2[0] - e1[0] * e2[2];
      n[2] = e1[0] * e2[1] - e1[1] * e2[0];
      const REAL len = sqrt(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]);
      for (int a = 0; a < 3; ++a) {
        n[a] /= len;
        c[a] = tri[a];
      }
    } else {
      __global const shape* sh = &shapes[found];
      for (int a = 0; a < 3; ++a) c[a] = sh->center[a];
      if (sh->kind == ARCUS_SHAPE_SPHERE) {
        qa = RC(0.5) / sh->radius;
        qd = RC(0.5) * sh->radius;
      } else {
        for (int a = 0; a < 3; ++a) n[a] = sh->normal[a];
      }
    }
    /* The start on the negative side (crossing.h's convention). */
    const REAL oc[3] = {o[0] - c[0], o[1] - c[1], o[2] - c[2]};
    const REAL g0 = qa * (oc[0] * oc[0] + oc[1] * oc[1] + oc[2] * oc[2]) + n[0] * oc[0] + n[1] * oc[1] +
                    n[2] * oc[2] - qd;
    const REAL sign = g0 > RC(0) ? RC(-1) : RC(1);
    q[0][l] = sign * qa;
    q[1][l] = c[0];
    q[2][l] = c[1];
    q[3][l] = c[2];
    q[4][l] = sign * n[0];
    q[5][l] = sign * n[1];
    q[6][l] = sign * n[2];
    q[7][l] = sign * qd;
  }

  for (int a = 0; a < 3; ++a) {
    hs->lo[a] = VLOAD(0, lo[a]);
    hs->hi[a] = VLOAD(0, hi[a]);
  }
  hs->kind = VLOAD(0, kind);
  hs->index = VLOAD(0, index);
  hs->tests = VLOAD(0, tests);
  hs->predict = VLOAD(0, predict);
  hs->step = VLOAD(0, hstep);
  const MASKV hits = VLOAD(0, hit) != (IDXV)0;
  const MASKV retries = VLOAD(0, retry) != (IDXV)0;
  *status = SEL(*status, (IDXV)ARCUS_STATUS_RETRY, retries);
  if (!ANY(hits)) return;

  quadric surf;
  surf.a = VLOAD(0, q[0]);
  surf.cx = VLOAD(0, q[1]);
  surf.cy = VLOAD(0, q[2]);
  surf.cz = VLOAD(0, q[3]);
  surf.nx = VLOAD(0, q[4]);
  surf.ny = VLOAD(0, q[5]);
  surf.nz = VLOAD(0, q[6]);
  surf.d = VLOAD(0, q[7]);
  /* The path crosses the surface within the step where the step's end lies beyond it;
   * otherwise (a chord through a whole sphere, a chord in the plane) the chord's own
   * hit point stands, off the path by at most the step's sagitta. */
  const MASKV bracketed = hits & (surface_distance(job, &surf, *y1) > RC(0));
  const MASKV chord = hits & !bracketed;
  if (ANY(chord)) {
    const REALV t = VLOAD(0, t_hit);
    ray6 at = ray_step(y0, t, ray_step(*y1, (REALV)RC(-1), y0)); /* y0 + t·(y1 − y0) */
    *y1 = ray_select(*y1, at, chord);
    *s1 = SEL(*s1, s0 + t * (*s1 - s0), chord);
  }
  if (ANY(bracketed)) cross_surface(m, job, &surf, y0, comp0, s0, *s1 - s0, y1, comp1, s1, bracketed);
  *status = SEL(*status, (IDXV)ARCUS_STATUS_HIT, hits);
}

#endif /* ARCUS_USE_GEOMETRY */
