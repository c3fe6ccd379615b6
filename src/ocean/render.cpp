#include "ocean/render.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <string>

#include "bvh/bvh.h"
#include "core/buffer.h"
#include "core/context.h"
#include "core/error.h"
#include "core/features.h"
#include "core/launch.h"
#include "image/image_io.h"
#include "ocean/sky_light.h"
#include "photon/photon_map.h"
#include "scene/common_keys.h"  // the pinhole camera's checks, shared
#include "spectral/cie.h"
#include "spectral/srgb.h"

// Fresnel at the surface for the sun's beam: the scalar code the kernels share.
#include "common/real.h"
#include "common/fresnel.h"

namespace arcus::ocean {
namespace {

ARCUS_KERNEL_ARGS(RenderArg, "arcus_ocean_render", ARCUS_OCEAN_RENDER_ARGS);
ARCUS_KERNEL_ARGS(RadiiArg, "arcus_ocean_photon_radii", ARCUS_OCEAN_RADII_ARGS);

constexpr double kPi = 3.14159265358979323846;
// Rows of the light tables over distance: linear interpolation between rows 1/1023 of
// the longest distance apart errs by (h σ_t)²/8 relatively, < 1e-4 for σ_t < 2.4/m
// (water at 780 nm) over 30 m.
constexpr int kLightRows = 1024;
// Pixels per launch at most: the scratch holds two spectra per pixel (the transmittance,
// the per-step estimate's sums over its k photons).
constexpr int64_t kMaxSlicePixels = 16384;
// Photons whose radii one work-item finds, each search bounded by the last one's.
constexpr size_t kRadiiChunk = 16;
constexpr int kMaxBeamK = 65536;
// Photons a beam radius is estimated from (render.cl, arcus_ocean_photon_radii): at
// 400 000 photons and k = 250, 32 of them give 4 % more noise than all 250 (9.8 %
// against 9.4 % in sRGB) for 2.4 s of map time against 6.3 s; at 2 M photons and
// k = 1250, 64 gain nothing (4.49 % against 4.48 %).
constexpr int kRadiusK = 32;
// The trace's share of the progress bar.
constexpr double kTraceShare = 0.3;

double seconds_since(std::chrono::steady_clock::time_point t0) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
}

std::string number(double x) {
  char b[32];
  std::snprintf(b, sizeof b, "%g", x);
  return b;
}

// The sun's beam below the flat surface: its direction in the water (Snell: the
// tangential part shrinks by 1/n) and what of its plane irradiance crosses the surface
// per unit area normal to that direction, T/μ_w (μ_w: the beam's cosine to the
// vertical in the water).
struct Refracted {
  double direction[3];
  double per_normal_area;
};

Refracted refracted_sun(const Light& L, double n_water) {
  const double l = std::hypot(L.direction[0], L.direction[1], L.direction[2]);
  const double k[3] = {L.direction[0] / l, L.direction[1] / l, L.direction[2] / l};
  Refracted r;
  r.direction[0] = k[0] / n_water;
  r.direction[1] = k[1] / n_water;
  const double mu_w = std::sqrt(std::max(0.0, 1 - r.direction[0] * r.direction[0] - r.direction[1] * r.direction[1]));
  r.direction[2] = -mu_w;
  r.per_normal_area = (1 - arcus_fresnel_reflectance(-k[2], 1.0, n_water)) / mu_w;
  return r;
}

// What a light sends toward the water at nm, per unit of the light tables' distance
// law: a point light's radiant intensity [W/sr/nm] (spots over their cone's solid
// angle), the sun's irradiance normal to its beam just below the surface [W/m²/nm]
// (its spectrum is the plane irradiance on the surface).
double intensity(const Light& L, const Medium& medium, double nm) {
  if (L.kind == Light::directional) return light_spectrum(L, nm) * refracted_sun(L, medium.n_water).per_normal_area;
  const double solid_angle =
      L.kind == Light::spot ? 2 * kPi * (1 - std::cos(L.half_angle_deg * kPi / 180)) : 4 * kPi;
  return light_spectrum(L, nm) / solid_angle;
}

// Progress of one stage mapped onto [offset, offset + share] of the caller's bar.
struct StageProgress {
  arcus_progress_callback outer;
  void* user;
  double offset, share;
  static int32_t call(void* self, double fraction) {
    auto* s = static_cast<StageProgress*>(self);
    return s->outer ? s->outer(s->user, s->offset + s->share * fraction) : 0;
  }
};

const KernelSource& render_source() {
  static const KernelSource source{"ocean/render",
                                   [] {
                                     std::vector<const char*> files = photon::device_headers();
                                     files.push_back("common/fresnel.h");  // the surface's reflection
                                     files.push_back("common/philox.h");   // step subsampling's jitter
                                     files.push_back("ocean/ocean_desc.h");
                                     files.push_back("ocean/render.cl");
                                     return files;
                                   }(),
                                   ""};
  return source;
}

bool inelastic(const WaterTables& w) {
  for (int e : {kRaman, kFluorescePhyto, kFluoresceCdom})
    for (double c : w.event[e])
      if (c > 0) return true;
  return false;
}

// M[m][i]: radiance per metre and per unit intensity at λ_m from excitation λ_i
// (photons re-emitted at rate μ_j(λ_i), density h_j(λ_m | λ_i) per nm, energy λ_i/λ_m
// each, isotropically: 1/4π); empty when the water re-emits nothing.
std::vector<double> inelastic_redistribution(const WaterTables& w, double band) {
  if (!inelastic(w)) return {};
  const size_t n = w.grid.count;
  std::vector<double> M(n * n, 0.0);
  const int events[kProcessCount] = {kRaman, kFluorescePhyto, kFluoresceCdom};
  for (int p = 0; p < kProcessCount; ++p) {
    const auto& h = w.emission[p];
    if (h.size() != n * n) continue;
    for (size_t i = 0; i < n; ++i) {
      const double mu = w.event[events[p]][i];
      if (mu <= 0) continue;
      for (size_t m = 0; m < n; ++m)
        M[m * n + i] += mu * h[i * n + m] * (w.grid.nm(int(i)) / w.grid.nm(int(m))) * band / (4 * kPi);
    }
  }
  return M;
}

// The kernel's light tables (kernels/ocean/ocean_desc.h): per light, kLightRows rows
// of the intensity reaching distance d per sample (the sun's: its beam's irradiance
// after a slant path d below the surface), then as many of the inelastic in-scattering
// G of eq. 4.5 (its redistribution M folded in once, here).
std::vector<double> light_tables(const WaterTables& w, const std::vector<Light>& lights, const Medium& medium,
                                 const std::vector<double>& st, const std::vector<double>& M, double g_step) {
  const size_t n = w.grid.count;
  const bool any_inelastic = !M.empty();
  std::vector<double> out(lights.size() * 2 * kLightRows * n, 0.0);
  std::vector<double> reach(n);
  for (size_t l = 0; l < lights.size(); ++l)
    for (int g = 0; g < kLightRows && lights[l].kind != Light::sky; ++g) {  // a sky: sky_tables
      const double d = g * g_step;
      for (size_t m = 0; m < n; ++m)
        reach[m] = intensity(lights[l], medium, w.grid.nm(int(m))) * std::exp(-st[m] * d);
      double* E = &out[((l * 2 * kLightRows) + g) * n];
      std::copy(reach.begin(), reach.end(), E);
      if (!any_inelastic) continue;
      double* G = E + kLightRows * n;
      for (size_t m = 0; m < n; ++m) {
        double sum = 0;
        for (size_t i = 0; i < n; ++i) sum += M[m * n + i] * reach[i];
        G[m] = sum;
      }
    }
  return out;
}

// The stored photons as the map's photons: the event, then the powers and grid samples
// of the wavelengths each carries (kernels/ocean/ocean_desc.h).
photon::Photons map_photons(const StoredPhotons& s, const Grid& grid) {
  photon::Photons p;
  p.channels = ARCUS_OCEAN_MAP_CHANNELS;
  p.positions = s.positions;
  p.directions = s.directions;
  p.powers.reserve(s.size() * ARCUS_OCEAN_MAP_CHANNELS);
  for (size_t i = 0; i < s.size(); ++i) {
    p.powers.push_back(double(s.events[i]));
    const double* power = &s.powers[i * ARCUS_OCEAN_MAX_HEROES];
    const double* nm = &s.wavelengths[i * ARCUS_OCEAN_MAX_HEROES];
    p.powers.insert(p.powers.end(), power, power + ARCUS_OCEAN_MAX_HEROES);
    for (int j = 0; j < ARCUS_OCEAN_MAX_HEROES; ++j) {
      const double k = grid.count == 1 ? 0 : std::round((nm[j] - grid.first_nm) / grid.step_nm);
      p.powers.push_back(power[j] > 0 ? std::clamp(k, 0.0, double(grid.count - 1)) : 0.0);
    }
  }
  return p;
}

// Adds an image sampled at every stride-th pixel (the centres of stride × stride
// blocks, cw × ch of them, n reals each) to the fine image (w × h), bilinearly between
// those centres and held at the edges.
void add_bilinear(const std::vector<double>& coarse, int cw, int ch, int stride, size_t n, int w, int h,
                  std::vector<double>* fine) {
  auto axis = [stride](int p, int samples, int* i0, int* i1, double* t) {
    const double x = std::clamp((p + 0.5) / stride - 0.5, 0.0, double(samples - 1));
    *i0 = std::min(int(x), std::max(samples - 2, 0));
    *i1 = std::min(*i0 + 1, samples - 1);
    *t = x - *i0;
  };
  for (int py = 0; py < h; ++py) {
    int y0, y1;
    double ty;
    axis(py, ch, &y0, &y1, &ty);
    for (int px = 0; px < w; ++px) {
      int x0, x1;
      double tx;
      axis(px, cw, &x0, &x1, &tx);
      const double* a = &coarse[(size_t(y0) * cw + x0) * n];
      const double* b = &coarse[(size_t(y0) * cw + x1) * n];
      const double* c = &coarse[(size_t(y1) * cw + x0) * n];
      const double* e = &coarse[(size_t(y1) * cw + x1) * n];
      double* out = &(*fine)[(size_t(py) * w + px) * n];
      for (size_t m = 0; m < n; ++m)
        out[m] += (1 - ty) * ((1 - tx) * a[m] + tx * b[m]) + ty * ((1 - tx) * c[m] + tx * e[m]);
    }
  }
}

}  // namespace

void check_march(const MarchParams& m) {
  require(m.steps >= 1 && m.steps <= 1000000, "march.steps: must be in 1..1000000, got " + std::to_string(m.steps));
  require(std::isfinite(m.distance) && m.distance > 0, "march.distance: must be finite and > 0, got " + number(m.distance));
  require(m.estimator == MarchParams::per_step || m.estimator == MarchParams::beam,
          "march.estimator: unknown estimator " + std::to_string(int(m.estimator)));
  // The per-step estimate gathers k photons; the beam's radii come from at most
  // kRadiusK of them, k only scales them.
  const int k_max = m.estimator == MarchParams::per_step ? ARCUS_PHOTON_MAX_K : kMaxBeamK;
  require(m.k >= 1 && m.k <= k_max, "march.k: must be in 1.." + std::to_string(k_max) + " (" +
                                        (m.estimator == MarchParams::per_step ? "per-step" : "beam") +
                                        " estimate), got " + std::to_string(m.k));
  require(std::isfinite(m.exposure) && m.exposure > 0, "march.exposure: must be finite and > 0, got " + number(m.exposure));
  require(m.estimate_stride >= 1 && m.estimate_stride <= 64,
          "march.estimate_stride: must be in 1..64, got " + std::to_string(m.estimate_stride));
  require(std::isfinite(m.photon_tile) && m.photon_tile >= 0,
          "march.photon_tile: must be finite and >= 0, got " + number(m.photon_tile));
  // The per-step estimate's k nearest would miss the photons across the tile's edges.
  require(m.photon_tile == 0 || m.estimator == MarchParams::beam,
          "march.photon_tile: folds photons for the beam estimate only (march.estimator)");
  require(m.step_subsample >= 1 && m.step_subsample <= m.steps,
          "march.step_subsample: must be in 1..march.steps (" + std::to_string(m.steps) + "), got " +
              std::to_string(m.step_subsample));
  require(m.step_subsample == 1 || m.estimator == MarchParams::per_step,
          "march.step_subsample: subsamples the per-step estimate only (march.estimator)");
}

arcus_features render_features(const WaterTables& water, const MarchParams& march) {
  arcus_features f = 0;
  if (march.single_scattering && inelastic(water)) f |= ARCUS_FEATURE_OCEAN_INELASTIC;
  if (march.multiple_scattering) f |= ARCUS_FEATURE_OCEAN_PHOTON_MAP;
  if (march.multiple_scattering && march.estimator == MarchParams::beam) f |= ARCUS_FEATURE_OCEAN_BEAM;
  return f;
}

std::unique_ptr<RenderJob> render(arcus_context_t* ctx, const WaterTables& w, const std::vector<Light>& lights,
                                  const Medium& medium, const TraceParams& trace_params, const arcus_camera& camera,
                                  const MarchParams& march, arcus_progress_callback progress, void* user,
                                  bool* cancelled) {
  const auto t0 = std::chrono::steady_clock::now();
  scene::check_camera(scene::camera_desc(camera), "camera");
  check_march(march);
  check_trace(lights, medium, trace_params);
  for (size_t l = 0; l < lights.size(); ++l) {
    const Light::Kind kind = lights[l].kind;
    require(kind == Light::point || kind == Light::spot ||
                ((kind == Light::directional || kind == Light::sky) && medium.surface),
            "lights[" + std::to_string(l) + "]: images are lit by point and spot lights in the water and by the sun "
            "and the sky above a surface (medium.surface)");
  }
  if (medium.surface)
    require(camera.position[2] < 0, "camera.position: must be in the water, below the surface (z < 0)");
  if (march.photon_tile > 0) {  // the same at every horizontal place, or the tile would not stand for it
    bool plane = medium.surface;
    for (const Light& L : lights) plane = plane && (L.kind == Light::directional || L.kind == Light::sky);
    for (int a = 0; a < 2; ++a) plane = plane && !std::isfinite(medium.box_lo[a]) && !std::isfinite(medium.box_hi[a]);
    require(plane, "march.photon_tile: needs a scene the same at every horizontal place: a surface, lit by the sun "
                   "and the sky alone, no walls");
  }
  const Grid& grid = w.grid;
  const size_t n = grid.count;
  auto job = std::make_unique<RenderJob>(ctx);
  job->width = camera.width;
  job->height = camera.height;
  job->exposure = march.exposure;
  for (int k = 0; k < grid.count; ++k) job->wavelengths.push_back(grid.nm(k));
  *cancelled = false;

  // ---- photons (multiple scattering only)
  photon::PhotonMap* map = nullptr;
  std::unique_ptr<photon::PhotonMap> map_owner;
  arcus_features trace_bits = 0;
  if (march.multiple_scattering) {
    TraceParams tp = trace_params;
    tp.store = true;
    tp.depths.clear();
    tp.tile = march.photon_tile;
    tp.tile_center[0] = camera.position[0];
    tp.tile_center[1] = camera.position[1];
    StageProgress stage{progress, user, 0, kTraceShare};
    trace_into(job.get(), ctx, w, lights, medium, tp, progress ? &StageProgress::call : nullptr, &stage, cancelled);
    trace_bits = job->features;
    job->render_stats.trace_seconds = job->trace_seconds;
    job->render_stats.photons_stored = job->photons.size();
    if (*cancelled) return job;
    const auto tm = std::chrono::steady_clock::now();
    // The per-step estimate gathers every photon about a stretch of each ray: the
    // largest leaves mean the fewest nodes to visit (at the thesis' settings, 128×96,
    // 32 against 16: 8.9 s against 9.3 s; 8: 9.8 s; 4: 11.0 s).
    const int min_leaf = march.estimator == MarchParams::per_step ? 32 : 1;
    map_owner = std::make_unique<photon::PhotonMap>(ctx, map_photons(job->photons, grid), min_leaf);
    map = map_owner.get();
    job->render_stats.map_seconds = seconds_since(tm);
  }
  job->features = trace_bits | render_features(w, march);

  // ---- optics and light tables
  const double band = grid.count == 1 ? 1.0 : grid.step_nm;
  const double dt = march.distance / march.steps;
  std::vector<double> st(n, 0.0);
  for (int e = 0; e < kEventCount; ++e)
    for (size_t m = 0; m < n; ++m) st[m] += w.event[e][m];
  std::vector<double> optics(6 * n);
  for (size_t m = 0; m < n; ++m) {
    optics[m] = st[m];
    optics[n + m] = std::exp(-st[m] * dt);
    optics[2 * n + m] = std::exp(-st[m] * dt / 2);
    for (int s = 0; s < kScattererCount; ++s) optics[(3 + s) * n + m] = w.event[kScatterWater + s][m];
  }
  arcus_ocean_render_desc d{};
  append_phases(w, &optics, &d.phases);
  double d_max = 0;
  for (const Light& L : lights)
    if (L.kind == Light::directional)  // the slant path down to the deepest march point
      d_max = std::max(d_max, (-camera.position[2] + march.distance) /
                                  -refracted_sun(L, medium.n_water).direction[2]);
    else
      d_max = std::max(d_max, std::hypot(L.position[0] - camera.position[0], L.position[1] - camera.position[1],
                                         L.position[2] - camera.position[2]) +
                                  march.distance);
  const double g_step = d_max / (kLightRows - 1);
  const std::vector<double> M = inelastic_redistribution(w, band);
  const std::vector<double> tables = light_tables(w, lights, medium, st, M, g_step);
  const SkyTables sky = sky_tables(w, lights, medium, st, M, -camera.position[2] + march.distance);
  std::vector<double> light_buf;
  for (const Light& L : lights) {
    double axis[3] = {L.direction[0], L.direction[1], L.direction[2]};
    const double norm = std::hypot(axis[0], axis[1], axis[2]);
    for (double& a : axis) a = norm > 0 ? a / norm : 0;
    if (L.kind == Light::directional) {  // the kernel takes the beam as it runs in the water
      const Refracted r = refracted_sun(L, medium.n_water);
      std::copy(r.direction, r.direction + 3, axis);
    }
    const double rec[ARCUS_OCEAN_LIGHT_REALS] = {double(L.kind), L.position[0], L.position[1], L.position[2], axis[0],
                                                 axis[1], axis[2], std::cos(L.half_angle_deg * kPi / 180), 0, 0};
    light_buf.insert(light_buf.end(), rec, rec + ARCUS_OCEAN_LIGHT_REALS);
  }

  // ---- the camera
  double f[3], r[3], u[3];
  for (int a = 0; a < 3; ++a) f[a] = camera.look_at[a] - camera.position[a];
  const double fl = std::hypot(f[0], f[1], f[2]);
  for (double& x : f) x /= fl;
  r[0] = f[1] * camera.up[2] - f[2] * camera.up[1];
  r[1] = f[2] * camera.up[0] - f[0] * camera.up[2];
  r[2] = f[0] * camera.up[1] - f[1] * camera.up[0];
  const double rl = std::hypot(r[0], r[1], r[2]);
  for (double& x : r) x /= rl;
  u[0] = r[1] * f[2] - r[2] * f[1];
  u[1] = r[2] * f[0] - r[0] * f[2];
  u[2] = r[0] * f[1] - r[1] * f[0];
  const double half_h = std::tan(camera.vfov_deg * kPi / 360), half_w = half_h * camera.width / camera.height;
  for (int a = 0; a < 3; ++a) {
    d.eye[a] = camera.position[a];
    d.forward[a] = f[a];
    d.right[a] = r[a] * half_w;
    d.up[a] = u[a] * half_h;
  }
  d.step = dt;
  d.band = band;
  d.g_step = g_step;
  d.width = static_cast<int32_t>(camera.width);
  d.height = static_cast<int32_t>(camera.height);
  d.count = static_cast<int32_t>(n);
  d.steps = march.steps;
  d.k = march.k;
  d.light_count = static_cast<int32_t>(lights.size());
  d.g_samples = kLightRows;
  d.single = march.single_scattering;
  d.multiple = march.multiple_scattering;
  d.surface = medium.surface;
  d.stride = 1;
  d.sky_rows = sky.rows;
  d.sky_cosines = sky.cosines;
  d.sky_d_step = sky.d_step;
  d.n_water = medium.n_water;
  d.tile = march.photon_tile;
  d.tile_x = camera.position[0];
  d.tile_y = camera.position[1];
  d.subsample = march.step_subsample;
  d.seed = static_cast<int32_t>(trace_params.seed & 0x7fffffff);
  d.image_width = d.width;
  d.image_height = d.height;

  const Layout layout{1, 1};  // scalar: a pixel per work-item (render.cl)
  const BuiltProgram built = ctx->runtime->program(render_source(), render_features(w, march), layout);
  job->stats.build_seconds += built.seconds;
  const size_t pixels = size_t(camera.width) * camera.height;
  Launch<RenderArg> launch(ctx, built.program);
  launch.upload(RenderArg::optics, optics, "the water's optics");
  launch.upload(RenderArg::lights, light_buf, "the lights");
  launch.upload(RenderArg::light_tables, tables, "the light tables");
  launch.upload(RenderArg::sky, sky.data.empty() ? std::vector<double>{0} : sky.data, "the sky's tables");
  DeviceBuffer radiance_dev(ctx, pixels * n * sizeof(double), "the spectral image");
  DeviceBuffer scratch_dev(ctx, std::min<size_t>(pixels, kMaxSlicePixels) * 2 * n * sizeof(double),
                           "the transmittances and k-set sums");

  // The map's view for the kernel: the k-nearest map itself, or (beam) the photons
  // re-ordered under a BVH of their spheres, with their radii.
  std::unique_ptr<DeviceBuffer> beam_nodes, beam_photons, radii_dev;
  arcus_photon_map_desc map_desc{0, ARCUS_OCEAN_MAP_CHANNELS};
  const DeviceBuffer *nodes_arg = nullptr, *photons_arg = nullptr;
  if (map) {
    map_desc = map->desc();
    nodes_arg = map->nodes();
    photons_arg = map->photons();
  }
  if (map && march.estimator == MarchParams::beam && map->size() > 0) {
    const auto tb = std::chrono::steady_clock::now();
    const size_t count = map->size();
    DeviceBuffer radii(ctx, count * sizeof(double), "the photons' radii");
    Launch<RadiiArg> rk(ctx, built.program);
    rk.bind(RadiiArg::nodes, map->nodes());
    rk.bind(RadiiArg::photons, map->photons());
    rk.bind_value(RadiiArg::map, map->desc());
    rk.bind_value(RadiiArg::k, int32_t(march.k));
    rk.bind_value(RadiiArg::kr, int32_t(std::min(march.k, kRadiusK)));
    rk.bind_value(RadiiArg::chunk, int32_t(kRadiiChunk));
    rk.bind(RadiiArg::radii, &radii);
    rk.run((count + kRadiiChunk - 1) / kRadiiChunk);
    std::vector<double> r_slot(count);
    radii.read(ctx, 0, count * sizeof(double), r_slot.data());
    // Folded into a tile, a photon's sphere may reach no further than the neighbouring
    // cells' copies (render.cl, ocean_beam_leg); any radius gives a consistent estimate.
    if (march.photon_tile > 0)
      for (double& r : r_slot) r = std::min(r, march.photon_tile / 2);
    d.r_max = *std::max_element(r_slot.begin(), r_slot.end());
    // The map's photons (slot order, structure of arrays) read back once.
    const size_t comps = ARCUS_PHOTON_POWER + ARCUS_OCEAN_MAP_CHANNELS;
    std::vector<double> soa(comps * count);
    map->photons()->read(ctx, 0, soa.size() * sizeof(double), soa.data());
    std::vector<bvh::Bounds> spheres(count);
    for (size_t q = 0; q < count; ++q)
      for (int a = 0; a < 3; ++a) {
        spheres[q].lo[a] = soa[a * count + q] - r_slot[q];
        spheres[q].hi[a] = soa[a * count + q] + r_slot[q];
      }
    const bvh::Flat tree = bvh::build(spheres);
    std::vector<double> ordered(comps * count), r_ordered(count);
    for (size_t s = 0; s < count; ++s) {
      const size_t q = tree.order[s];
      for (size_t c = 0; c < comps; ++c) ordered[c * count + s] = soa[c * count + q];
      r_ordered[s] = r_slot[q];
    }
    beam_nodes = std::make_unique<DeviceBuffer>(ctx, tree.nodes.size() * sizeof(arcus_bvh_node_d), "the photon spheres' BVH",
                                                tree.nodes.data());
    beam_photons = std::make_unique<DeviceBuffer>(ctx, ordered.size() * sizeof(double), "the beam's photons", ordered.data());
    radii_dev = std::make_unique<DeviceBuffer>(ctx, count * sizeof(double), "the beam's radii", r_ordered.data());
    nodes_arg = beam_nodes.get();
    photons_arg = beam_photons.get();
    job->render_stats.map_seconds += seconds_since(tb);
  }

  const auto te = std::chrono::steady_clock::now();
  launch.bind(RenderArg::nodes, nodes_arg);
  launch.bind(RenderArg::photons, photons_arg);
  launch.bind_value(RenderArg::map, map_desc);
  launch.bind(RenderArg::radii, radii_dev.get());
  launch.bind(RenderArg::scratch, &scratch_dev);
  // One pass over a pixel grid: its pixels in slices of at most the transmittances'
  // rows, into `out`; progress over `share` of what is left after the trace.
  auto pass = [&](const arcus_ocean_render_desc& desc, DeviceBuffer* out, double from, double share) {
    launch.bind(RenderArg::radiance, out);
    const double traced = march.multiple_scattering ? kTraceShare : 0.0;
    StageProgress stage{progress, user, traced + (1 - traced) * from, (1 - traced) * share};
    SliceRange slices{uint64_t(desc.width) * desc.height, 64, kMaxSlicePixels};
    slices.progress = progress ? &StageProgress::call : nullptr;
    slices.progress_user = &stage;
    arcus_job_stats run{};
    arcus_ocean_render_desc sliced = desc;
    const bool stopped = launch.run_slices(slices, [&](uint64_t first, uint64_t end) {
      sliced.first_pixel = static_cast<int32_t>(first);
      sliced.end_pixel = static_cast<int32_t>(end);
      launch.bind_value(RenderArg::rd, sliced);
      return size_t(end - first);
    }, &run);
    job->stats.kernel_seconds += run.kernel_seconds;
    job->stats.launches += run.launches;
    return stopped;
  };
  const int stride = map ? march.estimate_stride : 1;
  if (stride == 1) {
    *cancelled = pass(d, &radiance_dev, 0, 1);
  } else {
    // The lights' single scattering at every pixel, the photon estimate at every
    // stride-th, added bilinearly (render.h, MarchParams::estimate_stride).
    arcus_ocean_render_desc lights_only = d, photons_only = d;
    lights_only.multiple = 0;
    photons_only.single = 0;
    photons_only.stride = stride;
    photons_only.width = (d.width + stride - 1) / stride;
    photons_only.height = (d.height + stride - 1) / stride;
    const size_t coarse = size_t(photons_only.width) * photons_only.height;
    DeviceBuffer coarse_dev(ctx, coarse * n * sizeof(double), "the photon estimate's pixels");
    const double lights_share = march.single_scattering ? 0.2 : 0.0;
    *cancelled = (march.single_scattering && pass(lights_only, &radiance_dev, 0, lights_share)) ||
                 pass(photons_only, &coarse_dev, lights_share, 1 - lights_share);
    if (!*cancelled) {
      std::vector<double> fine(pixels * n, 0.0), sparse(coarse * n);
      if (march.single_scattering) radiance_dev.read(ctx, 0, fine.size() * sizeof(double), fine.data());
      coarse_dev.read(ctx, 0, sparse.size() * sizeof(double), sparse.data());
      add_bilinear(sparse, photons_only.width, photons_only.height, stride, n, d.width, d.height, &fine);
      radiance_dev.write(ctx, 0, fine.size() * sizeof(double), fine.data());
    }
  }
  job->render_stats.estimate_seconds += seconds_since(te);

  // ---- spectra to colour
  job->spectral.resize(pixels * n);
  radiance_dev.read(ctx, 0, job->spectral.size() * sizeof(double), job->spectral.data());
  const auto weights = spectral::band_weights(job->wavelengths);
  job->rgb.resize(pixels * 3);
  for (size_t p = 0; p < pixels; ++p) {
    std::array<double, 3> xyz{0, 0, 0};
    for (size_t m = 0; m < n; ++m)
      for (int c = 0; c < 3; ++c) xyz[c] += job->spectral[p * n + m] * weights[m][c];
    const auto rgb = spectral::xyz_to_linear_srgb(xyz);
    for (int c = 0; c < 3; ++c) job->rgb[3 * p + c] = static_cast<float>(rgb[c]);
  }
  image::require_finite_pixels(job->rgb, static_cast<int>(camera.width), "RGB", "the ocean render");
  job->render_stats.total_seconds = seconds_since(t0);
  job->stats.total_seconds = job->render_stats.total_seconds;
  return job;
}

}  // namespace arcus::ocean
