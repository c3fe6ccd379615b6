// The C entry points: argument checks, locking, and turning exceptions into statuses
// and last-error messages.  The work itself lives in runtime.cpp and curved/.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <fstream>
#include <functional>
#include <memory>
#include <new>
#include <string>

#include "arcus/arcus.h"
#include "core/context.h"
#include "core/error.h"
#include "curved/advance_job.h"
#include "curved/fields.h"

using arcus::Error;
using arcus::fail;
using arcus::require;
using arcus::require_pointer;

namespace {

thread_local std::string t_last_error;

// A null handle: there is no context to keep the message on.
arcus_status null_handle(const char* name) {
  t_last_error = std::string(name) + " is NULL";
  return ARCUS_ERROR_INVALID_ARGUMENT;
}

// Runs body (returning an arcus_status; exceptions become statuses) and leaves the
// message of a failure in *message.
template <class Body>
arcus_status run_catching(Body&& body, std::string* message) {
  arcus_status status = ARCUS_SUCCESS;
  try {
    status = body(message);
  } catch (const Error& e) {
    status = e.status();
    *message = e.what();
  } catch (const std::bad_alloc&) {
    status = ARCUS_ERROR_OUT_OF_MEMORY;
    *message = "out of host memory";
  } catch (const std::exception& e) {
    status = ARCUS_ERROR_INVALID_ARGUMENT;
    *message = e.what();
  }
  return status;
}

// A call that needs no context (device queries, creation).
template <class Body>
arcus_status without_context(Body&& body) {
  std::string message;
  arcus_status status = run_catching(
      [&](std::string*) {
        body();
        return ARCUS_SUCCESS;
      },
      &message);
  if (status != ARCUS_SUCCESS) t_last_error = message;
  return status;
}

// A call on ctx: null-checked, locked, errors kept on the context.
template <class Body>
arcus_status with_context(arcus_context_t* ctx, const char* handle_name, Body&& body) {
  if (!ctx) return null_handle(handle_name);
  std::string message;
  arcus_status status;
  arcus_error_callback callback;
  void* user;
  {
    std::lock_guard<std::mutex> lock(ctx->lock);
    status = run_catching(body, &message);
    if (status != ARCUS_SUCCESS) ctx->last_error = message;
    callback = ctx->callback;
    user = ctx->callback_user;
  }
  // Outside the lock, so that the callback may call arcus (on this context too).
  if (status != ARCUS_SUCCESS && callback) callback(user, status, message.c_str());
  return status;
}

template <class Body>
arcus_status simple(arcus_context_t* ctx, const char* handle_name, Body&& body) {
  return with_context(ctx, handle_name, [&](std::string*) {
    body();
    return ARCUS_SUCCESS;
  });
}

arcus_context_t* ctx_of(arcus_field_t* f) { return f ? f->ctx : nullptr; }
arcus_context_t* ctx_of(arcus_job_t* j) { return j ? j->ctx : nullptr; }

// Retain and release of the objects that belong to a context (fields, jobs): the last
// release frees the object under its context's lock, then drops the context.
template <class T>
arcus_status retain(T* object, const char* name) {
  if (!object) return null_handle(name);
  object->refs.fetch_add(1);
  return ARCUS_SUCCESS;
}

template <class T>
arcus_status release(T* object, const char* name) {
  if (!object) return null_handle(name);
  if (object->refs.fetch_sub(1) == 1) {
    arcus_context_t* ctx = object->ctx;
    {
      std::lock_guard<std::mutex> lock(ctx->lock);
      delete object;
    }
    arcus::release_context(ctx);
  }
  return ARCUS_SUCCESS;
}

// Creates a field of ctx from a filled description and data.
arcus_status make_field(arcus_context_t* ctx, arcus_field_t** out,
                        const std::function<void(arcus_field_desc_d*, std::vector<double>*)>& build) {
  return simple(ctx, "ctx", [&] {
    require_pointer(out, "out");
    *out = nullptr;
    auto field = std::make_unique<arcus_field_s>();
    build(&field->desc, &field->data);
    field->ctx = ctx;
    ctx->refs.fetch_add(1);
    *out = field.release();
  });
}

void require_finite(double v, const char* name) {
  require(std::isfinite(v), std::string(name) + " is not finite");
}
void require_finite3(const double* v, const char* name) {
  require_pointer(v, name);
  for (int a = 0; a < 3; ++a) require(std::isfinite(v[a]), std::string(name) + "[" + std::to_string(a) + "] is not finite");
}

}  // namespace

namespace arcus {
void release_context(arcus_context_t* ctx) {
  if (ctx->refs.fetch_sub(1) == 1) delete ctx;
}
}  // namespace arcus

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
      fail(ARCUS_ERROR_DEVICE_NOT_FOUND, "index " + std::to_string(index) + ": there are only " +
                                             std::to_string(arcus::devices().size()) + " devices");
    *info = arcus::devices()[index].info;
  });
}

arcus_status arcus_context_create(int32_t device, arcus_context_t** out) {
  return without_context([&] {
    require_pointer(out, "out");
    *out = nullptr;
    uint32_t index = arcus::resolve_device(device);
    auto ctx = std::make_unique<arcus_context_s>();
    ctx->runtime = arcus::runtime_for(index);
    cl_int err = CL_SUCCESS;
    ctx->queue = arcus::ClQueue(clCreateCommandQueue(ctx->runtime->context(), ctx->runtime->entry().device,
                                                     CL_QUEUE_PROFILING_ENABLE, &err));
    arcus::check_cl(err, "clCreateCommandQueue");
    *out = ctx.release();
  });
}

arcus_status arcus_context_retain(arcus_context_t* ctx) {
  if (!ctx) return null_handle("ctx");
  ctx->refs.fetch_add(1);
  return ARCUS_SUCCESS;
}

arcus_status arcus_context_release(arcus_context_t* ctx) {
  if (!ctx) return null_handle("ctx");
  arcus::release_context(ctx);
  return ARCUS_SUCCESS;
}

arcus_status arcus_context_get_device(arcus_context_t* ctx, arcus_device_info* info) {
  return simple(ctx, "ctx", [&] {
    require_pointer(info, "info");
    *info = ctx->runtime->entry().info;
  });
}

const char* arcus_context_last_error(arcus_context_t* ctx) {
  if (!ctx) return "ctx is NULL";
  return ctx->last_error.c_str();
}

arcus_status arcus_context_set_error_callback(arcus_context_t* ctx, arcus_error_callback callback, void* user) {
  return simple(ctx, "ctx", [&] {
    ctx->callback = callback;
    ctx->callback_user = user;
  });
}

/* ---- fields ---- */

arcus_status arcus_field_create_constant(arcus_context_t* ctx, double n, arcus_field_t** out) {
  return make_field(ctx, out, [&](arcus_field_desc_d* d, std::vector<double>*) {
    require(std::isfinite(n) && n > 0, "n must be positive and finite");
    d->kind = ARCUS_FIELD_CONSTANT;
    d->n0 = n;
  });
}

arcus_status arcus_field_create_linear(arcus_context_t* ctx, double n0, const double gradient[3],
                                       arcus_field_t** out) {
  return make_field(ctx, out, [&](arcus_field_desc_d* d, std::vector<double>*) {
    require_finite(n0, "n0");
    require_finite3(gradient, "gradient");
    d->kind = ARCUS_FIELD_LINEAR;
    d->n0 = n0;
    std::copy(gradient, gradient + 3, d->vec);
  });
}

arcus_status arcus_field_create_linear_n2(arcus_context_t* ctx, double a, const double k[3], arcus_field_t** out) {
  return make_field(ctx, out, [&](arcus_field_desc_d* d, std::vector<double>*) {
    require_finite(a, "a");
    require_finite3(k, "k");
    d->kind = ARCUS_FIELD_LINEAR_N2;
    d->n0 = a;
    std::copy(k, k + 3, d->vec);
  });
}

arcus_status arcus_field_create_luneburg(arcus_context_t* ctx, const double center[3], double radius,
                                         arcus_field_t** out) {
  return make_field(ctx, out, [&](arcus_field_desc_d* d, std::vector<double>*) {
    require_finite3(center, "center");
    require(std::isfinite(radius) && radius > 0, "radius must be positive and finite");
    d->kind = ARCUS_FIELD_LUNEBURG;
    d->inv_radius2 = 1.0 / (radius * radius);
    std::copy(center, center + 3, d->vec);
  });
}

arcus_status arcus_field_create_fisheye(arcus_context_t* ctx, const double center[3], double radius, double n0,
                                        arcus_field_t** out) {
  return make_field(ctx, out, [&](arcus_field_desc_d* d, std::vector<double>*) {
    require_finite3(center, "center");
    require(std::isfinite(radius) && radius > 0, "radius must be positive and finite");
    require(std::isfinite(n0) && n0 > 0, "n0 must be positive and finite");
    d->kind = ARCUS_FIELD_FISHEYE;
    d->n0 = n0;
    d->inv_radius2 = 1.0 / (radius * radius);
    std::copy(center, center + 3, d->vec);
  });
}

arcus_status arcus_atmosphere_desc_init(arcus_atmosphere_desc* desc) {
  return without_context([&] {
    require_pointer(desc, "desc");
    *desc = arcus_atmosphere_desc{};
    desc->spherical = 0;
    desc->wavelength = 550.0;
    desc->sea_level_temperature = 288.15;
    desc->sea_level_pressure = 101325.0;
  });
}

arcus_status arcus_field_create_atmosphere(arcus_context_t* ctx, const arcus_atmosphere_desc* desc,
                                           arcus_field_t** out) {
  return make_field(ctx, out, [&](arcus_field_desc_d* d, std::vector<double>* data) {
    require_pointer(desc, "desc");
    arcus::build_atmosphere(*desc, d, data);
  });
}

arcus_status arcus_field_create_grid(arcus_context_t* ctx, const double* values, const uint32_t dims[3],
                                     const double origin[3], const double spacing[3], arcus_field_t** out) {
  return make_field(ctx, out, [&](arcus_field_desc_d* d, std::vector<double>* data) {
    arcus::build_grid(values, dims, origin, spacing, d, data);
  });
}

arcus_status arcus_field_create_grid_from_file(arcus_context_t* ctx, const char* path, arcus_scalar_type type,
                                               const uint32_t dims[3], const double origin[3],
                                               const double spacing[3], arcus_field_t** out) {
  return make_field(ctx, out, [&](arcus_field_desc_d* d, std::vector<double>* data) {
    require_pointer(path, "path");
    require_pointer(dims, "dims");
    require(type == ARCUS_FLOAT32 || type == ARCUS_FLOAT64, "type must be ARCUS_FLOAT32 or ARCUS_FLOAT64");
    const size_t count = arcus::grid_value_count(dims, origin, spacing);
    const size_t width = type == ARCUS_FLOAT32 ? 4 : 8;
    std::ifstream file(path, std::ios::binary | std::ios::ate);
    if (!file) fail(ARCUS_ERROR_IO, std::string("path: cannot open '") + path + "'");
    const std::streamoff end = file.tellg();
    if (end < 0) fail(ARCUS_ERROR_IO, std::string("path: cannot read '") + path + "' (not a regular file?)");
    const auto size = static_cast<size_t>(end);
    if (size != count * width)
      fail(ARCUS_ERROR_IO, std::string("path: '") + path + "' holds " + std::to_string(size) + " bytes, but " +
                               std::to_string(dims[0]) + "x" + std::to_string(dims[1]) + "x" +
                               std::to_string(dims[2]) + " values of " + std::to_string(width) + " bytes need " +
                               std::to_string(count * width));
    file.seekg(0);
    std::vector<double> values(count);
    if (type == ARCUS_FLOAT64) {
      file.read(reinterpret_cast<char*>(values.data()), static_cast<std::streamsize>(size));
    } else {
      std::vector<float> f(count);
      file.read(reinterpret_cast<char*>(f.data()), static_cast<std::streamsize>(size));
      values.assign(f.begin(), f.end());
    }
    if (!file) fail(ARCUS_ERROR_IO, std::string("path: reading '") + path + "' failed");
    arcus::build_grid(values.data(), dims, origin, spacing, d, data);
  });
}

arcus_status arcus_field_retain(arcus_field_t* field) { return retain(field, "field"); }

arcus_status arcus_field_release(arcus_field_t* field) { return release(field, "field"); }

arcus_status arcus_field_get_kind(arcus_field_t* field, arcus_field_kind* kind) {
  return simple(ctx_of(field), "field", [&] {
    require_pointer(kind, "kind");
    *kind = static_cast<arcus_field_kind>(field->desc.kind);
  });
}

arcus_status arcus_field_evaluate(arcus_field_t* field, size_t count, const double* positions, double* n,
                                  double* gradient) {
  return simple(ctx_of(field), "field", [&] {
    require(count == 0 || positions, "positions is NULL");
    require(count == 0 || n, "n is NULL");
    for (size_t i = 0; i < count; ++i) {
      const double* p = positions + 3 * i;
      double g[3];
      field_eval(&field->desc, field->data.data(), p[0], p[1], p[2], &n[i], &g[0], &g[1], &g[2]);
      if (gradient) std::copy(g, g + 3, gradient + 3 * i);
    }
  });
}

/* ---- advance and jobs ---- */

arcus_status arcus_advance_params_init(arcus_advance_params* params) {
  return without_context([&] {
    require_pointer(params, "params");
    arcus::default_advance_params(params);
  });
}

arcus_status arcus_features_to_string(uint32_t features, char* buffer, size_t size) {
  return without_context([&] {
    require_pointer(buffer, "buffer");
    std::string s = arcus::feature_names(features);
    require(size > s.size(), "size: the buffer needs " + std::to_string(s.size() + 1) + " bytes");
    std::memcpy(buffer, s.c_str(), s.size() + 1);
  });
}

arcus_status arcus_advance(arcus_context_t* ctx, arcus_field_t* field, const arcus_advance_params* params,
                           size_t count, const double* origins, const double* directions, arcus_job_t** job) {
  return with_context(ctx, "ctx", [&](std::string* message) {
    require_pointer(job, "job");
    *job = nullptr;
    require_pointer(field, "field");
    require_pointer(params, "params");
    return arcus::advance(ctx, field, *params, count, origins, directions, job, message);
  });
}

arcus_status arcus_job_retain(arcus_job_t* job) { return retain(job, "job"); }

arcus_status arcus_job_release(arcus_job_t* job) { return release(job, "job"); }

arcus_status arcus_job_get_count(arcus_job_t* job, size_t* count) {
  return simple(ctx_of(job), "job", [&] {
    require_pointer(count, "count");
    *count = job->count;
  });
}

arcus_status arcus_job_get_end_states(arcus_job_t* job, double* positions, double* directions, uint64_t* steps,
                                      int32_t* status, double* lengths) {
  return simple(ctx_of(job), "job", [&] {
    if (positions) std::copy(job->positions.begin(), job->positions.end(), positions);
    if (directions) std::copy(job->directions.begin(), job->directions.end(), directions);
    if (steps) std::copy(job->steps.begin(), job->steps.end(), steps);
    if (status) std::copy(job->status.begin(), job->status.end(), status);
    if (lengths) std::copy(job->lengths.begin(), job->lengths.end(), lengths);
  });
}

arcus_status arcus_job_get_path_size(arcus_job_t* job, size_t* total_points) {
  return simple(ctx_of(job), "job", [&] {
    require_pointer(total_points, "total_points");
    require(!job->path_offsets.empty(), "job: the job was advanced without record_path");
    *total_points = job->path_offsets.back();
  });
}

arcus_status arcus_job_get_paths(arcus_job_t* job, uint64_t* offsets, double* points, uint64_t* needed) {
  return simple(ctx_of(job), "job", [&] {
    require(!job->path_offsets.empty(), "job: the job was advanced without record_path");
    if (offsets) std::copy(job->path_offsets.begin(), job->path_offsets.end(), offsets);
    if (points) std::copy(job->path_points.begin(), job->path_points.end(), points);
    if (needed) std::copy(job->path_needed.begin(), job->path_needed.end(), needed);
  });
}

arcus_status arcus_job_get_features(arcus_job_t* job, uint32_t* features) {
  return simple(ctx_of(job), "job", [&] {
    require_pointer(features, "features");
    *features = job->features;
  });
}

arcus_status arcus_job_get_stats(arcus_job_t* job, arcus_job_stats* stats) {
  return simple(ctx_of(job), "job", [&] {
    require_pointer(stats, "stats");
    *stats = job->stats;
  });
}

}  // extern "C"
