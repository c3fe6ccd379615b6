// Long jobs run in slices: an optional callback sees the fraction done, and a non-zero
// return cancels the job, which comes back with ARCUS_ERROR_CANCELLED holding the results
// so far (the unfinished rays flagged ARCUS_RAY_CANCELLED, each where it got to).
#include <chrono>

#include "test_util.h"

using namespace arcus_test;

namespace {

class Progress : public ArcusTest {};

struct Seen {
  std::vector<double> fractions;
  int cancel_after = -1;  // calls before asking to cancel; -1: never
};

int32_t record(void* user, double fraction) {
  Seen* s = static_cast<Seen*>(user);
  s->fractions.push_back(fraction);
  return s->cancel_after >= 0 && static_cast<int>(s->fractions.size()) > s->cancel_after ? 1 : 0;
}

TEST_F(Progress, TheCallbackSeesTheFractionGrowToOne) {
  auto field = linear(1.0, {0, 0.1, 0});
  ASSERT_TRUE(field);
  Rays rays;
  for (int i = 0; i < 256; ++i) rays.add({0, 0.01 * i, 0}, {1, 0.001 * i, 0});
  for (arcus_method m : {ARCUS_METHOD_RK4, ARCUS_METHOD_DP45}) {
    // Enough work for several slices of about a quarter second each.
    arcus_advance_params p = m == ARCUS_METHOD_RK4 ? fixed(m, 2e-4, 2000.0) : dp45(2e5, 1e-13, 1e-16);
    Seen seen;
    p.progress = record;
    p.progress_user = &seen;
    const Trace t = trace(ctx(), field.get(), p, rays);
    ASSERT_EQ(t.status, ARCUS_SUCCESS) << last_error();
    arcus_job_stats stats;
    ASSERT_EQ(arcus_job_get_stats(t.job.get(), &stats), ARCUS_SUCCESS);
    std::printf("method %d: %u launches, fractions", m, stats.launches);
    for (double f : seen.fractions) std::printf(" %.3f", f);
    std::printf("\n");
    ASSERT_GE(seen.fractions.size(), 2u) << "method " << m;
    EXPECT_EQ(seen.fractions.back(), 1.0);
    EXPECT_EQ(stats.launches, seen.fractions.size()) << "one call per launch, the last one on completion";
    for (size_t i = 0; i + 1 < seen.fractions.size(); ++i) {
      EXPECT_GT(seen.fractions[i], 0.0);
      EXPECT_LE(seen.fractions[i], seen.fractions[i + 1]);
    }
    for (size_t i = 0; i < rays.size(); ++i) EXPECT_EQ(t.ray_status[i], ARCUS_RAY_DONE);
  }
}

TEST_F(Progress, ACancelledJobKeepsItsResultsSoFarAndFlagsTheRest) {
  // RK4 with steps of 1e-5 m over 10 km (1e9 steps per ray) would take hours; the
  // callback cancels it after its first slice.
  const V3 G{0, 0.1, 0};
  auto field = linear(1.0, G);
  ASSERT_TRUE(field);
  Rays rays;
  for (int i = 0; i < 64; ++i) rays.add({0, 0.01 * i, 0}, {1, 0.002 * i, 0});
  arcus_advance_params p = fixed(ARCUS_METHOD_RK4, 1e-5, 1e4);
  p.max_steps = 2000000000;  // the default 10^7 would end the rays first
  Seen seen;
  seen.cancel_after = 0;
  p.progress = record;
  p.progress_user = &seen;
  const auto start = std::chrono::steady_clock::now();
  const Trace t = trace(ctx(), field.get(), p, rays);
  const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  EXPECT_EQ(t.status, ARCUS_ERROR_CANCELLED);
  ASSERT_TRUE(t.job) << "a cancelled job comes back with its results";
  EXPECT_TRUE(contains_ci(last_error().c_str(), "cancel")) << last_error();
  EXPECT_LT(seconds, 30.0) << "cancelling must stop the job";
  ASSERT_EQ(seen.fractions.size(), 1u);
  EXPECT_GT(seen.fractions[0], 0.0);
  EXPECT_LT(seen.fractions[0], 0.01);
  for (size_t i = 0; i < rays.size(); ++i) {
    EXPECT_EQ(t.ray_status[i], ARCUS_RAY_CANCELLED) << "ray " << i;
    // Where it got to is a point of its path: the catenary at the arc length reported
    // (RK4 at 1e-5 m errs by far less than 1e-9 m over this stretch).
    ASSERT_GT(t.lengths[i], 0.0);
    EXPECT_LT(t.lengths[i], 1e4);
    EXPECT_EQ(t.steps[i], static_cast<uint64_t>(std::llround(t.lengths[i] / 1e-5))) << "ray " << i;
    const RayState want = catenary_end(1.0, G, rays.origin(i), rays.direction(i), t.lengths[i]);
    EXPECT_LT(distance(t.pos(i), want.pos), 1e-9) << "ray " << i;
  }
}

// What a progress callback tries on the context running its job (and on another).
struct Reentry {
  arcus_context_t* ctx;
  arcus_field_t* field;  // the job's field, whose only user reference the callback drops
  arcus_context_t* other;
  arcus_status kind_status = ARCUS_SUCCESS, release_status = ARCUS_SUCCESS, context_status = ARCUS_SUCCESS;
  arcus_status other_status = ARCUS_ERROR_INVALID_ARGUMENT;
  std::string message;
  int calls = 0;
};

int32_t reenter(void* user, double) {
  auto* r = static_cast<Reentry*>(user);
  if (r->calls++ > 0) return 0;
  arcus_field_kind kind;
  r->kind_status = arcus_field_get_kind(r->field, &kind);
  r->message = arcus_last_error();
  r->release_status = arcus_field_release(r->field);
  arcus_device_info info;
  r->context_status = arcus_context_get_device(r->ctx, &info);
  // Another context is free: calls on it work, objects made there too.
  arcus_field_t* f = nullptr;
  r->other_status = arcus_field_create_constant(r->other, 1.0, &f);
  arcus_field_release(f);
  return 0;
}

TEST_F(Progress, ACallbackCallingItsOwnContextGetsReentrantInsteadOfADeadlock) {
  // Before: every such call waited for the lock its own thread held, for ever.
  arcus_context_t* other = nullptr;
  ASSERT_EQ(arcus_context_create(ARCUS_DEVICE_DEFAULT, &other), ARCUS_SUCCESS);
  ContextPtr other_guard(other);
  arcus_field_t* field = nullptr;
  const double g[3] = {0, 0.1, 0};
  ASSERT_EQ(arcus_field_create_linear(ctx(), 1.0, g, &field), ARCUS_SUCCESS);
  Rays rays;
  for (int i = 0; i < 64; ++i) rays.add({0, 0.01 * i, 0}, {1, 0.001 * i, 0});
  arcus_advance_params p = fixed(ARCUS_METHOD_RK4, 2e-4, 1000.0);
  Reentry r{ctx(), field, other};
  p.progress = reenter;
  p.progress_user = &r;
  const Trace t = trace(ctx(), field, p, rays);
  ASSERT_EQ(t.status, ARCUS_SUCCESS) << last_error();
  ASSERT_GE(r.calls, 1);
  EXPECT_EQ(r.kind_status, ARCUS_ERROR_REENTRANT);
  EXPECT_TRUE(contains_ci(r.message.c_str(), "progress callback")) << r.message;
  EXPECT_EQ(r.release_status, ARCUS_ERROR_REENTRANT) << "refused: the reference stays the caller's";
  EXPECT_EQ(r.context_status, ARCUS_ERROR_REENTRANT);
  EXPECT_EQ(r.other_status, ARCUS_SUCCESS);
  EXPECT_STREQ(arcus_status_string(ARCUS_ERROR_REENTRANT), "ARCUS_ERROR_REENTRANT");
  // The refused release did nothing: the field is the caller's to release now.
  arcus_field_kind kind;
  EXPECT_EQ(arcus_field_get_kind(field, &kind), ARCUS_SUCCESS);
  EXPECT_EQ(arcus_field_release(field), ARCUS_SUCCESS);
  // The job's results are whole.
  for (size_t i = 0; i < rays.size(); ++i) EXPECT_EQ(t.ray_status[i], ARCUS_RAY_DONE);
}

}  // namespace
