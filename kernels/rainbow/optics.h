/* One ray through one particle with its polarisation and phase (thesis §4.4.2): the
 * particle's surfaces, the Fresnel interface in amplitudes, and the walk of the ray
 * through p = 0..P.  Scalar code that the host includes too (tests, and the bisection
 * that finds the projected edge): prepend common/real.h, common/fresnel.h,
 * bvh/bvh_desc.h, bvh/traverse.h and rainbow/rainbow_desc.h.
 *
 * Conventions.  Fields are complex 3-vectors, a wave e^{i(k·x − ωt)}: the optical path
 * l adds the phase +2πl/λ, and an evanescent transmitted wave under total internal
 * reflection decays for cos θ_t = +i·sqrt(sin²θ_t − 1).  At an interface the incident
 * direction k, the normal m toward the incident side, s = k × m / |k × m| (normal to
 * the plane of incidence) and p = s × k for every ray (incident, reflected, refracted)
 * fix the signs of the Fresnel amplitudes below; at normal incidence they reduce to
 * r_s = (n1 − n2)/(n1 + n2) = −r_p, the same reflected field whatever s is taken.
 * Transmitted amplitudes carry sqrt(n2 cos θ_t / (n1 cos θ_i)), so |E|² is the ray's
 * share of power and |r|² + |t|² = 1 at every interface (§2.2.3). */
#ifndef ARCUS_RAINBOW_OPTICS_H
#define ARCUS_RAINBOW_OPTICS_H

#ifndef __OPENCL_C_VERSION__
#include "bvh/traverse.h"
#include "common/fresnel.h"
#include "rainbow/rainbow_desc.h"
#endif

/* ---- complex numbers and vectors ------------------------------------------------ */
typedef struct rb_complex {
  REAL re, im;
} rb_complex;

ARCUS_INLINE rb_complex rb_c(REAL re, REAL im) {
  rb_complex c;
  c.re = re;
  c.im = im;
  return c;
}
ARCUS_INLINE rb_complex rb_mul(rb_complex a, rb_complex b) {
  return rb_c(a.re * b.re - a.im * b.im, a.re * b.im + a.im * b.re);
}
ARCUS_INLINE rb_complex rb_div(rb_complex a, rb_complex b) {
  const REAL d = b.re * b.re + b.im * b.im;
  return rb_c((a.re * b.re + a.im * b.im) / d, (a.im * b.re - a.re * b.im) / d);
}
ARCUS_INLINE rb_complex rb_scale(rb_complex a, REAL s) { return rb_c(a.re * s, a.im * s); }

ARCUS_INLINE REAL rb_dot(const REAL* a, const REAL* b) { return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]; }
ARCUS_INLINE void rb_cross(const REAL* a, const REAL* b, REAL* out) {
  const REAL x = a[1] * b[2] - a[2] * b[1], y = a[2] * b[0] - a[0] * b[2], z = a[0] * b[1] - a[1] * b[0];
  out[0] = x;
  out[1] = y;
  out[2] = z;
}
ARCUS_INLINE void rb_normalize(REAL* a) {
  const REAL l = sqrt(rb_dot(a, a));
  a[0] /= l;
  a[1] /= l;
  a[2] /= l;
}

/* A ray's field for both incident polarisations: E[pol][axis] complex. */
typedef struct rb_field {
  rb_complex e[2][3];
} rb_field;

/* The complex component of field pol along the real unit vector u. */
ARCUS_INLINE rb_complex rb_component(const rb_field* f, int pol, const REAL* u) {
  return rb_c(f->e[pol][0].re * u[0] + f->e[pol][1].re * u[1] + f->e[pol][2].re * u[2],
              f->e[pol][0].im * u[0] + f->e[pol][1].im * u[1] + f->e[pol][2].im * u[2]);
}

ARCUS_INLINE REAL rb_power(const rb_field* f, int pol) {
  REAL s = 0;
  for (int a = 0; a < 3; ++a) s += f->e[pol][a].re * f->e[pol][a].re + f->e[pol][a].im * f->e[pol][a].im;
  return s;
}

/* ---- Fresnel in amplitudes (thesis §2.2.3, eq. 2.17 for total internal reflection) */
typedef struct rb_fresnel {
  rb_complex rs, rp, ts, tp; /* ts, tp: power-normalised; 0 under total reflection */
  REAL cos_t;                /* 0 under total reflection */
  int total;                 /* total internal reflection */
} rb_fresnel;

/* cos_i = cos θ_i > 0 on the incident side; eta = n1 / n2. */
ARCUS_INLINE rb_fresnel rb_fresnel_coefficients(REAL cos_i, REAL n1, REAL n2) {
  rb_fresnel f;
  const arcus_fresnel_real a = arcus_fresnel_amplitudes(cos_i, n1, n2); /* common/fresnel.h */
  if (!a.total) {
    const REAL cos_t = a.cos_t;
    const REAL ds = n1 * cos_i + n2 * cos_t, dp = n2 * cos_i + n1 * cos_t;
    const REAL power = sqrt(n2 * cos_t / (n1 * cos_i)); /* 0 at grazing incidence */
    f.rs = rb_c(a.rs, 0);
    f.rp = rb_c(a.rp, 0);
    f.ts = rb_c(RC(2) * n1 * cos_i / ds * power, 0);
    f.tp = rb_c(RC(2) * n1 * cos_i / dp * power, 0);
    f.cos_t = cos_t;
    f.total = 0;
  } else {
    /* cos θ_t = i·c: the same formulas continued, each |r| = 1 with a phase (eq. 2.17) */
    const REAL c = sqrt(a.sin2_t - RC(1));
    f.rs = rb_div(rb_c(n1 * cos_i, -n2 * c), rb_c(n1 * cos_i, n2 * c));
    f.rp = rb_div(rb_c(n2 * cos_i, -n1 * c), rb_c(n2 * cos_i, n1 * c));
    f.ts = rb_c(0, 0);
    f.tp = rb_c(0, 0);
    f.cos_t = 0;
    f.total = 1;
  }
  return f;
}

/* A unit vector normal to the unit vector k (any: used at normal incidence only). */
ARCUS_INLINE void rb_any_normal(const REAL* k, REAL* out) {
  const REAL a[3] = {fabs(k[0]) < RC(0.9) ? RC(1) : RC(0), fabs(k[0]) < RC(0.9) ? RC(0) : RC(1), RC(0)};
  rb_cross(k, a, out);
  rb_normalize(out);
}

/* The interface at which the ray k (unit) with field `in` meets the normal m (unit,
 * toward the incident side), from index n1 into n2: the reflected direction and field,
 * and (unless totally reflected: returns 0) the refracted ones. */
ARCUS_INLINE int rb_interface(const REAL* k, const REAL* m, REAL n1, REAL n2, const rb_field* in, REAL* kr,
                              rb_field* er, REAL* kt, rb_field* et, rb_fresnel* out_f) {
  const REAL cos_i = fmin(RC(1), -rb_dot(k, m));
  REAL s[3];
  rb_cross(k, m, s);
  if (rb_dot(s, s) < RC(1e-28))
    rb_any_normal(k, s);
  else
    rb_normalize(s);
  REAL pi[3], pr[3], pt[3];
  rb_cross(s, k, pi);
  for (int a = 0; a < 3; ++a) kr[a] = k[a] + RC(2) * cos_i * m[a];
  rb_cross(s, kr, pr);
  const rb_fresnel f = rb_fresnel_coefficients(cos_i, n1, n2);
  *out_f = f;
  if (!f.total) {
    const REAL eta = n1 / n2;
    for (int a = 0; a < 3; ++a) kt[a] = eta * k[a] + (eta * cos_i - f.cos_t) * m[a];
    rb_normalize(kt);
    rb_cross(s, kt, pt);
  }
  for (int pol = 0; pol < 2; ++pol) {
    const rb_complex es = rb_component(in, pol, s), ep = rb_component(in, pol, pi);
    const rb_complex rs = rb_mul(f.rs, es), rp = rb_mul(f.rp, ep);
    const rb_complex ts = rb_mul(f.ts, es), tp = rb_mul(f.tp, ep);
    for (int a = 0; a < 3; ++a) {
      er->e[pol][a] = rb_c(rs.re * s[a] + rp.re * pr[a], rs.im * s[a] + rp.im * pr[a]);
      if (!f.total) et->e[pol][a] = rb_c(ts.re * s[a] + tp.re * pt[a], ts.im * s[a] + tp.im * pt[a]);
    }
  }
  return !f.total;
}

/* ---- surfaces -------------------------------------------------------------------- */

/* A mesh particle on the device: the shared BVH's nodes, triangles (9 per leaf slot)
 * and slot → triangle order, and per slot its vertices' normals (9 reals) for a mesh
 * that approximates a smooth surface, or null for flat faces.  Null for other shapes. */
typedef struct rb_mesh {
  ARCUS_GLOBAL const bvh_node* nodes;
  ARCUS_GLOBAL const REAL* tris;
  ARCUS_GLOBAL const int* order;
  ARCUS_GLOBAL const REAL* normals;
} rb_mesh;

/* The barycentric weights (u of v1, v of v2) of the point x in the plane of the
 * triangle v0, v1, v2. */
ARCUS_INLINE void rb_barycentric(ARCUS_GLOBAL const REAL* tri, const REAL* x, REAL* u, REAL* v) {
  const REAL e1[3] = {tri[3] - tri[0], tri[4] - tri[1], tri[5] - tri[2]};
  const REAL e2[3] = {tri[6] - tri[0], tri[7] - tri[1], tri[8] - tri[2]};
  const REAL w[3] = {x[0] - tri[0], x[1] - tri[1], x[2] - tri[2]};
  const REAL g11 = rb_dot(e1, e1), g12 = rb_dot(e1, e2), g22 = rb_dot(e2, e2);
  const REAL b1 = rb_dot(e1, w), b2 = rb_dot(e2, w), det = g11 * g22 - g12 * g12;
  *u = (g22 * b1 - g12 * b2) / det;
  *v = (g11 * b2 - g12 * b1) / det;
}

/* The smooth mesh's normal field at barycentric (u, v) of slot s, unnormalised. */
ARCUS_INLINE void rb_mesh_normal(const rb_mesh* m, int s, REAL u, REAL v, REAL* n) {
  ARCUS_GLOBAL const REAL* nv = m->normals + 9 * (size_t)s;
  for (int a = 0; a < 3; ++a) n[a] = (RC(1) - u - v) * nv[a] + u * nv[3 + a] + v * nv[6 + a];
}

/* The raindrop of thesis eq. 4.21 in its own frame (y up; the equation's "= 0" is the
 * surface F = 0 of F = (x² + z²)/a² (1 − k y/b) + y²/b² − 1, negative inside). */
ARCUS_INLINE REAL rb_raindrop_f(const REAL* s, const REAL* q) {
  const REAL a = s[0], b = s[1], k = s[2];
  return (q[0] * q[0] + q[2] * q[2]) / (a * a) * (RC(1) - k * q[1] / b) + q[1] * q[1] / (b * b) - RC(1);
}

/* F along o + t·w as the cubic c[0] + c[1] t + c[2] t² + c[3] t³. */
ARCUS_INLINE void rb_raindrop_cubic(const REAL* s, const REAL* o, const REAL* w, REAL* c) {
  const REAL a2 = s[0] * s[0], b = s[1], b2 = b * b, k = s[2];
  const REAL A0 = o[0] * o[0] + o[2] * o[2], A1 = RC(2) * (o[0] * w[0] + o[2] * w[2]), A2 = w[0] * w[0] + w[2] * w[2];
  const REAL B0 = RC(1) - k * o[1] / b, B1 = -k * w[1] / b;
  c[3] = A2 * B1 / a2;
  c[2] = (A2 * B0 + A1 * B1) / a2 + w[1] * w[1] / b2;
  c[1] = (A1 * B0 + A0 * B1) / a2 + RC(2) * o[1] * w[1] / b2;
  c[0] = A0 * B0 / a2 + o[1] * o[1] / b2 - RC(1);
}

ARCUS_INLINE REAL rb_cubic(const REAL* c, REAL t) { return ((c[3] * t + c[2]) * t + c[1]) * t + c[0]; }

/* The first t in (lo, hi] where the cubic crosses zero in the direction `rising` (1:
 * from negative to positive, leaving the drop; 0: entering), or −1.  The cubic is split
 * at its turning points into monotonic pieces; a crossing in a piece is found by
 * bisection to the last bit, so a ray skimming the surface finds its true crossing or
 * none, never a spurious one. */
ARCUS_INLINE REAL rb_cubic_crossing(const REAL* c, REAL lo, REAL hi, int rising) {
  REAL cuts[4];
  int n = 0;
  cuts[n++] = lo;
  /* turning points: 3c3 t² + 2c2 t + c1 = 0 */
  const REAL qa = RC(3) * c[3], qb = RC(2) * c[2], qc = c[1];
  REAL r0 = hi, r1 = hi;
  if (fabs(qa) > RC(0)) {
    const REAL disc = qb * qb - RC(4) * qa * qc;
    if (disc > 0) {
      const REAL sq = sqrt(disc);
      const REAL q = qb >= 0 ? -RC(0.5) * (qb + sq) : -RC(0.5) * (qb - sq);
      r0 = q / qa;
      r1 = q != 0 ? qc / q : hi;
      if (r0 > r1) {
        const REAL t = r0;
        r0 = r1;
        r1 = t;
      }
    }
  } else if (qb != 0) {
    r0 = -qc / qb;
  }
  if (r0 > lo && r0 < hi) cuts[n++] = r0;
  if (r1 > lo && r1 < hi && r1 > cuts[n - 1]) cuts[n++] = r1;
  cuts[n++] = hi;
  for (int i = 0; i + 1 < n; ++i) {
    REAL a = cuts[i], b = cuts[i + 1];
    const REAL fa = rb_cubic(c, a), fb = rb_cubic(c, b);
    const int ok = rising ? (fa < 0 && fb >= 0) : (fa > 0 && fb <= 0);
    if (!ok) continue;
    for (int it = 0; it < 200; ++it) {
      const REAL mid = RC(0.5) * (a + b);
      if (!(mid > a && mid < b)) break;
      const REAL fm = rb_cubic(c, mid);
      if (rising ? fm < 0 : fm > 0)
        a = mid;
      else
        b = mid;
    }
    return b;
  }
  return -RC(1);
}

/* The nearest surface crossing of o + t·k (world, k unit) beyond t_min, entering
 * (inside = 0) or leaving (inside = 1): t and the outward unit normal, or 0 on a miss.
 * *slot: the mesh's leaf slot hit (−1 for other shapes). */
ARCUS_INLINE int rb_hit(const rainbow_cast_desc* d, const rb_mesh* m, const REAL* o, const REAL* k, int inside,
                        REAL* t_out, REAL* n_out, int* slot) {
  (void)m; /* meshes only */
  *slot = -1;
  if (d->kind == ARCUS_RAINBOW_SHAPE_SPHERE) {
    const REAL r = d->shape[0];
    const REAL b = rb_dot(o, k), c = rb_dot(o, o) - r * r;
    if (!inside) {
      const REAL disc = b * b - c;
      if (!(disc >= 0) || b > 0) return 0;
      const REAL sq = sqrt(disc);
      const REAL t = c / (-b + sq); /* the nearer root, without cancellation */
      *t_out = t;
    } else {
      /* leaving from a point on the sphere: the far root is −2b (c = 0 up to rounding) */
      const REAL disc = fmax(b * b - c, RC(0));
      *t_out = -b + sqrt(disc);
      if (!(*t_out > 0)) return 0;
    }
    for (int a = 0; a < 3; ++a) n_out[a] = (o[a] + *t_out * k[a]) / r;
    rb_normalize(n_out);
    return 1;
  }
#ifdef ARCUS_USE_RAINBOW_IMPLICIT
  if (d->kind == ARCUS_RAINBOW_SHAPE_RAINDROP) {
    const REAL* R = d->rotation;
    /* into the drop's frame: q = Rᵀ x */
    const REAL q[3] = {R[0] * o[0] + R[3] * o[1] + R[6] * o[2], R[1] * o[0] + R[4] * o[1] + R[7] * o[2],
                       R[2] * o[0] + R[5] * o[1] + R[8] * o[2]};
    const REAL w[3] = {R[0] * k[0] + R[3] * k[1] + R[6] * k[2], R[1] * k[0] + R[4] * k[1] + R[7] * k[2],
                       R[2] * k[0] + R[5] * k[1] + R[8] * k[2]};
    /* within the bounding sphere only: the cubic has far roots beyond y = b/k */
    const REAL bound = d->shape[3];
    const REAL bq = rb_dot(q, w), cq = rb_dot(q, q) - bound * bound, disc = bq * bq - cq;
    if (!(disc > 0)) return 0;
    const REAL t_far = -bq + sqrt(disc);
    const REAL t_near = fmax(-bq - sqrt(disc), RC(0));
    REAL c[4];
    rb_raindrop_cubic(d->shape, q, w, c);
    /* leaving: skip the start point itself, where F is 0 up to rounding */
    const REAL lo = inside ? bound * RC(1e-9) : t_near;
    const REAL t = rb_cubic_crossing(c, lo, t_far, inside);
    if (!(t > 0)) return 0;
    const REAL p[3] = {q[0] + t * w[0], q[1] + t * w[1], q[2] + t * w[2]};
    const REAL a2 = d->shape[0] * d->shape[0], b = d->shape[1], kk = d->shape[2];
    const REAL g[3] = {RC(2) * p[0] / a2 * (RC(1) - kk * p[1] / b),
                       -(p[0] * p[0] + p[2] * p[2]) / a2 * kk / b + RC(2) * p[1] / (b * b),
                       RC(2) * p[2] / a2 * (RC(1) - kk * p[1] / b)};
    for (int a = 0; a < 3; ++a) n_out[a] = R[3 * a] * g[0] + R[3 * a + 1] * g[1] + R[3 * a + 2] * g[2];
    rb_normalize(n_out);
    *t_out = t;
    return 1;
  }
#endif
#ifdef ARCUS_USE_RAINBOW_MESH
  if (d->kind == ARCUS_RAINBOW_SHAPE_MESH) {
    /* step off the face the ray starts on; the mesh is in world coordinates already */
    const REAL off = inside ? d->shape[1] : RC(0);
    const REAL start[3] = {o[0] + off * k[0], o[1] + off * k[1], o[2] + off * k[2]};
    REAL t, u, v;
    int tests = 0;
    const int s = bvh_segment_closest(m->nodes, m->tris, start[0], start[1], start[2], k[0], k[1], k[2],
                                      RC(4) * d->shape[0], &t, &u, &v, &tests);
    if (s < 0) return 0;
    ARCUS_GLOBAL const REAL* tri = m->tris + 9 * (size_t)s;
    const REAL e1[3] = {tri[3] - tri[0], tri[4] - tri[1], tri[5] - tri[2]};
    const REAL e2[3] = {tri[6] - tri[0], tri[7] - tri[1], tri[8] - tri[2]};
    rb_cross(e1, e2, n_out);
    rb_normalize(n_out);
    /* outward: against the ray when entering, along it when leaving (any winding) */
    const REAL side = rb_dot(n_out, k);
    if ((inside && side < 0) || (!inside && side > 0))
      for (int a = 0; a < 3; ++a) n_out[a] = -n_out[a];
    if (m->normals) {
      /* a smooth surface: the vertex normals interpolated (Phong), turned to the face's
       * outward side; where the ray would not cross the interpolated surface the way
       * it crosses the face (near a silhouette), the face's normal stays */
      REAL ns[3];
      rb_mesh_normal(m, s, u, v, ns);
      rb_normalize(ns);
      if (rb_dot(ns, n_out) < 0)
        for (int a = 0; a < 3; ++a) ns[a] = -ns[a];
      const REAL cross_s = rb_dot(ns, k);
      if (inside ? cross_s > 0 : cross_s < 0)
        for (int a = 0; a < 3; ++a) n_out[a] = ns[a];
    }
    *t_out = t + off;
    *slot = s;
    return 1;
  }
#endif
  return 0;
}

/* ---- focal lines (thesis §4.4.2.3) ------------------------------------------------
 * The thesis adds a focal line where dθ/db > 0, which holds for the primary bow of a
 * sphere.  For any shape we count them along the ray instead: the ray carries its
 * differentials with respect to its grid coordinates u, v (dP, dk: Igehy 1999, "Tracing
 * ray differentials"), so its neighbours at distance s lie at dP + s·dk; projected on
 * the plane normal to k this 2×2 Jacobian's determinant is a quadratic in s, and each
 * of its zeros along a segment (or beyond the exit, to infinity) is a focal line the
 * ray passes (a double zero, a point focus, is two).  Each adds −π/2 (the Gouy phase). */
typedef struct rb_diff {
  REAL dp[2][3], dk[2][3];
} rb_diff;

/* The zeros of the transverse Jacobian's determinant for s in (0, s_max) (s_max may be
 * +inf). */
ARCUS_INLINE int rb_focal_count(const rb_diff* g, const REAL* k, REAL s_max) {
  REAL e1[3], e2[3];
  rb_any_normal(k, e1);
  rb_cross(k, e1, e2);
  const REAL a1 = rb_dot(g->dp[0], e1), a2 = rb_dot(g->dp[0], e2), b1 = rb_dot(g->dp[1], e1), b2 = rb_dot(g->dp[1], e2);
  const REAL c1 = rb_dot(g->dk[0], e1), c2 = rb_dot(g->dk[0], e2), d1 = rb_dot(g->dk[1], e1), d2 = rb_dot(g->dk[1], e2);
  /* det [[a1 + s c1, b1 + s d1], [a2 + s c2, b2 + s d2]] = qa s² + qb s + qc */
  const REAL qa = c1 * d2 - d1 * c2, qb = a1 * d2 + c1 * b2 - b1 * c2 - d1 * a2, qc = a1 * b2 - b1 * a2;
  REAL roots[2];
  int n = 0;
  if (fabs(qa) > RC(1e-300) * (fabs(qb) + fabs(qc))) {
    const REAL disc = qb * qb - RC(4) * qa * qc;
    if (disc < 0) return 0;
    const REAL sq = sqrt(disc), q = qb >= 0 ? -RC(0.5) * (qb + sq) : -RC(0.5) * (qb - sq);
    roots[n++] = q / qa;
    if (q != 0) roots[n++] = qc / q;
  } else if (qb != 0) {
    roots[n++] = -qc / qb;
  }
  int count = 0;
  for (int i = 0; i < n; ++i) count += roots[i] > 0 && roots[i] < s_max;
  return count;
}

/* The differential of the unit normal along the surface, dN = (I − N Nᵀ) H dP / |∇F|
 * (H the Hessian of the surface's implicit function); on a smooth mesh the derivative
 * of the interpolated normal across the triangle `slot`; a flat face: 0. */
ARCUS_INLINE void rb_normal_differential(const rainbow_cast_desc* d, const rb_mesh* m, int slot, const REAL* pos,
                                         const REAL* nrm, const REAL* dp, REAL* dn) {
  (void)m; /* smooth meshes only */
  (void)slot;
  if (d->kind == ARCUS_RAINBOW_SHAPE_SPHERE) {
    const REAL r = d->shape[0];
    const REAL along = rb_dot(dp, nrm);
    for (int a = 0; a < 3; ++a) dn[a] = (dp[a] - along * nrm[a]) / r;
    return;
  }
#ifdef ARCUS_USE_RAINBOW_IMPLICIT
  if (d->kind == ARCUS_RAINBOW_SHAPE_RAINDROP) {
    const REAL* R = d->rotation;
    const REAL q[3] = {R[0] * pos[0] + R[3] * pos[1] + R[6] * pos[2], R[1] * pos[0] + R[4] * pos[1] + R[7] * pos[2],
                       R[2] * pos[0] + R[5] * pos[1] + R[8] * pos[2]};
    const REAL w[3] = {R[0] * dp[0] + R[3] * dp[1] + R[6] * dp[2], R[1] * dp[0] + R[4] * dp[1] + R[7] * dp[2],
                       R[2] * dp[0] + R[5] * dp[1] + R[8] * dp[2]};
    const REAL a2 = d->shape[0] * d->shape[0], b = d->shape[1], k = d->shape[2];
    const REAL squash = RC(1) - k * q[1] / b;
    const REAL g[3] = {RC(2) * q[0] / a2 * squash, -(q[0] * q[0] + q[2] * q[2]) / a2 * k / b + RC(2) * q[1] / (b * b),
                       RC(2) * q[2] / a2 * squash};
    const REAL hxy = -RC(2) * k * q[0] / (a2 * b), hzy = -RC(2) * k * q[2] / (a2 * b);
    const REAL hw[3] = {RC(2) / a2 * squash * w[0] + hxy * w[1], hxy * w[0] + RC(2) / (b * b) * w[1] + hzy * w[2],
                        hzy * w[1] + RC(2) / a2 * squash * w[2]};
    const REAL hw_world[3] = {R[0] * hw[0] + R[1] * hw[1] + R[2] * hw[2], R[3] * hw[0] + R[4] * hw[1] + R[5] * hw[2],
                              R[6] * hw[0] + R[7] * hw[1] + R[8] * hw[2]};
    const REAL len = sqrt(rb_dot(g, g));
    const REAL along = rb_dot(hw_world, nrm);
    for (int a = 0; a < 3; ++a) dn[a] = (hw_world[a] - along * nrm[a]) / len;
    return;
  }
#endif
  dn[0] = dn[1] = dn[2] = RC(0);
#ifdef ARCUS_USE_RAINBOW_MESH
  if (d->kind == ARCUS_RAINBOW_SHAPE_MESH && m->normals && slot >= 0) {
    ARCUS_GLOBAL const REAL* tri = m->tris + 9 * (size_t)slot;
    REAL u, v, du, dv;
    rb_barycentric(tri, pos, &u, &v);
    REAL n[3];
    rb_mesh_normal(m, slot, u, v, n);
    const REAL len = sqrt(rb_dot(n, n));
    const REAL sign = rb_dot(n, nrm) < 0 ? -RC(1) : RC(1);
    /* the face's own normal was kept (no interpolated crossing): flat there */
    REAL gap = 0;
    for (int a = 0; a < 3; ++a) gap += fabs(sign * n[a] / len - nrm[a]);
    if (gap > RC(1e-9)) return;
    const REAL moved[3] = {tri[0] + dp[0], tri[1] + dp[1], tri[2] + dp[2]};
    rb_barycentric(tri, moved, &du, &dv); /* linear: the weights' change along dP */
    ARCUS_GLOBAL const REAL* nv = m->normals + 9 * (size_t)slot;
    REAL dm[3];
    for (int a = 0; a < 3; ++a) dm[a] = du * (nv[3 + a] - nv[a]) + dv * (nv[6 + a] - nv[a]);
    const REAL along = rb_dot(dm, nrm) * sign;
    for (int a = 0; a < 3; ++a) dn[a] = sign * (dm[a] - along * sign * nrm[a]) / len;
  }
#endif
}

/* Moves the differentials from the ray's start to its hit at distance t on the surface
 * with unit normal nrm (either orientation): dP' = dP + t·dk + dt·k with dt keeping the
 * neighbours on the surface.  Returns the focal lines passed on the way. */
ARCUS_INLINE int rb_diff_propagate(rb_diff* g, const REAL* k, REAL t, const REAL* nrm) {
  const int focal = rb_focal_count(g, k, t);
  const REAL kn = rb_dot(k, nrm);
  for (int i = 0; i < 2; ++i) {
    REAL x[3];
    for (int a = 0; a < 3; ++a) x[a] = g->dp[i][a] + t * g->dk[i][a];
    const REAL dt = -rb_dot(x, nrm) / kn;
    for (int a = 0; a < 3; ++a) g->dp[i][a] = x[a] + dt * k[a];
  }
  return focal;
}

/* The direction differentials after reflection (reflect = 1) or refraction at the
 * interface of rb_interface: k incident, the outward normal nrm, side = +1 when the ray
 * arrives from outside (−1 from inside), eta = n1/n2, cos θ_t. */
ARCUS_INLINE void rb_diff_turn(const rainbow_cast_desc* d, const rb_mesh* mesh, int slot, rb_diff* g, const REAL* pos,
                               const REAL* k, const REAL* nrm, REAL side, REAL eta, REAL cos_t, int reflect) {
  const REAL m[3] = {side * nrm[0], side * nrm[1], side * nrm[2]}; /* toward the incident side */
  const REAL c = -rb_dot(k, m);
  for (int i = 0; i < 2; ++i) {
    REAL dm[3];
    rb_normal_differential(d, mesh, slot, pos, nrm, g->dp[i], dm);
    for (int a = 0; a < 3; ++a) dm[a] *= side;
    const REAL dc = -(rb_dot(g->dk[i], m) + rb_dot(k, dm));
    if (reflect) {
      for (int a = 0; a < 3; ++a) g->dk[i][a] += RC(2) * dc * m[a] + RC(2) * c * dm[a];
    } else {
      const REAL mu = eta * c - cos_t, dmu = eta * dc - eta * eta * c * dc / cos_t;
      for (int a = 0; a < 3; ++a) g->dk[i][a] = eta * g->dk[i][a] + dmu * m[a] + mu * dm[a];
    }
  }
}

/* ---- the walk -------------------------------------------------------------------- */

/* Writes the record of term p leaving at `pos` along `k` with field `f`. */
ARCUS_INLINE void rb_emit(ARCUS_GLOBAL REAL* rec, const REAL* k, const rb_field* f, REAL path, const REAL* pos,
                          REAL sequence, int focal) {
  /* the outgoing (θ, φ) frame; along ±z, φ = 0 */
  const REAL st = sqrt(k[0] * k[0] + k[1] * k[1]);
  const REAL cp = st > RC(1e-300) ? k[0] / st : RC(1), sp = st > RC(1e-300) ? k[1] / st : RC(0);
  const REAL et[3] = {k[2] * cp, k[2] * sp, -st};
  const REAL ep[3] = {-sp, cp, RC(0)};
  for (int a = 0; a < 3; ++a) rec[a] = k[a];
  for (int pol = 0; pol < 2; ++pol) {
    const rb_complex ct = rb_component(f, pol, et), cph = rb_component(f, pol, ep);
    rec[3 + 4 * pol] = ct.re;
    rec[4 + 4 * pol] = ct.im;
    rec[5 + 4 * pol] = cph.re;
    rec[6 + 4 * pol] = cph.im;
  }
  /* to the outgoing reference plane, normal to k through the centre (Fig. 4.14) */
  rec[11] = path - rb_dot(pos, k);
  rec[12] = RC(1);
  rec[13] = sequence;
  rec[14] = (REAL)focal;
}

ARCUS_INLINE void rb_emit_none(ARCUS_GLOBAL REAL* rec) {
  for (int c = 0; c < ARCUS_RAINBOW_RECORD; ++c) rec[c] = RC(0);
}

/* Sequence codes of flat-faced meshes: the faces met, folded into an integer below 2^50
 * that a double holds exactly.  A smooth mesh's triangles are one surface, as a
 * sphere's points are: no code. */
ARCUS_INLINE int rb_face(const rb_mesh* m, int slot) { return slot < 0 || m->normals ? -1 : m->order[slot]; }

ARCUS_INLINE REAL rb_sequence(REAL code, int face) {
  if (face < 0) return code;
  const REAL m = RC(1125899906842597); /* a prime below 2^50 */
  const REAL x = code * RC(1000003) + (REAL)(face + 1);
  return x - floor(x / m) * m;
}

/* Traces the ray entering along +z through (u, v) on the incident plane and writes its
 * P + 1 records, record p at records + p·stride.  Returns the power (both
 * polarisations summed, each starting at 1) still inside after P, or −1 on a miss. */
ARCUS_INLINE REAL rb_trace(const rainbow_cast_desc* d, const rb_mesh* m, REAL u, REAL v, ARCUS_GLOBAL REAL* records,
                           size_t stride) {
  const REAL o[3] = {u, v, -d->plane};
  const REAL k0[3] = {RC(0), RC(0), RC(1)};
  REAL t, nrm[3];
  int slot;
  if (!rb_hit(d, m, o, k0, 0, &t, nrm, &slot)) {
    for (int p = 0; p <= d->bounces; ++p) rb_emit_none(records + (size_t)p * stride);
    return -RC(1);
  }
  REAL pos[3] = {o[0], o[1], o[2] + t};
  /* from the incident reference plane through the centre (z = 0) to the entry point */
  REAL path = pos[2];
  REAL sequence = rb_sequence(RC(0), rb_face(m, slot));
  rb_field f;
  for (int pol = 0; pol < 2; ++pol)
    for (int a = 0; a < 3; ++a) f.e[pol][a] = rb_c(pol == a ? RC(1) : RC(0), RC(0));
  rb_diff g;
  for (int i = 0; i < 2; ++i)
    for (int a = 0; a < 3; ++a) {
      g.dp[i][a] = i == a ? RC(1) : RC(0);
      g.dk[i][a] = RC(0);
    }
  int focal = rb_diff_propagate(&g, k0, t, nrm);
  REAL k[3] = {k0[0], k0[1], k0[2]};
  REAL kr[3], kt[3];
  rb_field fr, ft;
  rb_fresnel fres;
  const int in = rb_interface(k, nrm, RC(1), d->n, &f, kr, &fr, kt, &ft, &fres);
  rb_diff gr = g;
  rb_diff_turn(d, m, slot, &gr, pos, k, nrm, RC(1), RC(1) / d->n, fres.cos_t, 1);
  rb_emit(records, kr, &fr, path, pos, sequence, focal + rb_focal_count(&gr, kr, (REAL)INFINITY));
  if (!in) { /* cannot happen from air, kept for n < 1 */
    for (int p = 1; p <= d->bounces; ++p) rb_emit_none(records + (size_t)p * stride);
    return RC(0);
  }
  rb_diff_turn(d, m, slot, &g, pos, k, nrm, RC(1), RC(1) / d->n, fres.cos_t, 0);
  for (int a = 0; a < 3; ++a) k[a] = kt[a];
  f = ft;
  for (int p = 1; p <= d->bounces; ++p) {
    ARCUS_GLOBAL REAL* rec = records + (size_t)p * stride;
    if (!rb_hit(d, m, pos, k, 1, &t, nrm, &slot)) {
      /* lost inside (a rounding escape at a grazing edge): nothing leaves later */
      for (int q = p; q <= d->bounces; ++q) rb_emit_none(records + (size_t)q * stride);
      return RC(0);
    }
    focal += rb_diff_propagate(&g, k, t, nrm);
    for (int a = 0; a < 3; ++a) pos[a] += t * k[a];
    path += d->n * t;
    sequence = rb_sequence(sequence, rb_face(m, slot));
    const REAL inward[3] = {-nrm[0], -nrm[1], -nrm[2]};
    const int out = rb_interface(k, inward, d->n, RC(1), &f, kr, &fr, kt, &ft, &fres);
    if (out) {
      rb_diff gt = g;
      rb_diff_turn(d, m, slot, &gt, pos, k, nrm, -RC(1), d->n, fres.cos_t, 0);
      rb_emit(rec, kt, &ft, path, pos, sequence, focal + rb_focal_count(&gt, kt, (REAL)INFINITY));
    } else {
      rb_emit_none(rec);
    }
    rb_diff_turn(d, m, slot, &g, pos, k, nrm, -RC(1), d->n, fres.cos_t, 1);
    for (int a = 0; a < 3; ++a) k[a] = kr[a];
    f = fr;
  }
  return rb_power(&f, 0) + rb_power(&f, 1);
}

#endif /* ARCUS_RAINBOW_OPTICS_H */
