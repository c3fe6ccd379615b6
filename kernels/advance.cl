/* Batched ray advance through a non-linear medium (thesis §4.1.6, eq. 4.2):
 *   d/ds (n dr/ds) = ∇n   as the first-order system in (r, v = n·dr/ds):
 *   dr/ds = v / n,  dv/ds = ∇n.
 * Methods (thesis §4.3.5): Euler, RK2 (midpoint), RK4, Dormand–Prince 5(4) with FSAL
 * and a per-ray adaptive step; or, for a constant field, one straight segment.
 *
 * Layout: each work-item holds ARCUS_GROUPS independent groups of ARCUS_LANES rays.
 * The lanes give SIMD on PoCL; the independent groups give the core several
 * dependency chains to overlap (../shared/notes/opencl-on-pocl.md).  On a GPU both
 * are 1: one ray per work-item.
 *
 * Compiled with exactly one of ARCUS_METHOD_{STRAIGHT,EULER,RK2,RK4,DP45}, with
 * ARCUS_FIELD_KIND, and optionally ARCUS_FEATURE_BOX, ARCUS_FEATURE_RECORD_PATH,
 * ARCUS_FEATURE_FLOAT.  The host prepends arcus_real.h, field.h and advance.h.      */

typedef struct ray6 {
  REALV x, y, z;    /* r, or dr/ds */
  REALV vx, vy, vz; /* v, or dv/ds */
} ray6;

/* The right-hand side of the ray equation. */
ARCUS_INLINE ray6 ray_derivative(const field_desc* f, __global const REAL* data, ray6 y) {
  ray6 d;
  REALV n;
  field_eval(f, data, y.x, y.y, y.z, &n, &d.vx, &d.vy, &d.vz);
  REALV inv_n = RC(1) / n;
  d.x = y.vx * inv_n;
  d.y = y.vy * inv_n;
  d.z = y.vz * inv_n;
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
#ifdef ARCUS_FEATURE_FLOAT
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

/* The groups advance in lockstep, one stage at a time for all of them, so each stage
 * offers ARCUS_GROUPS independent dependency chains to the core (a single chain is
 * latency-bound: measured 3× slower).  FOR_GROUPS loops are fully unrolled. */
#define FOR_GROUPS(g) _Pragma("unroll") for (int g = 0; g < ARCUS_GROUPS; ++g)

/* ---------------------------------------------------------------- fixed steps */
/* y_new[g] = one step of length h from y[g], for every group; comp: see ray_advance. */
#if defined(ARCUS_METHOD_STRAIGHT) || defined(ARCUS_METHOD_EULER)
/* Straight: a constant field has ∇n = 0, so one step r + L·v/n is exact. */
ARCUS_INLINE void fixed_step(const field_desc* f, __global const REAL* data, const ray6* y, ray6* y_new, ray6* comp,
                             REALV h) {
  FOR_GROUPS(g) y_new[g] = ray_advance(y[g], h, ray_derivative(f, data, y[g]), &comp[g]);
}
#elif defined(ARCUS_METHOD_RK2)
/* Explicit midpoint. */
ARCUS_INLINE void fixed_step(const field_desc* f, __global const REAL* data, const ray6* y, ray6* y_new, ray6* comp,
                             REALV h) {
  ray6 k[ARCUS_GROUPS];
  FOR_GROUPS(g) k[g] = ray_derivative(f, data, y[g]);
  FOR_GROUPS(g) k[g] = ray_derivative(f, data, ray_step(y[g], RC(0.5) * h, k[g]));
  FOR_GROUPS(g) y_new[g] = ray_advance(y[g], h, k[g], &comp[g]);
}
#elif defined(ARCUS_METHOD_RK4)
/* Classical fourth order: k = k1..k4 in turn, acc = k1 + 2 k2 + 2 k3 + k4. */
ARCUS_INLINE void fixed_step(const field_desc* f, __global const REAL* data, const ray6* y, ray6* y_new, ray6* comp,
                             REALV h) {
  const REALV half_h = RC(0.5) * h;
  ray6 k[ARCUS_GROUPS], acc[ARCUS_GROUPS];
  FOR_GROUPS(g) {
    k[g] = ray_derivative(f, data, y[g]);
    acc[g] = k[g];
  }
  FOR_GROUPS(g) {
    k[g] = ray_derivative(f, data, ray_step(y[g], half_h, k[g]));
    acc[g] = ray_fma(k[g], RC(2), acc[g]);
  }
  FOR_GROUPS(g) {
    k[g] = ray_derivative(f, data, ray_step(y[g], half_h, k[g]));
    acc[g] = ray_fma(k[g], RC(2), acc[g]);
  }
  FOR_GROUPS(g) {
    k[g] = ray_derivative(f, data, ray_step(y[g], h, k[g]));
    y_new[g] = ray_advance(y[g], h * RC(1.0 / 6.0), ray_fma(k[g], RC(1), acc[g]), &comp[g]);
  }
}
#endif

/* ---------------------------------------------------------------- box and path */
#ifdef ARCUS_FEATURE_BOX
/* Shrinks t, the fraction of the step p0 → p1 that stays inside [lo, hi]. */
ARCUS_INLINE REALV box_axis_fraction(REALV t, REALV p0, REALV p1, REAL lo, REAL hi) {
  t = SEL(t, fmin(t, (hi - p0) / (p1 - p0)), p1 > hi);
  t = SEL(t, fmin(t, (lo - p0) / (p1 - p0)), p1 < lo);
  return t;
}

/* Lanes in `moved` whose step y0 → *y1 left the box end where the chord crosses the
 * face (linear interpolation: exact for straight rays, O(h²·curvature) otherwise). */
ARCUS_INLINE MASKV clip_to_box(const advance_desc* job, ray6 y0, REALV s0, ray6* y1, REALV* s1, MASKV moved) {
  REALV t = RC(1);
  t = box_axis_fraction(t, y0.x, y1->x, job->box_min[0], job->box_max[0]);
  t = box_axis_fraction(t, y0.y, y1->y, job->box_min[1], job->box_max[1]);
  t = box_axis_fraction(t, y0.z, y1->z, job->box_min[2], job->box_max[2]);
  MASKV left = moved & (t < RC(1));
  ray6 d = ray_fma(y0, RC(-1), *y1);
  *y1 = ray_select(*y1, ray_step(y0, t, d), left);
  *s1 = SEL(*s1, s0 + t * (*s1 - s0), left);
  return left;
}

ARCUS_INLINE MASKV outside_box(const advance_desc* job, ray6 y) {
  return (y.x < job->box_min[0]) | (y.x > job->box_max[0]) | (y.y < job->box_min[1]) | (y.y > job->box_max[1]) |
         (y.z < job->box_min[2]) | (y.z > job->box_max[2]);
}
#endif

#ifdef ARCUS_FEATURE_RECORD_PATH
/* Appends the current point of the lanes in `moved`; counts every point, so a count
 * above the capacity tells the host how much room the path needed. */
ARCUS_INLINE void record_point(__global REAL* path, int capacity, size_t first_ray, ray6 y, MASKV moved, IDXV* count) {
  REAL xs[ARCUS_LANES], ys[ARCUS_LANES], zs[ARCUS_LANES];
  IDX cs[ARCUS_LANES], ms[ARCUS_LANES];
  VSTORE(y.x, 0, xs);
  VSTORE(y.y, 0, ys);
  VSTORE(y.z, 0, zs);
  VSTORE_IDX(*count, 0, cs);
  VSTORE_IDX((IDXV)moved, 0, ms);
  for (int l = 0; l < ARCUS_LANES; ++l) {
    if (!ms[l]) continue;
    if (cs[l] < capacity) {
      __global REAL* p = path + ((first_ray + l) * (size_t)capacity + (size_t)cs[l]) * 3;
      p[0] = xs[l];
      p[1] = ys[l];
      p[2] = zs[l];
    }
    cs[l] += 1;
  }
  *count = VLOAD(0, cs);
}
#define RECORD(g, moved) \
  record_point(path, job.path_capacity, (first_vector + (g)) * ARCUS_LANES, y[g], (moved), &points[g])
#else
#define RECORD(g, moved)
#endif

/* ---------------------------------------------------------------- Dormand–Prince */
#ifdef ARCUS_METHOD_DP45
/* Dormand & Prince (1980) 5(4) coefficients; the 7th stage is the next step's first
 * (FSAL).  E = b5 − b4 weighs the embedded error estimate. */
#define A21 (1.0 / 5.0)
#define A31 (3.0 / 40.0)
#define A32 (9.0 / 40.0)
#define A41 (44.0 / 45.0)
#define A42 (-56.0 / 15.0)
#define A43 (32.0 / 9.0)
#define A51 (19372.0 / 6561.0)
#define A52 (-25360.0 / 2187.0)
#define A53 (64448.0 / 6561.0)
#define A54 (-212.0 / 729.0)
#define A61 (9017.0 / 3168.0)
#define A62 (-355.0 / 33.0)
#define A63 (46732.0 / 5247.0)
#define A64 (49.0 / 176.0)
#define A65 (-5103.0 / 18656.0)
#define B1 (35.0 / 384.0)
#define B3 (500.0 / 1113.0)
#define B4 (125.0 / 192.0)
#define B5 (-2187.0 / 6784.0)
#define B6 (11.0 / 84.0)
#define E1 (71.0 / 57600.0)
#define E3 (-71.0 / 16695.0)
#define E4 (71.0 / 1920.0)
#define E5 (-17253.0 / 339200.0)
#define E6 (22.0 / 525.0)
#define E7 (-1.0 / 40.0)

/* Largest |err_i| / (atol + rtol·max(|y_i|, |y5_i|)) over the six components. */
#define DP_ERR_TERM(c) fabs(err.c) / (job->atol + job->rtol * fmax(fabs(y.c), fabs(y5.c)))
ARCUS_INLINE REALV dp_error_norm(const advance_desc* job, ray6 y, ray6 y5, ray6 err) {
  REALV e = DP_ERR_TERM(x);
  e = fmax(e, DP_ERR_TERM(y));
  e = fmax(e, DP_ERR_TERM(z));
  e = fmax(e, DP_ERR_TERM(vx));
  e = fmax(e, DP_ERR_TERM(vy));
  return fmax(e, DP_ERR_TERM(vz));
}

/* Step-size factor 0.9·err^(−1/5) in [0.2, 5].  Computed in float with exp2/log2:
 * double pow costs ~100 ns on PoCL and the factor needs no more precision.  A NaN or
 * huge error (a non-finite trial state) takes the smallest factor. */
ARCUS_INLINE REALV dp_step_factor(REALV err) {
  err = SEL((REALV)RC(1e10), fmax(err, RC(1e-10)), err <= RC(1e10));
  FLOATV fac = 0.9f * exp2(-0.2f * log2(TO_FLOATV(err)));
  return TO_REALV(clamp(fac, 0.2f, 5.0f));
}

/* Accepts or rejects one group's trial step from y to y5 (error estimate err) and
 * adapts its step size. */
ARCUS_INLINE MASKV dp_decide(const advance_desc* job, ray6* y, ray6* comp, ray6* k1, REALV* s, REALV* h, IDXV* steps,
                             IDXV* rejections, IDXV* status, REALV h_try, MASKV last, ray6 y5, ray6 comp5, ray6 k7,
                             ray6 err) {
  MASKV active = *status == (IDXV)ARCUS_STATUS_ACTIVE;
  REALV norm = dp_error_norm(job, *y, y5, err);
  MASKV accept = active & (norm <= RC(1));
  MASKV reject = active & !(norm <= RC(1));
  *y = ray_select(*y, y5, accept);
  *comp = ray_select(*comp, comp5, accept);
  *k1 = ray_select(*k1, k7, accept);
  *s = SEL(*s, SEL(*s + h_try, (REALV)job->length, last), accept);
  *steps += ONE_IF(accept);
  *rejections = SEL(*rejections + ONE_IF(reject), (IDXV)0, accept);

  REALV h_next = h_try * dp_step_factor(norm);
  if (job->max_step > RC(0)) h_next = fmin(h_next, (REALV)job->max_step);
  *h = SEL(*h, h_next, active);

  MASKV gave_up = reject & ((*rejections > (IDXV)job->max_rejections) | (h_try <= job->min_step));
  *status = SEL(*status, (IDXV)ARCUS_STATUS_FAILED, gave_up);
  *status = SEL(*status, (IDXV)ARCUS_STATUS_DONE, accept & last);
  *status = SEL(*status, (IDXV)ARCUS_STATUS_STEP_LIMIT, accept & !last & (*steps >= (IDXV)job->max_steps));
  return accept;
}

/* One trial step of every active lane of every group (stages in lockstep). */
ARCUS_INLINE void dp_attempt(const field_desc* f, __global const REAL* data, const advance_desc* job, ray6* y, ray6* comp,
                             ray6* k1,
                       REALV* s, REALV* h, IDXV* steps, IDXV* rejections, IDXV* status, MASKV* accepted) {
  ray6 k2[ARCUS_GROUPS], k3[ARCUS_GROUPS], k4[ARCUS_GROUPS], k5[ARCUS_GROUPS], k6[ARCUS_GROUPS];
  ray6 k7[ARCUS_GROUPS], y5[ARCUS_GROUPS], comp5[ARCUS_GROUPS];
  REALV h_try[ARCUS_GROUPS];
  MASKV last[ARCUS_GROUPS];
  FOR_GROUPS(g) {
    REALV remaining = job->length - s[g];
    last[g] = remaining <= h[g];
    h_try[g] = SEL(h[g], remaining, last[g]);
    k2[g] = ray_derivative(f, data, ray_step(y[g], h_try[g], ray_scale(k1[g], RC(A21))));
  }
  FOR_GROUPS(g) {
    ray6 t = ray_fma(k2[g], RC(A32), ray_scale(k1[g], RC(A31)));
    k3[g] = ray_derivative(f, data, ray_step(y[g], h_try[g], t));
  }
  FOR_GROUPS(g) {
    ray6 t = ray_fma(k3[g], RC(A43), ray_fma(k2[g], RC(A42), ray_scale(k1[g], RC(A41))));
    k4[g] = ray_derivative(f, data, ray_step(y[g], h_try[g], t));
  }
  FOR_GROUPS(g) {
    ray6 t = ray_fma(k4[g], RC(A54), ray_fma(k3[g], RC(A53), ray_fma(k2[g], RC(A52), ray_scale(k1[g], RC(A51)))));
    k5[g] = ray_derivative(f, data, ray_step(y[g], h_try[g], t));
  }
  FOR_GROUPS(g) {
    ray6 t = ray_fma(k5[g], RC(A65),
                     ray_fma(k4[g], RC(A64), ray_fma(k3[g], RC(A63), ray_fma(k2[g], RC(A62), ray_scale(k1[g], RC(A61))))));
    k6[g] = ray_derivative(f, data, ray_step(y[g], h_try[g], t));
  }
  FOR_GROUPS(g) {
    ray6 t = ray_fma(k6[g], RC(B6),
                     ray_fma(k5[g], RC(B5), ray_fma(k4[g], RC(B4), ray_fma(k3[g], RC(B3), ray_scale(k1[g], RC(B1))))));
    comp5[g] = comp[g];
    y5[g] = ray_advance(y[g], h_try[g], t, &comp5[g]);
    k7[g] = ray_derivative(f, data, y5[g]);
  }
  FOR_GROUPS(g) {
    ray6 e = ray_fma(k7[g], RC(E7), ray_fma(k6[g], RC(E6), ray_fma(k5[g], RC(E5), ray_fma(k4[g], RC(E4),
                     ray_fma(k3[g], RC(E3), ray_scale(k1[g], RC(E1)))))));
    accepted[g] = dp_decide(job, &y[g], &comp[g], &k1[g], &s[g], &h[g], &steps[g], &rejections[g], &status[g],
                            h_try[g], last[g], y5[g], comp5[g], k7[g], ray_times(e, h_try[g]));
  }
}

/* The first trial step: the caller's, else 1% of the state's scale over the
 * derivative's (Hairer, Nørsett & Wanner's h0 heuristic, first stage); either way
 * within max_step and [min_step, length], as every later step. */
ARCUS_INLINE REALV dp_initial_step(const advance_desc* job, ray6 y, ray6 k) {
#define DP_SCALE(c) (job->atol + job->rtol * fabs(y.c))
  REALV d0 = fmax(fmax(fabs(y.x) / DP_SCALE(x), fabs(y.y) / DP_SCALE(y)), fabs(y.z) / DP_SCALE(z));
  d0 = fmax(d0, fmax(fmax(fabs(y.vx) / DP_SCALE(vx), fabs(y.vy) / DP_SCALE(vy)), fabs(y.vz) / DP_SCALE(vz)));
  REALV d1 = fmax(fmax(fabs(k.x) / DP_SCALE(x), fabs(k.y) / DP_SCALE(y)), fabs(k.z) / DP_SCALE(z));
  d1 = fmax(d1, fmax(fmax(fabs(k.vx) / DP_SCALE(vx), fabs(k.vy) / DP_SCALE(vy)), fabs(k.vz) / DP_SCALE(vz)));
#undef DP_SCALE
  REALV h = RC(0.01) * d0 / d1;
  h = SEL(h, (REALV)RC(1e-6), !(h > RC(0)) | !isfinite(h));
  if (job->step > RC(0)) h = (REALV)job->step;
  if (job->max_step > RC(0)) h = fmin(h, (REALV)job->max_step);
  return clamp(h, (REALV)job->min_step, (REALV)job->length);
}
#endif

/* ---------------------------------------------------------------- the kernel */
__kernel void arcus_advance(__global const REAL* rays_in, __global REAL* rays_out, __global ulong* steps_out,
                            __global int* status_out, __global REAL* path, __global uint* path_points,
                            const field_desc field, __global const REAL* field_data, const advance_desc job) {
  const field_desc* f = &field;
  const size_t first_vector = get_global_id(0) * ARCUS_GROUPS;
  const size_t stride = (size_t)job.stride;

  ray6 y[ARCUS_GROUPS], comp[ARCUS_GROUPS]; /* comp: see ray_advance */
  REALV s[ARCUS_GROUPS];
  IDXV steps[ARCUS_GROUPS], status[ARCUS_GROUPS];
#ifdef ARCUS_FEATURE_RECORD_PATH
  IDXV points[ARCUS_GROUPS];
#endif
#ifdef ARCUS_METHOD_DP45
  ray6 k1[ARCUS_GROUPS];
  REALV h[ARCUS_GROUPS];
  IDXV rejections[ARCUS_GROUPS];
#endif

  /* Start: v = n(r0)·d/|d|.  Bad directions or origins are flagged, not advanced. */
  FOR_GROUPS(g) {
    const size_t v = first_vector + g;
    REALV x = VLOAD(v, rays_in), yy = VLOAD(v, rays_in + stride), z = VLOAD(v, rays_in + 2 * stride);
    REALV dx = VLOAD(v, rays_in + 3 * stride), dy = VLOAD(v, rays_in + 4 * stride);
    REALV dz = VLOAD(v, rays_in + 5 * stride);
    /* Scaled by its largest component first, so that no finite non-zero direction
     * under- or overflows when squared (the host applies the same test). */
    REALV dmax = fmax(fmax(fabs(dx), fabs(dy)), fabs(dz));
    MASKV valid = (dmax > RC(0)) & isfinite(dx) & isfinite(dy) & isfinite(dz) & isfinite(x) & isfinite(yy) &
                  isfinite(z); /* each component: fmax ignores NaNs */
    dx /= dmax;
    dy /= dmax;
    dz /= dmax;
    REALV n, gx, gy, gz;
    field_eval(f, field_data, x, yy, z, &n, &gx, &gy, &gz);
    REALV n_over_len = n * rsqrt(dx * dx + dy * dy + dz * dz);
    y[g].x = x;
    y[g].y = yy;
    y[g].z = z;
    y[g].vx = n_over_len * dx;
    y[g].vy = n_over_len * dy;
    y[g].vz = n_over_len * dz;
    comp[g] = ray_times(y[g], RC(0));
    s[g] = RC(0);
    steps[g] = 0;
    status[g] = SEL((IDXV)ARCUS_STATUS_INVALID_INPUT, (IDXV)ARCUS_STATUS_ACTIVE, valid);
    /* A start where n is not a positive finite number cannot be advanced. */
    status[g] = SEL(status[g], (IDXV)ARCUS_STATUS_FAILED, valid & !((n > RC(0)) & isfinite(n)));
#ifdef ARCUS_FEATURE_BOX
    status[g] = SEL(status[g], (IDXV)ARCUS_STATUS_LEFT_BOX,
                    (status[g] == (IDXV)ARCUS_STATUS_ACTIVE) & outside_box(&job, y[g]));
#endif
#ifdef ARCUS_FEATURE_RECORD_PATH
    points[g] = 0;
    RECORD(g, status[g] != (IDXV)ARCUS_STATUS_INVALID_INPUT);
#endif
#ifdef ARCUS_METHOD_DP45
    k1[g] = ray_derivative(f, field_data, y[g]);
    h[g] = dp_initial_step(&job, y[g], k1[g]);
    rejections[g] = 0;
#endif
  }

#ifdef ARCUS_METHOD_DP45
  /* Adaptive: every lane takes its own steps; the loop runs while any lane of any group
   * is active (neighbouring rays take similar step counts, so idle lanes cost little). */
  for (;;) {
    MASKV alive = 0;
    FOR_GROUPS(g) alive |= status[g] == (IDXV)ARCUS_STATUS_ACTIVE;
    if (!ANY(alive)) break;
#ifdef ARCUS_FEATURE_BOX
    ray6 y_old[ARCUS_GROUPS];
    REALV s_old[ARCUS_GROUPS];
    FOR_GROUPS(g) {
      y_old[g] = y[g];
      s_old[g] = s[g];
    }
#endif
    MASKV accepted[ARCUS_GROUPS];
    dp_attempt(f, field_data, &job, y, comp, k1, s, h, steps, rejections, status, accepted);
    FOR_GROUPS(g) {
#ifdef ARCUS_FEATURE_BOX
      MASKV left = clip_to_box(&job, y_old[g], s_old[g], &y[g], &s[g], accepted[g] & outside_box(&job, y[g]));
      status[g] = SEL(status[g], (IDXV)ARCUS_STATUS_LEFT_BOX, left);
#endif
      RECORD(g, accepted[g]);
    }
  }
#else
  /* Fixed steps: every ray takes the same fixed_steps steps (the last one shortened to
   * end exactly at `length`), so the loop is uniform and needs no lane masks unless a
   * box can stop rays early. */
  for (int k = 0; k < job.fixed_steps; ++k) {
    const REAL hk = (k == job.fixed_steps - 1) ? job.last_step : job.step;
    ray6 y_new[ARCUS_GROUPS], comp_new[ARCUS_GROUPS];
    FOR_GROUPS(g) comp_new[g] = comp[g];
    fixed_step(f, field_data, y, y_new, comp_new, (REALV)hk);
    FOR_GROUPS(g) {
#ifdef ARCUS_FEATURE_BOX
      MASKV active = status[g] == (IDXV)ARCUS_STATUS_ACTIVE;
      REALV s_new = s[g] + hk;
      MASKV left = clip_to_box(&job, y[g], s[g], &y_new[g], &s_new, active & outside_box(&job, y_new[g]));
      y[g] = ray_select(y[g], y_new[g], active);
      comp[g] = ray_select(comp[g], comp_new[g], active);
      s[g] = SEL(s[g], s_new, active);
      steps[g] += ONE_IF(active);
      status[g] = SEL(status[g], (IDXV)ARCUS_STATUS_LEFT_BOX, left);
      RECORD(g, active);
#else
      y[g] = y_new[g];
      comp[g] = comp_new[g];
      RECORD(g, status[g] == (IDXV)ARCUS_STATUS_ACTIVE);
#endif
    }
  }
  /* The rays still active went the whole way, or as far as max_steps allowed: the host
   * chose fixed_steps as the least n with n·step >= length, or max_steps. */
  const int stopped_early = job.fixed_steps * job.step < job.length;
  const REAL s_end = stopped_early ? job.fixed_steps * job.step : job.length;
  FOR_GROUPS(g) {
    MASKV active = status[g] == (IDXV)ARCUS_STATUS_ACTIVE;
    s[g] = SEL(s[g], (REALV)s_end, active); /* exact, where summing the steps is not */
#ifndef ARCUS_FEATURE_BOX
    steps[g] = SEL(steps[g], (IDXV)job.fixed_steps, active);
#endif
    status[g] = SEL(status[g], (IDXV)(stopped_early ? ARCUS_STATUS_STEP_LIMIT : ARCUS_STATUS_DONE), active);
    status[g] = SEL(status[g], (IDXV)ARCUS_STATUS_FAILED, active & !ray_finite(y[g]));
  }
#endif

  /* End states: position, unit direction v/|v|, arc length; invalid rays echo input. */
  FOR_GROUPS(g) {
    const size_t v = first_vector + g;
    MASKV invalid = status[g] == (IDXV)ARCUS_STATUS_INVALID_INPUT;
    REALV inv_v = rsqrt(y[g].vx * y[g].vx + y[g].vy * y[g].vy + y[g].vz * y[g].vz);
    VSTORE(SEL(y[g].x, VLOAD(v, rays_in), invalid), v, rays_out);
    VSTORE(SEL(y[g].y, VLOAD(v, rays_in + stride), invalid), v, rays_out + stride);
    VSTORE(SEL(y[g].z, VLOAD(v, rays_in + 2 * stride), invalid), v, rays_out + 2 * stride);
    VSTORE(SEL(y[g].vx * inv_v, VLOAD(v, rays_in + 3 * stride), invalid), v, rays_out + 3 * stride);
    VSTORE(SEL(y[g].vy * inv_v, VLOAD(v, rays_in + 4 * stride), invalid), v, rays_out + 4 * stride);
    VSTORE(SEL(y[g].vz * inv_v, VLOAD(v, rays_in + 5 * stride), invalid), v, rays_out + 5 * stride);
    VSTORE(s[g], v, rays_out + 6 * stride);
    IDX st[ARCUS_LANES], sc[ARCUS_LANES];
    VSTORE_IDX(steps[g], 0, st);
    VSTORE_IDX(status[g], 0, sc);
#ifdef ARCUS_FEATURE_RECORD_PATH
    IDX pc[ARCUS_LANES];
    VSTORE_IDX(points[g], 0, pc);
#endif
    for (int l = 0; l < ARCUS_LANES; ++l) {
      const size_t ray = v * ARCUS_LANES + l;
      steps_out[ray] = (ulong)st[l];
      status_out[ray] = (int)sc[l];
#ifdef ARCUS_FEATURE_RECORD_PATH
      path_points[ray] = (uint)pc[l];
#endif
    }
  }
}
