// The C entry points of arcus_core.h: status names, version, devices, contexts, feature
// names, and what every job has.
#include <cstring>
#include <memory>
#include <string>

#include "arcus/arcus_core.h"
#include "core/call.h"
#include "core/context.h"
#include "core/features.h"
#include "core/job.h"

using arcus::Handle;
using arcus::HandleRef;
using arcus::require;
using arcus::require_pointer;
using namespace arcus::api;

namespace {
thread_local std::string t_last_error;
}  // namespace

namespace arcus::api {

void set_thread_error(const std::string& message) { t_last_error = message; }

arcus_status bad_handle(const void* handle, arcus_status status, const std::string& message) {
  set_thread_error(message);
  const arcus::HandleRef other(arcus::retain_any_handle(handle));
  if (other) {
    arcus_context_t* ctx = context_of(other.get());
    arcus::ContextLock lock(ctx);
    ctx->last_error = message;
  }
  return status;
}

HandleRef hold(const void* handle, const HandleKind& kind, const char* name, arcus_status* status) {
  std::string message;
  HandleRef ref;
  arcus_context_t* reentered = nullptr;
  *status = run_catching(
      [&](std::string*) {
        ref = HandleRef(arcus::retain_handle(handle, kind, name, arcus::refuse_reentry, &reentered));
        return ARCUS_SUCCESS;
      },
      &message);
  if (*status == ARCUS_SUCCESS) return ref;
  if (reentered) {
    // This thread is inside a call on that context, which holds its lock and keeps it
    // alive: the message is stored without a lock or a reference.  No error callback:
    // it would run under the lock, and a callback that calls arcus would re-enter again.
    set_thread_error(message);
    reentered->last_error = message;
  } else {
    bad_handle(handle, *status, message);
  }
  return ref;
}

}  // namespace arcus::api

extern "C" {

const char* arcus_status_string(arcus_status status) {
  switch (status) {
    case ARCUS_SUCCESS: return "ARCUS_SUCCESS";
    case ARCUS_ERROR_INVALID_ARGUMENT: return "ARCUS_ERROR_INVALID_ARGUMENT";
    case ARCUS_ERROR_OUT_OF_MEMORY: return "ARCUS_ERROR_OUT_OF_MEMORY";
    case ARCUS_ERROR_DEVICE_NOT_FOUND: return "ARCUS_ERROR_DEVICE_NOT_FOUND";
    case ARCUS_ERROR_UNSUPPORTED: return "ARCUS_ERROR_UNSUPPORTED";
    case ARCUS_ERROR_KERNEL_BUILD: return "ARCUS_ERROR_KERNEL_BUILD";
    case ARCUS_ERROR_OPENCL: return "ARCUS_ERROR_OPENCL";
    case ARCUS_ERROR_IO: return "ARCUS_ERROR_IO";
    case ARCUS_ERROR_INVALID_RAYS: return "ARCUS_ERROR_INVALID_RAYS";
    case ARCUS_ERROR_PATH_OVERFLOW: return "ARCUS_ERROR_PATH_OVERFLOW";
    case ARCUS_ERROR_CANCELLED: return "ARCUS_ERROR_CANCELLED";
    case ARCUS_ERROR_REENTRANT: return "ARCUS_ERROR_REENTRANT";
    case ARCUS_ERROR_NOT_FINITE: return "ARCUS_ERROR_NOT_FINITE";
  }
  return "ARCUS_ERROR_UNKNOWN";
}

arcus_status arcus_get_version(int* major, int* minor, int* patch) {
  return without_context([&] {
    require(major && minor && patch, "major, minor and patch must not be NULL");
    *major = ARCUS_VERSION_MAJOR;
    *minor = ARCUS_VERSION_MINOR;
    *patch = ARCUS_VERSION_PATCH;
  });
}

const char* arcus_last_error(void) { return t_last_error.c_str(); }

arcus_status arcus_device_count(uint32_t* count) {
  return without_context([&] {
    require_pointer(count, "count");
    *count = static_cast<uint32_t>(arcus::devices().size());
  });
}

arcus_status arcus_device_get_info(uint32_t index, arcus_device_info* info) {
  return without_context([&] {
    require_pointer(info, "info");
    if (index >= arcus::devices().size())
      arcus::fail(ARCUS_ERROR_DEVICE_NOT_FOUND, "index " + std::to_string(index) + ": there are only " +
                                                    std::to_string(arcus::devices().size()) + " devices");
    *info = arcus::devices()[index].info;
  });
}

arcus_status arcus_context_create(int32_t device, arcus_context_t** out) {
  return without_context([&] {
    require_pointer(out, "out");
    *out = nullptr;
    const uint32_t index = arcus::resolve_device(device);
    *out = std::make_unique<arcus_context_s>(arcus::runtime_for(index)).release();
  });
}

arcus_status arcus_context_retain(arcus_context_t* ctx) { return retain(ctx, arcus::kContextHandle, "ctx"); }

arcus_status arcus_context_release(arcus_context_t* ctx) { return release(ctx, arcus::kContextHandle, "ctx"); }

arcus_status arcus_context_get_device(arcus_context_t* ctx, arcus_device_info* info) {
  return simple<arcus_context_s>(ctx, arcus::kContextHandle, "ctx", [&](arcus_context_s* c) {
    require_pointer(info, "info");
    *info = c->runtime->entry().info;
  });
}

const char* arcus_context_last_error(arcus_context_t* ctx) {
  if (!ctx) return "ctx is NULL";
  const HandleRef h(arcus::retain_any_handle(ctx));
  if (!h || &h.get()->kind() != &arcus::kContextHandle) return "ctx is not a live arcus context";
  // The caller holds a reference (this one is not the last), so the string outlives it.
  return ctx->last_error.c_str();
}

arcus_status arcus_context_set_error_callback(arcus_context_t* ctx, arcus_error_callback callback, void* user) {
  return simple<arcus_context_s>(ctx, arcus::kContextHandle, "ctx", [&](arcus_context_s* c) {
    c->callback = callback;
    c->callback_user = user;
  });
}

arcus_status arcus_features_to_string(arcus_features features, char* buffer, size_t size) {
  return without_context([&] {
    require_pointer(buffer, "buffer");
    const std::string s = arcus::feature_names(features);
    require(size > s.size(), "size: the buffer needs " + std::to_string(s.size() + 1) + " bytes");
    std::memcpy(buffer, s.c_str(), s.size() + 1);
  });
}

arcus_status arcus_job_retain(arcus_job_t* job) { return retain(job, arcus::kJobHandle, "job"); }

arcus_status arcus_job_release(arcus_job_t* job) { return release(job, arcus::kJobHandle, "job"); }

arcus_status arcus_job_get_count(arcus_job_t* job, size_t* count) {
  return simple<arcus_job_s>(job, arcus::kJobHandle, "job", [&](arcus_job_s* j) {
    require_pointer(count, "count");
    *count = j->count;
  });
}

arcus_status arcus_job_get_features(arcus_job_t* job, arcus_features* features) {
  return simple<arcus_job_s>(job, arcus::kJobHandle, "job", [&](arcus_job_s* j) {
    require_pointer(features, "features");
    *features = j->features;
  });
}

arcus_status arcus_job_get_stats(arcus_job_t* job, arcus_job_stats* stats) {
  return simple<arcus_job_s>(job, arcus::kJobHandle, "job", [&](arcus_job_s* j) {
    require_pointer(stats, "stats");
    *stats = j->stats;
  });
}

}  // extern "C"
