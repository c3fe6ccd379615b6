// Ray paths with closed forms: catenaries (linear n), parabolas (linear n²), the
// Luneburg lens focus, Maxwell's fish-eye circles and straight lines in a constant field,
// in double and in float precision.  Every DP45 comparison uses dp45_bound() (test_util.h):
// the tolerance mapped to the end point times the path's turning, from the closed form
// alone, with the measured error printed against it.
#include "test_util.h"

using namespace arcus_test;

namespace {

class ClosedForms : public ArcusTest {};

// The catenary through o along d (catenary_end): its turning (it turns monotonically
// towards G: the angle between its end directions), A = n·|d across G| (conserved, the
// least n on it) and the least radius of curvature A/g (curvature g·A/n²).
struct CatenaryScale {
  RayState end;
  PathScale scale;
  double A, ell;
};
CatenaryScale catenary_scale(double n0, const V3& G, const V3& o, const V3& d, double L) {
  CatenaryScale c;
  c.end = catenary_end(n0, G, o, d, L);
  const V3 dh = normalize(d), gh = normalize(G);
  const double n_start = n0 + dot(G, o);
  c.A = n_start * norm(dh - dot(dh, gh) * gh);
  c.ell = c.A / norm(G);
  c.scale = PathScale{norm(c.end.pos), L};
  c.scale.turning = angle_between(dh, c.end.dir);
  c.scale.n_min = c.A;
  return c;
}

// One catenary comparison per ray: end point and end direction against catenary_end().
void expect_catenary(const Trace& t, const Rays& rays, double n0, const V3& G, double L, double rtol, double atol,
                     const char* name) {
  ASSERT_EQ(t.status, ARCUS_SUCCESS);
  for (size_t i = 0; i < rays.size(); ++i) {
    const CatenaryScale c = catenary_scale(n0, G, rays.origin(i), rays.direction(i), L);
    const double bound = dp45_bound(rtol, atol, c.scale);
    // dv/ds = G is constant, so every Runge–Kutta step adds exactly h·G to v: the end
    // direction v/|v| is exact but for rounding (≲ 1e-12 rad over these runs), tighter than
    // dp45_direction_bound.
    const double dir_bound = std::min(1e-12, dp45_direction_bound(rtol, atol, c.scale, c.ell));
    const double err = distance(t.pos(i), c.end.pos), dir_err = angle_between(t.dir(i), c.end.dir);
    std::printf("%s ray %zu: error %.3e m (bound %.3e), direction %.3e rad (bound %.3e)\n", name, i, err, bound,
                dir_err, dir_bound);
    EXPECT_EQ(t.ray_status[i], ARCUS_RAY_DONE) << "ray " << i;
    EXPECT_LT(err, bound) << name << " ray " << i;
    EXPECT_LT(dir_err, dir_bound) << name << " ray " << i;
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
  expect_catenary(t, rays, n0, G, L, rtol, atol, "n = 1 + 0.1 y");
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
  expect_catenary(t, rays, n0, G, L, rtol, atol, "turning point");
  for (size_t i = 0; i < rays.size(); ++i) {
    // Precondition: the closed form says this ray has passed its turning point.
    const CatenaryScale c = catenary_scale(n0, G, rays.origin(i), rays.direction(i), L);
    ASSERT_GT(c.end.dir[1], 0.0);
    EXPECT_GT(t.dir(i)[1], 0.0) << "ray " << i << " did not turn up";
    const double A = n0 * std::cos(rad(elevations[i]));
    const double n_end = n_at(field.get(), t.pos(i));
    const double A_end = n_end * std::hypot(t.dir(i)[0], t.dir(i)[2]);
    // A_end = n(r_end)·|v across G|/|v| errs by at most 2δv + g·δr (|v| ≠ n(r_end) by
    // δv + g·δr, scaled by A/n ≤ 1), with δv v's error (n ≤ n0 + g·L) and δr the
    // position's.
    const double dv = dp45_v_bound(rtol, atol, c.scale, n0 + 0.2 * L);
    const double bound = 2.0 * dv + 0.2 * dp45_bound(rtol, atol, c.scale);
    std::printf("ray %zu: n cos(theta) off by %.3e (bound %.3e)\n", i, std::fabs(A_end - A), bound);
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
  expect_catenary(t0, r0, n0, G0, L, rtol, atol, "axis-aligned");
  expect_catenary(t1, r1, n0, G, L, rtol, atol, "rotated");
  ASSERT_EQ(t0.status, ARCUS_SUCCESS);
  for (size_t i = 0; i < cases.size(); ++i) {
    // Each run lies within its bound of the same (rotated) closed form.
    const CatenaryScale c = catenary_scale(n0, G0, r0.origin(i), r0.direction(i), L);
    EXPECT_LT(distance(rotate(t0.pos(i), axis, turn), t1.pos(i)), 2.0 * dp45_bound(rtol, atol, c.scale)) << "ray " << i;
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
    ASSERT_GT(n_min, 0.1) << "test design: keep n away from zero";
    // The parabola turns monotonically towards K; its curvature |∇n × d|/n ≤ |K|/(2n²),
    // so its radius of curvature is ≥ 2 n_min²/|K|.
    PathScale scale{norm(want.pos), L};
    scale.turning = angle_between(normalize(dirs[i]), want.dir);
    scale.n_min = n_min;
    const double bound = dp45_bound(rtol, atol, scale);
    const double dir_bound = dp45_direction_bound(rtol, atol, scale, 2.0 * n_min * n_min / norm(K));
    std::printf("ray %zu: error %.3e m (bound %.3e), direction %.3e rad (bound %.3e)\n", i,
                distance(t.pos(i), want.pos), bound, angle_between(t.dir(i), want.dir), dir_bound);
    EXPECT_EQ(t.ray_status[i], ARCUS_RAY_DONE);
    EXPECT_LT(distance(t.pos(i), want.pos), bound) << "ray " << i << " steps " << t.steps[i];
    EXPECT_LT(angle_between(t.dir(i), want.dir), dir_bound) << "ray " << i;
  }
}

// A Luneburg lens n = sqrt(2 − |r − c|²/R²) and a plane wave along +x.  A ray at impact
// offset b (in units of R, across x) enters the sphere at E = c + R(−sqrt(1 − b²), b),
// where n = 1, and runs on the ellipse p(τ) = p0 cos(τ/R) + R v0 sin(τ/R) with p0 = E − c
// and v0 = x̂ (luneburg_end): at τ = πR/2 it reaches p = R x̂, the antipodal point F = c +
// R x̂, whatever b.  There n = 1 again and dp/dτ = −p0/R, so it leaves along
// d = (sqrt(1 − b²), −b), as conservation of r × v also requires.
struct LuneburgCase {
  V3 c;
  double R;
  V3 origin, exit_dir;
  double arc_to_focus;  // from the origin to F
};
LuneburgCase luneburg_plane_wave(const V3& c, double R, double start_x, double by, double bz) {
  const double b2 = by * by + bz * bz;
  const V3 origin = c + V3{start_x * R, by * R, bz * R};
  const V3 entry = c + R * V3{-std::sqrt(1.0 - b2), by, bz};
  const LuneburgEllipse inside(c, R, entry, {1, 0, 0});
  return {c, R, origin, {std::sqrt(1.0 - b2), -by, -bz}, distance(origin, entry) + inside.arc_length(kPi * R / 2)};
}
// Bounds for these paths: ≤ 1.5R straight, then ≤ πR (half an ellipse inside the sphere)
// curving on the scale R, then straight; two kinks of ∇n (entry and exit, n = 1 there).
PathScale luneburg_scale(const V3& end, double L) {
  PathScale p{norm(end), L};
  p.turning = kPi;
  p.kinks = 2;
  return p;
}

TEST_F(ClosedForms, LuneburgLensFocusesParallelRaysOnTheFarSide) {
  // F is the largest-x point of the sphere, so the rays first reach the plane x = c_x + R
  // there: a box whose +x face is that plane stops each ray at F (status LEFT_BOX).
  const V3 c{1.0, 2.0, -1.0};
  const double R = 0.5, rtol = 1e-10, atol = 1e-13;
  auto field = luneburg(c, R);
  ASSERT_TRUE(field);
  arcus_advance_params p = dp45(10.0 * R, rtol, atol);
  // "The end state is where the path crossed the box": the crossing of the computed path,
  // so the only error is the integration error.
  set_box(&p, c - V3{2 * R, 2 * R, 2 * R}, c + V3{R, 2 * R, 2 * R});
  const std::vector<std::pair<double, double>> impacts{{0, 0}, {0.1, 0}, {0.4, 0}, {0, -0.6}, {0.3, 0.4}, {-0.8, 0}, {0.5, -0.5}};
  Rays rays;
  std::vector<LuneburgCase> cases;
  for (const auto& b : impacts) {
    cases.push_back(luneburg_plane_wave(c, R, -1.5, b.first, b.second));
    rays.add(cases.back().origin, {1, 0, 0});
  }
  const Trace t = trace(ctx(), field.get(), p, rays);
  ASSERT_EQ(t.status, ARCUS_SUCCESS);
  const V3 F = c + V3{R, 0, 0};
  for (size_t i = 0; i < impacts.size(); ++i) {
    const PathScale scale = luneburg_scale(F, (1.5 + kPi) * R);
    const double bound = dp45_bound(rtol, atol, scale);
    const double dir_bound = dp45_direction_bound(rtol, atol, scale, R);
    EXPECT_EQ(t.ray_status[i], ARCUS_RAY_LEFT_BOX) << "ray " << i;
    std::printf("impact %.2f R: distance to the focus %.3e m (bound %.3e), direction %.3e rad (bound %.3e), "
                "arc %.3e m from the closed form\n",
                std::hypot(impacts[i].first, impacts[i].second), distance(t.pos(i), F), bound,
                angle_between(t.dir(i), cases[i].exit_dir), dir_bound, std::fabs(t.lengths[i] - cases[i].arc_to_focus));
    EXPECT_LT(distance(t.pos(i), F), bound) << "ray " << i << " misses the focus";
    EXPECT_LT(angle_between(t.dir(i), cases[i].exit_dir), dir_bound) << "ray " << i;
    // The arc length to F, from the ellipse: an error δs along the path moves the end by
    // δs, and the box stops it at F within the crossing tolerance.
    EXPECT_NEAR(t.lengths[i], cases[i].arc_to_focus, bound) << "ray " << i;
  }
  // The axial ray is straight (∇n along it): exactly 2.5 R to F.
  EXPECT_NEAR(cases[0].arc_to_focus, 2.5 * R, 1e-15);
}

TEST_F(ClosedForms, LuneburgLensRaysLeaveAlongTheLineThroughTheFocus) {
  // No box: the rays cross the far surface at F and go on straight along exit_dir, so at
  // arc L they are at F + (L − arc_to_focus)·exit_dir.  This sees errors along the path
  // (speed |v|/n ≠ 1) that a box stopping every ray at F hides.  The exit kink lies in the
  // run here: fixed steps across it err O(h·|Δ∇n|) in v (the stages sample one side or the
  // other), DP45 by at most dp45_kink_factor() times its tolerance.
  const V3 c{1.0, 2.0, -1.0};
  const double R = 0.5, L = 6.0 * R, rtol = 1e-10, atol = 1e-13;
  auto field = luneburg(c, R);
  ASSERT_TRUE(field);
  const std::vector<std::pair<double, double>> impacts{{0, 0}, {0.1, 0}, {0.4, 0}, {0, -0.6}, {0.3, 0.4}, {-0.8, 0}};
  Rays rays;
  std::vector<LuneburgCase> cases;
  for (const auto& b : impacts) {
    cases.push_back(luneburg_plane_wave(c, R, -1.5, b.first, b.second));
    rays.add(cases.back().origin, {1, 0, 0});
  }
  const Trace t = trace(ctx(), field.get(), dp45(L, rtol, atol), rays);
  ASSERT_EQ(t.status, ARCUS_SUCCESS);
  for (size_t i = 0; i < impacts.size(); ++i) {
    const V3 want = c + V3{R, 0, 0} + (L - cases[i].arc_to_focus) * cases[i].exit_dir;
    const PathScale scale = luneburg_scale(want, L);
    const double bound = dp45_bound(rtol, atol, scale);
    const double dir_bound = dp45_direction_bound(rtol, atol, scale, R);
    std::printf("impact %.2f R: error %.3e m (bound %.3e), direction %.3e rad (bound %.3e)\n",
                std::hypot(impacts[i].first, impacts[i].second), distance(t.pos(i), want), bound,
                angle_between(t.dir(i), cases[i].exit_dir), dir_bound);
    EXPECT_EQ(t.ray_status[i], ARCUS_RAY_DONE) << "ray " << i;
    EXPECT_LT(distance(t.pos(i), want), bound) << "ray " << i;
    EXPECT_LT(angle_between(t.dir(i), cases[i].exit_dir), dir_bound) << "ray " << i;
  }
}

TEST_F(ClosedForms, LuneburgLensInFloatPrecisionFocusesOnTheFarSide) {
  // The focus test in float, DP45 at rtol 1e-6 (well above float's resolution, so the
  // controller can meet it): the integration error (dp45_bound at that tolerance) plus
  // float's rounding (float_rounding_bound; F itself is only resolved to ε_f·|F|).
  const V3 c{1.0, 2.0, -1.0};
  const double R = 0.5, L = 6.0 * R, rtol = 1e-6, atol = 1e-8;
  auto field = luneburg(c, R);
  ASSERT_TRUE(field);
  const std::vector<std::pair<double, double>> impacts{{0.1, 0}, {0.4, 0}, {0, -0.6}, {0.3, 0.4}, {-0.8, 0}};
  Rays rays;
  std::vector<LuneburgCase> cases;
  for (const auto& b : impacts) {
    cases.push_back(luneburg_plane_wave(c, R, -1.5, b.first, b.second));
    rays.add(cases.back().origin, {1, 0, 0});
  }
  arcus_advance_params boxed = dp45(L, rtol, atol);
  boxed.precision = ARCUS_PRECISION_FLOAT;
  set_box(&boxed, c - V3{2 * R, 2 * R, 2 * R}, c + V3{R, 2 * R, 2 * R});
  arcus_advance_params through = boxed;
  through.use_box = 0;
  const Trace tb = trace(ctx(), field.get(), boxed, rays);
  const Trace tt = trace(ctx(), field.get(), through, rays);
  ASSERT_EQ(tb.status, ARCUS_SUCCESS) << last_error();
  ASSERT_EQ(tt.status, ARCUS_SUCCESS) << last_error();
  EXPECT_TRUE(tb.features & ARCUS_FEATURE_FLOAT);
  const V3 F = c + V3{R, 0, 0};
  for (size_t i = 0; i < impacts.size(); ++i) {
    const PathScale focus = luneburg_scale(F, (1.5 + kPi) * R);
    const double bound = dp45_bound(rtol, atol, focus) + float_rounding_bound(focus);
    EXPECT_EQ(tb.ray_status[i], ARCUS_RAY_LEFT_BOX) << "ray " << i;
    EXPECT_LT(distance(tb.pos(i), F), bound) << "ray " << i;
    const V3 want = F + (L - cases[i].arc_to_focus) * cases[i].exit_dir;
    const PathScale line = luneburg_scale(want, L);
    const double line_bound = dp45_bound(rtol, atol, line) + float_rounding_bound(line);
    const double dir_bound = dp45_direction_bound(rtol, atol, line, R) + float_rounding_bound(line) / R;
    std::printf("float, impact %.2f R: focus missed by %.3e m (bound %.3e); at L off by %.3e m (bound %.3e), "
                "direction %.3e rad (bound %.3e)\n",
                std::hypot(impacts[i].first, impacts[i].second), distance(tb.pos(i), F), bound,
                distance(tt.pos(i), want), line_bound, angle_between(tt.dir(i), cases[i].exit_dir), dir_bound);
    EXPECT_EQ(tt.ray_status[i], ARCUS_RAY_DONE) << "ray " << i;
    EXPECT_LT(distance(tt.pos(i), want), line_bound) << "ray " << i;
    EXPECT_LT(angle_between(tt.dir(i), cases[i].exit_dir), dir_bound) << "ray " << i;
  }
}

// Maxwell's fish-eye cases: every ray is the circle through its start P, tangent to d
// there, and through the conjugate point P' = c − R²(P − c)/|P − c|² (fisheye_end).
struct FishEyeCase {
  V3 P, d;
  double L;
};
// Bounds for a fish-eye arc: it curves on the smaller of its circle's radius and R; n is
// smallest at the circle's point farthest from c.
PathScale fisheye_scale(const V3& c, double R, double n0, const FishEyeCase& k, const RayState& end, double* ell) {
  const Circle circle = fisheye_circle(c, R, k.P, k.d);
  const double far = norm(circle.centre - c) + circle.radius;
  *ell = std::min(circle.radius, R);
  PathScale p{norm(end.pos), k.L};
  p.turning = k.L / *ell;
  p.n_min = n0 / (1.0 + far * far / (R * R));
  return p;
}

TEST_F(ClosedForms, MaxwellFishEyeRaysAreCircles) {
  // Arcs up to more than a full turn.
  const V3 c{0.3, -0.2, 0.1};
  const double R = 2.0, n0 = 1.5, rtol = 1e-10, atol = 1e-13;
  auto field = fisheye(c, R, n0);
  ASSERT_TRUE(field);
  const std::vector<FishEyeCase> cases{{c + V3{0.5 * R, 0, 0}, {0, 1, 0}, 20.0},  // circle of radius 2.5: 1.27 turns
                                       {c + 2.0 * V3{0.6, 0.8, -0.4}, {0.2, -0.5, 0.9}, 7.0},
                                       {c + V3{-1.0, 0.5, 2.0}, {1, 1, 0}, 12.0},
                                       {c + V3{0.1, 0.1, 0.0}, {0, 0, 1}, 5.0}};
  for (const FishEyeCase& k : cases) {
    Rays rays;
    rays.add(k.P, k.d);
    const Trace t = trace(ctx(), field.get(), dp45(k.L, rtol, atol), rays);
    ASSERT_EQ(t.status, ARCUS_SUCCESS);
    const RayState want = fisheye_end(c, R, k.P, k.d, k.L);
    double ell = 0;
    const PathScale scale = fisheye_scale(c, R, n0, k, want, &ell);
    const double bound = dp45_bound(rtol, atol, scale);
    const double dir_bound = dp45_direction_bound(rtol, atol, scale, ell);
    std::printf("arc %.0f m: error %.3e m (bound %.3e), direction %.3e rad (bound %.3e)\n", k.L,
                distance(t.pos(0), want.pos), bound, angle_between(t.dir(0), want.dir), dir_bound);
    EXPECT_EQ(t.ray_status[0], ARCUS_RAY_DONE);
    EXPECT_LT(distance(t.pos(0), want.pos), bound) << "P = " << k.P[0] << "," << k.P[1] << "," << k.P[2];
    EXPECT_LT(angle_between(t.dir(0), want.dir), dir_bound);
    // Test design: every case turns by more than 0.3 rad (a straight tracer must fail).
    ASSERT_GT(angle_between(want.dir, normalize(k.d)), 0.3);
  }
}

TEST_F(ClosedForms, MaxwellFishEyeInFloatPrecisionFollowsTheCircles) {
  // Float against double with the same fixed RK4 steps (2 mm: up to 10⁴ of them): the
  // same truncation, so the difference is float's rounding alone (float_rounding_bound;
  // uncompensated, N·ε_f·|r| would exceed it).  The direction's rounding: the position's
  // over the length the path turns on, plus v's own (ε_f, well inside).  And float DP45
  // at rtol 1e-6 against the circle: dp45_bound plus the rounding.
  const V3 c{0.3, -0.2, 0.1};
  const double R = 2.0, n0 = 1.5, rtol = 1e-6, atol = 1e-8;
  auto field = fisheye(c, R, n0);
  ASSERT_TRUE(field);
  const std::vector<FishEyeCase> cases{{c + V3{0.5 * R, 0, 0}, {0, 1, 0}, 20.0},
                                       {c + 2.0 * V3{0.6, 0.8, -0.4}, {0.2, -0.5, 0.9}, 7.0},
                                       {c + V3{-1.0, 0.5, 2.0}, {1, 1, 0}, 12.0}};
  for (const FishEyeCase& k : cases) {
    Rays rays;
    rays.add(k.P, k.d);
    const RayState want = fisheye_end(c, R, k.P, k.d, k.L);
    double ell = 0;
    const PathScale scale = fisheye_scale(c, R, n0, k, want, &ell);
    arcus_advance_params rk4 = fixed(ARCUS_METHOD_RK4, 0.002, k.L);
    const Trace d = trace(ctx(), field.get(), rk4, rays);
    rk4.precision = ARCUS_PRECISION_FLOAT;
    const Trace f = trace(ctx(), field.get(), rk4, rays);
    arcus_advance_params adaptive = dp45(k.L, rtol, atol);
    adaptive.precision = ARCUS_PRECISION_FLOAT;
    const Trace a = trace(ctx(), field.get(), adaptive, rays);
    ASSERT_EQ(d.status, ARCUS_SUCCESS);
    ASSERT_EQ(f.status, ARCUS_SUCCESS) << last_error();
    ASSERT_EQ(a.status, ARCUS_SUCCESS) << last_error();
    ASSERT_TRUE(f.features & ARCUS_FEATURE_FLOAT);
    const double rounding = float_rounding_bound(scale);
    const double dp_bound = dp45_bound(rtol, atol, scale) + rounding;
    std::printf("arc %.0f m: float - double RK4 %.3e m (bound %.3e), %.3e rad (bound %.3e); float DP45 error %.3e m "
                "(bound %.3e)\n",
                k.L, distance(f.pos(0), d.pos(0)), rounding, angle_between(f.dir(0), d.dir(0)), rounding / ell,
                distance(a.pos(0), want.pos), dp_bound);
    EXPECT_EQ(f.ray_status[0], ARCUS_RAY_DONE);
    EXPECT_EQ(a.ray_status[0], ARCUS_RAY_DONE);
    EXPECT_LT(distance(f.pos(0), d.pos(0)), rounding);
    EXPECT_LT(angle_between(f.dir(0), d.dir(0)), rounding / ell);
    EXPECT_LT(distance(a.pos(0), want.pos), dp_bound);
    EXPECT_LT(angle_between(a.dir(0), want.dir), dp45_direction_bound(rtol, atol, scale, ell) + rounding / ell);
    // Float really ran in float: its rounding shows (≥ 100 ulps of double).
    EXPECT_GT(distance(f.pos(0), d.pos(0)), 1e-14 * (norm(want.pos) + k.L));
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
    EXPECT_EQ(t.features, ARCUS_FEATURE_CURVED_STRAIGHT) << "method " << m;
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
    EXPECT_EQ(t.features, ARCUS_FEATURE_CURVED_STRAIGHT | ARCUS_FEATURE_CURVED_BOX);
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
