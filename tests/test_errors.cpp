// Bad input: invalid rays (flagged, the others unharmed bit for bit), bad numbers, unknown
// devices, null pointers in every entry point, bad grids and grid files, path overflow,
// and the error reporting itself (messages naming the argument, the callback).
#include "test_util.h"

#include <unistd.h>

#include <atomic>
#include <fstream>

using namespace arcus_test;

namespace {

class BadInput : public ArcusTest {};

const double kNaN = std::numeric_limits<double>::quiet_NaN();
const double kInf = std::numeric_limits<double>::infinity();

TEST_F(BadInput, DeterminismInvalidRaysAreFlaggedAndTheOthersAreBitwiseUnchanged) {
  // Determinism: the good rays give the numbers they give without the bad ones beside
  // them, bit for bit; and those numbers lie on their catenaries (dp45_bound, RK4's order).
  auto field = linear(1.0, {0.05, 0.2, -0.1});
  ASSERT_TRUE(field);
  // Good rays interleaved with bad ones: NaN and zero directions, Inf and NaN origins.
  Rays good, mixed;
  std::vector<bool> bad;
  auto add_good = [&](const V3& o, const V3& d) {
    good.add(o, d);
    mixed.add(o, d);
    bad.push_back(false);
  };
  auto add_bad = [&](const V3& o, const V3& d) {
    mixed.add(o, d);
    bad.push_back(true);
  };
  add_good({0, 0, 0}, {1, 0.1, 0});
  add_bad({0, 0, 0}, {kNaN, 1, 0});
  add_good({1, 2, 3}, {0.3, -0.2, 1});
  add_bad({0, 0, 0}, {0, 0, 0});
  add_good({-1, 0.5, 0}, {-1, 0.4, 0.2});
  add_bad({kInf, 0, 0}, {1, 0, 0});
  add_bad({0, kNaN, 0}, {1, 0, 0});
  add_bad({0, 0, 0}, {1, -kInf, 0});
  add_good({0, 0, 7}, {0, 1, 0});
  for (arcus_method m : {ARCUS_METHOD_DP45, ARCUS_METHOD_RK4}) {
    const arcus_advance_params p = m == ARCUS_METHOD_DP45 ? dp45(5.0, 1e-10, 1e-13) : fixed(m, 0.01, 5.0);
    const Trace ref = trace(ctx(), field.get(), p, good);
    const Trace t = trace(ctx(), field.get(), p, mixed);
    ASSERT_EQ(ref.status, ARCUS_SUCCESS);
    EXPECT_EQ(t.status, ARCUS_ERROR_INVALID_RAYS);
    ASSERT_TRUE(t.job) << "the job must come back with ARCUS_ERROR_INVALID_RAYS";
    ASSERT_EQ(t.size(), mixed.size());
    size_t g = 0;
    for (size_t i = 0; i < mixed.size(); ++i) {
      if (bad[i]) {
        EXPECT_EQ(t.ray_status[i], ARCUS_RAY_INVALID_INPUT) << "ray " << i;
        continue;
      }
      EXPECT_EQ(t.ray_status[i], ARCUS_RAY_DONE) << "ray " << i;
      // Bitwise: same numbers whatever shares the ray's lanes.
      EXPECT_EQ(std::memcmp(&t.positions[3 * i], &ref.positions[3 * g], 3 * sizeof(double)), 0) << "ray " << i;
      EXPECT_EQ(std::memcmp(&t.directions[3 * i], &ref.directions[3 * g], 3 * sizeof(double)), 0) << "ray " << i;
      EXPECT_EQ(std::memcmp(&t.lengths[i], &ref.lengths[g], sizeof(double)), 0) << "ray " << i;
      EXPECT_EQ(t.steps[i], ref.steps[g]) << "ray " << i;
      // Against the closed form: n = 1 + G·r; along the catenary n ≥ A = n·|d across G|
      // and the curvature is ≤ |G|/A.
      const V3 G{0.05, 0.2, -0.1};
      const RayState want = catenary_end(1.0, G, mixed.origin(i), mixed.direction(i), 5.0);
      const V3 d = normalize(mixed.direction(i)), gh = normalize(G);
      const double A = (1.0 + dot(G, mixed.origin(i))) * norm(d - dot(d, gh) * gh);
      PathScale scale{norm(want.pos), 5.0};
      scale.turning = angle_between(d, want.dir);
      scale.n_min = A;
      // RK4 at h = 0.01 errs by ≲ h⁴·∫κ⁴ds ≤ h⁴·κ_max³·turning (test_curved_hard_cases.cpp,
      // SteepLinearGradientHundredPerMetre), plus 500 steps' rounding.
      const double kappa = norm(G) / A;
      const double bound = m == ARCUS_METHOD_DP45 ? dp45_bound(1e-10, 1e-13, scale)
                                                  : 1e-8 * kappa * kappa * kappa * scale.turning + 500 * 4 * 2.2e-16 * 10;
      EXPECT_LT(distance(t.pos(i), want.pos), bound) << "ray " << i;
      ++g;
    }
  }
}

TEST_F(BadInput, NonPositiveOrNonFiniteAdvanceParametersAreRejected) {
  auto field = linear(1.0, {0, 0.1, 0});
  ASSERT_TRUE(field);
  const double o[3] = {0, 0, 0}, d[3] = {1, 0, 0};
  auto run = [&](const arcus_advance_params& p) {
    arcus_job_t* job = reinterpret_cast<arcus_job_t*>(0x1);  // must be overwritten with NULL
    const arcus_status st = arcus_curved_advance(ctx(), field.get(), &p, 1, o, d, nullptr, &job);
    EXPECT_EQ(job, nullptr) << "no job on " << arcus_status_string(st);
    if (job && job != reinterpret_cast<arcus_job_t*>(0x1)) arcus_job_release(job);
    return st;
  };
  arcus_advance_params p = dp45(1.0, 1e-9, 1e-12);
  for (double bad : {0.0, -1.0, kNaN, kInf}) {
    p = dp45(bad, 1e-9, 1e-12);
    expect_invalid(run(p), "length", "length");
  }
  for (double bad : {0.0, -1e-9, kNaN}) {
    p = dp45(1.0, bad, 1e-12);
    expect_invalid(run(p), "rtol", "rtol");
    p = dp45(1.0, 1e-9, bad);
    expect_invalid(run(p), "atol", "atol");
  }
  for (double bad : {0.0, -0.1, kNaN}) {
    p = fixed(ARCUS_METHOD_RK4, bad, 1.0);
    expect_invalid(run(p), "step", "fixed step");
  }
  p = dp45(1.0, 1e-9, 1e-12);
  p.method = static_cast<arcus_method>(42);
  expect_invalid(run(p), "method", "method");
  p = dp45(1.0, 1e-9, 1e-12);
  p.precision = static_cast<arcus_precision>(42);
  expect_invalid(run(p), "precision", "precision");
}

TEST_F(BadInput, BadFieldParametersAreRejected) {
  arcus_field_t* f = nullptr;
  const double c[3] = {0, 0, 0}, g[3] = {0, 0.1, 0};
  const double nan3[3] = {0, kNaN, 0};
  expect_invalid(arcus_field_create_constant(ctx(), kNaN, &f), nullptr, "constant NaN");
  expect_invalid(arcus_field_create_constant(ctx(), 0.0, &f), nullptr, "constant 0");
  expect_invalid(arcus_field_create_linear(ctx(), kNaN, g, &f), "n0", "linear n0 NaN");
  expect_invalid(arcus_field_create_linear(ctx(), 1.0, nan3, &f), "gradient", "linear gradient NaN");
  expect_invalid(arcus_field_create_linear_n2(ctx(), 1.0, nan3, &f), nullptr, "linear n2 k NaN");
  expect_invalid(arcus_field_create_luneburg(ctx(), c, 0.0, &f), "radius", "Luneburg radius 0");
  expect_invalid(arcus_field_create_luneburg(ctx(), c, -2.0, &f), "radius", "Luneburg radius < 0");
  expect_invalid(arcus_field_create_luneburg(ctx(), nan3, 1.0, &f), "center", "Luneburg centre NaN");
  expect_invalid(arcus_field_create_fisheye(ctx(), c, -1.0, 1.0, &f), "radius", "fish-eye radius");
  expect_invalid(arcus_field_create_fisheye(ctx(), c, 1.0, 0.0, &f), "n0", "fish-eye n0");
  arcus_atmosphere_desc d;
  arcus_atmosphere_desc_init(&d);
  d.wavelength = 200.0;
  expect_invalid(arcus_field_create_atmosphere(ctx(), &d, &f), "wavelength", "wavelength below 300 nm");
  d.wavelength = 1800.0;
  expect_invalid(arcus_field_create_atmosphere(ctx(), &d, &f), "wavelength", "wavelength above 1690 nm");
  arcus_atmosphere_desc_init(&d);
  d.sea_level_temperature = -5.0;
  expect_invalid(arcus_field_create_atmosphere(ctx(), &d, &f), "temperature", "negative temperature");
  arcus_atmosphere_desc_init(&d);
  d.sea_level_pressure = 0.0;
  expect_invalid(arcus_field_create_atmosphere(ctx(), &d, &f), "pressure", "zero pressure");
  arcus_atmosphere_desc_init(&d);
  d.inversion_count = 1;
  d.inversions = nullptr;
  expect_invalid(arcus_field_create_atmosphere(ctx(), &d, &f), "inversions", "inversions NULL with count 1");
  const arcus_inversion nan_inv{0.0, kNaN, 5.0};
  d.inversions = &nan_inv;
  expect_invalid(arcus_field_create_atmosphere(ctx(), &d, &f), "inversion", "NaN inversion");
  EXPECT_EQ(f, nullptr);
}

TEST(DeviceErrors, UnknownDeviceIndexIsDeviceNotFoundWithAMessage) {
  arcus_context_t* c = nullptr;
  EXPECT_EQ(arcus_context_create(999, &c), ARCUS_ERROR_DEVICE_NOT_FOUND);
  EXPECT_EQ(c, nullptr);
  const char* msg = arcus_last_error();
  ASSERT_NE(msg, nullptr);
  EXPECT_TRUE(contains_ci(msg, "device")) << msg;
  EXPECT_TRUE(contains_ci(msg, "999")) << msg;
  if (c) arcus_context_release(c);
}

TEST(NullPointers, EveryGlobalFunctionRejectsNullOutputs) {
  int a = 0;
  EXPECT_EQ(arcus_get_version(nullptr, &a, &a), ARCUS_ERROR_INVALID_ARGUMENT);
  EXPECT_EQ(arcus_get_version(&a, nullptr, &a), ARCUS_ERROR_INVALID_ARGUMENT);
  EXPECT_EQ(arcus_get_version(&a, &a, nullptr), ARCUS_ERROR_INVALID_ARGUMENT);
  EXPECT_EQ(arcus_device_count(nullptr), ARCUS_ERROR_INVALID_ARGUMENT);
  EXPECT_EQ(arcus_device_get_info(0, nullptr), ARCUS_ERROR_INVALID_ARGUMENT);
  EXPECT_EQ(arcus_context_create(ARCUS_DEVICE_DEFAULT, nullptr), ARCUS_ERROR_INVALID_ARGUMENT);
  EXPECT_GT(std::strlen(arcus_last_error()), 0u);
  EXPECT_EQ(arcus_context_retain(nullptr), ARCUS_ERROR_INVALID_ARGUMENT);
  EXPECT_EQ(arcus_context_release(nullptr), ARCUS_ERROR_INVALID_ARGUMENT);
  arcus_device_info info;
  EXPECT_EQ(arcus_context_get_device(nullptr, &info), ARCUS_ERROR_INVALID_ARGUMENT);
  EXPECT_NE(arcus_context_last_error(nullptr), nullptr);
  EXPECT_EQ(arcus_context_set_error_callback(nullptr, nullptr, nullptr), ARCUS_ERROR_INVALID_ARGUMENT);
  EXPECT_EQ(arcus_atmosphere_desc_init(nullptr), ARCUS_ERROR_INVALID_ARGUMENT);
  EXPECT_EQ(arcus_advance_params_init(nullptr), ARCUS_ERROR_INVALID_ARGUMENT);
  EXPECT_EQ(arcus_features_to_string(ARCUS_FEATURE_CURVED_DP45, nullptr, 64), ARCUS_ERROR_INVALID_ARGUMENT);
  EXPECT_EQ(arcus_field_retain(nullptr), ARCUS_ERROR_INVALID_ARGUMENT);
  EXPECT_EQ(arcus_field_release(nullptr), ARCUS_ERROR_INVALID_ARGUMENT);
  arcus_field_kind kind;
  EXPECT_EQ(arcus_field_get_kind(nullptr, &kind), ARCUS_ERROR_INVALID_ARGUMENT);
  const double p[3] = {0, 0, 0};
  double n;
  EXPECT_EQ(arcus_field_evaluate(nullptr, 1, p, &n, nullptr), ARCUS_ERROR_INVALID_ARGUMENT);
  EXPECT_EQ(arcus_job_retain(nullptr), ARCUS_ERROR_INVALID_ARGUMENT);
  EXPECT_EQ(arcus_job_release(nullptr), ARCUS_ERROR_INVALID_ARGUMENT);
  size_t count;
  EXPECT_EQ(arcus_job_get_count(nullptr, &count), ARCUS_ERROR_INVALID_ARGUMENT);
  EXPECT_EQ(arcus_job_get_curved_end_states(nullptr, nullptr, nullptr, nullptr, nullptr, nullptr),
                                            ARCUS_ERROR_INVALID_ARGUMENT);
  EXPECT_EQ(arcus_job_get_curved_path_size(nullptr, &count), ARCUS_ERROR_INVALID_ARGUMENT);
  uint64_t off[2];
  EXPECT_EQ(arcus_job_get_curved_paths(nullptr, off, nullptr, nullptr), ARCUS_ERROR_INVALID_ARGUMENT);
  arcus_features features;
  EXPECT_EQ(arcus_job_get_features(nullptr, &features), ARCUS_ERROR_INVALID_ARGUMENT);
  arcus_job_stats stats;
  EXPECT_EQ(arcus_job_get_stats(nullptr, &stats), ARCUS_ERROR_INVALID_ARGUMENT);
}

TEST_F(BadInput, EveryContextFunctionRejectsNullArguments) {
  const double c[3] = {0, 0, 0}, g[3] = {0, 0.1, 0}, one[3] = {1, 1, 1};
  const uint32_t dims[3] = {2, 2, 2};
  const std::vector<double> values(8, 1.0);
  arcus_field_t* f = nullptr;
  arcus_device_info info;
  EXPECT_EQ(arcus_context_get_device(ctx(), nullptr), ARCUS_ERROR_INVALID_ARGUMENT);
  // Every factory: NULL context, NULL output, NULL array argument.
  EXPECT_EQ(arcus_field_create_constant(nullptr, 1.0, &f), ARCUS_ERROR_INVALID_ARGUMENT);
  expect_invalid(arcus_field_create_constant(ctx(), 1.0, nullptr), "out", "constant out");
  EXPECT_EQ(arcus_field_create_linear(nullptr, 1.0, g, &f), ARCUS_ERROR_INVALID_ARGUMENT);
  expect_invalid(arcus_field_create_linear(ctx(), 1.0, nullptr, &f), "gradient", "linear gradient");
  expect_invalid(arcus_field_create_linear(ctx(), 1.0, g, nullptr), "out", "linear out");
  EXPECT_EQ(arcus_field_create_linear_n2(nullptr, 1.0, g, &f), ARCUS_ERROR_INVALID_ARGUMENT);
  expect_invalid(arcus_field_create_linear_n2(ctx(), 1.0, nullptr, &f), nullptr, "linear n2 k");
  expect_invalid(arcus_field_create_linear_n2(ctx(), 1.0, g, nullptr), "out", "linear n2 out");
  EXPECT_EQ(arcus_field_create_luneburg(nullptr, c, 1.0, &f), ARCUS_ERROR_INVALID_ARGUMENT);
  expect_invalid(arcus_field_create_luneburg(ctx(), nullptr, 1.0, &f), "center", "Luneburg centre");
  expect_invalid(arcus_field_create_luneburg(ctx(), c, 1.0, nullptr), "out", "Luneburg out");
  EXPECT_EQ(arcus_field_create_fisheye(nullptr, c, 1.0, 1.0, &f), ARCUS_ERROR_INVALID_ARGUMENT);
  expect_invalid(arcus_field_create_fisheye(ctx(), nullptr, 1.0, 1.0, &f), "center", "fish-eye centre");
  expect_invalid(arcus_field_create_fisheye(ctx(), c, 1.0, 1.0, nullptr), "out", "fish-eye out");
  arcus_atmosphere_desc d;
  arcus_atmosphere_desc_init(&d);
  EXPECT_EQ(arcus_field_create_atmosphere(nullptr, &d, &f), ARCUS_ERROR_INVALID_ARGUMENT);
  expect_invalid(arcus_field_create_atmosphere(ctx(), nullptr, &f), "desc", "atmosphere desc");
  expect_invalid(arcus_field_create_atmosphere(ctx(), &d, nullptr), "out", "atmosphere out");
  EXPECT_EQ(arcus_field_create_grid(nullptr, values.data(), dims, c, one, &f), ARCUS_ERROR_INVALID_ARGUMENT);
  expect_invalid(arcus_field_create_grid(ctx(), nullptr, dims, c, one, &f), "values", "grid values");
  expect_invalid(arcus_field_create_grid(ctx(), values.data(), nullptr, c, one, &f), "dims", "grid dims");
  expect_invalid(arcus_field_create_grid(ctx(), values.data(), dims, nullptr, one, &f), "origin", "grid origin");
  expect_invalid(arcus_field_create_grid(ctx(), values.data(), dims, c, nullptr, &f), "spacing", "grid spacing");
  expect_invalid(arcus_field_create_grid(ctx(), values.data(), dims, c, one, nullptr), "out", "grid out");
  EXPECT_EQ(arcus_field_create_grid_from_file(nullptr, "x", ARCUS_FLOAT64, dims, c, one, &f),
            ARCUS_ERROR_INVALID_ARGUMENT);
  expect_invalid(arcus_field_create_grid_from_file(ctx(), nullptr, ARCUS_FLOAT64, dims, c, one, &f), "path",
                 "grid file path");
  {
    // A readable file of the right size, so that only the null argument is wrong.
    const std::string path = temp_path("null_args");
    std::ofstream(path, std::ios::binary).write(reinterpret_cast<const char*>(values.data()),
                                                std::streamsize(values.size() * sizeof(double)));
    const char* p = path.c_str();
    expect_invalid(arcus_field_create_grid_from_file(ctx(), p, ARCUS_FLOAT64, nullptr, c, one, &f), "dims",
                   "grid file dims");
    expect_invalid(arcus_field_create_grid_from_file(ctx(), p, ARCUS_FLOAT64, dims, nullptr, one, &f), "origin",
                   "grid file origin");
    expect_invalid(arcus_field_create_grid_from_file(ctx(), p, ARCUS_FLOAT64, dims, c, nullptr, &f), "spacing",
                   "grid file spacing");
    expect_invalid(arcus_field_create_grid_from_file(ctx(), p, ARCUS_FLOAT64, dims, c, one, nullptr), "out",
                   "grid file out");
    expect_invalid(arcus_field_create_grid_from_file(ctx(), p, static_cast<arcus_scalar_type>(7), dims, c, one, &f),
                   "type", "grid file scalar type");
    std::remove(path.c_str());
  }
  EXPECT_EQ(f, nullptr);
  (void)info;

  // Field accessors with a valid field and NULL outputs.
  auto field = linear(1.0, {0, 0.1, 0});
  ASSERT_TRUE(field);
  EXPECT_EQ(arcus_field_get_kind(field.get(), nullptr), ARCUS_ERROR_INVALID_ARGUMENT);
  double n;
  EXPECT_EQ(arcus_field_evaluate(field.get(), 1, nullptr, &n, nullptr), ARCUS_ERROR_INVALID_ARGUMENT);
  EXPECT_EQ(arcus_field_evaluate(field.get(), 1, c, nullptr, nullptr), ARCUS_ERROR_INVALID_ARGUMENT);

  // arcus_curved_advance: each pointer argument NULL in turn.
  arcus_advance_params p = dp45(1.0, 1e-9, 1e-12);
  const double o[3] = {0, 0, 0}, dir[3] = {1, 0, 0};
  arcus_job_t* job = nullptr;
  EXPECT_EQ(arcus_curved_advance(nullptr, field.get(), &p, 1, o, dir, nullptr, &job), ARCUS_ERROR_INVALID_ARGUMENT);
  expect_invalid(arcus_curved_advance(ctx(), nullptr, &p, 1, o, dir, nullptr, &job), "field", "advance field");
  expect_invalid(arcus_curved_advance(ctx(), field.get(), nullptr, 1, o, dir, nullptr, &job), "params", "advance params");
  expect_invalid(arcus_curved_advance(ctx(), field.get(), &p, 1, nullptr, dir, nullptr, &job), "origins", "advance origins");
  expect_invalid(arcus_curved_advance(ctx(), field.get(), &p, 1, o, nullptr, nullptr, &job), "directions", "advance directions");
  expect_invalid(arcus_curved_advance(ctx(), field.get(), &p, 1, o, dir, nullptr, nullptr), "job", "advance job");
  EXPECT_EQ(job, nullptr);

  // Job accessors with a valid job and NULL outputs.
  Rays rays;
  rays.add({0, 0, 0}, {1, 0, 0});
  const Trace t = trace(ctx(), field.get(), p, rays);
  ASSERT_TRUE(t.job);
  EXPECT_EQ(arcus_job_get_count(t.job.get(), nullptr), ARCUS_ERROR_INVALID_ARGUMENT);
  EXPECT_EQ(arcus_job_get_curved_path_size(t.job.get(), nullptr), ARCUS_ERROR_INVALID_ARGUMENT);
  EXPECT_EQ(arcus_job_get_features(t.job.get(), nullptr), ARCUS_ERROR_INVALID_ARGUMENT);
  EXPECT_EQ(arcus_job_get_stats(t.job.get(), nullptr), ARCUS_ERROR_INVALID_ARGUMENT);
}

TEST_F(BadInput, PathOverflowKeepsTheJobAndReportsWhatWasNeeded) {
  auto field = linear(1.0, {0, 0.5, 0});
  ASSERT_TRUE(field);
  arcus_advance_params p = dp45(20.0, 1e-10, 1e-13);
  p.record_path = 1;
  p.path_capacity = 3;
  Rays rays;
  rays.add({0, 0, 0}, {1, 0.2, 0});
  rays.add({0, 1, 0}, {1, -0.5, 0.3});
  const Trace t = trace(ctx(), field.get(), p, rays);
  EXPECT_EQ(t.status, ARCUS_ERROR_PATH_OVERFLOW);
  ASSERT_TRUE(t.job) << "the job must come back with ARCUS_ERROR_PATH_OVERFLOW";
  size_t total = 0;
  ASSERT_EQ(arcus_job_get_curved_path_size(t.job.get(), &total), ARCUS_SUCCESS);
  std::vector<uint64_t> offsets(rays.size() + 1), needed(rays.size());
  std::vector<double> points(3 * total);
  ASSERT_EQ(arcus_job_get_curved_paths(t.job.get(), offsets.data(), points.data(), needed.data()), ARCUS_SUCCESS);
  for (size_t i = 0; i < rays.size(); ++i) {
    const uint64_t kept = offsets[i + 1] - offsets[i];
    EXPECT_LE(kept, 3u) << "ray " << i;
    EXPECT_GT(needed[i], kept) << "ray " << i;
    // The end states are still complete: the rays ran their full length.
    EXPECT_EQ(t.ray_status[i], ARCUS_RAY_DONE) << "ray " << i;
    EXPECT_NEAR(t.lengths[i], 20.0, 1e-9);
    // The full path has the origin and one point per accepted step.
    EXPECT_EQ(needed[i], t.steps[i] + 1) << "ray " << i;
  }
  // The same job with enough room is not an overflow, and keeps what was needed.
  p.path_capacity = 0;  // DP45: 4096 points
  const Trace ok = trace(ctx(), field.get(), p, rays);
  EXPECT_EQ(ok.status, ARCUS_SUCCESS);
  ASSERT_TRUE(ok.job);
  std::vector<uint64_t> needed_ok(rays.size()), offsets_ok(rays.size() + 1);
  ASSERT_EQ(arcus_job_get_curved_paths(ok.job.get(), offsets_ok.data(), nullptr, needed_ok.data()), ARCUS_SUCCESS);
  for (size_t i = 0; i < rays.size(); ++i) {
    EXPECT_EQ(needed_ok[i], needed[i]) << "ray " << i;
    EXPECT_EQ(offsets_ok[i + 1] - offsets_ok[i], needed_ok[i]) << "ray " << i;
  }
}

TEST_F(BadInput, ErrorCallbackSeesEveryErrorUntilRemoved) {
  struct Seen {
    int calls = 0;
    arcus_status status = ARCUS_SUCCESS;
    std::string message;
  } seen;
  auto cb = [](void* user, arcus_status st, const char* msg) {
    Seen* s = static_cast<Seen*>(user);
    ++s->calls;
    s->status = st;
    s->message = msg ? msg : "(null)";
  };
  ASSERT_EQ(arcus_context_set_error_callback(ctx(), cb, &seen), ARCUS_SUCCESS);
  const double c[3] = {0, 0, 0};
  arcus_field_t* f = nullptr;
  EXPECT_EQ(arcus_field_create_luneburg(ctx(), c, -1.0, &f), ARCUS_ERROR_INVALID_ARGUMENT);
  EXPECT_EQ(seen.calls, 1);
  EXPECT_EQ(seen.status, ARCUS_ERROR_INVALID_ARGUMENT);
  EXPECT_EQ(seen.message, std::string(arcus_context_last_error(ctx())));
  EXPECT_TRUE(contains_ci(seen.message.c_str(), "radius")) << seen.message;
  // A successful call does not call it.
  auto ok = constant(1.0);
  EXPECT_EQ(seen.calls, 1);
  // An error in arcus_curved_advance does.
  arcus_advance_params p = dp45(-1.0, 1e-9, 1e-12);
  const double o[3] = {0, 0, 0}, d[3] = {1, 0, 0};
  arcus_job_t* job = nullptr;
  EXPECT_EQ(arcus_curved_advance(ctx(), ok.get(), &p, 1, o, d, nullptr, &job), ARCUS_ERROR_INVALID_ARGUMENT);
  EXPECT_EQ(seen.calls, 2);
  EXPECT_TRUE(contains_ci(seen.message.c_str(), "length")) << seen.message;
  // Removed: no more calls.
  ASSERT_EQ(arcus_context_set_error_callback(ctx(), nullptr, nullptr), ARCUS_SUCCESS);
  EXPECT_EQ(arcus_field_create_luneburg(ctx(), c, -1.0, &f), ARCUS_ERROR_INVALID_ARGUMENT);
  EXPECT_EQ(seen.calls, 2);
}

TEST_F(BadInput, LastErrorIsPerContext) {
  arcus_context_t* other = nullptr;
  ASSERT_EQ(arcus_context_create(ARCUS_DEVICE_DEFAULT, &other), ARCUS_SUCCESS);
  ContextPtr guard(other);
  const double c[3] = {0, 0, 0};
  arcus_field_t* f = nullptr;
  EXPECT_EQ(arcus_field_create_luneburg(ctx(), c, -1.0, &f), ARCUS_ERROR_INVALID_ARGUMENT);
  EXPECT_EQ(arcus_field_create_fisheye(other, c, 1.0, -3.0, &f), ARCUS_ERROR_INVALID_ARGUMENT);
  EXPECT_TRUE(contains_ci(arcus_context_last_error(other), "n0")) << arcus_context_last_error(other);
  // The suite's context still holds its own error, not the other context's.
  EXPECT_TRUE(contains_ci(arcus_context_last_error(ctx()), "radius")) << arcus_context_last_error(ctx());
  EXPECT_FALSE(contains_ci(arcus_context_last_error(ctx()), "n0")) << arcus_context_last_error(ctx());
}

// The error callback runs after the context's lock is released, so it may call arcus.
TEST_F(BadInput, ErrorCallbackMayCallTheLibrary) {
  struct Seen {
    arcus_context_t* ctx;
    std::atomic<int> calls{0};
    arcus_status device_status = ARCUS_ERROR_INVALID_ARGUMENT;
  } seen{ctx()};
  auto callback = [](void* user, arcus_status, const char*) {
    auto* s = static_cast<Seen*>(user);
    arcus_device_info info;
    s->device_status = arcus_context_get_device(s->ctx, &info);
    s->calls++;
  };
  ASSERT_EQ(arcus_context_set_error_callback(ctx(), callback, &seen), ARCUS_SUCCESS);
  EXPECT_EQ(arcus_context_get_device(ctx(), nullptr), ARCUS_ERROR_INVALID_ARGUMENT);
  EXPECT_EQ(arcus_context_set_error_callback(ctx(), nullptr, nullptr), ARCUS_SUCCESS);
  EXPECT_EQ(seen.calls.load(), 1);
  EXPECT_EQ(seen.device_status, ARCUS_SUCCESS);
}

// In float, a direction that is zero after conversion is invalid, and the call says so.
TEST_F(BadInput, DirectionThatVanishesInFloatIsReportedAsInvalid) {
  FieldPtr medium = linear(1.0, {0, 0.1, 0});
  ASSERT_TRUE(medium);
  Rays rays;
  rays.add({0, 0, 0}, {1e-50, 0, 0});
  rays.add({0, 0, 0}, {1, 0, 0});
  arcus_advance_params p = fixed(ARCUS_METHOD_RK4, 0.1, 1.0);
  p.precision = ARCUS_PRECISION_FLOAT;
  Trace t = trace(ctx(), medium.get(), p, rays);
  EXPECT_EQ(t.status, ARCUS_ERROR_INVALID_RAYS);
  EXPECT_EQ(t.ray_status[0], ARCUS_RAY_INVALID_INPUT);
  EXPECT_EQ(t.ray_status[1], ARCUS_RAY_DONE);
  EXPECT_TRUE(contains_ci(arcus_context_last_error(ctx()), "float")) << last_error();
}

// Parameters that do not survive conversion to float are rejected, not run as 0 or inf.
TEST_F(BadInput, ParametersOutsideFloatRangeAreRejected) {
  FieldPtr medium = linear(1.0, {0, 0.1, 0});
  ASSERT_TRUE(medium);
  Rays rays;
  rays.add({0, 0, 0}, {1, 0, 0});
  arcus_advance_params p = fixed(ARCUS_METHOD_RK4, 1e-50, 1.0);
  p.precision = ARCUS_PRECISION_FLOAT;
  Trace t = trace(ctx(), medium.get(), p, rays);
  EXPECT_EQ(t.status, ARCUS_ERROR_INVALID_ARGUMENT);
  EXPECT_TRUE(contains_ci(arcus_context_last_error(ctx()), "params.step")) << last_error();
  arcus_advance_params q = dp45(1.0, 1e-6, 1e-9);
  q.min_step = 2.0;  // more than the length
  t = trace(ctx(), medium.get(), q, rays);
  EXPECT_EQ(t.status, ARCUS_ERROR_INVALID_ARGUMENT);
  EXPECT_TRUE(contains_ci(arcus_context_last_error(ctx()), "min_step")) << last_error();
}

}  // namespace
