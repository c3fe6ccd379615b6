// The rainbow engine's ray optics (kernels/rainbow/optics.h, compiled here on the host
// exactly as the kernels compile it): Fresnel amplitudes against their closed forms and
// conservation, total internal reflection's phases against eq. 2.17's relative phase,
// the sphere's exit directions and optical paths against geometric closed forms, the
// raindrop's surface, and the focal lines counted along rays against the thesis' rule
// for the primary bow (§4.4.2.3).
#include <gtest/gtest.h>

#include <cmath>
#include <complex>
#include <vector>

#define ARCUS_USE_RAINBOW_IMPLICIT
#include "common/real.h"
#include "bvh/bvh_desc.h"
typedef arcus_bvh_node_d bvh_node;
#include "bvh/traverse.h"
#include "rainbow/optics.h"
#include "rainbow/airy.h"
#include "rainbow/particle.h"

namespace {

constexpr double kPi = 3.14159265358979323846;

double norm2(rb_complex c) { return c.re * c.re + c.im * c.im; }

rainbow_cast_desc sphere_desc(double radius, double n, int bounces) {
  rainbow_cast_desc d{};
  for (int i = 0; i < 9; ++i) d.rotation[i] = i % 4 == 0;
  d.kind = ARCUS_RAINBOW_SHAPE_SPHERE;
  d.shape[0] = radius;
  d.n = n;
  d.plane = 2 * radius;
  d.bounces = bounces;
  return d;
}

// The records of one ray, record p at [p·R, (p+1)·R).
struct Traced {
  std::vector<double> rec;
  double left;
  const double* at(int p) const { return &rec[size_t(p) * ARCUS_RAINBOW_RECORD]; }
};

Traced trace(const rainbow_cast_desc& d, double u, double v) {
  Traced t;
  t.rec.assign(size_t(d.bounces + 1) * ARCUS_RAINBOW_RECORD, 0.0);
  const rb_mesh none{};
  t.left = rb_trace(&d, &none, u, v, t.rec.data(), ARCUS_RAINBOW_RECORD);
  return t;
}

double power(const double* rec) {
  double s = 0;
  for (int c = 3; c < 11; ++c) s += rec[c] * rec[c];
  return s;
}

// Energy: |r|² + |t|² = 1 at every angle both ways (t carries the power factor), to
// rounding (1e-12: a handful of operations on numbers of order 1).
TEST(RainbowOptics, FresnelConservesEnergyBothWays) {
  for (const double n2 : {1.333, 1.5, 2.4})
    for (const bool inside : {false, true})
      for (int i = 0; i <= 1000; ++i) {
        const double cos_i = 1e-6 + (1 - 1e-6) * i / 1000.0;
        const double a = inside ? n2 : 1, b = inside ? 1 : n2;
        const rb_fresnel f = rb_fresnel_coefficients(cos_i, a, b);
        if (f.total) {
          EXPECT_NEAR(norm2(f.rs), 1, 1e-12);
          EXPECT_NEAR(norm2(f.rp), 1, 1e-12);
        } else {
          EXPECT_NEAR(norm2(f.rs) + norm2(f.ts), 1, 1e-12) << cos_i;
          EXPECT_NEAR(norm2(f.rp) + norm2(f.tp), 1, 1e-12) << cos_i;
        }
      }
}

// Normal incidence: r = (n1 − n2)/(n1 + n2) for the field, which in the s, p = s × k
// bases is r_s = r and r_p = −r (the reflected p axis is reversed).
TEST(RainbowOptics, NormalIncidenceReflection) {
  const rb_fresnel f = rb_fresnel_coefficients(1, 1, 1.5);
  EXPECT_NEAR(f.rs.re, -0.2, 1e-15);
  EXPECT_NEAR(f.rp.re, 0.2, 1e-15);
  EXPECT_NEAR(norm2(f.ts), 0.96, 1e-15);
}

// Brewster's angle tan θ_B = n2/n1: r_p vanishes there (to rounding of the angle).
TEST(RainbowOptics, BrewsterAngleHasNoParallelReflection) {
  const double n = 1.333, cos_b = std::cos(std::atan(n));
  EXPECT_NEAR(rb_fresnel_coefficients(cos_b, 1, n).rp.re, 0, 1e-15);
  EXPECT_NEAR(rb_fresnel_coefficients(std::cos(std::atan(1 / n)), n, 1).rp.re, 0, 1e-15);
}

// Total internal reflection: the relative phase δ = δ_s − δ_p obeys
// tan(δ/2) = cos θ sqrt(sin²θ − n²) / sin²θ, n = n2/n1 (Born & Wolf §1.5.4; thesis
// eq. 2.17), an independent closed form of the same physics; 1e-12 rad.
TEST(RainbowOptics, TotalInternalReflectionPhases) {
  const double n1 = 1.333, n = 1 / n1;
  for (double deg = 49; deg < 89.9; deg += 0.5) {
    const double th = deg * kPi / 180;
    const rb_fresnel f = rb_fresnel_coefficients(std::cos(th), n1, 1);
    ASSERT_TRUE(f.total) << deg;
    const double ds = std::atan2(f.rs.im, f.rs.re), dp = std::atan2(f.rp.im, f.rp.re);
    double delta = std::remainder(ds - dp, 2 * kPi);
    const double expect = 2 * std::atan(std::cos(th) * std::sqrt(std::sin(th) * std::sin(th) - n * n) /
                                        (std::sin(th) * std::sin(th)));
    // the sign of δ depends on the basis convention; its size does not
    EXPECT_NEAR(std::fabs(delta), expect, 1e-12) << deg;
  }
}

// At any interface the outgoing fields are transverse and carry the incident power
// (1e-12).
TEST(RainbowOptics, InterfaceFieldsAreTransverseAndConserved) {
  const double k[3] = {0.3, -0.4, std::sqrt(1 - 0.25)};
  for (double tilt = 0; tilt < 1.5; tilt += 0.1) {
    double m[3] = {std::sin(tilt) * 0.6, std::sin(tilt) * 0.8, -std::cos(tilt)};
    rb_normalize(m);
    if (rb_dot(k, m) >= 0) continue;
    rb_field in;
    for (int pol = 0; pol < 2; ++pol) {
      // two independent complex transverse fields
      double e1[3], e2[3];
      rb_any_normal(k, e1);
      rb_cross(k, e1, e2);
      for (int a = 0; a < 3; ++a) in.e[pol][a] = rb_c(pol ? e1[a] : 0.6 * e1[a], pol ? 0.3 * e2[a] : 0.8 * e2[a]);
    }
    for (const double n2 : {1.333, 0.75}) {
      double kr[3], kt[3];
      rb_field er, et;
      rb_fresnel f;
      const int through = rb_interface(k, m, 1, n2, &in, kr, &er, kt, &et, &f);
      for (int pol = 0; pol < 2; ++pol) {
        double out = rb_power(&er, pol) + (through ? rb_power(&et, pol) : 0);
        EXPECT_NEAR(out, rb_power(&in, pol), 1e-12) << tilt << " " << n2;
        for (int a = 0; a < 2; ++a) {
          const rb_field& e = a ? et : er;
          const double* dir = a ? kt : kr;
          if (a && !through) continue;
          EXPECT_NEAR(rb_component(&e, pol, dir).re, 0, 1e-12);
          EXPECT_NEAR(rb_component(&e, pol, dir).im, 0, 1e-12);
        }
      }
    }
  }
}

// A sphere in geometric closed form (van de Hulst 1957 §12.2): a ray at impact
// parameter b = r sin i, refracted at τ (sin i = n sin τ), leaves term p deviated by
// D = 2(i − τ) + (p − 1)(π − 2τ) toward the axis (p ≥ 1; p = 0: π − 2i away from it),
// and its optical path between
// the reference planes through the centre is −2r cos i + 2 p n r cos τ.  Directions to
// 1e-12, paths to 1e-12 of r; each ray's power over p plus what is left inside sums to
// the incident 2 (two polarisations) to 1e-12.
TEST(RainbowOptics, SphereMatchesGeometricClosedForms) {
  const double r = 1e-3, n = 1.3317;
  const rainbow_cast_desc d = sphere_desc(r, n, 6);
  for (const double b : {0.0, 0.1, 0.5, 0.86, 0.95, 0.999}) {
    const Traced t = trace(d, 0, b * r);
    const double i = std::asin(b), tau = std::asin(b / n);
    double total = t.left;
    for (int p = 0; p <= 6; ++p) {
      const double* rec = t.at(p);
      ASSERT_EQ(rec[12], 1) << b << " " << p;
      total += power(rec);
      const double D = p == 0 ? -(kPi - 2 * i) : 2 * (i - tau) + (p - 1) * (kPi - 2 * tau);
      // the ray enters at +y moving along +z and turns toward −y by D
      EXPECT_NEAR(rec[2], std::cos(D), 1e-12) << b << " " << p;
      EXPECT_NEAR(rec[1], -std::sin(D), 1e-12) << b << " " << p;
      EXPECT_NEAR(rec[11], -2 * r * std::cos(i) + 2 * p * n * r * std::cos(tau), 1e-12 * r) << b << " " << p;
    }
    EXPECT_NEAR(total, 2, 1e-12) << b;
  }
}

// The raindrop traced as a sphere (a = b = r, k = 0) gives the sphere's records, and a
// deformed drop's hits lie on eq. 4.21's surface with the gradient as normal.
TEST(RainbowOptics, RaindropSurface) {
  const double r = 1e-3, n = 1.3317;
  rainbow_cast_desc s = sphere_desc(r, n, 3), d = s;
  d.kind = ARCUS_RAINBOW_SHAPE_RAINDROP;
  d.shape[0] = d.shape[1] = r;
  d.shape[2] = 0;
  d.shape[3] = 1.01 * r;
  for (const double b : {0.0, 0.3, 0.86, 0.99}) {
    const Traced ts = trace(s, 0.2 * b * r, b * r * 0.9), td = trace(d, 0.2 * b * r, b * r * 0.9);
    for (size_t c = 0; c < ts.rec.size(); ++c) EXPECT_NEAR(td.rec[c], ts.rec[c], 1e-9) << b << " " << c;
  }
  const arcus::rainbow::Particle drop = arcus::rainbow::raindrop(4e-3);
  d.shape[0] = drop.a;
  d.shape[1] = drop.b;
  d.shape[2] = drop.k;
  d.shape[3] = drop.bound;
  for (double u = -0.75; u <= 0.76; u += 0.25) {  // inside the silhouette
    const double o[3] = {u * drop.a, 0.3 * u * drop.b, -3 * drop.bound}, k[3] = {0, 0, 1};
    double t, nrm[3];
    int slot;
    const rb_mesh none{};
    ASSERT_TRUE(rb_hit(&d, &none, o, k, 0, &t, nrm, &slot));
    const double q[3] = {o[0], o[1], o[2] + t};
    EXPECT_NEAR(rb_raindrop_f(d.shape, q), 0, 1e-12);
    // the normal: the gradient, normalised (by finite differences, 1e-6 relative)
    const double h = 1e-9;
    double g[3];
    for (int a = 0; a < 3; ++a) {
      double qp[3] = {q[0], q[1], q[2]}, qm[3] = {q[0], q[1], q[2]};
      qp[a] += h;
      qm[a] -= h;
      g[a] = (rb_raindrop_f(d.shape, qp) - rb_raindrop_f(d.shape, qm)) / (2 * h);
    }
    rb_normalize(g);
    for (int a = 0; a < 3; ++a) EXPECT_NEAR(nrm[a], g[a], 1e-6);
  }
}

// Table 4.4's shapes hold the volume of their nominal equivalent sphere: the thesis
// fitted a, b, k to Beard & Chuang's drops of that volume, so the equivalent diameter
// must come back within the table's three printed digits' reach (3 %).
TEST(RainbowOptics, RaindropVolumesMatchTheirEquivalentSpheres) {
  for (int mm = 1; mm <= 6; ++mm) {
    const arcus::rainbow::Particle p = arcus::rainbow::raindrop(mm * 1e-3);
    EXPECT_NEAR(2 * arcus::rainbow::equivalent_radius(p) / (mm * 1e-3), 1, 0.03) << mm << " mm";
  }
}

// Focal lines (§4.4.2.3): the two rays of a primary-bow angle differ by one, and the
// thesis adds it to the ray whose scattering angle grows with b (b beyond the rainbow
// ray's b_r, where dθ/db > 0).  A paraxial ray through the sphere (p = 1) crosses the
// axis at a point focus: two.  Reflection outside (p = 0) passes none.
TEST(RainbowOptics, FocalLinesAlongSphereRays) {
  const double r = 1e-3, n = 1.3317;
  const rainbow_cast_desc d = sphere_desc(r, n, 3);
  const double b_r = std::sqrt((4 - n * n) / 3);  // cos² i = (n² − 1)/3
  const Traced inner = trace(d, 0, (b_r - 0.1) * r), outer = trace(d, 0, (b_r + 0.08) * r);
  EXPECT_EQ(outer.at(2)[14], inner.at(2)[14] + 1);
  const Traced paraxial = trace(d, 0.01 * r, 0.02 * r);
  EXPECT_EQ(paraxial.at(1)[14], 2);
  EXPECT_EQ(paraxial.at(0)[14], 0);
  // rotating the ray about the axis changes nothing
  const Traced turned = trace(d, (b_r - 0.1) * r * std::sqrt(0.5), (b_r - 0.1) * r * std::sqrt(0.5));
  for (int p = 0; p <= 3; ++p) EXPECT_EQ(turned.at(p)[14], inner.at(p)[14]) << p;
}

// The Airy function on the negative axis (rainbow/airy.h, the uniform approximation's
// at caustics) against published values (DLMF §9.9, Table 9.9.1): Ai(0), Ai'(0), and
// the zeros a_k of Ai and a'_k of Ai' on both sides of the series/asymptotic switch at
// z = 8, where Ai's amplitude is about 0.2-0.5; 1e-9 of that in the series, 1e-7 in the
// asymptotic expansion (its first term left out).
TEST(RainbowOptics, AiryFunctionOnTheNegativeAxis) {
  double ai, aip;
  rb_airy_negative(0, &ai, &aip);
  EXPECT_NEAR(ai, 0.355028053887817239, 1e-15);
  EXPECT_NEAR(aip, -0.258819403792806798, 1e-15);
  for (const double a : {2.3381074104597674, 4.08794944413097, 5.520559828095515, 7.944133587112781}) {
    rb_airy_negative(a, &ai, &aip);
    EXPECT_NEAR(ai, 0, 1e-10) << a;
  }
  for (const double a : {9.022650853340979, 12.828776752865757, 14.527829951775335}) {
    rb_airy_negative(a, &ai, &aip);
    EXPECT_NEAR(ai, 0, 1e-7) << a;
  }
  for (const double a : {1.0187929716474715, 3.2481975821798375, 7.372177255049634, 8.488486734019721,
                         12.384788371845747}) {
    rb_airy_negative(a, &ai, &aip);
    EXPECT_NEAR(aip, 0, a < 8 ? 1e-10 : 1e-7) << a;
  }
}

}  // namespace
