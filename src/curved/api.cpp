// The C entry points of arcus_curved.h: fields, advancing rays, and advance jobs.
#include <exception>
#include <memory>
#include <string>

#include "arcus/arcus_curved.h"
#include "core/call.h"
#include "curved/advance.h"
#include "curved/fields.h"

using arcus::require;
using arcus::require_pointer;
using arcus::curved::AdvanceJob;
using arcus::curved::FieldBuild;
using namespace arcus::api;

namespace {

// Creates a field of ctx from what build() returns (it throws on bad parameters).
template <class Build>
arcus_status make_field(arcus_context_t* ctx, arcus_field_t** out, Build&& build) {
  return simple<arcus_context_s>(ctx, arcus::kContextHandle, "ctx", [&](arcus_context_s* c) {
    require_pointer(out, "out");
    *out = nullptr;
    FieldBuild b = build();
    auto field = std::make_unique<arcus_field_s>(c);
    field->desc = b.desc;
    field->data = std::move(b.data);
    arcus::retain_context(c);  // the field's reference, dropped with it
    *out = field.release();
  });
}

// The results of an advance job; another engine's job is an invalid argument.
template <class Body>
arcus_status on_advance_job(arcus_job_t* job, Body&& body) {
  return on_job<AdvanceJob>(job, "an advance job", body);
}

}  // namespace

extern "C" {

arcus_status arcus_field_create_constant(arcus_context_t* ctx, double n, arcus_field_t** out) {
  return make_field(ctx, out, [&] { return arcus::curved::constant(n); });
}

arcus_status arcus_field_create_linear(arcus_context_t* ctx, double n0, const double gradient[3], arcus_field_t** out) {
  return make_field(ctx, out, [&] { return arcus::curved::linear(n0, gradient); });
}

arcus_status arcus_field_create_linear_n2(arcus_context_t* ctx, double a, const double k[3], arcus_field_t** out) {
  return make_field(ctx, out, [&] { return arcus::curved::linear_n2(a, k); });
}

arcus_status arcus_field_create_luneburg(arcus_context_t* ctx, const double center[3], double radius,
                                         arcus_field_t** out) {
  return make_field(ctx, out, [&] { return arcus::curved::luneburg(center, radius); });
}

arcus_status arcus_field_create_fisheye(arcus_context_t* ctx, const double center[3], double radius, double n0,
                                        arcus_field_t** out) {
  return make_field(ctx, out, [&] { return arcus::curved::fisheye(center, radius, n0); });
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
  return make_field(ctx, out, [&] {
    require_pointer(desc, "desc");
    return arcus::curved::atmosphere(*desc);
  });
}

arcus_status arcus_field_create_grid(arcus_context_t* ctx, const double* values, const uint32_t dims[3],
                                     const double origin[3], const double spacing[3], arcus_field_t** out) {
  return make_field(ctx, out, [&] {
    const size_t count = arcus::curved::grid_value_count(dims, origin, spacing);
    require_pointer(values, "values");
    return arcus::curved::grid(std::vector<double>(values, values + count), dims, origin, spacing);
  });
}

arcus_status arcus_field_create_grid_from_file(arcus_context_t* ctx, const char* path, int32_t type,
                                               const uint32_t dims[3], const double origin[3],
                                               const double spacing[3], arcus_field_t** out) {
  // The file is read before the context's lock is taken: a slow or blocking file must
  // not hold up every other call on the context.  Its errors are reported under the lock.
  arcus_status status;
  const arcus::HandleRef held = hold(ctx, arcus::kContextHandle, "ctx", &status);  // alive while unlocked
  if (!held) return status;
  std::vector<double> values;
  std::exception_ptr failed;
  if (out) {
    try {
      values = arcus::curved::read_grid_file(path, type, arcus::curved::grid_value_count(dims, origin, spacing));
    } catch (...) {
      failed = std::current_exception();
    }
  }
  return make_field(ctx, out, [&] {
    if (failed) std::rethrow_exception(failed);
    return arcus::curved::grid(std::move(values), dims, origin, spacing);
  });
}

arcus_status arcus_field_retain(arcus_field_t* field) { return retain(field, arcus::curved::kFieldHandle, "field"); }

arcus_status arcus_field_release(arcus_field_t* field) { return release(field, arcus::curved::kFieldHandle, "field"); }

arcus_status arcus_field_get_kind(arcus_field_t* field, arcus_field_kind* kind) {
  return simple<arcus_field_s>(field, arcus::curved::kFieldHandle, "field", [&](arcus_field_s* f) {
    require_pointer(kind, "kind");
    *kind = static_cast<arcus_field_kind>(f->desc.kind);
  });
}

arcus_status arcus_field_evaluate(arcus_field_t* field, size_t count, const double* positions, double* n,
                                  double* gradient) {
  return simple<arcus_field_s>(field, arcus::curved::kFieldHandle, "field", [&](arcus_field_s* f) {
    require(count == 0 || positions, "positions is NULL");
    require(count == 0 || n, "n is NULL");
    const medium m{&f->desc, f->data.data()};
    for (size_t i = 0; i < count; ++i) {
      const double* p = positions + 3 * i;
      double g[3];
      field_eval(&m, p[0], p[1], p[2], &n[i], &g[0], &g[1], &g[2]);
      if (gradient) std::copy(g, g + 3, gradient + 3 * i);
    }
  });
}

arcus_status arcus_advance_params_init(arcus_advance_params* params) {
  return without_context([&] {
    require_pointer(params, "params");
    arcus::curved::default_advance_params(params);
  });
}

arcus_status arcus_curved_advance(arcus_context_t* ctx, arcus_field_t* field, const arcus_advance_params* params,
                                  size_t count, const double* origins, const double* directions, const double* wavelengths,
                                  arcus_job_t** job) {
  return on<arcus_context_s>(ctx, arcus::kContextHandle, "ctx", [&](arcus_context_s* c, std::string* message) {
    require_pointer(job, "job");
    *job = nullptr;
    auto* f = object_of<arcus_field_s>(c, field, arcus::curved::kFieldHandle, "field");
    require_pointer(params, "params");
    return arcus::curved::advance(c, f, *params, count, origins, directions, wavelengths, job, message);
  });
}

arcus_status arcus_job_get_curved_end_states(arcus_job_t* job, double* positions, double* directions, uint64_t* steps,
                                             int32_t* status, double* lengths) {
  return on_advance_job(job, [&](AdvanceJob* j) {
    copy_out(j->positions, positions);
    copy_out(j->directions, directions);
    copy_out(j->steps, steps);
    copy_out(j->status, status);
    copy_out(j->lengths, lengths);
  });
}

arcus_status arcus_job_get_curved_failures(arcus_job_t* job, int32_t* failures) {
  return on_advance_job(job, [&](AdvanceJob* j) {
    require_pointer(failures, "failures");
    copy_out(j->failures, failures);
  });
}

arcus_status arcus_job_get_curved_path_size(arcus_job_t* job, size_t* total_points) {
  return on_advance_job(job, [&](AdvanceJob* j) {
    require_pointer(total_points, "total_points");
    require(!j->path_offsets.empty(), "job: the job was advanced without record_path");
    *total_points = j->path_offsets.back();
  });
}

arcus_status arcus_job_get_curved_paths(arcus_job_t* job, uint64_t* offsets, double* points, uint64_t* needed) {
  return on_advance_job(job, [&](AdvanceJob* j) {
    require(!j->path_offsets.empty(), "job: the job was advanced without record_path");
    copy_out(j->path_offsets, offsets);
    copy_out(j->path_points, points);
    copy_out(j->path_needed, needed);
  });
}

}  // extern "C"
