// Determinism across slices: a job cut into launches of any size computes the same
// numbers, bit for bit — the state kept on the device between slices is complete (DP45's
// step size and rejection count, the float path's Kahan terms, path points) and nothing
// depends on where a slice ends.  A determinism test: it compares the code with itself.
#include <gtest/gtest.h>

#include <vector>

#include "core/slices.h"
#include "unit_util.h"

namespace {

using arcus_unit::Context;

struct Result {
  std::vector<double> positions, directions, lengths, points;
  std::vector<uint64_t> steps, offsets;
  std::vector<int32_t> status;
  uint32_t launches = 0;
};

Result run(arcus_context_t* ctx, arcus_field_t* field, arcus_advance_params p, int32_t slice_units) {
  arcus::testing::set_slice_units(slice_units);
  std::vector<double> o, d;
  for (int i = 0; i < 40; ++i) {
    o.insert(o.end(), {0.0, 0.05 * i, 0.0});
    d.insert(d.end(), {1.0, 0.01 * i - 0.2, 0.02 * (i % 3)});
  }
  const size_t n = o.size() / 3;
  arcus_job_t* job = nullptr;
  EXPECT_EQ(arcus_curved_advance(ctx, field, &p, n, o.data(), d.data(), nullptr, &job), ARCUS_SUCCESS)
      << arcus_context_last_error(ctx);
  arcus::testing::set_slice_units(0);
  Result r;
  if (!job) return r;
  r.positions.resize(3 * n);
  r.directions.resize(3 * n);
  r.lengths.resize(n);
  r.steps.resize(n);
  r.status.resize(n);
  arcus_job_get_curved_end_states(job, r.positions.data(), r.directions.data(), r.steps.data(), r.status.data(),
                                  r.lengths.data());
  if (p.record_path) {
    size_t total = 0;
    arcus_job_get_curved_path_size(job, &total);
    r.points.resize(3 * total);
    r.offsets.resize(n + 1);
    arcus_job_get_curved_paths(job, r.offsets.data(), r.points.data(), nullptr);
  }
  arcus_job_stats stats;
  arcus_job_get_stats(job, &stats);
  r.launches = stats.launches;
  arcus_job_release(job);
  return r;
}

void expect_same(const Result& a, const Result& b, const char* what) {
  EXPECT_EQ(a.positions, b.positions) << what;
  EXPECT_EQ(a.directions, b.directions) << what;
  EXPECT_EQ(a.lengths, b.lengths) << what;
  EXPECT_EQ(a.steps, b.steps) << what;
  EXPECT_EQ(a.status, b.status) << what;
  EXPECT_EQ(a.points, b.points) << what;
  EXPECT_EQ(a.offsets, b.offsets) << what;
}

TEST(SliceDeterminism, AnySliceSizeGivesTheSameNumbers) {
  Context ctx;
  const double c[3] = {0.3, 1.0, 0.0};
  arcus_field_t* lens = nullptr;
  ASSERT_EQ(arcus_field_create_fisheye(ctx, c, 1.5, 1.2, &lens), ARCUS_SUCCESS);
  std::vector<std::pair<const char*, arcus_advance_params>> jobs;
  arcus_advance_params p;
  arcus_advance_params_init(&p);
  p.length = 6.0;
  p.rtol = 1e-10;
  p.atol = 1e-13;
  jobs.push_back({"dp45", p});
  p.record_path = 1;
  p.use_box = 1;
  for (int a = 0; a < 3; ++a) {
    p.box_min[a] = -2;
    p.box_max[a] = 3;
  }
  jobs.push_back({"dp45 box path", p});
  p.precision = ARCUS_PRECISION_FLOAT;
  p.rtol = 1e-6;
  p.atol = 1e-8;
  jobs.push_back({"dp45 float box path", p});
  arcus_advance_params q;
  arcus_advance_params_init(&q);
  q.method = ARCUS_METHOD_RK4;
  q.step = 0.01;
  q.length = 6.0;
  jobs.push_back({"rk4", q});
  q.precision = ARCUS_PRECISION_FLOAT;
  q.record_path = 1;
  jobs.push_back({"rk4 float path", q});
  q.precision = ARCUS_PRECISION_DOUBLE;
  q.use_box = 1;
  for (int a = 0; a < 3; ++a) {
    q.box_min[a] = -2;
    q.box_max[a] = 3;
  }
  jobs.push_back({"rk4 box path", q});
  for (const auto& job : jobs) {
    const Result whole = run(ctx, lens, job.second, 1 << 30);
    EXPECT_EQ(whole.launches, 1u) << job.first;
    for (int32_t units : {1, 7, 64}) {
      const Result sliced = run(ctx, lens, job.second, units);
      if (units == 1) {
        EXPECT_GT(sliced.launches, 1u) << job.first;
      }
      expect_same(whole, sliced, job.first);
    }
  }
  arcus_field_release(lens);
}

}  // namespace
