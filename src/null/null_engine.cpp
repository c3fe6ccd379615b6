// The null engine (include/arcus/arcus_null.h): the smallest engine there is, written as
// docs/adding-an-engine.md says, to prove that an engine needs nothing from the core
// but what every engine uses: it registers its handle kind and its feature table, names
// its kernel source, and builds, launches and reports its jobs through the core.
#include <chrono>
#include <cmath>
#include <memory>
#include <string>
#include <vector>

#include "arcus/arcus_null.h"
#include "core/buffer.h"
#include "core/call.h"
#include "core/features.h"
#include "core/job.h"
#include "core/kernel_source.h"
#include "core/launch.h"
#include "null/null_desc.h"  // kernels/null/null_desc.h: the kernel's arguments

namespace arcus::null_engine {
namespace {

// What a swatch handle is called in error messages ("swatch is a job, not a swatch").
const HandleKind kSwatchHandle("swatch");

// The -D flag its one feature compiles with: the kernel refuses to build without it.
const FeatureTable kTable{"null", {{ARCUS_FEATURE_NULL_FILL, "NULL_FILL", "-D ARCUS_USE_NULL_FILL"}}};
const FeatureTableEntry kRegistered(&kTable);

const KernelSource kFill{"null/fill", {"common/real.h", "null/null_desc.h", "null/fill.cl"}, ""};
ARCUS_KERNEL_ARGS(FillArg, "arcus_null_fill", ARCUS_NULL_FILL_ARGS);

struct NullJob : arcus_job_s {
  explicit NullJob(arcus_context_t* ctx) : arcus_job_s(ctx, "null") {}
  std::vector<float> rgb;
};

constexpr uint32_t kMaxSide = 4096;

}  // namespace
}  // namespace arcus::null_engine

struct arcus_swatch_s : arcus::Handle {
  arcus_swatch_s(arcus_context_t* ctx, const float c[3])
      : Handle(arcus::null_engine::kSwatchHandle, ctx), rgb{c[0], c[1], c[2]} {}
  float rgb[3];
};

using namespace arcus;
using namespace arcus::api;
using null_engine::kSwatchHandle;

extern "C" {

arcus_status arcus_swatch_create(arcus_context_t* ctx, const float rgb[3], arcus_swatch_t** out) {
  return simple<arcus_context_s>(ctx, kContextHandle, "ctx", [&](arcus_context_s*) {
    require_pointer(out, "out");
    *out = nullptr;
    require_pointer(rgb, "rgb");
    for (int c = 0; c < 3; ++c)
      require(std::isfinite(rgb[c]) && rgb[c] >= 0, "rgb must be finite and >= 0, got rgb[" + std::to_string(c) +
                                                         "] = " + std::to_string(rgb[c]));
    auto swatch = std::make_unique<arcus_swatch_s>(ctx, rgb);
    retain_context(ctx);  // the swatch's reference
    *out = swatch.release();
  });
}

arcus_status arcus_swatch_retain(arcus_swatch_t* swatch) { return retain(swatch, kSwatchHandle, "swatch"); }
arcus_status arcus_swatch_release(arcus_swatch_t* swatch) { return release(swatch, kSwatchHandle, "swatch"); }

arcus_status arcus_null_fill(arcus_swatch_t* swatch, uint32_t width, uint32_t height, arcus_job_t** job) {
  return on<arcus_swatch_s>(swatch, kSwatchHandle, "swatch", [&](arcus_swatch_s* s, std::string*) {
    const auto start = std::chrono::steady_clock::now();
    require_pointer(job, "job");
    *job = nullptr;
    require(width >= 1 && width <= null_engine::kMaxSide, "width must lie in [1, 4096], got " + std::to_string(width));
    require(height >= 1 && height <= null_engine::kMaxSide,
            "height must lie in [1, 4096], got " + std::to_string(height));
    arcus_context_t* ctx = s->owner();
    auto j = std::make_unique<null_engine::NullJob>(ctx);
    j->count = size_t(width) * height;
    j->features = ARCUS_FEATURE_NULL_FILL;
    j->rgb.resize(3 * j->count);
    DeviceBuffer image(ctx, j->rgb.size() * sizeof(float), "the image");
    const BuiltProgram built = build_job_program(ctx, *j, null_engine::kFill, Layout{1, 1});
    Launch<null_engine::FillArg> launch(ctx, built.program);
    launch.upload(null_engine::FillArg::colour, s->rgb, 3, "the swatch's colour");
    launch.bind(null_engine::FillArg::rgb, &image);
    launch.bind_value(null_engine::FillArg::pixels, static_cast<cl_uint>(j->count));
    j->stats.kernel_seconds = launch.run(j->count);
    j->stats.launches = 1;
    image.read(ctx, 0, j->rgb.size() * sizeof(float), j->rgb.data());
    j->stats.total_seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    retain_context(ctx);  // the job's reference
    *job = j.release();
    return ARCUS_SUCCESS;
  });
}

arcus_status arcus_job_get_null_image(arcus_job_t* job, float* rgb) {
  return on_job<null_engine::NullJob>(job, "a null fill", [&](null_engine::NullJob* j) {
    require_pointer(rgb, "rgb");
    copy_out(j->rgb, rgb);
  });
}

}  // extern "C"
