/* The ray state of the ray equation (thesis §4.1.6, eq. 4.2):
 *   d/ds (n dr/ds) = ∇n   as the first-order system in (r, v = n·dr/ds):
 *   dr/ds = v / n,  dv/ds = ∇n,
 * and the arithmetic the integrators do on it, one lane group at a time.            */

typedef struct ray6 {
  REALV x, y, z;    /* r, or dr/ds */
  REALV vx, vy, vz; /* v, or dv/ds */
} ray6;

/* The right-hand side of the ray equation at y; *n_out: n there. */
ARCUS_INLINE ray6 ray_derivative(const medium* m, ray6 y, REALV* n_out) {
  ray6 d;
  REALV n;
  field_eval(m, y.x, y.y, y.z, &n, &d.vx, &d.vy, &d.vz);
  REALV inv_n = RC(1) / n;
  d.x = y.vx * inv_n;
  d.y = y.vy * inv_n;
  d.z = y.vz * inv_n;
  *n_out = n;
  return d;
}

/* h·k, h per lane */
ARCUS_INLINE ray6 ray_times(ray6 k, REALV h) {
  ray6 r;
  r.x = h * k.x;
  r.y = h * k.y;
  r.z = h * k.z;
  r.vx = h * k.vx;
  r.vy = h * k.vy;
  r.vz = h * k.vz;
  return r;
}

/* c·k */
ARCUS_INLINE ray6 ray_scale(ray6 k, REAL c) { return ray_times(k, (REALV)c); }

/* acc + c·k */
ARCUS_INLINE ray6 ray_fma(ray6 k, REAL c, ray6 acc) {
  ray6 r;
  r.x = fma((REALV)c, k.x, acc.x);
  r.y = fma((REALV)c, k.y, acc.y);
  r.z = fma((REALV)c, k.z, acc.z);
  r.vx = fma((REALV)c, k.vx, acc.vx);
  r.vy = fma((REALV)c, k.vy, acc.vy);
  r.vz = fma((REALV)c, k.vz, acc.vz);
  return r;
}

/* y + h·t, h per lane */
ARCUS_INLINE ray6 ray_step(ray6 y, REALV h, ray6 t) {
  ray6 r;
  r.x = fma(h, t.x, y.x);
  r.y = fma(h, t.y, y.y);
  r.z = fma(h, t.z, y.z);
  r.vx = fma(h, t.vx, y.vx);
  r.vy = fma(h, t.vy, y.vy);
  r.vz = fma(h, t.vz, y.vz);
  return r;
}

/* b where m holds, else a */
ARCUS_INLINE ray6 ray_select(ray6 a, ray6 b, MASKV m) {
  ray6 r;
  r.x = SEL(a.x, b.x, m);
  r.y = SEL(a.y, b.y, m);
  r.z = SEL(a.z, b.z, m);
  r.vx = SEL(a.vx, b.vx, m);
  r.vy = SEL(a.vy, b.vy, m);
  r.vz = SEL(a.vz, b.vz, m);
  return r;
}

/* y + h·t, the update of the state at the end of a step.  In float, positions of
 * hundreds of metres lose the low bits of every small step (RK4, 10⁵ steps of 0.01 m:
 * 0.54 m off), so the float path carries what was lost in *comp (Kahan summation); in
 * double *comp is not touched and compiles away. */
ARCUS_INLINE ray6 ray_advance(ray6 y, REALV h, ray6 t, ray6* comp) {
#ifdef ARCUS_USE_FLOAT
  ray6 d = ray_fma(*comp, RC(-1), ray_times(t, h));
  ray6 sum = ray_fma(d, RC(1), y);
  *comp = ray_fma(d, RC(-1), ray_fma(y, RC(-1), sum)); /* (sum − y) − d */
  return sum;
#else
  return ray_step(y, h, t);
#endif
}

/* Each component on its own: a sum of large finite coordinates can overflow. */
ARCUS_INLINE MASKV ray_finite(ray6 y) {
  return isfinite(y.x) & isfinite(y.y) & isfinite(y.z) & isfinite(y.vx) & isfinite(y.vy) & isfinite(y.vz);
}
