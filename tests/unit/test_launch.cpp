// Kernel launches by argument name (core/launch.h): the kernel's signature and the
// host's names come from one list; an argument left unbound is refused by its name;
// a range job runs every unit once, in order, whatever the slices.
#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "core/error.h"
#include "core/launch.h"
#include "core/runtime.h"
#include "unit_util.h"

namespace {

using arcus_unit::Context;

// The list as a *_desc.h would hold it (the kernel text below repeats it: no header).
#define TEST_RAMP_ARGS(X) X(__global REAL*, out) X(const REAL, scale) X(const int, first)
ARCUS_KERNEL_ARGS(RampArg, "ramp", TEST_RAMP_ARGS);

const arcus::KernelSource kRamp{"test/launch", {"common/real.h"}, R"(
#define TEST_RAMP_ARGS(X) X(__global REAL*, out) X(const REAL, scale) X(const int, first)
__kernel void ramp(ARCUS_PARAMS(TEST_RAMP_ARGS)) {
  const int i = first + (int)get_global_id(0);
  out[i] = scale * (REAL)i;
}
)"};

TEST(Launch, AnArgumentLeftUnboundIsRefusedByItsName) {
  Context ctx;
  const arcus::BuiltProgram program = ctx.ctx->runtime->program(kRamp, 0, arcus::Layout{});
  arcus::DeviceBuffer out(ctx, 8 * sizeof(double), "out");
  arcus::Launch<RampArg> launch(ctx, program.program);
  launch.bind(RampArg::out, &out);
  launch.bind_value(RampArg::first, int32_t(0));
  try {
    launch.run(8);
    FAIL() << "scale was never bound";
  } catch (const arcus::Error& e) {
    EXPECT_EQ(e.status(), ARCUS_ERROR_INVALID_ARGUMENT);
    EXPECT_NE(std::string(e.what()).find("ramp: argument scale"), std::string::npos) << e.what();
  }
}

TEST(Launch, ARangeRunsEveryUnitOnceInItsSlices) {
  Context ctx;
  const arcus::BuiltProgram program = ctx.ctx->runtime->program(kRamp, 0, arcus::Layout{});
  const size_t n = 100;
  arcus::DeviceBuffer out(ctx, n * sizeof(double), "out");
  arcus::Launch<RampArg> launch(ctx, program.program);
  launch.bind(RampArg::out, &out);
  launch.bind_value(RampArg::scale, 0.5);
  arcus::testing::set_slice_units(7);
  arcus::SliceRange range{n, 1};
  arcus_job_stats stats{};
  const bool cancelled = launch.run_slices(range, [&](uint64_t first, uint64_t end) {
    launch.bind_value(RampArg::first, static_cast<int32_t>(first));
    return size_t(end - first);
  }, &stats);
  arcus::testing::set_slice_units(0);
  EXPECT_FALSE(cancelled);
  EXPECT_EQ(range.done, n);
  EXPECT_EQ(stats.launches, 15u) << "100 units, 7 a slice";
  std::vector<double> values(n);
  out.read(ctx, 0, n * sizeof(double), values.data());
  for (size_t i = 0; i < n; ++i) ASSERT_EQ(values[i], 0.5 * static_cast<double>(i)) << i;
}

}  // namespace
