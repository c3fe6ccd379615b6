#include "bvh/device_bvh.h"

#include <algorithm>
#include <limits>

#include "core/error.h"
#include "core/layout.h"
#include "core/runtime.h"

namespace arcus::bvh {
namespace {

// Reals on the device in the kernel's precision (float: rounded to nearest).
std::shared_ptr<DeviceBuffer> upload(arcus_context_t* ctx, bool single, const std::vector<double>& values,
                                     const char* what) {
  if (single) {
    const std::vector<float> f(values.begin(), values.end());
    return std::make_shared<DeviceBuffer>(ctx, f.size() * sizeof(float), what, f.data());
  }
  return std::make_shared<DeviceBuffer>(ctx, values.size() * sizeof(double), what, values.data());
}

// 7 per segment, as the kernels read them.
std::vector<double> segment_values(const std::vector<Segment>& segments) {
  std::vector<double> out;
  out.reserve(7 * segments.size());
  for (const Segment& s : segments)
    out.insert(out.end(), {s.origin[0], s.origin[1], s.origin[2], s.direction[0], s.direction[1], s.direction[2], s.t_max});
  return out;
}

BuiltProgram program_for(arcus_context_t* ctx, bool single) {
  if (!single && !ctx->info.fp64)
    fail(ARCUS_ERROR_UNSUPPORTED, std::string("the device '") + ctx->info.name +
                                      "' has no double precision (cl_khr_fp64); use a float BVH");
  return ctx->runtime->program(kernel_source(), kernel_features(single), choose_layout(ctx->runtime->entry(), 1));
}

cl_uint checked_count(size_t n, const char* what) {
  require(n <= std::numeric_limits<cl_uint>::max(), std::string(what) + ": more than 2^32 - 1");
  return static_cast<cl_uint>(n);
}

AllHits run_all_hits(arcus_context_t* ctx, const DeviceBvh& bvh, const std::vector<double>& queries, size_t count,
                     bool points, size_t capacity) {
  const cl_uint n = checked_count(count, "all_hits: queries");
  const cl_uint cap = checked_count(capacity, "all_hits: capacity");
  AllHits result;
  if (n == 0) return result;
  const BuiltProgram program = program_for(ctx, bvh.single());
  const std::shared_ptr<DeviceBuffer> input = upload(ctx, bvh.single(), queries, "the BVH queries");
  DeviceBuffer pairs(ctx, 2 * static_cast<size_t>(cap) * sizeof(cl_int), "the BVH hit pairs");
  const cl_uint zero = 0;
  DeviceBuffer counter(ctx, sizeof zero, "the BVH hit counter", &zero);
  KernelCall kernel(program.program, "arcus_bvh_all_hits");
  kernel.set(0, bvh.nodes().get());
  kernel.set(1, bvh.triangles().get());
  kernel.set(2, bvh.order_buffer().get());
  kernel.set(3, input.get());
  kernel.set_value(4, n);
  kernel.set_value(5, static_cast<cl_int>(points));
  kernel.set(6, &pairs);
  kernel.set_value(7, cap);
  kernel.set(8, &counter);
  kernel.run(ctx, n);
  cl_uint found = 0;
  counter.read(ctx, 0, sizeof found, &found);
  result.needed = found;
  if (found > cap) {
    result.overflow = true;
    return result;
  }
  std::vector<cl_int> raw(2 * static_cast<size_t>(found));
  pairs.read(ctx, 0, raw.size() * sizeof(cl_int), raw.data());
  result.pairs.resize(found);
  for (size_t k = 0; k < found; ++k)
    result.pairs[k] = {static_cast<uint32_t>(raw[2 * k]), static_cast<uint32_t>(raw[2 * k + 1])};
  return result;
}

}  // namespace

DeviceBvh::DeviceBvh(arcus_context_t* ctx, const TriangleBvh& bvh, bool single)
    : single_(single), depth_(bvh.tree.depth), order_(bvh.tree.order) {
  require(!bvh.tree.nodes.empty() && bvh.triangles.size() == 9 * bvh.tree.order.size(),
          "DeviceBvh: the BVH's nodes and triangles do not match");
  if (single) {
    const std::vector<arcus_bvh_node_f> nodes = to_float(bvh.tree.nodes);
    nodes_ = std::make_shared<DeviceBuffer>(ctx, nodes.size() * sizeof nodes[0], "the BVH nodes", nodes.data());
  } else {
    nodes_ = std::make_shared<DeviceBuffer>(ctx, bvh.tree.nodes.size() * sizeof(arcus_bvh_node_d), "the BVH nodes",
                                            bvh.tree.nodes.data());
  }
  triangles_ = upload(ctx, single, bvh.triangles, "the BVH triangles");
  const std::vector<cl_int> order(order_.begin(), order_.end());
  order_buffer_ = std::make_shared<DeviceBuffer>(ctx, order.size() * sizeof(cl_int), "the BVH order", order.data());
}

const KernelSource& kernel_source() {
  static const KernelSource source{
      "bvh/kernels", {"common/real.h", "bvh/bvh_desc.h", "bvh/traverse.h", "bvh/bvh_kernels.cl"}, ""};
  return source;
}

arcus_features kernel_features(bool single) { return single ? ARCUS_FEATURE_FLOAT : 0; }

std::vector<Hit> closest_hits(arcus_context_t* ctx, const DeviceBvh& bvh, const std::vector<Segment>& segments,
                              double* kernel_seconds) {
  const cl_uint n = checked_count(segments.size(), "closest_hits: segments");
  std::vector<Hit> hits(n);
  if (kernel_seconds) *kernel_seconds = 0;
  if (n == 0) return hits;
  const BuiltProgram program = program_for(ctx, bvh.single());
  const size_t real = bvh.single() ? sizeof(float) : sizeof(double);
  const std::shared_ptr<DeviceBuffer> input = upload(ctx, bvh.single(), segment_values(segments), "the BVH segments");
  DeviceBuffer slot(ctx, n * sizeof(cl_int), "the BVH hit slots");
  DeviceBuffer tuv(ctx, 3 * n * real, "the BVH hit distances");
  DeviceBuffer tests(ctx, n * sizeof(cl_int), "the BVH test counts");
  KernelCall kernel(program.program, "arcus_bvh_closest");
  kernel.set(0, bvh.nodes().get());
  kernel.set(1, bvh.triangles().get());
  kernel.set(2, input.get());
  kernel.set_value(3, n);
  kernel.set(4, &slot);
  kernel.set(5, &tuv);
  kernel.set(6, &tests);
  const double seconds = kernel.run(ctx, n);
  if (kernel_seconds) *kernel_seconds = seconds;
  std::vector<cl_int> s(n), c(n);
  std::vector<double> t(3 * static_cast<size_t>(n));
  slot.read(ctx, 0, n * sizeof(cl_int), s.data());
  tests.read(ctx, 0, n * sizeof(cl_int), c.data());
  if (bvh.single()) {
    std::vector<float> f(t.size());
    tuv.read(ctx, 0, f.size() * sizeof(float), f.data());
    std::copy(f.begin(), f.end(), t.begin());
  } else {
    tuv.read(ctx, 0, t.size() * sizeof(double), t.data());
  }
  for (size_t i = 0; i < n; ++i) {
    hits[i].tests = c[i];
    if (s[i] < 0) continue;
    hits[i].slot = s[i];
    hits[i].primitive = static_cast<int32_t>(bvh.order()[s[i]]);
    hits[i].t = t[3 * i];
    hits[i].u = t[3 * i + 1];
    hits[i].v = t[3 * i + 2];
  }
  return hits;
}

AllHits all_hits(arcus_context_t* ctx, const DeviceBvh& bvh, const std::vector<Segment>& segments, size_t capacity) {
  return run_all_hits(ctx, bvh, segment_values(segments), segments.size(), false, capacity);
}

AllHits all_hits(arcus_context_t* ctx, const DeviceBvh& bvh, const std::vector<double>& points, size_t capacity) {
  require(points.size() % 3 == 0, "all_hits: points must hold 3 numbers per point");
  return run_all_hits(ctx, bvh, points, points.size() / 3, true, capacity);
}

}  // namespace arcus::bvh
