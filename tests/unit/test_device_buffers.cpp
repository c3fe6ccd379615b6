// Device-resident buffers: made from host data or by a kernel, handed from one launch to
// the next without a trip through the host, counted against their context and freed
// with their owner; sizes are checked before anything is allocated.
#include <gtest/gtest.h>

#include <memory>
#include <numeric>
#include <vector>

#include "core/buffer.h"
#include "core/error.h"
#include "core/runtime.h"
#include "curved/fields.h"
#include "unit_util.h"

namespace {

using arcus_unit::Context;

TEST(DeviceBuffer, AKernelsOutputFeedsTheNextKernelOnTheDevice) {
  Context ctx;
  // Two kernels of one program: `fill` creates the data on the device, `twice` reads it.
  arcus::KernelSource source{"test/buffers", {"common/real.h"}, R"(
__kernel void fill(__global REAL* a, REAL scale) { a[get_global_id(0)] = scale * (REAL)get_global_id(0); }
__kernel void twice(__global const REAL* a, __global REAL* b) { b[get_global_id(0)] = 2 * a[get_global_id(0)]; }
)"};
  arcus::Layout layout;
  const arcus::BuiltProgram program = ctx.ctx->runtime->program(source, 0, layout);
  const size_t n = 1000;
  const uint64_t before = ctx.ctx->device_bytes->load();
  {
    arcus::DeviceBuffer a(ctx, n * sizeof(double), "a"), b(ctx, n * sizeof(double), "b");
    EXPECT_EQ(ctx.ctx->device_bytes->load(), before + 2 * n * sizeof(double));
    arcus::KernelCall fill(program.program, "fill"), twice(program.program, "twice");
    fill.set(0, &a);
    fill.set_value(1, 0.5);
    fill.run(ctx, n);
    twice.set(0, &a);
    twice.set(1, &b);
    twice.run(ctx, n);
    std::vector<double> out(n);
    b.read(ctx, 0, n * sizeof(double), out.data());
    for (size_t i = 0; i < n; ++i) ASSERT_EQ(out[i], static_cast<double>(i)) << i;
    // And from host data, written and read back.
    std::vector<double> host(n);
    std::iota(host.begin(), host.end(), 1.0);
    arcus::DeviceBuffer c(ctx, n * sizeof(double), "c", host.data());
    std::vector<double> back(n);
    c.read(ctx, 0, n * sizeof(double), back.data());
    EXPECT_EQ(back, host);
  }
  EXPECT_EQ(ctx.ctx->device_bytes->load(), before) << "buffers are released with their owner";
}

TEST(DeviceBuffer, TooLargeIsOutOfMemoryNamingTheBufferBeforeAllocating) {
  Context ctx;
  const double too_big = static_cast<double>(ctx.ctx->runtime->entry().max_alloc) * 2;
  try {
    arcus::check_device_allocation(ctx, too_big, too_big, "the photon map");
    FAIL() << "a buffer twice the device's largest must not fit";
  } catch (const arcus::Error& e) {
    EXPECT_EQ(e.status(), ARCUS_ERROR_OUT_OF_MEMORY);
    EXPECT_NE(std::string(e.what()).find("the photon map"), std::string::npos) << e.what();
  }
  EXPECT_THROW(arcus::DeviceBuffer(ctx, static_cast<size_t>(too_big), "x"), arcus::Error);
}

TEST(DeviceBuffer, AFieldsDataStaysOnTheDeviceBetweenJobs) {
  Context ctx;
  const uint64_t before = ctx.ctx->device_bytes->load();
  const uint32_t dims[3] = {4, 4, 4};
  const double origin[3] = {0, 0, 0}, spacing[3] = {1, 1, 1};
  std::vector<double> values(64, 1.0);
  arcus_field_t* field = nullptr;
  ASSERT_EQ(arcus_field_create_grid(ctx, values.data(), dims, origin, spacing, &field), ARCUS_SUCCESS);
  arcus_advance_params p;
  arcus_advance_params_init(&p);
  p.length = 2;
  const double o[3] = {0.5, 0.5, 0.5}, d[3] = {1, 0, 0};
  const arcus::DeviceBuffer* first = nullptr;
  uint64_t after_first = 0;
  for (int k = 0; k < 2; ++k) {
    arcus_job_t* job = nullptr;
    ASSERT_EQ(arcus_curved_advance(ctx, field, &p, 1, o, d, nullptr, &job), ARCUS_SUCCESS);
    arcus_job_release(job);
    const arcus::DeviceBuffer* data = field->device_data[0].get();
    ASSERT_NE(data, nullptr);
    if (k == 0) {
      first = data;
      after_first = ctx.ctx->device_bytes->load();
      EXPECT_EQ(after_first, before + 64 * sizeof(double)) << "the grid, once; the job's buffers are gone";
    } else {
      EXPECT_EQ(data, first) << "the second job reuses the uploaded grid";
      EXPECT_EQ(ctx.ctx->device_bytes->load(), after_first);
    }
  }
  arcus_field_release(field);
  EXPECT_EQ(ctx.ctx->device_bytes->load(), before);
}

// An internal hook narrows the device: double precision is then unsupported, float works.
TEST(DeviceSupport, DoubleOnADeviceWithoutFp64IsUnsupported) {
  Context ctx;
  arcus::testing::set_fp64(ctx, false);
  const double g[3] = {0, 0.1, 0}, o[3] = {0, 0, 0}, d[3] = {1, 0, 0};
  arcus_field_t* field = nullptr;
  ASSERT_EQ(arcus_field_create_linear(ctx, 1.0, g, &field), ARCUS_SUCCESS);
  arcus_advance_params p;
  arcus_advance_params_init(&p);
  arcus_job_t* job = nullptr;
  EXPECT_EQ(arcus_curved_advance(ctx, field, &p, 1, o, d, nullptr, &job), ARCUS_ERROR_UNSUPPORTED);
  EXPECT_EQ(job, nullptr);
  EXPECT_NE(std::string(arcus_context_last_error(ctx)).find("cl_khr_fp64"), std::string::npos);
  p.precision = ARCUS_PRECISION_FLOAT;
  EXPECT_EQ(arcus_curved_advance(ctx, field, &p, 1, o, d, nullptr, &job), ARCUS_SUCCESS);
  arcus_job_release(job);
  arcus_field_release(field);
}

}  // namespace
