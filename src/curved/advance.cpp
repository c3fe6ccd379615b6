#include "curved/advance.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <limits>
#include <string>
#include <vector>

#include "core/context.h"
#include "core/error.h"
#include "core/limits.h"
#include "core/format.h"
#include "curved/fields.h"

namespace arcus::curved {
namespace {

constexpr uint32_t kDefaultDpPathCapacity = 4096;
constexpr double kMaxDefaultPathBytes = 1024.0 * 1024.0 * 1024.0;  // a default capacity stays under this
constexpr uint32_t kCpuGroupsFixed = 4;  // measured (bench --sweep-layout): 8 lanes × 4 groups
constexpr uint32_t kCpuGroupsDp45 = 2;   // DP45's seven stages hold more state: 8 × 2
constexpr double kFirstSliceRaySteps = 1 << 24;  // ≈ 20 ms of RK4 on two cores
constexpr int32_t kFirstSliceAttempts = 256;     // DP45: most rays finish in one slice

const char* method_name(int32_t m) {
  switch (m) {
    case ARCUS_METHOD_EULER: return "Euler";
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

}  // namespace

void check_advance_params(const arcus_advance_params& p, bool straight) {
  // Enumerations arrive as int32_t members: checked before any use as an enum.
  require(p.method >= ARCUS_METHOD_EULER && p.method <= ARCUS_METHOD_DP45,
          "params.method = " + std::to_string(p.method) + " is not an arcus_method");
  require(p.precision == ARCUS_PRECISION_DOUBLE || p.precision == ARCUS_PRECISION_FLOAT,
          "params.precision = " + std::to_string(p.precision) + " is not an arcus_precision");
  const bool single = p.precision == ARCUS_PRECISION_FLOAT;
  const char* in = single ? " in float precision" : "";
  auto finite = [&](double v, const char* name) {
    require(representable(v, single), std::string("params.") + name + " = " + number(v) + " is not a finite number" + in);
  };
  finite(p.length, "length");
  require(p.length > 0, "params.length = " + number(p.length) + " must be positive");
  if (p.method == ARCUS_METHOD_DP45 && !straight) {
    finite(p.rtol, "rtol");
    finite(p.atol, "atol");
    finite(p.step, "step");
    finite(p.min_step, "min_step");
    finite(p.max_step, "max_step");
    require(p.rtol > 0, "params.rtol = " + number(p.rtol) + " must be positive");
    require(p.atol > 0, "params.atol = " + number(p.atol) + " must be positive");
    require(p.step >= 0, "params.step (the initial DP45 step, 0: automatic) must be >= 0");
    require(p.min_step >= 0, "params.min_step must be >= 0");
    require(p.min_step <= p.length, "params.min_step must not exceed params.length");
    require(p.max_step >= 0, "params.max_step must be >= 0 (0: unbounded)");
    require(p.max_step == 0 || p.max_step >= p.min_step, "params.max_step must be >= params.min_step");
    require(p.max_rejections >= 1, "params.max_rejections must be at least 1");
  } else if (!straight) {
    finite(p.step, "step");
    require(p.step > 0, std::string("params.step = ") + number(p.step) + " must be positive for " + method_name(p.method));
  }
  require(p.max_steps >= 1, "params.max_steps must be at least 1");
  require(p.use_box == 0 || p.use_box == 1, "params.use_box must be 0 or 1");
  if (p.use_box) {
    for (int a = 0; a < 3; ++a) {
      finite(p.box_min[a], "box_min");
      finite(p.box_max[a], "box_max");
      require(p.box_min[a] < p.box_max[a], "params.box_min[" + std::to_string(a) + "] must be < box_max");
    }
  }
  require(p.record_path == 0 || p.record_path == 1, "params.record_path must be 0 or 1");
  require(p.path_capacity <= static_cast<uint32_t>(std::numeric_limits<int32_t>::max()),
          "params.path_capacity must be at most 2^31 - 1");
}

namespace {

void validate(const arcus_advance_params& p, const arcus_field_desc_d& field, const std::vector<double>& data,
              const arcus_device_info& device) {
  check_advance_params(p, field.kind == ARCUS_KIND_CONSTANT);
  const bool single = p.precision == ARCUS_PRECISION_FLOAT;
  if (!single && !device.fp64)
    fail(ARCUS_ERROR_UNSUPPORTED, std::string("device '") + device.name +
                                      "' has no double precision (cl_khr_fp64); use ARCUS_PRECISION_FLOAT");
  if (single) {
    const arcus_field_desc_d& f = field;
    const double values[] = {f.n0, f.inv_radius2, f.refractivity, f.earth_radius, f.geopotential_radius,
                             f.vec[0], f.vec[1], f.vec[2], f.origin[0], f.origin[1], f.origin[2],
                             f.inv_spacing[0], f.inv_spacing[1], f.inv_spacing[2]};
    bool ok = std::all_of(std::begin(values), std::end(values), [](double v) { return representable(v, true); }) &&
              std::all_of(data.begin(), data.end(), [](double v) { return representable(v, true); });
    require(ok, "field: its parameters or values do not fit in float precision; use ARCUS_PRECISION_DOUBLE");
  }
}

// Why a ray cannot be advanced in the kernel's precision ("" if it can): the kernel's
// own test — a finite origin, a finite direction with a non-zero component, and (with
// per-ray wavelengths in a dispersive field) a wavelength in Ciddor's range.
std::string ray_problem(const double* o, const double* d, const double* wavelength, bool single) {
  auto value = [single](double v) { return single ? static_cast<double>(static_cast<float>(v)) : v; };
  const std::string in = single ? " in float precision" : "";
  bool nonzero = false;
  for (int a = 0; a < 3; ++a) {
    if (!std::isfinite(value(o[a]))) return "origin is not finite" + in;
    if (!std::isfinite(value(d[a]))) return "direction is not finite" + in;
    nonzero |= value(d[a]) != 0;
  }
  if (!nonzero) return "direction is zero" + in;
  if (wavelength && !(*wavelength >= ARCUS_MIN_WAVELENGTH && *wavelength <= ARCUS_MAX_WAVELENGTH))
    return "wavelength " + number(*wavelength) + " nm is outside 300..1690 nm";
  return "";
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
  t.layer = f.layer;
  t.layer_above = f.layer_above;
  t.inversions_top = f.inversions_top;
  t.layers_top = f.layers_top;
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

// How close to the box a crossing must end: the job's own tolerance for DP45, else a
// few units in the last place of the box's coordinates.
double crossing_tolerance(const arcus_advance_params& p, bool dp45, bool single) {
  double scale = 0;
  for (int a = 0; a < 3; ++a) scale = std::max({scale, std::fabs(p.box_min[a]), std::fabs(p.box_max[a])});
  if (dp45) return p.atol + p.rtol * scale;
  return (single ? 1e-6 : 1e-12) * std::max(scale, 1.0);
}

template <class AdvanceDesc, class Real>
AdvanceDesc make_advance_desc(const arcus_advance_params& p, const arcus_field_desc_d& f, const Plan& plan,
                              size_t stride) {
  AdvanceDesc d{};
  d.length = static_cast<Real>(p.length);
  d.step = static_cast<Real>(plan.dp45 ? p.step : plan.straight ? p.length : p.step);
  d.rtol = static_cast<Real>(p.rtol);
  d.atol = static_cast<Real>(p.atol);
  d.min_step = static_cast<Real>(p.min_step);
  d.max_step = static_cast<Real>(bounded_max_step(p, f));
  for (int a = 0; a < 3; ++a) {
    d.box_min[a] = static_cast<Real>(p.box_min[a]);
    d.box_max[a] = static_cast<Real>(p.box_max[a]);
  }
  d.cross_tol = static_cast<Real>(crossing_tolerance(p, plan.dp45, plan.single));
  const uint64_t int_max = static_cast<uint64_t>(std::numeric_limits<int32_t>::max());
  d.max_steps = static_cast<int32_t>(std::min<uint64_t>(p.max_steps, int_max));
  d.max_rejections = static_cast<int32_t>(std::min<uint64_t>(p.max_rejections, int_max));
  d.stride = static_cast<int32_t>(stride);
  if (!plan.dp45) {
    const FixedSteps fs = fixed_steps<Real>(p.length, static_cast<double>(d.step), p.max_steps);
    d.fixed_steps = fs.steps;
    d.last_step = static_cast<Real>(fs.last_step);
  }
  return d;
}

// Points kept per ray's path: the caller's path_capacity, else exactly enough for a
// fixed-step path (the origin and every step), else (DP45) up to 4096 as long as all
// rays' paths fit in 1 GiB.  Overflow is reported after the run, never silent.
uint32_t path_capacity(const arcus_advance_params& p, bool fixed, int32_t steps, size_t count, double point_bytes) {
  if (!p.record_path) return 0;
  const double rays = static_cast<double>(std::max<size_t>(count, 1));
  double points = p.path_capacity;
  if (!points && fixed) points = steps + 1.0;
  if (!points) points = std::max(16.0, std::min<double>(kDefaultDpPathCapacity, kMaxDefaultPathBytes / (point_bytes * rays)));
  const double bytes = points * point_bytes * rays;
  if (!p.path_capacity && bytes > kMaxDefaultPathBytes)
    fail(ARCUS_ERROR_OUT_OF_MEMORY, "record_path: " + std::to_string(count) + " paths of " +
                                        std::to_string(static_cast<uint64_t>(points)) + " points need " +
                                        number(bytes / 1073741824.0) +
                                        " GiB; set params.path_capacity or advance fewer rays");
  return static_cast<uint32_t>(points);
}

// Unit end direction from v, scaled first so that |v|² cannot overflow (|v| = n can
// exceed 1e154 in a steep field).
void unit_direction(const double* v, double* out) {
  const double scale = std::max({std::fabs(v[0]), std::fabs(v[1]), std::fabs(v[2])});
  double u[3] = {v[0] / scale, v[1] / scale, v[2] / scale};
  const double len = std::sqrt(u[0] * u[0] + u[1] * u[1] + u[2] * u[2]);
  for (int c = 0; c < 3; ++c) out[c] = u[c] / len;
}

// Rays, state and path on the device for one job.
struct DeviceRays {
  std::unique_ptr<DeviceBuffer> input, wavelengths, state, istate, path;
};

// Runs the job's slices in precision Real and stores the results into job.  Returns
// whether the progress callback cancelled it.
template <class Real, class FieldDesc, class AdvanceDesc>
bool run(arcus_context_t* ctx, arcus_field_t* field, const arcus_advance_params& p, const Plan& plan,
         cl_program program, size_t count, const double* origins, const double* directions, const double* wavelengths,
         const AdvanceExtension* ext, AdvanceJob* job) {
  const uint32_t point_reals = ext ? ext->record_components : 3;
  const bool single = sizeof(Real) == sizeof(float);
  const size_t per_item = plan.layout.per_item();
  const size_t items = std::max<size_t>(1, (count + per_item - 1) / per_item);
  const size_t stride = items * per_item;
  AdvanceDesc desc = make_advance_desc<AdvanceDesc, Real>(p, field->desc, plan, stride);
  const uint32_t capacity = path_capacity(p, !plan.dp45, desc.fixed_steps, count, point_reals * double(sizeof(Real)));
  desc.path_capacity = static_cast<int32_t>(capacity);
  job->path_capacity = capacity;

  // Every size checked before anything is allocated.
  const size_t state_reals = single ? ARCUS_STATE_REALS_FLOAT : ARCUS_STATE_REALS_DOUBLE;
  const bool step_major = point_reals == 7;  // whole states (AdvanceExtension::take_paths)
  const double path_bytes = static_cast<double>(step_major ? stride : count) * capacity * point_reals * sizeof(Real);
  const double ray_bytes = static_cast<double>(stride) *
                           ((ARCUS_IN_COMPONENTS + state_reals + (plan.dispersion ? 1 : 0)) * sizeof(Real) +
                            ARCUS_STATE_INTS * sizeof(int32_t));
  if (p.record_path)
    check_device_allocation(ctx, path_bytes, path_bytes + ray_bytes,
                            "record_path: " + std::to_string(count) + " paths of params.path_capacity = " +
                                std::to_string(capacity) + " points");
  check_device_allocation(ctx, static_cast<double>(stride) * state_reals * sizeof(Real), ray_bytes + path_bytes,
                          std::to_string(count) + " rays");
  // On the host: the staged input and state as on the device, the paths read back, and
  // the job's results (positions, directions, lengths, steps, statuses: 80 bytes a ray).
  limits::require_host_memory(ray_bytes + path_bytes + 80.0 * count, std::to_string(count) + " rays");

  // Structure-of-arrays input; padding rays have a zero direction, so the kernel
  // marks them invalid and they never take a step.
  DeviceRays dev;
  {
    std::vector<Real> in(ARCUS_IN_COMPONENTS * stride, Real(0));
    for (size_t i = 0; i < count; ++i)
      for (int c = 0; c < 3; ++c) {
        in[c * stride + i] = static_cast<Real>(origins[3 * i + c]);
        in[(3 + c) * stride + i] = static_cast<Real>(directions[3 * i + c]);
      }
    dev.input = std::make_unique<DeviceBuffer>(ctx, in.size() * sizeof(Real), "the rays", in.data());
  }
  if (plan.dispersion) {
    std::vector<Real> w(stride, Real(550));
    for (size_t i = 0; i < count; ++i) w[i] = static_cast<Real>(wavelengths[i]);
    dev.wavelengths = std::make_unique<DeviceBuffer>(ctx, w.size() * sizeof(Real), "the wavelengths", w.data());
  }
  dev.state = std::make_unique<DeviceBuffer>(ctx, state_reals * stride * sizeof(Real), "the ray state");
  dev.istate = std::make_unique<DeviceBuffer>(ctx, ARCUS_STATE_INTS * stride * sizeof(int32_t), "the ray state");
  if (p.record_path)
    dev.path = std::make_unique<DeviceBuffer>(ctx, static_cast<size_t>(path_bytes), "record_path");
  DeviceBuffer* data = field_data_on_device(ctx, field, single);

  Launch<AdvanceArg> launch(ctx, program);
  launch.bind(AdvanceArg::rays_in, dev.input.get());
  launch.bind(AdvanceArg::wavelengths, dev.wavelengths.get());
  launch.bind(AdvanceArg::state, dev.state.get());
  launch.bind(AdvanceArg::istate, dev.istate.get());
  launch.bind(AdvanceArg::path, dev.path.get());
  launch.bind_value(AdvanceArg::field, field_desc_as<FieldDesc>(field->desc));
  launch.bind(AdvanceArg::field_data, data);
  if (ext && ext->bind_args) ext->bind_args(launch, stride, single);

  // Slices: up to `units` steps of every ray (fixed) or attempts (DP45) per launch.
  std::vector<int32_t> status(stride);
  std::vector<Real> s(stride);
  int32_t done = 0;  // fixed: steps taken by every ray so far
  SliceJob slices;
  slices.first_units = plan.dp45 ? kFirstSliceAttempts : kFirstSliceRaySteps / static_cast<double>(stride);
  slices.launch = [&](int64_t units, bool first) {
    const int32_t n = static_cast<int32_t>(std::min<int64_t>(units, std::numeric_limits<int32_t>::max()));
    desc.first_slice = first ? 1 : 0;
    desc.slice_begin = done;
    desc.slice_end = plan.dp45 ? n : static_cast<int32_t>(std::min<int64_t>(int64_t(done) + n, desc.fixed_steps));
    launch.bind_value(AdvanceArg::job, desc);
    const double seconds = launch.run(items);
    if (!plan.dp45) done = desc.slice_end;
    return seconds;
  };
  // Fixed steps without a box end together; adaptive or boxed rays each in their time.
  slices.finished = [&] {
    if (!plan.dp45 && !p.use_box) return done >= desc.fixed_steps;
    dev.istate->read(ctx, ARCUS_STATE_STATUS * stride * sizeof(int32_t), stride * sizeof(int32_t), status.data());
    return std::none_of(status.begin(), status.end(),
                        [](int32_t w) { return (w & ((1 << ARCUS_FAILURE_SHIFT) - 1)) == ARCUS_STATUS_ACTIVE; });
  };
  // The share of the path travelled, over all rays.
  slices.fraction = [&] {
    if (!plan.dp45) return static_cast<double>(done) / desc.fixed_steps;
    dev.state->read(ctx, ARCUS_STATE_S * stride * sizeof(Real), stride * sizeof(Real), s.data());
    double sum = 0;
    for (size_t i = 0; i < count; ++i) sum += std::min(1.0, static_cast<double>(s[i]) / p.length);
    return sum / static_cast<double>(std::max<size_t>(count, 1));
  };
  slices.progress = p.progress;
  slices.progress_user = p.progress_user;
  const bool cancelled = run_in_slices(slices, &job->stats);

  if (ext && ext->finished) ext->finished(stride, single);
  // The results are the state.
  std::vector<Real> st(state_reals * stride);
  std::vector<int32_t> ist(ARCUS_STATE_INTS * stride);
  dev.state->read(ctx, 0, st.size() * sizeof(Real), st.data());
  dev.istate->read(ctx, 0, ist.size() * sizeof(int32_t), ist.data());
  job->positions.resize(3 * count);
  job->directions.resize(3 * count);
  job->lengths.resize(count);
  job->steps.resize(count);
  job->status.resize(count);
  job->failures.resize(count);
  for (size_t i = 0; i < count; ++i) {
    const int32_t word = ist[ARCUS_STATE_STATUS * stride + i];
    int32_t ray_status = word & ((1 << ARCUS_FAILURE_SHIFT) - 1);
    if (ray_status == ARCUS_STATUS_ACTIVE) ray_status = ARCUS_STATUS_CANCELLED;
    job->status[i] = ray_status;
    job->failures[i] = word >> ARCUS_FAILURE_SHIFT;
    job->steps[i] = static_cast<uint64_t>(ist[ARCUS_STATE_STEPS * stride + i]);
    job->lengths[i] = static_cast<double>(st[ARCUS_STATE_S * stride + i]);
    if (ray_status == ARCUS_STATUS_INVALID_INPUT) {  // echoes its input
      std::copy(origins + 3 * i, origins + 3 * i + 3, job->positions.begin() + 3 * i);
      std::copy(directions + 3 * i, directions + 3 * i + 3, job->directions.begin() + 3 * i);
      continue;
    }
    double v[3];
    for (int c = 0; c < 3; ++c) {
      job->positions[3 * i + c] = static_cast<double>(st[(ARCUS_STATE_X + c) * stride + i]);
      v[c] = static_cast<double>(st[(ARCUS_STATE_X + 3 + c) * stride + i]);
    }
    unit_direction(v, &job->directions[3 * i]);
  }

  if (p.record_path && ext && ext->take_paths) {
    for (size_t i = 0; i < count; ++i)
      job->path_needed.push_back(static_cast<uint64_t>(static_cast<uint32_t>(ist[ARCUS_STATE_POINTS * stride + i])));
    ext->take_paths(std::move(dev.path), capacity, stride);
  } else if (p.record_path) {
    std::vector<Real> points(count * capacity * 3);
    dev.path->read(ctx, 0, points.size() * sizeof(Real), points.data());
    job->path_offsets.assign(count + 1, 0);
    job->path_needed.resize(count);
    for (size_t i = 0; i < count; ++i) {
      job->path_needed[i] = static_cast<uint64_t>(static_cast<uint32_t>(ist[ARCUS_STATE_POINTS * stride + i]));
      job->path_offsets[i + 1] = job->path_offsets[i] + std::min<uint64_t>(job->path_needed[i], capacity);
    }
    job->path_points.resize(3 * job->path_offsets[count]);
    for (size_t i = 0; i < count; ++i) {
      const Real* src = points.data() + i * capacity * 3;
      std::copy(src, src + 3 * (job->path_offsets[i + 1] - job->path_offsets[i]),
                job->path_points.begin() + static_cast<std::ptrdiff_t>(3 * job->path_offsets[i]));
    }
  }
  return cancelled;
}

}  // namespace

DeviceBuffer* field_data_on_device(arcus_context_t* ctx, arcus_field_t* field, bool single) {
  std::shared_ptr<DeviceBuffer>& data = field->device_data[single ? 1 : 0];
  if (!data && !field->data.empty()) {
    // Doubles go up as they are; only float needs a converted copy on the way.
    const size_t n = field->data.size();
    if (single) {
      const std::vector<float> values(field->data.begin(), field->data.end());
      data = std::make_shared<DeviceBuffer>(ctx, n * sizeof(float), "the field's data", values.data());
    } else {
      data = std::make_shared<DeviceBuffer>(ctx, n * sizeof(double), "the field's data", field->data.data());
    }
  }
  return data.get();
}

void bind_field_and_job(KernelLaunch& launch, unsigned field_arg, unsigned data_arg, unsigned job_arg,
                        arcus_context_t* ctx, arcus_field_t* field, const arcus_advance_params& p, const Plan& plan,
                        size_t stride) {
  auto bind = [&](unsigned arg, const auto& value) { launch.bind_bytes(arg, sizeof value, &value); };
  if (plan.single) {
    bind(field_arg, field_desc_as<arcus_field_desc_f>(field->desc));
    bind(job_arg, make_advance_desc<arcus_advance_desc_f, float>(p, field->desc, plan, stride));
  } else {
    bind(field_arg, field_desc_as<arcus_field_desc_d>(field->desc));
    bind(job_arg, make_advance_desc<arcus_advance_desc_d, double>(p, field->desc, plan, stride));
  }
  launch.bind_buffer(data_arg, field_data_on_device(ctx, field, plan.single));
}

namespace {

arcus_features field_feature(int32_t kind) {
  switch (kind) {
    case ARCUS_KIND_LINEAR: return ARCUS_FEATURE_CURVED_FIELD_LINEAR;
    case ARCUS_KIND_LINEAR_N2: return ARCUS_FEATURE_CURVED_FIELD_LINEAR_N2;
    case ARCUS_KIND_LUNEBURG: return ARCUS_FEATURE_CURVED_FIELD_LUNEBURG;
    case ARCUS_KIND_FISHEYE: return ARCUS_FEATURE_CURVED_FIELD_FISHEYE;
    case ARCUS_KIND_ATMOSPHERE: return ARCUS_FEATURE_CURVED_FIELD_ATMOSPHERE;
    case ARCUS_KIND_GRID: return ARCUS_FEATURE_CURVED_FIELD_GRID;
    default: return 0;  // constant: no field code at all
  }
}

}  // namespace

template <class Real>
FixedSteps fixed_steps(double length, double step, uint64_t max_steps) {
  const uint64_t int_max = static_cast<uint64_t>(std::numeric_limits<int32_t>::max());
  const uint64_t limit = std::min<uint64_t>(max_steps, int_max);
  const Real L = static_cast<Real>(length), h = static_cast<Real>(step);
  FixedSteps fs;
  // When max_steps stops the ray first, that n is never needed (and may not fit an int).
  const double n = std::max(1.0, std::ceil(static_cast<double>(L / h)));
  int64_t steps = n > static_cast<double>(limit) + 1.0 ? static_cast<int64_t>(limit) + 1 : static_cast<int64_t>(n);
  if (steps <= static_cast<int64_t>(limit)) {
    while (steps > 1 && static_cast<Real>(steps - 1) * h >= L) --steps;
    while (static_cast<Real>(steps) * h < L) ++steps;
  }
  if (static_cast<uint64_t>(steps) > limit) {
    fs.steps = static_cast<int32_t>(limit);
    fs.last_step = static_cast<double>(h);
    fs.capped = true;
  } else {
    fs.steps = static_cast<int32_t>(steps);
    fs.last_step = static_cast<double>(L - static_cast<Real>(steps - 1) * h);
  }
  return fs;
}
template FixedSteps fixed_steps<double>(double, double, uint64_t);
template FixedSteps fixed_steps<float>(double, double, uint64_t);

Plan plan_advance(const arcus_advance_params& p, const arcus_field_desc_d& field, const std::vector<double>& data,
                  const arcus_device_info& device, const DeviceEntry& entry, bool with_wavelengths) {
  validate(p, field, data, device);
  Plan plan;
  plan.straight = field.kind == ARCUS_KIND_CONSTANT;
  plan.dp45 = p.method == ARCUS_METHOD_DP45 && !plan.straight;
  plan.single = p.precision == ARCUS_PRECISION_FLOAT;
  plan.dispersion = with_wavelengths && dispersive(field);
  static const arcus_features kMethods[] = {ARCUS_FEATURE_CURVED_EULER, ARCUS_FEATURE_CURVED_RK2, ARCUS_FEATURE_CURVED_RK4,
                                            ARCUS_FEATURE_CURVED_DP45};
  plan.features = plan.straight ? ARCUS_FEATURE_CURVED_STRAIGHT : kMethods[p.method] | field_feature(field.kind);
  if (p.use_box) plan.features |= ARCUS_FEATURE_CURVED_BOX;
  if (p.record_path) plan.features |= ARCUS_FEATURE_CURVED_RECORD_PATH;
  if (plan.single) plan.features |= ARCUS_FEATURE_FLOAT;
  if (plan.dispersion) plan.features |= ARCUS_FEATURE_CURVED_DISPERSION;
  // A straight job is one step: groups would only add padding.
  plan.layout = choose_layout(entry, plan.straight ? 1 : plan.dp45 ? kCpuGroupsDp45 : kCpuGroupsFixed);
  return plan;
}


arcus_status advance(arcus_context_t* ctx, arcus_field_t* field, const arcus_advance_params& p, size_t count,
                     const double* origins, const double* directions, const double* wavelengths, arcus_job_t** job_out,
                     std::string* message, const AdvanceExtension* ext) {
  const auto start = std::chrono::steady_clock::now();
  require(count == 0 || origins, "origins is NULL");
  require(count == 0 || directions, "directions is NULL");
  require(count <= (size_t(1) << 30), "count: more than 2^30 rays in one call");
  Plan plan = plan_advance(p, field->desc, field->data, ctx->info, ctx->runtime->entry(), wavelengths != nullptr);
  if (ext) plan.features |= ext->features;
  const BuiltProgram program =
      ctx->runtime->program(ext && ext->source ? *ext->source : advance_source(), plan.features, plan.layout);

  auto job = std::make_unique<AdvanceJob>(ctx);
  job->count = count;
  job->features = plan.features;
  job->stats.build_seconds = program.seconds;
  job->stats.program_origin = program.origin;
  job->stats.lanes = plan.layout.lanes;
  job->stats.groups = plan.layout.groups;
  const double* ray_wavelengths = plan.dispersion ? wavelengths : nullptr;
  bool cancelled = false;
  if (count > 0) {
    if (plan.single)
      cancelled = run<float, arcus_field_desc_f, arcus_advance_desc_f>(ctx, field, p, plan, program.program, count,
                                                                      origins, directions, ray_wavelengths, ext, job.get());
    else
      cancelled = run<double, arcus_field_desc_d, arcus_advance_desc_d>(ctx, field, p, plan, program.program, count,
                                                                       origins, directions, ray_wavelengths, ext, job.get());
  } else if (p.record_path) {
    job->path_offsets.assign(1, 0);
  }
  job->stats.total_seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();

  // Bad rays are counted as the kernel judged them, explained by the host's same test.
  size_t bad = 0, unfinished = 0;
  std::string first_bad;
  for (size_t i = 0; i < count; ++i) {
    unfinished += job->status[i] == ARCUS_RAY_CANCELLED;
    if (job->status[i] == ARCUS_RAY_INVALID_INPUT && bad++ < 3) {
      const std::string why = ray_problem(origins + 3 * i, directions + 3 * i,
                                          ray_wavelengths ? ray_wavelengths + i : nullptr, plan.single);
      first_bad += (first_bad.empty() ? "" : "; ") + ("ray " + std::to_string(i) + ": " +
                                                      (why.empty() ? "invalid input" : why));
    }
  }
  size_t overflowed = 0;
  uint64_t longest = 0;
  for (uint64_t needed : job->path_needed)
    if (needed > job->path_capacity) {
      ++overflowed;
      longest = std::max(longest, needed);
    }

  arcus_status status = ARCUS_SUCCESS;
  message->clear();
  auto add = [&](arcus_status s, const std::string& text) {
    if (status == ARCUS_SUCCESS) status = s;
    *message += (message->empty() ? "" : "; ") + text;
  };
  if (cancelled)
    add(ARCUS_ERROR_CANCELLED, "the progress callback cancelled the job; " + std::to_string(unfinished) + " of " +
                                   std::to_string(count) + " rays are unfinished (ARCUS_RAY_CANCELLED)");
  if (bad)
    add(ARCUS_ERROR_INVALID_RAYS, std::to_string(bad) + " of " + std::to_string(count) + " rays have invalid input (" +
                                      first_bad + (bad > 3 ? "; ..." : "") +
                                      "); they are marked ARCUS_RAY_INVALID_INPUT, the others were advanced");
  if (overflowed)
    add(ARCUS_ERROR_PATH_OVERFLOW, "record_path: " + std::to_string(overflowed) +
                                       " rays needed more than path_capacity = " + std::to_string(job->path_capacity) +
                                       " points (the longest needs " + std::to_string(longest) +
                                       "); their paths hold the first points only; set params.path_capacity");
  retain_context(ctx);  // the job's reference to its context, dropped with the job
  *job_out = job.release();
  return status;
}

}  // namespace arcus::curved
