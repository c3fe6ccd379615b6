#include "translucency/render.h"

#include <chrono>
#include <cmath>
#include <functional>
#include <string>

#include "bvh/bvh.h"
#include "bvh/device_bvh.h"
#include "core/buffer.h"
#include "core/context.h"
#include "core/error.h"
#include "core/format.h"
#include "core/kernel_source.h"
#include "core/launch.h"
#include "core/layout.h"
#include "translucency/surface.h"

// The kernels' shared headers: R_d, the gather's arguments, Fresnel (scalar host code
// after common/real.h).
#include "common/real.h"
#include "common/fresnel.h"
#include "translucency/dipole_rd.h"
#include "translucency/translucency_desc.h"

namespace arcus::translucency {
namespace {

const KernelSource kGather{"translucency/gather",
                           {"common/real.h", "bvh/bvh_desc.h", "translucency/dipole_rd.h",
                            "translucency/translucency_desc.h", "translucency/gather.cl"},
                           ""};
ARCUS_KERNEL_ARGS(AllArg, "arcus_translucency_gather_all", ARCUS_TRANSLUCENCY_GATHER_ALL_ARGS);
ARCUS_KERNEL_ARGS(TreeArg, "arcus_translucency_gather_tree", ARCUS_TRANSLUCENCY_GATHER_TREE_ARGS);


double seconds_since(std::chrono::steady_clock::time_point start) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

void check_params(const arcus_translucency_render_params& p) {
  check_view(p.camera, p.ortho_height, p.mm_per_unit, p.exit);
  auto finite_at_least = [](double v, double lo, bool open, const char* name, const char* what) {
    require(std::isfinite(v) && (open ? v > lo : v >= lo),
            std::string(name) + " = " + number(v) + " is not " + what);
  };
  finite_at_least(p.profile_scale, 0, true, "params->profile_scale", "a finite stretch > 0");
  require(p.profile_scaling == ARCUS_PROFILE_SCALE_ENERGY || p.profile_scaling == ARCUS_PROFILE_SCALE_THESIS,
          "params->profile_scaling = " + std::to_string(p.profile_scaling) +
              " is not ARCUS_PROFILE_SCALE_ENERGY (0) or ARCUS_PROFILE_SCALE_THESIS (1)");
  finite_at_least(p.sample_spacing_mm, 0, false, "params->sample_spacing_mm", "a finite spacing >= 0 (0: automatic)");
  require(p.gather == ARCUS_GATHER_HIERARCHICAL || p.gather == ARCUS_GATHER_BRUTE_FORCE,
          "params->gather = " + std::to_string(p.gather) +
              " is not ARCUS_GATHER_HIERARCHICAL (0) or ARCUS_GATHER_BRUTE_FORCE (1)");
  require(std::isfinite(p.max_solid_angle) && p.max_solid_angle >= 0 && p.max_solid_angle <= 4 * M_PI,
          "params->max_solid_angle = " + number(p.max_solid_angle) + " is not 0 (automatic) or a solid angle in (0, 4π] sr");
  require(std::isfinite(p.highlight_deg) && p.highlight_deg >= 0 && p.highlight_deg < 90,
          "params->highlight_deg = " + number(p.highlight_deg) + " is not an angle in [0, 90) degrees");
}

// The kernels' channel terms (dipole_rd.h) for the dipole stretched by s: R_d(r/s)/s² is
// the dipole whose coefficients are divided by s (R_d is an area density); the thesis'
// R_d(r/s) is that times s².
std::vector<double> channel_terms(const arcus_dipole& d, double s, int32_t scaling) {
  std::vector<double> out(3 * ARCUS_DIPOLE_TERMS);
  const double factor = scaling == ARCUS_PROFILE_SCALE_THESIS ? s * s : 1;
  for (int c = 0; c < 3; ++c) {
    const Terms t = terms(Channel{d.sigma_a[c] / s, d.sigma_s_prime[c] / s, d.eta});
    double* o = &out[size_t(c) * ARCUS_DIPOLE_TERMS];
    o[ARCUS_DIPOLE_Z_R] = t.z_r;
    o[ARCUS_DIPOLE_Z_V] = t.z_v;
    o[ARCUS_DIPOLE_SIGMA_TR] = t.sigma_tr;
    o[ARCUS_DIPOLE_WEIGHT] = factor * t.albedo / (4 * M_PI);
  }
  return out;
}

// A table's samples channel-major for the kernel, stretched by s as channel_terms
// stretches a dipole (the reach × s; the values / s² to keep the energy, or as they are).
std::vector<double> table_channels(const arcus_profile_table& t, double s, int32_t scaling) {
  std::vector<double> out(3 * size_t(t.count));
  const double factor = scaling == ARCUS_PROFILE_SCALE_THESIS ? 1 : 1 / (s * s);
  for (uint32_t k = 0; k < t.count; ++k)
    for (int c = 0; c < 3; ++c) out[size_t(c) * t.count + k] = factor * t.values[3 * size_t(k) + size_t(c)];
  return out;
}

// The profile's narrowest feature, before any stretch: the dipole's smallest mean free
// path 1/σ′_t; a table's smallest half-width (where R first falls to half of R(0))
// times 1.3, the dipole's ratio (for r ≪ ℓ_d, R_d ∝ d⁻³ halves at r ≈ 0.77 z_r).
double natural_spacing(const ProfileSource& profile) {
  double spacing = INFINITY;
  if (profile.dipole) {
    for (int c = 0; c < 3; ++c)
      spacing = std::min(spacing, 1 / (profile.dipole->sigma_a[c] + profile.dipole->sigma_s_prime[c]));
    return spacing;
  }
  const arcus_profile_table& t = *profile.table;
  for (int c = 0; c < 3; ++c) {
    const double peak = t.values[size_t(c)];
    for (uint32_t k = 1; k < t.count; ++k)
      if (t.values[3 * size_t(k) + size_t(c)] <= peak / 2) {
        const double u = double(k) / (t.count - 1);
        spacing = std::min(spacing, 1.3 * t.reach_mm * u * u);
        break;
      }
  }
  // A profile that never halves is flat over its reach: its samples need be no finer.
  return std::isfinite(spacing) ? spacing : t.reach_mm / 16;
}

// The samples' spacing: the caller's, or the profile's narrowest feature stretched by s,
// coarsened until the samples fit.
double choose_spacing(const Surface& surface, const ProfileSource& profile, double s, double asked) {
  if (asked > 0) {
    const uint64_t n = sample_count(surface, asked);
    require(n <= kMaxSamples, "params->sample_spacing_mm = " + number(asked) + " would take " +
                                  (n == UINT64_MAX ? std::string("more than 2^64") : std::to_string(n)) +
                                  " samples over " + number(surface.area) + " mm^2, more than " +
                                  std::to_string(kMaxSamples) + ": give a larger spacing");
    return asked;
  }
  double spacing = s * natural_spacing(profile);
  for (uint64_t n; (n = sample_count(surface, spacing)) > kMaxSamples;)
    spacing *= 1.05 * std::sqrt(double(n) / double(kMaxSamples));
  return spacing;
}

// The samples' BVH with each node's cluster (translucency_desc.h); reorders the samples
// and their powers into leaf order.
struct Tree {
  std::vector<arcus_bvh_node_d> nodes;
  std::vector<double> clusters;
};

Tree build_tree(std::vector<double>* positions, std::vector<double>* powers, const std::vector<double>& areas) {
  const size_t n = areas.size();
  std::vector<bvh::Bounds> boxes(n);
  for (size_t s = 0; s < n; ++s)
    for (int a = 0; a < 3; ++a) boxes[s].lo[a] = boxes[s].hi[a] = (*positions)[3 * s + a];
  const bvh::Flat flat = bvh::build(boxes, 8);
  std::vector<double> pos(3 * n), pow(3 * n), area(n);
  for (size_t slot = 0; slot < n; ++slot) {
    const size_t s = flat.order[slot];
    for (int a = 0; a < 3; ++a) {
      pos[3 * slot + a] = (*positions)[3 * s + a];
      pow[3 * slot + a] = (*powers)[3 * s + a];
    }
    area[slot] = areas[s];
  }
  *positions = std::move(pos);
  *powers = std::move(pow);
  Tree t{flat.nodes, std::vector<double>(flat.nodes.size() * ARCUS_CLUSTER_SIZE, 0.0)};
  // A node's sums: power per channel, Σ w·x and Σ w·x_a·x_b (xx, yy, zz, xy, xz, yz) with
  // w the power of all channels, Σ ΔA·x.
  struct Sums {
    double power[3] = {0, 0, 0}, weighted[3] = {0, 0, 0}, by_area[3] = {0, 0, 0}, second[6] = {0, 0, 0, 0, 0, 0},
           weight = 0, area = 0;
    void add(const Sums& o) {
      for (int k = 0; k < 3; ++k) {
        power[k] += o.power[k];
        weighted[k] += o.weighted[k];
        by_area[k] += o.by_area[k];
      }
      for (int k = 0; k < 6; ++k) second[k] += o.second[k];
      weight += o.weight;
      area += o.area;
    }
  };
  static constexpr int kPairA[6] = {0, 1, 2, 0, 0, 1}, kPairB[6] = {0, 1, 2, 1, 2, 2};
  const std::vector<double>& p = *positions;
  const std::vector<double>& e = *powers;
  std::function<Sums(int)> sum = [&](int at) {
    const arcus_bvh_node_d& node = t.nodes[size_t(at)];
    Sums total;
    if (node.count > 0) {
      for (int s = node.first; s < node.first + node.count; ++s) {
        Sums one;
        one.weight = e[3 * size_t(s)] + e[3 * size_t(s) + 1] + e[3 * size_t(s) + 2];
        one.area = area[size_t(s)];
        for (int k = 0; k < 3; ++k) {
          one.power[k] = e[3 * size_t(s) + k];
          one.weighted[k] = one.weight * p[3 * size_t(s) + k];
          one.by_area[k] = one.area * p[3 * size_t(s) + k];
        }
        for (int k = 0; k < 6; ++k)
          one.second[k] = one.weight * p[3 * size_t(s) + kPairA[k]] * p[3 * size_t(s) + kPairB[k]];
        total.add(one);
      }
    } else if (node.first >= 0) {
      total.add(sum(node.first));
      total.add(sum(node.first + 1));
    }
    double* c = &t.clusters[size_t(at) * ARCUS_CLUSTER_SIZE];
    for (int k = 0; k < 3; ++k) {
      c[ARCUS_CLUSTER_POWER + k] = total.power[k];
      // Unlit nodes are skipped by the kernel; their centroid is the area's, for tidiness.
      c[ARCUS_CLUSTER_CENTROID + k] = total.weight > 0 ? total.weighted[k] / total.weight
                                      : total.area > 0 ? total.by_area[k] / total.area
                                                       : 0;
    }
    c[ARCUS_CLUSTER_AREA] = total.area;
    if (total.weight > 0)  // unlit nodes add nothing: no spread needed
      for (int k = 0; k < 6; ++k) {
        const double* mean = &c[ARCUS_CLUSTER_CENTROID];
        c[ARCUS_CLUSTER_SPREAD + k] = total.second[k] / total.weight - mean[kPairA[k]] * mean[kPairB[k]];
      }
    return total;
  };
  sum(0);
  return t;
}

// Σ_i R_d E ΔA at each point (3 planes of `stride`): the kernel of the job's features.
std::vector<double> gather(arcus_context_t* ctx, RenderJob& job, const std::vector<double>& points,
                           std::vector<double> positions, std::vector<double> powers, const std::vector<double>& areas,
                           const std::vector<double>& channels, uint32_t table_size, double table_reach,
                           const arcus_translucency_render_params& p, size_t* stride_out, bool* cancelled) {
  const size_t count = points.size() / 3;
  const bool tree = p.gather == ARCUS_GATHER_HIERARCHICAL;
  // A table is read one point a work-item (gather.cl): no lanes to gather into.
  const Layout layout = tree || table_size > 0 ? Layout{1, 1} : choose_layout(ctx->runtime->entry(), 4);
  const size_t per_item = layout.per_item();
  const size_t stride = std::max<size_t>(per_item, (count + per_item - 1) / per_item * per_item);
  *stride_out = stride;
  require(stride <= UINT32_MAX && positions.size() / 3 <= UINT32_MAX, "the render is too large for one gather");
  std::vector<double> planes(3 * stride, 0.0);
  for (size_t i = 0; i < count; ++i)
    for (int a = 0; a < 3; ++a) planes[size_t(a) * stride + i] = points[3 * i + a];
  const BuiltProgram built = build_job_program(ctx, job, kGather, layout);
  DeviceBuffer sums(ctx, 3 * stride * sizeof(double), "the gathered sums");
  std::vector<double> out(3 * stride, 0.0);
  sums.write(ctx, 0, out.size() * sizeof(double), out.data());
  SliceRange slices;
  slices.progress = p.progress;
  slices.progress_user = p.progress_user;
  // What both kernels take alike, by the same names.
  auto bind_inputs = [&](auto& launch, auto args) {
    using Args = decltype(args);
    launch.upload(Args::exits, planes, "the exit points");
    launch.upload(Args::samples, positions, "the irradiance samples");
    launch.upload(Args::powers, powers, "the samples' powers");
    launch.upload(Args::channels, channels, table_size > 0 ? "the profile's table" : "the dipole's terms");
    launch.bind(Args::sums, &sums);
    launch.bind_value(Args::stride, static_cast<cl_uint>(stride));
    launch.bind_value(Args::table_size, static_cast<cl_uint>(table_size));
    launch.bind_value(Args::table_reach, table_reach);
  };
  if (!tree) {
    Launch<AllArg> launch(ctx, built.program);
    bind_inputs(launch, AllArg{});
    launch.bind_value(AllArg::sample_count, static_cast<cl_uint>(positions.size() / 3));
    // Units: lane groups of points, `groups` of them a work-item.
    slices.total = stride / layout.lanes;
    slices.first_units = double(layout.groups) * 16;
    *cancelled = launch.run_slices(slices, [&](uint64_t first, uint64_t end) {
      launch.bind_value(AllArg::first, static_cast<cl_uint>(first));
      launch.bind_value(AllArg::count, static_cast<cl_uint>(end - first));
      return size_t((end - first + layout.groups - 1) / layout.groups);
    }, &job.stats);
  } else {
    const Tree t = build_tree(&positions, &powers, areas);
    job.render.tree_nodes = t.nodes.size();
    DeviceBuffer visits(ctx, stride * sizeof(cl_uint), "the nodes visited");
    Launch<TreeArg> launch(ctx, built.program);
    bind_inputs(launch, TreeArg{});
    launch.upload(TreeArg::nodes, t.nodes, "the samples' BVH");
    launch.upload(TreeArg::clusters, t.clusters, "the BVH's clusters");
    launch.bind_value(TreeArg::max_solid_angle, p.max_solid_angle > 0     ? p.max_solid_angle
                                                : table_size > 0 ? kDefaultSolidAngleTable
                                                                 : kDefaultSolidAngleDipole);
    launch.bind(TreeArg::visits, &visits);
    slices.total = count;
    slices.first_units = 256;
    *cancelled = launch.run_slices(slices, [&](uint64_t first, uint64_t end) {
      launch.bind_value(TreeArg::first, static_cast<cl_uint>(first));
      launch.bind_value(TreeArg::count, static_cast<cl_uint>(end - first));
      return size_t(end - first);
    }, &job.stats);
    std::vector<cl_uint> v(stride, 0);
    visits.read(ctx, 0, v.size() * sizeof(cl_uint), v.data());
    double total = 0;
    for (size_t i = 0; i < count; ++i) total += v[i];
    job.render.mean_visits = count ? total / double(count) : 0;
  }
  sums.read(ctx, 0, out.size() * sizeof(double), out.data());
  return out;
}

}  // namespace

double phong_exponent(double b_deg) { return -std::log(2.0) / std::log(std::cos(b_deg * M_PI / 180)); }

std::unique_ptr<RenderJob> render(arcus_context_t* ctx, const geometry::Mesh& mesh, const ProfileSource& profile,
                                  const std::vector<arcus_directional_light>& lights,
                                  const arcus_translucency_render_params& p, bool* cancelled) {
  const auto start = std::chrono::steady_clock::now();
  check_params(p);
  const std::vector<Light> light_list = lights_of(lights);
  *cancelled = false;
  auto job = std::make_unique<RenderJob>(ctx);
  job->features = (profile.table ? ARCUS_FEATURE_TRANSLUCENCY_TABLE : ARCUS_FEATURE_TRANSLUCENCY_DIPOLE) |
                  (p.gather == ARCUS_GATHER_HIERARCHICAL ? ARCUS_FEATURE_TRANSLUCENCY_HIERARCHICAL : 0);
  const double eta = profile.eta();
  const Surface surface = make_surface(mesh, p.mm_per_unit);
  const double spacing = choose_spacing(surface, profile, p.profile_scale, p.sample_spacing_mm);
  const Samples samples = make_samples(surface, spacing);
  const scene::CameraDesc camera = camera_in_mm(p.camera, p.mm_per_unit);
  const bvh::DeviceBvh bvh(ctx, bvh::build_triangles(surface.mesh), false);
  std::vector<double> powers = sample_irradiance(ctx, bvh, surface, samples, light_list, eta);
  for (size_t s = 0; s < samples.size(); ++s)
    for (int c = 0; c < 3; ++c) powers[3 * s + c] *= samples.areas[s];
  const Views views = camera_hits(ctx, bvh, surface, camera, p.ortho_height * p.mm_per_unit);

  const size_t pixels = size_t(camera.width) * camera.height;
  std::vector<size_t> seen;
  std::vector<double> points;
  std::vector<uint32_t> seen_triangle;
  for (size_t px = 0; px < pixels; ++px)
    if (views.triangle[px] >= 0) {
      seen.push_back(px);
      seen_triangle.push_back(static_cast<uint32_t>(views.triangle[px]));
      points.insert(points.end(), &views.points[3 * px], &views.points[3 * px] + 3);
    }
  const std::vector<uint8_t> lit = visibility(ctx, bvh, surface, points, seen_triangle, light_list);
  job->render.irradiance_seconds = seconds_since(start);

  const auto gather_start = std::chrono::steady_clock::now();
  size_t stride = 0;
  const std::vector<double> sums =
      profile.table
          ? gather(ctx, *job, points, samples.positions, powers, samples.areas,
                   table_channels(*profile.table, p.profile_scale, p.profile_scaling), profile.table->count,
                   profile.table->reach_mm * p.profile_scale, p, &stride, cancelled)
          : gather(ctx, *job, points, samples.positions, powers, samples.areas,
                   channel_terms(*profile.dipole, p.profile_scale, p.profile_scaling), 0, 0, p, &stride, cancelled);
  job->render.gather_seconds = seconds_since(gather_start);

  // The exit term (1/π)F_t(η, ω_o), normalised when asked; the highlight.
  const double exit_scale = (1 / M_PI) / (p.exit == ARCUS_EXIT_NORMALIZED ? exit_transmittance(eta) : 1.0);
  const double exponent = p.highlight_deg > 0 ? phong_exponent(p.highlight_deg) : 0;
  job->rgb.assign(3 * pixels, 0.0f);
  job->subsurface.assign(3 * pixels, 0.0f);
  job->covered.assign(pixels, 0);
  for (size_t i = 0; i < seen.size(); ++i) {
    const size_t px = seen[i];
    const Vec3 n = vec3(&views.normals[3 * px]), v = vec3(&views.toward_eye[3 * px]);
    const double cos_o = std::fabs(dot(n, v));
    const double exit = exit_scale * (1 - arcus_fresnel_reflectance(cos_o, 1.0, eta));
    if (p.highlight_deg > 0)
      for (size_t l = 0; l < light_list.size(); ++l) {
        if (!lit[i * light_list.size() + l]) continue;
        const Vec3 to = light_list[l].toward;
        const double cos_i = std::max(0.0, dot(n, to));
        const Vec3 mirror = (2 * cos_i) * n - to;
        const double cos_a = std::max(0.0, dot(mirror, v));
        // Phong's normalised lobe (eq. 3.2) with the Fresnel reflectance as k_s.
        const double lobe = arcus_fresnel_reflectance(cos_i, 1.0, eta) * (exponent + 2) / (2 * M_PI) *
                    std::pow(cos_a, exponent) * cos_i;
        for (int c = 0; c < 3; ++c)
          job->rgb[3 * px + c] += static_cast<float>(lobe * light_list[l].irradiance[c]);
      }
    for (int c = 0; c < 3; ++c) {
      const double sub = exit * sums[size_t(c) * stride + i];
      job->subsurface[3 * px + c] = static_cast<float>(sub);
      job->rgb[3 * px + c] += static_cast<float>(sub);
    }
    job->covered[px] = 1;
  }
  job->count = pixels;
  job->render.width = camera.width;
  job->render.height = camera.height;
  job->render.samples = samples.size();
  job->render.sample_spacing_mm = spacing;
  job->render.surface_area_mm2 = surface.area;
  job->render.covered_pixels = seen.size();
  job->stats.total_seconds = seconds_since(start);
  return job;
}

}  // namespace arcus::translucency
