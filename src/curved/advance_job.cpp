#include "curved/advance_job.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdlib>
#include <limits>
#include <string>
#include <vector>

#include "advance.h"
#include "core/context.h"
#include "core/error.h"

namespace arcus {
namespace {

constexpr uint32_t kDefaultDpPathCapacity = 4096;
constexpr double kMaxPathBytes = 1024.0 * 1024.0 * 1024.0;  // default capacity stays under this

const char* method_name(arcus_method m) {
  switch (m) {
    case ARCUS_METHOD_EULER: return "EULER";
    case ARCUS_METHOD_RK2: return "RK2";
    case ARCUS_METHOD_RK4: return "RK4";
    default: return "DP45";
  }
}

// Whether v survives conversion to the kernel's precision: finite, and not flushed to 0.
bool representable(double v, bool single) {
  if (!single) return std::isfinite(v);
  const float f = static_cast<float>(v);
  return std::isfinite(f) && (v == 0 || f != 0);
}

void validate(const arcus_advance_params& p, const arcus_field_t* field, const DeviceEntry& device) {
  require(p.method >= ARCUS_METHOD_EULER && p.method <= ARCUS_METHOD_DP45,
          "params.method = " + std::to_string(p.method) + " is not an arcus_method");
  require(p.precision == ARCUS_PRECISION_DOUBLE || p.precision == ARCUS_PRECISION_FLOAT,
          "params.precision = " + std::to_string(p.precision) + " is not an arcus_precision");
  const bool single = p.precision == ARCUS_PRECISION_FLOAT;
  const char* in = single ? " in float precision" : "";
  auto number = [&](double v, const char* name) {
    require(representable(v, single), std::string("params.") + name + " = " + std::to_string(v) +
                                          " is not a finite number" + in);
  };
  number(p.length, "length");
  require(p.length > 0, "params.length must be positive");
  const bool straight = field->desc.kind == ARCUS_KIND_CONSTANT;
  if (p.method == ARCUS_METHOD_DP45 && !straight) {
    number(p.rtol, "rtol");
    number(p.atol, "atol");
    number(p.step, "step");
    number(p.min_step, "min_step");
    number(p.max_step, "max_step");
    require(p.rtol > 0, "params.rtol must be positive (got " + std::to_string(p.rtol) + ")");
    require(p.atol > 0, "params.atol must be positive (got " + std::to_string(p.atol) + ")");
    require(p.step >= 0, "params.step (the initial DP45 step, 0: automatic) must be >= 0");
    require(p.min_step >= 0, "params.min_step must be >= 0");
    require(p.min_step <= p.length, "params.min_step must not exceed params.length");
    require(p.max_step >= 0, "params.max_step must be >= 0 (0: unbounded)");
    require(p.max_step == 0 || p.max_step >= p.min_step, "params.max_step must be >= params.min_step");
    require(p.max_rejections >= 1, "params.max_rejections must be at least 1");
  } else if (!straight) {
    number(p.step, "step");
    require(p.step > 0, std::string("params.step must be positive for ") + method_name(p.method));
  }
  require(p.max_steps >= 1, "params.max_steps must be at least 1");
  require(p.use_box == 0 || p.use_box == 1, "params.use_box must be 0 or 1");
  if (p.use_box) {
    for (int a = 0; a < 3; ++a) {
      number(p.box_min[a], "box_min");
      number(p.box_max[a], "box_max");
      require(p.box_min[a] < p.box_max[a], "params.box_min[" + std::to_string(a) + "] must be < box_max");
    }
  }
  require(p.record_path == 0 || p.record_path == 1, "params.record_path must be 0 or 1");
  require(p.path_capacity <= static_cast<uint32_t>(std::numeric_limits<int32_t>::max()),
          "params.path_capacity must be at most 2^31 - 1");
  if (!single && !device.info.fp64)
    fail(ARCUS_ERROR_UNSUPPORTED, std::string("device '") + device.info.name +
                                      "' has no double precision (cl_khr_fp64); use ARCUS_PRECISION_FLOAT");
  if (single) {
    const arcus_field_desc_d& f = field->desc;
    const double values[] = {f.n0, f.inv_radius2, f.refractivity, f.earth_radius, f.geopotential_radius,
                             f.vec[0], f.vec[1], f.vec[2], f.origin[0], f.origin[1], f.origin[2],
                             f.inv_spacing[0], f.inv_spacing[1], f.inv_spacing[2]};
    bool ok = std::all_of(std::begin(values), std::end(values), [](double v) { return representable(v, true); }) &&
              std::all_of(field->data.begin(), field->data.end(), [](double v) { return representable(v, true); });
    require(ok, "field: its parameters or values do not fit in float precision; use ARCUS_PRECISION_DOUBLE");
  }
}

// Why a ray cannot be advanced in the kernel's precision ("" if it can): the kernel's
// own test — a finite origin, and a finite direction with a non-zero component.
std::string ray_problem(const double* o, const double* d, bool single) {
  auto value = [single](double v) { return single ? static_cast<double>(static_cast<float>(v)) : v; };
  const std::string in = single ? " in float precision" : "";
  bool nonzero = false;
  for (int a = 0; a < 3; ++a) {
    if (!std::isfinite(value(o[a]))) return "origin is not finite" + in;
    if (!std::isfinite(value(d[a]))) return "direction is not finite" + in;
    nonzero |= value(d[a]) != 0;
  }
  return nonzero ? "" : "direction is zero" + in;
}

uint32_t env_choice(const char* name, uint32_t fallback, std::initializer_list<uint32_t> allowed) {
  const char* v = std::getenv(name);
  if (!v || !*v) return fallback;
  uint32_t x = static_cast<uint32_t>(std::strtoul(v, nullptr, 10));
  for (uint32_t a : allowed)
    if (a == x) return x;
  fail(ARCUS_ERROR_INVALID_ARGUMENT, std::string(name) + "=" + v + " is not one of the allowed values");
}

// Field and job descriptions in the kernel's precision (same member names).
template <class To, class From>
To field_desc_as(const From& f) {
  To t{};
  t.n0 = f.n0;
  t.inv_radius2 = f.inv_radius2;
  t.refractivity = f.refractivity;
  t.earth_radius = f.earth_radius;
  t.geopotential_radius = f.geopotential_radius;
  for (int a = 0; a < 3; ++a) {
    t.vec[a] = f.vec[a];
    t.origin[a] = f.origin[a];
    t.inv_spacing[a] = f.inv_spacing[a];
    t.dims[a] = f.dims[a];
  }
  t.kind = f.kind;
  t.spherical = f.spherical;
  t.count = f.count;
  return t;
}

// fixed_step: the fixed step, the whole length for a straight job, 0 for DP45 (which reads
// p.step as its first trial step).
template <class Desc, class Real>
Desc make_advance_desc(const arcus_advance_params& p, double fixed_step, size_t stride) {
  Desc d{};
  const bool fixed = fixed_step > 0;
  d.length = static_cast<Real>(p.length);
  d.step = static_cast<Real>(fixed ? fixed_step : p.step);
  d.rtol = static_cast<Real>(p.rtol);
  d.atol = static_cast<Real>(p.atol);
  d.min_step = static_cast<Real>(p.min_step);
  d.max_step = static_cast<Real>(p.max_step);
  for (int a = 0; a < 3; ++a) {
    d.box_min[a] = static_cast<Real>(p.box_min[a]);
    d.box_max[a] = static_cast<Real>(p.box_max[a]);
  }
  const uint64_t int_max = static_cast<uint64_t>(std::numeric_limits<int32_t>::max());
  d.max_steps = static_cast<int32_t>(std::min<uint64_t>(p.max_steps, int_max));
  d.max_rejections = static_cast<int32_t>(std::min<uint64_t>(p.max_rejections, int_max));
  d.stride = static_cast<int32_t>(stride);
  if (fixed) {
    // The least n with n·step >= length, in the kernel's arithmetic, so the last step
    // ends exactly at `length`; capped by max_steps (the kernel then reports it).  When
    // max_steps stops the ray first, that n is never needed (and may not fit an int).
    const Real L = d.length, h = d.step;
    const uint64_t max_steps = std::min<uint64_t>(p.max_steps, int_max);
    double n = std::max(1.0, std::ceil(static_cast<double>(L / h)));
    const bool capped = n > static_cast<double>(max_steps) + 1.0;
    int64_t steps = capped ? static_cast<int64_t>(max_steps) + 1 : static_cast<int64_t>(n);
    if (!capped) {
      while (steps > 1 && static_cast<Real>(steps - 1) * h >= L) --steps;
      while (static_cast<Real>(steps) * h < L) ++steps;
    }
    if (static_cast<uint64_t>(steps) > max_steps) {
      steps = static_cast<int64_t>(max_steps);
      d.last_step = h;
    } else {
      d.last_step = L - static_cast<Real>(steps - 1) * h;
    }
    d.fixed_steps = static_cast<int32_t>(steps);
  }
  return d;
}

// Outside a Luneburg lens or a grid the field is constant, so the adaptive step grows
// without bound there and one step could jump over the whole medium unsampled.  Half
// the lens radius, or half the grid's smallest extent, keeps at least two stages of
// every crossing path inside, where the error estimate sees the medium.
double bounded_max_step(const arcus_advance_params& p, const arcus_field_desc_d& f) {
  double cap = 0;
  if (f.kind == ARCUS_KIND_LUNEBURG) cap = 0.5 / std::sqrt(f.inv_radius2);
  if (f.kind == ARCUS_KIND_GRID)
    for (int a = 0; a < 3; ++a) {
      double extent = (f.dims[a] - 1) / f.inv_spacing[a];
      cap = a == 0 ? 0.5 * extent : std::min(cap, 0.5 * extent);
    }
  if (cap == 0) return p.max_step;
  return p.max_step > 0 ? std::min(p.max_step, cap) : cap;
}

struct Launch {
  uint32_t features = 0;
  std::string options;
  uint32_t lanes = 1, groups = 1;
};

Launch plan(const arcus_advance_params& p, const arcus_field_t* field, const DeviceEntry& device) {
  Launch l;
  const bool straight = field->desc.kind == ARCUS_KIND_CONSTANT;
  const char* method = straight ? "STRAIGHT" : method_name(p.method);
  if (straight) {
    l.features |= ARCUS_FEATURE_STRAIGHT;
  } else {
    static const uint32_t method_bits[] = {ARCUS_FEATURE_EULER, ARCUS_FEATURE_RK2, ARCUS_FEATURE_RK4,
                                           ARCUS_FEATURE_DP45};
    l.features |= method_bits[p.method];
    l.features |= field->desc.kind == ARCUS_KIND_ATMOSPHERE ? ARCUS_FEATURE_ATMOSPHERE
                  : field->desc.kind == ARCUS_KIND_GRID     ? ARCUS_FEATURE_GRID
                                                            : ARCUS_FEATURE_ANALYTIC_FIELD;
  }
  // Lanes and independent groups per work-item (opencl-on-pocl.md).  Measured on PoCL
  // (bench --sweep-layout): 8 lanes × 4 groups is fastest for the fixed-step methods
  // (8 groups spill registers), 8 × 2 for DP45, whose seven stages hold more state.
  l.lanes = env_choice("ARCUS_LANES", device.info.lanes, {1, 2, 4, 8, 16});
  const uint32_t default_groups = device.info.is_gpu ? 1 : (p.method == ARCUS_METHOD_DP45 && !straight ? 2 : 4);
  l.groups = env_choice("ARCUS_GROUPS", straight ? 1 : default_groups, {1, 2, 3, 4, 6, 8, 12, 16});
  l.options = "-cl-std=CL1.2 -D ARCUS_LANES=" + std::to_string(l.lanes) + " -D ARCUS_GROUPS=" +
              std::to_string(l.groups) + " -D ARCUS_METHOD_" + method + " -D ARCUS_FIELD_KIND=" +
              std::to_string(field->desc.kind);
  if (p.use_box) {
    l.features |= ARCUS_FEATURE_BOX;
    l.options += " -D ARCUS_FEATURE_BOX";
  }
  if (p.record_path) {
    l.features |= ARCUS_FEATURE_RECORD_PATH;
    l.options += " -D ARCUS_FEATURE_RECORD_PATH";
  }
  if (p.precision == ARCUS_PRECISION_FLOAT) {
    l.features |= ARCUS_FEATURE_FLOAT;
    l.options += " -D ARCUS_FEATURE_FLOAT -cl-single-precision-constant";
  }
  return l;
}

ClMem make_buffer(cl_context ctx, cl_mem_flags flags, size_t bytes, const void* host = nullptr) {
  cl_int err = CL_SUCCESS;
  ClMem m(clCreateBuffer(ctx, flags | (host ? CL_MEM_COPY_HOST_PTR : 0), std::max<size_t>(bytes, 8),
                         const_cast<void*>(host), &err));
  if (err == CL_MEM_OBJECT_ALLOCATION_FAILURE || err == CL_OUT_OF_HOST_MEMORY || err == CL_OUT_OF_RESOURCES)
    fail(ARCUS_ERROR_OUT_OF_MEMORY, "could not allocate a device buffer of " + std::to_string(bytes) + " bytes");
  check_cl(err, "clCreateBuffer");
  return m;
}

void set_arg(cl_kernel k, cl_uint i, size_t size, const void* value) {
  check_cl(clSetKernelArg(k, i, size, value), "clSetKernelArg");
}

void read_buffer(cl_command_queue q, const ClMem& m, size_t bytes, void* out) {
  if (bytes) check_cl(clEnqueueReadBuffer(q, m.get(), CL_TRUE, 0, bytes, out, 0, nullptr, nullptr),
                      "clEnqueueReadBuffer");
}

// The field's data on the device, uploaded once per precision.
cl_mem field_buffer(arcus_field_t* field, cl_context ctx, bool single) {
  if (field->data.empty()) return nullptr;
  ClMem& m = field->device_data[single ? 1 : 0];
  if (!m) {
    if (single) {
      std::vector<float> f(field->data.begin(), field->data.end());
      m = make_buffer(ctx, CL_MEM_READ_ONLY, f.size() * sizeof(float), f.data());
    } else {
      m = make_buffer(ctx, CL_MEM_READ_ONLY, field->data.size() * sizeof(double), field->data.data());
    }
  }
  return m.get();
}

// Points kept per ray's path: the caller's path_capacity, else exactly enough for a
// fixed-step path (the origin and every step), else (DP45) up to 4096 as long as all
// rays' paths fit in 1 GiB.  Overflow is reported after the run, never silent.
uint32_t path_capacity(const arcus_advance_params& p, bool fixed, int32_t fixed_steps, size_t count, size_t real_bytes) {
  if (!p.record_path) return 0;
  const double rays = static_cast<double>(std::max<size_t>(count, 1)), point_bytes = 3.0 * real_bytes;
  double points = p.path_capacity;
  if (!points && fixed) points = fixed_steps + 1.0;
  if (!points) points = std::max(16.0, std::min<double>(kDefaultDpPathCapacity, kMaxPathBytes / (point_bytes * rays)));
  if (points * point_bytes * rays > (p.path_capacity ? 1e18 : kMaxPathBytes))
    fail(ARCUS_ERROR_OUT_OF_MEMORY, "record_path: " + std::to_string(count) + " paths of " +
                                        std::to_string(static_cast<uint64_t>(points)) + " points need " +
                                        std::to_string(points * point_bytes * rays / 1073741824.0) +
                                        " GiB; set params.path_capacity or advance fewer rays");
  return static_cast<uint32_t>(points);
}

// Runs the kernel in precision Real and stores the results into job.
template <class Real, class FieldDesc, class AdvanceDesc>
void run(arcus_context_t* ctx, arcus_field_t* field, const arcus_advance_params& p, const Launch& launch,
         cl_program program, size_t count, const double* origins, const double* directions, arcus_job_t* job) {
  cl_context clctx = ctx->runtime->context();
  const size_t per_item = static_cast<size_t>(launch.lanes) * launch.groups;
  const size_t items = std::max<size_t>(1, (count + per_item - 1) / per_item);
  const size_t stride = items * per_item;
  const bool dp45 = (launch.features & ARCUS_FEATURE_DP45) != 0;
  const bool straight = (launch.features & ARCUS_FEATURE_STRAIGHT) != 0;

  // Structure-of-arrays input; padding rays have a zero direction, so the kernel
  // marks them invalid and they never take a step.
  std::vector<Real> in(ARCUS_IN_COMPONENTS * stride, Real(0));
  for (size_t i = 0; i < count; ++i)
    for (int c = 0; c < 3; ++c) {
      in[c * stride + i] = static_cast<Real>(origins[3 * i + c]);
      in[(3 + c) * stride + i] = static_cast<Real>(directions[3 * i + c]);
    }
  ClMem in_buf = make_buffer(clctx, CL_MEM_READ_ONLY, in.size() * sizeof(Real), in.data());
  ClMem out_buf = make_buffer(clctx, CL_MEM_WRITE_ONLY, ARCUS_OUT_COMPONENTS * stride * sizeof(Real));
  ClMem steps_buf = make_buffer(clctx, CL_MEM_WRITE_ONLY, stride * sizeof(cl_ulong));
  ClMem status_buf = make_buffer(clctx, CL_MEM_WRITE_ONLY, stride * sizeof(cl_int));
  cl_mem data = field_buffer(field, clctx, sizeof(Real) == sizeof(float));
  FieldDesc fdesc = field_desc_as<FieldDesc>(field->desc);
  AdvanceDesc adesc = make_advance_desc<AdvanceDesc, Real>(p, dp45 ? 0.0 : straight ? p.length : p.step, stride);
  adesc.max_step = static_cast<Real>(bounded_max_step(p, field->desc));
  const uint32_t capacity = path_capacity(p, !dp45, adesc.fixed_steps, count, sizeof(Real));
  adesc.path_capacity = static_cast<int32_t>(capacity);
  job->path_capacity = capacity;
  // Only real rays record points (padding rays are invalid), so count × capacity.
  ClMem path_buf, points_buf;
  if (p.record_path) {
    path_buf = make_buffer(clctx, CL_MEM_WRITE_ONLY, count * capacity * 3 * sizeof(Real));
    points_buf = make_buffer(clctx, CL_MEM_WRITE_ONLY, stride * sizeof(cl_uint));
  }

  cl_int err = CL_SUCCESS;
  ClKernel kernel(clCreateKernel(program, "arcus_advance", &err));
  check_cl(err, "clCreateKernel");
  cl_mem bufs[] = {in_buf.get(), out_buf.get(), steps_buf.get(), status_buf.get(), path_buf.get(), points_buf.get()};
  for (cl_uint i = 0; i < 6; ++i) set_arg(kernel.get(), i, sizeof(cl_mem), bufs[i] ? &bufs[i] : nullptr);
  set_arg(kernel.get(), 6, sizeof fdesc, &fdesc);
  set_arg(kernel.get(), 7, sizeof(cl_mem), data ? &data : nullptr);
  set_arg(kernel.get(), 8, sizeof adesc, &adesc);

  // One work-item per work-group on CPUs: PoCL runs each group on one thread, and
  // many small groups balance the adaptive rays over the cores.
  const size_t local = ctx->runtime->entry().info.is_gpu ? 0 : 1;
  ClEvent event;
  cl_event ev = nullptr;
  check_cl(clEnqueueNDRangeKernel(ctx->queue.get(), kernel.get(), 1, nullptr, &items, local ? &local : nullptr, 0,
                                  nullptr, &ev),
           "clEnqueueNDRangeKernel");
  event = ClEvent(ev);
  check_cl(clWaitForEvents(1, &ev), "clWaitForEvents");
  cl_ulong t0 = 0, t1 = 0;
  if (clGetEventProfilingInfo(ev, CL_PROFILING_COMMAND_START, sizeof t0, &t0, nullptr) == CL_SUCCESS &&
      clGetEventProfilingInfo(ev, CL_PROFILING_COMMAND_END, sizeof t1, &t1, nullptr) == CL_SUCCESS)
    job->stats.kernel_seconds = (t1 - t0) * 1e-9;

  std::vector<Real> out(ARCUS_OUT_COMPONENTS * stride);
  read_buffer(ctx->queue.get(), out_buf, out.size() * sizeof(Real), out.data());
  job->steps.resize(stride);
  job->status.resize(stride);
  read_buffer(ctx->queue.get(), steps_buf, stride * sizeof(cl_ulong), job->steps.data());
  read_buffer(ctx->queue.get(), status_buf, stride * sizeof(cl_int), job->status.data());
  job->steps.resize(count);
  job->status.resize(count);
  job->positions.resize(3 * count);
  job->directions.resize(3 * count);
  job->lengths.resize(count);
  for (size_t i = 0; i < count; ++i) {
    for (int c = 0; c < 3; ++c) {
      job->positions[3 * i + c] = static_cast<double>(out[c * stride + i]);
      job->directions[3 * i + c] = static_cast<double>(out[(3 + c) * stride + i]);
    }
    job->lengths[i] = static_cast<double>(out[6 * stride + i]);
  }

  if (p.record_path) {
    std::vector<cl_uint> needed(stride);
    read_buffer(ctx->queue.get(), points_buf, stride * sizeof(cl_uint), needed.data());
    std::vector<Real> points(count * capacity * 3);
    read_buffer(ctx->queue.get(), path_buf, points.size() * sizeof(Real), points.data());
    job->path_offsets.assign(count + 1, 0);
    job->path_needed.assign(needed.begin(), needed.begin() + count);
    for (size_t i = 0; i < count; ++i)
      job->path_offsets[i + 1] = job->path_offsets[i] + std::min<uint64_t>(needed[i], capacity);
    job->path_points.resize(3 * job->path_offsets[count]);
    for (size_t i = 0; i < count; ++i) {
      const Real* src = points.data() + i * capacity * 3;
      std::copy(src, src + 3 * (job->path_offsets[i + 1] - job->path_offsets[i]),
                job->path_points.begin() + 3 * job->path_offsets[i]);
    }
  }
}

}  // namespace

void default_advance_params(arcus_advance_params* p) {
  *p = arcus_advance_params{};
  p->method = ARCUS_METHOD_DP45;
  p->precision = ARCUS_PRECISION_DOUBLE;
  p->length = 1.0;
  p->step = 0.0;
  p->rtol = 1e-9;
  p->atol = 1e-12;
  p->min_step = 1e-12;
  p->max_step = 0.0;
  p->max_rejections = 64;
  p->max_steps = 10000000;
  p->use_box = 0;
  p->record_path = 0;
  p->path_capacity = 0;
}

std::string feature_names(uint32_t features) {
  static const char* names[] = {"STRAIGHT", "EULER", "RK2", "RK4", "DP45", "ANALYTIC_FIELD",
                                "ATMOSPHERE", "GRID", "BOX", "RECORD_PATH", "FLOAT"};
  std::string s;
  for (unsigned b = 0; b < sizeof names / sizeof *names; ++b)
    if (features & (1u << b)) s += (s.empty() ? "" : " ") + std::string(names[b]);
  return s;
}

arcus_status advance(arcus_context_t* ctx, arcus_field_t* field, const arcus_advance_params& p, size_t count,
                     const double* origins, const double* directions, arcus_job_t** job_out, std::string* message) {
  auto start = std::chrono::steady_clock::now();
  require(field->ctx == ctx, "field belongs to another context");
  require(count == 0 || origins, "origins is NULL");
  require(count == 0 || directions, "directions is NULL");
  require(count <= (size_t(1) << 30), "count: more than 2^30 rays in one call");
  const DeviceEntry& device = ctx->runtime->entry();
  validate(p, field, device);

  Launch launch = plan(p, field, device);
  BuiltProgram program = ctx->runtime->program(launch.options);

  auto job = std::make_unique<arcus_job_s>();
  job->count = count;
  job->features = launch.features;
  job->stats.build_seconds = program.build_seconds;
  job->stats.cache_hit = program.cache_hit ? 1 : 0;
  job->stats.lanes = launch.lanes;
  job->stats.groups = launch.groups;
  if (count > 0) {
    if (p.precision == ARCUS_PRECISION_FLOAT)
      run<float, arcus_field_desc_f, arcus_advance_desc_f>(ctx, field, p, launch, program.program, count, origins,
                                                            directions, job.get());
    else
      run<double, arcus_field_desc_d, arcus_advance_desc_d>(ctx, field, p, launch, program.program, count,
                                                             origins, directions, job.get());
  } else if (p.record_path) {
    job->path_offsets.assign(1, 0);
  }
  job->stats.total_seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();

  // Bad rays are counted as the kernel judged them, explained by the host's same test.
  const bool single = p.precision == ARCUS_PRECISION_FLOAT;
  size_t bad = 0;
  std::string first_bad;
  for (size_t i = 0; i < count; ++i)
    if (job->status[i] == ARCUS_RAY_INVALID_INPUT && bad++ < 3) {
      std::string why = ray_problem(origins + 3 * i, directions + 3 * i, single);
      first_bad += (first_bad.empty() ? "" : "; ") + ("ray " + std::to_string(i) + ": " +
                                                      (why.empty() ? "invalid input" : why));
    }

  const uint32_t capacity = job->path_capacity;
  size_t overflowed = 0;
  uint64_t longest = 0;
  for (size_t i = 0; i < job->path_needed.size(); ++i)
    if (job->path_needed[i] > capacity) {
      ++overflowed;
      longest = std::max(longest, job->path_needed[i]);
    }

  arcus_status status = ARCUS_SUCCESS;
  message->clear();
  if (bad) {
    status = ARCUS_ERROR_INVALID_RAYS;
    *message = std::to_string(bad) + " of " + std::to_string(count) + " rays have invalid input (" + first_bad +
               (bad > 3 ? "; ..." : "") + "); they are marked ARCUS_RAY_INVALID_INPUT, the others were advanced";
  }
  if (overflowed) {
    if (!bad) status = ARCUS_ERROR_PATH_OVERFLOW;
    *message += (message->empty() ? "" : "; ") + std::string("record_path: ") + std::to_string(overflowed) +
                " rays needed more than path_capacity = " + std::to_string(capacity) +
                " points (the longest needs " + std::to_string(longest) +
                "); their paths hold the first points only; set params.path_capacity";
  }
  job->ctx = ctx;
  ctx->refs.fetch_add(1);
  *job_out = job.release();
  return status;
}

}  // namespace arcus
