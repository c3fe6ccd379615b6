#include "core/rng.h"

#include "core/buffer.h"
#include "core/error.h"

namespace arcus {

const KernelSource& rng_fill_source() {
  static const KernelSource source{"common/rng_fill", {"common/real.h", "common/philox.h", "common/rng_fill.cl"}, ""};
  return source;
}

std::vector<double> rng_fill(arcus_context_t* ctx, Layout layout, bool single, uint64_t seed, uint64_t first_index,
                             uint32_t draws, uint32_t count, double* kernel_seconds) {
  const BuiltProgram program = ctx->runtime->program(rng_fill_source(), single ? ARCUS_FEATURE_FLOAT : 0, layout);
  const size_t values = static_cast<size_t>(count) * draws, real = single ? sizeof(float) : sizeof(double);
  DeviceBuffer out(ctx, values * real, "the random numbers");
  KernelCall kernel(program.program, "arcus_rng_fill");
  kernel.set_value(0, static_cast<cl_ulong>(seed));
  kernel.set_value(1, static_cast<cl_ulong>(first_index));
  kernel.set_value(2, static_cast<cl_uint>(draws));
  kernel.set_value(3, static_cast<cl_uint>(count));
  kernel.set(4, &out);
  const size_t per_item = layout.per_item();
  const double seconds = kernel.run(ctx, std::max<size_t>(1, (count + per_item - 1) / per_item));
  if (kernel_seconds) *kernel_seconds = seconds;
  std::vector<double> result(values);
  if (single) {
    std::vector<float> f(values);
    out.read(ctx, 0, values * real, f.data());
    result.assign(f.begin(), f.end());
  } else {
    out.read(ctx, 0, values * real, result.data());
  }
  return result;
}

}  // namespace arcus
