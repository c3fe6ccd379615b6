// Handles: every call checks them.  NULL, a released handle, a handle of another type,
// an object of another context or a pointer that is no arcus object gives
// ARCUS_ERROR_INVALID_ARGUMENT with a message — never undefined behaviour.  Contexts are
// independent (two threads, two contexts), and a job outlives its context's release.
// A call keeps the objects it was handed alive while it runs, whatever other threads
// release meanwhile (run under ASan by scripts/sanitize.sh, where a use after free is a
// report).
#include <signal.h>
#include <stdlib.h>
#include <sys/mman.h>

#include <atomic>
#include <chrono>
#include <condition_variable>
#include <mutex>
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
  // As the field argument of arcus_curved_advance.
  arcus_advance_params p = dp45(1.0, 1e-9, 1e-12);
  arcus_job_t* job = nullptr;
  EXPECT_EQ(arcus_curved_advance(ctx(), reinterpret_cast<arcus_field_t*>(t.job.get()), &p, 1, rays.origins.data(),
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
    // The catenary within the tolerance (rtol 1e-10 over 50 m: see test_curved_closed_forms).
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
  ASSERT_EQ(arcus_curved_advance(c, f, &p, 1, o, d, nullptr, &job), ARCUS_SUCCESS);
  ASSERT_EQ(arcus_field_release(f), ARCUS_SUCCESS);
  ASSERT_EQ(arcus_context_release(c), ARCUS_SUCCESS);  // the user's reference; the job keeps its own
  double pos[3];
  int32_t status = -1;
  ASSERT_EQ(arcus_job_get_curved_end_states(job, pos, nullptr, nullptr, &status, nullptr), ARCUS_SUCCESS);
  EXPECT_EQ(status, ARCUS_RAY_DONE);
  EXPECT_LT(distance({pos[0], pos[1], pos[2]}, catenary_end(1.0, {0, 0.1, 0}, {0, 0, 0}, {1, 0.1, 0}, 10.0).pos), 1e-8);
  size_t points = 0;
  EXPECT_EQ(arcus_job_get_curved_path_size(job, &points), ARCUS_SUCCESS);
  EXPECT_GT(points, 2u);
  ASSERT_EQ(arcus_job_release(job), ARCUS_SUCCESS);  // frees the context too
}

// A job that holds its context's lock until told to let go: its progress callback (run
// under the lock) waits for `go`, then cancels the job.
struct LockHolder {
  std::mutex m;
  std::condition_variable cv;
  bool holding = false, go = false;

  static int32_t callback(void* user, double) {
    auto* h = static_cast<LockHolder*>(user);
    std::unique_lock<std::mutex> lock(h->m);
    h->holding = true;
    h->cv.notify_all();
    h->cv.wait(lock, [&] { return h->go; });
    return 1;
  }
  void wait_until_holding() {
    std::unique_lock<std::mutex> lock(m);
    cv.wait(lock, [&] { return holding; });
  }
  void let_go() {
    std::lock_guard<std::mutex> lock(m);
    go = true;
    cv.notify_all();
  }
};

TEST(Contexts, AFieldReleasedByAnotherThreadWhileACallWaitsToUseItIsFreedOnlyAfterThatCall) {
  // Thread `user` calls arcus_field_evaluate on a field and waits for the context's lock
  // (a long job holds it); meanwhile thread `releaser` drops the field's last reference.
  // The waiting call took a reference of its own when it checked the handle, so it gets
  // a live field, and the field is freed when that call ends.  (Before the calls held
  // references, whichever thread got the lock first won: when it was the releaser,
  // the waiting call used freed memory, a heap-use-after-free under ASan.)  The race
  // is repeated, since which waiter a mutex wakes first is up to the system.
  arcus_context_t* c = nullptr;
  ASSERT_EQ(arcus_context_create(ARCUS_DEVICE_DEFAULT, &c), ARCUS_SUCCESS);
  ContextPtr guard(c);
  arcus_field_t* slow_field = nullptr;
  const double g[3] = {0, 0.1, 0};
  ASSERT_EQ(arcus_field_create_linear(c, 1.0, g, &slow_field), ARCUS_SUCCESS);
  FieldPtr slow_guard(slow_field);
  for (int round = 0; round < 12; ++round) {
    arcus_field_t* field = nullptr;
    const double n_expected = 1.25 + round;
    ASSERT_EQ(arcus_field_create_constant(c, n_expected, &field), ARCUS_SUCCESS);
    LockHolder holder;
    std::thread job([&] {
      arcus_advance_params p{};
      ASSERT_EQ(arcus_advance_params_init(&p), ARCUS_SUCCESS);
      p.method = ARCUS_METHOD_RK4;
      p.step = 1e-5;
      p.length = 1e4;
      p.max_steps = 2000000000;
      p.progress = LockHolder::callback;
      p.progress_user = &holder;
      const double o[3] = {0, 0, 0}, d[3] = {1, 0, 0};
      arcus_job_t* j = nullptr;
      EXPECT_EQ(arcus_curved_advance(c, slow_field, &p, 1, o, d, nullptr, &j), ARCUS_ERROR_CANCELLED);
      arcus_job_release(j);
    });
    holder.wait_until_holding();
    arcus_status used = ARCUS_ERROR_INVALID_ARGUMENT;
    double n = 0;
    std::thread user([&] {
      const double at[3] = {0, 0, 0};
      used = arcus_field_evaluate(field, 1, at, &n, nullptr);
    });
    std::this_thread::sleep_for(std::chrono::milliseconds(50));  // `user` is waiting for the lock
    std::thread releaser([&] { EXPECT_EQ(arcus_field_release(field), ARCUS_SUCCESS); });
    std::this_thread::sleep_for(std::chrono::milliseconds(50));
    holder.let_go();
    job.join();
    user.join();
    releaser.join();
    EXPECT_EQ(used, ARCUS_SUCCESS) << "round " << round << ": " << arcus_context_last_error(c);
    EXPECT_EQ(n, n_expected) << "round " << round;
    arcus_field_kind kind;
    EXPECT_EQ(arcus_field_get_kind(field, &kind), ARCUS_ERROR_INVALID_ARGUMENT) << "freed once both calls ended";
  }
}

TEST(Contexts, ManyThreadsUsingAndReleasingOneFieldNeverTouchFreedMemory) {
  // Determinism aside, the plain race: threads evaluate a field while one releases the
  // last reference.  Every call either sees a live field (and a right answer) or is
  // told the handle is gone; under ASan nothing reads freed memory.
  arcus_context_t* c = nullptr;
  ASSERT_EQ(arcus_context_create(ARCUS_DEVICE_DEFAULT, &c), ARCUS_SUCCESS);
  ContextPtr guard(c);
  for (int round = 0; round < 200; ++round) {
    arcus_field_t* field = nullptr;
    ASSERT_EQ(arcus_field_create_constant(c, 1.5, &field), ARCUS_SUCCESS);
    std::atomic<int> wrong{0};
    std::atomic<bool> start{false};
    auto use = [&] {
      while (!start) std::this_thread::yield();
      for (int k = 0; k < 20; ++k) {
        const double at[3] = {0, 0, 0};
        double n = 0;
        const arcus_status st = arcus_field_evaluate(field, 1, at, &n, nullptr);
        if ((st == ARCUS_SUCCESS && n != 1.5) || (st != ARCUS_SUCCESS && st != ARCUS_ERROR_INVALID_ARGUMENT)) ++wrong;
      }
    };
    std::thread a(use), b(use);
    start = true;
    EXPECT_EQ(arcus_field_release(field), ARCUS_SUCCESS);
    a.join();
    b.join();
    EXPECT_EQ(wrong.load(), 0) << "round " << round;
  }
}

TEST(Threads, AThreadWhoseSignalStackTheKernelCompilerReplacedExitsCleanly) {
  // The regression test of scripts/sanitize.sh's use_sigaltstack=0.  ASan gives each
  // thread an alternate signal stack of 4 x SIGSTKSZ (32 KiB on a CPU without AMX) and
  // unmaps it when the thread exits.  LLVM, inside PoCL's kernel compiler, replaces a
  // thread's alternate stack smaller than SIGSTKSZ + 64 KiB with one from malloc, which
  // ASan then fails to unmap: "CHECK failed: sanitizer_posix.cpp:61 "unable to unmap"",
  // in every thread that compiled a kernel.  This thread installs such a small stack
  // itself (so the test fails the same way on a CPU with AMX, whose larger stacks LLVM
  // leaves alone), compiles a kernel with both program caches off, and exits.
  setenv("ARCUS_CACHE_DIR", "off", 1);
  // Read when PoCL starts: ctest runs each test in a process of its own
  // (gtest_discover_tests), so none has started yet.
  setenv("POCL_KERNEL_CACHE", "0", 1);
  arcus_status status = ARCUS_ERROR_INVALID_ARGUMENT;
  std::thread t([&] {
    stack_t small{};
    small.ss_size = 32 * 1024;
    small.ss_sp = mmap(nullptr, small.ss_size, PROT_READ | PROT_WRITE, MAP_PRIVATE | MAP_ANONYMOUS, -1, 0);
    ASSERT_NE(small.ss_sp, MAP_FAILED);
    ASSERT_EQ(sigaltstack(&small, nullptr), 0);
    arcus_context_t* c = nullptr;
    ASSERT_EQ(arcus_context_create(ARCUS_DEVICE_DEFAULT, &c), ARCUS_SUCCESS);
    ContextPtr guard(c);
    arcus_field_t* f = nullptr;
    const double g[3] = {0, 0.1, 0};
    ASSERT_EQ(arcus_field_create_linear(c, 1.0, g, &f), ARCUS_SUCCESS);
    FieldPtr field_guard(f);
    Rays rays;
    rays.add({0, 0, 0}, {1, 0, 0});
    status = trace(c, f, dp45(1.0, 1e-9, 1e-12), rays).status;
  });
  t.join();
  EXPECT_EQ(status, ARCUS_SUCCESS);
}

}  // namespace
