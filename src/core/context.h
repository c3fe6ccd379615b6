// The object behind arcus_context_t, and how the objects of a context live and die.
// Every call on a context serialises on ctx->lock, taken through ContextLock.
#pragma once

#include <atomic>
#include <cstdint>
#include <memory>
#include <mutex>
#include <string>

#include "arcus/arcus_core.h"
#include "core/handle.h"
#include "core/opencl.h"
#include "core/runtime.h"

struct arcus_context_s : arcus::Handle {
  explicit arcus_context_s(std::shared_ptr<arcus::DeviceRuntime> rt);

  std::mutex lock;
  std::shared_ptr<arcus::DeviceRuntime> runtime;
  arcus::ClQueue queue;
  arcus_device_info info;  // the device as this context's jobs see it (tests may narrow it)
  std::string last_error;
  arcus_error_callback callback = nullptr;
  void* callback_user = nullptr;
  // Bytes of device memory held by this context's buffers (shared with the buffers,
  // which may outlive the context object's lock but not its accounting).
  std::shared_ptr<std::atomic<uint64_t>> device_bytes = std::make_shared<std::atomic<uint64_t>>(0);
};

namespace arcus {

// Ownership: an object of a context holds a reference to it, taken at creation.
void retain_context(arcus_context_t* ctx);
void release_context(arcus_context_t* ctx);

// Drops a reference to an object of a context (a field, job, scene); the last one
// deletes it under its context's lock and then releases the context.
void release_object(Handle* object);

// Drops a reference to a context or an object, whichever `h` is.
void release_handle(Handle* h);

// ctx->lock, held by this thread for the object's lifetime.  The thread remembers the
// contexts it holds, so that a call re-entering one (from a progress callback, which
// runs under the lock) is refused with ARCUS_ERROR_REENTRANT instead of deadlocking.
class ContextLock {
 public:
  explicit ContextLock(arcus_context_t* ctx);
  ~ContextLock();
  ContextLock(const ContextLock&) = delete;
  ContextLock& operator=(const ContextLock&) = delete;

 private:
  arcus_context_t* ctx_;
};

// Whether this thread holds ctx's lock (its calls on ctx are re-entries).
bool holds_lock(const arcus_context_t* ctx);

// Throws ARCUS_ERROR_REENTRANT when this thread holds the lock of h's context, after
// storing that context in *reentered (an arcus_context_t**; may be null).
void refuse_reentry(Handle* h, void* reentered);

// One reference to a context or an object, dropped when the HandleRef goes: what a call
// holds on the handles it was given, so that no other thread frees them mid-call.
class HandleRef {
 public:
  HandleRef() = default;
  explicit HandleRef(Handle* retained) : h_(retained) {}
  HandleRef(HandleRef&& other) noexcept : h_(other.h_) { other.h_ = nullptr; }
  HandleRef& operator=(HandleRef&& other) noexcept;
  ~HandleRef() { reset(); }
  Handle* get() const { return h_; }
  explicit operator bool() const { return h_ != nullptr; }
  void reset();
  // The reference handed on (to a caller that now owns it); this HandleRef is empty.
  Handle* release_to_caller() {
    Handle* h = h_;
    h_ = nullptr;
    return h;
  }

 private:
  Handle* h_ = nullptr;
};

// The context of a live object (itself for a context).
arcus_context_t* context_of(Handle* h);

// Items (rays, photons) are spread over work-items of one lane group each ... the local
// work size arcus launches with: 1 on CPUs (PoCL runs a work-group on one thread, and
// many small groups balance uneven work over the cores), the driver's choice on GPUs.
size_t local_work_size(const arcus_context_t* ctx);

namespace testing {
// Makes ctx's jobs see a device without double precision (ARCUS_ERROR_UNSUPPORTED).
void set_fp64(arcus_context_t* ctx, bool fp64);
}  // namespace testing

}  // namespace arcus
