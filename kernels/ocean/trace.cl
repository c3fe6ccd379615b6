/* Spectral photon tracing through water (thesis §4.2, Fig. 4.5): each photon carries
 * one wavelength; free flights are drawn from the extinction coefficient, and at each
 * interaction a Russian roulette over the ten events of §4.2 (eq. 4.3–4.4) decides
 * between absorption, elastic scattering by one of three scatterers and an inelastic
 * re-emission (Raman, chlorophyll or CDOM fluorescence) at a new wavelength drawn by
 * inverting the tabulated CDF of the emission distribution (Stokes and anti-Stokes
 * alike), isotropically.  Photons are stored once scattered at least once (§4.2); an
 * interaction limit ends the rest (§5.3: five).
 *
 * One photon at a time per work-item, scalar: a photon's branches (ten events,
 * boundaries) differ from its neighbours', so lanes would mostly idle.  Work-item r
 * traces the photons i ≡ r (mod rows) in order and adds into its own tally row, so a
 * result depends neither on the launch's size nor on the device's lane layout.
 * Random numbers: Philox (common/philox.h), photon i's leg L (a flight and what ends
 * it) reads blocks 4 + 4L … 7 + 4L; emission reads blocks 0, 1 and (a point of a lit
 * disc or periodic tile on the surface) 2.  With a tile (d.tile > 0: an image of a sea
 * the same at every horizontal place) photons are stored folded into it.
 *
 * Hero wavelengths (Wilkie et al. 2014, "Hero wavelength spectral sampling"): the
 * stored photons carry d.heroes wavelengths, the hero's grid sample k and companions
 * at k + j·count/heroes (cyclically, so each of them, drawn as the hero, would carry
 * the same set).  The hero draws the path; the set shares it until an inelastic event
 * (after which the hero goes on alone: only its wavelength was re-emitted).  Each
 * stored photon splits the hero's power among the set by the balance heuristic over
 * "which of them was the hero": wavelength j's share is L_j / Σ L_i, L_i its emission
 * probability times the path's density at λ_i (σ_e e^(−σ_t s) per interaction,
 * e^(−σ_t s) per flight to a boundary; Fresnel, the bottom and the directions do not
 * depend on λ).  Unbiased per wavelength; one wavelength per photon puts each grid
 * sample's light in a different few photons, so colours came out blotchy.  The energy
 * tallies and the irradiance profiles follow the hero alone (the thesis' estimator).
 *
 * Features: ARCUS_USE_OCEAN_INELASTIC (the inelastic events), ARCUS_USE_OCEAN_BOUNDARIES
 * (surface, bottom, box), ARCUS_USE_OCEAN_DEPTHS (irradiance tallies at depths).   */

/* Two uniform draws of photon i's block `block`. */
ARCUS_INLINE void ocean_draw2(ulong seed, ulong i, uint block, REAL* u0, REAL* u1) {
  arcus_u32 w[4];
  arcus_rng_block(seed, i, block, w);
  *u0 = arcus_u01_double(w[0], w[1]);
  *u1 = arcus_u01_double(w[2], w[3]);
}

/* Where λ falls on the grid: samples k0, k1 and the weight t of k1. */
ARCUS_INLINE void ocean_grid_at(const ocean_desc* d, REAL nm, int* k0, int* k1, REAL* t) {
  if (d->count == 1) {
    *k0 = *k1 = 0;
    *t = RC(0);
    return;
  }
  const REAL x = clamp((nm - d->first_nm) / d->step_nm, RC(0), (REAL)(d->count - 1));
  const int k = min((int)x, d->count - 2);
  *k0 = k;
  *k1 = k + 1;
  *t = x - (REAL)k;
}

/* The nearest sample: the wavelength bin a tally adds to. */
ARCUS_INLINE int ocean_bin(const ocean_desc* d, REAL nm) {
  if (d->count == 1) return 0;
  return clamp((int)rint((nm - d->first_nm) / d->step_nm), 0, d->count - 1);
}

/* A unit vector at cos θ = mu, azimuth phi about the unit vector a. */
ARCUS_INLINE REAL3 ocean_turn(REAL3 a, REAL mu, REAL phi) {
  const REAL3 helper = fabs(a.x) < RC(0.9) ? (REAL3)(RC(1), RC(0), RC(0)) : (REAL3)(RC(0), RC(1), RC(0));
  const REAL3 e1 = normalize(cross(a, helper)), e2 = cross(a, e1);
  const REAL s = sqrt(fmax(RC(0), RC(1) - mu * mu));
  return normalize(mu * a + s * (cos(phi) * e1 + sin(phi) * e2));
}

/* x in [0, width] where a density running linearly from p0 to p1 over the width holds
 * `mass` (the inverse of its integral; the stable root of the quadratic). */
ARCUS_INLINE REAL ocean_linear_inverse(REAL p0, REAL p1, REAL width, REAL mass) {
  const REAL a = (p1 - p0) / (RC(2) * width);
  const REAL disc = fmax(p0 * p0 + RC(4) * a * mass, RC(0));
  const REAL den = p0 + sqrt(disc);
  const REAL x = den > RC(0) ? RC(2) * mass / den : width;
  return clamp(x, RC(0), width);
}

/* The piecewise-linear density given at abscissae x[0..n) by its values p[] and CDF c[]
 * (c[0] = 0, c[n−1] = 1), inverted at u.  The CDF's step to the next sample is never
 * 0 where u lands, so the search is exact. */
ARCUS_INLINE REAL ocean_sample_table(__global const REAL* x, __global const REAL* p, __global const REAL* c, int n,
                                     REAL u) {
  int lo = 0, hi = n - 1; /* c[lo] <= u < c[hi] */
  while (hi - lo > 1) {
    const int mid = (lo + hi) / 2;
    if (c[mid] <= u) lo = mid;
    else hi = mid;
  }
  return x[lo] + ocean_linear_inverse(p[lo], p[hi], x[hi] - x[lo], u - c[lo]);
}

/* The re-emitted wavelength of inelastic process p (0 Raman, 1 chlorophyll, 2 CDOM)
 * excited at grid sample k, for a uniform u: the tabulated CDF inverted, the density
 * linear between samples (src/ocean/water.h, WaterTables::emission). */
ARCUS_INLINE REAL ocean_emission_nm(const ocean_desc* d, __global const REAL* water, int p, int k, REAL u) {
  const size_t nn = (size_t)d->count * (size_t)d->count;
  __global const REAL* pdf = water + d->emission_offset + 2 * (size_t)p * nn + (size_t)k * (size_t)d->count;
  __global const REAL* cdf = pdf + nn;
  int lo = 0, hi = d->count - 1; /* cdf[lo] <= u < cdf[hi] */
  while (hi - lo > 1) {
    const int mid = (lo + hi) / 2;
    if (cdf[mid] <= u) lo = mid;
    else hi = mid;
  }
  return d->first_nm + d->step_nm * (REAL)lo + ocean_linear_inverse(pdf[lo], pdf[hi], d->step_nm, u - cdf[lo]);
}

/* Henyey–Greenstein: cos θ for a uniform u (the closed-form inverse). */
ARCUS_INLINE REAL ocean_hg_cos(REAL g, REAL u) {
  if (fabs(g) < RC(1e-6)) return RC(2) * u - RC(1);
  const REAL s = (RC(1) - g * g) / (RC(1) - g + RC(2) * g * u);
  return clamp((RC(1) + g * g - s * s) / (RC(2) * g), RC(-1), RC(1));
}

/* cos θ of scatterer s's phase function for a uniform u (thesis eq. 3.26, 3.28–3.29). */
ARCUS_INLINE REAL ocean_phase_cos(const ocean_phases* d, __global const REAL* water, int s, REAL u) {
  switch (d->kind[s]) {
    case ARCUS_OCEAN_PHASE_RAYLEIGH_LIKE: {
      /* p ∝ 1 + a μ²: F(μ) = (μ + aμ³/3 + 1 + a/3) / (2 + 2a/3) = u, a cubic with one
       * real root (its derivative is positive): Cardano. */
      const REAL a = d->a[s];
      const REAL c = (RC(2) * u - RC(1)) * (RC(1) + a / RC(3));
      if (a < RC(1e-12)) return c;
      const REAL p = RC(3) / a, q = RC(-3) * c / a;
      const REAL r = sqrt(q * q / RC(4) + p * p * p / RC(27));
      return clamp(cbrt(-q / RC(2) + r) + cbrt(-q / RC(2) - r), RC(-1), RC(1));
    }
    case ARCUS_OCEAN_PHASE_HG:
      return ocean_hg_cos(d->gf[s], u);
    case ARCUS_OCEAN_PHASE_TWO_TERM_HG: {
      /* the lobe by u, then u rescaled within the lobe's share: one draw for both */
      const REAL z = d->zeta[s];
      if (u < z) return ocean_hg_cos(d->gf[s], u / z);
      return ocean_hg_cos(d->gb[s], (u - z) / (RC(1) - z));
    }
    case ARCUS_OCEAN_PHASE_TABLE: {
      const int n = d->count[s];
      __global const REAL* x = water + d->offset[s];
      return ocean_sample_table(x, x + n, x + 2 * n, n, u);
    }
    default:
      return RC(2) * u - RC(1);
  }
}

/* Unpolarised Fresnel reflectance for light going from index n1 into n2 at cos_i. */
ARCUS_INLINE REAL ocean_fresnel(REAL cos_i, REAL n1, REAL n2) {
  const REAL sin_t = n1 / n2 * sqrt(fmax(RC(0), RC(1) - cos_i * cos_i));
  if (sin_t >= RC(1)) return RC(1); /* total internal reflection */
  const REAL cos_t = sqrt(RC(1) - sin_t * sin_t);
  const REAL rs = (n1 * cos_i - n2 * cos_t) / (n1 * cos_i + n2 * cos_t);
  const REAL rp = (n2 * cos_i - n1 * cos_t) / (n2 * cos_i + n1 * cos_t);
  return RC(0.5) * (rs * rs + rp * rp);
}

/* The extinction σ_t at grid position (k0, k1, t), and the event drawn by u. */
ARCUS_INLINE REAL ocean_extinction(const ocean_desc* d, __global const REAL* water, int k0, int k1, REAL t) {
  REAL sum = RC(0);
  for (int e = 0; e < d->events; ++e) {
    __global const REAL* c = water + (size_t)e * (size_t)d->count;
    sum += c[k0] + t * (c[k1] - c[k0]);
  }
  return sum;
}

ARCUS_INLINE int ocean_roulette(const ocean_desc* d, __global const REAL* water, int k0, int k1, REAL t,
                                REAL target) {
  REAL sum = RC(0);
  for (int e = 0; e < d->events; ++e) {
    __global const REAL* c = water + (size_t)e * (size_t)d->count;
    sum += c[k0] + t * (c[k1] - c[k0]);
    if (target < sum) return d->event_ids[e];
  }
  return d->event_ids[d->events - 1]; /* rounding at the top end */
}

/* The coefficient of event id e at grid sample k (0 for an event the water lacks). */
ARCUS_INLINE REAL ocean_event_coefficient(const ocean_desc* d, __global const REAL* water, int e, int k) {
  for (int a = 0; a < d->events; ++a)
    if (d->event_ids[a] == e) return water[(size_t)a * (size_t)d->count + (size_t)k];
  return RC(0);
}

/* The carried wavelengths' path densities times e^(−σ_t len) and, for an interaction
 * (e ≥ 0), σ_e; rescaled so that the largest is 1 (only their ratios matter). */
ARCUS_INLINE void ocean_heroes_follow(const ocean_desc* d, __global const REAL* water, int heroes, const int* hk,
                                      REAL* like, REAL len, int e) {
  if (heroes < 2) return;
  REAL top = RC(0);
  for (int j = 0; j < heroes; ++j) {
    like[j] *= exp(-ocean_extinction(d, water, hk[j], hk[j], RC(0)) * len); /* at grid sample hk[j] */
    if (e >= 0) like[j] *= ocean_event_coefficient(d, water, e, hk[j]);
    top = fmax(top, like[j]);
  }
  if (top > RC(0))
    for (int j = 0; j < heroes; ++j) like[j] /= top;
}

#ifdef ARCUS_USE_OCEAN_BOUNDARIES
/* Distance along dir to the nearest boundary, and which: 0 box (*face: the axis, +3
 * for its upper face), 1 surface, 2 bottom. */
ARCUS_INLINE REAL ocean_boundary(const ocean_desc* d, REAL3 p, REAL3 dir, int* which, int* face) {
  REAL best = (REAL)INFINITY;
  *which = 0;
  *face = 0;
  const REAL pc[3] = {p.x, p.y, p.z}, dc[3] = {dir.x, dir.y, dir.z};
  for (int a = 0; a < 3; ++a) {
    const int up = dc[a] > RC(0);
    const REAL wall = up ? d->box_hi[a] : d->box_lo[a];
    if (dc[a] == RC(0) || !isfinite(wall)) continue;
    const REAL s = fmax(RC(0), (wall - pc[a]) / dc[a]);
    if (s < best) {
      best = s;
      *face = a + 3 * up;
    }
  }
  if (d->surface && dir.z > RC(0)) {
    const REAL s = fmax(RC(0), -p.z / dir.z);
    if (s <= best) {
      best = s;
      *which = 1;
    }
  }
  if (isfinite(d->bottom_depth) && dir.z < RC(0)) {
    const REAL s = fmax(RC(0), (-d->bottom_depth - p.z) / dir.z);
    if (s <= best) {
      best = s;
      *which = 2;
    }
  }
  return best;
}
#endif

#ifdef ARCUS_USE_OCEAN_DEPTHS
/* A flight from z0 to z1 (length len) of power w in wavelength bin b: plane
 * irradiances by counting crossings (downward: z0 ≥ −depth > z1, so photons entering
 * at the surface count at depth 0), scalar irradiance by the track length inside a
 * layer of thickness desc.layer about the depth (clipped to the water). */
ARCUS_INLINE void ocean_tally_depths(const ocean_desc* d, __global const REAL* depths, __global REAL* row, REAL z0,
                                     REAL z1, REAL len, REAL w, int b) {
  const REAL zmin = fmin(z0, z1), zmax = fmax(z0, z1);
  for (int j = 0; j < d->depth_count; ++j) {
    const REAL z = -depths[j];
    __global REAL* cell = row + ((size_t)j * (size_t)d->count + (size_t)b) * 3;
    if (z0 >= z && z > z1) cell[0] += w;
    else if (z0 < z && z <= z1) cell[1] += w;
    REAL lo = fmax(z - RC(0.5) * d->layer, d->box_lo[2]), hi = fmin(z + RC(0.5) * d->layer, d->box_hi[2]);
    if (d->surface) hi = fmin(hi, RC(0));
    if (isfinite(d->bottom_depth)) lo = fmax(lo, -d->bottom_depth);
    if (hi <= lo || zmax < lo || zmin > hi) continue;
    const REAL inside = zmax > zmin ? len * (fmin(zmax, hi) - fmax(zmin, lo)) / (zmax - zmin) : len;
    cell[2] += w * inside / (hi - lo);
  }
}
#endif

/* Refracts a downward direction from air into water (Snell: the tangential part
 * shrinks by 1/n) and returns the Fresnel transmittance. */
ARCUS_INLINE REAL ocean_enter_water(const ocean_desc* d, REAL3* dir) {
  const REAL cos_i = -dir->z;
  const REAL T = RC(1) - ocean_fresnel(cos_i, RC(1), d->n_water);
  const REAL tx = dir->x / d->n_water, ty = dir->y / d->n_water;
  *dir = (REAL3)(tx, ty, -sqrt(fmax(RC(0), RC(1) - tx * tx - ty * ty)));
  return T;
}

__kernel void arcus_ocean_trace(ARCUS_PARAMS(ARCUS_OCEAN_TRACE_ARGS)) {
  const int r = (int)get_global_id(0);
  if (r >= d.rows) return;
  const ocean_desc* dp = &d;
  __global REAL* t = tallies + (size_t)r * (size_t)ARCUS_OCEAN_TALLY_REALS(d.bins);
#ifdef ARCUS_USE_OCEAN_DEPTHS
  __global REAL* depth_row = depth_tallies + (size_t)r * (size_t)d.depth_count * (size_t)d.count * 3;
#endif
  const ulong rows = (ulong)d.rows;
  ulong i = d.first_photon + ((ulong)r + rows - d.first_photon % rows) % rows;
  for (; i < d.end_photon; i += rows) {
    REAL u0, u1;
    /* ---- emission: the (light, sample) pair by the emission CDF, then where and whither */
    ocean_draw2(d.seed, i, 0, &u0, &u1);
    const int pairs = d.light_count * d.count;
    int lo = -1, hi = pairs - 1; /* the first pair whose CDF exceeds u0 */
    while (hi - lo > 1) {
      const int mid = (lo + hi) / 2;
      if (emission[mid] > u0) hi = mid;
      else lo = mid;
    }
    __global const REAL* L = lights + (size_t)(hi / d.count) * ARCUS_OCEAN_LIGHT_REALS;
    REAL nm = d.first_nm + d.step_nm * (REAL)(hi % d.count);
    /* the carried set: grid samples count/heroes apart, each L_j from its pair's
     * emission probability (the same light) */
    int heroes = d.heroes, hk[ARCUS_OCEAN_MAX_HEROES];
    REAL like[ARCUS_OCEAN_MAX_HEROES];
    for (int j = 0; j < heroes; ++j) {
      hk[j] = (hi % d.count + j * (d.count / heroes)) % d.count;
      const int pair = (hi / d.count) * d.count + hk[j];
      like[j] = emission[pair] - (pair > 0 ? emission[pair - 1] : RC(0));
    }
    const int kind = (int)L[0];
    REAL3 p = (REAL3)(L[1], L[2], L[3]), axis = (REAL3)(L[4], L[5], L[6]), dir;
    REAL a0, a1;
    ocean_draw2(d.seed, i, 1, &a0, &a1);
    REAL power = d.power;
    t[ARCUS_OCEAN_T_EMITTED] += power;
    t[ARCUS_OCEAN_T_PHOTONS] += RC(1);
    if (kind == ARCUS_OCEAN_EMIT_POINT) {
      dir = ocean_turn((REAL3)(RC(0), RC(0), RC(1)), RC(1) - RC(2) * a0, RC(2) * OCEAN_PI * a1);
    } else if (kind == ARCUS_OCEAN_EMIT_SPOT) {
      dir = ocean_turn(axis, RC(1) - a0 * (RC(1) - L[7]), RC(2) * OCEAN_PI * a1);
    } else {
      if (kind == ARCUS_OCEAN_EMIT_SKY) /* cosine-weighted from the upper hemisphere */
        dir = ocean_turn((REAL3)(RC(0), RC(0), RC(-1)), sqrt(a0), RC(2) * OCEAN_PI * a1);
      else
        dir = axis;
      if (d.surface) {
        p.z = RC(0);
        REAL b0, b1; /* block 2: the sky's direction took a0, a1 */
        ocean_draw2(d.seed, i, 2, &b0, &b1);
        if (d.tile > RC(0)) { /* a point of the periodic tile, uniform */
          p.x = d.tile_x + d.tile * (b0 - RC(0.5));
          p.y = d.tile_y + d.tile * (b1 - RC(0.5));
        } else if (L[8] > RC(0)) { /* a point of the lit disc on the surface: radius R√u, uniform in area */
          const REAL rr = L[8] * sqrt(b0), phi = RC(2) * OCEAN_PI * b1;
          p.x += rr * cos(phi);
          p.y += rr * sin(phi);
        }
        const REAL T = ocean_enter_water(dp, &dir);
        t[ARCUS_OCEAN_T_ESCAPED(d.bins)] += power * (RC(1) - T); /* reflected by the surface */
        power *= T;
      } else if (kind == ARCUS_OCEAN_EMIT_DIRECTIONAL && L[8] > RC(0)) {
        /* a point of the beam's disc: radius R√u, uniform in area */
        const REAL3 helper = fabs(axis.x) < RC(0.9) ? (REAL3)(RC(1), RC(0), RC(0)) : (REAL3)(RC(0), RC(1), RC(0));
        const REAL3 e1 = normalize(cross(axis, helper)), e2 = cross(axis, e1);
        const REAL rr = L[8] * sqrt(a0), phi = RC(2) * OCEAN_PI * a1;
        p += rr * (cos(phi) * e1 + sin(phi) * e2);
      }
    }

    /* ---- transport */
    const REAL3 start = p;
    int n = 0, bounces = 0;
    for (uint leg = 0;; ++leg) {
      int k0, k1;
      REAL tw;
      ocean_grid_at(dp, nm, &k0, &k1, &tw);
      const REAL sigma_t = ocean_extinction(dp, water, k0, k1, tw);
      REAL uf, ur;
      ocean_draw2(d.seed, i, 4 + 4 * leg, &uf, &ur);
      REAL s = sigma_t > RC(0) ? -log1p(-uf) / sigma_t : (REAL)INFINITY;
#ifdef ARCUS_USE_OCEAN_BOUNDARIES
      int which, face;
      const REAL to_wall = ocean_boundary(dp, p, dir, &which, &face);
      if (to_wall <= s) {
        if (!isfinite(to_wall)) {
          t[ARCUS_OCEAN_T_ESCAPED(d.bins) + min(n, d.bins)] += power; /* out to infinity */
          break;
        }
        REAL3 q = p + to_wall * dir;
        /* exactly on the plane it reached, so the depth tallies count the crossing */
        if (which == 1) q.z = RC(0);
        if (which == 2) q.z = -d.bottom_depth;
        if (which == 0 && face == 2) q.z = d.box_lo[2];
        if (which == 0 && face == 5) q.z = d.box_hi[2];
        ocean_heroes_follow(dp, water, heroes, hk, like, to_wall, -1);
#ifdef ARCUS_USE_OCEAN_DEPTHS
        ocean_tally_depths(dp, depths, depth_row, p.z, q.z, to_wall, power, ocean_bin(dp, nm));
#endif
        p = q;
        REAL ub, uc, ud;
        ocean_draw2(d.seed, i, 5 + 4 * leg, &ub, &uc);
        ocean_draw2(d.seed, i, 6 + 4 * leg, &ud, &u1);
        if (which == 0) {
          t[ARCUS_OCEAN_T_ESCAPED(d.bins) + min(n, d.bins)] += power;
          break;
        }
        if (which == 1) { /* the surface from below: Fresnel reflection or escape */
          if (ub >= ocean_fresnel(dir.z, d.n_water, RC(1))) {
            t[ARCUS_OCEAN_T_ESCAPED(d.bins) + min(n, d.bins)] += power;
            break;
          }
          dir.z = -dir.z;
        } else { /* the bottom: Lambertian with its albedo, else absorbed there */
          if (ub >= d.bottom_albedo) {
            t[ARCUS_OCEAN_T_BOTTOM] += power;
            break;
          }
          dir = ocean_turn((REAL3)(RC(0), RC(0), RC(1)), sqrt(uc), RC(2) * OCEAN_PI * ud);
        }
        if (++bounces > ARCUS_OCEAN_MAX_BOUNCES) {
          t[ARCUS_OCEAN_T_PAST_LIMIT] += power;
          break;
        }
        continue;
      }
#endif
      if (!isfinite(s)) { /* nothing to meet: an empty, unbounded medium */
        t[ARCUS_OCEAN_T_ESCAPED(d.bins) + min(n, d.bins)] += power;
        break;
      }
      const REAL3 q = p + s * dir;
#ifdef ARCUS_USE_OCEAN_DEPTHS
      ocean_tally_depths(dp, depths, depth_row, p.z, q.z, s, power, ocean_bin(dp, nm));
#endif
      p = q;
      ++n;
      t[ARCUS_OCEAN_T_INTERACTIONS] += RC(1);
      const int e = ocean_roulette(dp, water, k0, k1, tw, ur * sigma_t);
      ocean_heroes_follow(dp, water, heroes, hk, like, s, e);
      t[ARCUS_OCEAN_T_COUNT + e] += RC(1);
      t[ARCUS_OCEAN_T_ARRIVING + e] += power;
      const REAL3 arrived = dir;
      REAL um, uphi;
      ocean_draw2(d.seed, i, 5 + 4 * leg, &um, &uphi);
      if (e == ARCUS_OCEAN_SCATTER_WATER || e == ARCUS_OCEAN_SCATTER_DETRITUS || e == ARCUS_OCEAN_SCATTER_PHYTO) {
        dir = ocean_turn(dir, ocean_phase_cos(&d.phases, water, e - ARCUS_OCEAN_SCATTER_WATER, um), RC(2) * OCEAN_PI * uphi);
      }
#ifdef ARCUS_USE_OCEAN_INELASTIC
      else if (e == ARCUS_OCEAN_RAMAN || e == ARCUS_OCEAN_FLUORESCE_PHYTO || e == ARCUS_OCEAN_FLUORESCE_CDOM) {
        /* The exciting sample by λ's place between k0 and k1 (so the emission
         * distribution is interpolated linearly in λi), then λo from its CDF. */
        const int process = e == ARCUS_OCEAN_RAMAN ? 0 : e == ARCUS_OCEAN_FLUORESCE_PHYTO ? 1 : 2;
        REAL uk, ue;
        ocean_draw2(d.seed, i, 6 + 4 * leg, &uk, &ue);
        const int k = uk < tw ? k1 : k0;
        const REAL out_nm = ocean_emission_nm(dp, water, process, k, ue);
        const REAL ratio = nm / out_nm; /* energy of the new photon per old one */
        t[ARCUS_OCEAN_T_ABSORBED + e] += power * (RC(1) - ratio);
        t[ARCUS_OCEAN_T_BY_INTERACTION + min(n, d.bins)] += power * (RC(1) - ratio);
        power *= ratio;
        nm = out_nm;
        heroes = 1; /* only the hero's wavelength was re-emitted: it goes on alone */
        dir = ocean_turn((REAL3)(RC(0), RC(0), RC(1)), RC(1) - RC(2) * um, RC(2) * OCEAN_PI * uphi);
      }
#endif
      else { /* absorption */
        t[ARCUS_OCEAN_T_ABSORBED + e] += power;
        t[ARCUS_OCEAN_T_BY_INTERACTION + min(n, d.bins)] += power;
        const REAL3 moved = p - start;
        t[ARCUS_OCEAN_T_ABSORBED_R2] += power * dot(moved, moved);
        break;
      }
      if (d.store && n >= 2) { /* scattered before: the photon map's multiple scattering */
        __global REAL* sp = stored + ((size_t)i * (size_t)(d.limit - 1) + (size_t)(n - 2)) * ARCUS_OCEAN_PHOTON_REALS;
        /* folded into the periodic tile: the copy of this photon that lies in it */
        sp[0] = d.tile > RC(0) ? p.x - d.tile * ocean_tile_cell(p.x, d.tile_x, d.tile) : p.x;
        sp[1] = d.tile > RC(0) ? p.y - d.tile * ocean_tile_cell(p.y, d.tile_y, d.tile) : p.y;
        sp[2] = p.z;
        sp[3] = arrived.x;
        sp[4] = arrived.y;
        sp[5] = arrived.z;
        sp[ARCUS_OCEAN_STORED_EVENT] = (REAL)e;
        if (heroes == 1) {
          sp[ARCUS_OCEAN_STORED_POWER] = power;
          sp[ARCUS_OCEAN_STORED_NM] = nm;
        } else {
          REAL sum = RC(0);
          for (int j = 0; j < heroes; ++j) sum += like[j];
          for (int j = 0; j < heroes; ++j) {
            sp[ARCUS_OCEAN_STORED_POWER + j] = power * like[j] / sum;
            sp[ARCUS_OCEAN_STORED_NM + j] = d.first_nm + d.step_nm * (REAL)hk[j];
          }
        }
        t[ARCUS_OCEAN_T_STORED] += RC(1);
      }
      if (n >= d.limit) {
        t[ARCUS_OCEAN_T_PAST_LIMIT] += power;
        break;
      }
    }
  }
}
