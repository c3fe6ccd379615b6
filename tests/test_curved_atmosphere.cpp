// The atmosphere's index of refraction against its definition (thesis §3.1.1): the US
// Standard Atmosphere 1976 with inversion layers, evaluated here independently of the
// library's segments, below sea level, inside and above every layer; and a ray below a
// surface inversion, where host and kernels used to disagree.
#include <algorithm>
#include <cmath>
#include <vector>

#include "test_util.h"

using namespace arcus_test;

namespace {

class AtmosphereProfile : public ArcusTest {};

// The atmosphere's n(h) from its definition, independently of the library's segments:
// US Standard Atmosphere 1976 temperatures (NOAA-S/T 76-1562, table 4; the first lapse
// rate continued below sea level) plus each inversion's offset (delta_t at and below its
// base, fading linearly to 0 at its top), pressure from the hydrostatic equation
// integrated here by composite Simpson in geopotential height (steps of 1/8 m, with the
// kinks on panel boundaries: ~1e-13 relative), n − 1 = Ciddor's refractivity (T/p
// scaled, 550 nm) · p/T.  Heights are geometric; H = r0·h/(r0 + h).
struct ProfileReference {
  std::vector<arcus_inversion> inversions;
  double t0 = 288.15, p0 = 101325.0;
  static constexpr double kR0 = 6356766.0, kGMR = 0.034163194736310366;
  double geopotential(double h) const { return kR0 * h / (kR0 + h); }
  double temperature(double H) const {
    static const double base[] = {0, 11000, 20000, 32000, 47000, 51000, 71000, 84852};
    static const double lapse[] = {-0.0065, 0, 0.001, 0.0028, 0, -0.0028, -0.002, 0};
    double T = t0;
    if (H < 0) T += lapse[0] * H;
    for (int i = 0; i < 8 && H > base[i]; ++i) T += lapse[i] * (std::min(H, i < 7 ? base[i + 1] : H) - base[i]);
    for (const auto& l : inversions) {
      const double b = geopotential(l.base), t = geopotential(l.top);
      T += H <= b ? l.delta_t : H < t ? l.delta_t * (t - H) / (t - b) : 0.0;
    }
    return T;
  }
  double n(double h) const {
    const double H = geopotential(h);
    // ∫ dH'/T from 0 to H by Simpson on panels ending at every break (T is linear
    // between them).
    std::vector<double> cuts{std::min(0.0, H), std::max(0.0, H)};
    auto cut = [&](double b) {
      if (b > cuts[0] && b < cuts[1]) cuts.push_back(b);
    };
    for (double b : {11000.0, 20000.0, 32000.0}) cut(b);
    for (const auto& l : inversions) cut(geopotential(l.base)), cut(geopotential(l.top));
    std::sort(cuts.begin(), cuts.end());
    double integral = 0;
    for (size_t k = 0; k + 1 < cuts.size(); ++k) {
      const double a = cuts[k], c = cuts[k + 1];
      const int m = 2 * std::max(1, int(std::ceil((c - a) * 4)));
      const double dh = (c - a) / m;
      double sum = 1 / temperature(a) + 1 / temperature(c);
      for (int i = 1; i < m; ++i) sum += (i % 2 ? 4 : 2) / temperature(a + i * dh);
      integral += sum * dh / 3;
    }
    if (H < 0) integral = -integral;  // the panels ran from H up to 0
    const double p = p0 * std::exp(-kGMR * integral);
    const double s2 = std::pow(1000.0 / 550.0, 2);
    const double refractivity = 1e-8 * (5792105 / (238.0185 - s2) + 167917 / (57.362 - s2)) * 288.15 / 101325.0;
    return 1 + refractivity * p / temperature(H);
  }
};

// The same n(h) below, inside and above every layer: the field's (the host's segments,
// which the kernels evaluate word for word: field.h) and the definition's.  Before,
// below a surface inversion the kernels extended its steep lapse rate downward while the
// host's profile kept a constant offset: the two disagreed below sea level, and the
// kernels' air reached 0 K at −2975 m.  Bound: 1e-11 on n − 1 ≈ 3e-4, ~3e-8 relative
// (the segments' closed-form pressure against the Simpson sum, both near 1e-13, and the
// library's geometric/geopotential conversion in double).
TEST_F(AtmosphereProfile, TheFieldIsTheProfileBelowInsideAndAboveEveryLayer) {
  const std::vector<std::vector<arcus_inversion>> cases{
      {{0.0, 100.0, -10.0}}, {{0.0, 2.0, 15.0}}, {{100.0, 150.0, -8.0}, {300.0, 330.0, -5.0}}, {}};
  for (const auto& inv : cases) {
    auto field = atmosphere(atmosphere_desc(0, inv));
    ASSERT_TRUE(field);
    ProfileReference ref;
    ref.inversions = inv;
    std::vector<double> heights{-3000, -1500, -1000, -300, -1, 1000, 5000, 11500};
    for (const auto& l : inv)
      for (double h : {l.base - 1.0, l.base + 0.25 * (l.top - l.base), 0.5 * (l.base + l.top), l.top - 0.1, l.top + 1.0})
        heights.push_back(h);
    for (double h : heights) {
      V3 g;
      const double n = n_at(field.get(), {0, h, 0}, &g);
      EXPECT_NEAR(n - 1, ref.n(h) - 1, 1e-11) << inv.size() << " layers, h = " << h << " m";
      // ∇n is the derivative of that n: a central difference over ±1 cm (its error, the
      // third derivative times 1e-4/6, is far below the bound; no point is within 1 cm
      // of a kink).
      const double dn = (ref.n(h + 0.01) - ref.n(h - 0.01)) / 0.02;
      EXPECT_NEAR(g[1], dn, 1e-6 * std::fabs(dn) + 1e-12) << inv.size() << " layers, h = " << h << " m";
    }
  }
}

// A ray below a surface inversion in a spherical atmosphere: it used to take 10^7 steps
// (41 s) as the kernels' air cooled toward 0 K below sea level.  Now the air there is
// ordinary, and the ray, horizontal at −2500 m, conserves Bouguer's n·r·sin z to the
// tolerance.
TEST_F(AtmosphereProfile, ARayBelowASurfaceInversionTravelsAsInOrdinaryAir) {
  const std::vector<arcus_inversion> inv{{0.0, 100.0, -10.0}};
  auto f = atmosphere(atmosphere_desc(1, inv));
  ASSERT_TRUE(f);
  const double r0 = ARCUS_EARTH_RADIUS - 2500;
  Rays rays;
  rays.add({0, r0, 0}, {1, 0, 0});
  arcus_advance_params p = dp45(20000, 1e-10, 1e-9);
  p.max_steps = 100000;
  const Trace t = trace(ctx(), f.get(), p, rays);
  ASSERT_EQ(t.status, ARCUS_SUCCESS) << last_error();
  EXPECT_EQ(t.ray_status[0], ARCUS_RAY_DONE);
  EXPECT_LT(t.steps[0], 1000u) << "steps taken";
  const V3 pos = t.pos(0), dir = t.dir(0);
  const double start = n_at(f.get(), {0, r0, 0}) * r0;  // sin z = 1 at the start
  const double end = n_at(f.get(), pos) * norm(cross(pos, dir)) / norm(dir);
  EXPECT_NEAR(end, start, 1e-8 * start);
}

}  // namespace
