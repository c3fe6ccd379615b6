#include "ocean/trace.h"

#include <algorithm>
#include <cmath>
#include <numeric>
#include <string>

#include "bvh/bvh.h"
#include "core/buffer.h"
#include "core/context.h"
#include "core/error.h"
#include "core/features.h"
#include "core/launch.h"
#include "ocean/ocean_desc.h"  // kernels/ocean/ocean_desc.h: shared with the kernel

namespace arcus::ocean {
namespace {

static_assert(sizeof(arcus_ocean_desc) % 8 == 0, "ocean_desc must pack alike on host and device");
ARCUS_KERNEL_ARGS(TraceArg, "arcus_ocean_trace", ARCUS_OCEAN_TRACE_ARGS);

constexpr double kPi = 3.14159265358979323846;
// Photons per work-item in the first slice (slices then size themselves).
constexpr double kFirstSlicePhotons = 200;

std::string number(double x) {
  char b[32];
  std::snprintf(b, sizeof b, "%g", x);
  return b;
}

bool finite3(const double* v) { return std::isfinite(v[0]) && std::isfinite(v[1]) && std::isfinite(v[2]); }

// Each light's power in each grid band [W]: its spectrum at the sample times the band
// (step_nm; the whole spectrum's value for a one-sample grid) times, for directional
// and sky light, the area it falls on (the beam's disc, the lit disc of the surface or
// the periodic tile; without either 1 m² of surface).
std::vector<double> band_powers(const std::vector<Light>& lights, const Grid& grid, double tile) {
  std::vector<double> w(lights.size() * grid.count);
  const double band = grid.count == 1 ? 1.0 : grid.step_nm;
  for (size_t l = 0; l < lights.size(); ++l) {
    const Light& L = lights[l];
    double area = 1;
    const bool plane = L.kind == Light::directional || L.kind == Light::sky;
    if (plane && tile > 0) area = tile * tile;
    else if (plane && L.radius > 0) area = kPi * L.radius * L.radius;
    for (int k = 0; k < grid.count; ++k) w[l * grid.count + k] = light_spectrum(L, grid.nm(k)) * band * area;
  }
  return w;
}

bool has_inelastic(const WaterTables& w) {
  for (int e : {kRaman, kFluorescePhyto, kFluoresceCdom})
    for (double c : w.event[e])
      if (c > 0) return true;
  return false;
}

bool bounded(const Medium& m) {
  bool b = m.surface || std::isfinite(m.bottom_depth);
  for (int a = 0; a < 3; ++a) b = b || std::isfinite(m.box_lo[a]) || std::isfinite(m.box_hi[a]);
  return b;
}

}  // namespace

void append_phases(const WaterTables& w, std::vector<double>* out, arcus_ocean_phases* p) {
  std::vector<double>& buf = *out;
  for (int s = 0; s < kScattererCount; ++s) {
    const Phase& ph = w.phase[s];
    p->kind[s] = ph.kind;
    p->a[s] = ph.a;
    p->gf[s] = ph.g_forward;
    p->gb[s] = ph.g_backward;
    p->zeta[s] = ph.forward_weight;
    p->offset[s] = p->count[s] = 0;
    if (ph.kind != Phase::table) continue;
    // cosines, the density normalised over the sphere's cosines (∫ p dμ = 1 with
    // linear interpolation), its cumulative integral
    const size_t m = ph.cosines.size();
    std::vector<double> pdf(ph.values), cdf(m, 0.0);
    for (size_t j = 1; j < m; ++j)
      cdf[j] = cdf[j - 1] + 0.5 * (pdf[j - 1] + pdf[j]) * (ph.cosines[j] - ph.cosines[j - 1]);
    const double total = cdf.back();
    for (size_t j = 0; j < m; ++j) {
      pdf[j] /= total;
      cdf[j] /= total;
    }
    cdf.back() = 1;
    p->offset[s] = static_cast<int32_t>(buf.size());
    p->count[s] = static_cast<int32_t>(m);
    buf.insert(buf.end(), ph.cosines.begin(), ph.cosines.end());
    buf.insert(buf.end(), pdf.begin(), pdf.end());
    buf.insert(buf.end(), cdf.begin(), cdf.end());
  }
}

std::vector<double> water_buffer(const WaterTables& w, bool inelastic, arcus_ocean_desc* d) {
  const size_t n = w.grid.count;
  std::vector<double> buf;
  d->events = 0;
  for (int e = 0; e < kEventCount; ++e) {
    // An event absent at every sample costs the roulette nothing: it is left out.
    if (std::none_of(w.event[e].begin(), w.event[e].end(), [](double c) { return c > 0; })) continue;
    if (!inelastic && (e == kRaman || e == kFluorescePhyto || e == kFluoresceCdom)) continue;
    d->event_ids[d->events++] = e;
    buf.insert(buf.end(), w.event[e].begin(), w.event[e].end());
  }
  d->emission_offset = static_cast<int32_t>(buf.size());
  if (inelastic)
    for (int p = 0; p < kProcessCount; ++p) {
      const auto& pdf = w.emission[p];
      const auto& cdf = w.cdf[p];
      if (pdf.size() == n * n && cdf.size() == n * n) {
        buf.insert(buf.end(), pdf.begin(), pdf.end());
        buf.insert(buf.end(), cdf.begin(), cdf.end());
      } else {
        buf.insert(buf.end(), 2 * n * n, 0.0);
      }
    }
  append_phases(w, &buf, &d->phases);
  if (buf.empty()) buf.push_back(0);  // OpenCL buffers are never empty
  return buf;
}

namespace {

void normalise(double* v) {
  const double n = std::sqrt(v[0] * v[0] + v[1] * v[1] + v[2] * v[2]);
  for (int a = 0; a < 3; ++a) v[a] /= n;
}

// Work-items (= tally rows): a fixed count per device kind, never the layout, so a
// result is the same whatever ARCUS_LANES/ARCUS_GROUPS say.
int32_t tally_rows(const arcus_context_t* ctx, uint64_t photons) {
  const int64_t want = ctx->info.is_gpu ? 8192 : 256;
  return static_cast<int32_t>(std::max<int64_t>(1, std::min<int64_t>(want, static_cast<int64_t>(photons))));
}

}  // namespace

double light_spectrum(const Light& light, double nm) {
  const Spectrum& s = light.spectrum;
  if (s.nm.size() == 1) return s.values[0];
  if (nm < s.nm.front() || nm > s.nm.back()) return 0;
  const size_t j = std::min<size_t>(std::upper_bound(s.nm.begin(), s.nm.end(), nm) - s.nm.begin(), s.nm.size() - 1);
  const double t = (nm - s.nm[j - 1]) / (s.nm[j] - s.nm[j - 1]);
  return s.values[j - 1] + t * (s.values[j] - s.values[j - 1]);
}

double Tallies::escaped() const {
  return std::accumulate(escaped_by_interaction.begin(), escaped_by_interaction.end(), 0.0);
}

double Tallies::absorbed_total() const {
  return std::accumulate(absorbed_by_interaction.begin(), absorbed_by_interaction.end(), 0.0);
}

void check_light(const Light& L, size_t index) {
  const std::string w = "lights[" + std::to_string(index) + "]";
  require(L.kind >= Light::point && L.kind <= Light::sky, w + ".kind: unknown light kind " + std::to_string(L.kind));
  require(finite3(L.position), w + ".position: must be finite");
  // The photons it sends are gathered under a BVH (bvh.h): their positions must be
  // representable, and a light's are where they start.
  require(bvh::representable(L.position), w + ".position: lies beyond the " + number(bvh::kMaxCoordinate) +
                                              " m from the origin that the photon map can represent");
  require(finite3(L.direction), w + ".direction: must be finite");
  require(std::hypot(L.direction[0], L.direction[1], L.direction[2]) > 0 || L.kind == Light::point ||
              L.kind == Light::sky,
          w + ".direction: must not be zero");
  require(std::isfinite(L.half_angle_deg) && L.half_angle_deg > 0 && L.half_angle_deg <= 180,
          w + ".half_angle_deg: must be in (0, 180], got " + number(L.half_angle_deg));
  require(std::isfinite(L.radius) && L.radius >= 0, w + ".radius: must be finite and >= 0, got " + number(L.radius));
  const Spectrum& s = L.spectrum;
  require(!s.nm.empty() && s.nm.size() == s.values.size(),
          w + ".spectrum: needs as many wavelengths as values, and at least one");
  for (size_t j = 0; j < s.nm.size(); ++j) {
    require(std::isfinite(s.nm[j]) && (j == 0 || s.nm[j] > s.nm[j - 1]),
            w + ".spectrum.nm: must be finite and strictly increasing");
    require(std::isfinite(s.values[j]) && s.values[j] >= 0,
            w + ".spectrum.values[" + std::to_string(j) + "]: must be finite and >= 0, got " + number(s.values[j]));
  }
}

void check_trace(const std::vector<Light>& lights, const Medium& m, const TraceParams& p) {
  require(!lights.empty(), "lights: a trace needs at least one light");
  for (size_t l = 0; l < lights.size(); ++l) {
    check_light(lights[l], l);
    const Light& L = lights[l];
    const std::string w = "lights[" + std::to_string(l) + "]";
    if (L.kind == Light::sky) require(m.surface, w + ": a sky light needs the surface (setup.surface = 1)");
    if (m.surface && (L.kind == Light::directional || L.kind == Light::sky)) {
      if (L.kind == Light::directional)
        require(L.direction[2] < 0, w + ".direction: light from above the surface must point down (z < 0)");
    } else {
      if (m.surface) require(L.position[2] <= 0, w + ".position: must be in the water (z <= 0)");
      for (int a = 0; a < 3; ++a)
        require(L.position[a] >= m.box_lo[a] && L.position[a] <= m.box_hi[a], w + ".position: outside the box");
      if (std::isfinite(m.bottom_depth))
        require(L.position[2] >= -m.bottom_depth, w + ".position: below the bottom");
    }
  }
  require(std::isfinite(m.n_water) && m.n_water >= 1 && m.n_water <= 3,
          "setup.n_water: must be in [1, 3], got " + number(m.n_water));
  require(!std::isnan(m.bottom_depth) && m.bottom_depth > 0,
          "setup.bottom_depth: must be > 0 (+inf: no bottom), got " + number(m.bottom_depth));
  require(std::isfinite(m.bottom_albedo) && m.bottom_albedo >= 0 && m.bottom_albedo <= 1,
          "setup.bottom_albedo: must be in [0, 1], got " + number(m.bottom_albedo));
  for (int a = 0; a < 3; ++a)
    require(!std::isnan(m.box_lo[a]) && !std::isnan(m.box_hi[a]) && m.box_lo[a] < m.box_hi[a],
            "setup.box: lo must be below hi on every axis");
  require(p.photons > 0, "params.photons: must be > 0");
  require(p.wavelengths_per_photon >= 1 && p.wavelengths_per_photon <= ARCUS_OCEAN_MAX_HEROES,
          "params.wavelengths_per_photon: must be in 1.." + std::to_string(ARCUS_OCEAN_MAX_HEROES) + ", got " +
              std::to_string(p.wavelengths_per_photon));
  require(p.max_interactions >= 1 && p.max_interactions <= ARCUS_OCEAN_MAX_INTERACTIONS,
          "params.max_interactions: must be in 1.." + std::to_string(ARCUS_OCEAN_MAX_INTERACTIONS) + ", got " +
              std::to_string(p.max_interactions));
  for (size_t j = 0; j < p.depths.size(); ++j)
    require(std::isfinite(p.depths[j]) && p.depths[j] >= 0 && p.depths[j] < m.bottom_depth,
            "setup.depths[" + std::to_string(j) + "]: must be finite, >= 0 and above the bottom, got " +
                number(p.depths[j]));
  if (!p.depths.empty()) {
    require(m.surface || m.box_hi[2] == 0,
            "setup.depths: irradiance profiles need a plane-parallel column (surface = 1, or box_hi z = 0)");
    require(std::isfinite(p.layer) && p.layer > 0, "setup.layer: must be finite and > 0, got " + number(p.layer));
  }
}

int carried_wavelengths(int requested, int grid_count) {
  int h = std::clamp(requested, 1, ARCUS_OCEAN_MAX_HEROES);
  while (grid_count % h != 0) --h;  // the set must be the same whichever member is the hero
  return h;
}

arcus_features trace_features(const WaterTables& water, const Medium& medium, const TraceParams& params) {
  arcus_features f = 0;
  if (params.force_inelastic || has_inelastic(water)) f |= ARCUS_FEATURE_OCEAN_INELASTIC;
  if (bounded(medium)) f |= ARCUS_FEATURE_OCEAN_BOUNDARIES;
  if (!params.depths.empty()) f |= ARCUS_FEATURE_OCEAN_DEPTHS;
  return f;
}

std::unique_ptr<TraceJob> trace(arcus_context_t* ctx, const WaterTables& water, const std::vector<Light>& lights,
                                const Medium& medium, const TraceParams& params, arcus_progress_callback progress,
                                void* user, bool* cancelled) {
  auto job = std::make_unique<TraceJob>(ctx);
  trace_into(job.get(), ctx, water, lights, medium, params, progress, user, cancelled);
  return job;
}

void trace_into(TraceJob* job, arcus_context_t* ctx, const WaterTables& water, const std::vector<Light>& lights_in,
                const Medium& medium, const TraceParams& params, arcus_progress_callback progress, void* user,
                bool* cancelled) {
  check_trace(lights_in, medium, params);
  if (!ctx->info.fp64) fail(ARCUS_ERROR_UNSUPPORTED, "the ocean engine needs double precision (cl_khr_fp64)");
  const Grid& grid = water.grid;
  const size_t n = grid.count;
  job->water = water;
  job->limit = params.max_interactions;
  job->depths = params.depths;
  job->features = trace_features(water, medium, params);
  const bool inelastic = job->features & ARCUS_FEATURE_OCEAN_INELASTIC;

  arcus_ocean_desc d{};
  const std::vector<double> water_buf = water_buffer(water, inelastic, &d);
  require(d.events > 0 || bounded(medium), "water: absorbs and scatters nothing, and nothing bounds it");

  // Lights: the kernel's records and the emission CDF over (light, sample) pairs.
  std::vector<Light> lights = lights_in;
  std::vector<double> light_buf;
  for (Light& L : lights) {
    if (L.kind != Light::point && L.kind != Light::sky) normalise(L.direction);
    const double rec[ARCUS_OCEAN_LIGHT_REALS] = {double(L.kind),
                                                 L.position[0],
                                                 L.position[1],
                                                 L.position[2],
                                                 L.direction[0],
                                                 L.direction[1],
                                                 L.direction[2],
                                                 std::cos(L.half_angle_deg * kPi / 180),
                                                 L.radius,
                                                 0};
    light_buf.insert(light_buf.end(), rec, rec + ARCUS_OCEAN_LIGHT_REALS);
  }
  std::vector<double> cdf = band_powers(lights, grid, params.tile);
  const double total = std::accumulate(cdf.begin(), cdf.end(), 0.0);
  require(total > 0 && std::isfinite(total), "lights: emit nothing on the grid's wavelengths");
  std::partial_sum(cdf.begin(), cdf.end(), cdf.begin());
  for (double& c : cdf) c /= total;
  cdf.back() = 1;

  d.first_nm = grid.first_nm;
  d.step_nm = grid.count == 1 ? 1.0 : grid.step_nm;
  d.power = total / static_cast<double>(params.photons);
  d.n_water = medium.n_water;
  d.bottom_depth = medium.bottom_depth;
  d.bottom_albedo = medium.bottom_albedo;
  for (int a = 0; a < 3; ++a) {
    d.box_lo[a] = medium.box_lo[a];
    d.box_hi[a] = medium.box_hi[a];
  }
  d.layer = params.layer;
  d.tile = params.tile;
  d.tile_x = params.tile_center[0];
  d.tile_y = params.tile_center[1];
  d.seed = params.seed;
  d.count = grid.count;
  d.heroes = carried_wavelengths(params.wavelengths_per_photon, grid.count);
  d.limit = params.max_interactions;
  d.bins = std::min(d.limit, ARCUS_OCEAN_INTERACTION_BINS);
  d.light_count = static_cast<int32_t>(lights.size());
  d.surface = medium.surface;
  d.store = params.store;
  d.rows = tally_rows(ctx, params.photons);
  d.depth_count = static_cast<int32_t>(params.depths.size());

  const size_t rows = d.rows, tally_reals = ARCUS_OCEAN_TALLY_REALS(d.bins);
  const size_t depth_reals = params.depths.size() * n * 3;
  const size_t store_slots = params.store ? params.photons * (d.limit - 1) : 0;
  check_device_allocation(ctx, std::max<double>(store_slots, 1) * ARCUS_OCEAN_PHOTON_REALS * sizeof(double),
                          (double(rows) * (tally_reals + depth_reals) + double(store_slots) * ARCUS_OCEAN_PHOTON_REALS +
                           water_buf.size()) *
                              sizeof(double),
                          "a trace of " + std::to_string(params.photons) + " photons");

  const Layout layout{1, 1};  // scalar: one photon at a time per work-item (trace.cl)
  const BuiltProgram built = build_job_program(ctx, *job, trace_source(), layout);
  Launch<TraceArg> launch(ctx, built.program);
  launch.upload(TraceArg::water, water_buf, "the water's tables");
  launch.upload(TraceArg::lights, light_buf, "the lights");
  launch.upload(TraceArg::emission, cdf, "the lights' emission");
  std::vector<double> depths = params.depths;
  if (depths.empty()) depths.push_back(0);
  launch.upload(TraceArg::depths, depths, "the tally depths");
  std::vector<double> zeros(rows * tally_reals, 0.0);
  DeviceBuffer tallies_dev(ctx, zeros.size() * sizeof(double), "the tallies", zeros.data());
  std::vector<double> depth_zeros(std::max<size_t>(rows * depth_reals, 1), 0.0);
  DeviceBuffer depth_dev(ctx, depth_zeros.size() * sizeof(double), "the irradiance tallies", depth_zeros.data());
  std::vector<double> stored;
  if (store_slots) stored.assign(store_slots * ARCUS_OCEAN_PHOTON_REALS, 0.0);
  if (stored.empty()) stored.push_back(0);
  DeviceBuffer stored_dev(ctx, stored.size() * sizeof(double), "the stored photons", stored.data());
  launch.bind(TraceArg::tallies, &tallies_dev);
  launch.bind(TraceArg::depth_tallies, &depth_dev);
  launch.bind(TraceArg::stored, &stored_dev);
  // A slice: photons [first, end), a tally row a work-item.
  SliceRange photons{params.photons, kFirstSlicePhotons * static_cast<double>(rows)};
  photons.progress = progress;
  photons.progress_user = user;
  *cancelled = launch.run_slices(photons, [&](uint64_t first, uint64_t end) {
    d.first_photon = first;
    d.end_photon = end;
    launch.bind_value(TraceArg::d, d);
    return rows;
  }, &job->stats);
  job->trace_seconds = job->stats.kernel_seconds;
  job->count = photons.done;

  // The rows, summed in row order.
  std::vector<double> rows_out(rows * tally_reals);
  tallies_dev.read(ctx, 0, rows_out.size() * sizeof(double), rows_out.data());
  std::vector<double> sum(tally_reals, 0.0);
  for (size_t r = 0; r < rows; ++r)
    for (size_t j = 0; j < tally_reals; ++j) sum[j] += rows_out[r * tally_reals + j];
  Tallies& t = job->tallies;
  t.photons = static_cast<uint64_t>(sum[ARCUS_OCEAN_T_PHOTONS]);
  t.interactions = static_cast<uint64_t>(sum[ARCUS_OCEAN_T_INTERACTIONS]);
  t.stored = static_cast<uint64_t>(sum[ARCUS_OCEAN_T_STORED]);
  t.emitted = sum[ARCUS_OCEAN_T_EMITTED];
  t.past_limit = sum[ARCUS_OCEAN_T_PAST_LIMIT];
  t.bottom = sum[ARCUS_OCEAN_T_BOTTOM];
  t.absorbed_r2 = sum[ARCUS_OCEAN_T_ABSORBED_R2];
  for (int e = 0; e < kEventCount; ++e) {
    t.count[e] = sum[ARCUS_OCEAN_T_COUNT + e];
    t.arriving[e] = sum[ARCUS_OCEAN_T_ARRIVING + e];
    t.absorbed[e] = sum[ARCUS_OCEAN_T_ABSORBED + e];
  }
  t.absorbed_by_interaction.assign(sum.begin() + ARCUS_OCEAN_T_BY_INTERACTION,
                                   sum.begin() + ARCUS_OCEAN_T_BY_INTERACTION + d.bins + 1);
  t.escaped_by_interaction.assign(sum.begin() + ARCUS_OCEAN_T_ESCAPED(d.bins),
                                  sum.begin() + ARCUS_OCEAN_T_ESCAPED(d.bins) + d.bins + 1);

  if (depth_reals) {
    std::vector<double> dr(rows * depth_reals);
    depth_dev.read(ctx, 0, dr.size() * sizeof(double), dr.data());
    Irradiance& ir = job->irradiance;
    const size_t cells = params.depths.size() * n;
    ir.ed.assign(cells, 0.0);
    ir.eu.assign(cells, 0.0);
    ir.e0.assign(cells, 0.0);
    const double per_nm = 1.0 / d.step_nm;
    for (size_t r = 0; r < rows; ++r)
      for (size_t c = 0; c < cells; ++c) {
        ir.ed[c] += dr[r * depth_reals + 3 * c] * per_nm;
        ir.eu[c] += dr[r * depth_reals + 3 * c + 1] * per_nm;
        ir.e0[c] += dr[r * depth_reals + 3 * c + 2] * per_nm;
      }
  }
  if (store_slots) {
    stored_dev.read(ctx, 0, stored.size() * sizeof(double), stored.data());
    StoredPhotons& sp = job->photons;
    for (size_t s = 0; s < store_slots; ++s) {
      const double* x = &stored[s * ARCUS_OCEAN_PHOTON_REALS];
      if (!(x[ARCUS_OCEAN_STORED_POWER] > 0)) continue;
      sp.positions.insert(sp.positions.end(), x, x + 3);
      sp.directions.insert(sp.directions.end(), x + 3, x + 6);
      sp.events.push_back(static_cast<int32_t>(x[ARCUS_OCEAN_STORED_EVENT]));
      sp.powers.insert(sp.powers.end(), x + ARCUS_OCEAN_STORED_POWER, x + ARCUS_OCEAN_STORED_POWER + ARCUS_OCEAN_MAX_HEROES);
      sp.wavelengths.insert(sp.wavelengths.end(), x + ARCUS_OCEAN_STORED_NM, x + ARCUS_OCEAN_STORED_NM + ARCUS_OCEAN_MAX_HEROES);
    }
  }
}

}  // namespace arcus::ocean
