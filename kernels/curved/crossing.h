#ifdef ARCUS_USE_BOX
/* Where a ray's integrated path crosses a surface (ARCUS_USE_BOX): the surface of the
 * job's box, or a primitive the rendering engine's per-step hook found the step's chord
 * to hit (render/hits.h).  A step that ends beyond the surface is shortened, with the
 * method's own step from its start, until its end lies within job->cross_tol of the
 * surface: the end stays on the path the integrator would have taken (a chord between
 * the step's ends would miss it by O(h²·curvature)).  Regula falsi with the Illinois
 * modification on the signed distance along the step: the bracket always holds the
 * crossing, and the iteration converges superlinearly even when the path is curved. */

#define ARCUS_CROSSING_ITERATIONS 64

/* Signed distance of r from the box surface in the maximum norm: < 0 inside, > 0
 * outside, 0 on a face. */
ARCUS_INLINE REALV box_distance(const advance_desc* job, ray6 y) {
  REALV d = fmax(job->box_min[0] - y.x, y.x - job->box_max[0]);
  d = fmax(d, fmax(job->box_min[1] - y.y, y.y - job->box_max[1]));
  return fmax(d, fmax(job->box_min[2] - y.z, y.z - job->box_max[2]));
}

/* A surface other than the box, one per lane: the zero set of
 *   a·|p − c|² + n·(p − c) − d,
 * a plane (a = 0, n its unit normal, d = 0) or a sphere (a = 1/(2r), n = 0, d = r/2:
 * the value is (|p − c|² − r²)/(2r), the signed distance to first order near it).
 * Signs are chosen so that the step's start lies on the negative side.           */
typedef struct quadric {
  REALV a, cx, cy, cz, nx, ny, nz, d;
} quadric;

/* The box's distance (q null) or the quadric's value at y. */
ARCUS_INLINE REALV surface_distance(const advance_desc* job, const quadric* q, ray6 y) {
  if (!q) return box_distance(job, y);
  REALV px = y.x - q->cx, py = y.y - q->cy, pz = y.z - q->cz;
  return q->a * (px * px + py * py + pz * pz) + (q->nx * px + q->ny * py + q->nz * pz) - q->d;
}

/* Puts a coordinate within tol of a face onto it, so that the end of a ray that left
 * the box lies on the box exactly (it moves by at most the crossing tolerance). */
ARCUS_INLINE REALV snap(REALV v, REAL lo, REAL hi, REAL tol, MASKV m) {
  v = SEL(v, (REALV)lo, m & (fabs(v - lo) <= tol));
  return SEL(v, (REALV)hi, m & (fabs(v - hi) <= tol));
}

/* Lanes in `crossed` took the step y0 → *y1 (length h, from arc s0) whose end lies
 * beyond the surface (the box: q null; else the lanes' quadrics) although y0 lies on
 * its negative side: moves *y1, *comp1 and *s1 to where the path crosses it. */
ARCUS_INLINE void cross_surface(const medium* m, const advance_desc* job, const quadric* q, ray6 y0, ray6 comp0,
                                REALV s0, REALV h, ray6* y1, ray6* comp1, REALV* s1, MASKV crossed) {
  REALV t_lo = RC(0), t_hi = RC(1);
  REALV g_lo = surface_distance(job, q, y0), g_hi = surface_distance(job, q, *y1);
  ray6 y_lo = y0, c_lo = comp0;
  IDXV side = 0; /* which end moved last: −1 the inner, +1 the outer (Illinois) */
  MASKV searching = crossed;
  for (int it = 0; it < ARCUS_CROSSING_ITERATIONS && ANY(searching); ++it) {
    REALV t = t_lo - g_lo * (t_hi - t_lo) / (g_hi - g_lo);
    t = SEL(t, RC(0.5) * (t_lo + t_hi), !((t > t_lo) & (t < t_hi))); /* bisect when flat */
    ray6 c = comp0, yt;
    REALV n;
    method_steps(m, &y0, &yt, &c, t * h, &n, 1);
    REALV g = surface_distance(job, q, yt);
    MASKV done = searching & (fabs(g) <= job->cross_tol);
    MASKV inner = searching & !(g > RC(0)); /* on or inside: the crossing lies beyond t */
    MASKV outer = searching & (g > RC(0)) & !done;
    g_hi = SEL(g_hi, RC(0.5) * g_hi, inner & !done & (side == (IDXV)-1));
    g_lo = SEL(g_lo, RC(0.5) * g_lo, outer & (side == (IDXV)1));
    /* A point within the tolerance ends the search, on either side of the surface. */
    MASKV take_lo = inner | done;
    t_lo = SEL(t_lo, t, take_lo);
    g_lo = SEL(g_lo, g, inner & !done);
    y_lo = ray_select(y_lo, yt, take_lo);
    c_lo = ray_select(c_lo, c, take_lo);
    t_hi = SEL(t_hi, t, outer);
    g_hi = SEL(g_hi, g, outer);
    side = SEL(side, (IDXV)-1, inner);
    side = SEL(side, (IDXV)1, outer);
    searching &= !done;
  }
  /* Lanes that did not converge keep the last point on the start's side. */
  if (!q) {
    y_lo.x = snap(y_lo.x, job->box_min[0], job->box_max[0], job->cross_tol, crossed);
    y_lo.y = snap(y_lo.y, job->box_min[1], job->box_max[1], job->cross_tol, crossed);
    y_lo.z = snap(y_lo.z, job->box_min[2], job->box_max[2], job->cross_tol, crossed);
  }
  *y1 = ray_select(*y1, y_lo, crossed);
  *comp1 = ray_select(*comp1, c_lo, crossed);
  *s1 = SEL(*s1, s0 + t_lo * h, crossed);
}
ARCUS_INLINE void cross_box(const medium* m, const advance_desc* job, ray6 y0, ray6 comp0, REALV s0, REALV h,
                            ray6* y1, ray6* comp1, REALV* s1, MASKV crossed) {
  cross_surface(m, job, 0, y0, comp0, s0, h, y1, comp1, s1, crossed);
}
#endif /* ARCUS_USE_BOX */
