// Handles: every call checks them.  NULL, a released handle, a handle of another type,
// an object of another context or a pointer that is no arcus object gives
// ARCUS_ERROR_INVALID_ARGUMENT with a message — never undefined behaviour.  Contexts are
// independent (two threads, two contexts), and a job outlives its context's release.
#include <thread>

#include "test_util.h"

using namespace arcus_test;

namespace {

class Handles : public ArcusTest {};

TEST_F(Handles, AHandleOfTheWrongTypeIsRejectedWithAMessage) {
  auto field = linear(1.0, {0, 0.1, 0});
  ASSERT_TRUE(field);
  Rays rays;
  rays.add({0, 0, 0}, {1, 0, 0});
  const Trace t = trace(ctx(), field.get(), dp45(1.0, 1e-9, 1e-12), rays);
  ASSERT_TRUE(t.job);
  // A job where a field is expected, a field where a job is, a context as either.
  arcus_field_kind kind;
  EXPECT_EQ(arcus_field_get_kind(reinterpret_cast<arcus_field_t*>(t.job.get()), &kind), ARCUS_ERROR_INVALID_ARGUMENT);
  EXPECT_TRUE(contains_ci(arcus_last_error(), "field is a job, not a field")) << arcus_last_error();
  size_t count = 0;
  EXPECT_EQ(arcus_job_get_count(reinterpret_cast<arcus_job_t*>(field.get()), &count), ARCUS_ERROR_INVALID_ARGUMENT);
  EXPECT_TRUE(contains_ci(arcus_last_error(), "job is a field")) << arcus_last_error();
  EXPECT_EQ(arcus_field_retain(reinterpret_cast<arcus_field_t*>(ctx())), ARCUS_ERROR_INVALID_ARGUMENT);
  EXPECT_EQ(arcus_job_release(reinterpret_cast<arcus_job_t*>(field.get())), ARCUS_ERROR_INVALID_ARGUMENT);
  // The message also lands on the context of the object that was passed.
  EXPECT_TRUE(contains_ci(arcus_context_last_error(ctx()), "job is a field")) << arcus_context_last_error(ctx());
  // As the field argument of arcus_advance.
  arcus_advance_params p = dp45(1.0, 1e-9, 1e-12);
  arcus_job_t* job = nullptr;
  EXPECT_EQ(arcus_advance(ctx(), reinterpret_cast<arcus_field_t*>(t.job.get()), &p, 1, rays.origins.data(),
                          rays.directions.data(), nullptr, &job),
            ARCUS_ERROR_INVALID_ARGUMENT);
  EXPECT_EQ(job, nullptr);
  EXPECT_TRUE(contains_ci(arcus_context_last_error(ctx()), "field is a job")) << arcus_context_last_error(ctx());
  // Nothing was harmed: both objects still work.
  EXPECT_EQ(arcus_field_get_kind(field.get(), &kind), ARCUS_SUCCESS);
  EXPECT_EQ(kind, ARCUS_FIELD_LINEAR);
  EXPECT_EQ(arcus_job_get_count(t.job.get(), &count), ARCUS_SUCCESS);
  EXPECT_EQ(count, 1u);
}

TEST_F(Handles, AReleasedHandleOrAForeignPointerIsRejected) {
  arcus_field_t* f = nullptr;
  ASSERT_EQ(arcus_field_create_constant(ctx(), 1.5, &f), ARCUS_SUCCESS);
  ASSERT_EQ(arcus_field_release(f), ARCUS_SUCCESS);
  arcus_field_kind kind;
  EXPECT_EQ(arcus_field_get_kind(f, &kind), ARCUS_ERROR_INVALID_ARGUMENT);
  EXPECT_TRUE(contains_ci(arcus_last_error(), "not a live arcus handle")) << arcus_last_error();
  EXPECT_EQ(arcus_field_release(f), ARCUS_ERROR_INVALID_ARGUMENT) << "a double release";
  // A pointer to something that is no arcus object at all.
  double not_a_handle[16] = {};
  EXPECT_EQ(arcus_field_get_kind(reinterpret_cast<arcus_field_t*>(not_a_handle), &kind), ARCUS_ERROR_INVALID_ARGUMENT);
  EXPECT_EQ(arcus_context_retain(reinterpret_cast<arcus_context_t*>(not_a_handle)), ARCUS_ERROR_INVALID_ARGUMENT);
  EXPECT_STREQ(arcus_context_last_error(reinterpret_cast<arcus_context_t*>(not_a_handle)),
               "ctx is not a live arcus context");
}

TEST_F(Handles, AFieldOfAnotherContextIsRejected) {
  arcus_context_t* other = nullptr;
  ASSERT_EQ(arcus_context_create(ARCUS_DEVICE_DEFAULT, &other), ARCUS_SUCCESS);
  ContextPtr guard(other);
  arcus_field_t* foreign = nullptr;
  const double g[3] = {0, 0.1, 0};
  ASSERT_EQ(arcus_field_create_linear(other, 1.0, g, &foreign), ARCUS_SUCCESS);
  FieldPtr foreign_guard(foreign);
  Rays rays;
  rays.add({0, 0, 0}, {1, 0, 0});
  const Trace t = trace(ctx(), foreign, dp45(1.0, 1e-9, 1e-12), rays);
  EXPECT_EQ(t.status, ARCUS_ERROR_INVALID_ARGUMENT);
  EXPECT_FALSE(t.job);
  EXPECT_TRUE(contains_ci(arcus_context_last_error(ctx()), "field belongs to another context"))
      << arcus_context_last_error(ctx());
  // On its own context it works.
  EXPECT_EQ(trace(other, foreign, dp45(1.0, 1e-9, 1e-12), rays).status, ARCUS_SUCCESS);
}

TEST(Contexts, TwoContextsDrivenFromTwoThreadsAtOnceGiveTheirSerialResults) {
  // Each thread owns a context and advances its own field; the results must equal the
  // same jobs run one after the other (the closed form checks them too).
  struct Work {
    double gradient;
    std::vector<double> positions;
    arcus_status status = ARCUS_ERROR_INVALID_ARGUMENT;
  };
  auto run = [](Work* w) {
    arcus_context_t* c = nullptr;
    if (arcus_context_create(ARCUS_DEVICE_DEFAULT, &c) != ARCUS_SUCCESS) return;
    const double g[3] = {0, w->gradient, 0};
    arcus_field_t* f = nullptr;
    arcus_field_create_linear(c, 1.0, g, &f);
    Rays rays;
    for (int i = 0; i < 64; ++i) rays.add({0, 0.01 * i, 0}, {1, 0.002 * i, 0});
    const Trace t = trace(c, f, dp45(50.0, 1e-10, 1e-13), rays);
    w->status = t.status;
    w->positions = t.positions;
    arcus_field_release(f);
    arcus_context_release(c);
  };
  Work parallel[2] = {{0.1, {}}, {-0.05, {}}}, serial[2] = {{0.1, {}}, {-0.05, {}}};
  std::thread a(run, &parallel[0]), b(run, &parallel[1]);
  a.join();
  b.join();
  run(&serial[0]);
  run(&serial[1]);
  for (int k = 0; k < 2; ++k) {
    ASSERT_EQ(parallel[k].status, ARCUS_SUCCESS);
    EXPECT_EQ(parallel[k].positions, serial[k].positions) << "context " << k;
    // The catenary within the tolerance (rtol 1e-10 over 50 m: see test_closed_forms).
    const V3 end{parallel[k].positions[0], parallel[k].positions[1], parallel[k].positions[2]};
    EXPECT_LT(distance(end, catenary_end(1.0, {0, parallel[k].gradient, 0}, {0, 0, 0}, {1, 0, 0}, 50.0).pos), 1e-7);
  }
}

TEST(Contexts, AJobsResultsCanBeReadAfterTheUserReleasedItsContext) {
  arcus_context_t* c = nullptr;
  ASSERT_EQ(arcus_context_create(ARCUS_DEVICE_DEFAULT, &c), ARCUS_SUCCESS);
  arcus_field_t* f = nullptr;
  const double g[3] = {0, 0.1, 0};
  ASSERT_EQ(arcus_field_create_linear(c, 1.0, g, &f), ARCUS_SUCCESS);
  arcus_advance_params p = dp45(10.0, 1e-10, 1e-13);
  p.record_path = 1;
  const double o[3] = {0, 0, 0}, d[3] = {1, 0.1, 0};
  arcus_job_t* job = nullptr;
  ASSERT_EQ(arcus_advance(c, f, &p, 1, o, d, nullptr, &job), ARCUS_SUCCESS);
  ASSERT_EQ(arcus_field_release(f), ARCUS_SUCCESS);
  ASSERT_EQ(arcus_context_release(c), ARCUS_SUCCESS);  // the user's reference; the job keeps its own
  double pos[3];
  int32_t status = -1;
  ASSERT_EQ(arcus_job_get_end_states(job, pos, nullptr, nullptr, &status, nullptr), ARCUS_SUCCESS);
  EXPECT_EQ(status, ARCUS_RAY_DONE);
  EXPECT_LT(distance({pos[0], pos[1], pos[2]}, catenary_end(1.0, {0, 0.1, 0}, {0, 0, 0}, {1, 0.1, 0}, 10.0).pos), 1e-8);
  size_t points = 0;
  EXPECT_EQ(arcus_job_get_path_size(job, &points), ARCUS_SUCCESS);
  EXPECT_GT(points, 2u);
  ASSERT_EQ(arcus_job_release(job), ARCUS_SUCCESS);  // frees the context too
}

}  // namespace
