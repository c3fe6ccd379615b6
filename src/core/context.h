// The object behind arcus_context_t, and how the objects of a context live and die.
// Every call on a context serialises on ctx->lock.
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
