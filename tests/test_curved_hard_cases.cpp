// Numerically hard cases (thesis §5.4.1): rays at the turning point of an inferior mirage,
// rays crossing inversion layers (discontinuous ∇n), the Novaya-Zemlya geometry (a sun
// 1.5e11 m away) and very steep linear gradients.  Flat atmospheres conserve the
// horizontal part of v = n·dr/ds exactly (∇n is vertical: Snell's law n·cos e = const);
// spherical ones conserve r × v (Bouguer: n·r·sin z = const).  Both give exact checks.
#include "test_util.h"

using namespace arcus_test;

namespace {

class HardCases : public ArcusTest {
 protected:
  static bool all_finite(const Trace& t) {
    for (size_t i = 0; i < t.size(); ++i)
      if (!finite(t.pos(i)) || !finite(t.dir(i)) || !std::isfinite(t.lengths[i])) return false;
    return true;
  }
  // Horizontal part of v at the end of ray i in a flat atmosphere: n(r_end)·|d_xz|.
  static double snell_invariant(arcus_field_t* f, const V3& pos, const V3& dir) {
    return n_at(f, pos) * std::hypot(dir[0], dir[2]);
  }

  // Reference end state of a ray through a flat atmosphere that climbs or sinks
  // monotonically to arc L (it may start horizontal, at its turning point), by
  // quadrature.  Snell: A = n·cos e is constant, so along the path ds = n·|dy|/sqrt(n² −
  // A²) and the horizontal distance is A·|dy|/sqrt(n² − A²).  With y = y0 ± u² (dy =
  // 2u du) the integrands stay finite at a turning point, and n − A is formed without
  // cancellation: n(y0) − A = n0·d_y²/(|d|(|d| + |d_h|)) plus ∫ n'(y) dy (the field's
  // gradient).  Composite 8-point Gauss–Legendre on panels of ≤ 0.02 in u (< 3% change of
  // n − A across one for these rays) that end at every kink of n(y) (`kinks`: the
  // layers' bases and tops), so each is smooth: ~1e-15 relative.  The end is where s = L
  // (Newton, ds/du known).
  static RayState flat_atmosphere_end(arcus_field_t* f, const V3& o, const V3& d, double L,
                                      const std::vector<double>& kinks) {
    static const double gx[4] = {0.1834346424956498, 0.5255324099163290, 0.7966664774136267, 0.9602898564975363};
    static const double gw[4] = {0.3626837833783620, 0.3137066458778873, 0.2223810344533745, 0.1012285362903763};
    // Gauss–Legendre over [a, b] of a function of one variable.
    auto gauss = [&](double a, double b, auto&& fn) {
      const double mid = 0.5 * (a + b), half = 0.5 * (b - a);
      double sum = 0.0;
      for (int j = 0; j < 4; ++j) sum += gw[j] * (fn(mid - half * gx[j]) + fn(mid + half * gx[j]));
      return half * sum;
    };
    const double len = norm(d), hlen = std::hypot(d[0], d[2]);
    V3 g0;
    const double n0 = n_at(f, o, &g0);
    const double sgn = d[1] != 0.0 ? (d[1] > 0.0 ? 1.0 : -1.0) : (g0[1] > 0.0 ? 1.0 : -1.0);
    const double A = n0 * hlen / len;
    const double gap0 = n0 * d[1] * d[1] / (len * (len + hlen));
    const V3 hor = normalize(V3{d[0], 0.0, d[2]});
    auto y_of = [&](double u) { return o[1] + sgn * u * u; };
    auto dn_dy = [&](double y) {
      V3 g;
      n_at(f, {0.0, y, 0.0}, &g);
      return g[1];
    };
    // ds/du and dx/du at u, in a panel starting at ua where n − A = gap_a.
    auto rates = [&](double ua, double gap_a, double u, double* dx) {
      const double gap = gap_a + gauss(y_of(ua), y_of(u), dn_dy);
      const double root = std::sqrt(gap * (gap + 2.0 * A));
      *dx = 2.0 * u * A / root;
      return 2.0 * u * (A + gap) / root;
    };
    auto arc = [&](double ua, double gap_a, double ub, double* dx) {
      const double mid = 0.5 * (ua + ub), half = 0.5 * (ub - ua);
      double ds = 0.0, x = 0.0;
      *dx = 0.0;
      for (int j = 0; j < 4; ++j)
        for (double side : {-1.0, 1.0}) {
          ds += gw[j] * rates(ua, gap_a, mid + side * half * gx[j], &x);
          *dx += gw[j] * x;
        }
      *dx *= half;
      return ds * half;
    };
    std::vector<double> kink_u;
    for (double k : kinks)
      if ((k - o[1]) * sgn > 0.0) kink_u.push_back(std::sqrt(std::fabs(k - o[1])));
    double u = 0.0, s = 0.0, x = 0.0, gap = gap0;
    for (;;) {
      double next = u + 0.02;
      for (double k : kink_u)
        if (k > u && k < next) next = k;
      double dx = 0.0;
      const double ds = arc(u, gap, next, &dx);
      if (s + ds < L) {
        s += ds;
        x += dx;
        gap += gauss(y_of(u), y_of(next), dn_dy);
        u = next;
        continue;
      }
      double end = u + (next - u) * (L - s) / ds;
      for (int it = 0; it < 50; ++it) {
        double unused = 0.0;
        const double step = (s + arc(u, gap, end, &dx) - L) / rates(u, gap, end, &unused);
        end -= step;
        if (std::fabs(step) < 1e-16 * (1.0 + end)) break;
      }
      arc(u, gap, end, &dx);
      const double gap_end = gap + gauss(y_of(u), y_of(end), dn_dy);
      const V3 pos = V3{o[0], y_of(end), o[2]} + (x + dx) * hor;
      const V3 dir = normalize(A * hor + sgn * std::sqrt(gap_end * (gap_end + 2.0 * A)) * V3{0.0, 1.0, 0.0});
      return {pos, dir};
    }
  }
};

// Air: n ∈ [1, 1.001].  Drift of a conserved part of v read back as n(r_end) times the
// unit end direction: v's own error (dp45_v_bound) twice (the part, and |v| against n)
// plus n(r_end)'s, |∇n|·δr with |∇n| < 1e-5 m⁻¹ in these layers.
double invariant_bound(double rtol, double atol, const PathScale& p) {
  return 2.0 * dp45_v_bound(rtol, atol, p, 1.001) + 1e-5 * dp45_bound(rtol, atol, p);
}

// ∫κ^p ds along the catenary n = n0 + g·y with A = n·cos e: with n = A cosh u,
// κ = g·A/n² and ds = (A/g) cosh u du, so ∫κ^p ds = (g/A)^(p−1) ∫ cosh^(1−2p) u du over
// [u0, u1] (Simpson, 2000 intervals: the integrand is smooth on the scale 1).  For p = 1
// it is the total turning.
double catenary_curvature_integral(double g, double A, double u0, double u1, int p) {
  const int n = 2000;
  const double du = (u1 - u0) / n;
  double sum = 0.0;
  for (int k = 0; k <= n; ++k) {
    const double w = (k == 0 || k == n) ? 1.0 : (k % 2 ? 4.0 : 2.0);
    sum += w * std::pow(std::cosh(u0 + k * du), 1.0 - 2.0 * p);
  }
  return std::pow(g / A, p - 1) * sum * du / 3.0;
}

TEST_F(HardCases, SnellQuadratureReproducesTheCatenary) {
  // The reference of the atmosphere tests checked where it has a closed form: n = n0 + g·y
  // depends on y alone, so flat_atmosphere_end must give catenary_end; from a turning
  // point (the mirage's case) and through 20 km of a weak gradient (the layers' case).
  struct Case {
    double n0, g;
    V3 o, d;
    double L;
  };
  const std::vector<Case> cases{{1.0003, 7e-6, {0, 1, 0}, {1, 0, 0}, 200.0},
                                {1.0003, 7e-6, {0, 1.5, 0}, {0.2, 1e-3, 1}, 400.0},
                                {1.0003, -2.6e-8, {0, 50, 0}, {std::cos(rad(0.2)), std::sin(rad(0.2)), 0}, 20000.0},
                                {1.0003, -2.6e-8, {0, 400, 0}, {std::cos(rad(-1.5)), std::sin(rad(-1.5)), 0.1}, 20000.0}};
  for (const Case& k : cases) {
    auto field = linear(k.n0, {0, k.g, 0});
    ASSERT_TRUE(field);
    const RayState want = catenary_end(k.n0, {0, k.g, 0}, k.o, k.d, k.L);
    // Splitting the panels at fake kinks must not matter either.
    const RayState got = flat_atmosphere_end(field.get(), k.o, k.d, k.L, {k.o[1] + 0.3, k.o[1] - 7.0});
    // The closed form is the less precise of the two here: its height (A cosh u − n0)/g
    // loses ε·n0 to cancellation before the division by g, ≈ 4ε·n0/|g|.
    const double bound = 4.0 * std::numeric_limits<double>::epsilon() * k.n0 / std::fabs(k.g) + 1e-15 * k.L;
    std::printf("quadrature - catenary over %.0f m: %.3e m (bound %.3e), %.3e rad\n", k.L, distance(got.pos, want.pos),
                bound, angle_between(got.dir, want.dir));
    EXPECT_LT(distance(got.pos, want.pos), bound);
    EXPECT_LT(angle_between(got.dir, want.dir), 1e-12);
  }
}

TEST_F(HardCases, MirageRayHorizontalAtStartTurnsUp) {
  // Hot ground: +15 K at the ground fading to 0 at 2 m, so dT/dy = −7.5 K/m and n grows
  // with height in the layer: a horizontal ray at 1 m is at its turning point and climbs.
  const std::vector<arcus_inversion> inv{{0.0, 2.0, 15.0}};
  auto field = atmosphere(atmosphere_desc(0, inv));
  ASSERT_TRUE(field);
  const V3 o{0.0, 1.0, 0.0};
  V3 grad;
  const double n0 = n_at(field.get(), o, &grad);
  ASSERT_GT(grad[1], 0.0) << "a hot ground layer must make n increase with height";
  Rays rays;
  for (const V3& d : std::vector<V3>{{1, 0, 0}, {-1, 0, 0}, {0, 0, 1}, {0.6, 0, -0.8}}) rays.add(o, d);
  const double L = 200.0, rtol = 1e-10, atol = 1e-13;
  const Trace t = trace(ctx(), field.get(), dp45(L, rtol, atol), rays);
  ASSERT_EQ(t.status, ARCUS_SUCCESS);
  ASSERT_TRUE(all_finite(t));
  // Locally n ≈ n0 + g·(y − 1): a catenary with the local gradient.  Over the rise
  // (≈ g L²/2 ≈ 0.14 m) the gradient itself changes by n''·Δy with n'' ≈ 2(n−1)(dT/dy)²/T²
  // ≈ 3.4e-7 m⁻² (n − 1 ∝ p/T), i.e. by < 0.7% of g ≈ 7e-6 m⁻¹ at the far end, less on
  // average: the rise agrees with the local catenary within 1%.
  const RayState local = catenary_end(n0 - grad[1] * o[1], {0, grad[1], 0}, o, {1, 0, 0}, L);
  const double rise = local.pos[1] - o[1];
  std::printf("local gradient %.4e /m, closed-form rise over %.0f m: %.5f m\n", grad[1], L, rise);
  for (size_t i = 0; i < rays.size(); ++i) {
    // The exact path by quadrature (Snell; no kink below the layer's top at 2 m).
    const RayState want = flat_atmosphere_end(field.get(), o, rays.direction(i), L, {2.0});
    PathScale scale{norm(want.pos), L};
    scale.turning = angle_between(normalize(rays.direction(i)), want.dir);
    const double bound = dp45_bound(rtol, atol, scale);
    EXPECT_EQ(t.ray_status[i], ARCUS_RAY_DONE);
    EXPECT_GT(t.pos(i)[1], o[1]) << "ray " << i << " must turn up";
    EXPECT_GT(t.dir(i)[1], 0.0) << "ray " << i;
    EXPECT_NEAR(t.pos(i)[1] - o[1], rise, 0.01 * rise) << "ray " << i;
    std::printf("ray %zu: rise %.5f m (%+.3f%% from the local catenary), %.3e m from the quadrature (bound %.3e)\n",
                i, t.pos(i)[1] - o[1], 100 * ((t.pos(i)[1] - o[1]) / rise - 1), distance(t.pos(i), want.pos), bound);
    EXPECT_LT(distance(t.pos(i), want.pos), bound) << "ray " << i;
    EXPECT_LT(angle_between(t.dir(i), want.dir), dp45_direction_bound(rtol, atol, scale, 1.0 / grad[1])) << "ray " << i;
    // Snell: n·cos e is conserved; it started as n0 (horizontal).
    EXPECT_NEAR(snell_invariant(field.get(), t.pos(i), t.dir(i)), n0, invariant_bound(rtol, atol, scale))
        << "ray " << i;
  }
}

TEST_F(HardCases, MirageRayDescendingTurnsAtTheBottomAndClimbsBack) {
  // A ray 1 mrad below horizontal from 1.5 m: it bottoms out Δy ≈ θ²/(2κ) ≈ 7 cm lower
  // (κ = g/n), about 146 m on, and climbs back.
  const std::vector<arcus_inversion> inv{{0.0, 2.0, 15.0}};
  auto field = atmosphere(atmosphere_desc(0, inv));
  ASSERT_TRUE(field);
  const V3 o{0.0, 1.5, 0.0};
  const double theta = 1e-3;
  const double n0 = n_at(field.get(), o);
  arcus_advance_params p = dp45(400.0, 1e-10, 1e-13);
  p.record_path = 1;
  // Path vertices are points of the path; the lowest vertex lies above the true bottom by
  // at most κ·(h/2)²/2 = κh²/8 (κ = g/n ≈ 7e-6 m⁻¹).  Steps ≤ 10 m make that ≤ 1e-4 m.
  p.max_step = 10.0;
  Rays rays;
  rays.add(o, {std::cos(theta), -std::sin(theta), 0});
  const Trace t = trace(ctx(), field.get(), p, rays);
  ASSERT_EQ(t.status, ARCUS_SUCCESS);
  ASSERT_TRUE(all_finite(t));
  EXPECT_EQ(t.ray_status[0], ARCUS_RAY_DONE);
  size_t total = 0;
  ASSERT_EQ(arcus_job_get_curved_path_size(t.job.get(), &total), ARCUS_SUCCESS);
  ASSERT_GT(total, 2u);
  std::vector<uint64_t> offsets(2);
  std::vector<double> points(3 * total);
  ASSERT_EQ(arcus_job_get_curved_paths(t.job.get(), offsets.data(), points.data(), nullptr), ARCUS_SUCCESS);
  double y_min = 1e9;
  for (size_t k = offsets[0]; k < offsets[1]; ++k) y_min = std::min(y_min, points[3 * k + 1]);
  // Snell (exact in a flat atmosphere): at the bottom the ray is horizontal, so
  // n(y_bottom) = n0·cos θ.  Solve it by bisection on the host evaluation of n (n grows
  // with y in the layer).
  double lo = o[1] - 0.5, hi = o[1];
  const double target = n0 * std::cos(theta);
  ASSERT_LT(n_at(field.get(), {0, lo, 0}), target);
  for (int it = 0; it < 60; ++it) {
    const double mid = 0.5 * (lo + hi);
    (n_at(field.get(), {0, mid, 0}) < target ? lo : hi) = mid;
  }
  const double bottom = 0.5 * (lo + hi);
  std::printf("Snell bottom %.6f m, lowest path vertex %.6f m\n", bottom, y_min);
  // Below the bottom only by the integration error; above it by at most the sampling gap.
  // |r_end| ≤ |o| + L; n varies by < 5e-5 in the layer, so |e| < 0.01 rad on the path.
  PathScale scale{norm(o) + 400.0, 400.0};
  scale.turning = 0.02;
  const double integration = dp45_bound(1e-10, 1e-13, scale);
  EXPECT_GE(y_min, bottom - integration);
  EXPECT_LT(y_min, bottom + 1e-4 + integration);
  // Climbed back: above the start and rising.
  EXPECT_GT(t.pos(0)[1], o[1]);
  EXPECT_GT(t.dir(0)[1], 0.0);
  EXPECT_NEAR(snell_invariant(field.get(), t.pos(0), t.dir(0)), n0 * std::cos(theta),
              invariant_bound(1e-10, 1e-13, scale));
}

TEST_F(HardCases, InversionLayersCrossedByDP45MatchTheSnellQuadrature) {
  // Two inversions (a Fata-Morgana-like profile): ∇n jumps at 100, 150, 300 and 330 m.
  // Rays cross them at grazing and steeper angles, one from above; none turns within L,
  // so flat_atmosphere_end gives the exact end state.  Each of the loose and the tight
  // run lies within its own bound of it, counting the kinks it crosses.
  const std::vector<double> kinks{100.0, 150.0, 300.0, 330.0};
  const std::vector<arcus_inversion> inv{{100.0, 150.0, -8.0}, {300.0, 330.0, -5.0}};
  auto field = atmosphere(atmosphere_desc(0, inv));
  auto plain = atmosphere(atmosphere_desc(0, {}));
  ASSERT_TRUE(field && plain);
  Rays rays;
  for (double e : {0.2, 0.5, 1.0, 3.0}) rays.add({0, 50, 0}, {std::cos(rad(e)), std::sin(rad(e)), 0});
  rays.add({0, 400, 0}, {std::cos(rad(-1.5)), std::sin(rad(-1.5)), 0.1});
  const double L = 20000.0;
  const double rtol = 1e-9, atol = 1e-12;
  const Trace loose = trace(ctx(), field.get(), dp45(L, rtol, atol), rays);
  const Trace tight = trace(ctx(), field.get(), dp45(L, 1e-12, 1e-15), rays);
  const Trace none = trace(ctx(), plain.get(), dp45(L, rtol, atol), rays);
  ASSERT_EQ(loose.status, ARCUS_SUCCESS);
  ASSERT_EQ(tight.status, ARCUS_SUCCESS);
  ASSERT_EQ(none.status, ARCUS_SUCCESS);
  ASSERT_TRUE(all_finite(loose) && all_finite(tight));
  for (size_t i = 0; i < rays.size(); ++i) {
    EXPECT_EQ(loose.ray_status[i], ARCUS_RAY_DONE) << "ray " << i;
    EXPECT_EQ(tight.ray_status[i], ARCUS_RAY_DONE) << "ray " << i;
    const RayState want = flat_atmosphere_end(field.get(), rays.origin(i), rays.direction(i), L, kinks);
    PathScale scale{norm(want.pos), L};
    scale.turning = angle_between(normalize(rays.direction(i)), want.dir);
    const double y0 = rays.origin(i)[1], y1 = want.pos[1];
    for (double k : kinks) scale.kinks += (k - y0) * (k - y1) < 0 ? 1 : 0;
    ASSERT_GE(scale.kinks, 1) << "test design: ray " << i << " must cross a layer boundary";
    const double bound = dp45_bound(rtol, atol, scale), tight_bound = dp45_bound(1e-12, 1e-15, scale);
    const double err = distance(loose.pos(i), want.pos), tight_err = distance(tight.pos(i), want.pos);
    const double effect = distance(none.pos(i), want.pos);
    std::printf("ray %zu (%.0f kinks): error %.3e m (bound %.3e), at 1e-12 %.3e m (bound %.3e); the inversions move "
                "it %.3f m\n",
                i, scale.kinks, err, bound, tight_err, tight_bound, effect);
    EXPECT_LT(err, bound) << "ray " << i;
    EXPECT_LT(tight_err, tight_bound) << "ray " << i;
    EXPECT_LT(angle_between(loose.dir(i), want.dir), dp45_direction_bound(rtol, atol, scale, 1e4)) << "ray " << i;
    // The test is meaningful: ignoring the layers would be caught 10 times over.
    EXPECT_GT(effect, 10.0 * bound) << "ray " << i;
    // Snell's invariant across the jumps.
    const V3 d0 = normalize(rays.direction(i));
    const double invariant = n_at(field.get(), rays.origin(i)) * std::hypot(d0[0], d0[2]);
    EXPECT_NEAR(snell_invariant(field.get(), loose.pos(i), loose.dir(i)), invariant,
                invariant_bound(rtol, atol, scale))
        << "ray " << i;
  }
}

TEST_F(HardCases, LooseToleranceStepsDoNotJumpOverAThinLayer) {
  // At rtol 1e-6 one adaptive step of a ray sinking at 1.5° spanned the 300–330 m layer
  // with no stage inside it, so neither the step nor its error estimate saw the layer:
  // the end was 3 m off, the whole of the layer's effect.  DP45's steps now span at most
  // half the thinnest layer in height (field_step_cap), down to a layer of 3 m.  The
  // kink bound of dp45_bound is too wide to tell (169× v's tolerance per kink): the
  // check is that the error is a small part of what the thin layer does to the ray.
  for (double thickness : {30.0, 3.0}) {
    const std::vector<double> kinks{100.0, 150.0, 300.0, 300.0 + thickness};
    const std::vector<arcus_inversion> inv{{100.0, 150.0, -8.0}, {300.0, 300.0 + thickness, -5.0}};
    auto field = atmosphere(atmosphere_desc(0, inv));
    auto without = atmosphere(atmosphere_desc(0, {inv[0]}));
    ASSERT_TRUE(field && without);
    Rays rays;
    rays.add({0, 400, 0}, {std::cos(rad(-1.5)), std::sin(rad(-1.5)), 0.1});
    rays.add({0, 400, 0}, {std::cos(rad(-0.8)), std::sin(rad(-0.8)), 0.0});
    const double L = 20000.0;
    // (At 1e-5 a kink inside a step still costs up to 17 % of the layer's effect: the
    // tolerance asked for is 0.2 m over this path, and a kink multiplies it.)
    for (double rtol : {1e-6, 1e-7}) {
      const Trace t = trace(ctx(), field.get(), dp45(L, rtol, rtol * 1e-3), rays);
      ASSERT_EQ(t.status, ARCUS_SUCCESS);
      for (size_t i = 0; i < rays.size(); ++i) {
        const RayState want = flat_atmosphere_end(field.get(), rays.origin(i), rays.direction(i), L, kinks);
        const RayState unlayered =
            flat_atmosphere_end(without.get(), rays.origin(i), rays.direction(i), L, {100.0, 150.0});
        const double err = distance(t.pos(i), want.pos), effect = distance(unlayered.pos, want.pos);
        std::printf("layer %.0f m, rtol %.0e, ray %zu: %llu steps, error %.3e m; the layer moves the end %.3f m\n",
                    thickness, rtol, i, (unsigned long long)t.steps[i], err, effect);
        ASSERT_GT(effect, 0.3) << "test design: the thin layer must matter";
        EXPECT_LT(err, 0.05 * effect) << "layer " << thickness << " rtol " << rtol << " ray " << i;
      }
    }
  }
}

TEST_F(HardCases, AtmosphereInFloatPrecisionFollowsTheQuadratureAndTheDoubleRun) {
  // Flat atmospheres in float (ARCUS_PRECISION_FLOAT).  n − 1 ≈ 3e-4 is resolved to
  // ε_f/3e-4 ≈ 2e-4 of itself in float, and so is ∇n, which moves the mirage's rise
  // (g·L²/2 ≈ 0.14 m) by ≈ 3e-5 m: inside the rounding bound.
  // (1) The hot-ground mirage (no kink on these paths), DP45 at rtol 1e-6 (above float's
  // resolution, so the controller can meet it), against the quadrature: dp45_bound at
  // that tolerance plus float_rounding_bound; the mirage lifts the ray by ≥ 10 times that.
  const std::vector<arcus_inversion> hot{{0.0, 2.0, 15.0}};
  auto mirage = atmosphere(atmosphere_desc(0, hot));
  ASSERT_TRUE(mirage);
  const double rtol = 1e-6, atol = 1e-8, L = 200.0;
  for (const V3& d : std::vector<V3>{{1, 0, 0}, {0.6, 0, -0.8}, {1, 2e-3, 0}}) {
    const V3 o{3.0, 1.0, -2.0};
    Rays rays;
    rays.add(o, d);
    arcus_advance_params p = dp45(L, rtol, atol);
    p.precision = ARCUS_PRECISION_FLOAT;
    const Trace t = trace(ctx(), mirage.get(), p, rays);
    ASSERT_EQ(t.status, ARCUS_SUCCESS) << last_error();
    ASSERT_TRUE(t.features & ARCUS_FEATURE_FLOAT);
    EXPECT_EQ(t.ray_status[0], ARCUS_RAY_DONE);
    const RayState want = flat_atmosphere_end(mirage.get(), o, d, L, {2.0});
    ASSERT_LT(want.pos[1], 2.0) << "test design: stay in the layer";
    PathScale scale{norm(want.pos), L};
    scale.turning = angle_between(normalize(d), want.dir);
    const double bound = dp45_bound(rtol, atol, scale) + float_rounding_bound(scale);
    const double lift = distance(want.pos, o + L * normalize(d));
    std::printf("float mirage: error %.3e m (bound %.3e), lift %.3e m\n", distance(t.pos(0), want.pos), bound, lift);
    EXPECT_LT(distance(t.pos(0), want.pos), bound);
    EXPECT_GT(lift, 10.0 * bound) << "test design";
  }
  // (2) The inversion layers, 20 km: float and double with the same fixed RK4 steps have
  // the same truncation, so they differ by float's rounding alone (the steps are the
  // params', not the run's).  The layers move the rays by ≥ 100 times that.
  const std::vector<arcus_inversion> layers{{100.0, 150.0, -8.0}, {300.0, 330.0, -5.0}};
  auto inversions = atmosphere(atmosphere_desc(0, layers));
  auto plain = atmosphere(atmosphere_desc(0, {}));
  ASSERT_TRUE(inversions && plain);
  Rays rays;
  rays.add({0, 50, 0}, {std::cos(rad(0.5)), std::sin(rad(0.5)), 0});
  rays.add({0, 400, 0}, {std::cos(rad(-1.5)), std::sin(rad(-1.5)), 0.1});
  const double far = 20000.0;
  arcus_advance_params p = fixed(ARCUS_METHOD_RK4, 10.0, far);
  const Trace d = trace(ctx(), inversions.get(), p, rays);
  const Trace none = trace(ctx(), plain.get(), p, rays);
  p.precision = ARCUS_PRECISION_FLOAT;
  const Trace f = trace(ctx(), inversions.get(), p, rays);
  ASSERT_EQ(d.status, ARCUS_SUCCESS);
  ASSERT_EQ(f.status, ARCUS_SUCCESS) << last_error();
  for (size_t i = 0; i < rays.size(); ++i) {
    PathScale scale{norm(rays.origin(i)) + far, far};  // |r_end| ≤ |o| + L
    scale.turning = 0.03;                              // < 1.5° + the bending
    const double rounding = float_rounding_bound(scale);
    std::printf("float inversions ray %zu: float - double %.3e m (bound %.3e); the layers move it %.3f m\n", i,
                distance(f.pos(i), d.pos(i)), rounding, distance(none.pos(i), d.pos(i)));
    EXPECT_EQ(f.ray_status[i], ARCUS_RAY_DONE);
    EXPECT_LT(distance(f.pos(i), d.pos(i)), rounding) << "ray " << i;
    EXPECT_GT(distance(none.pos(i), d.pos(i)), 100.0 * rounding) << "test design: ray " << i;
    EXPECT_GT(distance(f.pos(i), d.pos(i)), 0.0) << "float ran in double?";
  }
}

TEST_F(HardCases, NovayaZemlyaSunRaysAreStableOverAstronomicalDistance) {
  // Spherical atmosphere, cold layer at the ground (−10 K fading out at 100 m: n falls
  // with height at 0.8× the Earth's curvature), observer 10 m up, nearly horizontal rays
  // traced 1.5e11 m out to the sun (thesis §5.4.1, Fig. 5.14b).
  const std::vector<arcus_inversion> inv{{0.0, 100.0, -10.0}};
  auto field = atmosphere(atmosphere_desc(1, inv));
  auto standard = atmosphere(atmosphere_desc(1, {}));
  ASSERT_TRUE(field && standard);
  const double h = 10.0, L = 1.5e11;
  const V3 o{0.0, ARCUS_EARTH_RADIUS + h, 0.0};
  const std::vector<double> elevations{0.0, 0.05, 0.1, 0.2, 0.5};
  Rays rays;
  for (double e : elevations) rays.add(o, {std::cos(rad(e)), std::sin(rad(e)), 0});
  const Trace t8 = trace(ctx(), field.get(), dp45(L, 1e-8, 1e-11), rays);
  const Trace t11 = trace(ctx(), field.get(), dp45(L, 1e-11, 1e-14), rays);
  // The same rays stopped 2000 km out, far above the atmosphere (> 300 km high).
  const Trace near11 = trace(ctx(), field.get(), dp45(2.0e6, 1e-11, 1e-14), rays);
  const Trace std11 = trace(ctx(), standard.get(), dp45(L, 1e-11, 1e-14), rays);
  ASSERT_EQ(t8.status, ARCUS_SUCCESS);
  ASSERT_EQ(t11.status, ARCUS_SUCCESS);
  ASSERT_EQ(near11.status, ARCUS_SUCCESS);
  ASSERT_EQ(std11.status, ARCUS_SUCCESS);
  ASSERT_TRUE(all_finite(t8) && all_finite(t11) && all_finite(std11));
  const double n_obs = n_at(field.get(), o);
  // The part of the path in air (≤ 2000 km, |r| ≤ R_E + 2000 km): it turns by the bending
  // (< 0.03 rad) and crosses 8 kinks of ∇n (the layer's top, 7 breaks of the 1976 lapse
  // rates up to 84.852 km).  A position error δr shifts the ray across the layers, and so
  // its bending, by δr·|∂∇n/∂r|·(arc in dense air) ≈ δr·(n − 1)/H²·1e5 m (H ≈ 8 km): ℓ =
  // 2e6 m for dp45_direction_bound.
  PathScale air{ARCUS_EARTH_RADIUS + 2.0e6, 2.0e6};
  air.turning = 0.03;
  air.kinks = 8;
  const double ell = 2.0e6;
  for (size_t i = 0; i < rays.size(); ++i) {
    EXPECT_EQ(t8.ray_status[i], ARCUS_RAY_DONE) << "ray " << i;
    EXPECT_EQ(t11.ray_status[i], ARCUS_RAY_DONE) << "ray " << i;
    EXPECT_NEAR(t11.lengths[i], L, 1e-9 * L);
    // Far out the ray is straight (any Runge–Kutta step is exact where ∇n = 0), so the
    // relative end-point difference is the angle between the two runs' escape
    // directions, each within its direction bound.
    const double rel = distance(t8.pos(i), t11.pos(i)) / norm(t11.pos(i));
    const double bound = dp45_direction_bound(1e-8, 1e-11, air, ell) + dp45_direction_bound(1e-11, 1e-14, air, ell);
    const V3 d0 = normalize(rays.direction(i));
    const double bend = angle_between(d0, t11.dir(i));
    const double bend_std = angle_between(d0, std11.dir(i));
    ASSERT_LT(bend, air.turning) << "test design";
    std::printf("e = %.2f deg: steps %llu (tol 1e-8) %llu (tol 1e-11), %llu to 2000 km; relative end difference "
                "%.3e (bound %.3e); bending %.4f deg (standard atmosphere %.4f deg)\n",
                elevations[i], (unsigned long long)t8.steps[i], (unsigned long long)t11.steps[i],
                (unsigned long long)near11.steps[i], rel, bound, deg(bend), deg(bend_std));
    EXPECT_LT(rel, bound) << "ray " << i;
    // DP45 in (near) vacuum grows the step geometrically (by its maximum factor ≥ 2 per
    // accepted step when the error estimate vanishes), so going on from 2e6 m to 1.5e11 m
    // takes at most log2(1.5e11/2e6) ≈ 17 more steps, plus the few needed to leave the
    // thinnest air; 100 catches a step cap or a stalled controller.
    EXPECT_LE(t11.steps[i], near11.steps[i] + 100) << "ray " << i;
    // Bouguer's invariant n·|r × d| = |r × v| (the field is central), with n = 1 out
    // there.  It drifts by |r|·δv + n·δr: relative to |r × v| ≈ R_E, δv + δr/R_E; and
    // rounding of |r| ≈ 1.5e11 m at the end (16 ε relative, i.e. 2.4e-5 m·|d|).
    const double want = n_obs * norm(cross(o, d0));
    const double got = n_at(field.get(), t11.pos(i)) * norm(cross(t11.pos(i), t11.dir(i)));
    const double drift = dp45_v_bound(1e-11, 1e-14, air, 1.001) + dp45_bound(1e-11, 1e-14, air) / ARCUS_EARTH_RADIUS;
    std::printf("  Bouguer: n|r x d| off by %.3e relative (bound %.3e)\n", std::fabs(got / want - 1.0),
                drift + 16 * 2.2e-16 * L / want);
    EXPECT_NEAR(got / want, 1.0, drift + 16 * 2.2e-16 * L / want) << "ray " << i;
    // The cold layer bends the sun's rays more than the standard atmosphere does
    // (that is the Novaya-Zemlya effect: the sun is seen when geometrically below the horizon).
    if (i == 0) {
      EXPECT_GT(bend, bend_std);
    }
  }
}

TEST_F(HardCases, SteepLinearGradientHundredPerMetre) {
  // n = 1 + 100·y: the downward ray turns within 1.4 mm, the upward one climbs to n ≈ 90.
  const double n0 = 1.0, L = 1.0, rtol = 1e-10, atol = 1e-14;
  for (double g : {100.0, -100.0}) {
    const V3 G{0.0, g, 0.0};
    auto field = linear(n0, G);
    ASSERT_TRUE(field);
    Rays rays;
    for (double e : {-30.0, -5.0, 0.0, 5.0, 30.0}) {
      // Rays must not head towards n ≤ 0: along −G they turn at n = n0 cos e > 0.
      rays.add({0, 0, 0}, {std::cos(rad(e)), std::sin(rad(e)), 0.2});
    }
    const Trace t = trace(ctx(), field.get(), dp45(L, rtol, atol), rays);
    ASSERT_EQ(t.status, ARCUS_SUCCESS);
    ASSERT_TRUE(all_finite(t));
    for (size_t i = 0; i < rays.size(); ++i) {
      const V3 d = normalize(rays.direction(i));
      const RayState want = catenary_end(n0, G, {0, 0, 0}, d, L);
      PathScale scale{norm(want.pos), L};
      scale.turning = angle_between(d, want.dir);
      scale.n_min = n0 * std::hypot(d[0], d[2]);  // A: the least n on the catenary
      const double bound = dp45_bound(rtol, atol, scale);
      EXPECT_EQ(t.ray_status[i], ARCUS_RAY_DONE) << "g " << g << " ray " << i;
      EXPECT_LT(distance(t.pos(i), want.pos), bound) << "g " << g << " ray " << i;
      std::printf("g %+.0f ray %zu DP45: error %.3e m (bound %.3e)\n", g, i, distance(t.pos(i), want.pos), bound);
    }
    // Fixed steps of 1e-4 m, well inside the 1.4 mm turn, against the catenary.  An
    // order-p method errs by ≈ c·h^(p+1)·|r^(p+1)| a step, and along a catenary the
    // position's derivatives go as the curvature's powers, |r^(p+1)| ≲ κ^p (κ = g·A/n²
    // varies on the catenary's own scale 1/κ); v = n·dr/ds is exact for every method
    // (dv/ds = G is constant).  Errors shrink along the path (a height error δy changes
    // the speed |v|/n by g·δy/n, which feeds back as −g·v_y/n²·δy: δy falls as 1/n on
    // the way up and grows by at most n_start/A = 1/cos(e) ≤ 1.2 before the turn).  So
    // the error is ≲ 1.2·c·h^p·∫κ^p ds; c ≤ 1/2 (Euler: r''·h²/2, exactly; measured
    // 0.50, ≤ 0.12, ≤ 0.009 of h^p·∫κ^p ds for Euler, RK2, RK4).  Bound: h^p·∫κ^p ds,
    // plus rounding for RK4 (10⁴ steps through |r| ≤ 2: 10⁴·4ε·2).
    const double h = 1e-4;
    for (arcus_method m : {ARCUS_METHOD_EULER, ARCUS_METHOD_RK2, ARCUS_METHOD_RK4}) {
      const int p = m == ARCUS_METHOD_EULER ? 1 : m == ARCUS_METHOD_RK2 ? 2 : 4;
      const Trace f = trace(ctx(), field.get(), fixed(m, h, L), rays);
      ASSERT_EQ(f.status, ARCUS_SUCCESS);
      for (size_t i = 0; i < rays.size(); ++i) {
        const V3 d = normalize(rays.direction(i));
        const RayState want = catenary_end(n0, G, {0, 0, 0}, d, L);
        const double A = n0 * std::hypot(d[0], d[2]);
        const double vy = n0 * d[1] * (g > 0 ? 1.0 : -1.0);  // v along G/|G| at the start
        const double u0 = std::asinh(vy / A), u1 = std::asinh((vy + std::fabs(g) * L) / A);
        const double bound = std::pow(h, p) * catenary_curvature_integral(std::fabs(g), A, u0, u1, p) +
                             (L / h) * 4.0 * std::numeric_limits<double>::epsilon() * 2.0;
        const double err = distance(f.pos(i), want.pos);
        std::printf("g %+.0f ray %zu method %d (order %d): error %.3e m (bound %.3e)\n", g, i, m, p, err, bound);
        EXPECT_EQ(f.ray_status[i], ARCUS_RAY_DONE) << "method " << m << " ray " << i;
        EXPECT_LT(err, bound) << "method " << m << " ray " << i;
        // v is exact: so is the end direction, but for rounding (10⁴ steps of ≲ ε each).
        EXPECT_LT(angle_between(f.dir(i), want.dir), 1e-12) << "method " << m << " ray " << i;
      }
    }
  }
}

// A caller's first DP45 step obeys max_step and the Luneburg cap like every later
// step: a first step of 20 would otherwise jump over the unit lens unrefracted.
TEST_F(HardCases, CallersFirstDp45StepIsCappedAndCannotJumpOverALens) {
  FieldPtr lens = luneburg({0, 0, 0}, 1.0);
  ASSERT_TRUE(lens);
  Rays rays;
  rays.add({-10, 0.5, 0}, {1, 0, 0});
  arcus_advance_params p = dp45(20.0, 1e-10, 1e-12);
  p.step = 20.0;
  Trace t = trace(ctx(), lens.get(), p, rays);
  ASSERT_EQ(t.status, ARCUS_SUCCESS) << last_error();
  // A ray at impact parameter b = R/2 passes the focus F = (R, 0, 0) and leaves along
  // (sqrt(1 − b²), −b, 0) (test_curved_closed_forms.cpp): it ends on that line.  A straight pass
  // would keep (1, 0, 0) and end 0.5 m off it.  Bounds: dp45_bound over ≤ 20 m, turning π
  // inside the lens (scale R = 1) and two kinks at its surface; the line's distance from
  // the end errs by no more than the end point.
  const V3 exit_dir{std::sqrt(0.75), -0.5, 0.0};
  PathScale scale{10.02 + 20.0, 20.0};  // |r_end| ≤ |origin| + L
  scale.turning = kPi;
  scale.kinks = 2;
  const V3 off = (t.pos(0) - V3{1, 0, 0});
  const double from_line = norm(off - dot(off, exit_dir) * exit_dir);
  std::printf("%.3e m off the exit line (bound %.3e), direction off by %.3e rad (bound %.3e)\n", from_line,
              dp45_bound(1e-10, 1e-12, scale), angle_between(t.dir(0), exit_dir),
              dp45_direction_bound(1e-10, 1e-12, scale, 1.0));
  EXPECT_LT(from_line, dp45_bound(1e-10, 1e-12, scale));
  EXPECT_LT(angle_between(t.dir(0), exit_dir), dp45_direction_bound(1e-10, 1e-12, scale, 1.0));
  EXPECT_GT(dot(off, exit_dir), 0.0) << "the ray must be past the focus";
}

// Tiny but non-zero directions are valid (normalised without underflow); origins whose
// sum would overflow are still finite and valid; the host and kernel agree on both.
TEST_F(HardCases, ExtremeButFiniteRaysAreAdvancedAndReportedConsistently) {
  FieldPtr medium = constant(1.5);
  ASSERT_TRUE(medium);
  Rays rays;
  rays.add({0, 0, 0}, {1e-200, 0, 0});
  rays.add({1e308, 1e308, 0}, {0, 0, 1});
  Trace t = trace(ctx(), medium.get(), dp45(2.0, 1e-9, 1e-12), rays);
  ASSERT_EQ(t.status, ARCUS_SUCCESS) << last_error();
  EXPECT_EQ(t.ray_status[0], ARCUS_RAY_DONE);
  EXPECT_DOUBLE_EQ(t.pos(0)[0], 2.0);
  EXPECT_EQ(t.ray_status[1], ARCUS_RAY_DONE);
  EXPECT_DOUBLE_EQ(t.pos(1)[2], 2.0);
}

}  // namespace
