// The objects behind the public handles.  Each holds a reference count; fields and
// jobs retain their context.  Every call on a context serialises on ctx->lock.
#pragma once

#include <atomic>
#include <memory>
#include <mutex>
#include <string>
#include <vector>

#include "arcus/arcus.h"
#include "core/opencl.h"
#include "core/runtime.h"
#include "field.h"

struct arcus_context_s {
  std::atomic<int> refs{1};
  std::mutex lock;
  std::shared_ptr<arcus::DeviceRuntime> runtime;
  arcus::ClQueue queue;
  std::string last_error;
  arcus_error_callback callback = nullptr;
  void* callback_user = nullptr;
};

struct arcus_field_s {
  std::atomic<int> refs{1};
  arcus_context_t* ctx = nullptr;  // retained
  arcus_field_desc_d desc{};       // kind, parameters (double)
  std::vector<double> data;        // atmosphere segments or grid values
  arcus::ClMem device_data[2];     // data uploaded per precision (double, float), lazily
};

struct arcus_job_s {
  std::atomic<int> refs{1};
  arcus_context_t* ctx = nullptr;  // retained
  size_t count = 0;
  std::vector<double> positions, directions, lengths;  // count×3, count×3, count
  std::vector<uint64_t> steps;
  std::vector<int32_t> status;
  uint32_t path_capacity = 0;          // points kept per ray
  std::vector<uint64_t> path_offsets;  // count+1 (empty without record_path)
  std::vector<uint64_t> path_needed;   // count
  std::vector<double> path_points;     // path_offsets[count]×3
  uint32_t features = 0;
  arcus_job_stats stats{};
};

namespace arcus {
// Releases one reference; frees at zero.  Shared by the C entry points.
void release_context(arcus_context_t* ctx);
}  // namespace arcus
