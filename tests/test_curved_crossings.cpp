// A ray that leaves the box ends where its integrated path crosses the box — not where
// the last step's chord does (thesis §4.3.5; the rendering engine's surface hits use the
// same routine).  Checked against the parabola of a linear-n² medium, whose crossing of
// a plane has a closed form, and, for the fixed-step methods, against their own path.
#include "test_util.h"

using namespace arcus_test;

namespace {

class Crossings : public ArcusTest {
 protected:
  // n² = 1 + K·r: every path is a parabola in τ (test_util.h, Parabola).  The box's
  // +x face at x = 3 is the one the rays below reach first (checked).
  static constexpr double a = 1.0, face = 3.0;
  static V3 K() { return {0.1, 0.4, 0.05}; }
  static void box(arcus_advance_params* p) { set_box(p, {-10, -10, -10}, {face, 10, 10}); }
  static std::vector<V3> directions() { return {{1, 0, 0}, {1, 0.3, 0.1}, {1, -0.5, 0.2}, {0.8, 0.6, -0.1}}; }
  static Rays rays() {
    Rays r;
    for (const V3& d : directions()) r.add({0, 0, 0}, d);
    return r;
  }
  // The closed-form crossing: the positive root of x(τ) = x0 + v0x τ + Kx τ²/4 = face.
  struct Crossing {
    V3 position;
    double length;
  };
  static Crossing exact(const V3& d) {
    const Parabola p(a, K(), {0, 0, 0}, d);
    const double qa = K()[0] / 4, qb = p.v0[0], qc = -face;
    const double tau = (-qb + std::sqrt(qb * qb - 4 * qa * qc)) / (2 * qa);
    const V3 r = p.position(tau);
    EXPECT_LT(std::fabs(r[1]), 10.0);  // no other face is crossed first
    EXPECT_LT(std::fabs(r[2]), 10.0);
    return {r, p.arc_length(tau)};
  }
};

TEST_F(Crossings, Dp45EndsOnTheParabolaWhereItCrossesThePlane) {
  auto field = linear_n2(a, K());
  ASSERT_TRUE(field);
  const double rtol = 1e-10, atol = 1e-12, L = 20.0;
  arcus_advance_params p = dp45(L, rtol, atol);
  box(&p);
  p.record_path = 1;
  const Rays r = rays();
  const Trace t = trace(ctx(), field.get(), p, r);
  ASSERT_EQ(t.status, ARCUS_SUCCESS) << last_error();
  std::vector<uint64_t> offsets(r.size() + 1);
  size_t total = 0;
  ASSERT_EQ(arcus_job_get_curved_path_size(t.job.get(), &total), ARCUS_SUCCESS);
  std::vector<double> points(3 * total);
  ASSERT_EQ(arcus_job_get_curved_paths(t.job.get(), offsets.data(), points.data(), nullptr), ARCUS_SUCCESS);
  for (size_t i = 0; i < r.size(); ++i) {
    const Crossing want = exact(r.direction(i));
    EXPECT_EQ(t.ray_status[i], ARCUS_RAY_LEFT_BOX) << "ray " << i;
    // The end lies on the face exactly, and on the path to the tolerance: the controller
    // keeps each step's error relative to |y| under rtol, and on this smooth, non-focusing
    // path the end errs by about rtol times the sizes involved (Hairer, Nørsett & Wanner
    // I.II.4, tolerance proportionality): rtol·(|r_end| + s) with the closed form's values,
    // plus atol.  The crossing is found to atol + rtol·10 (the box's size), inside that.
    const double bound = rtol * (norm(want.position) + want.length + 10.0) + atol;
    EXPECT_EQ(t.pos(i)[0], face) << "ray " << i;
    EXPECT_LT(distance(t.pos(i), want.position), bound) << "ray " << i;
    EXPECT_NEAR(t.lengths[i], want.length, bound) << "ray " << i;
    std::printf("ray %zu: %llu steps, end %.3e m from the closed-form crossing, length off by %.3e m (bound %.1e)\n",
                i, (unsigned long long)t.steps[i], distance(t.pos(i), want.position),
                std::fabs(t.lengths[i] - want.length), bound);
    // The path's last point is the end state; every point lies inside the box.
    const size_t last = offsets[i + 1] - 1;
    EXPECT_EQ(V3({points[3 * last], points[3 * last + 1], points[3 * last + 2]}), t.pos(i)) << "ray " << i;
    for (size_t k = offsets[i]; k < offsets[i + 1]; ++k) EXPECT_LE(points[3 * k], face) << "ray " << i;
  }
}

TEST_F(Crossings, FixedStepMethodsEndOnTheirOwnPath) {
  // A fixed-step method's path up to arc s is what it computes with length = s: the same
  // steps, the last one shortened.  The box run must end where that run ends; a chord
  // between the steps' ends would miss it by ≈ κh²/8 (κ ≈ 0.2/m here: 6e-4 m at h = 0.15).
  auto field = linear_n2(a, K());
  ASSERT_TRUE(field);
  const Rays r = rays();
  for (arcus_method m : {ARCUS_METHOD_EULER, ARCUS_METHOD_RK2, ARCUS_METHOD_RK4}) {
    const double h = 0.15;
    arcus_advance_params p = fixed(m, h, 20.0);
    box(&p);
    const Trace t = trace(ctx(), field.get(), p, r);
    ASSERT_EQ(t.status, ARCUS_SUCCESS) << last_error();
    for (size_t i = 0; i < r.size(); ++i) {
      ASSERT_EQ(t.ray_status[i], ARCUS_RAY_LEFT_BOX) << "method " << m << " ray " << i;
      EXPECT_EQ(t.pos(i)[0], face);
      Rays one;
      one.add(r.origin(i), r.direction(i));
      const Trace own = trace(ctx(), field.get(), fixed(m, h, t.lengths[i]), one);
      ASSERT_EQ(own.status, ARCUS_SUCCESS);
      // Both end after the same full steps and a last one of the same length (to the
      // rounding of s); the crossing is found to 1e-12 relative of the box's size.
      EXPECT_LT(distance(t.pos(i), own.pos(0)), 1e-10) << "method " << m << " ray " << i;
      EXPECT_EQ(t.steps[i], own.steps[0]) << "method " << m << " ray " << i;
    }
    // RK4 at this step is accurate enough to meet the closed form too (its global error
    // is below 1e-6 m here, the chord's 6e-4 m).
    if (m == ARCUS_METHOD_RK4) {
      for (size_t i = 0; i < r.size(); ++i) EXPECT_LT(distance(t.pos(i), exact(r.direction(i)).position), 1e-6);
    }
  }
}

TEST_F(Crossings, FloatPrecisionAlsoEndsOnTheFace) {
  auto field = linear_n2(a, K());
  ASSERT_TRUE(field);
  arcus_advance_params p = dp45(20.0, 1e-6, 1e-8);
  p.precision = ARCUS_PRECISION_FLOAT;
  box(&p);
  const Rays r = rays();
  const Trace t = trace(ctx(), field.get(), p, r);
  ASSERT_EQ(t.status, ARCUS_SUCCESS) << last_error();
  for (size_t i = 0; i < r.size(); ++i) {
    EXPECT_EQ(t.ray_status[i], ARCUS_RAY_LEFT_BOX);
    EXPECT_EQ(t.pos(i)[0], face);
    // Float resolves 3 m to 2.4e-7 m; rtol 1e-6 over ~40 steps: 1e-4 m covers both.
    EXPECT_LT(distance(t.pos(i), exact(r.direction(i)).position), 1e-4) << "ray " << i;
  }
}

TEST_F(Crossings, StraightRaysLeaveTheBoxAtTheSlabIntersection) {
  auto field = constant(1.33);
  ASSERT_TRUE(field);
  arcus_advance_params p = dp45(100.0, 1e-9, 1e-12);
  set_box(&p, {-1, -2, -3}, {4, 5, 6});
  Rays r;
  r.add({0, 0, 0}, {1, 2, 3});    // leaves through z = 6 at t = 2
  r.add({1, 1, 1}, {-1, 0, 0});   // through x = -1 after 2
  r.add({0, 0, 0}, {0, -1, 0.5}); // through y = -2 after √5
  const Trace t = trace(ctx(), field.get(), p, r);
  ASSERT_EQ(t.status, ARCUS_SUCCESS);
  const std::vector<V3> want{{2, 4, 6}, {-1, 1, 1}, {0, -2, 1}};
  const std::vector<double> lengths{2 * std::sqrt(14.0), 2.0, std::sqrt(5.0)};
  for (size_t i = 0; i < r.size(); ++i) {
    EXPECT_EQ(t.ray_status[i], ARCUS_RAY_LEFT_BOX);
    EXPECT_LT(distance(t.pos(i), want[i]), 1e-12) << "ray " << i;
    EXPECT_NEAR(t.lengths[i], lengths[i], 1e-12) << "ray " << i;
  }
}

// A fixed-step ray that stops at its length reports exactly that length, with a box too.
TEST_F(Crossings, FixedStepLengthIsExactWithABox) {
  FieldPtr medium = linear(1.0, {0, 0.1, 0});
  ASSERT_TRUE(medium);
  Rays rays;
  rays.add({0, 0, 0}, {1, 0, 0});
  arcus_advance_params p = fixed(ARCUS_METHOD_RK4, 0.01, 1000.0);
  p.precision = ARCUS_PRECISION_FLOAT;
  set_box(&p, {-1e5, -1e5, -1e5}, {1e5, 1e5, 1e5});
  Trace t = trace(ctx(), medium.get(), p, rays);
  ASSERT_EQ(t.status, ARCUS_SUCCESS) << last_error();
  EXPECT_EQ(t.ray_status[0], ARCUS_RAY_DONE);
  EXPECT_EQ(t.lengths[0], 1000.0);
}

}  // namespace
