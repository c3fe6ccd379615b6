#include "render/trace.h"

#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <memory>
#include <string>

#include "core/error.h"
#include "curved/advance.h"

namespace arcus::render {
namespace {

using curved::AdvanceArg;
ARCUS_KERNEL_ARGS(WalkArg, "arcus_walk", ARCUS_WALK_ARGS);
ARCUS_KERNEL_ARGS(CapsulesArg, "arcus_path_capsules", ARCUS_PATH_CAPSULES_ARGS);

// The hit records the kernels left (render_desc.h layout, `stride` entries per
// component) as objects and primitives of the scene.
void fill_hits(const RenderScene* scene, const bvh::DeviceBvh* bvh, const std::vector<int32_t>& hit_ints, size_t stride,
               size_t count, TraceOutput* out) {
  out->object.assign(count, -1);
  out->primitive.assign(count, -1);
  out->hit_step.assign(count, -1);
  out->hit_kind.assign(count, ARCUS_HIT_NONE);
  out->hit_index.assign(count, -1);
  out->tests.assign(count, 0);
  for (size_t i = 0; i < count && stride; ++i) {
    const int32_t kind = hit_ints[ARCUS_HIT_KIND * stride + i];
    const int32_t index = hit_ints[ARCUS_HIT_INDEX * stride + i];
    out->tests[i] = hit_ints[ARCUS_HIT_TESTS * stride + i];
    if (out->status[i] != ARCUS_STATUS_HIT) continue;
    out->hit_step[i] = hit_ints[ARCUS_HIT_STEP * stride + i];
    out->hit_kind[i] = kind;
    if (kind == ARCUS_HIT_TRIANGLE) {
      const uint32_t tri = bvh->order()[static_cast<size_t>(index)];
      const uint32_t mesh = scene->triangles.geometry[tri];
      out->hit_index[i] = static_cast<int32_t>(tri);
      out->object[i] = scene->mesh_object[mesh];
      out->primitive[i] = static_cast<int32_t>(tri - scene->triangles.mesh_first[mesh]);
    } else if (kind == ARCUS_HIT_SHAPE) {
      out->hit_index[i] = index;
      out->object[i] = scene->shape_object[static_cast<size_t>(index)];
      out->primitive[i] = 0;
    }
  }
}

// The scene's bounds as the job's box.
void use_bounds(const RenderScene* scene, arcus_advance_params* p) {
  p->use_box = 1;
  for (int a = 0; a < 3; ++a) {
    p->box_min[a] = scene->lo[a];
    p->box_max[a] = scene->hi[a];
  }
}

// The geometry arguments of the trace and walk kernels (ARCUS_GEOMETRY_ARGS,
// curved/advance_desc.h), with the hit records and predictions they fill or read.
struct GeometryArgs {
  std::unique_ptr<DeviceBuffer> hits, predictions;
  template <class Args>
  void bind(arcus_context_t* ctx, RenderScene* scene, bool single, Launch<Args>& launch, size_t stride, size_t count,
            const int32_t* predicted, bool occlusion, bool from_surface) {
    const auto& bvh = scene->device_bvh[single ? 1 : 0];
    hits = std::make_unique<DeviceBuffer>(ctx, ARCUS_HIT_INTS * stride * sizeof(int32_t), "the hit records");
    if (predicted) {
      std::vector<int32_t> pred(stride, -1);
      std::copy(predicted, predicted + count, pred.begin());
      predictions = std::make_unique<DeviceBuffer>(ctx, stride * sizeof(int32_t), "the predicted steps", pred.data());
    }
    arcus_geometry_desc geo{};
    geo.shape_count = static_cast<int32_t>(scene->shapes.size());
    geo.triangle_count = static_cast<int32_t>(scene->triangles.triangle_count());
    geo.occlusion = occlusion ? 1 : 0;
    geo.from_surface = from_surface ? 1 : 0;
    launch.bind(Args::nodes, bvh ? bvh->nodes().get() : nullptr);
    launch.bind(Args::tris, bvh ? bvh->triangles().get() : nullptr);
    launch.bind(Args::shapes, scene->device_shapes[single ? 1 : 0].get());
    launch.bind_value(Args::geo, geo);
    launch.bind(Args::hit_ints, hits.get());
    launch.bind(Args::predictions, predictions.get());
  }
  std::vector<int32_t> read(arcus_context_t* ctx, size_t stride) const {
    std::vector<int32_t> v(ARCUS_HIT_INTS * stride);
    hits->read(ctx, 0, v.size() * sizeof(int32_t), v.data());
    return v;
  }
};

}  // namespace

namespace {

// trace() and record_paths(): the advance with the per-step hook; with `paths`, every
// net point of every ray is recorded too (up to its hit), at most `capacity` a ray.  A
// longer path keeps its first points and is marked as ending on a hit (which it did
// not reach): a walk along it that finds nothing is then traced instead.
TraceOutput run_trace(arcus_context_t* ctx, RenderScene* scene, arcus_advance_params p, const TraceInput& in,
                      DevicePaths* paths, uint32_t capacity_hint) {
  const bool single = p.precision == ARCUS_PRECISION_FLOAT;
  scene->upload(ctx, single);
  use_bounds(scene, &p);
  p.record_path = paths ? 1 : 0;
  p.path_capacity = paths ? std::max<uint32_t>(capacity_hint, 2) : 0;
  GeometryArgs geometry;
  std::vector<int32_t> hit_ints;
  size_t stride_seen = 0;
  curved::AdvanceExtension ext;
  ext.features = ARCUS_FEATURE_RENDER_GEOMETRY | (paths ? ARCUS_FEATURE_RENDER_RECORD_STATE : 0);
  ext.source = &trace_source();
  ext.record_components = DevicePaths::kReals;
  ext.bind_args = [&](Launch<AdvanceArg>& launch, size_t stride, bool is_single) {
    geometry.bind(ctx, scene, is_single, launch, stride, in.count, in.predictions, in.occlusion, in.from_surface);
  };
  ext.finished = [&](size_t stride, bool) {
    stride_seen = stride;
    hit_ints = geometry.read(ctx, stride);
  };
  if (paths)
    ext.take_paths = [&](std::unique_ptr<DeviceBuffer> b, uint32_t capacity, size_t stride) {
      paths->points = std::move(b);
      paths->capacity = capacity;
      paths->stride = stride;
    };
  TraceOutput out;
  {
    arcus_job_t* raw = nullptr;
    std::string message;
    const arcus_status status = curved::advance(ctx, scene->field, p, in.count, in.origins, in.directions,
                                                in.wavelengths, &raw, &message, &ext);
    std::unique_ptr<curved::AdvanceJob> job(static_cast<curved::AdvanceJob*>(raw));
    if (job) job->owner()->drop();  // the job's reference to its context: the caller holds others
    if (job) {
      out.stats.total_seconds += job->stats.total_seconds;
      out.stats.kernel_seconds += job->stats.kernel_seconds;
      out.stats.build_seconds += job->stats.build_seconds;
      out.stats.launches += job->stats.launches;
      out.features |= job->features;
    }
    if (status != ARCUS_SUCCESS && !(paths && status == ARCUS_ERROR_PATH_OVERFLOW)) fail(status, message);
    out.positions = std::move(job->positions);
    out.directions = std::move(job->directions);
    out.lengths = std::move(job->lengths);
    out.steps = std::move(job->steps);
    out.status = std::move(job->status);
    const auto& bvh = scene->device_bvh[single ? 1 : 0];
    fill_hits(scene, bvh.get(), hit_ints, stride_seen, in.count, &out);
    if (paths) {
      paths->from_surface = in.from_surface;
      paths->counts.resize(in.count);
      paths->end_status = out.status;
      for (size_t r = 0; r < in.count; ++r) {
        paths->counts[r] = static_cast<int32_t>(std::min<uint64_t>(job->path_needed[r], paths->capacity));
        if (job->path_needed[r] > paths->capacity) paths->end_status[r] = ARCUS_STATUS_HIT;  // cut short
      }
    }
    return out;
  }
}

}  // namespace

void TraceOutput::copy_ray(size_t to, const TraceOutput& from, size_t k) {
  for (int a = 0; a < 3; ++a) {
    positions[3 * to + a] = from.positions[3 * k + a];
    directions[3 * to + a] = from.directions[3 * k + a];
  }
  lengths[to] = from.lengths[k];
  steps[to] = from.steps[k];
  status[to] = from.status[k];
  object[to] = from.object[k];
  primitive[to] = from.primitive[k];
  hit_kind[to] = from.hit_kind[k];
  hit_index[to] = from.hit_index[k];
  hit_step[to] = from.hit_step[k];
  tests[to] = from.tests[k];
}

TraceOutput trace(arcus_context_t* ctx, RenderScene* scene, arcus_advance_params p, const TraceInput& in) {
  return run_trace(ctx, scene, p, in, nullptr, 0);
}

TraceOutput record_paths(arcus_context_t* ctx, RenderScene* scene, arcus_advance_params p, const TraceInput& in,
                         uint32_t capacity_hint, DevicePaths* paths) {
  return run_trace(ctx, scene, p, in, paths, capacity_hint);
}

namespace {

// The walk kernels' plan and program for `p` (its box already the scene's bounds).
struct WalkProgram {
  curved::Plan plan;
  BuiltProgram program;
};
WalkProgram walk_program(arcus_context_t* ctx, RenderScene* scene, const arcus_advance_params& p) {
  WalkProgram w{curved::plan_advance(p, scene->field->desc, scene->field->data, ctx->info, ctx->runtime->entry(), false),
                {}};
  w.program = ctx->runtime->program(trace_source(), w.plan.features | ARCUS_FEATURE_RENDER_GEOMETRY, w.plan.layout);
  return w;
}

template <class Real>
void prove_chunks_in(arcus_context_t* ctx, RenderScene* scene, const arcus_advance_params& p, DevicePaths* paths) {
  constexpr int kChunk = 16;     // ARCUS_SMART_CHUNK (kernels/render/hits.h)
  constexpr int kPerItem = 64;   // paths a work-item
  const int32_t longest = paths->counts.empty() ? 0 : *std::max_element(paths->counts.begin(), paths->counts.end());
  const uint32_t chunks = static_cast<uint32_t>((std::max(0, longest - 1) + kChunk - 1) / kChunk);
  paths->capsules.reset();
  paths->chunks = 0;
  // Paths leaving a surface are not proved this way: a capsule around their first chunk
  // meets the surface they leave (the walk's own proof, seeing the points, rules it out).
  if (chunks == 0 || !paths->points || paths->from_surface) return;
  const WalkProgram w = walk_program(ctx, scene, p);
  DeviceBuffer d_counts(ctx, paths->counts.size() * sizeof(int32_t), "the path lengths", paths->counts.data());
  auto radii = std::make_shared<DeviceBuffer>(ctx, paths->count() * chunks * sizeof(Real), "the chunks' proofs");
  Launch<CapsulesArg> launch(ctx, w.program.program);
  launch.bind(CapsulesArg::paths, paths->points.get());
  launch.bind_value(CapsulesArg::slots, static_cast<int32_t>(paths->stride));
  launch.bind(CapsulesArg::counts, &d_counts);
  launch.bind_value(CapsulesArg::count, static_cast<int32_t>(paths->count()));
  launch.bind_value(CapsulesArg::chunks, static_cast<int32_t>(chunks));
  launch.bind_value(CapsulesArg::per_item, static_cast<int32_t>(kPerItem));
  launch.bind(CapsulesArg::radii, radii.get());
  launch.run((paths->count() + kPerItem - 1) / kPerItem);
  paths->capsules = std::move(radii);
  paths->chunks = chunks;
}

template <class Real>
TraceOutput walk_in(arcus_context_t* ctx, RenderScene* scene, const arcus_advance_params& p, const DevicePaths& paths,
                    const std::vector<WalkRay>& rays, const MirrorPlane& plane, const int32_t* predictions,
                    bool occlusion) {
  const bool single = sizeof(Real) == sizeof(float);
  const size_t count = rays.size();
  const WalkProgram w = walk_program(ctx, scene, p);
  const curved::Plan& plan = w.plan;
  const size_t per_item = plan.layout.per_item();
  const size_t items = std::max<size_t>(1, (count + per_item - 1) / per_item);
  const size_t stride = items * per_item;

  std::vector<int32_t> table(3 * stride, 0);
  for (size_t r = 0; r < count; ++r) {
    table[r] = rays[r].a;
    table[r + stride] = rays[r].b;
    table[r + 2 * stride] = rays[r].mirror;
  }
  std::vector<int32_t> counts = paths.counts, ends = paths.end_status;
  if (counts.empty()) counts.push_back(0), ends.push_back(ARCUS_STATUS_INVALID_INPUT);  // no NULL buffers
  DeviceBuffer d_counts(ctx, counts.size() * sizeof(int32_t), "the path lengths", counts.data());
  DeviceBuffer d_end(ctx, ends.size() * sizeof(int32_t), "the path endings", ends.data());
  DeviceBuffer d_rays(ctx, table.size() * sizeof(int32_t), "the walked rays", table.data());
  DeviceBuffer d_out(ctx, DevicePaths::kReals * stride * sizeof(Real), "the walked rays");
  DeviceBuffer d_status(ctx, stride * sizeof(int32_t), "the walked rays");
  const std::array<Real, 4> mirror{static_cast<Real>(plane.normal[0]), static_cast<Real>(plane.normal[1]),
                                   static_cast<Real>(plane.normal[2]), static_cast<Real>(plane.offset)};
  Launch<WalkArg> launch(ctx, w.program.program);
  launch.bind(WalkArg::paths, paths.points.get());
  launch.bind_value(WalkArg::slots, static_cast<int32_t>(paths.stride));
  launch.bind(WalkArg::counts, &d_counts);
  launch.bind(WalkArg::end_status, &d_end);
  launch.bind(WalkArg::rays, &d_rays);
  launch.bind_value(WalkArg::ray_count, static_cast<int32_t>(count));
  launch.bind_value(WalkArg::plane4, mirror);
  launch.bind(WalkArg::wavelengths, nullptr);  // walks are not dispersive (see plan_advance above)
  launch.bind(WalkArg::out, &d_out);
  launch.bind(WalkArg::out_status, &d_status);
  launch.bind(WalkArg::radii, paths.capsules.get());
  launch.bind_value(WalkArg::chunks, static_cast<int32_t>(paths.capsules ? paths.chunks : 0));
  curved::bind_field_and_job(launch, WalkArg::field, WalkArg::field_data, WalkArg::job, ctx, scene->field, p, plan,
                             stride);
  GeometryArgs geometry;
  geometry.bind(ctx, scene, single, launch, stride, count, predictions, occlusion, paths.from_surface);
  TraceOutput out;
  out.features = plan.features | ARCUS_FEATURE_RENDER_GEOMETRY;
  out.stats.kernel_seconds = launch.run(items);
  out.stats.launches = 1;

  std::vector<Real> state(DevicePaths::kReals * stride);
  d_out.read(ctx, 0, state.size() * sizeof(Real), state.data());
  out.status.resize(count);
  d_status.read(ctx, 0, count * sizeof(int32_t), out.status.data());
  out.positions.resize(3 * count);
  out.directions.resize(3 * count);
  out.lengths.resize(count);
  out.steps.resize(count);
  for (size_t r = 0; r < count; ++r) {
    double v[3];
    for (int c = 0; c < 3; ++c) {
      out.positions[3 * r + c] = static_cast<double>(state[c * stride + r]);
      v[c] = static_cast<double>(state[(3 + c) * stride + r]);
    }
    const double len = std::sqrt(v[0] * v[0] + v[1] * v[1] + v[2] * v[2]);
    for (int c = 0; c < 3; ++c) out.directions[3 * r + c] = len > 0 ? v[c] / len : 0;
    out.lengths[r] = static_cast<double>(state[6 * stride + r]);
  }
  fill_hits(scene, scene->device_bvh[single ? 1 : 0].get(), geometry.read(ctx, stride), stride, count, &out);
  // The steps a walked ray stands for: the chords up to its hit, or all of its path's.
  for (size_t r = 0; r < count; ++r)
    out.steps[r] = out.status[r] == ARCUS_STATUS_HIT
                       ? static_cast<uint64_t>(out.hit_step[r] + 1)
                       : static_cast<uint64_t>(std::max(paths.counts[static_cast<size_t>(rays[r].a)], 1) - 1);
  return out;
}

}  // namespace

void prove_chunks(arcus_context_t* ctx, RenderScene* scene, const arcus_advance_params& params, DevicePaths* paths) {
  arcus_advance_params p = params;
  use_bounds(scene, &p);
  p.record_path = 0;
  if (p.precision == ARCUS_PRECISION_FLOAT)
    prove_chunks_in<float>(ctx, scene, p, paths);
  else
    prove_chunks_in<double>(ctx, scene, p, paths);
}

TraceOutput walk(arcus_context_t* ctx, RenderScene* scene, arcus_advance_params p, const DevicePaths& paths,
                 const std::vector<WalkRay>& rays, const MirrorPlane& plane, const int32_t* predictions,
                 bool occlusion) {
  const auto start = std::chrono::steady_clock::now();
  const bool single = p.precision == ARCUS_PRECISION_FLOAT;
  scene->upload(ctx, single);
  use_bounds(scene, &p);
  p.record_path = 0;
  TraceOutput out = single ? walk_in<float>(ctx, scene, p, paths, rays, plane, predictions, occlusion)
                           : walk_in<double>(ctx, scene, p, paths, rays, plane, predictions, occlusion);
  out.stats.total_seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return out;
}

}  // namespace arcus::render
