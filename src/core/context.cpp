#include "core/context.h"

#include <algorithm>
#include <vector>

#include "core/error.h"

namespace arcus {
namespace {

// The contexts whose lock this thread holds, innermost last (a job on one context may
// run a callback that calls another).
thread_local std::vector<const arcus_context_t*> t_held;

}  // namespace

void retain_context(arcus_context_t* ctx) { ctx->retain(); }

void release_context(arcus_context_t* ctx) {
  if (ctx->drop()) delete ctx;
}

void release_object(Handle* object) {
  if (!object->drop()) return;
  arcus_context_t* ctx = object->owner();
  if (holds_lock(ctx)) {
    // No call path drops a last reference under its context's lock today (calls take
    // and drop theirs outside it); were one to, taking the lock again would throw from
    // a destructor.  The lock is this thread's already.
    delete object;
  } else {
    ContextLock lock(ctx);
    delete object;
  }
  release_context(ctx);
}

void release_handle(Handle* h) {
  if (&h->kind() == &kContextHandle)
    release_context(static_cast<arcus_context_t*>(h));
  else
    release_object(h);
}

ContextLock::ContextLock(arcus_context_t* ctx) : ctx_(ctx) {
  // Taking a lock this thread holds would deadlock; every call path refuses re-entry
  // before it gets here (refuse_reentry), so this is the last line of defence.
  if (holds_lock(ctx)) fail(ARCUS_ERROR_REENTRANT, "a call re-entered its context (from a progress callback)");
  ctx->lock.lock();
  t_held.push_back(ctx);
}

ContextLock::~ContextLock() {
  t_held.erase(std::find(t_held.begin(), t_held.end(), ctx_));
  ctx_->lock.unlock();
}

bool holds_lock(const arcus_context_t* ctx) { return std::find(t_held.begin(), t_held.end(), ctx) != t_held.end(); }

void refuse_reentry(Handle* h, void* reentered) {
  arcus_context_t* ctx = context_of(h);
  if (!holds_lock(ctx)) return;
  if (reentered) *static_cast<arcus_context_t**>(reentered) = ctx;
  fail(ARCUS_ERROR_REENTRANT, std::string("a call on this ") + h->kind().name() +
                                    " from a progress callback of a job on its context: the context is busy with "
                                    "that job; make the call after the job returns");
}

HandleRef& HandleRef::operator=(HandleRef&& other) noexcept {
  if (this != &other) {
    reset();
    h_ = other.h_;
    other.h_ = nullptr;
  }
  return *this;
}

void HandleRef::reset() {
  if (h_) release_handle(h_);
  h_ = nullptr;
}

arcus_context_t* context_of(Handle* h) {
  return &h->kind() == &kContextHandle ? static_cast<arcus_context_t*>(h) : h->owner();
}

size_t local_work_size(const arcus_context_t* ctx) { return ctx->info.is_gpu ? 0 : 1; }

namespace testing {
void set_fp64(arcus_context_t* ctx, bool fp64) {
  ContextLock lock(ctx);
  ctx->info.fp64 = fp64 ? 1 : 0;
}
}  // namespace testing

}  // namespace arcus

arcus_context_s::arcus_context_s(std::shared_ptr<arcus::DeviceRuntime> rt)
    : Handle(arcus::kContextHandle, nullptr), runtime(std::move(rt)), info(runtime->entry().info) {
  cl_int err = CL_SUCCESS;
  queue = arcus::ClQueue(
      clCreateCommandQueue(runtime->context(), runtime->entry().device, CL_QUEUE_PROFILING_ENABLE, &err));
  arcus::check_cl(err, "clCreateCommandQueue");
}
