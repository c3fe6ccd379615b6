// A TriangleBvh on an OpenCL device, in the kernels' precision, and the batch queries
// of kernels/bvh/bvh_kernels.cl.  The buffers are shared: a scene keeps them on the
// device and every later job (render passes, rainbow patches) reuses them.
#pragma once

#include <cstdint>
#include <memory>
#include <utility>
#include <vector>

#include "bvh/bvh.h"
#include "core/buffer.h"
#include "core/kernel_source.h"

namespace arcus::bvh {

class DeviceBvh {
 public:
  // Uploads nodes (float: boxes rounded outwards), triangles (float: rounded to
  // nearest, which the outward boxes still contain) and the slot -> triangle order.
  DeviceBvh(arcus_context_t* ctx, const TriangleBvh& bvh, bool single);

  bool single() const { return single_; }
  size_t triangle_count() const { return order_.size(); }
  int depth() const { return depth_; }
  const std::vector<uint32_t>& order() const { return order_; }  // slot -> triangle index
  // Kernel arguments: bvh_node[], REAL[9 per slot], int order[].
  const std::shared_ptr<DeviceBuffer>& nodes() const { return nodes_; }
  const std::shared_ptr<DeviceBuffer>& triangles() const { return triangles_; }
  const std::shared_ptr<DeviceBuffer>& order_buffer() const { return order_buffer_; }

 private:
  bool single_;
  int depth_;
  std::vector<uint32_t> order_;
  std::shared_ptr<DeviceBuffer> nodes_, triangles_, order_buffer_;
};

// The kernel source "bvh/kernels" (common/real.h, bvh/bvh_desc.h, bvh/traverse.h,
// bvh/bvh_kernels.cl) and the features its programs are built with (0, or
// ARCUS_FEATURE_FLOAT).  Kernels that traverse from their own source list
// common/real.h, bvh/bvh_desc.h and bvh/traverse.h before their own files.
const KernelSource& kernel_source();
arcus_features kernel_features(bool single);

// The closest hit of each segment (Hit.slot, .primitive, .t, .u, .v, .tests).
std::vector<Hit> closest_hits(arcus_context_t* ctx, const DeviceBvh& bvh, const std::vector<Segment>& segments,
                              double* kernel_seconds = nullptr);

// (query index, triangle index) pairs, in no particular order.  When more than
// `capacity` were found, `overflow` is set, `pairs` is empty and `needed` says how many
// there are (call again with that capacity).
struct AllHits {
  std::vector<std::pair<uint32_t, uint32_t>> pairs;
  uint64_t needed = 0;
  bool overflow = false;
};

// Every triangle each segment hits (t in [0, t_max]).
AllHits all_hits(arcus_context_t* ctx, const DeviceBvh& bvh, const std::vector<Segment>& segments, size_t capacity);
// Every triangle whose bounding box contains each point (3 doubles per point).
AllHits all_hits(arcus_context_t* ctx, const DeviceBvh& bvh, const std::vector<double>& points, size_t capacity);

}  // namespace arcus::bvh
