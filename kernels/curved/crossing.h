#ifdef ARCUS_USE_BOX
/* Where a ray's integrated path crosses a surface (ARCUS_USE_BOX): the surface of
 * the job's box today, an intersected primitive in the rendering engine.  A step that
 * ends beyond the surface is shortened, with the method's own step from its start, until
 * its end lies within job->cross_tol of the surface: the end stays on the path the
 * integrator would have taken (a chord between the step's ends would miss it by
 * O(h²·curvature)).  Regula falsi with the Illinois modification on the signed
 * distance along the step: the bracket always holds the crossing, and the iteration
 * converges superlinearly even when the path is curved.                             */

#define ARCUS_CROSSING_ITERATIONS 64

/* Signed distance of r from the box surface in the maximum norm: < 0 inside, > 0
 * outside, 0 on a face. */
ARCUS_INLINE REALV box_distance(const advance_desc* job, ray6 y) {
  REALV d = fmax(job->box_min[0] - y.x, y.x - job->box_max[0]);
  d = fmax(d, fmax(job->box_min[1] - y.y, y.y - job->box_max[1]));
  return fmax(d, fmax(job->box_min[2] - y.z, y.z - job->box_max[2]));
}

/* Puts a coordinate within tol of a face onto it, so that the end of a ray that left
 * the box lies on the box exactly (it moves by at most the crossing tolerance). */
ARCUS_INLINE REALV snap(REALV v, REAL lo, REAL hi, REAL tol, MASKV m) {
  v = SEL(v, (REALV)lo, m & (fabs(v - lo) <= tol));
  return SEL(v, (REALV)hi, m & (fabs(v - hi) <= tol));
}

/* Lanes in `crossed` took the step y0 → *y1 (length h, from arc s0) whose end lies
 * outside the box although y0 lies inside: moves *y1, *comp1 and *s1 to where the path
 * crosses the box. */
ARCUS_INLINE void cross_box(const medium* m, const advance_desc* job, ray6 y0, ray6 comp0, REALV s0, REALV h,
                            ray6* y1, ray6* comp1, REALV* s1, MASKV crossed) {
  REALV t_lo = RC(0), t_hi = RC(1);
  REALV g_lo = box_distance(job, y0), g_hi = box_distance(job, *y1);
  ray6 y_lo = y0, c_lo = comp0;
  IDXV side = 0; /* which end moved last: −1 the inner, +1 the outer (Illinois) */
  MASKV searching = crossed;
  for (int it = 0; it < ARCUS_CROSSING_ITERATIONS && ANY(searching); ++it) {
    REALV t = t_lo - g_lo * (t_hi - t_lo) / (g_hi - g_lo);
    t = SEL(t, RC(0.5) * (t_lo + t_hi), !((t > t_lo) & (t < t_hi))); /* bisect when flat */
    ray6 c = comp0, yt;
    REALV n;
    method_steps(m, &y0, &yt, &c, t * h, &n, 1);
    REALV g = box_distance(job, yt);
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
  /* Lanes that did not converge keep the last point inside the box. */
  y_lo.x = snap(y_lo.x, job->box_min[0], job->box_max[0], job->cross_tol, crossed);
  y_lo.y = snap(y_lo.y, job->box_min[1], job->box_max[1], job->cross_tol, crossed);
  y_lo.z = snap(y_lo.z, job->box_min[2], job->box_max[2], job->cross_tol, crossed);
  *y1 = ray_select(*y1, y_lo, crossed);
  *comp1 = ray_select(*comp1, c_lo, crossed);
  *s1 = SEL(*s1, s0 + t_lo * h, crossed);
}
#endif /* ARCUS_USE_BOX */
