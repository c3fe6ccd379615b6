// Rays that cannot go on end FAILED with the reason available (arcus_job_get_curved_failures),
// never DONE at a meaningless point; fields whose derived quantities would not be finite
// are refused at creation; a job's path memory is checked before anything is allocated;
// a malformed layout override (ARCUS_LANES) is an error, not a guess.
#include <fcntl.h>
#include <sys/mman.h>
#include <sys/resource.h>
#include <sys/stat.h>
#include <unistd.h>

#include <chrono>
#include <cstdlib>
#include <future>

#include "test_util.h"

using namespace arcus_test;

namespace {

class Failures : public ArcusTest {
 protected:
  std::vector<int32_t> failures(const Trace& t) {
    std::vector<int32_t> f(t.size(), -1);
    EXPECT_EQ(arcus_job_get_curved_failures(t.job.get(), f.data()), ARCUS_SUCCESS);
    return f;
  }
};

TEST_F(Failures, ARayThatReachesNOfZeroFailsForThatReason) {
  // n = 1 − y: a ray going straight up has v_y = n = 1 − s and dr/ds = 1, so it reaches
  // n = 0 at y = 1 and would go on into n < 0 as if nothing happened.
  auto field = linear(1.0, {0, -1, 0});
  ASSERT_TRUE(field);
  Rays rays;
  rays.add({0, 0, 0}, {0, 1, 0});   // straight up: fails
  rays.add({0, 0, 0}, {1, 1, 0});   // at 45°: turns where n = cos 45° and stays in n > 0
  // y = 1 is a singular point of the ray equation (v = 0 there): with small fixed steps
  // the rounding of s makes the numerical ray turn back just short of it, as every ray a
  // little off vertical does.  Steps of 0.3 m take the stages of a step across it.
  std::vector<arcus_advance_params> jobs{dp45(2.0, 1e-9, 1e-12), fixed(ARCUS_METHOD_RK4, 0.3, 2.0),
                                         fixed(ARCUS_METHOD_EULER, 0.01, 2.0)};
  arcus_advance_params boxed = fixed(ARCUS_METHOD_RK2, 0.3, 2.0);
  set_box(&boxed, {-10, -10, -10}, {10, 10, 10});
  jobs.push_back(boxed);
  arcus_advance_params single = dp45(2.0, 1e-6, 1e-9);
  single.precision = ARCUS_PRECISION_FLOAT;
  jobs.push_back(single);
  for (size_t j = 0; j < jobs.size(); ++j) {
    const Trace t = trace(ctx(), field.get(), jobs[j], rays);
    ASSERT_EQ(t.status, ARCUS_SUCCESS) << "job " << j << ": " << last_error();
    const std::vector<int32_t> why = failures(t);
    EXPECT_EQ(t.ray_status[0], ARCUS_RAY_FAILED) << "job " << j;
    EXPECT_EQ(why[0], ARCUS_FAILURE_INDEX_NOT_POSITIVE) << "job " << j;
    // It stopped before n = 0: at the last good state (fixed steps without a box: the
    // state at the start of the slice in which it failed, here the origin).
    EXPECT_LE(t.pos(0)[1], 1.0) << "job " << j;
    EXPECT_LE(t.lengths[0], 1.0) << "job " << j;
    EXPECT_TRUE(finite(t.pos(0)) && finite(t.dir(0))) << "job " << j;
    EXPECT_EQ(t.ray_status[1], ARCUS_RAY_DONE) << "job " << j;
    EXPECT_EQ(why[1], ARCUS_FAILURE_NONE) << "job " << j;
  }
}

TEST_F(Failures, AStateThatOverflowsFailsAsNotFinite) {
  // n = 1 + 1e308·(x + y): n and v overflow within a step of any size.
  auto field = linear(1.0, {1e308, 1e308, 0});
  ASSERT_TRUE(field);
  Rays rays;
  rays.add({0, 0, 0}, {1, 1, 0});
  for (const arcus_advance_params& p : {dp45(1.0, 1e-9, 1e-12), fixed(ARCUS_METHOD_RK4, 0.1, 1.0)}) {
    const Trace t = trace(ctx(), field.get(), p, rays);
    ASSERT_EQ(t.status, ARCUS_SUCCESS) << last_error();
    EXPECT_EQ(t.ray_status[0], ARCUS_RAY_FAILED) << "method " << p.method;
    EXPECT_EQ(failures(t)[0], ARCUS_FAILURE_NOT_FINITE) << "method " << p.method;
  }
}

TEST_F(Failures, AToleranceThatCannotBeMetFailsForThatReason) {
  auto field = linear(1.0, {0, 0.5, 0});
  ASSERT_TRUE(field);
  Rays rays;
  rays.add({0, 0, 0}, {1, 0.2, 0});
  arcus_advance_params p = dp45(10.0, 1e-14, 1e-16);
  p.step = 1.0;
  p.min_step = 0.5;
  const Trace t = trace(ctx(), field.get(), p, rays);
  ASSERT_EQ(t.status, ARCUS_SUCCESS);
  EXPECT_EQ(t.ray_status[0], ARCUS_RAY_FAILED);
  EXPECT_EQ(failures(t)[0], ARCUS_FAILURE_TOLERANCE);
  EXPECT_EQ(t.lengths[0], 0.0) << "no step was accepted";
}

TEST_F(Failures, HugeIndexStillGivesAUnitEndDirection) {
  // |v| = n ≈ 1e200: |v|² overflows a double (and 1e20 a float), so the end direction
  // must be normalised without squaring v (it came out (0, 0, 0) with DONE).  The
  // relative gradient is 1e-10 /m, so the ray stays within 1e-8 rad of its start.
  for (int single = 0; single < 2; ++single) {
    const double n0 = single ? 1e20 : 1e200;
    auto field = linear(n0, {0, n0 * 1e-10, 0});
    ASSERT_TRUE(field);
    Rays rays;
    rays.add({0, 0, 0}, {3, 4, 0});
    arcus_advance_params p = fixed(ARCUS_METHOD_RK4, 0.5, 10.0);
    if (single) p.precision = ARCUS_PRECISION_FLOAT;
    const Trace t = trace(ctx(), field.get(), p, rays);
    ASSERT_EQ(t.status, ARCUS_SUCCESS) << last_error();
    EXPECT_EQ(t.ray_status[0], ARCUS_RAY_DONE);
    EXPECT_NEAR(norm(t.dir(0)), 1.0, single ? 1e-6 : 1e-15);
    EXPECT_LT(angle_between(t.dir(0), {0.6, 0.8, 0}), single ? 1e-6 : 1e-8);
  }
}

TEST_F(Failures, FieldsWhoseDerivedQuantitiesAreNotFiniteAreRefused) {
  arcus_field_t* f = nullptr;
  const double c[3] = {0, 0, 0};
  // 1/R² is what the kernels use: R = 1e-200 squares to 0, R = 1e200 to infinity.
  for (double r : {1e-200, 1e200}) {
    EXPECT_EQ(arcus_field_create_luneburg(ctx(), c, r, &f), ARCUS_ERROR_INVALID_ARGUMENT) << r;
    EXPECT_TRUE(contains_ci(last_error().c_str(), "radius")) << last_error();
    EXPECT_EQ(arcus_field_create_fisheye(ctx(), c, r, 1.0, &f), ARCUS_ERROR_INVALID_ARGUMENT) << r;
  }
  // 1/spacing is infinite for a subnormal spacing; the extent overflows for a huge one.
  const uint32_t dims[3] = {2, 4, 2};
  const std::vector<double> values(16, 1.0);
  for (double s : {1e-320, 1e308}) {  // 3·1e308 = inf
    const double spacing[3] = {1, s, 1};
    EXPECT_EQ(arcus_field_create_grid(ctx(), values.data(), dims, c, spacing, &f), ARCUS_ERROR_INVALID_ARGUMENT) << s;
    EXPECT_TRUE(contains_ci(last_error().c_str(), "spacing[1]")) << last_error();
  }
  EXPECT_EQ(f, nullptr);
  // Numbers in messages read as numbers: 1e308, not 310 digits.
  EXPECT_EQ(arcus_field_create_constant(ctx(), -1e308, &f), ARCUS_ERROR_INVALID_ARGUMENT);
  EXPECT_TRUE(contains_ci(last_error().c_str(), "-1e+308")) << last_error();
  EXPECT_LT(last_error().size(), 100u) << last_error();
}

TEST_F(Failures, AtmosphereLimitsAndTheirMessages) {
  arcus_atmosphere_desc d;
  arcus_atmosphere_desc_init(&d);
  arcus_field_t* f = nullptr;
  // The kernels scan every layer at every evaluation: the count is capped.
  std::vector<arcus_inversion> many(ARCUS_MAX_INVERSIONS + 1, arcus_inversion{0.0, 10.0, 0.1});
  d.inversion_count = static_cast<uint32_t>(many.size());
  d.inversions = many.data();
  const auto start = std::chrono::steady_clock::now();
  EXPECT_EQ(arcus_field_create_atmosphere(ctx(), &d, &f), ARCUS_ERROR_INVALID_ARGUMENT);
  EXPECT_LT(std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count(), 1.0);
  EXPECT_TRUE(contains_ci(last_error().c_str(), "1024")) << last_error();
  d.inversion_count = ARCUS_MAX_INVERSIONS;  // the most: accepted
  EXPECT_EQ(arcus_field_create_atmosphere(ctx(), &d, &f), ARCUS_SUCCESS) << last_error();
  FieldPtr guard(f);
  // A cold sea level with no inversions is blamed on the sea-level temperature.
  arcus_atmosphere_desc_init(&d);
  d.sea_level_temperature = 151.0;
  EXPECT_EQ(arcus_field_create_atmosphere(ctx(), &d, &f), ARCUS_ERROR_INVALID_ARGUMENT);
  EXPECT_TRUE(contains_ci(last_error().c_str(), "sea_level_temperature")) << last_error();
  EXPECT_FALSE(contains_ci(last_error().c_str(), "inversion")) << last_error();
}

TEST_F(Failures, PathMemoryIsCheckedBeforeAnythingIsAllocated) {
  auto field = linear(1.0, {0, 0.1, 0});
  ASSERT_TRUE(field);
  // A caller's huge path_capacity: ARCUS_ERROR_OUT_OF_MEMORY naming it (not the OpenCL
  // error of a failed allocation).
  Rays rays;
  for (int i = 0; i < 10; ++i) rays.add({0, 0, 0}, {1, 0.01 * i, 0});
  arcus_advance_params p = dp45(1.0, 1e-9, 1e-12);
  p.record_path = 1;
  p.path_capacity = 0x7fffffff;
  Trace t = trace(ctx(), field.get(), p, rays);
  EXPECT_EQ(t.status, ARCUS_ERROR_OUT_OF_MEMORY);
  EXPECT_TRUE(contains_ci(last_error().c_str(), "path_capacity")) << last_error();
  // A fan of 2^26 rays recording paths: refused before a byte is spent on it (the rays
  // themselves are address space the library must not even touch).
  const size_t count = size_t(1) << 26, bytes = 3 * count * sizeof(double);
  void* rays_in = mmap(nullptr, 2 * bytes, PROT_READ, MAP_PRIVATE | MAP_ANONYMOUS | MAP_NORESERVE, -1, 0);
  ASSERT_NE(rays_in, MAP_FAILED);
  struct rusage before, after;
  getrusage(RUSAGE_SELF, &before);
  p.path_capacity = 0;
  arcus_job_t* job = nullptr;
  const double* origins = static_cast<const double*>(rays_in);
  EXPECT_EQ(arcus_curved_advance(ctx(), field.get(), &p, count, origins, origins + 3 * count, nullptr, &job),
                                 ARCUS_ERROR_OUT_OF_MEMORY);
  getrusage(RUSAGE_SELF, &after);
  EXPECT_EQ(job, nullptr);
  EXPECT_TRUE(contains_ci(last_error().c_str(), "record_path")) << last_error();
  EXPECT_LT(after.ru_maxrss - before.ru_maxrss, 100 * 1024) << "kB of peak memory spent on a refused job";
  munmap(rays_in, 2 * bytes);
}

TEST_F(Failures, AMalformedLayoutOverrideIsAnError) {
  auto field = linear(1.0, {0, 0.1, 0});
  ASSERT_TRUE(field);
  Rays rays;
  rays.add({0, 0, 0}, {1, 0, 0});
  for (const char* bad : {"8abc", "4294967304", "3"}) {
    setenv("ARCUS_LANES", bad, 1);
    const Trace t = trace(ctx(), field.get(), dp45(1.0, 1e-9, 1e-12), rays);
    unsetenv("ARCUS_LANES");
    EXPECT_EQ(t.status, ARCUS_ERROR_INVALID_ARGUMENT) << bad;
    EXPECT_TRUE(contains_ci(last_error().c_str(), "ARCUS_LANES")) << last_error();
  }
}

// The default path capacity follows the steps actually taken: max_steps bounds it, and
// the float step count is the kernel's own.
TEST_F(Failures, DefaultPathCapacityFollowsTheStepsTaken) {
  FieldPtr medium = linear(1.0, {0, 0.1, 0});
  ASSERT_TRUE(medium);
  Rays rays;
  rays.add({0, 0, 0}, {1, 0, 0});
  arcus_advance_params p = fixed(ARCUS_METHOD_RK4, 1e-4, 1e4);  // 10⁸ steps, but…
  p.max_steps = 10;                                              // …only 10 taken
  p.record_path = 1;
  Trace t = trace(ctx(), medium.get(), p, rays);
  ASSERT_EQ(t.status, ARCUS_SUCCESS) << last_error();
  EXPECT_EQ(t.ray_status[0], ARCUS_RAY_STEP_LIMIT);
  size_t points = 0;
  ASSERT_EQ(arcus_job_get_curved_path_size(t.job.get(), &points), ARCUS_SUCCESS);
  EXPECT_EQ(points, 11u);

  // A length and step whose step count differs between float and double arithmetic.
  arcus_advance_params q = fixed(ARCUS_METHOD_EULER, 7.210077602228678e-03, 196.71196784464513);
  q.precision = ARCUS_PRECISION_FLOAT;
  q.record_path = 1;
  t = trace(ctx(), medium.get(), q, rays);
  EXPECT_EQ(t.status, ARCUS_SUCCESS) << last_error();
}

}  // namespace
