// The calls on jobs, through curved-light jobs: job getters and paths, per-job feature
// bits, stats and the program cache, determinism, and the C99 program c_api_dump.
#include "test_util.h"

#include <cstdio>
#include <thread>

using namespace arcus_test;


namespace {

class Api : public ArcusTest {
 protected:
  // One 100-ray DP45 job through n = 1 + 0.1·y, run twice on the suite's context.
  struct TwoRuns {
    FieldPtr field;
    Rays rays;
    Trace first, second;
  };
  static TwoRuns same_job_twice() {
    TwoRuns r;
    r.field = linear(1.0, {0, 0.1, 0});
    for (int i = 0; i < 100; ++i) r.rays.add({0, 0.01 * i, 0}, {1, 0.001 * i, 0});
    const arcus_advance_params p = dp45(5.0, 1e-9, 1e-12);
    if (!r.field) return r;
    r.first = trace(ctx(), r.field.get(), p, r.rays);
    r.second = trace(ctx(), r.field.get(), p, r.rays);
    return r;
  }
};

TEST_F(Api, FieldKindsAndHostEvaluation) {
  const V3 c{1, 2, 3};
  auto lin = linear(1.5, {0.1, -0.2, 0.3});
  auto n2 = linear_n2(2.0, {0.4, 0, 0});
  auto lun = luneburg(c, 2.0);
  auto fish = fisheye(c, 2.0, 1.5);
  auto con = constant(1.25);
  ASSERT_TRUE(lin && n2 && lun && fish && con);
  arcus_field_kind k;
  ASSERT_EQ(arcus_field_get_kind(lin.get(), &k), ARCUS_SUCCESS);
  EXPECT_EQ(k, ARCUS_FIELD_LINEAR);
  ASSERT_EQ(arcus_field_get_kind(n2.get(), &k), ARCUS_SUCCESS);
  EXPECT_EQ(k, ARCUS_FIELD_LINEAR_N2);
  ASSERT_EQ(arcus_field_get_kind(lun.get(), &k), ARCUS_SUCCESS);
  EXPECT_EQ(k, ARCUS_FIELD_LUNEBURG);
  ASSERT_EQ(arcus_field_get_kind(fish.get(), &k), ARCUS_SUCCESS);
  EXPECT_EQ(k, ARCUS_FIELD_FISHEYE);
  ASSERT_EQ(arcus_field_get_kind(con.get(), &k), ARCUS_SUCCESS);
  EXPECT_EQ(k, ARCUS_FIELD_CONSTANT);

  // Closed-form n and ∇n at a few points, to a few ulps (the formulas are one-liners).
  const double tol = 1e-14;
  const std::vector<V3> pts{{0, 0, 0}, {0.5, -1, 2}, {1.5, 2.5, 3.2}, {4, 4, 4}};
  for (const V3& p : pts) {
    V3 g;
    double n = n_at(lin.get(), p, &g);
    EXPECT_NEAR(n, 1.5 + 0.1 * p[0] - 0.2 * p[1] + 0.3 * p[2], tol);
    EXPECT_NEAR(distance(g, {0.1, -0.2, 0.3}), 0.0, tol);
    n = n_at(n2.get(), p, &g);
    EXPECT_NEAR(n, std::sqrt(2.0 + 0.4 * p[0]), tol);
    EXPECT_NEAR(distance(g, {0.2 / n, 0, 0}), 0.0, tol);  // ∇n = K/(2n)
    const V3 q = p - c;
    const double r2 = dot(q, q) / 4.0;  // (r/R)²
    n = n_at(lun.get(), p, &g);
    if (r2 < 1.0) {
      EXPECT_NEAR(n, std::sqrt(2.0 - r2), tol);
      EXPECT_NEAR(distance(g, (-1.0 / (4.0 * n)) * q), 0.0, tol);
    } else {
      EXPECT_EQ(n, 1.0);
      EXPECT_EQ(norm(g), 0.0);
    }
    n = n_at(fish.get(), p, &g);
    EXPECT_NEAR(n, 1.5 / (1.0 + r2), tol);
    // ∇n = −n0·(2q/R²)/(1 + (r/R)²)².
    EXPECT_NEAR(distance(g, (-1.5 * 2.0 / 4.0 / ((1 + r2) * (1 + r2))) * q), 0.0, tol);
    n = n_at(con.get(), p, &g);
    EXPECT_EQ(n, 1.25);
    EXPECT_EQ(norm(g), 0.0);
  }
  // Several points at once, gradient optional.
  std::vector<double> many;
  for (const V3& p : pts) many.insert(many.end(), p.begin(), p.end());
  std::vector<double> n(pts.size());
  ASSERT_EQ(arcus_field_evaluate(lin.get(), pts.size(), many.data(), n.data(), nullptr), ARCUS_SUCCESS);
  for (size_t i = 0; i < pts.size(); ++i)
    EXPECT_NEAR(n[i], 1.5 + 0.1 * pts[i][0] - 0.2 * pts[i][1] + 0.3 * pts[i][2], tol) << "point " << i;
}

TEST_F(Api, AtmosphereDefaultsAreTheStandardAtmosphere) {
  arcus_atmosphere_desc d;
  std::memset(&d, 0x5a, sizeof d);
  ASSERT_EQ(arcus_atmosphere_desc_init(&d), ARCUS_SUCCESS);
  EXPECT_EQ(d.spherical, 0);
  EXPECT_EQ(d.wavelength, 550.0);
  EXPECT_EQ(d.sea_level_temperature, 288.15);
  EXPECT_EQ(d.sea_level_pressure, 101325.0);
  EXPECT_EQ(d.inversion_count, 0u);
  EXPECT_EQ(d.inversions, nullptr);
  auto flat = atmosphere(d);
  d.spherical = 1;
  auto sphere = atmosphere(d);
  ASSERT_TRUE(flat && sphere);
  // Dry air at 550 nm, 15 °C, 101325 Pa: n − 1 ≈ 2.777e-4 (Ciddor; Edlén gives 2.778e-4).
  V3 g;
  const double n_flat = n_at(flat.get(), {0, 0, 0}, &g);
  EXPECT_NEAR(n_flat - 1.0, 2.777e-4, 0.01e-4);
  EXPECT_LT(g[1], 0.0);
  EXPECT_EQ(g[0], 0.0);
  EXPECT_EQ(g[2], 0.0);
  // n − 1 ∝ density ∝ p/T, so at the ground its scale height is the density's:
  // 1/H = g0·M/(R*·T0) − lapse/T0 = (0.0341632 − 0.0065)/288.15 m⁻¹, H = 10416.5 m
  // (geometric and geopotential height agree at sea level to first order).
  const double H = -(n_flat - 1.0) / g[1];
  EXPECT_NEAR(H, 10416.5, 20.0);
  // The spherical atmosphere at radius R_E + h equals the flat one at height h, with ∇n
  // radial.
  for (double h : {0.0, 1000.0, 11000.0, 30000.0}) {
    const V3 dir = normalize({0.3, 0.8, -0.5});
    V3 gs, gf;
    const double ns = n_at(sphere.get(), (ARCUS_EARTH_RADIUS + h) * dir, &gs);
    const double nf = n_at(flat.get(), {5.0, h, -7.0}, &gf);
    EXPECT_NEAR(ns, nf, 1e-15) << "h = " << h;
    EXPECT_NEAR(distance(gs, gf[1] * dir), 0.0, 1e-6 * std::fabs(gf[1])) << "h = " << h;
  }
  // Wavelength dispersion: blue light is refracted more than red.
  d.spherical = 0;
  d.wavelength = 400.0;
  auto blue = atmosphere(d);
  d.wavelength = 700.0;
  auto red = atmosphere(d);
  ASSERT_TRUE(blue && red);
  EXPECT_GT(n_at(blue.get(), {0, 0, 0}), n_at(red.get(), {0, 0, 0}));
}

TEST_F(Api, AdvanceParameterDefaults) {
  arcus_advance_params p;
  std::memset(&p, 0x5a, sizeof p);
  ASSERT_EQ(arcus_advance_params_init(&p), ARCUS_SUCCESS);
  EXPECT_EQ(p.method, ARCUS_METHOD_DP45);
  EXPECT_EQ(p.precision, ARCUS_PRECISION_DOUBLE);
  EXPECT_EQ(p.length, 1.0);
  EXPECT_EQ(p.rtol, 1e-9);
  EXPECT_EQ(p.atol, 1e-12);
  EXPECT_EQ(p.min_step, 1e-12);
  EXPECT_EQ(p.max_step, 0.0);
  EXPECT_EQ(p.max_rejections, 64u);
  EXPECT_EQ(p.max_steps, 10000000u);
  EXPECT_EQ(p.use_box, 0);
  EXPECT_EQ(p.record_path, 0);
  EXPECT_EQ(p.path_capacity, 0u);
}

TEST_F(Api, FeaturesReportedPerJob) {
  arcus_atmosphere_desc ad;
  arcus_atmosphere_desc_init(&ad);
  auto atm = atmosphere(ad);
  auto lin = linear(1.0, {0, 0.1, 0});
  const uint32_t dims[3] = {2, 2, 2};
  auto grd = grid(std::vector<double>(8, 1.0), dims, {0, 0, 0}, {1, 1, 1});
  auto con = constant(1.0);
  ASSERT_TRUE(atm && lin && grd && con);
  Rays rays;
  rays.add({0.5, 0.5, 0.5}, {1, 0.1, 0});
  auto features = [&](arcus_field_t* f, const arcus_advance_params& p) {
    const Trace t = trace(ctx(), f, p, rays);
    EXPECT_EQ(t.status, ARCUS_SUCCESS) << last_error();
    return t.features;
  };
  EXPECT_EQ(features(atm.get(), dp45(1.0, 1e-9, 1e-12)), ARCUS_FEATURE_CURVED_DP45 | ARCUS_FEATURE_CURVED_FIELD_ATMOSPHERE);
  arcus_advance_params p = fixed(ARCUS_METHOD_RK4, 0.1, 1.0);
  set_box(&p, {-10, -10, -10}, {10, 10, 10});
  p.record_path = 1;
  EXPECT_EQ(features(lin.get(), p),
            ARCUS_FEATURE_CURVED_RK4 | ARCUS_FEATURE_CURVED_FIELD_LINEAR | ARCUS_FEATURE_CURVED_BOX | ARCUS_FEATURE_CURVED_RECORD_PATH);
  p = fixed(ARCUS_METHOD_EULER, 0.1, 1.0);
  p.precision = ARCUS_PRECISION_FLOAT;
  EXPECT_EQ(features(grd.get(), p), ARCUS_FEATURE_CURVED_EULER | ARCUS_FEATURE_CURVED_FIELD_GRID | ARCUS_FEATURE_FLOAT);
  EXPECT_EQ(features(lin.get(), fixed(ARCUS_METHOD_RK2, 0.1, 1.0)), ARCUS_FEATURE_CURVED_RK2 | ARCUS_FEATURE_CURVED_FIELD_LINEAR);
  EXPECT_EQ(features(con.get(), dp45(1.0, 1e-9, 1e-12)), ARCUS_FEATURE_CURVED_STRAIGHT);

  char buf[256];
  ASSERT_EQ(arcus_features_to_string(ARCUS_FEATURE_CURVED_DP45 | ARCUS_FEATURE_CURVED_FIELD_ATMOSPHERE | ARCUS_FEATURE_FLOAT, buf,
                                     sizeof buf),
            ARCUS_SUCCESS);
  EXPECT_TRUE(contains_ci(buf, "DP45")) << buf;
  EXPECT_TRUE(contains_ci(buf, "ATMOSPHERE")) << buf;
  EXPECT_TRUE(contains_ci(buf, "FLOAT")) << buf;
  EXPECT_FALSE(contains_ci(buf, "STRAIGHT")) << buf;
  ASSERT_EQ(arcus_features_to_string(ARCUS_FEATURE_CURVED_STRAIGHT | ARCUS_FEATURE_CURVED_BOX, buf, sizeof buf),
            ARCUS_SUCCESS);
  EXPECT_STREQ(buf, "CURVED_STRAIGHT CURVED_BOX");
}

TEST_F(Api, SecondIdenticalJobHitsTheProgramCache) {
  const TwoRuns runs = same_job_twice();
  ASSERT_TRUE(runs.field);
  const Trace &first = runs.first, &second = runs.second;
  ASSERT_EQ(first.status, ARCUS_SUCCESS);
  ASSERT_EQ(second.status, ARCUS_SUCCESS);
  arcus_job_stats s1, s2;
  ASSERT_EQ(arcus_job_get_stats(first.job.get(), &s1), ARCUS_SUCCESS);
  ASSERT_EQ(arcus_job_get_stats(second.job.get(), &s2), ARCUS_SUCCESS);
  EXPECT_EQ(s2.program_origin, ARCUS_PROGRAM_MEMORY_CACHE);
  EXPECT_EQ(s2.build_seconds, 0.0);
  // The suite's earlier tests (or an earlier process, through the disk cache) may have
  // built this program already.
  EXPECT_GE(s1.program_origin, ARCUS_PROGRAM_BUILT);
  EXPECT_LE(s1.program_origin, ARCUS_PROGRAM_DISK_CACHE);
  for (const arcus_job_stats& s : {s1, s2}) {
    EXPECT_GE(s.lanes, 1u);
    EXPECT_GE(s.groups, 1u);
    EXPECT_TRUE(std::isfinite(s.kernel_seconds) && s.kernel_seconds >= 0.0);
    EXPECT_TRUE(std::isfinite(s.total_seconds) && s.total_seconds >= 0.0);
    EXPECT_TRUE(std::isfinite(s.build_seconds) && s.build_seconds >= 0.0);
  }
  std::printf("first job: program origin %d build %.3f s; second: origin %d; %u lanes x %u groups\n",
              s1.program_origin, s1.build_seconds, s2.program_origin, s2.lanes, s2.groups);
}

TEST_F(Api, DeterminismTheSameJobTwiceGivesTheSameNumbers) {
  // Determinism only: the same program on the same input repeats itself bit for bit.
  // The numbers themselves are checked against the catenary in test_curved_closed_forms.cpp
  // and here (dp45_bound).
  const TwoRuns runs = same_job_twice();
  ASSERT_TRUE(runs.field);
  const Rays& rays = runs.rays;
  const Trace &first = runs.first, &second = runs.second;
  ASSERT_EQ(first.status, ARCUS_SUCCESS);
  ASSERT_EQ(second.status, ARCUS_SUCCESS);
  EXPECT_EQ(first.positions, second.positions);
  EXPECT_EQ(first.directions, second.directions);
  EXPECT_EQ(first.steps, second.steps);
  for (size_t i = 0; i < rays.size(); i += 33) {
    const RayState want = catenary_end(1.0, {0, 0.1, 0}, rays.origin(i), rays.direction(i), 5.0);
    PathScale scale{norm(want.pos), 5.0};
    scale.turning = angle_between(normalize(rays.direction(i)), want.dir);
    EXPECT_LT(distance(first.pos(i), want.pos), dp45_bound(1e-9, 1e-12, scale)) << "ray " << i;
  }
}

TEST_F(Api, EndStatesGettersAcceptNullForUnwantedArrays) {
  auto field = linear(1.0, {0, 0.1, 0});
  ASSERT_TRUE(field);
  Rays rays;
  rays.add({0, 0, 0}, {3, 4, 0});  // not unit length
  const Trace t = trace(ctx(), field.get(), dp45(2.0, 1e-9, 1e-12), rays);
  ASSERT_EQ(t.status, ARCUS_SUCCESS);
  double pos[3] = {0, 0, 0};
  ASSERT_EQ(arcus_job_get_curved_end_states(t.job.get(), pos, nullptr, nullptr, nullptr, nullptr), ARCUS_SUCCESS);
  EXPECT_EQ(pos[0], t.positions[0]);
  ASSERT_EQ(arcus_job_get_curved_end_states(t.job.get(), nullptr, nullptr, nullptr, nullptr, nullptr), ARCUS_SUCCESS);
  // End directions are unit vectors.
  EXPECT_NEAR(norm(t.dir(0)), 1.0, 1e-15);
  // Without record_path there are no paths: arcus_curved.h promises INVALID_ARGUMENT.
  size_t total = 123;
  EXPECT_EQ(arcus_job_get_curved_path_size(t.job.get(), &total), ARCUS_ERROR_INVALID_ARGUMENT);
  EXPECT_EQ(total, 123u);
  EXPECT_TRUE(contains_ci(last_error().c_str(), "record_path")) << last_error();
}

TEST_F(Api, RecordedPathsLieOnTheCatenary) {
  // Fixed RK4 (0.05 m steps over 10 m) in n = 1 + 0.1·y: the path of ray i has its origin,
  // then one point per step, the last being the end state.  Each point lies on the
  // catenary y(x) = (A cosh((x − C)·g/A) − n0)/g through the origin.
  const double n0 = 1.0, g = 0.1, h = 0.05, L = 10.0;
  auto field = linear(n0, {0, g, 0});
  ASSERT_TRUE(field);
  arcus_advance_params p = fixed(ARCUS_METHOD_RK4, h, L);
  p.record_path = 1;
  Rays rays;
  rays.add({0, 0, 0}, {1, 0.5, 0});
  rays.add({0, 1, 0}, {1, -0.3, 0});
  rays.add({0, 2, 0}, {1, 0, 0});
  const Trace t = trace(ctx(), field.get(), p, rays);
  ASSERT_EQ(t.status, ARCUS_SUCCESS);
  size_t total = 0;
  ASSERT_EQ(arcus_job_get_curved_path_size(t.job.get(), &total), ARCUS_SUCCESS);
  std::vector<uint64_t> offsets(rays.size() + 1), needed(rays.size());
  std::vector<double> pts(3 * total);
  ASSERT_EQ(arcus_job_get_curved_paths(t.job.get(), offsets.data(), pts.data(), needed.data()), ARCUS_SUCCESS);
  EXPECT_EQ(offsets[0], 0u);
  EXPECT_EQ(offsets.back(), total);
  for (size_t i = 0; i < rays.size(); ++i) {
    const uint64_t kept = offsets[i + 1] - offsets[i];
    EXPECT_EQ(kept, t.steps[i] + 1) << "ray " << i << ": origin plus one point per step";
    EXPECT_EQ(needed[i], kept);
    ASSERT_GE(kept, 2u);
    const V3 first{pts[3 * offsets[i]], pts[3 * offsets[i] + 1], pts[3 * offsets[i] + 2]};
    const size_t e = offsets[i + 1] - 1;
    const V3 last{pts[3 * e], pts[3 * e + 1], pts[3 * e + 2]};
    EXPECT_EQ(distance(first, rays.origin(i)), 0.0);
    EXPECT_EQ(distance(last, t.pos(i)), 0.0);
    const V3 d = normalize(rays.direction(i));
    const double n_start = n0 + g * rays.origin(i)[1];
    const double A = n_start * d[0];
    const double C = -A * std::asinh(n_start * d[1] / A) / g;
    // RK4 with h = 0.05 at this curvature errs ≈ 1e-9 m (global, ∝ h⁴; cf. the
    // convergence test); 1e-7 leaves room and still catches a misplaced point.
    for (uint64_t k = offsets[i]; k < offsets[i + 1]; ++k) {
      const double x = pts[3 * k], y = pts[3 * k + 1];
      EXPECT_NEAR(y, (A * std::cosh((x - C) * g / A) - n0) / g, 1e-7) << "ray " << i << " point " << k - offsets[i];
      EXPECT_EQ(pts[3 * k + 2], 0.0);
    }
  }
}

TEST_F(Api, StopConditionsSetTheRayStatus) {
  auto field = linear(1.0, {0, 0.5, 0});
  ASSERT_TRUE(field);
  Rays rays;
  rays.add({0, 0, 0}, {1, 0.2, 0});
  // max_steps reached before length.
  arcus_advance_params p = fixed(ARCUS_METHOD_RK4, 0.1, 10.0);
  p.max_steps = 7;
  Trace t = trace(ctx(), field.get(), p, rays);
  ASSERT_EQ(t.status, ARCUS_SUCCESS);
  EXPECT_EQ(t.ray_status[0], ARCUS_RAY_STEP_LIMIT);
  EXPECT_EQ(t.steps[0], 7u);
  EXPECT_NEAR(t.lengths[0], 0.7, 1e-12);
  p = dp45(10.0, 1e-9, 1e-12);
  p.max_steps = 3;
  t = trace(ctx(), field.get(), p, rays);
  EXPECT_EQ(t.ray_status[0], ARCUS_RAY_STEP_LIMIT);
  EXPECT_EQ(t.steps[0], 3u);
  EXPECT_LT(t.lengths[0], 10.0);
  // A tolerance the smallest allowed step cannot meet: the ray fails (and says so).
  p = dp45(10.0, 1e-14, 1e-16);
  p.step = 1.0;
  p.min_step = 0.5;
  t = trace(ctx(), field.get(), p, rays);
  ASSERT_EQ(t.status, ARCUS_SUCCESS);
  EXPECT_EQ(t.ray_status[0], ARCUS_RAY_FAILED);
  EXPECT_LT(t.lengths[0], 10.0);
  // max_step bounds the DP45 step: at least length/max_step steps.
  p = dp45(10.0, 1e-3, 1e-6);
  p.max_step = 0.25;
  t = trace(ctx(), field.get(), p, rays);
  EXPECT_EQ(t.ray_status[0], ARCUS_RAY_DONE);
  EXPECT_GE(t.steps[0], 40u);
}

TEST_F(Api, FloatPrecisionFollowsTheDoubleResult) {
  // RK4, h = 0.1 over 10 m: truncation ≈ 1e-8 m here (h⁴·∫κ⁴ds, test_curved_hard_cases.cpp),
  // so double must match the closed form to 1e-6; float adds its rounding
  // (float_rounding_bound, test_util.h).
  const double n0 = 1.0, L = 10.0;
  const V3 G{0, 0.5, 0};
  auto field = linear(n0, G);
  ASSERT_TRUE(field);
  Rays rays;
  rays.add({0, 0, 0}, {1, 0.3, 0});
  arcus_advance_params p = fixed(ARCUS_METHOD_RK4, 0.1, L);
  const Trace d = trace(ctx(), field.get(), p, rays);
  p.precision = ARCUS_PRECISION_FLOAT;
  const Trace f = trace(ctx(), field.get(), p, rays);
  ASSERT_EQ(d.status, ARCUS_SUCCESS);
  ASSERT_EQ(f.status, ARCUS_SUCCESS);
  EXPECT_TRUE(f.features & ARCUS_FEATURE_FLOAT);
  EXPECT_FALSE(d.features & ARCUS_FEATURE_FLOAT);
  const RayState end = catenary_end(n0, G, {0, 0, 0}, {1, 0.3, 0}, L);
  const V3 want = end.pos;
  PathScale scale{norm(want), L};
  scale.turning = angle_between(normalize(V3{1, 0.3, 0}), end.dir);
  EXPECT_LT(distance(d.pos(0), want), 1e-6);
  EXPECT_LT(distance(f.pos(0), want), 1e-6 + float_rounding_bound(scale));
  // Float really ran in float: not bit-identical to double.
  EXPECT_NE(f.pos(0), d.pos(0));
  std::printf("float error %.3e m (bound %.3e), double error %.3e m\n", distance(f.pos(0), want),
              1e-6 + float_rounding_bound(scale), distance(d.pos(0), want));
}

TEST_F(Api, DeterminismARayInABatchEqualsTheRayTracedAlone) {
  // Rays share SIMD lanes and step loops; each ray's result must not depend on its
  // neighbours (masked lanes): a ray traced in a batch of 37 equals it traced alone, bit
  // for bit.  (Determinism; the batch's physics is checked against the fish-eye's circles
  // below.)
  const double R = 1.0, n0 = 1.0, L = 3.0, rtol = 1e-10, atol = 1e-13;
  auto field = fisheye({0, 0, 0}, R, n0);
  ASSERT_TRUE(field);
  Rays batch;
  for (int i = 0; i < 37; ++i) batch.add({0.1 + 0.02 * i, 0.3, -0.1 * (i % 5)}, {0.2, 1.0, 0.05 * i});
  const arcus_advance_params p = dp45(L, rtol, atol);
  const Trace all = trace(ctx(), field.get(), p, batch);
  ASSERT_EQ(all.status, ARCUS_SUCCESS);
  for (size_t i : {size_t(0), size_t(13), size_t(36)}) {
    Rays one;
    one.add(batch.origin(i), batch.direction(i));
    const Trace t = trace(ctx(), field.get(), p, one);
    ASSERT_EQ(t.status, ARCUS_SUCCESS);
    EXPECT_EQ(t.pos(0), all.pos(i)) << "ray " << i;
    EXPECT_EQ(t.dir(0), all.dir(i)) << "ray " << i;
    EXPECT_EQ(t.steps[0], all.steps[i]) << "ray " << i;
  }
  for (size_t i = 0; i < batch.size(); ++i) {
    // Every ray of the batch is on its circle (fisheye_end; the bound as in
    // test_curved_closed_forms.cpp: the arc curves on the smaller of its radius and R).
    const RayState want = fisheye_end({0, 0, 0}, R, batch.origin(i), batch.direction(i), L);
    const Circle k = fisheye_circle({0, 0, 0}, R, batch.origin(i), batch.direction(i));
    const double far = norm(k.centre) + k.radius;
    PathScale scale{norm(want.pos), L};
    scale.turning = L / std::min(k.radius, R);
    scale.n_min = n0 / (1.0 + far * far / (R * R));
    EXPECT_LT(distance(all.pos(i), want.pos), dp45_bound(rtol, atol, scale)) << "ray " << i;
  }
}

TEST_F(Api, DeterminismConcurrentCallsOnOneContextGiveTheSerialResults) {
  // The header: contexts, fields and jobs may be used from several threads at once (calls
  // serialise on the context's lock).  Four threads advance the same rays through the same
  // field on the shared context; each must get the serial result, bit for bit.  (The
  // serial result itself is checked against the catenary.)
  auto field = linear(1.0, {0, 0.5, 0});
  ASSERT_TRUE(field);
  Rays rays;
  for (int i = 0; i < 200; ++i) rays.add({0, 0.01 * i, 0}, {1, 0.001 * i, 0});
  const arcus_advance_params p = dp45(20.0, 1e-10, 1e-13);
  const Trace serial = trace(ctx(), field.get(), p, rays);
  ASSERT_EQ(serial.status, ARCUS_SUCCESS);
  for (size_t i = 0; i < rays.size(); i += 40) {
    const RayState want = catenary_end(1.0, {0, 0.5, 0}, rays.origin(i), rays.direction(i), 20.0);
    PathScale scale{norm(want.pos), 20.0};
    scale.turning = angle_between(normalize(rays.direction(i)), want.dir);
    scale.n_min = std::hypot(rays.direction(i)[0], rays.direction(i)[2]) / norm(rays.direction(i)) *
                  (1.0 + 0.5 * rays.origin(i)[1]);  // A, the least n on the catenary
    EXPECT_LT(distance(serial.pos(i), want.pos), dp45_bound(1e-10, 1e-13, scale)) << "ray " << i;
  }
  std::vector<std::vector<double>> positions(4);
  std::vector<arcus_status> status(4, ARCUS_ERROR_INVALID_ARGUMENT);
  std::vector<std::thread> threads;
  for (int k = 0; k < 4; ++k)
    threads.emplace_back([&, k] {
      arcus_job_t* job = nullptr;
      status[k] = arcus_curved_advance(ctx(), field.get(), &p, rays.size(), rays.origins.data(), rays.directions.data(), nullptr, &job);
      if (!job) return;
      positions[k].resize(3 * rays.size());
      arcus_job_get_curved_end_states(job, positions[k].data(), nullptr, nullptr, nullptr, nullptr);
      arcus_job_release(job);
    });
  for (std::thread& t : threads) t.join();
  for (int k = 0; k < 4; ++k) {
    EXPECT_EQ(status[k], ARCUS_SUCCESS) << "thread " << k;
    EXPECT_EQ(positions[k], serial.positions) << "thread " << k;
  }
}

}  // namespace

#ifdef ARCUS_C_API_DUMP
namespace {

TEST(CApiDump, PrintsEightRaysOnTheCatenary) {
  // tests/c_api_dump.c (C99): 8 rays through n = 1 + 0.1·y, DP45 rtol 1e-9, atol 1e-12,
  // 100 m; origins (0, 0.1 i, 0), directions (1, 0.05 i − 0.2, 0).
  FILE* pipe = popen(ARCUS_C_API_DUMP, "r");
  ASSERT_NE(pipe, nullptr);
  std::vector<std::string> lines;
  char buf[1024];
  while (std::fgets(buf, sizeof buf, pipe)) lines.emplace_back(buf);
  const int rc = pclose(pipe);
  EXPECT_EQ(rc, 0);
  ASSERT_EQ(lines.size(), 8u);
  for (int i = 0; i < 8; ++i) {
    V3 p, d;
    unsigned long long steps = 0;
    int status = -1;
    char tail = 0;
    ASSERT_EQ(std::sscanf(lines[i].c_str(), "%lf %lf %lf %lf %lf %lf %llu %d%c", &p[0], &p[1], &p[2], &d[0], &d[1],
                          &d[2], &steps, &status, &tail),
              9)
        << lines[i];
    EXPECT_EQ(tail, '\n');
    EXPECT_EQ(status, ARCUS_RAY_DONE);
    const V3 o{0.0, 0.1 * i, 0.0}, d0{1.0, 0.05 * i - 0.2, 0.0};
    const RayState want = catenary_end(1.0, {0, 0.1, 0}, o, d0, 100.0);
    // dp45_bound (test_util.h): n ≥ A ≥ 0.97 on these catenaries, whose radius of
    // curvature is ≥ A/g ≥ 9.7 m.
    PathScale scale{norm(want.pos), 100.0};
    scale.turning = angle_between(normalize(d0), want.dir);
    scale.n_min = 0.97;
    std::printf("ray %d: error %.3e m (bound %.3e)\n", i, distance(p, want.pos), dp45_bound(1e-9, 1e-12, scale));
    EXPECT_LT(distance(p, want.pos), dp45_bound(1e-9, 1e-12, scale)) << "ray " << i << " (" << steps << " steps)";
    EXPECT_LT(angle_between(d, want.dir), dp45_direction_bound(1e-9, 1e-12, scale, 9.7)) << "ray " << i;
  }
}

}  // namespace
#endif
