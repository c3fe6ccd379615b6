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
  static arcus_atmosphere_desc atmosphere_desc(int spherical, const std::vector<arcus_inversion>& inv) {
    arcus_atmosphere_desc d;
    EXPECT_EQ(arcus_atmosphere_desc_init(&d), ARCUS_SUCCESS);
    d.spherical = spherical;
    d.inversion_count = static_cast<uint32_t>(inv.size());
    d.inversions = inv.empty() ? nullptr : inv.data();
    return d;
  }
  static bool all_finite(const Trace& t) {
    for (size_t i = 0; i < t.size(); ++i)
      if (!finite(t.pos(i)) || !finite(t.dir(i)) || !std::isfinite(t.lengths[i])) return false;
    return true;
  }
  // Horizontal part of v at the end of ray i in a flat atmosphere: n(r_end)·|d_xz|.
  static double snell_invariant(arcus_field_t* f, const V3& pos, const V3& dir) {
    return n_at(f, pos) * std::hypot(dir[0], dir[2]);
  }
};

// Bound on the drift of a conserved component of v: each accepted step may err by
// √6·(atol + rtol·|v|) in v (|v| = n ≈ 1 in air), and the invariant is read back through
// n(r_end), whose error is |∇n|·δr ≤ 1e-5·δr here (|∇n| < 1e-5 m⁻¹ in these layers).
double invariant_bound(uint64_t steps, double rtol, double atol, double dr) {
  return 2.0 * std::sqrt(6.0) * double(steps) * (atol + rtol * 1.001) + 1e-5 * dr;
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
    EXPECT_EQ(t.ray_status[i], ARCUS_RAY_DONE);
    EXPECT_GT(t.pos(i)[1], o[1]) << "ray " << i << " must turn up";
    EXPECT_GT(t.dir(i)[1], 0.0) << "ray " << i;
    EXPECT_NEAR(t.pos(i)[1] - o[1], rise, 0.01 * rise) << "ray " << i;
    std::printf("ray %zu: rise %.5f m (%+.3f%% from the local catenary)\n", i, t.pos(i)[1] - o[1],
                100 * ((t.pos(i)[1] - o[1]) / rise - 1));
    // Snell: n·cos e is conserved; it started as n0 (horizontal).
    EXPECT_NEAR(snell_invariant(field.get(), t.pos(i), t.dir(i)), n0, invariant_bound(t.steps[i], rtol, atol, 1e-6))
        << "ray " << i;
  }
  // The layer is horizontally uniform: every azimuth rises alike (to the integration error).
  for (size_t i = 1; i < rays.size(); ++i)
    EXPECT_NEAR(t.pos(i)[1], t.pos(0)[1], dp45_bound(t.steps[i] + t.steps[0], rtol, atol, L, 1.001, 1.0, L));
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
  ASSERT_EQ(arcus_job_get_path_size(t.job.get(), &total), ARCUS_SUCCESS);
  ASSERT_GT(total, 2u);
  std::vector<uint64_t> offsets(2);
  std::vector<double> points(3 * total);
  ASSERT_EQ(arcus_job_get_paths(t.job.get(), offsets.data(), points.data(), nullptr), ARCUS_SUCCESS);
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
  const double integration = dp45_bound(t.steps[0], 1e-10, 1e-13, 400.0, 1.001, 1.0, 400.0);
  EXPECT_GE(y_min, bottom - integration);
  EXPECT_LT(y_min, bottom + 1e-4 + integration);
  // Climbed back: above the start and rising.
  EXPECT_GT(t.pos(0)[1], o[1]);
  EXPECT_GT(t.dir(0)[1], 0.0);
  EXPECT_NEAR(snell_invariant(field.get(), t.pos(0), t.dir(0)), n0 * std::cos(theta),
              invariant_bound(t.steps[0], 1e-10, 1e-13, 1e-6));
}

TEST_F(HardCases, InversionLayersCrossedByDP45MatchATightRun) {
  // Two inversions (a Fata-Morgana-like profile): ∇n jumps at 100, 150, 300 and 330 m.
  // Rays cross them at grazing and steeper angles, one from above.
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
    // Both runs err by at most their dp45_bound (|r| ≤ L + 400, n ∈ [1, 1.001]); the
    // tight one is 1000× smaller, so the loose bound (doubled) covers the difference.
    const double bound = 2.0 * dp45_bound(loose.steps[i], rtol, atol, L + 400.0, 1.001, 1.0, L);
    const double diff = distance(loose.pos(i), tight.pos(i));
    const double effect = distance(none.pos(i), tight.pos(i));
    std::printf("ray %zu: %llu/%llu steps, |loose - tight| = %.3e m (bound %.3e), inversion moves it %.3f m\n", i,
                (unsigned long long)loose.steps[i], (unsigned long long)tight.steps[i], diff, bound, effect);
    EXPECT_LT(diff, bound) << "ray " << i;
    // The test is meaningful: ignoring the layers would be caught 100 times over.
    EXPECT_GT(effect, 100.0 * bound) << "ray " << i;
    // Snell's invariant across the jumps.
    const V3 d0 = normalize(rays.direction(i));
    const double want = n_at(field.get(), rays.origin(i)) * std::hypot(d0[0], d0[2]);
    EXPECT_NEAR(snell_invariant(field.get(), loose.pos(i), loose.dir(i)), want,
                invariant_bound(loose.steps[i], rtol, atol, bound))
        << "ray " << i;
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
  for (size_t i = 0; i < rays.size(); ++i) {
    EXPECT_EQ(t8.ray_status[i], ARCUS_RAY_DONE) << "ray " << i;
    EXPECT_EQ(t11.ray_status[i], ARCUS_RAY_DONE) << "ray " << i;
    EXPECT_NEAR(t11.lengths[i], L, 1e-9 * L);
    // Far out the ray is straight, so the relative end-point difference is the angle
    // between the two runs' escape directions plus their relative position errors; each
    // accepted step adds at most √6·rtol to either (|v| ≈ 1, relative position tolerance
    // rtol), so |Δr|/|r| ≤ 2·√6·(N8·1e-8 + N11·1e-11).
    const double rel = distance(t8.pos(i), t11.pos(i)) / norm(t11.pos(i));
    const double bound = 2.0 * std::sqrt(6.0) * (double(t8.steps[i]) * 1e-8 + double(t11.steps[i]) * 1e-11);
    const V3 d0 = normalize(rays.direction(i));
    const double bend = angle_between(d0, t11.dir(i));
    const double bend_std = angle_between(d0, std11.dir(i));
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
    // Bouguer's invariant n·|r × d| (the field is central), with n = 1 out there.
    const double want = n_obs * norm(cross(o, d0));
    const double got = n_at(field.get(), t11.pos(i)) * norm(cross(t11.pos(i), t11.dir(i)));
    // Per step: |r|·δv with |r| ≈ R_E inside the atmosphere (√6·rtol each) and
    // round-off of |r| ≈ 1.5e11 m at the end (16 ε relative, i.e. 2.4e-5 m·|d|).
    EXPECT_NEAR(got / want, 1.0, 2.0 * std::sqrt(6.0) * double(near11.steps[i]) * 1e-11 + 16 * 2.2e-16 * L / want)
        << "ray " << i;
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
      const V3 d = rays.direction(i);
      const RayState want = catenary_end(n0, G, {0, 0, 0}, d, L);
      const double A = n0 * std::hypot(normalize(d)[0], normalize(d)[2]);
      const double n_max = n0 + std::fabs(g) * (std::fabs(want.pos[1]) + 1e-3);
      EXPECT_EQ(t.ray_status[i], ARCUS_RAY_DONE) << "g " << g << " ray " << i;
      EXPECT_LT(distance(t.pos(i), want.pos), dp45_bound(t.steps[i], rtol, atol, L, n_max, A, L))
          << "g " << g << " ray " << i << " steps " << t.steps[i];
    }
    // Fixed-step methods stay finite with a step well inside the 1.4 mm turn.
    for (arcus_method m : {ARCUS_METHOD_EULER, ARCUS_METHOD_RK2, ARCUS_METHOD_RK4}) {
      const Trace f = trace(ctx(), field.get(), fixed(m, 1e-4, L), rays);
      ASSERT_EQ(f.status, ARCUS_SUCCESS);
      EXPECT_TRUE(all_finite(f)) << "method " << m;
      for (size_t i = 0; i < rays.size(); ++i) EXPECT_EQ(f.ray_status[i], ARCUS_RAY_DONE);
    }
  }
}

}  // namespace
