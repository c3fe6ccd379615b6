/* The collecting sphere's queries (thesis §4.4.3.2-4.4.3.3): for each direction, every
 * patch holding it, found by walking the shared BVH over the patches' chord triangles
 * with the segment from the centre along the direction (all hits, not the closest);
 * in each, the corners' phasors and optical path interpolated bilinearly at the
 * direction, and the sum over patches with the phase of the path and the focal lines
 * (eq. 4.31).  One direction per work-item, scalar: the walks differ per direction.
 *
 * corners  ARCUS_RAINBOW_CORNER reals per patch corner (rainbow_desc.h)
 * patches  rainbow_patch per patch; triangle t of the BVH is half t % 2 of patch t / 2
 * dirs     3 reals per query direction (unit)
 * out      per direction and term: ARCUS_RAINBOW_QUERY_REALS (rainbow_desc.h)
 *
 * Near a fold caustic — the rainbow angle of a term — the two rays of the term that meet
 * there have amplitudes that grow without bound as they merge (geometric optics), while
 * the wave's intensity peaks at the Airy maximum a little inside the bow.  Where a
 * direction lies in exactly two patches of one term whose rays passed focal lines
 * differing by one, and whose phases lie within a few fringes of each other, their sum
 * is replaced by the uniform approximation of Chester, Friedman & Ursell (1957; Kravtsov
 * 1964, Ludwig 1966 for waves), which is the Airy function's form of the same two
 * rays: with Φ± their path phases (Φ+ for the ray with the extra focal line, which has
 * the larger), ξ = (Φ+ − Φ−)/2, ζ = (3ξ/2)^{2/3} and a± their amplitudes without phases,
 *   U = e^{i(Φc − π/2·F− − π/4)} √π [(a+ + a−) ζ^{1/4} Ai(−ζ) + i (a+ − a−) ζ^{−1/4} Ai'(−ζ)],
 * Φc = (Φ+ + Φ−)/2, which tends to the two rays' sum a few fringes away (where it is no
 * longer applied) and stays finite at the caustic.  The dark side, where no ray goes,
 * stays dark.
 *
 * Host prepends: common/real.h, bvh/bvh_desc.h, bvh/traverse.h, rainbow/rainbow_desc.h,
 * rainbow/optics.h, rainbow/airy.h. */

/* The pairing remembers the first two contributions of each term (a term with more
 * than two patches at a direction is no single fold there and keeps its plain sum).
 * Slots per term, not one shared pool: a pool of 8 filled up at P ≥ 5, where the
 * terms p = 4…P send several patches each to the primary bow's angles, and left the
 * primary's two rays unpaired there — their plain sum, 6× Debye's p = 2 peak at 100 µm. */
#define RB_PAIR_SLOTS (2 * (ARCUS_RAINBOW_MAX_BOUNCES + 1))
#define RB_UNIFORM_ZETA 30 /* ζ beyond which the two rays' sum is the Airy form to ~1e-6 */

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
  const REAL s0 = *s, t0 = *t;
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
  /* A patch with two coinciding corners has a singular Jacobian somewhere: where Newton
   * left the reals, the chord triangle's own coordinates stand. */
  if (!(isfinite(*s) && isfinite(*t))) {
    *s = s0;
    *t = t0;
  }
  *s = clamp(*s, RC(0), RC(1));
  *t = clamp(*t, RC(0), RC(1));
}

__kernel void arcus_rainbow_query(ARCUS_PARAMS(ARCUS_RAINBOW_QUERY_ARGS)) {
  const int i = (int)get_global_id(0);
  if (i >= q.count) return;
  __global REAL* o = out + (size_t)i * (size_t)q.terms * ARCUS_RAINBOW_QUERY_REALS;
  for (int c = 0; c < q.terms * ARCUS_RAINBOW_QUERY_REALS; ++c) o[c] = RC(0);
  const REAL d[3] = {dirs[3 * i], dirs[3 * i + 1], dirs[3 * i + 2]};
  /* the contributions, for the pairing at caustics: per term the number of patches
   * holding the direction and the first two's focal lines, path phases and four
   * amplitudes without phases (slots 2p and 2p + 1) */
  int kept_n[ARCUS_RAINBOW_MAX_BOUNCES + 1], kept_f[RB_PAIR_SLOTS];
  REAL kept_phase[RB_PAIR_SLOTS], kept_a[RB_PAIR_SLOTS][8];
  for (int p = 0; p <= ARCUS_RAINBOW_MAX_BOUNCES; ++p) kept_n[p] = 0;
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
    for (int k = 0; k < 4; ++k) c[k] = corners + (size_t)pt.corner[k] * ARCUS_RAINBOW_CORNER;
    REAL cc[4][3];
    for (int k = 0; k < 4; ++k)
      for (int a = 0; a < 3; ++a) cc[k][a] = c[k][a];
    /* the start: triangle (0, 1, 2) is (s, t) = (u + v, v); triangle (0, 2, 3) is (u, u + v) */
    REAL bs = tri % 2 == 0 ? u + v : u, bt = tri % 2 == 0 ? v : u + v;
    rb_bilinear_coordinates(cc[0], cc[1], cc[2], cc[3], d, &bs, &bt);
    if (!(isfinite(bs) && isfinite(bt))) continue; /* a degenerate chord triangle's hit */
    const REAL wgt[4] = {(RC(1) - bs) * (RC(1) - bt), bs * (RC(1) - bt), bs * bt, (RC(1) - bs) * bt};
    REAL e[9];
    for (int x = 0; x < 9; ++x)
      e[x] = wgt[0] * c[0][3 + x] + wgt[1] * c[1][3 + x] + wgt[2] * c[2][3 + x] + wgt[3] * c[3][3 + x];
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
    if (q.coherent && kept_n[pt.p]++ < 2) {
      const int slot = 2 * pt.p + kept_n[pt.p] - 1;
      const int focal = (int)c[0][12]; /* a kept patch's corners all passed the same */
      const REAL back = RC(1.5707963267948966) * (REAL)focal; /* undo the corners' −π/2·F */
      const rb_complex unturn = rb_c(cos(back), sin(back));
      kept_f[slot] = focal;
      kept_phase[slot] = phase;
      for (int k = 0; k < 4; ++k) {
        const rb_complex a = rb_mul(rb_c(e[2 * k], e[2 * k + 1]), unturn);
        kept_a[slot][2 * k] = a.re;
        kept_a[slot][2 * k + 1] = a.im;
      }
    }
  }
  /* the uniform approximation where a term's two rays meet at a fold */
  for (int p = 0; p < q.terms && q.coherent; ++p) {
    const int first = 2 * p, second = 2 * p + 1;
    if (kept_n[p] != 2 || abs(kept_f[first] - kept_f[second]) != 1) continue;
    const int hi = kept_f[first] > kept_f[second] ? first : second, lo = hi == first ? second : first;
    const REAL xi = RC(0.5) * (kept_phase[hi] - kept_phase[lo]);
    if (!(xi > RC(0))) continue; /* not the two rays of one fold */
    const REAL zeta = pow(RC(1.5) * xi, RC(2) / RC(3));
    if (zeta > RC(RB_UNIFORM_ZETA)) continue;
    REAL ai, aip;
    rb_airy_negative(zeta, &ai, &aip);
    const REAL z4 = sqrt(sqrt(fmax(zeta, RC(1e-30))));
    const REAL common = RC(0.5) * (kept_phase[hi] + kept_phase[lo]) -
                        RC(1.5707963267948966) * (REAL)kept_f[lo] - RC(0.785398163397448310);
    const rb_complex lead = rb_c(cos(common), sin(common));
    const REAL root_pi = RC(1.77245385090551603);
    __global REAL* op = o + (size_t)p * ARCUS_RAINBOW_QUERY_REALS;
    for (int k = 0; k < 4; ++k) {
      const rb_complex sum = rb_c(kept_a[hi][2 * k] + kept_a[lo][2 * k], kept_a[hi][2 * k + 1] + kept_a[lo][2 * k + 1]);
      const rb_complex diff =
          rb_c(kept_a[hi][2 * k] - kept_a[lo][2 * k], kept_a[hi][2 * k + 1] - kept_a[lo][2 * k + 1]);
      /* (a+ + a−) ζ^{1/4} Ai + i (a+ − a−) ζ^{−1/4} Ai' */
      const rb_complex inner = rb_c(sum.re * z4 * ai - diff.im * aip / z4, sum.im * z4 * ai + diff.re * aip / z4);
      const rb_complex uni = rb_scale(rb_mul(lead, inner), root_pi);
      /* replace the two rays' plain sum by it */
      for (int j = 0; j < 2; ++j) {
        const int m = j ? hi : lo;
        const REAL ph = kept_phase[m] - RC(1.5707963267948966) * (REAL)kept_f[m];
        const rb_complex ray = rb_mul(rb_c(kept_a[m][2 * k], kept_a[m][2 * k + 1]), rb_c(cos(ph), sin(ph)));
        op[2 * k] -= ray.re;
        op[2 * k + 1] -= ray.im;
      }
      op[2 * k] += uni.re;
      op[2 * k + 1] += uni.im;
    }
  }
}
