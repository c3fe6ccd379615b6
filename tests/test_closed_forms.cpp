// Ray paths with closed forms: catenaries (linear n), parabolas (linear n²), the
// Luneburg lens focus, Maxwell's fish-eye circles and straight lines in a constant field.
// Every DP45 comparison uses dp45_bound() (test_util.h): the sum over the accepted steps
// of the per-step tolerance the controller enforces, propagated to the end point.
#include "test_util.h"

using namespace arcus_test;

namespace {

class ClosedForms : public ArcusTest {};

// One catenary comparison per ray: end point and end direction against catenary_end().
void expect_catenary(const Trace& t, const Rays& rays, double n0, const V3& G, double L, double rtol, double atol) {
  ASSERT_EQ(t.status, ARCUS_SUCCESS);
  for (size_t i = 0; i < rays.size(); ++i) {
    const V3 o = rays.origin(i);
    const V3 d = rays.direction(i);
    const RayState want = catenary_end(n0, G, o, d, L);
    // Along a catenary n = A cosh u ≥ A (A = n·cos θ, conserved) and n ≤ n at the far end.
    const V3 dh = normalize(d);
    const double n_start = n0 + dot(G, o);
    const double A = n_start * norm(dh - dot(dh, normalize(G)) * normalize(G));
    const double n_max = std::max(n_start, n0 + dot(G, want.pos));
    const double r_max = norm(o) + L;
    const double bound = dp45_bound(t.steps[i], rtol, atol, r_max, n_max, A, L);
    EXPECT_EQ(t.ray_status[i], ARCUS_RAY_DONE) << "ray " << i;
    EXPECT_LT(distance(t.pos(i), want.pos), bound) << "ray " << i << " steps " << t.steps[i];
    // A direction error δv/n ≤ the same per-step sum without the lever arm L.
    const double dir_bound = std::sqrt(6.0) * double(t.steps[i]) * (atol + rtol * n_max) / A;
    EXPECT_LT(angle_between(t.dir(i), want.dir), dir_bound) << "ray " << i;
    EXPECT_NEAR(t.lengths[i], L, 1e-12 * L) << "ray " << i;
  }
}

TEST_F(ClosedForms, CatenaryLinearFieldUpwardAndOblique) {
  // The thesis' "cross" scene medium, n = 1 + 0.1·y (§5.4.1), rays at several elevations
  // and with out-of-plane components.
  const double n0 = 1.0, L = 30.0, rtol = 1e-10, atol = 1e-12;
  const V3 G{0.0, 0.1, 0.0};
  auto field = linear(n0, G);
  ASSERT_TRUE(field);
  Rays rays;
  for (double elev : {0.0, 10.0, 30.0, 60.0, 85.0}) rays.add({0.0, 0.5, 0.0}, {std::cos(rad(elev)), std::sin(rad(elev)), 0.0});
  rays.add({1.0, 2.0, -3.0}, {0.3, 0.2, 0.7});
  rays.add({-4.0, 0.0, 2.0}, {-0.5, 0.1, -0.2});
  const Trace t = trace(ctx(), field.get(), dp45(L, rtol, atol), rays);
  expect_catenary(t, rays, n0, G, L, rtol, atol);
  // The rays were really bent: the straight-line end point is far off (a test that
  // compared a straight tracer with the closed form must fail).
  const V3 straight = V3{0.0, 0.5, 0.0} + L * V3{1.0, 0.0, 0.0};
  EXPECT_GT(distance(t.pos(0), straight), 1.0);
}

TEST_F(ClosedForms, CatenaryThroughTheTurningPoint) {
  // Rays start downward, turn at n = A (the lowest point, horizontal tangent) and climb:
  // n·cos θ = A is conserved, so at the end n(end)·|d_end across G| must equal A.
  const double n0 = 1.5, L = 40.0, rtol = 1e-10, atol = 1e-12;
  const V3 G{0.0, 0.2, 0.0};
  auto field = linear(n0, G);
  ASSERT_TRUE(field);
  Rays rays;
  const std::vector<double> elevations{-5.0, -20.0, -45.0, -70.0};
  for (double e : elevations) rays.add({0.0, 0.0, 0.0}, {std::cos(rad(e)), std::sin(rad(e)), 0.0});
  const Trace t = trace(ctx(), field.get(), dp45(L, rtol, atol), rays);
  expect_catenary(t, rays, n0, G, L, rtol, atol);
  for (size_t i = 0; i < rays.size(); ++i) {
    // Precondition: the closed form says this ray has passed its turning point.
    const RayState want = catenary_end(n0, G, {0, 0, 0}, {std::cos(rad(elevations[i])), std::sin(rad(elevations[i])), 0}, L);
    ASSERT_GT(want.dir[1], 0.0);
    EXPECT_GT(t.dir(i)[1], 0.0) << "ray " << i << " did not turn up";
    const double A = n0 * std::cos(rad(elevations[i]));
    const double n_end = n_at(field.get(), t.pos(i));
    const double A_end = n_end * std::hypot(t.dir(i)[0], t.dir(i)[2]);
    // dv/ds = G does not depend on r, so v carries only the per-step local errors, summed:
    // δv ≤ √6·steps·(atol + rtol·n_max).  A_end = n(r_end)·|v_h|/|v| then errs by at most
    // 2δv + g·δr (|v| ≠ n(r_end) by δv + g·δr, scaled by A/n ≤ 1), δr the position bound.
    const double bound = std::sqrt(6.0) * double(t.steps[i]) * (atol + rtol * (n0 + 0.2 * L)) * 2.0 +
                         0.2 * dp45_bound(t.steps[i], rtol, atol, L, n0 + 0.2 * L, A, L);
    EXPECT_NEAR(A_end, A, bound) << "n cos(theta) not conserved, ray " << i;
  }
}

TEST_F(ClosedForms, CatenaryGradientInAGeneralDirection) {
  // The same problem rotated: G = rotation·(0, g, 0).  The rotated run must match both the
  // closed form and the rotated result of the axis-aligned run (isotropy).
  const double n0 = 1.2, g = 0.3, L = 25.0, rtol = 1e-10, atol = 1e-12;
  const V3 axis{1.0, 2.0, 3.0};
  const double turn = 1.1;
  const V3 G0{0.0, g, 0.0};
  const V3 G = rotate(G0, axis, turn);
  auto f0 = linear(n0, G0);
  auto f1 = linear(n0, G);
  ASSERT_TRUE(f0 && f1);
  Rays r0, r1;
  const std::vector<std::pair<V3, V3>> cases{{{0, 0, 0}, {1, 0.2, 0}},
                                             {{1, -1, 0.5}, {0.4, -0.6, 0.3}},
                                             {{0, 2, 0}, {-1, -0.1, 0.4}}};
  for (const auto& c : cases) {
    r0.add(c.first, c.second);
    r1.add(rotate(c.first, axis, turn), rotate(c.second, axis, turn));
  }
  const Trace t0 = trace(ctx(), f0.get(), dp45(L, rtol, atol), r0);
  const Trace t1 = trace(ctx(), f1.get(), dp45(L, rtol, atol), r1);
  expect_catenary(t1, r1, n0, G, L, rtol, atol);
  ASSERT_EQ(t0.status, ARCUS_SUCCESS);
  for (size_t i = 0; i < cases.size(); ++i) {
    const double bound = dp45_bound(t0.steps[i] + t1.steps[i], rtol, atol, 3.0 + L, n0 + g * (3.0 + L), 0.3, L);
    EXPECT_LT(distance(rotate(t0.pos(i), axis, turn), t1.pos(i)), bound) << "ray " << i;
  }
}

TEST_F(ClosedForms, ParabolaInLinearNSquaredField) {
  // n² = a + K·r: parabolic paths in the parameter τ (ds = n dτ); end point from Newton on
  // the closed-form arc length (linear_n2_end).  Rays along, against and across K.
  const double a = 1.0, L = 12.0, rtol = 1e-10, atol = 1e-12;
  const V3 K{0.2, 0.05, -0.1};
  auto field = linear_n2(a, K);
  ASSERT_TRUE(field);
  Rays rays;
  const V3 o{0.1, 0.2, 0.3};
  const std::vector<V3> dirs{{-0.6, 0.8, 0.1}, {1, 0, 0}, {0, 1, 0}, {-0.3, -0.2, 0.9}, {0.1, -1.0, -0.2}};
  for (const V3& d : dirs) rays.add(o, d);
  const Trace t = trace(ctx(), field.get(), dp45(L, rtol, atol), rays);
  ASSERT_EQ(t.status, ARCUS_SUCCESS);
  for (size_t i = 0; i < dirs.size(); ++i) {
    const RayState want = linear_n2_end(a, K, o, dirs[i], L);
    // |v|² = α(w² + m²) ≥ |K × v0|²/|K|²: n never drops below |K × v0|/|K| (or below its
    // start/end values when the minimum lies outside the path).
    const double n0 = std::sqrt(a + dot(K, o));
    const double n_end = std::sqrt(a + dot(K, want.pos));
    const double n_min = std::min({n0, n_end, norm(cross(K, n0 * normalize(dirs[i]))) / norm(K)});
    const double n_max = std::sqrt(a + norm(K) * (norm(o) + L));
    ASSERT_GT(n_min, 0.1) << "test design: keep n away from zero";
    const double bound = dp45_bound(t.steps[i], rtol, atol, norm(o) + L, n_max, n_min, L);
    EXPECT_EQ(t.ray_status[i], ARCUS_RAY_DONE);
    EXPECT_LT(distance(t.pos(i), want.pos), bound) << "ray " << i << " steps " << t.steps[i];
    EXPECT_LT(angle_between(t.dir(i), want.dir), bound) << "ray " << i;
  }
}

TEST_F(ClosedForms, LuneburgLensFocusesParallelRaysOnTheFarSide) {
  // Parallel rays entering along +x all leave the lens at the antipodal point F = c +
  // (R, 0, 0), the largest-x point of the sphere, so they first reach the plane x = c_x + R
  // there: a box whose +x face is that plane stops each ray at F (status LEFT_BOX).  By
  // conservation of r × v (a central field) with n = 1 at entry and exit, the exit
  // direction makes the angle asin(b/R) with +x, tilted back towards the axis:
  // d = (sqrt(1 − b²/R²), −b_vec/R).
  const V3 c{1.0, 2.0, -1.0};
  const double R = 0.5, rtol = 1e-10, atol = 1e-13;
  auto field = luneburg(c, R);
  ASSERT_TRUE(field);
  arcus_advance_params p = dp45(10.0 * R, rtol, atol);
  // "The end state is where the path crossed the box": the crossing of the computed path,
  // so the only error is the integration error, dp45_bound over the ≤ 4R of path (n from
  // 1 to √2).
  set_box(&p, c - V3{2 * R, 2 * R, 2 * R}, c + V3{R, 2 * R, 2 * R});
  const std::vector<std::pair<double, double>> impacts{{0, 0}, {0.1, 0}, {0.4, 0}, {0, -0.6}, {0.3, 0.4}, {-0.8, 0}, {0.5, -0.5}};
  Rays rays;
  for (const auto& b : impacts) rays.add(c + V3{-1.5 * R, b.first * R, b.second * R}, {1, 0, 0});
  const Trace t = trace(ctx(), field.get(), p, rays);
  ASSERT_EQ(t.status, ARCUS_SUCCESS);
  const V3 F = c + V3{R, 0, 0};
  const double bound = dp45_bound(t.max_steps(), rtol, atol, norm(c) + 2 * R, std::sqrt(2.0), 1.0, 4 * R);
  // Direction: the v errors alone give ≤ bound/L; a position error δr changes ∇n by
  // ≤ δr/R² (|∂²n| ≤ 1/R² inside), which over ≤ 4R of path turns v by ≤ 4δr/R more.
  const double dir_bound = 5.0 * bound / R;
  for (size_t i = 0; i < impacts.size(); ++i) {
    const V3 b{0.0, impacts[i].first, impacts[i].second};  // impact offset in units of R
    EXPECT_EQ(t.ray_status[i], ARCUS_RAY_LEFT_BOX) << "ray " << i;
    EXPECT_LT(distance(t.pos(i), F), bound) << "ray " << i << " misses the focus, b = " << norm(b);
    std::printf("impact %.2f R: %llu steps, distance to the focus %.3e R (bound %.3e R)\n", norm(b),
                (unsigned long long)t.steps[i], distance(t.pos(i), F) / R, bound / R);
    const V3 want_dir{std::sqrt(1.0 - dot(b, b)), -b[1], -b[2]};
    EXPECT_LT(angle_between(t.dir(i), want_dir), dir_bound) << "ray " << i;
  }
  // The axial ray is straight (∇n along it): it travels exactly 2.5 R to F.
  EXPECT_NEAR(t.lengths[0], 2.5 * R, bound);
}

TEST_F(ClosedForms, MaxwellFishEyeRaysAreCircles) {
  // Every ray is the circle through its start P, tangent to d there, and through the
  // conjugate point P' = c − R²(P − c)/|P − c|² (fisheye_end).  Arcs up to more than a
  // full turn.
  const V3 c{0.3, -0.2, 0.1};
  const double R = 2.0, n0 = 1.5, rtol = 1e-10, atol = 1e-13;
  auto field = fisheye(c, R, n0);
  ASSERT_TRUE(field);
  struct Case {
    V3 P, d;
    double L;
  };
  const std::vector<Case> cases{{c + V3{0.5 * R, 0, 0}, {0, 1, 0}, 20.0},  // circle of radius 2.5: 1.27 turns
                                {c + 2.0 * V3{0.6, 0.8, -0.4}, {0.2, -0.5, 0.9}, 7.0},
                                {c + V3{-1.0, 0.5, 2.0}, {1, 1, 0}, 12.0},
                                {c + V3{0.1, 0.1, 0.0}, {0, 0, 1}, 5.0}};
  for (const Case& k : cases) {
    Rays rays;
    rays.add(k.P, k.d);
    const Trace t = trace(ctx(), field.get(), dp45(k.L, rtol, atol), rays);
    ASSERT_EQ(t.status, ARCUS_SUCCESS);
    const RayState want = fisheye_end(c, R, k.P, k.d, k.L);
    // n along the circle is smallest at its point farthest from c (|q| + |ρ|), largest at
    // its nearest; both from the circle's geometry.
    const V3 p = k.P - c, pp = (-R * R / dot(p, p)) * p;
    const V3 m = normalize(p - dot(p, normalize(k.d)) * normalize(k.d));
    const double rho = -dot(p - pp, p - pp) / (2.0 * dot(m, p - pp));
    const double far = norm(p + rho * m) + std::fabs(rho);
    const double n_min = n0 / (1.0 + far * far / (R * R));
    // Rays of the fish-eye refocus (perfect imaging): nearby rays do not diverge
    // exponentially, amplification 1.
    const double bound = dp45_bound(t.steps[0], rtol, atol, norm(c) + far, n0, n_min, k.L);
    EXPECT_EQ(t.ray_status[0], ARCUS_RAY_DONE);
    EXPECT_LT(distance(t.pos(0), want.pos), bound) << "P = " << k.P[0] << "," << k.P[1] << "," << k.P[2];
    EXPECT_LT(angle_between(t.dir(0), want.dir), bound / std::min(1.0, std::fabs(rho)));
    // Test design: every case turns by more than 0.3 rad (a straight tracer must fail).
    ASSERT_GT(angle_between(want.dir, normalize(k.d)), 0.3);
  }
}

TEST_F(ClosedForms, ConstantFieldIsAStraightLineWithStraightFeatureOnly) {
  auto field = constant(1.33);
  ASSERT_TRUE(field);
  Rays rays;
  rays.add({0, 0, 0}, {1, 0, 0});
  rays.add({1, 2, 3}, {-2, 0.5, 7});  // not unit length
  rays.add({-1e3, 5e2, 1.0}, {1e-3, -2e-3, 3e-3});
  const double L = 123.456;
  for (arcus_method m : {ARCUS_METHOD_DP45, ARCUS_METHOD_RK4, ARCUS_METHOD_EULER}) {
    arcus_advance_params p = m == ARCUS_METHOD_DP45 ? dp45(L, 1e-9, 1e-12) : fixed(m, 0.5, L);
    const Trace t = trace(ctx(), field.get(), p, rays);
    EXPECT_EQ(t.status, ARCUS_SUCCESS) << "method " << m << ": " << last_error();
    if (t.status != ARCUS_SUCCESS) continue;
    // No integrator is compiled for a constant field, whatever the method asked for.
    EXPECT_EQ(t.features, ARCUS_FEATURE_STRAIGHT) << "method " << m;
    for (size_t i = 0; i < rays.size(); ++i) {
      const V3 o = rays.origin(i);
      const V3 d = normalize(rays.direction(i));
      // o + L·d̂ is a handful of roundings: 8 ulps of the magnitudes involved.
      const double eps = 8 * std::numeric_limits<double>::epsilon() * (norm(o) + L);
      EXPECT_LT(distance(t.pos(i), o + L * d), eps) << "ray " << i;
      EXPECT_LT(distance(t.dir(i), d), 8 * std::numeric_limits<double>::epsilon());
      EXPECT_EQ(t.ray_status[i], ARCUS_RAY_DONE);
      EXPECT_NEAR(t.lengths[i], L, 8 * std::numeric_limits<double>::epsilon() * L);
    }
  }
}

TEST_F(ClosedForms, ConstantFieldBoxExitIsTheExactIntersection) {
  auto field = constant(1.0);
  ASSERT_TRUE(field);
  Rays rays;
  rays.add({0, 0, 0}, {1, 0, 0});        // leaves through x = 4 after 4
  rays.add({0, 0, 0}, {0, -1, 1});       // through y = -2 after 2√2
  rays.add({1, 1, 1}, {0.3, 0.4, 1.2});  // through z = 6 after 5/1.2·|d|
  const std::vector<double> want_len{4.0, 2.0 * std::sqrt(2.0), 5.0 / 1.2 * norm({0.3, 0.4, 1.2})};
  // A ray-plane intersection: a few roundings of numbers ≤ 10.
  const double eps = 16 * std::numeric_limits<double>::epsilon() * 10.0;
  for (arcus_method m : {ARCUS_METHOD_DP45, ARCUS_METHOD_RK4}) {
    arcus_advance_params p = m == ARCUS_METHOD_DP45 ? dp45(100.0, 1e-9, 1e-12) : fixed(m, 0.5, 100.0);
    set_box(&p, {-1, -2, -3}, {4, 5, 6});
    const Trace t = trace(ctx(), field.get(), p, rays);
    EXPECT_EQ(t.status, ARCUS_SUCCESS) << "method " << m << ": " << last_error();
    if (t.status != ARCUS_SUCCESS) continue;
    EXPECT_EQ(t.features, ARCUS_FEATURE_STRAIGHT | ARCUS_FEATURE_BOX);
    for (size_t i = 0; i < rays.size(); ++i) {
      const V3 o = rays.origin(i);
      const V3 d = normalize(rays.direction(i));
      EXPECT_EQ(t.ray_status[i], ARCUS_RAY_LEFT_BOX) << "ray " << i;
      EXPECT_NEAR(t.lengths[i], want_len[i], eps) << "ray " << i;
      EXPECT_LT(distance(t.pos(i), o + want_len[i] * d), eps) << "ray " << i;
    }
  }
}

}  // namespace
