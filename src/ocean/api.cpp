// The C entry points of arcus_ocean.h: water objects, coefficient tables, photon
// traces and their tallies.
#include <algorithm>
#include <cmath>
#include <memory>
#include <string>

#include "arcus/arcus_ocean.h"
#include "core/call.h"
#include "ocean/trace.h"
#include "ocean/water.h"

using arcus::HandleType;
using arcus::require;
using arcus::require_pointer;
using namespace arcus::api;
namespace ocean = arcus::ocean;

struct arcus_water_s : arcus::Handle {
  arcus_water_s(arcus_context_t* ctx, ocean::Water w) : Handle(HandleType::Water, ctx), water(std::move(w)) {}
  ocean::Water water;
};

namespace {

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
  return simple<arcus_context_s>(ctx, HandleType::Context, "ctx", [&](arcus_context_s*) {
    require_pointer(out, "out");
    *out = nullptr;
    ocean::Water w = make();
    ocean::check_water(w);
    auto water = std::make_unique<arcus_water_s>(ctx, std::move(w));
    arcus::retain_context(ctx);  // the water's reference
    *out = water.release();
  });
}

ocean::TraceJob* trace_job(arcus_job_s* job) {
  auto* t = dynamic_cast<ocean::TraceJob*>(job);
  if (!t) arcus::fail(ARCUS_ERROR_INVALID_ARGUMENT, std::string("job is a ") + job->kind + " job, not an ocean trace");
  return t;
}

template <class Body>
arcus_status on_trace_job(arcus_job_t* job, Body&& body) {
  return simple<arcus_job_s>(job, HandleType::Job, "job", [&](arcus_job_s* j) { body(trace_job(j)); });
}

template <class T>
void copy_out(const std::vector<T>& from, T* to) {
  if (to) std::copy(from.begin(), from.end(), to);
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
    return w;
  });
}

arcus_status arcus_water_retain(arcus_water_t* water) { return retain(water, HandleType::Water, "water"); }
arcus_status arcus_water_release(arcus_water_t* water) { return release(water, HandleType::Water, "water"); }

arcus_status arcus_water_get_coefficients(arcus_water_t* water, const arcus_wavelength_grid* grid, double* events,
                                          double* absorption, double* scattering) {
  return simple<arcus_water_s>(water, HandleType::Water, "water", [&](arcus_water_s* w) {
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
  });
}

arcus_status arcus_ocean_trace(arcus_context_t* ctx, arcus_water_t* water, const arcus_ocean_setup* setup,
                               const arcus_ocean_trace_params* params, arcus_job_t** job) {
  return on<arcus_context_s>(ctx, HandleType::Context, "ctx", [&](arcus_context_s*, std::string* message) {
    require_pointer(job, "job");
    *job = nullptr;
    require_pointer(setup, "setup");
    require_pointer(params, "params");
    auto* w = arcus::api::object_of<arcus_water_s>(ctx, water, HandleType::Water, "water");
    require(setup->light_count == 0 || setup->lights, "setup.lights is NULL but light_count is " +
                                                          std::to_string(setup->light_count));
    std::vector<ocean::Light> lights(setup->light_count);
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
    ocean::Medium m;
    m.surface = setup->surface != 0;
    m.n_water = setup->n_water;
    m.bottom_depth = setup->bottom_depth;
    m.bottom_albedo = setup->bottom_albedo;
    for (int a = 0; a < 3; ++a) {
      m.box_lo[a] = setup->box_lo[a];
      m.box_hi[a] = setup->box_hi[a];
    }
    ocean::TraceParams p;
    p.photons = params->photons;
    p.max_interactions = static_cast<int>(std::min<uint32_t>(params->max_interactions, 1u << 20));
    p.seed = params->seed;
    p.store = params->store_photons != 0;
    p.force_inelastic = params->force_inelastic != 0;
    p.depths = copy_array(setup->depths, setup->depth_count, "setup.depths");
    p.layer = setup->layer;
    ocean::check_trace(lights, m, p);  // before the water is evaluated: cheap errors first
    const ocean::WaterTables tables = ocean::evaluate(w->water, grid_of(setup->grid));
    bool cancelled = false;
    auto j = ocean::trace(ctx, tables, lights, m, p, params->progress, params->progress_user, &cancelled);
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
    const ocean::StoredPhotons& s = j->photons;
    *count = s.size();
    copy_out(s.positions, positions);
    copy_out(s.directions, directions);
    copy_out(s.powers, powers);
    copy_out(s.wavelengths, wavelengths);
    copy_out(s.events, events);
  });
}

}  // extern "C"
