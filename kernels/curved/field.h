/* Index-of-refraction fields: n and ∇n at a point, analytic where the form allows
 * (thesis §2.2.2, §4.1.6).  Shared word for word by the host (arcus_field_evaluate,
 * double) and the kernels (REALV lanes), so both compute the same numbers.
 * The field kind is fixed at kernel build time by one ARCUS_FIELD_<KIND> define (the
 * device only compiles the field its job uses); the host passes the kind at run time. */
#ifndef ARCUS_FIELD_H
#define ARCUS_FIELD_H

#ifndef __OPENCL_C_VERSION__
#include "common/real.h" /* the device source has it prepended */
#include "sky/air.h"     /* likewise */
#endif

/* Field kinds: the values of arcus_field_kind in arcus.h. */
#define ARCUS_KIND_CONSTANT 0
#define ARCUS_KIND_LINEAR 1
#define ARCUS_KIND_LINEAR_N2 2
#define ARCUS_KIND_LUNEBURG 3
#define ARCUS_KIND_FISHEYE 4
#define ARCUS_KIND_ATMOSPHERE 5
#define ARCUS_KIND_GRID 6

/* ARCUS_ATM_G_M_OVER_R: kernels/sky/air.h. */
/* One atmosphere segment in the field data: temperature linear in geopotential height. */
#define ARCUS_ATM_SEGMENT_BASE_H 0 /* geopotential metres */
#define ARCUS_ATM_SEGMENT_BASE_T 1 /* K */
#define ARCUS_ATM_SEGMENT_LAPSE 2  /* K per geopotential metre */
#define ARCUS_ATM_SEGMENT_BASE_P 3 /* Pa */
#define ARCUS_ATM_SEGMENT_SIZE 4

/* The field description passed to kernels by value.  Declared once here for any real
 * type R and integer type I: the host declares a double and a float copy, the device
 * the one matching its precision, so the layouts match by construction.
 *   linear:     n0, vec = gradient            linear n²:  n0 = a, vec = k
 *   Luneburg:   vec = centre, inv_radius2     fish-eye:   n0, vec = centre, inv_radius2
 *   atmosphere: refractivity = (n−1)·T/p [K/Pa], earth_radius (of the sphere),
 *               geopotential_radius (US Standard Atmosphere 1976's r0), count = segments,
 *               layer = the thinnest segment's thickness below inversions_top (the
 *               highest inversion's top; 0 without inversions), layer_above = the
 *               thinnest above it, layers_top = the height of the last break
 *               (geometric metres): see field_step_cap
 *   grid:       origin, inv_spacing, dims                                           */
#define ARCUS_DECLARE_FIELD_DESC(NAME, R, I) \
  typedef struct NAME {                      \
    R n0;                                    \
    R inv_radius2;                           \
    R refractivity;                          \
    R earth_radius;                          \
    R geopotential_radius;                   \
    R layer;                                 \
    R layer_above;                           \
    R inversions_top;                        \
    R layers_top;                            \
    R vec[3];                                \
    R origin[3];                             \
    R inv_spacing[3];                        \
    I kind;                                  \
    I spherical;                             \
    I count;                                 \
    I dims[3];                               \
  } NAME

#ifdef __OPENCL_C_VERSION__
ARCUS_DECLARE_FIELD_DESC(field_desc, REAL, int);
/* The kind is a build-time constant on the device, from the job's field feature. */
#if defined(ARCUS_FIELD_LINEAR)
#define ARCUS_FIELD_KIND ARCUS_KIND_LINEAR
#elif defined(ARCUS_FIELD_LINEAR_N2)
#define ARCUS_FIELD_KIND ARCUS_KIND_LINEAR_N2
#elif defined(ARCUS_FIELD_LUNEBURG)
#define ARCUS_FIELD_KIND ARCUS_KIND_LUNEBURG
#elif defined(ARCUS_FIELD_FISHEYE)
#define ARCUS_FIELD_KIND ARCUS_KIND_FISHEYE
#elif defined(ARCUS_FIELD_ATMOSPHERE)
#define ARCUS_FIELD_KIND ARCUS_KIND_ATMOSPHERE
#elif defined(ARCUS_FIELD_GRID)
#define ARCUS_FIELD_KIND ARCUS_KIND_GRID
#else
#define ARCUS_FIELD_KIND ARCUS_KIND_CONSTANT
#endif
#define ARCUS_FIELD_KIND_OF(m) ARCUS_FIELD_KIND
#else
ARCUS_DECLARE_FIELD_DESC(arcus_field_desc_d, double, int32_t);
ARCUS_DECLARE_FIELD_DESC(arcus_field_desc_f, float, int32_t);
typedef arcus_field_desc_d field_desc;
#define ARCUS_FIELD_KIND_OF(m) ((m)->f->kind)
#endif

/* A field as one ray group sees it: the description, its data (atmosphere segments or
 * grid values) and, for per-ray wavelengths (ARCUS_USE_DISPERSION), each lane's
 * own refractivity in place of the description's. */
typedef struct medium {
  const field_desc* f;
  ARCUS_GLOBAL const REAL* data;
#ifdef ARCUS_USE_DISPERSION
  REALV refractivity;
#endif
} medium;

#ifdef ARCUS_USE_DISPERSION
#define MEDIUM_REFRACTIVITY(m) ((m)->refractivity)
#define GROUP_MEDIUM(m, g) (&(m)[g]) /* each lane group has its own wavelengths */
#else
#define MEDIUM_REFRACTIVITY(m) ((m)->f->refractivity)
#define GROUP_MEDIUM(m, g) (m) /* one medium for all groups */
#endif

/* Vacuum wavelengths Ciddor's dispersion formula covers, nm. */
#define ARCUS_MIN_WAVELENGTH 300.0
#define ARCUS_MAX_WAVELENGTH 1690.0

/* ciddor_refractivity: kernels/sky/air.h (the air's optics, shared with the sky). */

#ifdef __OPENCL_C_VERSION__
#ifdef ARCUS_USE_DISPERSION
#define ARCUS_MEDIA ARCUS_GROUPS
#else
#define ARCUS_MEDIA 1
#endif
/* Sets up the media of the work-item whose first lane vector is `first_vector`, as
 * medium med[ARCUS_MEDIA] (read through GROUP_MEDIUM): the field and its data, and with
 * per-ray wavelengths each lane's refractivity (an invalid wavelength gives NaN, which
 * the caller flags).  Every kernel that integrates rays (curved/advance.cl,
 * render/walk.cl) starts so. */
ARCUS_INLINE void media_init(medium* med, const field_desc* field, ARCUS_GLOBAL const REAL* data,
                             ARCUS_GLOBAL const REAL* wavelengths, size_t first_vector) {
  FOR_N(g, ARCUS_MEDIA) {
    med[g].f = field;
    med[g].data = data;
#ifdef ARCUS_USE_DISPERSION
    med[g].refractivity = ciddor_refractivity(VLOAD(first_vector + g, wavelengths));
#endif
  }
}
#endif

/* Atmosphere (thesis §3.1.1): temperature piecewise linear in geopotential height H
 * (US Standard Atmosphere 1976 plus inversion layers), pressure from the hydrostatic
 * equation in closed form per segment, n − 1 proportional to density p/T (Ciddor's
 * dry-air refractivity at the wavelength, scaled by the ideal-gas law).             */
ARCUS_INLINE void atmosphere_eval(const medium* m, REALV x, REALV y, REALV z, REALV* n, REALV* gx, REALV* gy,
                                  REALV* gz) {
  const field_desc* f = m->f;
  ARCUS_GLOBAL const REAL* seg = m->data;
  REALV radius = f->spherical ? sqrt(x * x + y * y + z * z) : y;
  REALV h = f->spherical ? radius - f->earth_radius : y;
  REALV ratio = f->geopotential_radius / (f->geopotential_radius + h);
  REALV H = h * ratio;        /* geopotential height */
  REALV dH_dh = ratio * ratio;
  /* Branch-free scan over the (few) segments: every lane picks its own. */
  REALV Hb = seg[ARCUS_ATM_SEGMENT_BASE_H], Tb = seg[ARCUS_ATM_SEGMENT_BASE_T];
  REALV L = seg[ARCUS_ATM_SEGMENT_LAPSE], pb = seg[ARCUS_ATM_SEGMENT_BASE_P];
  for (int k = 1; k < f->count; ++k) {
    ARCUS_GLOBAL const REAL* s = seg + k * ARCUS_ATM_SEGMENT_SIZE;
    MASKV above = H >= s[ARCUS_ATM_SEGMENT_BASE_H];
    Hb = SEL(Hb, (REALV)s[ARCUS_ATM_SEGMENT_BASE_H], above);
    Tb = SEL(Tb, (REALV)s[ARCUS_ATM_SEGMENT_BASE_T], above);
    L = SEL(L, (REALV)s[ARCUS_ATM_SEGMENT_LAPSE], above);
    pb = SEL(pb, (REALV)s[ARCUS_ATM_SEGMENT_BASE_P], above);
  }
  REALV dH = H - Hb;
  REALV T = Tb + L * dH;
  /* ∫ dH/T over the segment: log(T/Tb)/L, tending to dH/Tb as L → 0 (log1p keeps
   * it accurate for small L·dH/Tb, the select avoids 0/0). */
  REALV x_rel = L * dH / Tb;
  MASKV isothermal = fabs(x_rel) < RC(1e-12);
  REALV integral = SEL(log1p(x_rel) / L, dH / Tb, isothermal);
  REALV p = pb * exp(RC(-ARCUS_ATM_G_M_OVER_R) * integral);
  REALV refr = MEDIUM_REFRACTIVITY(m) * p / T; /* n − 1 */
  *n = RC(1) + refr;
  /* d(p/T)/dH = (p/T)·(−gM/(R·T) − L/T), then the chain rule to geometric height. */
  REALV dn_dh = refr * (RC(-ARCUS_ATM_G_M_OVER_R) - L) / T * dH_dh;
  if (f->spherical) {
    REALV s = dn_dh / radius;
    *gx = s * x;
    *gy = s * y;
    *gz = s * z;
  } else {
    *gx = RC(0);
    *gy = dn_dh;
    *gz = RC(0);
  }
}

/* One lane of the trilinear grid: the gradient is the exact derivative of the
 * interpolant, so values and gradient agree.  Outside, the face values extend
 * outwards with zero gradient across the face. */
ARCUS_INLINE REAL grid_axis(REAL u, int dim, int* i0, REAL* frac, REAL* inside) {
  *inside = (u >= RC(0) && u <= (REAL)(dim - 1)) ? RC(1) : RC(0);
  u = fmin(fmax(u, RC(0)), (REAL)(dim - 1));
  int i = (int)floor(u);
  i = i > dim - 2 ? dim - 2 : i;
  *i0 = i;
  *frac = u - (REAL)i;
  return u;
}

ARCUS_INLINE REAL grid_eval_one(const field_desc* f, ARCUS_GLOBAL const REAL* v, REAL x, REAL y, REAL z, REAL* gx,
                                REAL* gy, REAL* gz) {
  int i, j, k;
  REAL fx, fy, fz, ix, iy, iz;
  grid_axis((x - f->origin[0]) * f->inv_spacing[0], f->dims[0], &i, &fx, &ix);
  grid_axis((y - f->origin[1]) * f->inv_spacing[1], f->dims[1], &j, &fy, &iy);
  grid_axis((z - f->origin[2]) * f->inv_spacing[2], f->dims[2], &k, &fz, &iz);
  int nx = f->dims[0], nxy = f->dims[0] * f->dims[1];
  ARCUS_GLOBAL const REAL* c = v + (k * nxy + j * nx + i);
  REAL c000 = c[0], c100 = c[1], c010 = c[nx], c110 = c[nx + 1];
  REAL c001 = c[nxy], c101 = c[nxy + 1], c011 = c[nxy + nx], c111 = c[nxy + nx + 1];
  /* Interpolate along x, then y, then z, keeping the partial derivatives. */
  REAL c00 = c000 + fx * (c100 - c000), c10 = c010 + fx * (c110 - c010);
  REAL c01 = c001 + fx * (c101 - c001), c11 = c011 + fx * (c111 - c011);
  REAL c0 = c00 + fy * (c10 - c00), c1 = c01 + fy * (c11 - c01);
  REAL d00 = c100 - c000, d10 = c110 - c010, d01 = c101 - c001, d11 = c111 - c011;
  REAL dx0 = d00 + fy * (d10 - d00), dx1 = d01 + fy * (d11 - d01);
  *gx = ix * (dx0 + fz * (dx1 - dx0)) * f->inv_spacing[0];
  *gy = iy * ((c10 - c00) + fz * ((c11 - c01) - (c10 - c00))) * f->inv_spacing[1];
  *gz = iz * (c1 - c0) * f->inv_spacing[2];
  return c0 + fz * (c1 - c0);
}

ARCUS_INLINE void grid_eval(const field_desc* f, ARCUS_GLOBAL const REAL* values, REALV x, REALV y, REALV z,
                            REALV* n, REALV* gx, REALV* gy, REALV* gz) {
#if defined(__OPENCL_C_VERSION__) && ARCUS_LANES > 1
  /* Lanes gather from different cells: one lane at a time through private arrays. */
  REAL xs[ARCUS_LANES], ys[ARCUS_LANES], zs[ARCUS_LANES];
  REAL ns[ARCUS_LANES], gxs[ARCUS_LANES], gys[ARCUS_LANES], gzs[ARCUS_LANES];
  VSTORE(x, 0, xs);
  VSTORE(y, 0, ys);
  VSTORE(z, 0, zs);
  for (int l = 0; l < ARCUS_LANES; ++l)
    ns[l] = grid_eval_one(f, values, xs[l], ys[l], zs[l], &gxs[l], &gys[l], &gzs[l]);
  *n = VLOAD(0, ns);
  *gx = VLOAD(0, gxs);
  *gy = VLOAD(0, gys);
  *gz = VLOAD(0, gzs);
#else
  *n = grid_eval_one(f, values, x, y, z, gx, gy, gz);
#endif
}

/* n and ∇n of the field at (x, y, z). */
ARCUS_INLINE void field_eval(const medium* m, REALV x, REALV y, REALV z, REALV* n, REALV* gx, REALV* gy, REALV* gz) {
  const field_desc* f = m->f;
  const int kind = ARCUS_FIELD_KIND_OF(m);
  if (kind == ARCUS_KIND_CONSTANT) {
    *n = (REALV)f->n0;
    *gx = *gy = *gz = RC(0);
  } else if (kind == ARCUS_KIND_LINEAR) {
    *n = f->n0 + f->vec[0] * x + f->vec[1] * y + f->vec[2] * z;
    *gx = (REALV)f->vec[0];
    *gy = (REALV)f->vec[1];
    *gz = (REALV)f->vec[2];
  } else if (kind == ARCUS_KIND_LINEAR_N2) {
    /* n² = a + k·x  =>  ∇n = k / (2n) */
    *n = sqrt(f->n0 + f->vec[0] * x + f->vec[1] * y + f->vec[2] * z);
    REALV half_inv_n = RC(0.5) / *n;
    *gx = f->vec[0] * half_inv_n;
    *gy = f->vec[1] * half_inv_n;
    *gz = f->vec[2] * half_inv_n;
  } else if (kind == ARCUS_KIND_LUNEBURG) {
    /* n = sqrt(2 − ρ²), ρ = |r − c|/R, inside;  ∇n = −(r − c)/(R² n);  1 outside. */
    REALV dx = x - f->vec[0], dy = y - f->vec[1], dz = z - f->vec[2];
    REALV rho2 = (dx * dx + dy * dy + dz * dz) * f->inv_radius2;
    MASKV inside = rho2 < RC(1);
    REALV nin = sqrt(RC(2) - fmin(rho2, RC(1)));
    REALV s = SEL((REALV)RC(0), -f->inv_radius2 / nin, inside);
    *n = SEL((REALV)RC(1), nin, inside);
    *gx = s * dx;
    *gy = s * dy;
    *gz = s * dz;
  } else if (kind == ARCUS_KIND_FISHEYE) {
    /* n = n0 / q, q = 1 + ρ²;  ∇n = −2 n0 (r − c) / (R² q²) */
    REALV dx = x - f->vec[0], dy = y - f->vec[1], dz = z - f->vec[2];
    REALV inv_q = RC(1) / (RC(1) + (dx * dx + dy * dy + dz * dz) * f->inv_radius2);
    *n = f->n0 * inv_q;
    REALV s = RC(-2) * f->inv_radius2 * *n * inv_q;
    *gx = s * dx;
    *gy = s * dy;
    *gz = s * dz;
  } else if (kind == ARCUS_KIND_ATMOSPHERE) {
    atmosphere_eval(m, x, y, z, n, gx, gy, gz);
  } else {
    grid_eval(f, m->data, x, y, z, n, gx, gy, gz);
  }
}

/* The longest adaptive step the field allows from (r, v): an atmosphere's ∇n jumps at
 * every layer boundary, and a step whose stages all land outside a thin layer (an
 * inversion of a few metres) never sees it — the error estimate cannot either.  So,
 * below the top of the layers, no step may span more than half the thinnest layer in
 * height: every layer a ray crosses gets a stage inside.  Above the inversions only
 * the standard atmosphere's thick layers remain: there a step spans at most half the
 * thinnest of those, and never more than reaches half a thin layer into the
 * inversions (a ray coming down into them is held back as it arrives).  A horizontal
 * ray is not held back.  Other fields: no limit here (the host caps lenses, grids). */
ARCUS_INLINE REALV field_step_cap(const medium* m, REALV x, REALV y, REALV z, REALV vx, REALV vy, REALV vz) {
  const field_desc* f = m->f;
  if (ARCUS_FIELD_KIND_OF(m) != ARCUS_KIND_ATMOSPHERE) return (REALV)INFINITY;
  REALV radius = f->spherical ? sqrt(x * x + y * y + z * z) : y;
  REALV height = f->spherical ? radius - f->earth_radius : y;
  /* |dh/ds|: the direction's vertical component (v = n·dr/ds, |v| = n). */
  REALV rise = f->spherical ? fabs(x * vx + y * vy + z * vz) / radius : fabs(vy);
  REALV rate = rise / sqrt(vx * vx + vy * vy + vz * vz);
  const REALV thin = RC(0.5) * f->layer;
  const REALV above = fmin(RC(0.5) * f->layer_above, height - f->inversions_top + thin);
  const REALV cap = SEL(thin, above, height > f->inversions_top) / rate;
  return SEL(cap, (REALV)INFINITY, height > f->layers_top);
}

#endif /* ARCUS_FIELD_H */
