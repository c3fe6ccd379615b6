/* Batched ray advance through a non-linear medium (thesis §4.1.6, §4.3.5), in slices.
 *
 * Layout: each work-item holds ARCUS_GROUPS independent groups of ARCUS_LANES rays.
 * The lanes give SIMD on PoCL; the independent groups give the core several
 * dependency chains to overlap.  On a GPU both are 1: one ray per work-item.
 *
 * Slices: a launch advances the rays from their state on the device by at most one
 * slice (fixed steps: the steps [slice_begin, slice_end); DP45: slice_end attempts) and
 * stores the state back, so the host can report progress, cancel, and keep any one
 * launch short.  The state is the result: the host reads it back at the end.
 *
 * Each accepted step passes through the per-step hook: with ARCUS_USE_BOX a step
 * that leaves the box is shortened to end where its path crosses the box (crossing.h);
 * with ARCUS_USE_GEOMETRY (render jobs, which always have a box) the step's chord is
 * then tested against the scene, and a hit stops the ray on the hit surface
 * (render/hits.h).
 *
 * Compiled with one ARCUS_METHOD_*, one ARCUS_FIELD_* (none for a constant field), and
 * optionally ARCUS_USE_{BOX,RECORD_PATH,FLOAT,DISPERSION} (the kernel-side
 * names of the ARCUS_FEATURE_* bits: see src/curved/features.cpp).  The host prepends
 * common/real.h, curved/field.h, curved/advance_desc.h, curved/state.h,
 * curved/integrators.h and curved/crossing.h.                                       */

#ifdef ARCUS_USE_RECORD_PATH
/* Appends the current point of the lanes in `moved`; counts every point, so a count
 * above the capacity tells the host how much room the path needed.  A point is x y z,
 * ray by ray (ray r's point k at r·capacity + k), or with ARCUS_USE_RECORD_STATE the
 * whole state x y z vx vy vz s (the renderer's path cache: enough to resume the
 * integrator at any net point) step by step (at k·stride + r): the rays of a lane group
 * write, and later walk, neighbouring memory at each step, and memory past the
 * longest path of a region is never touched. */
#ifdef ARCUS_USE_RECORD_STATE
#define ARCUS_POINT_REALS 7
#else
#define ARCUS_POINT_REALS 3
#endif
ARCUS_INLINE void record_point(__global REAL* path, int capacity, size_t stride, size_t first_ray, ray6 y, REALV s,
                               MASKV moved, IDXV* count) {
  REAL c[ARCUS_POINT_REALS][ARCUS_LANES];
  IDX cs[ARCUS_LANES], ms[ARCUS_LANES];
  VSTORE(y.x, 0, c[0]);
  VSTORE(y.y, 0, c[1]);
  VSTORE(y.z, 0, c[2]);
#ifdef ARCUS_USE_RECORD_STATE
  VSTORE(y.vx, 0, c[3]);
  VSTORE(y.vy, 0, c[4]);
  VSTORE(y.vz, 0, c[5]);
  VSTORE(s, 0, c[6]);
#endif
  VSTORE_IDX(*count, 0, cs);
  VSTORE_IDX((IDXV)moved, 0, ms);
  for (int l = 0; l < ARCUS_LANES; ++l) {
    if (!ms[l]) continue;
    if (cs[l] < capacity) {
#ifdef ARCUS_USE_RECORD_STATE
      __global REAL* p = path + ((size_t)cs[l] * stride + first_ray + l) * ARCUS_POINT_REALS;
#else
      __global REAL* p = path + ((first_ray + l) * (size_t)capacity + (size_t)cs[l]) * ARCUS_POINT_REALS;
#endif
      for (int k = 0; k < ARCUS_POINT_REALS; ++k) p[k] = c[k][l];
    }
    cs[l] += 1;
  }
  *count = VLOAD(0, cs);
}
#define RECORD_AT(g, yv, sv, moved) \
  record_point(path, job.path_capacity, (size_t)job.stride, (first_vector + (g)) * ARCUS_LANES, (yv), (sv), (moved), \
               &points[g])
#else
#define RECORD_AT(g, yv, sv, moved)
#endif
#define RECORD(g, moved) RECORD_AT(g, y[g], s[g], moved)

/* Marks the active lanes in `m` FAILED for `why`. */
#define FAIL(g, m, why)                                                 \
  do {                                                                  \
    MASKV fail_ = (m) & (status[g] == (IDXV)ARCUS_STATUS_ACTIVE);       \
    status[g] = SEL(status[g], (IDXV)ARCUS_STATUS_FAILED, fail_);       \
    failure[g] = SEL(failure[g], (IDXV)(why), fail_);                   \
  } while (0)

/* The six components of a ray6 from/to a structure-of-arrays buffer, lane group v. */
ARCUS_INLINE ray6 ray_load(__global const REAL* p, size_t v, size_t stride) {
  ray6 r;
  r.x = VLOAD(v, p);
  r.y = VLOAD(v, p + stride);
  r.z = VLOAD(v, p + 2 * stride);
  r.vx = VLOAD(v, p + 3 * stride);
  r.vy = VLOAD(v, p + 4 * stride);
  r.vz = VLOAD(v, p + 5 * stride);
  return r;
}

ARCUS_INLINE void ray_store(ray6 r, __global REAL* p, size_t v, size_t stride) {
  VSTORE(r.x, v, p);
  VSTORE(r.y, v, p + stride);
  VSTORE(r.z, v, p + 2 * stride);
  VSTORE(r.vx, v, p + 3 * stride);
  VSTORE(r.vy, v, p + 4 * stride);
  VSTORE(r.vz, v, p + 5 * stride);
}

#ifdef ARCUS_USE_GEOMETRY
#define HIT_INT(c) (hit_ints + (c) * stride)
#endif

__kernel void arcus_advance(ARCUS_PARAMS(ARCUS_ADVANCE_ARGS)) {
  const size_t first_vector = get_global_id(0) * ARCUS_GROUPS;
  const size_t stride = (size_t)job.stride;
#define REAL_STATE(c) (state + (c) * stride)
#define INT_STATE(c) (istate + (c) * stride)

  medium med[ARCUS_MEDIA];
  media_init(med, &field, field_data, wavelengths, first_vector); /* a bad wavelength is flagged below */

  ray6 y[ARCUS_GROUPS], comp[ARCUS_GROUPS]; /* comp: see ray_advance */
  REALV s[ARCUS_GROUPS];
  IDXV steps[ARCUS_GROUPS], status[ARCUS_GROUPS], failure[ARCUS_GROUPS];
#ifdef ARCUS_USE_RECORD_PATH
  IDXV points[ARCUS_GROUPS];
#endif
#ifdef ARCUS_METHOD_DP45
  ray6 k1[ARCUS_GROUPS];
  REALV h[ARCUS_GROUPS];
  IDXV rejections[ARCUS_GROUPS];
#endif
#ifdef ARCUS_USE_GEOMETRY
  hit_state hs[ARCUS_GROUPS];
  smart_chunk chunk[ARCUS_GROUPS];
#endif

  if (job.first_slice) {
    /* Start: v = n(r0)·d/|d|.  Bad directions, origins or wavelengths are flagged, not
     * advanced; so is a start where n is not a positive finite number. */
    FOR_GROUPS(g) {
      const size_t v = first_vector + g;
      const ray6 in = ray_load(rays_in, v, stride); /* origin, direction */
      REALV x = in.x, yy = in.y, z = in.z, dx = in.vx, dy = in.vy, dz = in.vz;
      /* Scaled by its largest component first, so that no finite non-zero direction
       * under- or overflows when squared (the host applies the same test). */
      REALV dmax = fmax(fmax(fabs(dx), fabs(dy)), fabs(dz));
      MASKV valid = (dmax > RC(0)) & isfinite(dx) & isfinite(dy) & isfinite(dz) & isfinite(x) & isfinite(yy) &
                    isfinite(z); /* each component: fmax ignores NaNs */
#ifdef ARCUS_USE_DISPERSION
      REALV lambda = VLOAD(v, wavelengths);
      valid &= (lambda >= RC(ARCUS_MIN_WAVELENGTH)) & (lambda <= RC(ARCUS_MAX_WAVELENGTH));
#endif
      dx /= dmax;
      dy /= dmax;
      dz /= dmax;
      REALV n, gx, gy, gz;
      field_eval(GROUP_MEDIUM(med, g), x, yy, z, &n, &gx, &gy, &gz);
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
      failure[g] = (IDXV)ARCUS_FAIL_NONE;
      FAIL(g, !isfinite(n), ARCUS_FAIL_NOT_FINITE);
      FAIL(g, !(n > RC(0)), ARCUS_FAIL_INDEX_NOT_POSITIVE);
#ifdef ARCUS_USE_BOX
      status[g] = SEL(status[g], (IDXV)ARCUS_STATUS_LEFT_BOX,
                      (status[g] == (IDXV)ARCUS_STATUS_ACTIVE) & (box_distance(&job, y[g]) > RC(0)));
#endif
#ifdef ARCUS_USE_RECORD_PATH
      points[g] = 0;
      RECORD(g, status[g] != (IDXV)ARCUS_STATUS_INVALID_INPUT);
#endif
#ifdef ARCUS_METHOD_DP45
      rejections[g] = 0;
#endif
#ifdef ARCUS_USE_GEOMETRY
      hs[g].kind = (IDXV)ARCUS_HIT_NONE;
      hs[g].index = (IDXV)-1;
      hs[g].tests = 0;
      hs[g].step = (IDXV)-1;
      hs[g].predict = predictions ? VLOAD_I(v, predictions) : (IDXV)-1;
#endif
    }
  } else {
    FOR_GROUPS(g) {
      const size_t v = first_vector + g;
      y[g] = ray_load(REAL_STATE(ARCUS_STATE_X), v, stride);
      s[g] = VLOAD(v, REAL_STATE(ARCUS_STATE_S));
#ifdef ARCUS_USE_FLOAT
      comp[g] = ray_load(REAL_STATE(ARCUS_STATE_COMP), v, stride);
#else
      comp[g] = ray_times(y[g], RC(0));
#endif
      steps[g] = VLOAD_I(v, INT_STATE(ARCUS_STATE_STEPS));
      IDXV word = VLOAD_I(v, INT_STATE(ARCUS_STATE_STATUS));
      status[g] = word & (IDXV)((1 << ARCUS_FAILURE_SHIFT) - 1);
      failure[g] = word >> (IDXV)ARCUS_FAILURE_SHIFT;
#ifdef ARCUS_USE_RECORD_PATH
      points[g] = VLOAD_I(v, INT_STATE(ARCUS_STATE_POINTS));
#endif
#ifdef ARCUS_METHOD_DP45
      rejections[g] = VLOAD_I(v, INT_STATE(ARCUS_STATE_REJECTIONS));
      h[g] = VLOAD(v, REAL_STATE(ARCUS_STATE_H));
#endif
#ifdef ARCUS_USE_GEOMETRY
      hs[g].kind = VLOAD_I(v, HIT_INT(ARCUS_HIT_KIND));
      hs[g].index = VLOAD_I(v, HIT_INT(ARCUS_HIT_INDEX));
      hs[g].tests = VLOAD_I(v, HIT_INT(ARCUS_HIT_TESTS));
      hs[g].predict = VLOAD_I(v, HIT_INT(ARCUS_HIT_PREDICT));
      hs[g].step = VLOAD_I(v, HIT_INT(ARCUS_HIT_STEP));
#endif
    }
  }
#ifdef ARCUS_USE_GEOMETRY
  FOR_GROUPS(g) smart_chunk_start(&chunk[g], y[g], s[g]); /* skipped steps since this slice began */
#endif

#ifdef ARCUS_METHOD_DP45
  /* FSAL: the first stage is the derivative at the state (recomputed each slice: the
   * same function of the same state, so slicing does not change the results). */
  FOR_GROUPS(g) {
    REALV n;
    k1[g] = ray_derivative(GROUP_MEDIUM(med, g), y[g], &n);
    if (job.first_slice) h[g] = dp_initial_step(GROUP_MEDIUM(med, g), &job, y[g], k1[g]);
  }
  /* Adaptive: every lane takes its own steps; the loop runs while any lane of any group
   * is active (neighbouring rays take similar step counts, so idle lanes cost little). */
  for (int attempt = 0; attempt < job.slice_end; ++attempt) {
    MASKV alive = 0;
    FOR_GROUPS(g) alive |= status[g] == (IDXV)ARCUS_STATUS_ACTIVE;
    if (!ANY(alive)) break;
#ifdef ARCUS_USE_BOX
    ray6 y_old[ARCUS_GROUPS], comp_old[ARCUS_GROUPS];
    REALV s_old[ARCUS_GROUPS];
    FOR_GROUPS(g) {
      y_old[g] = y[g];
      comp_old[g] = comp[g];
      s_old[g] = s[g];
    }
#endif
    MASKV accepted[ARCUS_GROUPS];
    REALV h_taken[ARCUS_GROUPS];
    dp_attempt(med, &job, y, comp, k1, s, h, steps, rejections, status, failure, accepted, h_taken);
    FOR_GROUPS(g) {
#ifdef ARCUS_USE_BOX
      MASKV left = accepted[g] & (box_distance(&job, y[g]) > RC(0));
      if (ANY(left))
        cross_box(GROUP_MEDIUM(med, g), &job, y_old[g], comp_old[g], s_old[g], h_taken[g], &y[g], &comp[g], &s[g],
                  left);
      status[g] = SEL(status[g], (IDXV)ARCUS_STATUS_LEFT_BOX, left);
#endif
      /* Recorded before the geometry hook moves a hit's end onto its surface: a stored
       * path keeps the step the integrator took, so walking it finds the same hit. */
      RECORD(g, accepted[g]);
#ifdef ARCUS_USE_GEOMETRY
      if (ANY(accepted[g]))
        geometry_step(GROUP_MEDIUM(med, g), &job, &geo, nodes, tris, shapes, y_old[g], comp_old[g], s_old[g], &y[g],
                      &comp[g], &s[g], steps[g], accepted[g], accepted[g] & (status[g] != (IDXV)ARCUS_STATUS_ACTIVE), 0,
                      &hs[g], &chunk[g], &status[g]);
#endif
    }
  }
#else
  /* Fixed steps: every ray takes the same fixed_steps steps (the last one shortened to
   * end exactly at `length`), so the loop is uniform and needs no lane masks unless a
   * box can stop rays early. */
#ifndef ARCUS_USE_BOX
  ray6 y_start[ARCUS_GROUPS], comp_start[ARCUS_GROUPS]; /* the last state known good */
  REALV n_min[ARCUS_GROUPS];
#ifdef ARCUS_USE_RECORD_PATH
  IDXV points_start[ARCUS_GROUPS];
#endif
  FOR_GROUPS(g) {
    y_start[g] = y[g];
    comp_start[g] = comp[g];
    n_min[g] = (REALV)INFINITY;
#ifdef ARCUS_USE_RECORD_PATH
    points_start[g] = points[g];
#endif
  }
#endif
  for (int k = job.slice_begin; k < job.slice_end; ++k) {
    const REAL hk = (k == job.fixed_steps - 1) ? job.last_step : job.step;
    ray6 y_new[ARCUS_GROUPS], comp_new[ARCUS_GROUPS];
    REALV n0[ARCUS_GROUPS];
    FOR_GROUPS(g) comp_new[g] = comp[g];
    method_steps(med, y, y_new, comp_new, (REALV)hk, n0, ARCUS_GROUPS);
    FOR_GROUPS(g) {
#ifdef ARCUS_USE_BOX
      FAIL(g, !(n0[g] > RC(0)), ARCUS_FAIL_INDEX_NOT_POSITIVE);
      MASKV active = status[g] == (IDXV)ARCUS_STATUS_ACTIVE;
      REALV s_new = s[g] + hk;
      MASKV left = active & (box_distance(&job, y_new[g]) > RC(0));
      if (ANY(left))
        cross_box(GROUP_MEDIUM(med, g), &job, y[g], comp[g], s[g], (REALV)hk, &y_new[g], &comp_new[g], &s_new, left);
      status[g] = SEL(status[g], (IDXV)ARCUS_STATUS_LEFT_BOX, left);
      RECORD_AT(g, y_new[g], s_new, active); /* before the geometry hook: see above */
#ifdef ARCUS_USE_GEOMETRY
      const MASKV last_step = (IDXV)(k + 1 >= job.fixed_steps ? -1 : 0); /* the host marks these rays DONE */
      if (ANY(active))
        geometry_step(GROUP_MEDIUM(med, g), &job, &geo, nodes, tris, shapes, y[g], comp[g], s[g], &y_new[g],
                      &comp_new[g], &s_new, steps[g] + ONE_IF(active), active,
                      active & ((status[g] != (IDXV)ARCUS_STATUS_ACTIVE) | last_step), 0, &hs[g], &chunk[g],
                      &status[g]);
#endif
      y[g] = ray_select(y[g], y_new[g], active);
      comp[g] = ray_select(comp[g], comp_new[g], active);
      s[g] = SEL(s[g], s_new, active);
      steps[g] += ONE_IF(active);
#else
      /* The least n of the step: a ray must not enter n <= 0 (checked after the loop). */
      n_min[g] = fmin(n_min[g], n0[g]);
      y[g] = y_new[g];
      comp[g] = comp_new[g];
      RECORD(g, status[g] == (IDXV)ARCUS_STATUS_ACTIVE);
#endif
    }
  }
  /* The state after the last step must be finite; without a box the lanes were not
   * masked, so a lane that failed in this slice goes back to its state at its start. */
  const int finished = job.slice_end >= job.fixed_steps;
  /* The rays still active went the whole way, or as far as max_steps allowed: the host
   * chose fixed_steps as the least n with n·step >= length, or max_steps. */
  const int stopped_early = job.fixed_steps * job.step < job.length;
  const REAL s_end = finished ? (stopped_early ? job.fixed_steps * job.step : job.length) : job.slice_end * job.step;
  FOR_GROUPS(g) {
    FAIL(g, !ray_finite(y[g]), ARCUS_FAIL_NOT_FINITE);
#ifndef ARCUS_USE_BOX
    FAIL(g, !(n_min[g] > RC(0)), ARCUS_FAIL_INDEX_NOT_POSITIVE);
    /* Only the lanes still active moved legitimately; the others keep their state
     * (a ray that failed in this slice: its state at the slice's start). */
    MASKV moved = status[g] == (IDXV)ARCUS_STATUS_ACTIVE;
    y[g] = ray_select(y_start[g], y[g], moved);
    comp[g] = ray_select(comp_start[g], comp[g], moved);
#ifdef ARCUS_USE_RECORD_PATH
    points[g] = SEL(points_start[g], points[g], moved);
#endif
    steps[g] = SEL(steps[g], (IDXV)job.slice_end, moved);
    s[g] = SEL(s[g], (REALV)s_end, moved);
#else
    if (finished) s[g] = SEL(s[g], (REALV)s_end, status[g] == (IDXV)ARCUS_STATUS_ACTIVE);
#endif
    if (finished)
      status[g] = SEL(status[g], (IDXV)(stopped_early ? ARCUS_STATUS_STEP_LIMIT : ARCUS_STATUS_DONE),
                      status[g] == (IDXV)ARCUS_STATUS_ACTIVE);
  }
#endif

#ifdef ARCUS_USE_GEOMETRY
  /* Smart step selection's chunks live in private memory: the steps still held are
   * proved empty (or tested) before the slice ends. */
  FOR_GROUPS(g) {
    const MASKV open = status[g] == (IDXV)ARCUS_STATUS_ACTIVE;
    if (ANY(open))
      geometry_step(GROUP_MEDIUM(med, g), &job, &geo, nodes, tris, shapes, y[g], comp[g], s[g], &y[g], &comp[g], &s[g],
                    steps[g], open, open, 1, &hs[g], &chunk[g], &status[g]);
  }
#endif
  /* The state goes back to the device buffer: the next slice resumes from it, and after
   * the last one the host reads the results from it. */
  FOR_GROUPS(g) {
    const size_t v = first_vector + g;
    ray_store(y[g], REAL_STATE(ARCUS_STATE_X), v, stride);
    VSTORE(s[g], v, REAL_STATE(ARCUS_STATE_S));
#ifdef ARCUS_USE_FLOAT
    ray_store(comp[g], REAL_STATE(ARCUS_STATE_COMP), v, stride);
#endif
    VSTORE_I(steps[g], v, INT_STATE(ARCUS_STATE_STEPS));
    VSTORE_I(status[g] | (failure[g] << (IDXV)ARCUS_FAILURE_SHIFT), v, INT_STATE(ARCUS_STATE_STATUS));
#ifdef ARCUS_USE_RECORD_PATH
    VSTORE_I(points[g], v, INT_STATE(ARCUS_STATE_POINTS));
#endif
#ifdef ARCUS_METHOD_DP45
    VSTORE_I(rejections[g], v, INT_STATE(ARCUS_STATE_REJECTIONS));
    VSTORE(h[g], v, REAL_STATE(ARCUS_STATE_H));
#endif
#ifdef ARCUS_USE_GEOMETRY
    hit_state_store(hs[g], v, hit_ints, stride);
#endif
  }
}
