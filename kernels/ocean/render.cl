/* Radiance through water by ray marching (thesis §4.1.4, §4.2, eq. 4.5–4.6): along
 * each camera ray, at `steps` midpoints, the light scattered toward the camera —
 * single scattering straight from the lights (elastic, and inelastic through the
 * wavelength redistribution, eq. 4.5) and multiple scattering from the photon map
 * (eq. 4.6) — attenuated back to the camera, per grid sample.  The map holds photons
 * stored at scattering events from the second interaction on, with the power and
 * wavelength they leave with, so inelastic re-emission is already in their
 * wavelengths: the estimate weighs each by its scatterer's phase function (isotropic
 * for an inelastic event).  A stored photon may carry several wavelengths (hero
 * wavelengths, trace.cl), each with its power: all of them are added.
 *
 * Two estimates of the multiple scattering:
 *   per step (the thesis'): the k nearest photons of each march point,
 *     Σ p Φ / (4/3 π r_k³), each step's k-set updated from the last one's from a pool
 *     of the photons about a stretch of the ray (photon/photon_line.h), and with it
 *     the sums Σ p Φ: the ray's direction, so each photon's phase weight, is fixed
 *     along a straight leg;
 *   beam (ARCUS_USE_OCEAN_BEAM; Jarosz, Zwicker & Jensen 2008): every photon whose
 *     sphere of radius r_i (its own k-nearest distance) the ray passes through,
 *     Σ p Φ T(t_i) / (π r_i²), found in one BVH traversal per ray.
 *
 * Under a flat surface a ray reaching it goes on reflected (Fresnel; wholly outside
 * Snell's window): the reflected path is the straight ray's mirror image, so each
 * point past the surface is mirrored.  With a periodic photon tile (rd.tile > 0) the
 * map holds one tile's photons standing for their copies across the plane, and the
 * beam estimate folds each ray into it (ocean_beam_leg).
 *
 * One pixel per work-item, scalar (a ray's photons and BVH branches differ from its
 * neighbours').  The pixel's spectrum accumulates in `radiance` (count reals per
 * pixel) and its transmittance to the camera in `scratch`, both global, since a
 * spectrum of hundreds of samples does not fit in private memory.
 *
 * Host prepends: common/real.h, bvh/bvh_desc.h, photon/photon_desc.h,
 * photon/photon_map.h, photon/photon_line.h, ocean/ocean_desc.h.                  */

/* Scatterer s's phase function at cos θ = mu (thesis eq. 3.26, 3.28–3.29), per sr. */
ARCUS_INLINE REAL ocean_hg_value(REAL g, REAL mu) {
  const REAL den = RC(1) + g * g - RC(2) * g * mu;
  return (RC(1) - g * g) / (RC(4) * OCEAN_PI * den * sqrt(den));
}

ARCUS_INLINE REAL ocean_phase_value(const ocean_phases* p, __global const REAL* optics, int s, REAL mu) {
  switch (p->kind[s]) {
    case ARCUS_OCEAN_PHASE_RAYLEIGH_LIKE:
      return (RC(1) + p->a[s] * mu * mu) / (RC(4) * OCEAN_PI * (RC(1) + p->a[s] / RC(3)));
    case ARCUS_OCEAN_PHASE_HG:
      return ocean_hg_value(p->gf[s], mu);
    case ARCUS_OCEAN_PHASE_TWO_TERM_HG:
      return p->zeta[s] * ocean_hg_value(p->gf[s], mu) + (RC(1) - p->zeta[s]) * ocean_hg_value(p->gb[s], mu);
    case ARCUS_OCEAN_PHASE_TABLE: {
      const int n = p->count[s];
      __global const REAL* x = optics + p->offset[s];
      __global const REAL* pdf = x + n;
      int lo = 0, hi = n - 1;
      while (hi - lo > 1) {
        const int mid = (lo + hi) / 2;
        if (x[mid] <= mu) lo = mid;
        else hi = mid;
      }
      const REAL t = clamp((mu - x[lo]) / (x[hi] - x[lo]), RC(0), RC(1));
      return (pdf[lo] + t * (pdf[hi] - pdf[lo])) / (RC(2) * OCEAN_PI); /* density in μ over 2π */
    }
    default:
      return RC(1) / (RC(4) * OCEAN_PI);
  }
}

/* A stored photon's phase weight toward the camera: its scatterer's phase function at
 * the angle between its arriving direction and the direction toward the camera;
 * isotropic for an inelastic re-emission. */
ARCUS_INLINE REAL ocean_photon_phase(const ocean_phases* p, __global const REAL* optics, int event, REAL mu) {
  if (event >= ARCUS_OCEAN_SCATTER_WATER) return ocean_phase_value(p, optics, event - ARCUS_OCEAN_SCATTER_WATER, mu);
  return RC(1) / (RC(4) * OCEAN_PI);
}

#define OCEAN_MAP(c, slot) PHOTON(photons, map, c, slot)

/* The stored photon q's phase weight toward the camera, the ray running along w. */
ARCUS_INLINE REAL ocean_photon_toward(const ocean_phases* p, __global const REAL* optics, __global const REAL* photons,
                                      const photon_map_desc map, int q, REAL3 w) {
  const REAL mu = -(OCEAN_MAP(ARCUS_PHOTON_DIRECTION, q) * w.x + OCEAN_MAP(ARCUS_PHOTON_DIRECTION + 1, q) * w.y +
                    OCEAN_MAP(ARCUS_PHOTON_DIRECTION + 2, q) * w.z);
  return ocean_photon_phase(p, optics, (int)OCEAN_MAP(ARCUS_PHOTON_POWER + ARCUS_OCEAN_MAP_EVENT, q), mu);
}

/* Adds weight × the power of each wavelength photon q carries into sums[its grid sample]. */
ARCUS_INLINE void ocean_photon_add(__global const REAL* photons, const photon_map_desc map, int q, REAL weight,
                                   __global REAL* sums) {
  for (int j = 0; j < ARCUS_OCEAN_MAX_HEROES; ++j) {
    const REAL power = OCEAN_MAP(ARCUS_PHOTON_POWER + ARCUS_OCEAN_MAP_POWER + j, q);
    if (power != RC(0)) sums[(int)OCEAN_MAP(ARCUS_PHOTON_POWER + ARCUS_OCEAN_MAP_BIN + j, q)] += weight * power;
  }
}

/* The sky tables' column below a ray's vertical cosine wz (*c0) and its weight toward
 * the next (*ct): the tables run over cosines −1 … 1. */
ARCUS_INLINE void ocean_sky_column(REAL wz, int cosines, int* c0, REAL* ct) {
  const REAL cx = clamp((wz + RC(1)) * RC(0.5) * (REAL)(cosines - 1), RC(0), (REAL)(cosines - 1));
  *c0 = min((int)cx, max(cosines - 2, 0));
  *ct = cx - (REAL)*c0;
}

/* The beam estimate over one straight piece of a ray: the photons whose point nearest
 * the line o + t w lies at t in [t0, t1) and whose sphere the line passes through, each
 * dimmed by e^(−σ_t t) (t: the whole path's length to it) and by `weight`. */
ARCUS_INLINE void ocean_beam_piece(__global const bvh_node* nodes, __global const REAL* photons, const photon_map_desc map,
                                   __global const REAL* radii, const ocean_phases* phases, __global const REAL* optics,
                                   REAL3 o, REAL3 w, REAL t0, REAL t1, REAL weight, __global REAL* out) {
  __global const REAL* sigma_t = optics;
  const REAL3 inv = (REAL3)(RC(1) / w.x, RC(1) / w.y, RC(1) / w.z);
  int stack[ARCUS_BVH_MAX_DEPTH];
  int top = 0, node = 0;
  for (;;) {
    __global const bvh_node* nd = nodes + node;
    /* slab test of the node's box against the piece [t0, t1] */
    const REAL3 lo = ((REAL3)(nd->lo[0], nd->lo[1], nd->lo[2]) - o) * inv;
    const REAL3 hi = ((REAL3)(nd->hi[0], nd->hi[1], nd->hi[2]) - o) * inv;
    const REAL3 a = fmin(lo, hi), c = fmax(lo, hi);
    const REAL enter = fmax(fmax(a.x, a.y), fmax(a.z, t0)), leave = fmin(fmin(c.x, c.y), fmin(c.z, t1));
    if (enter <= leave) {
      if (nd->count > 0) {
        for (int q = nd->first; q < nd->first + nd->count; ++q) {
          const REAL3 v =
              (REAL3)(OCEAN_MAP(ARCUS_PHOTON_POSITION, q), OCEAN_MAP(ARCUS_PHOTON_POSITION + 1, q),
                      OCEAN_MAP(ARCUS_PHOTON_POSITION + 2, q)) -
              o;
          const REAL tc = dot(v, w), r = radii[q];
          if (tc < t0 || tc >= t1) continue;
          const REAL off2 = dot(v, v) - tc * tc;
          if (off2 >= r * r) continue;
          const REAL p = ocean_photon_toward(phases, optics, photons, map, q, w) * weight / (OCEAN_PI * r * r);
          for (int j = 0; j < ARCUS_OCEAN_MAX_HEROES; ++j) { /* the wavelengths it carries */
            const REAL power = OCEAN_MAP(ARCUS_PHOTON_POWER + ARCUS_OCEAN_MAP_POWER + j, q);
            if (power == RC(0)) continue;
            const int b = (int)OCEAN_MAP(ARCUS_PHOTON_POWER + ARCUS_OCEAN_MAP_BIN + j, q);
            out[b] += exp(-sigma_t[b] * tc) * p * power;
          }
        }
      } else {
        stack[top++] = nd->first + 1;
        node = nd->first;
        continue;
      }
    }
    if (top == 0) break;
    node = stack[--top];
  }
}

/* The beam estimate over a straight leg [ta, tb) of a ray.  With a periodic tile
 * (rd.tile > 0) the map holds one tile's photons, standing for their copies in every
 * cell of the lattice across the plane: the leg is cut where it crosses cells, and each
 * piece is searched against the copies in its own cell and in the neighbours it comes
 * within the largest radius of (radii ≤ tile/2, render.cpp).  Each photon copy is
 * counted in the one piece that holds its nearest point on the ray. */
ARCUS_INLINE void ocean_beam_leg(__global const bvh_node* nodes, __global const REAL* photons, const photon_map_desc map,
                                 __global const REAL* radii, const ocean_render_desc* rd, __global const REAL* optics,
                                 REAL3 o, REAL3 w, REAL ta, REAL tb, REAL weight, __global REAL* out) {
  const REAL P = rd->tile;
  if (!(P > RC(0))) {
    ocean_beam_piece(nodes, photons, map, radii, &rd->phases, optics, o, w, ta, tb, weight, out);
    return;
  }
  REAL t = ta;
  for (int pieces = 0; t < tb && pieces < 100000; ++pieces) {
    /* the cell (cx, cy) the ray is in just after t, and where it leaves it */
    const REAL3 h = o + t * w;
    REAL cx = ocean_tile_cell(h.x, rd->tile_x, P), cy = ocean_tile_cell(h.y, rd->tile_y, P);
    REAL exit_x = (REAL)INFINITY, exit_y = (REAL)INFINITY;
    if (w.x != RC(0)) {
      exit_x = (rd->tile_x + (cx + (w.x > RC(0) ? RC(0.5) : RC(-0.5))) * P - o.x) / w.x;
      if (exit_x <= t) { /* on the edge it leaves through: the next cell */
        cx += w.x > RC(0) ? RC(1) : RC(-1);
        exit_x += P / fabs(w.x);
      }
    }
    if (w.y != RC(0)) {
      exit_y = (rd->tile_y + (cy + (w.y > RC(0) ? RC(0.5) : RC(-0.5))) * P - o.y) / w.y;
      if (exit_y <= t) {
        cy += w.y > RC(0) ? RC(1) : RC(-1);
        exit_y += P / fabs(w.y);
      }
    }
    const REAL t_next = fmin(tb, fmin(exit_x, exit_y));
    const REAL3 e = o + t_next * w;
    /* the piece's reach, in its cell's frame: how far it comes toward each side */
    const REAL x0 = fmin(h.x, e.x) - rd->tile_x - cx * P, x1 = fmax(h.x, e.x) - rd->tile_x - cx * P;
    const REAL y0 = fmin(h.y, e.y) - rd->tile_y - cy * P, y1 = fmax(h.y, e.y) - rd->tile_y - cy * P;
    for (int a = -1; a <= 1; ++a) {
      if ((a < 0 && x0 - rd->r_max >= -P / 2) || (a > 0 && x1 + rd->r_max <= P / 2)) continue;
      for (int b = -1; b <= 1; ++b) {
        if ((b < 0 && y0 - rd->r_max >= -P / 2) || (b > 0 && y1 + rd->r_max <= P / 2)) continue;
        const REAL3 shifted = o - (REAL3)((cx + (REAL)a) * P, (cy + (REAL)b) * P, RC(0));
        ocean_beam_piece(nodes, photons, map, radii, &rd->phases, optics, shifted, w, t, t_next, weight, out);
      }
    }
    t = t_next;
  }
}

__kernel void arcus_ocean_render(ARCUS_PARAMS(ARCUS_OCEAN_RENDER_ARGS)) {
  const int pixel = rd.first_pixel + (int)get_global_id(0);
  if (pixel >= rd.end_pixel) return;
  const int n = rd.count;
  __global REAL* out = radiance + (size_t)pixel * (size_t)n;
  __global REAL* T = scratch + (size_t)(pixel - rd.first_pixel) * (size_t)(2 * n); /* then the k-set's sums */
  __global const REAL* sigma_t = optics;
  __global const REAL* step_factor = optics + n;
  __global const REAL* sigma_s = optics + 3 * n;
  const ocean_phases* phases = &rd.phases;

  /* The ray through the pixel's centre (a pixel of this pass spans stride × stride of
   * the image's). */
  const int px = pixel % rd.width, py = pixel / rd.width;
  const REAL sx = RC(2) * ((REAL)px + RC(0.5)) * (REAL)rd.stride / (REAL)rd.image_width - RC(1);
  const REAL sy = RC(1) - RC(2) * ((REAL)py + RC(0.5)) * (REAL)rd.stride / (REAL)rd.image_height;
  const REAL3 eye = (REAL3)(rd.eye[0], rd.eye[1], rd.eye[2]);
  const REAL3 dir = normalize((REAL3)(rd.forward[0], rd.forward[1], rd.forward[2]) +
                              sx * (REAL3)(rd.right[0], rd.right[1], rd.right[2]) +
                              sy * (REAL3)(rd.up[0], rd.up[1], rd.up[2]));
  const REAL per_nm = RC(1) / rd.band;

  for (int m = 0; m < n; ++m) {
    out[m] = RC(0);
    T[m] = optics[2 * n + m]; /* exp(−σ_t Δt/2): the first midpoint */
  }
  /* The sky tables' columns about this ray's vertical cosine (sky_c0, weight sky_ct of
   * the next). */
  __global const REAL* sky_window = sky + n;
  __global const REAL* sky_elastic = sky_window + rd.sky_cosines;
  __global const REAL* sky_inelastic = sky_elastic + (size_t)rd.sky_rows * (size_t)rd.sky_cosines * (size_t)n;
  int sky_c0;
  REAL sky_ct;
  ocean_sky_column(dir.z, rd.sky_cosines, &sky_c0, &sky_ct);
  const REAL through = rd.sky_rows > 0 ? sky_window[sky_c0] + sky_ct * (sky_window[sky_c0 + 1] - sky_window[sky_c0]) : RC(0);
  /* A ray reaching the surface goes on reflected, by Fresnel's R (wholly outside
   * Snell's window): its path below the surface is the mirror image of the straight
   * ray's beyond it, so the march follows the straight ray and mirrors each point. */
  const REAL to_surface = rd.surface && dir.z > RC(0) ? -eye.z / dir.z : (REAL)INFINITY;
  const REAL reflectance = isfinite(to_surface) ? arcus_fresnel_reflectance(dir.z, rd.n_water, RC(1)) : RC(0);
  const REAL3 mirrored = (REAL3)(dir.x, dir.y, -dir.z);
  REAL3 w = dir; /* the direction the ray runs at this step: dir, or mirrored once reflected */
  int reflected = 0;
#ifdef ARCUS_USE_OCEAN_PHOTON_MAP
#ifndef ARCUS_USE_OCEAN_BEAM
  REAL d2[ARCUS_PHOTON_SEARCH_CAPACITY];
  int slot[ARCUS_PHOTON_SEARCH_CAPACITY];
  REAL r_last = (REAL)INFINITY; /* the k-th nearest distance at the last estimate (∞: unknown) */
  int last = 0, chosen = 0, block = 1; /* the last estimate's step; this block's jittered step, its steps */
  /* The photons about a stretch of the ray (photon/photon_line.h) and the sums over the
   * k-set, Σ p Φ per grid sample, beside the transmittances. */
  photon_line line;
  line.count = -1;
  __global REAL* S = T + n;
#endif
#endif

  for (int s = 0; s < rd.steps; ++s) {
    const REAL t = ((REAL)s + RC(0.5)) * rd.step;
    REAL3 x = eye + t * dir;
    if (t > to_surface) { /* reflected: the mirror image below the surface */
      x.z = -x.z;
      if (!reflected) { /* the first step past it */
        reflected = 1;
        w = mirrored;
        for (int m = 0; m < n; ++m) T[m] *= reflectance;
#if defined(ARCUS_USE_OCEAN_PHOTON_MAP) && !defined(ARCUS_USE_OCEAN_BEAM)
        line.count = -1; /* its photons' phase weights were toward the straight ray */
#endif
        ocean_sky_column(w.z, rd.sky_cosines, &sky_c0, &sky_ct);
      }
    }
    /* ---- single scattering from the lights (eq. 4.5 and its elastic part) */
    if (rd.single) {
      for (int l = 0; l < rd.light_count; ++l) {
        __global const REAL* L = lights + (size_t)l * ARCUS_OCEAN_LIGHT_REALS;
        if ((int)L[0] == ARCUS_OCEAN_EMIT_SKY) continue; /* its own tables, below */
        const int sun = (int)L[0] == ARCUS_OCEAN_EMIT_DIRECTIONAL;
        REAL3 wi; /* the light's propagation at x */
        REAL dist, spread;
        if (sun) { /* the refracted beam, after its slant path from the surface */
          wi = (REAL3)(L[4], L[5], L[6]);
          dist = x.z / wi.z;
          spread = RC(1);
        } else {
          const REAL3 to_x = x - (REAL3)(L[1], L[2], L[3]);
          dist = length(to_x);
          if (!(dist > RC(0))) continue;
          wi = to_x / dist;
          spread = RC(1) / (dist * dist);
        }
        if ((int)L[0] == ARCUS_OCEAN_EMIT_SPOT && dot(wi, (REAL3)(L[4], L[5], L[6])) < L[7]) continue;
        const REAL mu = -dot(wi, w); /* toward the camera: −w */
        const REAL pw = ocean_phase_value(phases, optics, 0, mu), pd = ocean_phase_value(phases, optics, 1, mu),
                   pp = ocean_phase_value(phases, optics, 2, mu);
        /* the light tables at this distance (rows g, g + 1; beyond the last: its last) */
        const REAL gx = fmin(dist / rd.g_step, (REAL)(rd.g_samples - 1));
        const int g0 = min((int)gx, rd.g_samples - 2);
        const REAL gt = gx - (REAL)g0;
        __global const REAL* E = light_tables + ((size_t)l * (size_t)rd.g_samples * 2 + (size_t)g0) * (size_t)n;
        const REAL w = rd.step * spread;
        for (int m = 0; m < n; ++m) {
          const REAL e = E[m] + gt * (E[n + m] - E[m]);
          REAL in = (sigma_s[m] * pw + sigma_s[n + m] * pd + sigma_s[2 * n + m] * pp) * e;
#ifdef ARCUS_USE_OCEAN_INELASTIC
          __global const REAL* G = E + (size_t)rd.g_samples * (size_t)n;
          in += G[m] + gt * (G[n + m] - G[m]);
#endif
          out[m] += T[m] * in * w;
        }
      }
    }
    /* ---- the sky's first scattering: its tables at this depth and the ray's vertical
     * cosine, bilinear (constant along the ray in the cosine) */
    if (rd.single && rd.sky_rows > 0) {
      const REAL gx = fmin(-x.z / rd.sky_d_step, (REAL)(rd.sky_rows - 1));
      const int g0 = min((int)gx, rd.sky_rows - 2);
      const REAL gt = gx - (REAL)g0;
      __global const REAL* E0 = sky_elastic + ((size_t)g0 * (size_t)rd.sky_cosines + (size_t)sky_c0) * (size_t)n;
      __global const REAL* E1 = E0 + (size_t)rd.sky_cosines * (size_t)n;
      for (int m = 0; m < n; ++m) {
        const REAL a = E0[m] + sky_ct * (E0[n + m] - E0[m]), b = E1[m] + sky_ct * (E1[n + m] - E1[m]);
        REAL in = a + gt * (b - a);
#ifdef ARCUS_USE_OCEAN_INELASTIC
        __global const REAL* G = sky_inelastic + (size_t)g0 * (size_t)n;
        in += G[m] + gt * (G[n + m] - G[m]);
#endif
        out[m] += T[m] * in * rd.step;
      }
    }
#ifdef ARCUS_USE_OCEAN_PHOTON_MAP
#ifndef ARCUS_USE_OCEAN_BEAM
    /* ---- multiple scattering: the k nearest photons (eq. 4.6), at every step, or with
     * subsample m at one step of every block of m, uniform in it per pixel and block and
     * weighted by the block's steps: its expectation is the sum over every step. */
    if (s % rd.subsample == 0) {
      block = min(rd.subsample, rd.steps - s);
      chosen = s + (rd.subsample == 1 ? 0 : min((int)(arcus_rng_uniform_double((arcus_u64)rd.seed, (arcus_u64)pixel,
                                                                                (arcus_u32)(s / rd.subsample)) *
                                                      (REAL)block),
                                                 block - 1));
    }
    /* The last estimate's k photons lie within r_last + (s − last) Δt of this point
     * (triangle inequality; the mirror image past the surface only comes nearer), so
     * that bound loses none of the k nearest: it bounds the stretch's pool's reach and
     * prunes a lone search. */
    if (rd.multiple && s == chosen) {
      const REAL g = (REAL)(s - last) * rd.step * RC(1.000001);
      /* From the stretch's pool when the estimates are a step apart; subsampled, they
       * lie too far apart for it to pay (m = 2: 1.3× slower with it), and each searches
       * alone. */
      int changes = 0, fresh = 0;
      REAL r = rd.subsample == 1 ? photon_line_query(nodes, photons, map, &line, x.x, x.y, x.z, w.x, w.y, w.z,
                                                     (REAL)(rd.steps - 1 - s) * rd.step, rd.k, r_last, g, d2, slot,
                                                     &changes, &fresh)
                                 : RC(-1);
      if (fresh || r < RC(0))
        for (int m = 0; m < n; ++m) S[m] = RC(0);
      if (r >= RC(0)) { /* the stretch's k-set, updated, and its sums */
        for (int c = 0; c < changes; ++c) {
          const int i = abs(slot[c]) - 1;
          if (isnan(line.weight[i])) line.weight[i] = ocean_photon_toward(phases, optics, photons, map, line.slot[i], w);
          ocean_photon_add(photons, map, line.slot[i], slot[c] > 0 ? line.weight[i] : -line.weight[i], S);
        }
        r_last = r;
      } else { /* a lone search */
        const REAL limit = r_last + g;
        const int found = photon_knn(nodes, photons, map, x.x, x.y, x.z, RC(0), RC(0), RC(0), rd.k, limit * limit, d2, slot);
        for (int i = 0; i < found; ++i)
          ocean_photon_add(photons, map, slot[i], ocean_photon_toward(phases, optics, photons, map, slot[i], w), S);
        if (found > 0) {
          r = sqrt(d2[0]);
          r_last = found == rd.k ? r : (REAL)INFINITY;
        }
      }
      if (r >= RC(0)) {
        last = s;
        const REAL f = (REAL)block * rd.step * per_nm / (RC(4) / RC(3) * OCEAN_PI * r * r * r);
        for (int m = 0; m < n; ++m) out[m] += T[m] * fmax(S[m], RC(0)) * f; /* the sums' rounding kept ≥ 0 */
      }
    }
#endif
#endif
    for (int m = 0; m < n; ++m) T[m] *= step_factor[m];
  }

  /* ---- Snell's window: a ray reaching the surface within the march sees the sky
   * through it, n²T L_s, dimmed along its whole path */
  if (rd.single && rd.sky_rows > 0 && to_surface <= rd.step * (REAL)rd.steps)
    for (int m = 0; m < n; ++m) out[m] += through * sky[m] * exp(-sigma_t[m] * to_surface);

#ifdef ARCUS_USE_OCEAN_BEAM
  /* ---- multiple scattering: the beam estimate along the ray up to the surface, then
   * along its reflection (the straight ray's mirror image) */
  if (rd.multiple && map.count > 0) {
    const REAL length = rd.step * (REAL)rd.steps;
    ocean_beam_leg(nodes, photons, map, radii, &rd, optics, eye, dir, RC(0), fmin(length, to_surface), per_nm, out);
    if (to_surface < length)
      ocean_beam_leg(nodes, photons, map, radii, &rd, optics, (REAL3)(eye.x, eye.y, -eye.z), mirrored, to_surface, length,
                     per_nm * reflectance, out);
  }
#endif
}

/* Each photon's radius for the beam estimate: the distance that holds its k nearest
 * photons (itself included, as Jarosz et al. gather it), estimated from its kr ≤ k
 * nearest as r_kr (k/kr)^(1/3), the radius at which a locally uniform density holds k:
 * a query's cost grows with the photons it keeps.  (Any radius gives a consistent
 * estimate; the radius only trades noise for blur.)  A work-item takes `chunk`
 * consecutive slots, neighbours in the map's BVH order: the last one's kr-th distance
 * plus the distance moved bounds this one's (triangle inequality), which prunes the
 * search and loses none of the kr nearest. */
__kernel void arcus_ocean_photon_radii(ARCUS_PARAMS(ARCUS_OCEAN_RADII_ARGS)) {
  const int first = (int)get_global_id(0) * chunk;
  REAL d2[ARCUS_PHOTON_SEARCH_CAPACITY];
  int slot[ARCUS_PHOTON_SEARCH_CAPACITY];
  REAL bound = (REAL)INFINITY;
  REAL3 last = (REAL3)(RC(0), RC(0), RC(0));
  const REAL scale = cbrt((REAL)k / (REAL)kr);
  for (int q = first; q < min(first + chunk, map.count); ++q) {
    const REAL3 x = (REAL3)(OCEAN_MAP(ARCUS_PHOTON_POSITION, q), OCEAN_MAP(ARCUS_PHOTON_POSITION + 1, q),
                            OCEAN_MAP(ARCUS_PHOTON_POSITION + 2, q));
    const REAL limit = bound + length(x - last) * RC(1.000001);
    const int found = photon_knn(nodes, photons, map, x.x, x.y, x.z, RC(0), RC(0), RC(0), kr, limit * limit, d2, slot);
    const REAL r = found > 0 ? sqrt(d2[0]) : RC(0);
    radii[q] = r * scale;
    bound = found == kr ? r : (REAL)INFINITY;
    last = x;
  }
}
