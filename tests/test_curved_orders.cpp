// Orders of the integrators on non-linear media with closed forms (thesis §4.3.5,
// §5.4.1): Maxwell's fish-eye (circles, fisheye_end) and the inside of a Luneburg lens
// (ellipses, luneburg_end).  test_curved_convergence.cpp does the same on a linear field, where
// v = n·dr/ds is integrated exactly and only the position errs; here both do.
//
// Every observed order is log2(error(h)/error(h/2)) between neighbouring steps, and the
// steps are chosen where the smallest error stands ≥ 30× above the rounding of the run,
// asserted as a precondition, so that rounding shifts an observed order by < 0.1: each
// of its N steps, and the closed form, rounds coordinates ≲ 3 by ≲ 2ε, independently,
// so the rounding adds up like a random walk: √(N+1)·2ε·3.
#include "test_util.h"

using namespace arcus_test;

namespace {

constexpr double kEps = std::numeric_limits<double>::epsilon();

class Orders : public ArcusTest {
 protected:
  // Fish-eye n = 1/(1 + |r − c|²), R = 1: the medium changes on the scale 1 and its rays
  // are circles of radius 1.1..1.3 here.
  static constexpr double R = 1.0, n0 = 1.0;
  static V3 c() { return {0.2, -0.1, 0.3}; }
  struct Ray {
    V3 P, d;
  };
  static std::vector<Ray> fisheye_rays() {
    return {{c() + V3{0.5, 0.2, 0.0}, {0.0, 1.0, 0.3}},
            {c() + V3{-0.3, 0.8, 0.4}, {1.0, -0.2, 0.1}},
            {c() + V3{1.5, 0.0, 0.0}, {0.2, 1.0, 0.0}}};
  }
  // Rounding of a run of `steps` steps through coordinates of size ≲ 3 (see the top).
  static double round_off(double steps) { return std::sqrt(steps + 1.0) * 2.0 * kEps * 3.0; }

  // Fixed-step orders: error at L against fisheye_end for each step; expects `order` within
  // `slack` for every halving.
  void check_fixed_order(arcus_method method, double order, const std::vector<double>& steps, double slack,
                         const char* name) {
    auto field = fisheye(c(), R, n0);
    ASSERT_TRUE(field);
    const double L = 4.0;  // about half a turn of each circle
    for (const Ray& ray : fisheye_rays()) {
      Rays rays;
      rays.add(ray.P, ray.d);
      const RayState want = fisheye_end(c(), R, ray.P, ray.d, L);
      std::vector<double> err;
      for (double h : steps) {
        const Trace t = trace(ctx(), field.get(), fixed(method, h, L), rays);
        ASSERT_EQ(t.status, ARCUS_SUCCESS) << last_error();
        ASSERT_EQ(t.ray_status[0], ARCUS_RAY_DONE);
        // Powers of two dividing L: exactly L/h steps.
        EXPECT_EQ(t.steps[0], uint64_t(L / h)) << name << " h = " << h;
        err.push_back(distance(t.pos(0), want.pos));
      }
      ASSERT_GT(err.back(), 30.0 * round_off(L / steps.back())) << "test design: " << name << " hits round-off";
      for (size_t k = 0; k + 1 < steps.size(); ++k) {
        const double p = observed_order(err[k], err[k + 1]);
        std::printf("%s: h %.5f -> %.5f  error %.3e -> %.3e  order %.3f (expected %.0f +- %.1f)\n", name, steps[k],
                    steps[k + 1], err[k], err[k + 1], p, order, slack);
        EXPECT_NEAR(p, order, slack) << name << " h = " << steps[k];
      }
    }
  }
};

// ---- Dormand–Prince ---------------------------------------------------------------

TEST_F(Orders, DormandPrinceOneStepLocalErrorIsSixthOrder) {
  // One step of size h from the closed-form state (max_steps = 1; rtol = atol = 1 accept
  // any trial step), compared with the circle at arc h.  A fifth-order method errs by
  // O(h⁶) a step.  Dormand & Prince chose the fifth-order weights to make the h⁶ error
  // constants small, so at steps whose error stands above rounding the h⁷ term still
  // shows: on every ray the observed order must be ≥ 6 − 0.3 (a fourth-order slip, a
  // wrong weight, gives ≈ 5); on the last ray, whose h⁶ term is the largest, it falls
  // towards 6 with each halving (measured 6.9, 6.7, 6.4, 6.2), the finest to 6 ± 0.3.
  // Halvings whose finer error is within 30× of one step's rounding are left out.
  auto field = fisheye(c(), R, n0);
  ASSERT_TRUE(field);
  const std::vector<double> steps{0.4, 0.2, 0.1, 0.05, 0.025};
  const std::vector<Ray> rays_in = fisheye_rays();
  for (size_t i = 0; i < rays_in.size(); ++i) {
    const Ray& ray = rays_in[i];
    const bool last = i + 1 == rays_in.size();
    Rays rays;
    rays.add(ray.P, ray.d);
    std::vector<double> err_pos, err_dir;
    for (double h : steps) {
      arcus_advance_params p = dp45(1.0, 1.0, 1.0);
      p.step = h;
      p.max_steps = 1;
      const Trace t = trace(ctx(), field.get(), p, rays);
      ASSERT_EQ(t.status, ARCUS_SUCCESS) << last_error();
      ASSERT_EQ(t.ray_status[0], ARCUS_RAY_STEP_LIMIT);
      ASSERT_EQ(t.steps[0], 1u);
      // The job reports the arc it reached: exactly the trial step.
      ASSERT_EQ(t.lengths[0], h);
      const RayState want = fisheye_end(c(), R, ray.P, ray.d, h);
      err_pos.push_back(distance(t.pos(0), want.pos));
      err_dir.push_back(angle_between(t.dir(0), want.dir));
    }
    size_t used = 0;
    double previous = 1e9;
    for (size_t k = 0; k + 1 < steps.size(); ++k) {
      if (std::min(err_pos[k + 1], err_dir[k + 1]) < 30.0 * round_off(1.0)) continue;
      ++used;
      const double p = observed_order(err_pos[k], err_pos[k + 1]);
      const double q = observed_order(err_dir[k], err_dir[k + 1]);
      std::printf("DP45 one step, ray %zu: h %.3f -> %.3f  position error %.3e -> %.3e order %.3f, direction %.3f\n",
                  i, steps[k], steps[k + 1], err_pos[k], err_pos[k + 1], p, q);
      EXPECT_GT(p, 6.0 - 0.3) << "ray " << i << " h = " << steps[k];
      EXPECT_GT(q, 6.0 - 0.3) << "ray " << i << " h = " << steps[k];
      if (last) {
        EXPECT_LT(p, previous) << "h = " << steps[k];
      }
      previous = p;
    }
    ASSERT_GE(used, 3u) << "test design: ray " << i << " hits rounding";
    if (last) {
      ASSERT_EQ(used, steps.size() - 1) << "test design: the last ray must resolve every step";
      EXPECT_NEAR(previous, 6.0, 0.3);
    }
  }
}

TEST_F(Orders, DormandPrinceGlobalErrorAtAFixedStepIsFifthOrder) {
  // max_step = step = h and rtol = atol = 1: every trial step is accepted and the step
  // never changes (the factor 0.2..5 is clipped to max_step), so DP45 runs as a fixed-step
  // fifth-order method: global error a·h⁵ + b·h⁶ + …  With b·h as large as a here (see
  // above) the observed order lies between 5 and 6 and falls towards 5 with each halving
  // (measured 6.0 .. 5.2): every halving must give 5 − 0.3 .. 6 + 0.3, less than the one
  // before.  A fourth-order method gives ≈ 4, a sixth-order one ≥ 6 falling towards 6.
  // The first two rays: the third's h⁵ term is so small that its error at h = 0.0125
  // nears rounding.
  auto field = fisheye(c(), R, n0);
  ASSERT_TRUE(field);
  const double L = 4.0;
  const std::vector<double> steps{0.1, 0.05, 0.025, 0.0125};
  for (size_t i = 0; i < 2; ++i) {
    const Ray ray = fisheye_rays()[i];
    Rays rays;
    rays.add(ray.P, ray.d);
    const RayState want = fisheye_end(c(), R, ray.P, ray.d, L);
    std::vector<double> err;
    for (double h : steps) {
      arcus_advance_params p = dp45(L, 1.0, 1.0);
      p.step = h;
      p.max_step = h;
      const Trace t = trace(ctx(), field.get(), p, rays);
      ASSERT_EQ(t.status, ARCUS_SUCCESS) << last_error();
      ASSERT_EQ(t.ray_status[0], ARCUS_RAY_DONE);
      EXPECT_EQ(t.lengths[0], L);
      // Precondition: steps of h (a last sliver when the sum of the steps rounds below L).
      ASSERT_GE(t.steps[0], uint64_t(L / h));
      ASSERT_LE(t.steps[0], uint64_t(L / h) + 1);
      err.push_back(distance(t.pos(0), want.pos));
    }
    ASSERT_GT(err.back(), 30.0 * round_off(L / steps.back())) << "test design: the finest step hits rounding";
    for (size_t k = 0; k + 1 < steps.size(); ++k) {
      const double p = observed_order(err[k], err[k + 1]);
      std::printf("DP45 fixed step, ray %zu: h %.4f -> %.4f  error %.3e -> %.3e  order %.3f\n", i, steps[k],
                  steps[k + 1], err[k], err[k + 1], p);
      EXPECT_GT(p, 5.0 - 0.3) << "h = " << steps[k];
      EXPECT_LT(p, 6.0 + 0.3) << "h = " << steps[k];
      if (k > 0) {
        EXPECT_LT(p, observed_order(err[k - 1], err[k])) << "h = " << steps[k];
      }
    }
  }
}

// DP45 over tolerances 1e-5 .. 1e-12 (atol = rtol/100): every error within dp45_bound, and
// the error proportional to the tolerance.  Asymptotically error ∝ tol; where the kept
// solution's h⁷ term still dominates its local error (see the one-step test) the error per
// step goes as tol^(7/5) over tol^(-1/5) steps: tol^(6/5).  So the least-squares slope of
// log(error) over log(tol) must lie in 1 − 0.15 .. 6/5 + 0.1.  A controller that ignored
// the tolerance (slope 0) fails, and so does one that kept the fourth-order solution
// (error ≈ the estimate ≈ tol a step over tol^(-1/5) steps: slope 4/5).
struct TolerancePoint {
  double tol, err, bound;
};
void expect_tolerance_proportionality(const std::vector<TolerancePoint>& pts, const char* name) {
  double sx = 0, sy = 0, sxx = 0, sxy = 0;
  for (const TolerancePoint& q : pts) {
    std::printf("%s: tol %.0e  error %.3e  error/tol %.3e  bound %.3e (%.1f%% of it)\n", name, q.tol, q.err,
                q.err / q.tol, q.bound, 100.0 * q.err / q.bound);
    EXPECT_LT(q.err, q.bound) << name << " tol " << q.tol;
    const double x = std::log10(q.tol), y = std::log10(q.err);
    sx += x;
    sy += y;
    sxx += x * x;
    sxy += x * y;
  }
  const double n = double(pts.size());
  const double slope = (n * sxy - sx * sy) / (n * sxx - sx * sx);
  // The band of error/tol over the 7 decades: a slope up to 6/5 lets it drift by 10^1.4 ≈ 25.
  double lo = 1e300, hi = 0;
  for (const TolerancePoint& q : pts) {
    lo = std::min(lo, q.err / q.tol);
    hi = std::max(hi, q.err / q.tol);
  }
  std::printf("%s: error ~ tol^%.3f (allowed 0.85 .. 1.30), error/tol within %.3g .. %.3g (allowed: a factor 30)\n",
              name, slope, lo, hi);
  EXPECT_GT(slope, 0.85) << name;
  EXPECT_LT(slope, 1.30) << name;
  EXPECT_LT(hi, 30.0 * lo) << name;
}

TEST_F(Orders, DormandPrinceErrorTracksTheToleranceInAFishEye) {
  auto field = fisheye(c(), R, n0);
  ASSERT_TRUE(field);
  std::vector<Ray> rays_in = fisheye_rays();
  rays_in.push_back({c() + V3{0.1, 0.1, 0.0}, {0.0, 0.0, 1.0}});  // past the centre: a circle of radius 3.6
  const double L = 6.0;
  for (size_t i = 0; i < rays_in.size(); ++i) {
    const Ray& ray = rays_in[i];
    Rays rays;
    rays.add(ray.P, ray.d);
    const RayState want = fisheye_end(c(), R, ray.P, ray.d, L);
    // ∫ds/ℓ with ℓ the smaller of the circle's radius and the medium's scale R; n ≥ 1/(1 +
    // (2ρ + |P − c|)²) on the circle (its farthest point from c).
    const Circle k = fisheye_circle(c(), R, ray.P, ray.d);
    const double turning = L / std::min(k.radius, R);
    const double far = norm(k.centre - c()) + k.radius;
    const double n_min = n0 / (1.0 + far * far / (R * R));
    std::vector<TolerancePoint> pts;
    for (int e = 5; e <= 12; ++e) {
      const double tol = std::pow(10.0, -e);
      const Trace t = trace(ctx(), field.get(), dp45(L, tol, tol / 100), rays);
      ASSERT_EQ(t.status, ARCUS_SUCCESS) << last_error();
      ASSERT_EQ(t.ray_status[0], ARCUS_RAY_DONE);
      PathScale scale{norm(want.pos), L};
      scale.turning = turning;
      scale.n_min = n_min;
      pts.push_back({tol, distance(t.pos(0), want.pos), dp45_bound(tol, tol / 100, scale)});
    }
    expect_tolerance_proportionality(pts, ("fish-eye ray " + std::to_string(i)).c_str());
  }
}

TEST_F(Orders, DormandPrinceErrorTracksTheToleranceInALuneburgLens) {
  // Arcs of the lens' ellipses that stay well inside it (|r − c| ≤ 0.75 R, asserted): n
  // is smooth there, so no kink of ∇n at the surface blurs the orders.
  const V3 lc{0.5, -0.3, 0.2};
  const double lr = 2.0;
  auto field = luneburg(lc, lr);
  ASSERT_TRUE(field);
  struct Arc {
    V3 P, d;
    double L;
  };
  const std::vector<Arc> arcs{{lc + V3{0.6, 0.0, 0.0}, {0.0, 1.0, 0.2}, 1.4},
                              {lc + V3{-0.2, 0.5, 0.3}, {1.0, -0.3, 0.5}, 1.2},
                              {lc + V3{0.0, 0.3, -0.5}, {0.2, 0.1, 1.0}, 1.5}};
  for (size_t i = 0; i < arcs.size(); ++i) {
    const Arc& a = arcs[i];
    ASSERT_LT(LuneburgEllipse(lc, lr, a.P, a.d).inside_radius(a.L), 0.75 * lr) << "test design: arc " << i;
    Rays rays;
    rays.add(a.P, a.d);
    const RayState want = luneburg_end(lc, lr, a.P, a.d, a.L);
    // ∫ds/ℓ with the lens radius as ℓ (the paths curve less); n ≥ 1 inside.
    const double turning = a.L / lr;
    std::vector<TolerancePoint> pts;
    for (int e = 5; e <= 12; ++e) {
      const double tol = std::pow(10.0, -e);
      const Trace t = trace(ctx(), field.get(), dp45(a.L, tol, tol / 100), rays);
      ASSERT_EQ(t.status, ARCUS_SUCCESS) << last_error();
      ASSERT_EQ(t.ray_status[0], ARCUS_RAY_DONE);
      PathScale scale{norm(want.pos), a.L};
      scale.turning = turning;
      pts.push_back({tol, distance(t.pos(0), want.pos), dp45_bound(tol, tol / 100, scale)});
    }
    expect_tolerance_proportionality(pts, ("Luneburg arc " + std::to_string(i)).c_str());
  }
}

// ---- fixed steps on the fish-eye ----------------------------------------------------
// Each method's error at L falls as h^p once h is small against the circles (radius ≈ 1):
// the steps start where the measured order is within 0.15 of p (from above: the
// O(h^{p+1}) term still adds), and ±0.3 leaves room for that term while a method of the
// next lower or higher order fails by ≥ 0.7.

TEST_F(Orders, EulerIsFirstOrderInAFishEye) {
  check_fixed_order(ARCUS_METHOD_EULER, 1.0, {0.0125, 0.00625, 0.003125, 0.0015625}, 0.3, "Euler");
}

TEST_F(Orders, MidpointRK2IsSecondOrderInAFishEye) {
  check_fixed_order(ARCUS_METHOD_RK2, 2.0, {0.025, 0.0125, 0.00625, 0.003125}, 0.3, "RK2");
}

TEST_F(Orders, RK4IsFourthOrderInAFishEye) {
  check_fixed_order(ARCUS_METHOD_RK4, 4.0, {0.05, 0.025, 0.0125, 0.00625}, 0.3, "RK4");
}

}  // namespace
