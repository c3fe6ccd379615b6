#include "photon/photon_map.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <string>

#include "bvh/bvh.h"
#include "core/context.h"
#include "core/error.h"
#include "core/format.h"

namespace arcus::photon {
namespace {

const std::vector<const char*> kHeaders{"common/real.h", "bvh/bvh_desc.h", "photon/photon_desc.h",
                                        "photon/photon_map.h", "photon/photon_line.h"};

const KernelSource& source() {
  static const KernelSource s{"photon/photon_kernels",
                              [] {
                                std::vector<const char*> files = kHeaders;
                                files.push_back("photon/photon_kernels.cl");
                                return files;
                              }(),
                              ""};
  return s;
}

constexpr size_t kMaxItems = static_cast<size_t>(std::numeric_limits<int32_t>::max());

std::string triple(const double* v) {
  return "(" + number(v[0]) + ", " + number(v[1]) + ", " + number(v[2]) + ")";
}

bool finite3(const double* v) { return std::isfinite(v[0]) && std::isfinite(v[1]) && std::isfinite(v[2]); }

// v / |v|, scaled by its largest component first so that no finite non-zero vector
// under- or overflows when squared; false for a zero or non-finite one.
bool normalise(const double* v, double* out) {
  if (!finite3(v)) return false;
  const double scale = std::max({std::fabs(v[0]), std::fabs(v[1]), std::fabs(v[2])});
  if (scale == 0) return false;
  const double u[3] = {v[0] / scale, v[1] / scale, v[2] / scale};
  const double len = std::sqrt(u[0] * u[0] + u[1] * u[1] + u[2] * u[2]);
  for (int c = 0; c < 3; ++c) out[c] = u[c] / len;
  return true;
}

void require_device(arcus_context_t* ctx) {
  if (!ctx->info.fp64)
    fail(ARCUS_ERROR_UNSUPPORTED,
         std::string("photon map: device '") + ctx->info.name + "' has no double precision (cl_khr_fp64)");
}

// A checked batch of queries on the device: x y z (and the unit normal nx ny nz for
// surface queries), each component `count` reals.
struct Batch {
  size_t count = 0;
  arcus_photon_query_desc desc{};
  std::unique_ptr<DeviceBuffer> queries;
};

Batch upload_queries(arcus_context_t* ctx, const PhotonMap& map, const std::vector<double>& points,
                     const std::vector<double>& normals, const Query& q, double result_bytes_per_query) {
  require(map.usable_by(ctx), "photon map: it was built on another device than this context's");
  require(q.k >= 1 && q.k <= ARCUS_PHOTON_MAX_K, "photon query: k = " + std::to_string(q.k) + " is outside 1.." +
                                                     std::to_string(ARCUS_PHOTON_MAX_K) + " (ARCUS_PHOTON_MAX_K)");
  require(q.max_radius > 0, "photon query: max_radius = " + number(q.max_radius) +
                                " must be a positive number (+inf: no cap)");
  require(q.mode == Mode::surface || q.mode == Mode::volume,
          "photon query: mode = " + std::to_string(static_cast<int32_t>(q.mode)) + " is neither surface nor volume");
  require(q.cone == 0 || (q.cone >= 1 && std::isfinite(q.cone)),
          "photon query: cone = " + number(q.cone) + " must be 0 (no filter) or a finite number >= 1");
  require(points.size() % 3 == 0, "photon query: points hold " + std::to_string(points.size()) +
                                      " numbers, not three per query");
  const bool surface = q.mode == Mode::surface;
  const size_t n = points.size() / 3;
  if (surface)
    require(normals.size() == points.size(), "photon query: a surface estimate needs a normal per query (" +
                                                 std::to_string(n) + " points, " + std::to_string(normals.size()) +
                                                 " normal components)");
  else
    require(normals.empty(), "photon query: a volume estimate takes no normals");
  require(n <= kMaxItems, "photon query: " + std::to_string(n) + " queries are more than 2^31 - 1 in one batch");

  const int comps = surface ? 6 : 3;
  std::vector<double> soa(comps * n);
  for (size_t i = 0; i < n; ++i) {
    const double* p = &points[3 * i];
    require(finite3(p), "photon query " + std::to_string(i) + ": point " + triple(p) + " is not finite");
    for (int c = 0; c < 3; ++c) soa[c * n + i] = p[c];
    if (!surface) continue;
    double u[3];
    require(normalise(&normals[3 * i], u),
            "photon query " + std::to_string(i) + ": normal " + triple(&normals[3 * i]) + " is zero or not finite");
    for (int c = 0; c < 3; ++c) soa[(3 + c) * n + i] = u[c];
  }
  Batch b;
  b.count = n;
  b.desc.max_radius = q.max_radius;
  b.desc.cone = q.cone;
  b.desc.k = q.k;
  b.desc.mode = static_cast<int32_t>(q.mode);
  b.desc.count = static_cast<int32_t>(n);
  if (n == 0) return b;
  require_device(ctx);
  const double query_bytes = static_cast<double>(soa.size() * sizeof(double));
  check_device_allocation(ctx, std::max(query_bytes, result_bytes_per_query * n),
                          query_bytes + result_bytes_per_query * n, std::to_string(n) + " photon queries");
  b.queries = std::make_unique<DeviceBuffer>(ctx, soa.size() * sizeof(double), "the photon queries", soa.data());
  return b;
}

// The batch kernel `name` with the map's and the queries' arguments set (0..4).
KernelCall batch_kernel(arcus_context_t* ctx, const PhotonMap& map, const Batch& b, const char* name) {
  // Scalar traversal: one query per work-item whatever the device's lanes.
  const BuiltProgram program = ctx->runtime->program(source(), 0, Layout{1, 1});
  KernelCall call(program.program, name);
  set_map_arguments(call, 0, map);
  call.set(3, b.queries.get());
  call.set_value(4, b.desc);
  return call;
}

}  // namespace

PhotonMap::PhotonMap(arcus_context_t* ctx, const Photons& in, int min_leaf) : runtime_(ctx->runtime.get()) {
  const int ch = in.channels;
  require(ch >= 1 && ch <= ARCUS_PHOTON_CHANNELS, "photon map: channels = " + std::to_string(ch) + " is outside 1.." +
                                                      std::to_string(ARCUS_PHOTON_CHANNELS) +
                                                      " (ARCUS_PHOTON_CHANNELS)");
  require(in.positions.size() % 3 == 0,
          "photon map: positions hold " + std::to_string(in.positions.size()) + " numbers, not three per photon");
  const size_t n = in.positions.size() / 3;
  require(in.directions.size() == 3 * n, "photon map: " + std::to_string(n) + " positions but " +
                                             std::to_string(in.directions.size()) + " direction components");
  require(in.powers.size() == static_cast<size_t>(ch) * n,
          "photon map: " + std::to_string(n) + " photons of " + std::to_string(ch) + " channels need " +
              std::to_string(ch * n) + " powers, not " + std::to_string(in.powers.size()));
  require(n <= kMaxItems, "photon map: " + std::to_string(n) + " photons are more than 2^31 - 1");
  desc_.count = static_cast<int32_t>(n);
  desc_.channels = ch;

  std::vector<bvh::Bounds> bounds(n);
  std::vector<double> dirs(3 * n);
  for (size_t i = 0; i < n; ++i) {
    const double* p = &in.positions[3 * i];
    // The message is built only for a bad photon: millions of good ones pass here.
    auto which = [i] { return "photon map: photon " + std::to_string(i); };
    if (!finite3(p)) fail(ARCUS_ERROR_INVALID_ARGUMENT, which() + ": position " + triple(p) + " is not finite");
    if (!bvh::representable(p))
      fail(ARCUS_ERROR_INVALID_ARGUMENT, which() + ": position " + triple(p) + " lies beyond the " +
                                             number(bvh::kMaxCoordinate) + " m from the origin that the BVH can represent");
    if (!normalise(&in.directions[3 * i], &dirs[3 * i]))
      fail(ARCUS_ERROR_INVALID_ARGUMENT,
           which() + ": direction " + triple(&in.directions[3 * i]) + " is zero or not finite");
    for (int c = 0; c < ch; ++c) {
      const double w = in.powers[ch * i + c];
      if (!(std::isfinite(w) && w >= 0))
        fail(ARCUS_ERROR_INVALID_ARGUMENT,
             which() + ": power[" + std::to_string(c) + "] = " + number(w) + " is not a finite number >= 0");
    }
    for (int a = 0; a < 3; ++a) bounds[i].lo[a] = bounds[i].hi[a] = p[a];  // a point: zero-size bounds
  }
  if (n == 0) return;  // no buffers: the kernels look at desc.count first
  require_device(ctx);

  const double node_bytes_max = (2.0 * n) * sizeof(arcus_bvh_node_d);  // a binary tree over n leaves at most
  const double photon_bytes = static_cast<double>(n) * (ARCUS_PHOTON_POWER + ch) * sizeof(double);
  check_device_allocation(ctx, std::max(node_bytes_max, photon_bytes), node_bytes_max + photon_bytes,
                          "a photon map of " + std::to_string(n) + " photons");

  // The builder refuses trees deeper than the kernels' stack (ARCUS_BVH_MAX_DEPTH).
  bvh::Flat tree = bvh::build(bounds, std::max(4, min_leaf), min_leaf);
  depth_ = tree.depth;
  order_ = std::move(tree.order);

  // Photons in leaf order, a structure of arrays (kernels/photon/photon_desc.h).
  std::vector<double> soa((ARCUS_PHOTON_POWER + ch) * n);
  for (size_t s = 0; s < n; ++s) {
    const size_t i = order_[s];
    for (int a = 0; a < 3; ++a) {
      soa[(ARCUS_PHOTON_POSITION + a) * n + s] = in.positions[3 * i + a];
      soa[(ARCUS_PHOTON_DIRECTION + a) * n + s] = dirs[3 * i + a];
    }
    for (int c = 0; c < ch; ++c) soa[(ARCUS_PHOTON_POWER + c) * n + s] = in.powers[ch * i + c];
  }
  nodes_ = std::make_shared<DeviceBuffer>(ctx, tree.nodes.size() * sizeof(arcus_bvh_node_d), "the photon map's BVH",
                                          tree.nodes.data());
  photons_ = std::make_shared<DeviceBuffer>(ctx, soa.size() * sizeof(double), "the photon map's photons", soa.data());
}

size_t PhotonMap::bytes() const {
  return (nodes_ ? nodes_->bytes() : 0) + (photons_ ? photons_->bytes() : 0);
}

bool PhotonMap::usable_by(const arcus_context_t* ctx) const { return ctx->runtime.get() == runtime_; }

Estimates estimate(arcus_context_t* ctx, const PhotonMap& map, const std::vector<double>& points,
                   const std::vector<double>& normals, const Query& query) {
  const int ch = map.channels();
  const Batch b = upload_queries(ctx, map, points, normals, query, (ch + 1.0) * sizeof(double) + sizeof(int32_t));
  Estimates e;
  e.values.assign(b.count * ch, 0.0);
  e.radius.assign(b.count, 0.0);
  e.found.assign(b.count, 0);
  if (b.count == 0) return e;
  DeviceBuffer values(ctx, e.values.size() * sizeof(double), "the photon estimates");
  DeviceBuffer radius(ctx, b.count * sizeof(double), "the photon estimates' radii");
  DeviceBuffer found(ctx, b.count * sizeof(int32_t), "the photon estimates' counts");
  KernelCall call = batch_kernel(ctx, map, b, "arcus_photon_estimate");
  call.set(5, &values);
  call.set(6, &radius);
  call.set(7, &found);
  e.kernel_seconds = call.run(ctx, b.count);
  values.read(ctx, 0, values.bytes(), e.values.data());
  radius.read(ctx, 0, radius.bytes(), e.radius.data());
  found.read(ctx, 0, found.bytes(), e.found.data());
  return e;
}

Neighbours nearest(arcus_context_t* ctx, const PhotonMap& map, const std::vector<double>& points,
                   const std::vector<double>& normals, const Query& query) {
  const double k = query.k;
  const Batch b = upload_queries(ctx, map, points, normals, query, k * (sizeof(int32_t) + sizeof(double)) + 4.0);
  Neighbours r;
  r.found.assign(b.count, 0);
  if (b.count == 0) return r;
  const size_t entries = b.count * static_cast<size_t>(query.k);
  DeviceBuffer slots(ctx, entries * sizeof(int32_t), "the nearest photons");
  DeviceBuffer dist2(ctx, entries * sizeof(double), "the nearest photons' distances");
  DeviceBuffer found(ctx, b.count * sizeof(int32_t), "the nearest photons' counts");
  KernelCall call = batch_kernel(ctx, map, b, "arcus_photon_knn");
  call.set(5, &slots);
  call.set(6, &dist2);
  call.set(7, &found);
  call.run(ctx, b.count);
  std::vector<int32_t> s(entries);
  r.distance.resize(entries);
  slots.read(ctx, 0, slots.bytes(), s.data());
  dist2.read(ctx, 0, dist2.bytes(), r.distance.data());
  found.read(ctx, 0, found.bytes(), r.found.data());
  r.index.resize(entries);
  for (size_t j = 0; j < entries; ++j) {
    r.index[j] = s[j] < 0 ? -1 : static_cast<int64_t>(map.order()[s[j]]);
    r.distance[j] = std::sqrt(r.distance[j]);
  }
  return r;
}

LineMarch march_lines(arcus_context_t* ctx, const PhotonMap& map, const std::vector<double>& starts,
                      const std::vector<double>& directions, int steps, double step, int k) {
  require(starts.size() % 3 == 0 && directions.size() == starts.size(),
          "photon line march: a start and a direction (three numbers each) per line");
  require(steps >= 1 && std::isfinite(step) && step > 0, "photon line march: steps >= 1 and a step > 0");
  Query q;
  q.k = k;
  q.mode = Mode::surface;  // the lines' directions travel as the normals of surface queries, normalised
  const size_t per_line = static_cast<size_t>(steps) * (4 * sizeof(double) + 2 * sizeof(int64_t)) + 4;
  const Batch b = upload_queries(ctx, map, starts, directions, q, static_cast<double>(per_line));
  LineMarch m;
  const size_t e = b.count * static_cast<size_t>(steps);
  m.points.resize(3 * e);
  m.radius.resize(e);
  m.digest.resize(2 * e);
  m.lone.resize(b.count);
  if (b.count == 0) return m;
  DeviceBuffer points(ctx, m.points.size() * sizeof(double), "the lines' points");
  DeviceBuffer radius(ctx, e * sizeof(double), "the lines' k-th distances");
  DeviceBuffer digest(ctx, m.digest.size() * sizeof(int64_t), "the lines' k-sets");
  DeviceBuffer lone(ctx, b.count * sizeof(int32_t), "the lines' lone searches");
  KernelCall call = batch_kernel(ctx, map, b, "arcus_photon_line_march");
  call.set_value(5, int32_t(steps));
  call.set_value(6, step);
  call.set(7, &points);
  call.set(8, &radius);
  call.set(9, &digest);
  call.set(10, &lone);
  call.run(ctx, b.count);
  points.read(ctx, 0, points.bytes(), m.points.data());
  radius.read(ctx, 0, radius.bytes(), m.radius.data());
  digest.read(ctx, 0, digest.bytes(), m.digest.data());
  lone.read(ctx, 0, lone.bytes(), m.lone.data());
  return m;
}

const std::vector<const char*>& device_headers() { return kHeaders; }

void set_map_arguments(KernelCall& call, unsigned first, const PhotonMap& map) {
  call.set(first, map.nodes());
  call.set(first + 1, map.photons());
  call.set_value(first + 2, map.desc());
}

}  // namespace arcus::photon
