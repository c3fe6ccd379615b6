/* The collecting sphere's queries (thesis §4.4.3.2-4.4.3.3): for each direction, every
 * patch holding it, found by walking the shared BVH over the patches' chord triangles
 * with the segment from the centre along the direction (all hits, not the closest);
 * in each, the corners' phasors and optical path interpolated bilinearly at the
 * direction, and the sum over patches with the phase of the path and the focal lines
 * (eq. 4.31).  One direction per work-item, scalar: the walks differ per direction.
 *
 * corners  12 reals per patch corner record: direction (3), the four phasors (8) already
 *          normalised by eq. 4.29 and turned by −π/2 per focal line, optical path (1)
 * patches  rainbow_patch per patch; triangle t of the BVH is half t % 2 of patch t / 2
 * dirs     3 reals per query direction (unit)
 * out      per direction and term: ARCUS_RAINBOW_QUERY_REALS (rainbow_desc.h)
 *
 * Host prepends: common/real.h, bvh/bvh_desc.h, bvh/traverse.h, rainbow/rainbow_desc.h,
 * rainbow/optics.h. */

/* The bilinear coordinates (s, t) of the direction d in the patch with corners c0..c3
 * (unit vectors): B(s, t) = c0 + s·(c1 − c0) + t·(c3 − c0) + s·t·(c0 − c1 + c2 − c3)
 * parallel to d, by Newton's method in the plane normal to d, from the start the chord
 * triangle's hit gave.  The patch is a small piece of the sphere, so a few steps reach
 * rounding; a patch folded across a caustic has two solutions and the start picks the
 * one in the triangle that was hit. */
ARCUS_INLINE void rb_bilinear_coordinates(const REAL* c0, const REAL* c1, const REAL* c2, const REAL* c3,
                                          const REAL* d, REAL* s, REAL* t) {
  REAL e1[3], e2[3];
  rb_any_normal(d, e1);
  rb_cross(d, e1, e2);
  REAL es[3], et[3], ex[3];
  for (int a = 0; a < 3; ++a) {
    es[a] = c1[a] - c0[a];
    et[a] = c3[a] - c0[a];
    ex[a] = c0[a] - c1[a] + c2[a] - c3[a];
  }
  for (int it = 0; it < 6; ++it) {
    REAL b[3], bs[3], bt[3];
    for (int a = 0; a < 3; ++a) {
      b[a] = c0[a] + *s * es[a] + *t * et[a] + *s * *t * ex[a];
      bs[a] = es[a] + *t * ex[a];
      bt[a] = et[a] + *s * ex[a];
    }
    const REAL g1 = rb_dot(b, e1), g2 = rb_dot(b, e2);
    const REAL j11 = rb_dot(bs, e1), j12 = rb_dot(bt, e1), j21 = rb_dot(bs, e2), j22 = rb_dot(bt, e2);
    const REAL det = j11 * j22 - j12 * j21;
    if (!(fabs(det) > RC(0))) break;
    const REAL ds = (g1 * j22 - g2 * j12) / det, dt = (j11 * g2 - j21 * g1) / det;
    *s -= ds;
    *t -= dt;
    if (fabs(ds) + fabs(dt) < RC(1e-13)) break;
  }
  *s = clamp(*s, RC(0), RC(1));
  *t = clamp(*t, RC(0), RC(1));
}

__kernel void arcus_rainbow_query(__global const bvh_node* nodes, __global const REAL* tris,
                                  __global const int* order, __global const REAL* corners,
                                  __global const rainbow_patch* patches, __global const REAL* dirs,
                                  const rainbow_query_desc q, __global REAL* out) {
  const int i = (int)get_global_id(0);
  if (i >= q.count) return;
  __global REAL* o = out + (size_t)i * (size_t)q.terms * ARCUS_RAINBOW_QUERY_REALS;
  for (int c = 0; c < q.terms * ARCUS_RAINBOW_QUERY_REALS; ++c) o[c] = RC(0);
  const REAL d[3] = {dirs[3 * i], dirs[3 * i + 1], dirs[3 * i + 2]};
  bvh_ray r;
  bvh_ray_init(&r, RC(0), RC(0), RC(0), d[0], d[1], d[2]);
  bvh_walk w;
  REAL near, th, u, v;
  int tests = 0, s;
  /* chords lie inside the unit sphere: t ≤ 1 */
  bvh_walk_start(&w, nodes, bvh_ray_box(&r, nodes, RC(1), &near));
  while ((s = bvh_segment_next(nodes, tris, &r, RC(1), &w, &th, &u, &v, &tests)) >= 0) {
    const int tri = order[s];
    const rainbow_patch pt = patches[tri / 2];
    __global const REAL* c[4];
    for (int k = 0; k < 4; ++k) c[k] = corners + (size_t)pt.corner[k] * 12;
    REAL cc[4][3];
    for (int k = 0; k < 4; ++k)
      for (int a = 0; a < 3; ++a) cc[k][a] = c[k][a];
    /* the start: triangle (0, 1, 2) is (s, t) = (u + v, v); triangle (0, 2, 3) is (u, u + v) */
    REAL bs = tri % 2 == 0 ? u + v : u, bt = tri % 2 == 0 ? v : u + v;
    rb_bilinear_coordinates(cc[0], cc[1], cc[2], cc[3], d, &bs, &bt);
    const REAL wgt[4] = {(RC(1) - bs) * (RC(1) - bt), bs * (RC(1) - bt), bs * bt, (RC(1) - bs) * bt};
    REAL e[9];
    for (int x = 0; x < 9; ++x) e[x] = wgt[0] * c[0][3 + x] + wgt[1] * c[1][3 + x] + wgt[2] * c[2][3 + x] + wgt[3] * c[3][3 + x];
    /* eq. 4.31: the optical path's phase (the focal lines' is in the corners already) */
    const REAL phase = q.wave_number * e[8];
    const rb_complex shift = rb_c(cos(phase), sin(phase));
    __global REAL* op = o + (size_t)pt.p * ARCUS_RAINBOW_QUERY_REALS;
    for (int k = 0; k < 4; ++k) {
      const rb_complex z = rb_mul(rb_c(e[2 * k], e[2 * k + 1]), shift);
      op[2 * k] += z.re;
      op[2 * k + 1] += z.im;
      op[8 + k] += e[2 * k] * e[2 * k] + e[2 * k + 1] * e[2 * k + 1];
    }
  }
}
