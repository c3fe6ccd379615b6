#include "rainbow/cast.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <complex>
#include <limits>
#include <map>
#include <utility>
#include <string>
#include <vector>

#include "bvh/bvh.h"
#include "core/context.h"
#include "core/error.h"
#include "core/features.h"
#include "core/format.h"
#include "core/job.h"
#include "core/kernel_source.h"
#include "core/runtime.h"
#include "core/launch.h"

// The host traces single rays too (the bisection onto the projected edge) with the
// kernels' own code, every shape compiled in.
#define ARCUS_USE_RAINBOW_IMPLICIT
#define ARCUS_USE_RAINBOW_MESH
#include "rainbow/optics.h"

namespace arcus::rainbow {
namespace {

constexpr double kPi = 3.14159265358979323846;
constexpr int R = ARCUS_RAINBOW_RECORD;
// Patches wider than this are unresolved (a grazing fan, a fold seen edge-on): their
// bilinear interpolation would mean nothing, and their chords would cut far across the
// sphere, so they are left out and counted.
const double kMaxPatchCos = std::cos(60.0 * kPi / 180.0);

const FeatureTable kTable{"rainbow",
                          {{ARCUS_FEATURE_RAINBOW_IMPLICIT, "RAINBOW_IMPLICIT", "-D ARCUS_USE_RAINBOW_IMPLICIT"},
                           {ARCUS_FEATURE_RAINBOW_MESH, "RAINBOW_MESH", "-D ARCUS_USE_RAINBOW_MESH"},
                           {ARCUS_FEATURE_RAINBOW_AZIMUTH, "RAINBOW_AZIMUTH", "-D ARCUS_USE_RAINBOW_AZIMUTH"}}};
const FeatureTableEntry kRegistered(&kTable);

ARCUS_KERNEL_ARGS(CastArg, "arcus_rainbow_cast", ARCUS_RAINBOW_CAST_ARGS);

const KernelSource kCast{"rainbow/cast",
                         {"common/real.h", "common/fresnel.h", "bvh/bvh_desc.h", "bvh/traverse.h",
                          "rainbow/rainbow_desc.h", "rainbow/optics.h", "rainbow/cast.cl"},
                         ""};

double seconds_since(std::chrono::steady_clock::time_point t0) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
}

// Eq. 4.27-4.28: the grid denser toward the projection's edge.
double warp(double u, double alpha) { return alpha * u + (1 - alpha) * std::sin(kPi / 2 * u); }

// The signed solid angle of the spherical triangle (a, b, c) of unit vectors (Van
// Oosterom & Strackee 1983): positive when a, b, c turn counter-clockwise seen from
// outside.
double solid_angle(const double* a, const double* b, const double* c) {
  double bc[3];
  rb_cross(b, c, bc);
  const double triple = rb_dot(a, bc);
  const double den = 1 + rb_dot(a, b) + rb_dot(b, c) + rb_dot(c, a);
  return 2 * std::atan2(triple, den);
}

// The particle in the world frame for the kernels: its descriptor and (meshes) its
// triangles under the shared BVH.
struct Placed {
  rainbow_cast_desc desc{};
  bvh::TriangleBvh bvh;         // meshes only
  std::vector<double> normals;  // smooth meshes: 9 per leaf slot, the vertices' normals
  rb_mesh host_mesh() const {
    rb_mesh m{};
    if (!bvh.tree.order.empty()) {
      m.nodes = bvh.tree.nodes.data();
      m.tris = bvh.triangles.data();
      m.order = reinterpret_cast<const int*>(bvh.tree.order.data());
      m.normals = normals.empty() ? nullptr : normals.data();
    }
    return m;
  }
};

Placed place(const Particle& particle, const CastParams& params) {
  Placed pl;
  rainbow_cast_desc& d = pl.desc;
  std::copy(params.rotation, params.rotation + 9, d.rotation);
  d.kind = particle.kind;
  d.n = params.n;
  d.plane = 2 * particle.bound;
  d.bounces = params.bounces;
  switch (particle.kind) {
    case ARCUS_RAINBOW_SHAPE_SPHERE: d.shape[0] = particle.radius; break;
    case ARCUS_RAINBOW_SHAPE_RAINDROP:
      d.shape[0] = particle.a;
      d.shape[1] = particle.b;
      // Eq. 4.21 as printed is wide at +y; the drop is flattened underneath (Beard &
      // Chuang; thesis Fig. 4.11), so with y up the deformation enters with its sign flipped.
      d.shape[2] = -particle.k;
      d.shape[3] = particle.bound;
      break;
    default: {
      double m[12] = {0};
      for (int r = 0; r < 3; ++r)
        for (int c = 0; c < 3; ++c) m[4 * r + c] = params.rotation[3 * r + c];
      const geometry::Mesh world = geometry::transformed(particle.mesh, m);
      pl.bvh = bvh::build_triangles(world);
      d.shape[0] = particle.bound;
      d.shape[1] = particle.bound * 1e-9;  // steps a ray off the face it starts on
      if (particle.smooth) {
        const std::vector<double> vn = vertex_normals(world);
        pl.normals.resize(9 * pl.bvh.tree.order.size());
        for (size_t slot = 0; slot < pl.bvh.tree.order.size(); ++slot) {
          const uint32_t tri = pl.bvh.tree.order[slot];
          for (int k = 0; k < 3; ++k)
            for (int a = 0; a < 3; ++a) pl.normals[9 * slot + 3 * k + a] = vn[3 * world.triangles[3 * tri + k] + a];
        }
      }
    }
  }
  return pl;
}

// The host's view of the traced rays: record p of ray r.
struct Records {
  int rays = 0, terms = 0;
  std::vector<double> data;  // terms × rays × R
  double* at(int p, int r) { return &data[(size_t(p) * rays + r) * R]; }
  const double* at(int p, int r) const { return &data[(size_t(p) * rays + r) * R]; }
};

double ray_power(const double* rec) {
  if (rec[12] != 1) return 0;
  double s = 0;
  for (int c = 3; c < 11; ++c) s += rec[c] * rec[c];
  return s / 2;  // both polarisations, each incident with power 1
}

// The glints of a flat mesh: per term and sequence of faces, the rays' cast area (each
// hit cell's area shared among its four corners) and power, and their direction
// (area-weighted; all equal on flat faces, to rounding).
std::vector<Glint> glints(const Records& rec, const std::vector<double>& area, const std::vector<double>& left, int n) {
  std::map<std::pair<int, double>, Glint> by_sequence;
  const int cells = n - 1;
  std::vector<double> share(size_t(n) * n, 0.0);
  for (int j = 0; j < cells; ++j)
    for (int i = 0; i < cells; ++i) {
      const int c[4] = {j * n + i, j * n + i + 1, (j + 1) * n + i + 1, (j + 1) * n + i};
      if (left[c[0]] < 0 || left[c[1]] < 0 || left[c[2]] < 0 || left[c[3]] < 0) continue;
      for (int k = 0; k < 4; ++k) share[c[k]] += area[size_t(j) * cells + i] / 4;
    }
  for (int p = 0; p < rec.terms; ++p)
    for (int r = 0; r < rec.rays; ++r) {
      const double* q = rec.at(p, r);
      if (q[12] != 1 || share[r] == 0) continue;
      Glint& g = by_sequence[{p, q[13]}];
      g.p = p;
      g.area += share[r];
      g.cross_section += share[r] * ray_power(q);
      for (int a = 0; a < 3; ++a) g.direction[a] += share[r] * q[a];
    }
  std::vector<Glint> out;
  for (auto& entry : by_sequence) {
    Glint g = entry.second;
    const double l = std::sqrt(g.direction[0] * g.direction[0] + g.direction[1] * g.direction[1] +
                               g.direction[2] * g.direction[2]);
    for (double& x : g.direction) x /= l;
    out.push_back(g);
  }
  return out;
}

}  // namespace

arcus_features cast_features(const Particle& particle) {
  if (particle.kind == ARCUS_RAINBOW_SHAPE_RAINDROP) return ARCUS_FEATURE_RAINBOW_IMPLICIT;
  if (particle.kind == ARCUS_RAINBOW_SHAPE_MESH) return ARCUS_FEATURE_RAINBOW_MESH;
  return 0;
}

void check_cast(const CastParams& p) {
  require(std::isfinite(p.wavelength_nm) && p.wavelength_nm > 0,
          "wavelength_nm must be positive and finite, got " + number(p.wavelength_nm));
  require(std::isfinite(p.n) && p.n > 1 && p.n < 4,
          "the refractive index must lie in (1, 4) relative to air, got " + number(p.n));
  require(p.grid >= 4 && p.grid <= 8192, "grid must be 4 to 8192 rays per side, got " + std::to_string(p.grid));
  require(std::isfinite(p.alpha) && p.alpha > 0 && p.alpha <= 1,
          "alpha (the grid's warp, eq. 4.27) must lie in (0, 1], got " + number(p.alpha));
  require(p.bounces >= 0 && p.bounces <= ARCUS_RAINBOW_MAX_BOUNCES,
          "max_bounces must be 0 to " + std::to_string(ARCUS_RAINBOW_MAX_BOUNCES) + ", got " +
              std::to_string(p.bounces));
  check_rotation(p.rotation, "rotation");
  require(std::isnan(p.query_phi_deg) || std::isfinite(p.query_phi_deg),
          "query_phi_deg must be finite or NaN (every azimuth)");
}

void check_rotation(const double* m, const std::string& name) {
  // orthonormal with determinant +1, to rounding
  for (int i = 0; i < 9; ++i) require(std::isfinite(m[i]), name + " holds a non-finite entry");
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) {
      const double dot = m[i] * m[j] + m[3 + i] * m[3 + j] + m[6 + i] * m[6 + j];
      require(std::fabs(dot - (i == j)) < 1e-9, name + " is not orthonormal (columns " + std::to_string(i) +
                                                     ", " + std::to_string(j) + " give " + number(dot) + ")");
    }
  const double det = m[0] * (m[4] * m[8] - m[5] * m[7]) - m[1] * (m[3] * m[8] - m[5] * m[6]) +
                     m[2] * (m[3] * m[7] - m[4] * m[6]);
  require(det > 0, name + " is a reflection (determinant " + number(det) + "), not a rotation");
}

std::unique_ptr<RainbowJob> cast(arcus_context_t* ctx, const Particle& particle, const CastParams& params,
                                 arcus_progress_callback progress, void* progress_user, bool* cancelled) {
  check_cast(params);
  const auto t_start = std::chrono::steady_clock::now();
  auto job = std::make_unique<RainbowJob>(ctx);
  const int n = params.grid, terms = params.bounces + 1;
  const int rays = n * n;
  job->terms = terms;
  job->wave_number = 2 * kPi / (params.wavelength_nm * 1e-9);
  job->query_phi_deg = params.query_phi_deg;
  job->features = cast_features(particle);
  job->count = size_t(rays);
  arcus_rainbow_stats& info = job->info;
  info.refractive_index = params.n;
  info.rays = uint64_t(rays);

  Placed pl = place(particle, params);
  const rainbow_cast_desc& desc = pl.desc;
  // The grid over the particle's projection, a square of half-width `bound`.
  std::vector<double> points(2 * size_t(rays));
  for (int j = 0; j < n; ++j)
    for (int i = 0; i < n; ++i) {
      points[2 * (size_t(j) * n + i)] = particle.bound * warp(-1 + 2.0 * i / (n - 1), params.alpha);
      points[2 * (size_t(j) * n + i) + 1] = particle.bound * warp(-1 + 2.0 * j / (n - 1), params.alpha);
    }

  const Layout layout{1, 1};  // scalar: a ray per work-item (cast.cl)
  const BuiltProgram built = build_job_program(ctx, *job, kCast, layout);
  std::unique_ptr<bvh::DeviceBvh> mesh_bvh;
  std::unique_ptr<DeviceBuffer> normals_dev;
  if (particle.kind == ARCUS_RAINBOW_SHAPE_MESH) mesh_bvh = std::make_unique<bvh::DeviceBvh>(ctx, pl.bvh, false);
  if (!pl.normals.empty())
    normals_dev = std::make_unique<DeviceBuffer>(ctx, pl.normals.size() * sizeof(double), "the mesh's vertex normals",
                                                 pl.normals.data());

  // Traces the rays at `pts` ((u, v) pairs) into rec and left, in slices; `sliced`: the
  // caller's progress callback sees them (the grid's pass, not the few edge rays').
  auto trace = [&](const std::vector<double>& pts, Records& rec, std::vector<double>& left, bool sliced) {
    const int total = static_cast<int>(pts.size() / 2);
    rec.rays = total;
    rec.terms = terms;
    rec.data.assign(size_t(terms) * total * R, 0.0);
    left.assign(size_t(total), -1.0);
    Launch<CastArg> launch(ctx, built.program);
    launch.upload(CastArg::points, pts, "the cast grid");
    DeviceBuffer rec_dev(ctx, rec.data.size() * sizeof(double), "the traced rays");
    DeviceBuffer left_dev(ctx, left.size() * sizeof(double), "the rays' remaining power");
    launch.bind(CastArg::nodes, mesh_bvh ? mesh_bvh->nodes().get() : nullptr);
    launch.bind(CastArg::tris, mesh_bvh ? mesh_bvh->triangles().get() : nullptr);
    launch.bind(CastArg::order, mesh_bvh ? mesh_bvh->order_buffer().get() : nullptr);
    launch.bind(CastArg::normals, normals_dev.get());
    launch.bind_value(CastArg::rays, int32_t(total));
    launch.bind(CastArg::records, &rec_dev);
    launch.bind(CastArg::left, &left_dev);
    // A slice: rays [first, end), one a work-item.
    SliceRange slices{uint64_t(total), 65536};
    if (sliced) {
      slices.progress = progress;
      slices.progress_user = progress_user;
    }
    const bool stop = launch.run_slices(slices, [&](uint64_t first, uint64_t end) {
      rainbow_cast_desc d = desc;
      d.first = static_cast<int32_t>(first);
      d.count = static_cast<int32_t>(end - first);
      launch.bind_value(CastArg::d, d);
      return size_t(d.count);
    }, &job->stats);
    rec_dev.read(ctx, 0, rec.data.size() * sizeof(double), rec.data.data());
    left_dev.read(ctx, 0, left.size() * sizeof(double), left.data());
    return stop;
  };

  const auto t_cast = std::chrono::steady_clock::now();
  Records rec;
  std::vector<double> left;
  *cancelled = trace(points, rec, left, true);
  if (*cancelled) return job;

  // Rays onto the projected edge (§4.4.3.1): a grid point that misses beside one that
  // hits moves, by bisection along the segment between them, to the last point that
  // still hits, so the patches reach the edge.
  uint64_t moved = 0;
  if (params.edge_rays) {
    const rb_mesh host_mesh = pl.host_mesh();
    auto hits = [&](double u, double v) {
      const double o[3] = {u, v, -desc.plane}, k0[3] = {0, 0, 1};
      double t, nrm[3];
      int slot;
      return rb_hit(&desc, &host_mesh, o, k0, 0, &t, nrm, &slot) != 0;
    };
    std::vector<double> edge_points;
    std::vector<int> edge_rays;
    for (int j = 0; j < n; ++j)
      for (int i = 0; i < n; ++i) {
        const int r = j * n + i;
        if (left[r] >= 0) continue;
        const int nb[4][2] = {{i - 1, j}, {i + 1, j}, {i, j - 1}, {i, j + 1}};
        for (const auto& q : nb) {
          if (q[0] < 0 || q[0] >= n || q[1] < 0 || q[1] >= n) continue;
          const int s = q[1] * n + q[0];
          if (left[s] < 0) continue;
          double in[2] = {points[2 * s], points[2 * s + 1]}, out[2] = {points[2 * r], points[2 * r + 1]};
          for (int it = 0; it < 60; ++it) {
            const double mid[2] = {(in[0] + out[0]) / 2, (in[1] + out[1]) / 2};
            if ((mid[0] == in[0] && mid[1] == in[1]) || (mid[0] == out[0] && mid[1] == out[1])) break;
            if (hits(mid[0], mid[1])) {
              in[0] = mid[0];
              in[1] = mid[1];
            } else {
              out[0] = mid[0];
              out[1] = mid[1];
            }
          }
          // A flat crystal's silhouette is an edge between two faces: a ray exactly on
          // it meets both at once and its inner light goes astray.  On flat faces every
          // point carries the same light, so stop a thousandth of the segment inside.
          if (particle.kind == ARCUS_RAINBOW_SHAPE_MESH && !particle.smooth)
            for (int a = 0; a < 2; ++a) in[a] += 1e-3 * (points[2 * s + a] - in[a]);
          points[2 * r] = in[0];
          points[2 * r + 1] = in[1];
          edge_points.push_back(in[0]);
          edge_points.push_back(in[1]);
          edge_rays.push_back(r);
          break;
        }
      }
    moved = edge_rays.size();
    if (moved > 0) {
      Records er;
      std::vector<double> el;
      trace(edge_points, er, el, false);
      for (size_t e = 0; e < edge_rays.size(); ++e) {
        left[edge_rays[e]] = el[e];
        for (int p = 0; p < terms; ++p) std::copy(er.at(p, int(e)), er.at(p, int(e)) + R, rec.at(p, edge_rays[e]));
      }
    }
  }
  info.edge_rays = moved;
  info.cast_seconds = seconds_since(t_cast);

  // ---- the patches (§4.4.3.2) and the normalisation of eq. 4.29
  const auto t_patch = std::chrono::steady_clock::now();
  const int cells = n - 1;
  auto ray = [n](int i, int j) { return j * n + i; };
  std::vector<double> area(size_t(cells) * cells, 0.0);
  double intercepted = 0, remaining = 0;
  for (int j = 0; j < cells; ++j)
    for (int i = 0; i < cells; ++i) {
      const int c[4] = {ray(i, j), ray(i + 1, j), ray(i + 1, j + 1), ray(i, j + 1)};
      double a = 0;
      for (int k = 0; k < 4; ++k) {
        const double* p0 = &points[2 * c[k]];
        const double* p1 = &points[2 * c[(k + 1) % 4]];
        a += p0[0] * p1[1] - p1[0] * p0[1];
      }
      area[size_t(j) * cells + i] = std::fabs(a) / 2;
      bool all_hit = true;
      double l = 0;
      for (int k = 0; k < 4; ++k) {
        all_hit = all_hit && left[c[k]] >= 0;
        l += left[c[k]];
      }
      if (!all_hit) continue;
      intercepted += std::fabs(a) / 2;
      remaining += std::fabs(a) / 2 * l / 8;  // the mean of 4 corners, per polarisation
    }
  for (int r = 0; r < rays; ++r) info.hits += left[r] >= 0;
  info.intercepted = intercepted;

  // Per term: which cells make patches, their solid angles, and each corner's mean
  // cell area and solid angle (eq. 4.29's averages over the patches that hold it).
  struct Corner {
    double area = 0, solid = 0;
    int cells = 0;
  };
  std::vector<Corner> corner(size_t(terms) * rays);
  const double phi0 = params.query_phi_deg * kPi / 180;
  const double plane_n[3] = {-std::sin(phi0), std::cos(phi0), 0}, plane_d[3] = {std::cos(phi0), std::sin(phi0), 0};
  const bool filter = !std::isnan(params.query_phi_deg);
  std::vector<uint8_t> kept(size_t(terms) * cells * cells, 0);
  for (int p = 0; p < terms; ++p) {
    double power = 0;
    for (int j = 0; j < cells; ++j)
      for (int i = 0; i < cells; ++i) {
        const int c[4] = {ray(i, j), ray(i + 1, j), ray(i + 1, j + 1), ray(i, j + 1)};
        const double* q[4];
        bool ok = true;
        for (int k = 0; k < 4; ++k) {
          q[k] = rec.at(p, c[k]);
          ok = ok && q[k][12] == 1 && q[k][13] == q[0][13];
          for (int e = 0; e < 12 && ok; ++e) ok = std::isfinite(q[k][e]);
        }
        const double a = area[size_t(j) * cells + i];
        // the power leaving in term p through this cell: a record that does not exist
        // (a missed or totally reflected ray) carries none, so the books balance cell
        // by cell with what remains inside
        if (left[c[0]] >= 0 && left[c[1]] >= 0 && left[c[2]] >= 0 && left[c[3]] >= 0)
          power += a * (ray_power(q[0]) + ray_power(q[1]) + ray_power(q[2]) + ray_power(q[3])) / 4;
        if (!ok) continue;
        // A patch whose corners passed different numbers of focal lines straddles a
        // caustic: its corners belong to two branches of the wavefront (the two rays of
        // a rainbow angle), which interpolation must not mix (§4.4.3: adjacency is what
        // tells one wavefront from another).  It is left out, and counted.
        if (q[1][14] != q[0][14] || q[2][14] != q[0][14] || q[3][14] != q[0][14]) {
          ++info.patches_folded;
          continue;
        }
        const size_t cell = size_t(p) * cells * cells + size_t(j) * cells + i;
        double min_dot = 1;
        for (int k = 0; k < 4; ++k)
          for (int m = k + 1; m < 4; ++m) min_dot = std::min(min_dot, rb_dot(q[k], q[m]));
        if (min_dot < kMaxPatchCos) {
          ++info.patches_rejected;
          continue;
        }
        const double s = std::fabs(solid_angle(q[0], q[1], q[2]) + solid_angle(q[0], q[2], q[3]));
        // A patch whose corners leave in one direction (a focal point: the raindrop's
        // p = 2 has some) spreads its light over no solid angle, an infinite intensity
        // the interpolation cannot hold: unresolved, like the wide ones.
        if (!(s > 1e-15)) {
          ++info.patches_rejected;
          continue;
        }
        for (int k = 0; k < 4; ++k) {
          Corner& cr = corner[size_t(p) * rays + c[k]];
          cr.area += a;
          cr.solid += s;
          ++cr.cells;
        }
        if (filter) {
          double lo = 1, hi = -1, along = -1;
          for (int k = 0; k < 4; ++k) {
            const double x = rb_dot(q[k], plane_n);
            lo = std::min(lo, x);
            hi = std::max(hi, x);
            along = std::max(along, rb_dot(q[k], plane_d));
          }
          // near the poles every azimuth meets: keep what straddles the plane there too
          if (!(lo <= 0 && hi >= 0 && (along >= 0 || std::fabs(q[0][2]) > 0.999))) continue;
        }
        kept[cell] = 1;
      }
    if (p < 16) info.scattered[p] = intercepted > 0 ? power / intercepted : 0;
  }
  info.remaining = intercepted > 0 ? remaining / intercepted : 0;
  double scattered = 0;
  for (int p = 0; p < std::min(terms, 16); ++p) scattered += info.scattered[p];
  job->cross_section = scattered * intercepted;
  if (particle.kind == ARCUS_RAINBOW_SHAPE_MESH && !particle.smooth) job->glints = glints(rec, area, left, n);

  // The corners of kept patches, compacted: direction, normalised phasors turned by
  // their focal lines, optical path, focal lines.
  std::vector<int32_t> compact(size_t(terms) * rays, -1);
  std::vector<double> corners;
  std::vector<rainbow_patch> patches;
  geometry::Mesh chords;
  for (int p = 0; p < terms; ++p)
    for (int j = 0; j < cells; ++j)
      for (int i = 0; i < cells; ++i) {
        const size_t cell = size_t(p) * cells * cells + size_t(j) * cells + i;
        if (!kept[cell]) continue;
        const int c[4] = {ray(i, j), ray(i + 1, j), ray(i + 1, j + 1), ray(i, j + 1)};
        rainbow_patch pt{};
        pt.p = p;
        for (int k = 0; k < 4; ++k) {
          const size_t key = size_t(p) * rays + c[k];
          if (compact[key] < 0) {
            compact[key] = static_cast<int32_t>(corners.size() / ARCUS_RAINBOW_CORNER);
            const double* q = rec.at(p, c[k]);
            const Corner& cr = corner[key];
            const double scale = std::sqrt((cr.area / cr.cells) / std::max(cr.solid / cr.cells, 1e-300));
            // −π/2 per focal line (§4.4.2.3; the Gouy phase in this e^{i(kx − ωt)} convention)
            const std::complex<double> turn = std::polar(scale, -q[14] * kPi / 2);
            for (int a = 0; a < 3; ++a) corners.push_back(q[a]);
            for (int e = 0; e < 4; ++e) {
              const std::complex<double> z = std::complex<double>(q[3 + 2 * e], q[4 + 2 * e]) * turn;
              corners.push_back(z.real());
              corners.push_back(z.imag());
            }
            corners.push_back(q[11]);
            corners.push_back(q[14]);
            for (int a = 0; a < 3; ++a) chords.positions.push_back(q[a]);
          }
          pt.corner[k] = compact[key];
        }
        const uint32_t v[4] = {uint32_t(pt.corner[0]), uint32_t(pt.corner[1]), uint32_t(pt.corner[2]),
                               uint32_t(pt.corner[3])};
        chords.triangles.insert(chords.triangles.end(), {v[0], v[1], v[2], v[0], v[2], v[3]});
        patches.push_back(pt);
      }
  info.patches = patches.size();
  info.patch_seconds = seconds_since(t_patch);
  rec = Records{};  // the rays are no longer needed: free them before the BVH build

  const auto t_bvh = std::chrono::steady_clock::now();
  job->patch_count = patches.size();
  if (!patches.empty()) {
    job->bvh = std::make_unique<bvh::DeviceBvh>(ctx, bvh::build_triangles(chords), false);
    job->corners = std::make_unique<DeviceBuffer>(ctx, corners.size() * sizeof(double), "the patch corners",
                                                  corners.data());
    job->patches = std::make_unique<DeviceBuffer>(ctx, patches.size() * sizeof(rainbow_patch), "the patches",
                                                  patches.data());
  }
  info.bvh_seconds = seconds_since(t_bvh);
  job->stats.total_seconds = seconds_since(t_start);
  return job;
}

}  // namespace arcus::rainbow
