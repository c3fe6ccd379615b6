#include "core/context.h"

namespace arcus {

void retain_context(arcus_context_t* ctx) { ctx->retain(); }

void release_context(arcus_context_t* ctx) {
  if (ctx->drop()) delete ctx;
}

void release_object(Handle* object) {
  if (!object->drop()) return;
  arcus_context_t* ctx = object->owner();
  {
    std::lock_guard<std::mutex> lock(ctx->lock);
    delete object;
  }
  release_context(ctx);
}

arcus_context_t* context_of(Handle* h) {
  return h->type() == HandleType::Context ? static_cast<arcus_context_t*>(h) : h->owner();
}

size_t local_work_size(const arcus_context_t* ctx) { return ctx->info.is_gpu ? 0 : 1; }

namespace testing {
void set_fp64(arcus_context_t* ctx, bool fp64) {
  std::lock_guard<std::mutex> lock(ctx->lock);
  ctx->info.fp64 = fp64 ? 1 : 0;
}
}  // namespace testing

}  // namespace arcus

arcus_context_s::arcus_context_s(std::shared_ptr<arcus::DeviceRuntime> rt)
    : Handle(arcus::HandleType::Context, nullptr), runtime(std::move(rt)), info(runtime->entry().info) {
  cl_int err = CL_SUCCESS;
  queue = arcus::ClQueue(
      clCreateCommandQueue(runtime->context(), runtime->entry().device, CL_QUEUE_PROFILING_ENABLE, &err));
  arcus::check_cl(err, "clCreateCommandQueue");
}
