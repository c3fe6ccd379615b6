// Orders of convergence of the fixed-step methods and error control of DP45, measured
// against the closed-form catenary (thesis §4.3.5, §5.4.1).
#include "test_util.h"

using namespace arcus_test;

namespace {

class Convergence : public ArcusTest {
 protected:
  // n = 1 + 0.5·y: strongly curved (the catenary's scale A/g ≈ 2 m over L = 10 m), so the
  // truncation errors at the steps below sit far above round-off (≥ 1e-9 against
  // ≈ 1e-13 for a few hundred steps of size-10 numbers).
  static constexpr double n0 = 1.0, L = 10.0;
  static V3 G() { return {0.0, 0.5, 0.0}; }
  static Rays rays() {
    Rays r;
    r.add({0, 0, 0}, {1, 0.3, 0});
    r.add({0, 1, 0}, {0.5, -0.2, 0.4});
    return r;
  }
  // End-point errors of each ray against the closed form.
  static std::vector<double> errors(const Trace& t, const Rays& r) {
    std::vector<double> e;
    for (size_t i = 0; i < r.size(); ++i) {
      const V3 o = r.origin(i);
      const V3 d = r.direction(i);
      e.push_back(distance(t.pos(i), catenary_end(n0, G(), o, d, L).pos));
    }
    return e;
  }

  void check_order(arcus_method method, double expected, const std::vector<double>& steps, const char* name) {
    auto field = linear(n0, G());
    ASSERT_TRUE(field);
    const Rays r = rays();
    std::vector<std::vector<double>> err;  // [step][ray]
    for (double h : steps) {
      const Trace t = trace(ctx(), field.get(), fixed(method, h, L), r);
      ASSERT_EQ(t.status, ARCUS_SUCCESS);
      for (size_t i = 0; i < r.size(); ++i) {
        EXPECT_EQ(t.ray_status[i], ARCUS_RAY_DONE);
        // The steps are powers of two dividing L: exactly L/h fixed steps.
        EXPECT_EQ(t.steps[i], uint64_t(L / h)) << name << " h = " << h;
        EXPECT_NEAR(t.lengths[i], L, 1e-12 * L);
      }
      err.push_back(errors(t, r));
    }
    for (size_t i = 0; i < r.size(); ++i) {
      for (size_t k = 0; k + 1 < steps.size(); ++k) {
        // Halving h divides an order-p error by 2^p (asymptotic range: the prototype gave
        // observed orders within 0.12 of p already at the largest steps used here).
        const double p = std::log2(err[k][i] / err[k + 1][i]);
        std::printf("%s ray %zu: h %.6g -> %.6g  error %.3e -> %.3e  observed order %.3f\n", name, i, steps[k],
                    steps[k + 1], err[k][i], err[k + 1][i], p);
        EXPECT_NEAR(p, expected, 0.3) << name << " ray " << i << " h = " << steps[k];
      }
    }
  }
};

TEST_F(Convergence, EulerIsFirstOrder) {
  check_order(ARCUS_METHOD_EULER, 1.0, {0.125, 0.0625, 0.03125, 0.015625}, "Euler");
}

TEST_F(Convergence, MidpointRK2IsSecondOrder) {
  check_order(ARCUS_METHOD_RK2, 2.0, {0.25, 0.125, 0.0625, 0.03125}, "RK2");
}

TEST_F(Convergence, RK4IsFourthOrder) {
  check_order(ARCUS_METHOD_RK4, 4.0, {0.5, 0.25, 0.125, 0.0625}, "RK4");
}

TEST_F(Convergence, DormandPrinceErrorFallsWithTolerance) {
  auto field = linear(n0, G());
  ASSERT_TRUE(field);
  const Rays r = rays();
  std::vector<std::vector<double>> err;
  std::vector<std::vector<uint64_t>> steps;
  std::vector<double> tols;
  for (int e = 3; e <= 10; ++e) {
    const double tol = std::pow(10.0, -e);
    tols.push_back(tol);
    const Trace t = trace(ctx(), field.get(), dp45(L, tol, tol * 1e-3), r);
    ASSERT_EQ(t.status, ARCUS_SUCCESS);
    err.push_back(errors(t, r));
    steps.push_back(t.steps);
    for (size_t i = 0; i < r.size(); ++i) {
      EXPECT_EQ(t.ray_status[i], ARCUS_RAY_DONE);
      // Within what the tolerance promises (dp45_bound): the catenary turns monotonically
      // (its turning is the angle between its end directions) and n ≥ A ≥ 0.9 along it.
      const RayState want = catenary_end(n0, G(), r.origin(i), r.direction(i), L);
      PathScale scale{norm(want.pos), L};
      scale.turning = angle_between(normalize(r.direction(i)), want.dir);
      scale.n_min = 0.9;
      const double bound = dp45_bound(tol, tol * 1e-3, scale);
      EXPECT_LT(err.back()[i], bound) << "tol " << tol << " ray " << i;
      std::printf("DP45 tol %.0e ray %zu: %4llu steps, error %.3e (bound %.3e)\n", tol, i,
                  (unsigned long long)t.steps[i], err.back()[i], bound);
    }
  }
  for (size_t i = 0; i < r.size(); ++i) {
    for (size_t k = 0; k + 1 < tols.size(); ++k) {
      // A tenfold tighter tolerance shrinks the step by 10^(1/5) ≈ 1.6 and the error by
      // about ten; it must at least fall, and the step count must not fall.
      EXPECT_LT(err[k + 1][i], err[k][i]) << "ray " << i << " tol " << tols[k] << " -> " << tols[k + 1];
      EXPECT_GE(steps[k + 1][i], steps[k][i]) << "ray " << i;
    }
    // Over seven decades of tolerance the error must fall by well over five decades.
    EXPECT_LT(err.back()[i], 1e-5 * err.front()[i]) << "ray " << i;
  }
}

}  // namespace
