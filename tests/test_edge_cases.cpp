// Edge cases found in review: each test failed before its fix.
#include <gtest/gtest.h>

#include <atomic>
#include <cmath>
#include <cstdio>
#include <string>

#include "test_util.h"

namespace {
using namespace arcus_test;

class EdgeCases : public ArcusTest {};

// A caller's first DP45 step obeys max_step and the Luneburg cap like every later
// step: a first step of 20 would otherwise jump over the unit lens unrefracted.
TEST_F(EdgeCases, CallersFirstDp45StepIsCappedAndCannotJumpOverALens) {
  FieldPtr lens = luneburg({0, 0, 0}, 1.0);
  ASSERT_TRUE(lens);
  Rays rays;
  rays.add({-10, 0.5, 0}, {1, 0, 0});
  arcus_advance_params p = dp45(20.0, 1e-10, 1e-12);
  p.step = 20.0;
  Trace t = trace(ctx(), lens.get(), p, rays);
  ASSERT_EQ(t.status, ARCUS_SUCCESS) << last_error();
  // A ray at impact parameter b = R/2 passes the focus F = (R, 0, 0) and leaves along
  // (sqrt(1 − b²), −b, 0) (test_closed_forms.cpp): it ends on that line.  A straight pass
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

// The error callback runs after the context's lock is released, so it may call arcus.
TEST_F(EdgeCases, ErrorCallbackMayCallTheLibrary) {
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

// Tiny but non-zero directions are valid (normalised without underflow); origins whose
// sum would overflow are still finite and valid; the host and kernel agree on both.
TEST_F(EdgeCases, ExtremeButFiniteRaysAreAdvancedAndReportedConsistently) {
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

// In float, a direction that is zero after conversion is invalid, and the call says so.
TEST_F(EdgeCases, DirectionThatVanishesInFloatIsReportedAsInvalid) {
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
TEST_F(EdgeCases, ParametersOutsideFloatRangeAreRejected) {
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

// The default path capacity follows the steps actually taken: max_steps bounds it, and
// the float step count is the kernel's own.
TEST_F(EdgeCases, DefaultPathCapacityFollowsTheStepsTaken) {
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
  ASSERT_EQ(arcus_job_get_path_size(t.job.get(), &points), ARCUS_SUCCESS);
  EXPECT_EQ(points, 11u);

  // A length and step whose step count differs between float and double arithmetic.
  arcus_advance_params q = fixed(ARCUS_METHOD_EULER, 7.210077602228678e-03, 196.71196784464513);
  q.precision = ARCUS_PRECISION_FLOAT;
  q.record_path = 1;
  t = trace(ctx(), medium.get(), q, rays);
  EXPECT_EQ(t.status, ARCUS_SUCCESS) << last_error();
}

// A fixed-step ray that stops at its length reports exactly that length, with a box too.
TEST_F(EdgeCases, FixedStepLengthIsExactWithABox) {
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

// Grid files: the shape is checked before the file is read, and a directory is an I/O
// error, not a size.
TEST_F(EdgeCases, GridFileShapeIsCheckedFirstAndADirectoryIsAnIoError) {
  const uint32_t huge[3] = {1u << 31, 1u << 31, 4};
  const double origin[3] = {0, 0, 0}, spacing[3] = {1, 1, 1};
  arcus_field_t* f = nullptr;
  EXPECT_EQ(arcus_field_create_grid_from_file(ctx(), "/dev/null", ARCUS_FLOAT64, huge, origin, spacing, &f),
            ARCUS_ERROR_INVALID_ARGUMENT);
  EXPECT_TRUE(contains_ci(arcus_context_last_error(ctx()), "dims")) << last_error();
  const uint32_t dims[3] = {2, 2, 2};
  EXPECT_EQ(arcus_field_create_grid_from_file(ctx(), "/tmp", ARCUS_FLOAT64, dims, origin, spacing, &f),
            ARCUS_ERROR_IO);
  EXPECT_EQ(f, nullptr);
}

}  // namespace
