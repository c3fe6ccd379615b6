/* The integrators of the ray equation (thesis §4.3.5): one step of Euler, RK2
 * (midpoint), RK4, or Dormand–Prince 5(4) with FSAL and a per-ray adaptive step; for a
 * constant field the exact straight segment, with no integrator at all.  Exactly one
 * ARCUS_METHOD_{STRAIGHT,EULER,RK2,RK4,DP45} is defined.
 *
 * The steps act on `ng` lane groups in lockstep, stage by stage, so each stage offers
 * ng independent dependency chains (FOR_N); the kernel's loop passes all its groups,
 * the box crossing (crossing.h) one.  m: the groups' media (GROUP_MEDIUM).  *n0
 * receives the least n the step's stages met, which the caller checks: a ray must not
 * enter n <= 0, where the ray equation breaks down (a step across it can come back
 * out as if reflected).  comp: see ray_advance.                                      */

#if defined(ARCUS_METHOD_STRAIGHT)
/* A constant field has ∇n = 0 and |v| = n0: r + h·v/n0 is exact. */
ARCUS_INLINE void method_steps(const medium* m, const ray6* y, ray6* y_new, ray6* comp, REALV h, REALV* n0,
                               const int ng) {
  const REAL inv_n = RC(1) / m->f->n0;
  FOR_N(g, ng) {
    ray6 d;
    d.x = y[g].vx * inv_n;
    d.y = y[g].vy * inv_n;
    d.z = y[g].vz * inv_n;
    d.vx = d.vy = d.vz = RC(0);
    y_new[g] = ray_advance(y[g], h, d, &comp[g]);
    n0[g] = (REALV)m->f->n0;
  }
}
#elif defined(ARCUS_METHOD_EULER)
ARCUS_INLINE void method_steps(const medium* m, const ray6* y, ray6* y_new, ray6* comp, REALV h, REALV* n0,
                               const int ng) {
  FOR_N(g, ng) y_new[g] = ray_advance(y[g], h, ray_derivative(GROUP_MEDIUM(m, g), y[g], &n0[g]), &comp[g]);
}
#elif defined(ARCUS_METHOD_RK2)
/* Explicit midpoint. */
ARCUS_INLINE void method_steps(const medium* m, const ray6* y, ray6* y_new, ray6* comp, REALV h, REALV* n0,
                               const int ng) {
  ray6 k[ARCUS_GROUPS];
  REALV n;
  FOR_N(g, ng) k[g] = ray_derivative(GROUP_MEDIUM(m, g), y[g], &n0[g]);
  FOR_N(g, ng) {
    k[g] = ray_derivative(GROUP_MEDIUM(m, g), ray_step(y[g], RC(0.5) * h, k[g]), &n);
    n0[g] = fmin(n0[g], n);
  }
  FOR_N(g, ng) y_new[g] = ray_advance(y[g], h, k[g], &comp[g]);
}
#elif defined(ARCUS_METHOD_RK4)
/* Classical fourth order: k = k1..k4 in turn, acc = k1 + 2 k2 + 2 k3 + k4. */
ARCUS_INLINE void method_steps(const medium* m, const ray6* y, ray6* y_new, ray6* comp, REALV h, REALV* n0,
                               const int ng) {
  const REALV half_h = RC(0.5) * h;
  ray6 k[ARCUS_GROUPS], acc[ARCUS_GROUPS];
  REALV n;
  FOR_N(g, ng) {
    k[g] = ray_derivative(GROUP_MEDIUM(m, g), y[g], &n0[g]);
    acc[g] = k[g];
  }
  FOR_N(g, ng) {
    k[g] = ray_derivative(GROUP_MEDIUM(m, g), ray_step(y[g], half_h, k[g]), &n);
    n0[g] = fmin(n0[g], n);
    acc[g] = ray_fma(k[g], RC(2), acc[g]);
  }
  FOR_N(g, ng) {
    k[g] = ray_derivative(GROUP_MEDIUM(m, g), ray_step(y[g], half_h, k[g]), &n);
    n0[g] = fmin(n0[g], n);
    acc[g] = ray_fma(k[g], RC(2), acc[g]);
  }
  FOR_N(g, ng) {
    k[g] = ray_derivative(GROUP_MEDIUM(m, g), ray_step(y[g], h, k[g]), &n);
    n0[g] = fmin(n0[g], n);
    y_new[g] = ray_advance(y[g], h * RC(1.0 / 6.0), ray_fma(k[g], RC(1), acc[g]), &comp[g]);
  }
}
#elif defined(ARCUS_METHOD_DP45)
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

/* A trial step of size h from y (k1: the derivative there) for ng groups: the
 * fifth-order solution y5 (comp5: its compensation), k7 = the derivative at y5 with
 * n7 = n there, and the error estimate err (already times h). */
ARCUS_INLINE void dp_trial(const medium* m, const ray6* y, const ray6* comp, const ray6* k1, const REALV* h,
                           ray6* y5, ray6* comp5, ray6* k7, REALV* n7, ray6* err, const int ng) {
  ray6 k2[ARCUS_GROUPS], k3[ARCUS_GROUPS], k4[ARCUS_GROUPS], k5[ARCUS_GROUPS], k6[ARCUS_GROUPS];
  REALV n;
  FOR_N(g, ng) k2[g] = ray_derivative(GROUP_MEDIUM(m, g), ray_step(y[g], h[g], ray_scale(k1[g], RC(A21))), &n);
  FOR_N(g, ng) {
    ray6 t = ray_fma(k2[g], RC(A32), ray_scale(k1[g], RC(A31)));
    k3[g] = ray_derivative(GROUP_MEDIUM(m, g), ray_step(y[g], h[g], t), &n);
  }
  FOR_N(g, ng) {
    ray6 t = ray_fma(k3[g], RC(A43), ray_fma(k2[g], RC(A42), ray_scale(k1[g], RC(A41))));
    k4[g] = ray_derivative(GROUP_MEDIUM(m, g), ray_step(y[g], h[g], t), &n);
  }
  FOR_N(g, ng) {
    ray6 t = ray_fma(k4[g], RC(A54), ray_fma(k3[g], RC(A53), ray_fma(k2[g], RC(A52), ray_scale(k1[g], RC(A51)))));
    k5[g] = ray_derivative(GROUP_MEDIUM(m, g), ray_step(y[g], h[g], t), &n);
  }
  FOR_N(g, ng) {
    ray6 t = ray_fma(k5[g], RC(A65),
                     ray_fma(k4[g], RC(A64), ray_fma(k3[g], RC(A63), ray_fma(k2[g], RC(A62), ray_scale(k1[g], RC(A61))))));
    k6[g] = ray_derivative(GROUP_MEDIUM(m, g), ray_step(y[g], h[g], t), &n);
  }
  FOR_N(g, ng) {
    ray6 t = ray_fma(k6[g], RC(B6),
                     ray_fma(k5[g], RC(B5), ray_fma(k4[g], RC(B4), ray_fma(k3[g], RC(B3), ray_scale(k1[g], RC(B1))))));
    comp5[g] = comp[g];
    y5[g] = ray_advance(y[g], h[g], t, &comp5[g]);
    k7[g] = ray_derivative(GROUP_MEDIUM(m, g), y5[g], &n7[g]);
  }
  FOR_N(g, ng) {
    ray6 e = ray_fma(k7[g], RC(E7), ray_fma(k6[g], RC(E6), ray_fma(k5[g], RC(E5), ray_fma(k4[g], RC(E4),
                     ray_fma(k3[g], RC(E3), ray_scale(k1[g], RC(E1)))))));
    err[g] = ray_times(e, h[g]);
  }
}

/* A step of the fifth-order solution with no error control (the box crossing shortens
 * an accepted step, whose error is then smaller still). */
ARCUS_INLINE void method_steps(const medium* m, const ray6* y, ray6* y_new, ray6* comp, REALV h, REALV* n0,
                               const int ng) {
  ray6 k1[ARCUS_GROUPS], comp5[ARCUS_GROUPS], k7[ARCUS_GROUPS], err[ARCUS_GROUPS];
  REALV hs[ARCUS_GROUPS], n7[ARCUS_GROUPS];
  FOR_N(g, ng) {
    k1[g] = ray_derivative(GROUP_MEDIUM(m, g), y[g], &n0[g]);
    hs[g] = h;
  }
  dp_trial(m, y, comp, k1, hs, y_new, comp5, k7, n7, err, ng);
  FOR_N(g, ng) comp[g] = comp5[g];
}

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

/* One trial step of every active lane of every group (stages in lockstep): accepts or
 * rejects it and adapts the step size.  accepted[g]: the lanes that moved; h_taken[g]:
 * their step.  fmax drops NaNs, so a non-finite trial state is rejected explicitly; an
 * accepted state where n <= 0 ends the ray FAILED at its last good state. */
ARCUS_INLINE void dp_attempt(const medium* m, const advance_desc* job, ray6* y, ray6* comp, ray6* k1, REALV* s,
                             REALV* h, IDXV* steps, IDXV* rejections, IDXV* status, IDXV* failure, MASKV* accepted,
                             REALV* h_taken) {
  ray6 y5[ARCUS_GROUPS], comp5[ARCUS_GROUPS], k7[ARCUS_GROUPS], err[ARCUS_GROUPS];
  REALV n7[ARCUS_GROUPS];
  MASKV last[ARCUS_GROUPS];
  FOR_GROUPS(g) {
    REALV remaining = job->length - s[g];
    last[g] = remaining <= h[g];
    h_taken[g] = SEL(h[g], remaining, last[g]);
  }
  dp_trial(m, y, comp, k1, h_taken, y5, comp5, k7, n7, err, ARCUS_GROUPS);
  FOR_GROUPS(g) {
    MASKV active = status[g] == (IDXV)ARCUS_STATUS_ACTIVE;
    REALV norm = dp_error_norm(job, y[g], y5[g], err[g]);
    MASKV finite = ray_finite(y5[g]) & isfinite(n7[g]);
    norm = SEL((REALV)INFINITY, norm, finite);
    MASKV ok = active & (norm <= RC(1));
    MASKV nonpositive = ok & !(n7[g] > RC(0));
    MASKV accept = ok & !nonpositive;
    MASKV reject = active & !ok;
    y[g] = ray_select(y[g], y5[g], accept);
    comp[g] = ray_select(comp[g], comp5[g], accept);
    k1[g] = ray_select(k1[g], k7[g], accept);
    s[g] = SEL(s[g], SEL(s[g] + h_taken[g], (REALV)job->length, last[g]), accept);
    steps[g] += ONE_IF(accept);
    rejections[g] = SEL(rejections[g] + ONE_IF(reject), (IDXV)0, accept);

    REALV h_next = h_taken[g] * dp_step_factor(norm);
    if (job->max_step > RC(0)) h_next = fmin(h_next, (REALV)job->max_step);
    h_next = fmin(h_next, field_step_cap(GROUP_MEDIUM(m, g), y[g].x, y[g].y, y[g].z, y[g].vx, y[g].vy, y[g].vz));
    h[g] = SEL(h[g], h_next, active);

    MASKV gave_up = reject & ((rejections[g] > (IDXV)job->max_rejections) | (h_taken[g] <= job->min_step));
    status[g] = SEL(status[g], (IDXV)ARCUS_STATUS_FAILED, gave_up | nonpositive);
    /* Giving up on a state that overflows is no tolerance problem. */
    failure[g] = SEL(failure[g], SEL((IDXV)ARCUS_FAIL_NOT_FINITE, (IDXV)ARCUS_FAIL_TOLERANCE, finite), gave_up);
    failure[g] = SEL(failure[g], (IDXV)ARCUS_FAIL_INDEX_NOT_POSITIVE, nonpositive);
    status[g] = SEL(status[g], (IDXV)ARCUS_STATUS_DONE, accept & last[g]);
    status[g] = SEL(status[g], (IDXV)ARCUS_STATUS_STEP_LIMIT, accept & !last[g] & (steps[g] >= (IDXV)job->max_steps));
    accepted[g] = accept;
  }
}

/* The first trial step: the caller's, else 1% of the state's scale over the
 * derivative's (Hairer, Nørsett & Wanner's h0 heuristic, first stage); either way
 * within max_step, the field's cap and [min_step, length], as every later step. */
ARCUS_INLINE REALV dp_initial_step(const medium* m, const advance_desc* job, ray6 y, ray6 k) {
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
  h = fmin(h, field_step_cap(m, y.x, y.y, y.z, y.vx, y.vy, y.vz));
  return clamp(h, (REALV)job->min_step, (REALV)job->length);
}
#endif
