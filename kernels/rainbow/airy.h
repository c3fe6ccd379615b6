/* The Airy function and its derivative on the negative axis, Ai(−z) and Ai'(−z) for
 * z ≥ 0: what the uniform approximation at a fold caustic needs (query.cl).  Scalar code
 * the host includes too (tests).  Prepend common/real.h.
 *
 * z ≤ 8: the Maclaurin series Ai(x) = c1 f(x) − c2 g(x) (DLMF 9.4.1), whose largest term
 * there is about e^{15}, so cancellation costs at most ~1e-9 of Ai's size;
 * z > 8: the asymptotic expansions DLMF 9.7.9-9.7.10 with ξ = (2/3) z^{3/2} ≥ 15 and
 * terms up to ξ⁻⁴ (the first one left out is below 1e-7 relative). */
#ifndef ARCUS_RAINBOW_AIRY_H
#define ARCUS_RAINBOW_AIRY_H

ARCUS_INLINE void rb_airy_negative(REAL z, REAL* ai, REAL* aip) {
  if (z <= RC(8)) {
    const REAL x = -z, x3 = x * x * x;
    const REAL c1 = RC(0.355028053887817239), c2 = RC(0.258819403792806798);
    REAL t = RC(1), s = x, d = x * x / RC(2), e = RC(1); /* f, g, f', g' terms */
    REAL f = t, g = s, fp = d, gp = e;
    for (int k = 0; k < 80; ++k) {
      const REAL k3 = RC(3) * (REAL)k;
      t *= x3 / ((k3 + RC(2)) * (k3 + RC(3)));
      s *= x3 / ((k3 + RC(3)) * (k3 + RC(4)));
      d *= x3 / ((k3 + RC(3)) * (k3 + RC(5)));
      e *= x3 / ((k3 + RC(1)) * (k3 + RC(3)));
      f += t;
      g += s;
      fp += d;
      gp += e;
      if (fabs(t) + fabs(s) + fabs(d) + fabs(e) < RC(1e-18) * (fabs(f) + fabs(g) + fabs(fp) + fabs(gp))) break;
    }
    *ai = c1 * f - c2 * g;
    *aip = c1 * fp - c2 * gp;
    return;
  }
  /* DLMF 9.7.9-9.7.10: u_k, v_k of DLMF 9.7.2 */
  const REAL u1 = RC(0.0694444444444444444), u2 = RC(0.0371334876543209877), u3 = RC(0.0379930591278006401),
             u4 = RC(0.0576491904126697530);
  const REAL v1 = RC(-0.0972222222222222222), v2 = RC(-0.0438850308641975309), v3 = RC(-0.0424628307898948400),
             v4 = RC(-0.0626621634920322900);
  const REAL xi = RC(2) / RC(3) * z * sqrt(z), q = RC(1) / xi;
  const REAL c = cos(xi - RC(0.785398163397448310)), s = sin(xi - RC(0.785398163397448310));
  const REAL root_pi = RC(1.77245385090551603), z4 = sqrt(sqrt(z));
  *ai = (c * (RC(1) - u2 * q * q + u4 * q * q * q * q) + s * (u1 * q - u3 * q * q * q)) / (root_pi * z4);
  *aip = z4 / root_pi * (s * (RC(1) - v2 * q * q + v4 * q * q * q * q) - c * (v1 * q - v3 * q * q * q));
}

#endif /* ARCUS_RAINBOW_AIRY_H */
