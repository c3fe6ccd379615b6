// The rainbow engine's C API (include/arcus/arcus_rainbow.h): particles, the cast, sky renders, the
// collecting sphere's queries, refractive indices and Lorenz–Mie with the Debye series.
#include <algorithm>
#include <chrono>
#include <climits>
#include <cmath>
#include <complex>
#include <limits>
#include <memory>
#include <string>
#include <vector>

#include "arcus/arcus_rainbow.h"
#include "core/call.h"
#include "core/format.h"
#include "geometry/mesh_handle.h"
#include "image/image_io.h"
#include "rainbow/beams.h"
#include "rainbow/cast.h"
#include "rainbow/mie.h"
#include "rainbow/particle.h"
#include "rainbow/refractive_index.h"
#include "rainbow/sky.h"

using namespace arcus;
using namespace arcus::api;

namespace arcus::rainbow {
const HandleKind kParticleHandle("particle");
}  // namespace arcus::rainbow

struct arcus_particle_s : arcus::Handle {
  arcus_particle_s(arcus_context_t* ctx, rainbow::Particle p)
      : Handle(arcus::rainbow::kParticleHandle, ctx), particle(std::move(p)) {}
  rainbow::Particle particle;
};

namespace {

constexpr double kPi = 3.14159265358979323846;

// Makes *out a particle of ctx, for a call holding ctx's lock.
template <class Make>
void make_particle(arcus_context_t* ctx, arcus_particle_t** out, Make&& make) {
  require_pointer(out, "out");
  *out = nullptr;
  auto particle = std::make_unique<arcus_particle_s>(ctx, make());
  arcus::retain_context(ctx);  // the particle's reference
  *out = particle.release();
}

template <class Make>
arcus_status create_particle(arcus_context_t* ctx, arcus_particle_t** out, Make&& make) {
  return simple<arcus_context_s>(ctx, arcus::kContextHandle, "ctx",
                                 [&](arcus_context_s*) { make_particle(ctx, out, make); });
}

// The public API takes kelvin (arcus_core.h, "Units"); the formulation is written in °C.
constexpr double kCelsiusZero = 273.15;

double index_of(int32_t material, double wavelength_nm, double temperature_k, double fixed) {
  switch (material) {
    case ARCUS_MATERIAL_WATER: {
      const double lo = rainbow::kWaterMinC + kCelsiusZero, hi = rainbow::kWaterMaxC + kCelsiusZero;
      require(temperature_k >= lo && temperature_k <= hi,
              "temperature_k must lie in [" + number(lo) + ", " + number(hi) +
                  "] K (IAPWS R9-97, liquid water at 101.325 kPa), got " + number(temperature_k));
      return rainbow::water_index(wavelength_nm, temperature_k - kCelsiusZero);
    }
    case ARCUS_MATERIAL_ICE: return rainbow::ice_index(wavelength_nm);
    case ARCUS_MATERIAL_FIXED:
      require(std::isfinite(fixed) && fixed > 1, "refractive_index must be finite and above 1, got " + number(fixed));
      return fixed;
    default: fail(ARCUS_ERROR_INVALID_ARGUMENT, "material must be water (0), ice (1) or fixed (2), got " +
                                                    std::to_string(material));
  }
  return 0;
}

template <class Body>
arcus_status on_rainbow_job(arcus_job_t* job, Body&& body) {
  return on_job<rainbow::RainbowJob>(job, "a rainbow cast", body);
}

// θ and φ of a query: φ defaults to the cast's query_phi_deg (0 when it kept every azimuth).
std::vector<double> query_directions(const rainbow::RainbowJob& j, size_t count, const double* theta,
                                     const double* phi) {
  require(count == 0 || theta, "theta_deg is NULL");
  require(count <= (size_t(1) << 26), "count " + std::to_string(count) + " is more than 2^26 directions a call");
  const double phi0 = std::isnan(j.query_phi_deg) ? 0.0 : j.query_phi_deg;
  std::vector<double> t(theta, theta + count), f(count, phi0);
  if (phi) f.assign(phi, phi + count);
  return rainbow::directions(t, f);
}

// x and m of a sphere, and the cosines of its angles.
struct MieInput {
  double x;
  std::complex<double> m;
  std::vector<double> mu;
};

MieInput mie_input(double radius, double wavelength_nm, double n_re, double n_im, size_t count,
                   const double* theta_deg) {
  require(std::isfinite(radius) && radius > 0, "radius must be positive and finite, got " + number(radius));
  require(std::isfinite(wavelength_nm) && wavelength_nm > 0,
          "wavelength_nm must be positive and finite, got " + number(wavelength_nm));
  require(count == 0 || theta_deg, "theta_deg is NULL");
  MieInput in{2 * kPi * radius / (wavelength_nm * 1e-9), {n_re, n_im}, std::vector<double>(count)};
  for (size_t i = 0; i < count; ++i) {
    require(std::isfinite(theta_deg[i]) && theta_deg[i] >= 0 && theta_deg[i] <= 180,
            "theta[" + std::to_string(i) + "] must lie in [0, 180] degrees, got " + number(theta_deg[i]));
    in.mu[i] = std::cos(theta_deg[i] * kPi / 180);
  }
  return in;
}

// (re, im) pairs of `from` at out[stride·i + offset], i over the values.
void copy_complex(const std::vector<std::complex<double>>& from, double* out, size_t stride, size_t offset) {
  if (!out) return;
  for (size_t i = 0; i < from.size(); ++i) {
    out[2 * (stride * i + offset)] = from[i].real();
    out[2 * (stride * i + offset) + 1] = from[i].imag();
  }
}

}  // namespace

extern "C" {

arcus_status arcus_rainbow_refractive_index(int32_t material, double wavelength_nm, double temperature_k, double* n) {
  return without_context([&] {
    require_pointer(n, "n");
    *n = index_of(material, wavelength_nm, temperature_k, std::numeric_limits<double>::quiet_NaN());
  });
}

arcus_status arcus_particle_create_sphere(arcus_context_t* ctx, double radius, arcus_particle_t** out) {
  return create_particle(ctx, out, [&] { return rainbow::sphere(radius); });
}

arcus_status arcus_particle_create_raindrop(arcus_context_t* ctx, double diameter, arcus_particle_t** out) {
  return create_particle(ctx, out, [&] { return rainbow::raindrop(diameter); });
}

arcus_status arcus_particle_create_mesh(arcus_context_t* ctx, const char* path, double scale, int32_t smooth,
                                        arcus_particle_t** out) {
  return create_particle(ctx, out, [&] {
    require_pointer(path, "path");
    return rainbow::mesh(geometry::load_mesh(path), scale, smooth != 0);
  });
}

arcus_status arcus_particle_create_from_mesh(arcus_mesh_t* mesh, double scale, int32_t smooth, arcus_particle_t** out) {
  return simple<arcus_mesh_s>(mesh, arcus::geometry::kMeshHandle, "mesh", [&](arcus_mesh_s* m) {
    make_particle(m->owner(), out, [&] { return rainbow::mesh(m->mesh, scale, smooth != 0); });
  });
}

arcus_status arcus_particle_retain(arcus_particle_t* particle) {
  return retain(particle, arcus::rainbow::kParticleHandle, "particle");
}
arcus_status arcus_particle_release(arcus_particle_t* particle) {
  return release(particle, arcus::rainbow::kParticleHandle, "particle");
}

arcus_status arcus_particle_get_info(arcus_particle_t* particle, arcus_particle_info* info) {
  return simple<arcus_particle_s>(particle, arcus::rainbow::kParticleHandle, "particle", [&](arcus_particle_s* p) {
    require_pointer(info, "info");
    *info = arcus_particle_info{};
    info->kind = p->particle.kind;
    info->equivalent_radius = rainbow::equivalent_radius(p->particle);
    info->volume = p->particle.volume;
    info->bound_radius = p->particle.bound;
    info->triangles = static_cast<uint32_t>(p->particle.mesh.triangle_count());
  });
}

arcus_status arcus_rainbow_params_init(arcus_rainbow_params* params) {
  return without_context([&] {
    require_pointer(params, "params");
    *params = arcus_rainbow_params{};
    params->wavelength_nm = 550;
    params->material = ARCUS_MATERIAL_WATER;
    params->temperature_k = 293.15;
    params->temperature_c = std::numeric_limits<double>::quiet_NaN();  // the deprecated field: unset
    params->refractive_index = std::numeric_limits<double>::quiet_NaN();
    params->grid = 1000;
    params->alpha = 0.3;
    params->max_bounces = 3;
    params->edge_rays = 1;
    for (int i = 0; i < 9; ++i) params->rotation[i] = i % 4 == 0 ? 1 : 0;
    params->query_phi_deg = std::numeric_limits<double>::quiet_NaN();
  });
}

arcus_status arcus_rainbow_cast(arcus_context_t* ctx, arcus_particle_t* particle, const arcus_rainbow_params* params,
                                arcus_job_t** job) {
  return on<arcus_context_s>(ctx, arcus::kContextHandle, "ctx", [&](arcus_context_s*, std::string* message) {
    require_pointer(job, "job");
    *job = nullptr;
    require_pointer(params, "params");
    auto* p = object_of<arcus_particle_s>(ctx, particle, arcus::rainbow::kParticleHandle, "particle");
    rainbow::CastParams cp;
    cp.wavelength_nm = params->wavelength_nm;
    const double temperature_k =  // a finite deprecated °C field comes from code written for 0.9
        std::isfinite(params->temperature_c) ? params->temperature_c + kCelsiusZero : params->temperature_k;
    cp.n = index_of(params->material, params->wavelength_nm, temperature_k, params->refractive_index);
    // unsigned to int without wrapping; check_cast names what is out of range
    cp.grid = static_cast<int>(std::min<uint32_t>(params->grid, INT32_MAX));
    cp.alpha = params->alpha;
    cp.bounces = static_cast<int>(std::min<uint32_t>(params->max_bounces, INT32_MAX));
    cp.edge_rays = params->edge_rays != 0;
    for (int i = 0; i < 9; ++i) cp.rotation[i] = params->rotation[i];
    cp.query_phi_deg = params->query_phi_deg;
    bool cancelled = false;
    auto j = rainbow::cast(ctx, p->particle, cp, params->progress, params->progress_user, &cancelled);
    arcus::retain_context(ctx);  // the job's reference
    *job = j.release();
    if (!cancelled) return ARCUS_SUCCESS;
    *message = "the progress callback cancelled the cast: the job holds no patches";
    return ARCUS_ERROR_CANCELLED;
  });
}

arcus_status arcus_rainbow_trace_beams(arcus_context_t* ctx, arcus_particle_t* particle,
                                       const arcus_rainbow_params* params, size_t count, const double* rotations,
                                       arcus_job_t** job) {
  return on<arcus_context_s>(ctx, arcus::kContextHandle, "ctx", [&](arcus_context_s*, std::string* message) {
    require_pointer(job, "job");
    *job = nullptr;
    require_pointer(params, "params");
    auto* p = object_of<arcus_particle_s>(ctx, particle, arcus::rainbow::kParticleHandle, "particle");
    require(count >= 1 && count <= 65536, "count must be 1 to 65536 orientations, got " + std::to_string(count));
    require_pointer(rotations, "rotations");
    for (size_t o = 0; o < count; ++o)
      rainbow::check_rotation(rotations + 9 * o, "rotations[" + std::to_string(o) + "]");
    const double temperature_k =
        std::isfinite(params->temperature_c) ? params->temperature_c + kCelsiusZero : params->temperature_k;
    const double n = index_of(params->material, params->wavelength_nm, temperature_k, params->refractive_index);
    require(std::isfinite(n) && n > 1 && n < 4, "the refractive index must lie in (1, 4) relative to air, got " +
                                                    number(n));
    require(params->max_bounces <= ARCUS_RAINBOW_MAX_BOUNCES,
            "max_bounces must be 0 to " + std::to_string(ARCUS_RAINBOW_MAX_BOUNCES) + ", got " +
                std::to_string(params->max_bounces));
    const std::vector<rainbow::ConvexFace> faces = rainbow::convex_faces(p->particle);
    const auto t0 = std::chrono::steady_clock::now();
    auto j = std::make_unique<rainbow::RainbowJob>(ctx);
    const int bounces = static_cast<int>(params->max_bounces);
    j->terms = bounces + 1;
    j->wave_number = 2 * 3.14159265358979323846 / (params->wavelength_nm * 1e-9);
    j->count = count;
    rainbow::BeamTotals books;
    const bool cancelled =
        rainbow::trace_beams(faces, n, bounces, count, rotations, j->glints, books, params->progress,
                             params->progress_user);
    arcus_rainbow_stats& info = j->info;
    info.refractive_index = n;
    info.rays = books.beams;
    info.intercepted = books.intercepted / double(count);
    for (int t = 0; t < 16; ++t) info.scattered[t] = books.intercepted > 0 ? books.scattered[t] / books.intercepted : 0;
    info.remaining = books.intercepted > 0 ? books.remaining / books.intercepted : 0;
    info.cast_seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    j->stats.total_seconds = info.cast_seconds;
    j->cross_section = (books.intercepted - books.remaining - books.dropped) / double(count);
    arcus::retain_context(ctx);  // the job's reference
    *job = j.release();
    if (!cancelled) return ARCUS_SUCCESS;
    *message = "the progress callback cancelled the beam trace: the job holds the orientations traced so far";
    return ARCUS_ERROR_CANCELLED;
  });
}

arcus_status arcus_job_get_rainbow_stats(arcus_job_t* job, arcus_rainbow_stats* stats) {
  return on_rainbow_job(job, [&](rainbow::RainbowJob* j) {
    require_pointer(stats, "stats");
    *stats = j->info;
  });
}

arcus_status arcus_job_get_rainbow_phase(arcus_job_t* job, size_t count, const double* theta_deg, const double* phi_deg,
                                         int32_t coherent, double* parallel, double* perpendicular, double* per_bounce) {
  return on_rainbow_job(job, [&](rainbow::RainbowJob* j) {
    require(coherent >= 0 && coherent <= 2,
            "coherent must be 0 (intensities), 1 (phasors, uniform at caustics) or 2 (phasors, eq. 4.31 "
            "alone), got " + std::to_string(coherent));
    const std::vector<double> dirs = query_directions(*j, count, theta_deg, phi_deg);
    const rainbow::Phase ph =
        rainbow::phase(*j, rainbow::query(j->owner(), *j, dirs, coherent == 1), coherent != 0);
    copy_out(ph.parallel, parallel);
    copy_out(ph.perpendicular, perpendicular);
    copy_out(ph.per_bounce, per_bounce);
  });
}

arcus_status arcus_job_get_rainbow_glints(arcus_job_t* job, size_t* count, uint32_t* terms, double* directions,
                                          double* areas, double* cross_sections) {
  return on_rainbow_job(job, [&](rainbow::RainbowJob* j) {
    require_pointer(count, "count");
    const size_t have = j->glints.size();
    if (terms || directions || areas || cross_sections)
      require(*count >= have, "count is " + std::to_string(*count) + " but the cast has " + std::to_string(have) +
                                  " glints: call with NULL arrays first to learn how many");
    *count = have;
    for (size_t g = 0; g < have; ++g) {
      const rainbow::Glint& x = j->glints[g];
      if (terms) terms[g] = static_cast<uint32_t>(x.p);
      if (directions)
        for (int a = 0; a < 3; ++a) directions[3 * g + a] = x.direction[a];
      if (areas) areas[g] = x.area;
      if (cross_sections) cross_sections[g] = x.cross_section;
    }
  });
}

arcus_status arcus_job_get_rainbow_phasors(arcus_job_t* job, size_t count, const double* theta_deg, const double* phi_deg,
                                           double* phasors) {
  return on_rainbow_job(job, [&](rainbow::RainbowJob* j) {
    require_pointer(phasors, "phasors");
    const std::vector<double> dirs = query_directions(*j, count, theta_deg, phi_deg);
    const std::vector<double> sums = rainbow::query(j->owner(), *j, dirs, true);
    const size_t per = ARCUS_RAINBOW_QUERY_REALS;
    for (size_t i = 0; i < count * size_t(j->terms); ++i)
      for (int e = 0; e < 8; ++e) phasors[8 * i + e] = sums[per * i + e];
  });
}

arcus_status arcus_rainbow_mie(double radius, double wavelength_nm, double n_re, double n_im, size_t count,
                               const double* theta_deg, double* s1, double* s2, double* parallel, double* perpendicular,
                               arcus_mie_efficiencies* efficiencies) {
  return without_context([&] {
    const MieInput in = mie_input(radius, wavelength_nm, n_re, n_im, count, theta_deg);
    const rainbow::mie::Result r = rainbow::mie::scatter(in.x, in.m, in.mu);
    copy_complex(r.s1, s1, 1, 0);
    copy_complex(r.s2, s2, 1, 0);
    const rainbow::mie::Polarised ph = rainbow::mie::polarised_phase_function(r, in.x);
    copy_out(ph.parallel, parallel);
    copy_out(ph.perpendicular, perpendicular);
    if (efficiencies) *efficiencies = arcus_mie_efficiencies{r.q_ext, r.q_sca, r.q_back, r.g};
  });
}

arcus_status arcus_rainbow_mie_debye(double radius, double wavelength_nm, double n_re, double n_im, uint32_t max_p,
                                     size_t count, const double* theta_deg, double* s1, double* s2, double* parallel,
                                     double* perpendicular) {
  return without_context([&] {
    require(max_p <= 1000, "max_p must be 0 to 1000, got " + std::to_string(max_p));
    const MieInput in = mie_input(radius, wavelength_nm, n_re, n_im, count, theta_deg);
    const rainbow::mie::Debye d = rainbow::mie::debye(in.x, in.m, in.mu, static_cast<int>(max_p));
    const double q_sca = rainbow::mie::scatter(in.x, in.m, {}).q_sca;  // the whole sphere's scale
    const size_t terms = size_t(max_p) + 1;
    for (size_t p = 0; p < terms; ++p) {
      // p = 0 without diffraction: what a ray tracer's external reflection is
      const rainbow::mie::Amplitudes& a = p == 0 ? d.reflection : d.terms[p];
      copy_complex(a.s1, s1, terms, p);
      copy_complex(a.s2, s2, terms, p);
      const rainbow::mie::Polarised ph = rainbow::mie::polarised_phase_function(a, in.x, q_sca);
      for (size_t i = 0; i < count; ++i) {
        if (parallel) parallel[terms * i + p] = ph.parallel[i];
        if (perpendicular) perpendicular[terms * i + p] = ph.perpendicular[i];
      }
    }
  });
}

arcus_status arcus_rainbow_sky_init(arcus_rainbow_sky* sky) {
  return without_context([&] {
    require_pointer(sky, "sky");
    *sky = arcus_rainbow_sky{};
    sky->width = 320;
    sky->height = 240;
    sky->camera_position[1] = 1.7;
    sky->camera_forward[2] = 1;
    sky->camera_up[1] = 1;
    sky->fov_deg = 90;
    sky->sun_elevation_deg = 10;
    sky->sun_azimuth_deg = 180;
    sky->sun_diameter_deg = 0.53;
    sky->sun_samples = 16;
    const double lo[3] = {-2000, 0, 500}, hi[3] = {2000, 2000, 1500};
    std::copy(lo, lo + 3, sky->rain_min);
    std::copy(hi, hi + 3, sky->rain_max);
    sky->march_steps = 32;
    sky->sky_image_scale = 1;
  });
}

arcus_status arcus_rainbow_render(arcus_context_t* ctx, const arcus_rainbow_table* table, const arcus_rainbow_sky* sky,
                                  arcus_job_t** job) {
  return on<arcus_context_s>(ctx, arcus::kContextHandle, "ctx", [&](arcus_context_s*, std::string* message) {
    require_pointer(job, "job");
    *job = nullptr;
    require_pointer(table, "table");
    require_pointer(sky, "sky");
    bool cancelled = false;
    auto j = rainbow::render_sky(ctx, *table, *sky, &cancelled);
    arcus::retain_context(ctx);  // the job's reference
    *job = j.release();
    if (!cancelled) return ARCUS_SUCCESS;
    *message = "the progress callback cancelled the render: the image is incomplete";
    return ARCUS_ERROR_CANCELLED;
  });
}

arcus_status arcus_job_get_rainbow_image(arcus_job_t* job, uint32_t* width, uint32_t* height, float* xyz, float* rgb,
                                         float* theta_deg) {
  return on_job<rainbow::SkyJob>(job, "a rainbow sky render", [&](rainbow::SkyJob* j) {
    if (width) *width = j->width;
    if (height) *height = j->height;
    copy_out(j->xyz, xyz);
    copy_out(j->rgb, rgb);
    copy_out(j->theta, theta_deg);
  });
}

arcus_status arcus_job_write_rainbow_image(arcus_job_t* job, const char* exr_path, const char* png_path) {
  return on_job<rainbow::SkyJob>(job, "a rainbow sky render", [&](rainbow::SkyJob* j) {
    arcus::image::Image img;
    img.width = static_cast<int>(j->width);
    img.height = static_cast<int>(j->height);
    img.channels = {"R", "G", "B", "X", "Y", "Z", "theta"};
    const size_t n = size_t(j->width) * j->height;
    img.pixels.resize(n * img.channels.size());
    for (size_t p = 0; p < n; ++p) {
      float* px = &img.pixels[p * img.channels.size()];
      for (int c = 0; c < 3; ++c) {
        px[c] = j->rgb[3 * p + c];
        px[3 + c] = j->xyz[3 * p + c];
      }
      px[6] = j->theta[p];
    }
    if (exr_path) arcus::image::write_exr(exr_path, img);
    if (png_path) arcus::image::write_png(png_path, img, j->exposure);
  });
}

}  // extern "C"
