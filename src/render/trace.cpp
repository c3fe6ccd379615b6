#include "render/trace.h"

#include <memory>
#include <string>

#include "core/error.h"
#include "curved/advance.h"

namespace arcus::render {

TraceOutput trace(arcus_context_t* ctx, RenderScene* scene, arcus_advance_params p, const TraceInput& in) {
  const bool single = p.precision == ARCUS_PRECISION_FLOAT;
  scene->upload(ctx, single);
  const auto& bvh = scene->device_bvh[single ? 1 : 0];
  const auto& shapes = scene->device_shapes[single ? 1 : 0];
  p.use_box = 1;
  for (int a = 0; a < 3; ++a) {
    p.box_min[a] = scene->lo[a];
    p.box_max[a] = scene->hi[a];
  }
  p.record_path = 0;

  TraceOutput out;
  std::vector<int32_t> hit_ints;
  std::unique_ptr<DeviceBuffer> hits, hit_reals, predictions;
  curved::AdvanceExtension ext;
  ext.features = ARCUS_FEATURE_GEOMETRY;
  ext.source = &trace_source();
  ext.set_args = [&](KernelCall& kernel, unsigned arg, size_t stride, bool is_single) {
    const size_t real = is_single ? sizeof(float) : sizeof(double);
    hits = std::make_unique<DeviceBuffer>(ctx, ARCUS_HIT_INTS * stride * sizeof(int32_t), "the hit records");
    hit_reals = std::make_unique<DeviceBuffer>(ctx, ARCUS_HIT_REALS * stride * real, "the hit records");
    if (in.predictions) {
      std::vector<int32_t> pred(stride, -1);
      std::copy(in.predictions, in.predictions + in.count, pred.begin());
      predictions = std::make_unique<DeviceBuffer>(ctx, stride * sizeof(int32_t), "the predicted steps", pred.data());
    }
    arcus_geometry_desc geo{};
    geo.shape_count = static_cast<int32_t>(scene->shapes.size());
    geo.triangle_count = static_cast<int32_t>(scene->triangles.triangle_count());
    kernel.set(arg++, bvh ? bvh->nodes().get() : nullptr);
    kernel.set(arg++, bvh ? bvh->triangles().get() : nullptr);
    kernel.set(arg++, shapes.get());
    kernel.set_value(arg++, geo);
    kernel.set(arg++, hits.get());
    kernel.set(arg++, hit_reals.get());
    kernel.set(arg++, predictions.get());
  };
  size_t stride_seen = 0;
  ext.finished = [&](size_t stride, bool) {
    stride_seen = stride;
    hit_ints.resize(ARCUS_HIT_INTS * stride);
    hits->read(ctx, 0, hit_ints.size() * sizeof(int32_t), hit_ints.data());
  };

  arcus_job_t* raw = nullptr;
  std::string message;
  const arcus_status status = curved::advance(ctx, scene->field, p, in.count, in.origins, in.directions,
                                              in.wavelengths, &raw, &message, &ext);
  std::unique_ptr<curved::AdvanceJob> job(static_cast<curved::AdvanceJob*>(raw));
  if (job) job->owner()->drop();  // the job's reference to its context: the caller holds others
  if (status != ARCUS_SUCCESS) fail(status, message);

  out.positions = std::move(job->positions);
  out.directions = std::move(job->directions);
  out.lengths = std::move(job->lengths);
  out.steps = std::move(job->steps);
  out.status = std::move(job->status);
  out.stats = job->stats;
  out.object.assign(in.count, -1);
  out.primitive.assign(in.count, -1);
  out.hit_step.assign(in.count, -1);
  out.hit_kind.assign(in.count, ARCUS_HIT_NONE);
  out.hit_index.assign(in.count, -1);
  out.tests.assign(in.count, 0);
  const auto& order = bvh ? bvh->order() : std::vector<uint32_t>();
  for (size_t i = 0; i < in.count && stride_seen; ++i) {
    const int32_t kind = hit_ints[ARCUS_HIT_KIND * stride_seen + i];
    const int32_t index = hit_ints[ARCUS_HIT_INDEX * stride_seen + i];
    out.tests[i] = hit_ints[ARCUS_HIT_TESTS * stride_seen + i];
    if (out.status[i] != ARCUS_STATUS_HIT) continue;
    out.hit_step[i] = hit_ints[ARCUS_HIT_STEP * stride_seen + i];
    out.hit_kind[i] = kind;
    if (kind == ARCUS_HIT_TRIANGLE) {
      const uint32_t tri = order[static_cast<size_t>(index)];
      out.hit_index[i] = static_cast<int32_t>(tri);
      const uint32_t mesh = scene->triangles.geometry[tri];
      out.object[i] = scene->mesh_object[mesh];
      out.primitive[i] = static_cast<int32_t>(tri - scene->triangles.mesh_first[mesh]);
    } else if (kind == ARCUS_HIT_SHAPE) {
      out.hit_index[i] = index;
      out.object[i] = scene->shape_object[static_cast<size_t>(index)];
      out.primitive[i] = 0;
    }
  }
  return out;
}

}  // namespace arcus::render
