// The C entry points of arcus_ocean.h: water objects, coefficient tables, photon
// traces and their tallies.
#include <algorithm>
#include <cmath>
#include <memory>
#include <string>

#include "arcus/arcus_ocean.h"
#include "core/call.h"
#include "image/image_io.h"
#include "ocean/render.h"
#include "ocean/scene.h"
#include "ocean/trace.h"
#include "ocean/water.h"
#include "scene/common_keys.h"

using arcus::require;
using arcus::require_pointer;
using namespace arcus::api;
namespace ocean = arcus::ocean;

namespace arcus::ocean {
const HandleKind kWaterHandle("water");
}  // namespace arcus::ocean

struct arcus_water_s : arcus::Handle {
  arcus_water_s(arcus_context_t* ctx, ocean::Water w) : Handle(arcus::ocean::kWaterHandle, ctx), water(std::move(w)) {}
  ocean::Water water;
};

namespace {

// The ten events and the phase kinds are numbered once for the C API, once for the
// kernels and once inside: the same numbers, checked here.
constexpr bool same(int a, int b, int c) { return a == b && b == c; }
static_assert(same(ARCUS_EVENT_ABSORB_WATER, ocean::kAbsorbWater, ARCUS_OCEAN_ABSORB_WATER) &&
                  same(ARCUS_EVENT_RAMAN, ocean::kRaman, ARCUS_OCEAN_RAMAN) &&
                  same(ARCUS_EVENT_ABSORB_DETRITUS, ocean::kAbsorbDetritus, ARCUS_OCEAN_ABSORB_DETRITUS) &&
                  same(ARCUS_EVENT_ABSORB_PHYTO, ocean::kAbsorbPhyto, ARCUS_OCEAN_ABSORB_PHYTO) &&
                  same(ARCUS_EVENT_FLUORESCE_PHYTO, ocean::kFluorescePhyto, ARCUS_OCEAN_FLUORESCE_PHYTO) &&
                  same(ARCUS_EVENT_ABSORB_CDOM, ocean::kAbsorbCdom, ARCUS_OCEAN_ABSORB_CDOM) &&
                  same(ARCUS_EVENT_FLUORESCE_CDOM, ocean::kFluoresceCdom, ARCUS_OCEAN_FLUORESCE_CDOM) &&
                  same(ARCUS_EVENT_SCATTER_WATER, ocean::kScatterWater, ARCUS_OCEAN_SCATTER_WATER) &&
                  same(ARCUS_EVENT_SCATTER_DETRITUS, ocean::kScatterDetritus, ARCUS_OCEAN_SCATTER_DETRITUS) &&
                  same(ARCUS_EVENT_SCATTER_PHYTO, ocean::kScatterPhyto, ARCUS_OCEAN_SCATTER_PHYTO) &&
                  same(ARCUS_OCEAN_EVENT_COUNT, ocean::kEventCount, ARCUS_OCEAN_EVENTS),
              "the events' numbers disagree");
static_assert(same(ARCUS_PHASE_ISOTROPIC, ocean::Phase::isotropic, ARCUS_OCEAN_PHASE_ISOTROPIC) &&
                  same(ARCUS_PHASE_RAYLEIGH_LIKE, ocean::Phase::rayleigh_like, ARCUS_OCEAN_PHASE_RAYLEIGH_LIKE) &&
                  same(ARCUS_PHASE_HG, ocean::Phase::hg, ARCUS_OCEAN_PHASE_HG) &&
                  same(ARCUS_PHASE_TWO_TERM_HG, ocean::Phase::two_term_hg, ARCUS_OCEAN_PHASE_TWO_TERM_HG) &&
                  same(ARCUS_PHASE_TABLE, ocean::Phase::table, ARCUS_OCEAN_PHASE_TABLE),
              "the phase kinds' numbers disagree");
static_assert(same(ARCUS_OCEAN_LIGHT_POINT, ocean::Light::point, ARCUS_OCEAN_EMIT_POINT) &&
                  same(ARCUS_OCEAN_LIGHT_SPOT, ocean::Light::spot, ARCUS_OCEAN_EMIT_SPOT) &&
                  same(ARCUS_OCEAN_LIGHT_DIRECTIONAL, ocean::Light::directional, ARCUS_OCEAN_EMIT_DIRECTIONAL) &&
                  same(ARCUS_OCEAN_LIGHT_SKY, ocean::Light::sky, ARCUS_OCEAN_EMIT_SKY),
              "the light kinds' numbers disagree");

std::vector<double> copy_array(const double* p, uint32_t n, const std::string& name) {
  if (n == 0) return {};
  require(p != nullptr, name + " is NULL but its count is " + std::to_string(n));
  return std::vector<double>(p, p + n);
}

ocean::Spectrum spectrum_of(const arcus_spectrum& s, const std::string& name) {
  return {copy_array(s.nm, s.count, name + ".nm"), copy_array(s.values, s.count, name + ".values")};
}

ocean::Phase phase_of(const arcus_phase_function& p, const std::string& name) {
  ocean::Phase f;
  require(p.kind >= ARCUS_PHASE_ISOTROPIC && p.kind <= ARCUS_PHASE_TABLE,
          name + ".kind: unknown phase function kind " + std::to_string(p.kind));
  f.kind = static_cast<ocean::Phase::Kind>(p.kind);
  f.a = p.a;
  f.g_forward = p.g_forward;
  f.g_backward = p.g_backward;
  f.forward_weight = p.forward_weight;
  f.cosines = copy_array(p.table_cosines, p.table_count, name + ".table_cosines");
  f.values = copy_array(p.table_values, p.table_count, name + ".table_values");
  return f;
}

// The struct's view of a phase (tables are not handed back: their pointers would dangle).
arcus_phase_function phase_struct(const ocean::Phase& f) {
  arcus_phase_function p{};
  p.kind = f.kind;
  p.a = f.a;
  p.g_forward = f.g_forward;
  p.g_backward = f.g_backward;
  p.forward_weight = f.forward_weight;
  return p;
}

arcus_bio_optical bio_struct(const ocean::BioOptical& b) {
  arcus_bio_optical s{};
  s.chlorophyll = b.chlorophyll;
  s.a_d400 = b.a_d400;
  s.a_y440 = b.a_y440;
  s.s_d = b.s_d;
  s.s_y = b.s_y;
  s.chlorophyll_yield = b.chlorophyll_yield;
  s.cdom_yield_scale = b.cdom_yield_scale;
  s.raman_scale = b.raman_scale;
  s.stokes_only = !b.anti_stokes;
  s.detritus_scattering_reference_a_d400 = b.detritus_scattering_reference_a_d400;
  s.detritus_phase = phase_struct(b.detritus_phase);
  return s;
}

ocean::BioOptical bio_of(const arcus_bio_optical& s) {
  ocean::BioOptical b;
  b.chlorophyll = s.chlorophyll;
  b.a_d400 = s.a_d400;
  b.a_y440 = s.a_y440;
  b.s_d = s.s_d;
  b.s_y = s.s_y;
  b.chlorophyll_yield = s.chlorophyll_yield;
  b.cdom_yield_scale = s.cdom_yield_scale;
  b.raman_scale = s.raman_scale;
  b.anti_stokes = s.stokes_only == 0;
  b.detritus_scattering_reference_a_d400 = s.detritus_scattering_reference_a_d400;
  b.detritus_phase = phase_of(s.detritus_phase, "bio.detritus_phase");
  return b;
}

ocean::Grid grid_of(const arcus_wavelength_grid& g) {
  ocean::Grid grid{g.first_nm, g.step_nm, static_cast<int>(g.count)};
  require(g.count <= 100000, "grid.count: at most 100000 samples, got " + std::to_string(g.count));
  ocean::check_grid(grid);
  return grid;
}

template <class Make>
arcus_status create_water(arcus_context_t* ctx, arcus_water_t** out, Make&& make) {
  return simple<arcus_context_s>(ctx, arcus::kContextHandle, "ctx", [&](arcus_context_s*) {
    require_pointer(out, "out");
    *out = nullptr;
    ocean::Water w = make();
    ocean::check_water(w);
    auto water = std::make_unique<arcus_water_s>(ctx, std::move(w));
    arcus::retain_context(ctx);  // the water's reference
    *out = water.release();
  });
}

// A render job is a trace job too: the trace's getters take either.
template <class Body>
arcus_status on_trace_job(arcus_job_t* job, Body&& body) {
  return on_job<ocean::TraceJob>(job, "an ocean trace", body);
}

// What a setup and trace parameters say, as the engine takes it.
struct TraceInput {
  std::vector<ocean::Light> lights;
  ocean::Medium medium;
  ocean::TraceParams params;
};

TraceInput trace_input(const arcus_ocean_setup* setup, const arcus_ocean_trace_params* params) {
  require(setup->light_count == 0 || setup->lights, "setup.lights is NULL but light_count is " +
                                                        std::to_string(setup->light_count));
  TraceInput in;
  std::vector<ocean::Light>& lights = in.lights;
  lights.resize(setup->light_count);
  for (uint32_t l = 0; l < setup->light_count; ++l) {
    const arcus_ocean_light& s = setup->lights[l];
    ocean::Light& L = lights[l];
    L.kind = static_cast<ocean::Light::Kind>(s.kind);
    for (int a = 0; a < 3; ++a) {
      L.position[a] = s.position[a];
      L.direction[a] = s.direction[a];
    }
    L.half_angle_deg = s.half_angle_deg;
    L.radius = s.radius;
    L.spectrum = spectrum_of(s.spectrum, "lights[" + std::to_string(l) + "].spectrum");
  }
  ocean::Medium& m = in.medium;
  m.surface = setup->surface != 0;
  m.n_water = setup->n_water;
  m.bottom_depth = setup->bottom_depth;
  m.bottom_albedo = setup->bottom_albedo;
  for (int a = 0; a < 3; ++a) {
    m.box_lo[a] = setup->box_lo[a];
    m.box_hi[a] = setup->box_hi[a];
  }
  ocean::TraceParams& p = in.params;
  p.photons = params->photons;
  p.max_interactions = static_cast<int>(std::min<uint32_t>(params->max_interactions, 1u << 20));
  p.seed = params->seed;
  p.store = params->store_photons != 0;
  p.force_inelastic = params->force_inelastic != 0;
  p.wavelengths_per_photon = static_cast<int>(std::min<uint32_t>(params->wavelengths_per_photon, 1u << 20));
  p.depths = copy_array(setup->depths, setup->depth_count, "setup.depths");
  p.layer = setup->layer;
  return in;
}

ocean::MarchParams march_of(const arcus_ocean_march& s) {
  ocean::MarchParams m;
  m.steps = static_cast<int>(std::min<uint32_t>(s.steps, 1u << 30));
  m.distance = s.distance;
  m.k = static_cast<int>(std::min<uint32_t>(s.k, 1u << 30));
  m.estimator = static_cast<ocean::MarchParams::Estimator>(s.estimator);
  m.single_scattering = s.single_scattering != 0;
  m.multiple_scattering = s.multiple_scattering != 0;
  m.exposure = s.exposure;
  m.estimate_stride = static_cast<int>(std::min<uint32_t>(s.estimate_stride, 1u << 20));
  m.photon_tile = s.photon_tile;
  m.step_subsample = static_cast<int>(std::min<uint32_t>(s.step_subsample, 1u << 30));
  return m;
}

template <class Body>
arcus_status on_render_job(arcus_job_t* job, Body&& body) {
  return on_job<ocean::RenderJob>(job, "an ocean render", body);
}

// Runs a render and hands its job out (a cancelled one too, with ARCUS_ERROR_CANCELLED).
template <class Render>
arcus_status finish_render(arcus_context_t* ctx, arcus_job_t** job, std::string* message, Render&& run) {
  bool cancelled = false;
  auto j = run(&cancelled);
  arcus::retain_context(ctx);  // the job's reference
  *job = j.release();
  if (!cancelled) return ARCUS_SUCCESS;
  *message = "the progress callback cancelled the render: the job holds the pixels done so far";
  return ARCUS_ERROR_CANCELLED;
}

}  // namespace

extern "C" {

arcus_status arcus_bio_optical_init(arcus_bio_optical* bio) {
  return without_context([&] {
    require_pointer(bio, "bio");
    *bio = bio_struct(ocean::bio_optical_defaults());
  });
}

arcus_status arcus_bio_optical_preset(const char* name, arcus_bio_optical* bio) {
  return without_context([&] {
    require_pointer(name, "name");
    require_pointer(bio, "bio");
    *bio = bio_struct(ocean::preset(name));
  });
}

arcus_status arcus_water_create(arcus_context_t* ctx, const arcus_bio_optical* bio, arcus_water_t** out) {
  return create_water(ctx, out, [&] {
    require_pointer(bio, "bio");
    ocean::Water w;
    w.kind = ocean::Water::kBioOptical;
    w.bio = bio_of(*bio);
    return w;
  });
}

arcus_status arcus_water_create_iops(arcus_context_t* ctx, const arcus_water_iops* iops, arcus_water_t** out) {
  return create_water(ctx, out, [&] {
    require_pointer(iops, "iops");
    ocean::Water w;
    w.kind = ocean::Water::kIops;
    ocean::Iops& o = w.iops;
    o.absorption = spectrum_of(iops->absorption, "iops.absorption");
    o.scattering = spectrum_of(iops->scattering, "iops.scattering");
    o.phase = phase_of(iops->phase, "iops.phase");
    o.raman = iops->raman != 0;
    o.chlorophyll = iops->chlorophyll;
    o.chlorophyll_yield = iops->chlorophyll_yield;
    o.a_y440 = iops->a_y440;
    o.s_y = iops->s_y;
    o.anti_stokes = iops->stokes_only == 0;
    return w;
  });
}

arcus_status arcus_water_retain(arcus_water_t* water) { return retain(water, arcus::ocean::kWaterHandle, "water"); }
arcus_status arcus_water_release(arcus_water_t* water) { return release(water, arcus::ocean::kWaterHandle, "water"); }

arcus_status arcus_water_get_coefficients(arcus_water_t* water, const arcus_wavelength_grid* grid, double* events,
                                          double* absorption, double* scattering) {
  return simple<arcus_water_s>(water, arcus::ocean::kWaterHandle, "water", [&](arcus_water_s* w) {
    require_pointer(grid, "grid");
    const ocean::WaterTables t = ocean::evaluate(w->water, grid_of(*grid));
    const size_t n = grid->count;
    for (int e = 0; e < ocean::kEventCount; ++e)
      if (events) std::copy(t.event[e].begin(), t.event[e].end(), events + e * n);
    for (int c = 0; c < 4; ++c) {
      if (absorption) std::copy(t.absorption[c].begin(), t.absorption[c].end(), absorption + c * n);
      if (scattering) std::copy(t.scattering[c].begin(), t.scattering[c].end(), scattering + c * n);
    }
  });
}

arcus_status arcus_ocean_setup_init(arcus_ocean_setup* setup) {
  return without_context([&] {
    require_pointer(setup, "setup");
    *setup = arcus_ocean_setup{};
    setup->grid = {380, 5, 81};
    setup->n_water = 1.34;
    setup->bottom_depth = INFINITY;
    for (int a = 0; a < 3; ++a) {
      setup->box_lo[a] = -INFINITY;
      setup->box_hi[a] = INFINITY;
    }
    setup->layer = 0.1;
  });
}

arcus_status arcus_ocean_trace_params_init(arcus_ocean_trace_params* params) {
  return without_context([&] {
    require_pointer(params, "params");
    *params = arcus_ocean_trace_params{};
    params->photons = 400000;
    params->max_interactions = 5;
    params->seed = 1;
    params->wavelengths_per_photon = ocean::TraceParams{}.wavelengths_per_photon;
  });
}

arcus_status arcus_ocean_trace(arcus_context_t* ctx, arcus_water_t* water, const arcus_ocean_setup* setup,
                               const arcus_ocean_trace_params* params, arcus_job_t** job) {
  return on<arcus_context_s>(ctx, arcus::kContextHandle, "ctx", [&](arcus_context_s*, std::string* message) {
    require_pointer(job, "job");
    *job = nullptr;
    require_pointer(setup, "setup");
    require_pointer(params, "params");
    auto* w = arcus::api::object_of<arcus_water_s>(ctx, water, arcus::ocean::kWaterHandle, "water");
    const TraceInput in = trace_input(setup, params);
    ocean::check_trace(in.lights, in.medium, in.params);  // before the water is evaluated: cheap errors first
    const ocean::WaterTables tables = ocean::evaluate(w->water, grid_of(setup->grid));
    bool cancelled = false;
    auto j = ocean::trace(ctx, tables, in.lights, in.medium, in.params, params->progress, params->progress_user,
                          &cancelled);
    arcus::retain_context(ctx);  // the job's reference
    *job = j.release();
    if (!cancelled) return ARCUS_SUCCESS;
    *message = "the progress callback cancelled the trace: the job holds the photons traced so far";
    return ARCUS_ERROR_CANCELLED;
  });
}

arcus_status arcus_job_get_ocean_tallies(arcus_job_t* job, arcus_ocean_tallies* out) {
  return on_trace_job(job, [&](ocean::TraceJob* j) {
    require_pointer(out, "tallies");
    const ocean::Tallies& t = j->tallies;
    *out = arcus_ocean_tallies{};
    out->photons = t.photons;
    out->interactions = t.interactions;
    out->stored = t.stored;
    out->emitted = t.emitted;
    out->past_limit = t.past_limit;
    out->bottom = t.bottom;
    out->escaped = t.escaped();
    out->absorbed = t.absorbed_total();
    for (int e = 0; e < ocean::kEventCount; ++e) {
      out->count[e] = t.count[e];
      out->arriving[e] = t.arriving[e];
      out->absorbed_by[e] = t.absorbed[e];
    }
    out->max_interactions = static_cast<uint32_t>(j->limit);
    out->interaction_bins = static_cast<uint32_t>(j->tallies.absorbed_by_interaction.size() - 1);
  });
}

arcus_status arcus_job_get_ocean_by_interaction(arcus_job_t* job, double* absorbed, double* escaped) {
  return on_trace_job(job, [&](ocean::TraceJob* j) {
    copy_out(j->tallies.absorbed_by_interaction, absorbed);
    copy_out(j->tallies.escaped_by_interaction, escaped);
  });
}

arcus_status arcus_job_get_ocean_irradiance(arcus_job_t* job, double* ed, double* eu, double* e0) {
  return on_trace_job(job, [&](ocean::TraceJob* j) {
    copy_out(j->irradiance.ed, ed);
    copy_out(j->irradiance.eu, eu);
    copy_out(j->irradiance.e0, e0);
  });
}

arcus_status arcus_job_get_ocean_photons(arcus_job_t* job, size_t* count, double* positions, double* directions,
                                         double* powers, double* wavelengths, int32_t* events) {
  return on_trace_job(job, [&](ocean::TraceJob* j) {
    require_pointer(count, "count");
    // One entry per carried wavelength (a power > 0), at its photon's place.
    const ocean::StoredPhotons& s = j->photons;
    size_t n = 0;
    for (size_t i = 0; i < s.size(); ++i)
      for (int h = 0; h < ARCUS_OCEAN_MAX_HEROES; ++h) {
        const size_t c = i * ARCUS_OCEAN_MAX_HEROES + h;
        if (!(s.powers[c] > 0)) continue;
        for (int a = 0; a < 3; ++a) {
          if (positions) positions[3 * n + a] = s.positions[3 * i + a];
          if (directions) directions[3 * n + a] = s.directions[3 * i + a];
        }
        if (powers) powers[n] = s.powers[c];
        if (wavelengths) wavelengths[n] = s.wavelengths[c];
        if (events) events[n] = s.events[i];
        ++n;
      }
    *count = n;
  });
}

arcus_status arcus_ocean_march_init(arcus_ocean_march* march) {
  return without_context([&] {
    require_pointer(march, "march");
    const ocean::MarchParams d;
    *march = arcus_ocean_march{};
    march->steps = static_cast<uint32_t>(d.steps);
    march->distance = d.distance;
    march->k = static_cast<uint32_t>(d.k);
    march->estimator = d.estimator;
    march->single_scattering = d.single_scattering;
    march->multiple_scattering = d.multiple_scattering;
    march->exposure = d.exposure;
    march->estimate_stride = static_cast<uint32_t>(d.estimate_stride);
    march->photon_tile = d.photon_tile;
    march->step_subsample = static_cast<uint32_t>(d.step_subsample);
  });
}

arcus_status arcus_ocean_render(arcus_context_t* ctx, arcus_water_t* water, const arcus_ocean_setup* setup,
                                const arcus_ocean_trace_params* params, const arcus_camera* camera,
                                const arcus_ocean_march* march, arcus_job_t** job) {
  return on<arcus_context_s>(ctx, arcus::kContextHandle, "ctx", [&](arcus_context_s*, std::string* message) {
    require_pointer(job, "job");
    *job = nullptr;
    require_pointer(setup, "setup");
    require_pointer(params, "params");
    require_pointer(camera, "camera");
    require_pointer(march, "march");
    auto* w = arcus::api::object_of<arcus_water_s>(ctx, water, arcus::ocean::kWaterHandle, "water");
    const TraceInput in = trace_input(setup, params);
    const ocean::MarchParams m = march_of(*march);
    arcus::scene::check_camera(arcus::scene::camera_desc(*camera), "camera");
    ocean::check_march(m);
    ocean::check_trace(in.lights, in.medium, in.params);
    const ocean::WaterTables tables = ocean::evaluate(w->water, grid_of(setup->grid));
    return finish_render(ctx, job, message, [&](bool* cancelled) {
      return ocean::render(ctx, tables, in.lights, in.medium, in.params, *camera, m, params->progress,
                           params->progress_user, cancelled);
    });
  });
}

arcus_status arcus_ocean_render_scene(arcus_scene_t* scene, arcus_progress_callback progress, void* user,
                                      arcus_job_t** job) {
  return on<arcus_scene_s>(scene, arcus::scene::kSceneHandle, "scene", [&](arcus_scene_s* s, std::string* message) {
    require_pointer(job, "job");
    *job = nullptr;
    const ocean::OceanSceneDesc& d = ocean::ocean_scene(s)->desc;
    require(d.has_camera, s->name + ": the scene has no \"view\" to render");
    const ocean::WaterTables tables = ocean::evaluate(d.water, d.grid);
    return finish_render(s->owner(), job, message, [&](bool* cancelled) {
      return ocean::render(s->owner(), tables, d.lights, d.medium, d.trace, d.camera, d.march, progress, user,
                           cancelled);
    });
  });
}

arcus_status arcus_job_get_ocean_render_stats(arcus_job_t* job, arcus_ocean_render_stats* stats) {
  return on_render_job(job, [&](ocean::RenderJob* j) {
    require_pointer(stats, "stats");
    const ocean::RenderStats& r = j->render_stats;
    *stats = {r.trace_seconds, r.map_seconds, r.estimate_seconds, r.total_seconds, r.photons_stored};
  });
}

arcus_status arcus_job_get_ocean_image(arcus_job_t* job, uint32_t* width, uint32_t* height, uint32_t* samples,
                                       double* wavelengths, float* rgb, double* spectral) {
  return on_render_job(job, [&](ocean::RenderJob* j) {
    if (width) *width = j->width;
    if (height) *height = j->height;
    if (samples) *samples = static_cast<uint32_t>(j->wavelengths.size());
    copy_out(j->wavelengths, wavelengths);
    copy_out(j->rgb, rgb);
    copy_out(j->spectral, spectral);
  });
}

arcus_status arcus_job_write_ocean_image(arcus_job_t* job, const char* exr_path, const char* png_path,
                                         int32_t spectral_bands) {
  return on_render_job(job, [&](ocean::RenderJob* j) {
    arcus::image::Image img;
    img.width = static_cast<int>(j->width);
    img.height = static_cast<int>(j->height);
    img.channels = {"R", "G", "B"};
    const size_t n = j->wavelengths.size(), pixels = size_t(j->width) * j->height;
    if (spectral_bands)
      for (double nm : j->wavelengths) {
        char name[32];
        std::snprintf(name, sizeof name, "L%g", nm);
        img.channels.push_back(name);
      }
    const size_t c = img.channels.size();
    img.pixels.resize(pixels * c);
    for (size_t p = 0; p < pixels; ++p) {
      for (int k = 0; k < 3; ++k) img.pixels[p * c + k] = j->rgb[3 * p + k];
      if (spectral_bands)
        for (size_t m = 0; m < n; ++m) img.pixels[p * c + 3 + m] = static_cast<float>(j->spectral[p * n + m]);
    }
    if (exr_path) arcus::image::write_exr(exr_path, img);
    if (png_path) {
      img.channels.resize(3);
      std::vector<float> rgb(j->rgb);
      img.pixels = std::move(rgb);
      arcus::image::write_png(png_path, img, j->exposure);
    }
  });
}

}  // extern "C"
