/* The rendering engine's per-step hook (ARCUS_USE_GEOMETRY; thesis §4.1.6, §4.3):
 * every step a ray takes is a chord between two net points of its integrated path,
 * tested against the scene's triangles (through the BVH, bvh/traverse.h) and analytic
 * shapes.  The first chord that hits stops the ray, and its end is moved, with the
 * integrator's own step (curved/crossing.h), to where the integrated path crosses the
 * hit primitive's surface: a hit lies on the path, not on its chord.
 *
 * Smart step selection (thesis §4.3.3): a ray given a predicted hit step n (from its
 * neighbours or from the previous frame) skips the tests of its steps before n.  It
 * keeps the skipped steps' net points (whole states) in a chunk of at most
 * ARCUS_SMART_CHUNK, and when the chunk is full, when step n comes, when the ray ends
 * and when the slice ends, one test proves the chunk empty: no primitive comes
 * within the capsule around the chord from the chunk's first to its last point whose
 * radius is the farthest any point of the chunk strays from that chord.  If the proof
 * fails, its halves are proved in turn, down to single chords, which are intersected.  Either way no step
 * goes untested, so the hit found is exactly the exhaustive scan's, and its end is
 * moved onto the path from the same state with the same step.  (The thesis tests n,
 * then n − 1, n + 1 and takes the first hit found; here steps up to n − 1 are proved
 * empty or scanned first, so the hit is the first along the path whatever the order.)  A box
 * around the chunk would be a weaker proof: every path starts at the camera, so the
 * box of a path's first steps spans all the scene between the camera and them.
 *
 * Tests count one per chord query and one per proof: the thesis' t_intersection.   */
#ifdef ARCUS_USE_GEOMETRY

#define ARCUS_SMART_CHUNK 16 /* skipped steps per emptiness proof at most */

/* A ray's hit record while it is traced (render_desc.h has the device layout). */
typedef struct hit_state {
  IDXV kind, index, tests, predict, step;
} hit_state;

/* Stores lane group v of the rays' hit records (render_desc.h: `stride` entries a
 * component): the advance's at the end of a slice, the walk's at its end. */
ARCUS_INLINE void hit_state_store(hit_state h, size_t v, __global int* hit_ints, size_t stride) {
  VSTORE_I(h.kind, v, hit_ints + ARCUS_HIT_KIND * stride);
  VSTORE_I(h.index, v, hit_ints + ARCUS_HIT_INDEX * stride);
  VSTORE_I(h.tests, v, hit_ints + ARCUS_HIT_TESTS * stride);
  VSTORE_I(h.predict, v, hit_ints + ARCUS_HIT_PREDICT * stride);
  VSTORE_I(h.step, v, hit_ints + ARCUS_HIT_STEP * stride);
}

#define ARCUS_STATE_REALS 7 /* x y z vx vy vz s */

/* The skipped steps' net points of each lane of a group, since the last proof. */
typedef struct smart_chunk {
  REAL p[ARCUS_SMART_CHUNK + 1][ARCUS_STATE_REALS][ARCUS_LANES];
  int points[ARCUS_LANES]; /* points held: 1 (the start) .. ARCUS_SMART_CHUNK + 1 */
} smart_chunk;

/* Starts every lane's chunk at its current state. */
ARCUS_INLINE void smart_chunk_start(smart_chunk* c, ray6 y, REALV s) {
  VSTORE(y.x, 0, c->p[0][0]);
  VSTORE(y.y, 0, c->p[0][1]);
  VSTORE(y.z, 0, c->p[0][2]);
  VSTORE(y.vx, 0, c->p[0][3]);
  VSTORE(y.vy, 0, c->p[0][4]);
  VSTORE(y.vz, 0, c->p[0][5]);
  VSTORE(s, 0, c->p[0][6]);
  for (int l = 0; l < ARCUS_LANES; ++l) c->points[l] = 1;
}

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

/* Whether the segment a + t·d, t in [0, 1], meets the box [lo − r, hi + r]; inv[k] is
 * 1/d[k] (computed once per segment: divisions were most of a test's cost). */
ARCUS_INLINE int capsule_meets_box(const REAL a[3], const REAL d[3], const REAL inv[3], REAL r, const REAL* lo,
                                   const REAL* hi) {
  REAL t0 = RC(0), t1 = RC(1);
  for (int k = 0; k < 3; ++k) {
    const REAL l = lo[k] - r, h = hi[k] + r;
    if (d[k] == RC(0)) {
      if (a[k] < l || a[k] > h) return 0;
      continue;
    }
    REAL u0 = (l - a[k]) * inv[k], u1 = (h - a[k]) * inv[k];
    if (u0 > u1) {
      const REAL t = u0;
      u0 = u1;
      u1 = t;
    }
    t0 = fmax(t0, u0);
    t1 = fmin(t1, u1 + fabs(u1) * ARCUS_BVH_SLACK);
    if (t0 > t1) return 0;
  }
  return 1;
}

/* Whether points i..j of lane l's chunk lie strictly on one side of the plane through
 * v with normal n, beyond rounding: then no chord between them crosses the plane, so
 * none hits a triangle or disc in it (a half-space is convex). */
ARCUS_INLINE int span_beside_plane(const smart_chunk* c, int l, int i, int j, const REAL v[3], const REAL n[3]) {
  const REAL nn = fabs(n[0]) + fabs(n[1]) + fabs(n[2]);
  int side = 0;
  for (int k = i; k <= j; ++k) {
    const REAL p[3] = {c->p[k][0][l], c->p[k][1][l], c->p[k][2][l]};
    const REAL e = n[0] * (p[0] - v[0]) + n[1] * (p[1] - v[1]) + n[2] * (p[2] - v[2]);
    const REAL scale = fmax(fmax(fabs(p[0]), fabs(p[1])), fabs(p[2])) + fmax(fmax(fabs(v[0]), fabs(v[1])), fabs(v[2]));
    if (!(fabs(e) > RC(64) * ARCUS_BVH_SLACK * nn * scale)) return 0; /* on it, to rounding */
    const int s = e > RC(0) ? 1 : -1;
    if (side != 0 && s != side) return 0;
    side = s;
  }
  return 1;
}

/* Whether any primitive may come within r of the segment a + t·d, t in [0, 1]
 * (conservative: triangles by their boxes, grown by r).  Given the points the capsule
 * holds (`span`: lane l's chunk points i..j; NULL: none), a triangle or disc they all
 * lie beside is ruled out as well, however near the capsule comes to it: a path that
 * leaves a surface or runs along one proves its chunk at once. */
ARCUS_INLINE int geometry_meets_capsule(const geometry_desc* geo, __global const bvh_node* nodes,
                                        __global const REAL* tris, __global const shape* shapes, const REAL a[3],
                                        const REAL d[3], REAL r, const smart_chunk* span, int l, int i, int j) {
  const REAL inv[3] = {RC(1) / d[0], RC(1) / d[1], RC(1) / d[2]}; /* unused where d[k] = 0 */
  if (geo->triangle_count > 0 && nodes[0].first >= 0) {
    int stack[ARCUS_BVH_MAX_DEPTH];
    int sp = 0;
    REAL lo[3], hi[3];
    for (int k = 0; k < 3; ++k) lo[k] = nodes[0].lo[k], hi[k] = nodes[0].hi[k];
    if (capsule_meets_box(a, d, inv, r, lo, hi)) stack[sp++] = 0;
    while (sp > 0) {
      __global const bvh_node* n = &nodes[stack[--sp]];
      if (n->count > 0) {
        for (int t = n->first; t < n->first + n->count; ++t) {
          __global const REAL* v = tris + 9 * (size_t)t;
          for (int k = 0; k < 3; ++k) {
            lo[k] = fmin(fmin(v[k], v[3 + k]), v[6 + k]);
            hi[k] = fmax(fmax(v[k], v[3 + k]), v[6 + k]);
          }
          if (!capsule_meets_box(a, d, inv, r, lo, hi)) continue;
          if (!span) return 1;
          const REAL v0[3] = {v[0], v[1], v[2]};
          const REAL e1[3] = {v[3] - v[0], v[4] - v[1], v[5] - v[2]};
          const REAL e2[3] = {v[6] - v[0], v[7] - v[1], v[8] - v[2]};
          const REAL nt[3] = {e1[1] * e2[2] - e1[2] * e2[1], e1[2] * e2[0] - e1[0] * e2[2], e1[0] * e2[1] - e1[1] * e2[0]};
          if (!span_beside_plane(span, l, i, j, v0, nt)) return 1;
        }
        continue;
      }
      for (int c = 0; c < 2; ++c) {
        __global const bvh_node* child = &nodes[n->first + c];
        for (int k = 0; k < 3; ++k) lo[k] = child->lo[k], hi[k] = child->hi[k];
        if (capsule_meets_box(a, d, inv, r, lo, hi)) stack[sp++] = n->first + c;
      }
    }
  }
  for (int i = 0; i < geo->shape_count; ++i) {
    __global const shape* sh = &shapes[i];
    REAL lo[3], hi[3];
    for (int k = 0; k < 3; ++k) {
      const REAL n = sh->normal[k];
      const REAL extent = sh->kind == ARCUS_SHAPE_SPHERE ? sh->radius : sh->radius * sqrt(fmax(RC(0), RC(1) - n * n));
      lo[k] = sh->center[k] - extent;
      hi[k] = sh->center[k] + extent;
    }
    if (!capsule_meets_box(a, d, inv, r, lo, hi)) continue;
    if (sh->kind != ARCUS_SHAPE_SPHERE) {
      const REAL c0[3] = {sh->center[0], sh->center[1], sh->center[2]};
      const REAL nd[3] = {sh->normal[0], sh->normal[1], sh->normal[2]};
      if (!span || !span_beside_plane(span, l, i, j, c0, nd)) return 1;
      continue;
    }
    /* A sphere: the segment's closest approach to its centre. */
    const REAL dd = d[0] * d[0] + d[1] * d[1] + d[2] * d[2];
    const REAL ac[3] = {sh->center[0] - a[0], sh->center[1] - a[1], sh->center[2] - a[2]};
    const REAL t = dd > RC(0) ? clamp((ac[0] * d[0] + ac[1] * d[1] + ac[2] * d[2]) / dd, RC(0), RC(1)) : RC(0);
    const REAL q[3] = {ac[0] - t * d[0], ac[1] - t * d[1], ac[2] - t * d[2]};
    const REAL reach = sh->radius + r;
    if (q[0] * q[0] + q[1] * q[1] + q[2] * q[2] <= reach * reach * (RC(1) + RC(16) * ARCUS_BVH_SLACK)) return 1;
  }
  return 0;
}

/* The closest primitive the chord o + t·d, t in [0, 1], hits: its kind (ARCUS_HIT_*),
 * *index and *t. */
ARCUS_INLINE int chord_hit(const geometry_desc* geo, __global const bvh_node* nodes, __global const REAL* tris,
                           __global const shape* shapes, const REAL o[3], const REAL d[3], int* index, REAL* t) {
  REAL best = RC(1);
  int kind = ARCUS_HIT_NONE;
  if (geo->triangle_count > 0) {
    REAL th, u, v;
    int visits = 0;
    const int slot = bvh_segment_closest(nodes, tris, o[0], o[1], o[2], d[0], d[1], d[2], best, &th, &u, &v, &visits);
    if (slot >= 0) {
      best = th;
      kind = ARCUS_HIT_TRIANGLE;
      *index = slot;
    }
  }
  const int si = shapes_segment(shapes, geo->shape_count, o, d, &best);
  if (si >= 0) {
    kind = ARCUS_HIT_SHAPE;
    *index = si;
  }
  *t = best;
  return kind;
}

/* The squared distance of point p from the segment a + t·d, t in [0, 1] (dd = d·d). */
ARCUS_INLINE REAL segment_distance2(const REAL a[3], const REAL d[3], REAL dd, const REAL p[3]) {
  const REAL ap[3] = {p[0] - a[0], p[1] - a[1], p[2] - a[2]};
  const REAL u = dd > RC(0) ? clamp((ap[0] * d[0] + ap[1] * d[1] + ap[2] * d[2]) / dd, RC(0), RC(1)) : RC(0);
  const REAL q[3] = {ap[0] - u * d[0], ap[1] - u * d[1], ap[2] - u * d[2]};
  return q[0] * q[0] + q[1] * q[1] + q[2] * q[2];
}

/* The radius of the capsule around the chord a + t·d that holds points as far as
 * sqrt(r2) from it, grown by rounding: the points are exact, the distances computed
 * from them (and a mirror image of them) not. */
ARCUS_INLINE REAL capsule_radius(REAL r2, const REAL a[3], REAL dd) {
  const REAL scale = fmax(fmax(fabs(a[0]), fabs(a[1])), fmax(fabs(a[2]), sqrt(dd)));
  return sqrt(r2) * (RC(1) + RC(64) * ARCUS_BVH_SLACK) + RC(64) * ARCUS_BVH_SLACK * scale;
}

/* Whether chunk points i..j of lane l may come near a primitive: one test of the
 * capsule around the chord from point i to point j, as wide as the points between
 * stray from it. */
ARCUS_INLINE int smart_span_meets(const smart_chunk* c, int l, int i, int j, const geometry_desc* geo,
                                  __global const bvh_node* nodes, __global const REAL* tris,
                                  __global const shape* shapes) {
  const REAL a[3] = {c->p[i][0][l], c->p[i][1][l], c->p[i][2][l]};
  const REAL d[3] = {c->p[j][0][l] - a[0], c->p[j][1][l] - a[1], c->p[j][2][l] - a[2]};
  const REAL dd = d[0] * d[0] + d[1] * d[1] + d[2] * d[2];
  REAL r2 = RC(0);
  for (int k = i + 1; k < j; ++k) {
    const REAL p[3] = {c->p[k][0][l], c->p[k][1][l], c->p[k][2][l]};
    r2 = fmax(r2, segment_distance2(a, d, dd, p));
  }
  return geometry_meets_capsule(geo, nodes, tris, shapes, a, d, capsule_radius(r2, a, dd), c, l, i, j);
}

/* The smart-step proof of lane l's chunk: one capsule test for the whole chunk; where
 * a capsule meets a primitive, its two halves are tested in turn, down to single
 * chords, which are intersected.  Spans are visited along the path, so the first chord
 * that hits is the first along the path.  With `peel` (the chunk starts the path) the
 * first chord is intersected alone first: a path leaving a surface (a shadow ray, a
 * photon's bounce) starts too near it for a capsule around more to clear it.  Returns
 * the chord that hits (its start is chunk point `return`), or -1; the chunk then
 * restarts at its last point. */
ARCUS_INLINE int smart_chunk_close(smart_chunk* c, int l, int peel, const geometry_desc* geo,
                                   __global const bvh_node* nodes, __global const REAL* tris,
                                   __global const shape* shapes, IDX* tests, int* kind, int* index, REAL* t) {
  const int m = c->points[l] - 1; /* chords held */
  if (m <= 0) return -1;
  int lo[ARCUS_SMART_CHUNK + 1], hi[ARCUS_SMART_CHUNK + 1]; /* spans still to prove, the next on top */
  int sp = 0, hit_chord = -1;
  const int from = peel && m > 1 ? 1 : 0;
  lo[sp] = from;
  hi[sp++] = m;
  if (from) {
    lo[sp] = 0;
    hi[sp++] = 1;
  }
  while (sp > 0 && hit_chord < 0) {
    const int i = lo[--sp], j = hi[sp];
    *tests += 1;
    if (j - i == 1) {
      const REAL o[3] = {c->p[i][0][l], c->p[i][1][l], c->p[i][2][l]};
      const REAL e[3] = {c->p[j][0][l] - o[0], c->p[j][1][l] - o[1], c->p[j][2][l] - o[2]};
      *kind = chord_hit(geo, nodes, tris, shapes, o, e, index, t);
      if (*kind != ARCUS_HIT_NONE) hit_chord = i;
      continue;
    }
    if (!smart_span_meets(c, l, i, j, geo, nodes, tris, shapes)) continue;
    const int mid = (i + j) / 2;
    lo[sp] = mid; /* the far half waits under the near one */
    hi[sp++] = j;
    lo[sp] = i;
    hi[sp++] = mid;
  }
  if (hit_chord < 0) {
    for (int k = 0; k < ARCUS_STATE_REALS; ++k) c->p[0][k][l] = c->p[m][k][l];
    c->points[l] = 1;
  }
  return hit_chord;
}

/* The quadric (crossing.h) of a hit primitive, signed so that `from` lies on its
 * negative side. */
ARCUS_INLINE void hit_surface(int kind, int index, __global const REAL* tris, __global const shape* shapes,
                              const REAL from[3], REAL q[8]) {
  REAL qa = RC(0), c[3], n[3] = {RC(0), RC(0), RC(0)}, qd = RC(0);
  if (kind == ARCUS_HIT_TRIANGLE) {
    __global const REAL* tri = tris + 9 * (size_t)index;
    const REAL e1[3] = {tri[3] - tri[0], tri[4] - tri[1], tri[5] - tri[2]};
    const REAL e2[3] = {tri[6] - tri[0], tri[7] - tri[1], tri[8] - tri[2]};
    n[0] = e1[1] * e2[2] - e1[2] * e2[1];
    n[1] = e1[2] * e2[0] - e1[0] * e2[2];
    n[2] = e1[0] * e2[1] - e1[1] * e2[0];
    const REAL len = sqrt(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]);
    for (int k = 0; k < 3; ++k) {
      n[k] /= len;
      c[k] = tri[k];
    }
  } else {
    __global const shape* sh = &shapes[index];
    for (int k = 0; k < 3; ++k) c[k] = sh->center[k];
    if (sh->kind == ARCUS_SHAPE_SPHERE) {
      qa = RC(0.5) / sh->radius;
      qd = RC(0.5) * sh->radius;
    } else {
      for (int k = 0; k < 3; ++k) n[k] = sh->normal[k];
    }
  }
  const REAL oc[3] = {from[0] - c[0], from[1] - c[1], from[2] - c[2]};
  const REAL g0 = qa * (oc[0] * oc[0] + oc[1] * oc[1] + oc[2] * oc[2]) + n[0] * oc[0] + n[1] * oc[1] + n[2] * oc[2] - qd;
  const REAL sign = g0 > RC(0) ? RC(-1) : RC(1);
  q[0] = sign * qa;
  q[1] = c[0];
  q[2] = c[1];
  q[3] = c[2];
  q[4] = sign * n[0];
  q[5] = sign * n[1];
  q[6] = sign * n[2];
  q[7] = sign * qd;
}

/* Lanes in `moved` took the step y0 → *y1 (from arc s0; `steps` already counts it);
 * `ending`: the lanes stop after it anyway (left the box, reached the length).  Tests
 * the step's chord (or keeps it in the chunk), stops the lanes that hit (HIT, the end
 * moved onto the hit surface from the hit chord's start state).  With `flush` (the
 * slice ends) no step was taken: the lanes in `moved` stand at *y1, and their open
 * chunks are closed (the chunks live in private memory, not between slices). */
ARCUS_INLINE void geometry_step(const medium* m, const advance_desc* job, const geometry_desc* geo,
                                __global const bvh_node* nodes, __global const REAL* tris,
                                __global const shape* shapes, ray6 y0, ray6 comp0, REALV s0, ray6* y1, ray6* comp1,
                                REALV* s1, IDXV steps, MASKV moved, MASKV ending, int flush, hit_state* hs,
                                smart_chunk* chunk, IDXV* status) {
  REAL a0[ARCUS_STATE_REALS][ARCUS_LANES], a1[ARCUS_STATE_REALS][ARCUS_LANES];
  REAL h0[ARCUS_STATE_REALS][ARCUS_LANES], h1[ARCUS_STATE_REALS][ARCUS_LANES]; /* the hit chord's ends */
  REAL q[8][ARCUS_LANES];
  REAL t_hit[ARCUS_LANES];
  IDX k[ARCUS_LANES], mv[ARCUS_LANES], en[ARCUS_LANES], kind[ARCUS_LANES], index[ARCUS_LANES], tests[ARCUS_LANES],
      predict[ARCUS_LANES], hstep[ARCUS_LANES], hit[ARCUS_LANES], buffered[ARCUS_LANES];
  const ray6 ys[2] = {y0, *y1};
  const REALV ss[2] = {s0, *s1};
  for (int e = 0; e < 2; ++e) {
    REAL(*dst)[ARCUS_LANES] = e ? a1 : a0;
    VSTORE(ys[e].x, 0, dst[0]);
    VSTORE(ys[e].y, 0, dst[1]);
    VSTORE(ys[e].z, 0, dst[2]);
    VSTORE(ys[e].vx, 0, dst[3]);
    VSTORE(ys[e].vy, 0, dst[4]);
    VSTORE(ys[e].vz, 0, dst[5]);
    VSTORE(ss[e], 0, dst[6]);
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
    buffered[l] = 0;
    t_hit[l] = RC(1);
    for (int c = 0; c < 8; ++c) q[c][l] = RC(0);
    if (!mv[l] || (flush && (predict[l] < 0 || chunk->points[l] < 2))) continue;
    const IDX seg = k[l] - 1; /* this step's index along the path (flush: the last one) */
    int found_kind = ARCUS_HIT_NONE, found = -1;
    REAL t = RC(1);
    if (predict[l] >= 0) {
      /* Skipping: keep the step's end in the chunk; close the chunk when it is full,
       * before the tested range, when the ray ends, or when the slice does. */
      if (!flush) {
        const int at = chunk->points[l];
        for (int c = 0; c < ARCUS_STATE_REALS; ++c) chunk->p[at][c][l] = a1[c][l];
        chunk->points[l] = at + 1;
      }
      const int last_skipped = seg + 2 >= predict[l]; /* step n − 1 comes next: test it */
      if (chunk->points[l] == ARCUS_SMART_CHUNK + 1 || last_skipped || en[l] || flush) {
        int ci = -1;
        /* The chunk holds the points from seg + 2 − points on. */
        const int peel = geo->from_surface && seg + 2 - chunk->points[l] == 0;
        const int chord =
            smart_chunk_close(chunk, l, peel, geo, nodes, tris, shapes, &tests[l], &found_kind, &found, &t);
        if (chord >= 0) {
          ci = chord;
          for (int c = 0; c < ARCUS_STATE_REALS; ++c) {
            h0[c][l] = chunk->p[ci][c][l];
            h1[c][l] = chunk->p[ci + 1][c][l];
          }
          buffered[l] = 1;
          hstep[l] = seg - (chunk->points[l] - 2 - ci);
        } else if (last_skipped) {
          predict[l] = -1; /* every skipped step is proved empty: test from here on */
        }
      }
      if (found_kind == ARCUS_HIT_NONE) continue;
    } else {
      tests[l] += 1;
      const REAL o[3] = {a0[0][l], a0[1][l], a0[2][l]};
      const REAL d[3] = {a1[0][l] - o[0], a1[1][l] - o[1], a1[2][l] - o[2]};
      found_kind = chord_hit(geo, nodes, tris, shapes, o, d, &found, &t);
      if (found_kind == ARCUS_HIT_NONE) continue;
      hstep[l] = seg;
      for (int c = 0; c < ARCUS_STATE_REALS; ++c) {
        h0[c][l] = a0[c][l];
        h1[c][l] = a1[c][l];
      }
    }
    hit[l] = 1;
    kind[l] = found_kind;
    index[l] = found;
    t_hit[l] = t;
    predict[l] = -1;
    REAL ql[8];
    const REAL from[3] = {h0[0][l], h0[1][l], h0[2][l]};
    hit_surface(found_kind, found, tris, shapes, from, ql);
    for (int c = 0; c < 8; ++c) q[c][l] = ql[c];
  }

  hs->kind = VLOAD(0, kind);
  hs->index = VLOAD(0, index);
  hs->tests = VLOAD(0, tests);
  hs->predict = VLOAD(0, predict);
  hs->step = VLOAD(0, hstep);
  const MASKV hits = VLOAD(0, hit) != (IDXV)0;
  if (!ANY(hits)) return;

  /* The hit chord's ends: this step's, or a buffered chord's (its start state exactly
   * as the integrator had it; no Kahan compensation, which is zero in double). */
  const MASKV from_chunk = VLOAD(0, buffered) != (IDXV)0;
  ray6 hy0, hy1;
  hy0.x = VLOAD(0, h0[0]), hy0.y = VLOAD(0, h0[1]), hy0.z = VLOAD(0, h0[2]);
  hy0.vx = VLOAD(0, h0[3]), hy0.vy = VLOAD(0, h0[4]), hy0.vz = VLOAD(0, h0[5]);
  hy1.x = VLOAD(0, h1[0]), hy1.y = VLOAD(0, h1[1]), hy1.z = VLOAD(0, h1[2]);
  hy1.vx = VLOAD(0, h1[3]), hy1.vy = VLOAD(0, h1[4]), hy1.vz = VLOAD(0, h1[5]);
  const REALV hs0 = VLOAD(0, h0[6]);
  REALV hs1 = VLOAD(0, h1[6]);
  ray6 zero = ray_times(comp0, (REALV)RC(0));
  ray6 hc0 = ray_select(comp0, zero, from_chunk);
  ray6 hc1 = ray_select(*comp1, zero, from_chunk);

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
  MASKV bracketed = hits & (surface_distance(job, &surf, hy1) > RC(0));
  if (geo->occlusion) bracketed = hits & !hits; /* none: the chord's hit point stands */
  const MASKV chord = hits & !bracketed;
  if (ANY(chord)) {
    const REALV t = VLOAD(0, t_hit);
    ray6 at = ray_step(hy0, t, ray_step(hy1, (REALV)RC(-1), hy0)); /* y0 + t·(y1 − y0) */
    hy1 = ray_select(hy1, at, chord);
    hs1 = SEL(hs1, hs0 + t * (hs1 - hs0), chord);
  }
  if (ANY(bracketed)) cross_surface(m, job, &surf, hy0, hc0, hs0, hs1 - hs0, &hy1, &hc1, &hs1, bracketed);
  *y1 = ray_select(*y1, hy1, hits);
  *comp1 = ray_select(*comp1, hc1, hits);
  *s1 = SEL(*s1, hs1, hits);
  *status = SEL(*status, (IDXV)ARCUS_STATUS_HIT, hits);
}

#endif /* ARCUS_USE_GEOMETRY */
