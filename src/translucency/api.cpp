// The translucency engine's C API (include/arcus/arcus_translucency.h): host calls on
// the dipole model, with no context (errors go to the thread's last error), and the
// render, a job on a context.
#include <cmath>
#include <cstring>
#include <limits>
#include <string>

#include "core/call.h"
#include "core/format.h"
#include "geometry/mesh_handle.h"
#include "translucency/dipole.h"
#include "translucency/materials.h"
#include "translucency/estimate.h"
#include "translucency/hermite.h"
#include "translucency/inverse.h"
#include "translucency/photo_lights.h"
#include "translucency/photo_estimate.h"
#include "translucency/photo_shape.h"
#include "translucency/render.h"

using namespace arcus;
using namespace arcus::api;
using namespace arcus::translucency;

namespace {

// Channel c of a caller's dipole, checked.
Channel channel_of(const arcus_dipole& d, int c) {
  const Channel ch{d.sigma_a[c], d.sigma_s_prime[c], d.eta};
  check_channel(ch, "dipole->", c);
  return ch;
}

void check_dipole(const arcus_dipole* d) {
  require_pointer(d, "dipole");
  check_eta(d->eta, "dipole->eta");
  for (int c = 0; c < 3; ++c) channel_of(*d, c);
}

void check_table(const arcus_profile_table* t) {
  require_pointer(t, "profile");
  require(t->count >= 2 && t->count <= 65536, "profile->count = " + std::to_string(t->count) + " is not 2..65536");
  require(std::isfinite(t->reach_mm) && t->reach_mm > 0,
          "profile->reach_mm = " + number(t->reach_mm) + " is not a finite distance > 0");
  require_pointer(t->values, "profile->values");
  check_eta(t->eta, "profile->eta");
  for (size_t i = 0; i < 3 * size_t(t->count); ++i)
    require(std::isfinite(t->values[i]) && t->values[i] >= 0,
            "profile->values[" + std::to_string(i) + "] = " + number(t->values[i]) + " (sample " +
                std::to_string(i / 3) + ", channel " + std::to_string(i % 3) + ") is not a finite R_d >= 0");
  bool any = false;
  for (size_t i = 0; i < 3 * size_t(t->count); ++i) any = any || t->values[i] > 0;
  require(any, "profile->values: every sample is 0 (nothing would leave the surface)");
}

// The caller's count of items of `per_item` doubles, refused when the arrays could not
// hold them (their size would overflow).
void check_count(size_t count, size_t per_item, const char* name) {
  require(count <= std::numeric_limits<size_t>::max() / (per_item * sizeof(double)),
          std::string(name) + " " + std::to_string(count) + " is beyond any array");
}

}  // namespace

extern "C" {

arcus_status arcus_translucency_dipole_get_terms(const arcus_dipole* dipole, arcus_dipole_terms* terms) {
  return without_context([&] {
    require_pointer(terms, "terms");
    check_dipole(dipole);
    *terms = dipole_terms(*dipole);
  });
}

arcus_status arcus_translucency_dipole_profile(const arcus_dipole* dipole, double scale, int32_t scaling,
                                               size_t count, const double* r_mm, double* rd) {
  return without_context([&] {
    check_dipole(dipole);
    require(std::isfinite(scale) && scale > 0, "scale = " + number(scale) + " is not a finite stretch > 0");
    require(scaling == ARCUS_PROFILE_SCALE_ENERGY || scaling == ARCUS_PROFILE_SCALE_THESIS,
            "scaling = " + std::to_string(scaling) +
                " is not ARCUS_PROFILE_SCALE_ENERGY (0) or ARCUS_PROFILE_SCALE_THESIS (1)");
    check_count(count, 3, "count");
    if (count == 0) return;
    require_pointer(r_mm, "r_mm");
    require_pointer(rd, "rd");
    for (size_t i = 0; i < count; ++i)
      require(std::isfinite(r_mm[i]) && r_mm[i] >= 0,
              "r_mm[" + std::to_string(i) + "] = " + number(r_mm[i]) + " is not a finite distance >= 0");
    // Stretching the profile by s: R_d(r/s), and /s² to keep ∫2πr R_d dr (§5.2).
    const double factor = scaling == ARCUS_PROFILE_SCALE_ENERGY ? 1 / (scale * scale) : 1;
    for (int c = 0; c < 3; ++c) {
      const Terms t = terms(channel_of(*dipole, c));
      for (size_t i = 0; i < count; ++i) rd[3 * i + c] = factor * diffuse_reflectance(t, r_mm[i] / scale);
    }
  });
}

arcus_status arcus_translucency_dipole_from_material(const char* name, arcus_dipole* out) {
  return without_context([&] {
    require_pointer(name, "name");
    require_pointer(out, "out");
    std::string known;
    for (size_t m = 0; m < kMaterialCount; ++m) {
      const Material& mat = kMaterials[m];
      if (std::strcmp(name, mat.name) == 0) {
        for (int c = 0; c < 3; ++c) {
          out->sigma_a[c] = mat.sigma_a[c];
          out->sigma_s_prime[c] = mat.sigma_s_prime[c];
        }
        out->eta = mat.eta;
        return;
      }
      known += std::string(known.empty() ? "" : ", ") + mat.name;
    }
    fail(ARCUS_ERROR_INVALID_ARGUMENT, "name: no measured material \"" + std::string(name).substr(0, 64) +
                                           "\" (known: " + known + ")");
  });
}

arcus_status arcus_translucency_material_name(uint32_t index, const char** name) {
  return without_context([&] {
    require_pointer(name, "name");
    require(index < kMaterialCount, "index " + std::to_string(index) + " is not below the " +
                                        std::to_string(kMaterialCount) + " measured materials");
    *name = kMaterials[index].name;
  });
}

arcus_status arcus_translucency_dipole_from_reflectance(const double total_reflectance[3],
                                                        const double diffuse_length[3], double eta,
                                                        arcus_dipole* out) {
  return without_context([&] {
    require_pointer(total_reflectance, "total_reflectance");
    require_pointer(diffuse_length, "diffuse_length");
    require_pointer(out, "out");
    check_eta(eta, "eta");
    arcus_dipole d{};
    d.eta = eta;
    for (int c = 0; c < 3; ++c) {
      const std::string at = "[" + std::to_string(c) + "]";
      const double total = total_reflectance[c], length = diffuse_length[c];
      require(total > 0 && total < 1,
              "total_reflectance" + at + " = " + number(total) + " is not between 0 and 1 (exclusive)");
      require(std::isfinite(length) && length > 0,
              "diffuse_length" + at + " = " + number(length) + " is not a finite length > 0 (mm)");
      // σ_tr = σ_t′·sqrt(3(1 − α′)), so σ_t′ follows from ℓ_d = 1/σ_tr once α′ is known.
      const double albedo = albedo_for_reflectance(total, eta);
      const double sigma_t_prime = 1 / (length * std::sqrt(3 * (1 - albedo)));
      require(std::isfinite(sigma_t_prime) && albedo > 0,
              "total_reflectance" + at + " = " + number(total) + " is too close to 0 or 1 for a dipole");
      d.sigma_s_prime[c] = albedo * sigma_t_prime;
      d.sigma_a[c] = sigma_t_prime - d.sigma_s_prime[c];
    }
    *out = d;
  });
}

arcus_status arcus_translucency_henyey_greenstein(double g, size_t count, const double* cos_theta, double* phase) {
  return without_context([&] {
    require(g > -1 && g < 1, "g = " + number(g) + " is not between -1 and 1 (exclusive)");
    check_count(count, 1, "count");
    if (count == 0) return;
    require_pointer(cos_theta, "cos_theta");
    require_pointer(phase, "phase");
    for (size_t i = 0; i < count; ++i)
      require(cos_theta[i] >= -1 && cos_theta[i] <= 1,
              "cos_theta[" + std::to_string(i) + "] = " + number(cos_theta[i]) + " is not in [-1, 1]");
    for (size_t i = 0; i < count; ++i) phase[i] = henyey_greenstein(g, cos_theta[i]);
  });
}

arcus_status arcus_translucency_fresnel_reflectance(double cos_i, double n1, double n2, double* reflectance) {
  return without_context([&] {
    require_pointer(reflectance, "reflectance");
    require(cos_i >= 0 && cos_i <= 1, "cos_i = " + number(cos_i) + " is not in [0, 1]");
    require(std::isfinite(n1) && n1 > 0, "n1 = " + number(n1) + " is not a finite refractive index > 0");
    require(std::isfinite(n2) && n2 > 0, "n2 = " + number(n2) + " is not a finite refractive index > 0");
    *reflectance = fresnel_reflectance(cos_i, n1, n2);
  });
}

arcus_status arcus_translucency_render_params_init(arcus_translucency_render_params* params) {
  return without_context([&] {
    require_pointer(params, "params");
    arcus_translucency_render_params p{};
    p.camera = arcus_camera{{0, 0, 5}, {0, 0, 0}, {0, 1, 0}, 30, 256, 256};
    p.mm_per_unit = 1;
    p.exit = ARCUS_EXIT_THESIS;
    p.profile_scale = 1;
    p.profile_scaling = ARCUS_PROFILE_SCALE_ENERGY;
    p.gather = ARCUS_GATHER_HIERARCHICAL;
    p.max_solid_angle = 0;  // automatic: render.h
    p.highlight_deg = 10;
    *params = p;
  });
}

namespace {

// Both renders alike once the profile is checked.
arcus_status render_with(arcus_context_t* ctx, arcus_mesh_t* mesh, const translucency::ProfileSource& profile,
                         bool tabulated, size_t light_count, const arcus_directional_light* lights,
                         const arcus_translucency_render_params* params, arcus_job_t** job) {
  return on<arcus_context_s>(ctx, kContextHandle, "ctx", [&](arcus_context_s*, std::string* message) {
    require_pointer(job, "job");
    *job = nullptr;
    const auto* m = object_of<arcus_mesh_s>(ctx, mesh, geometry::kMeshHandle, "mesh");
    if (tabulated) check_table(profile.table);
    else check_dipole(profile.dipole);
    require_pointer(params, "params");
    require(light_count <= 64, "light_count = " + std::to_string(light_count) + " is not 1..64");
    if (light_count > 0) require_pointer(lights, "lights");
    const std::vector<arcus_directional_light> list(lights, lights + light_count);
    bool cancelled = false;
    auto j = translucency::render(ctx, m->mesh, profile, list, *params, &cancelled);
    retain_context(ctx);  // the job's reference
    *job = j.release();
    if (!cancelled) return ARCUS_SUCCESS;
    *message = "the progress callback cancelled the render: pixels not reached are 0";
    return ARCUS_ERROR_CANCELLED;
  });
}

}  // namespace

arcus_status arcus_translucency_render(arcus_context_t* ctx, arcus_mesh_t* mesh, const arcus_dipole* dipole,
                                       size_t light_count, const arcus_directional_light* lights,
                                       const arcus_translucency_render_params* params, arcus_job_t** job) {
  translucency::ProfileSource profile;
  profile.dipole = dipole;
  return render_with(ctx, mesh, profile, false, light_count, lights, params, job);
}

arcus_status arcus_translucency_render_table(arcus_context_t* ctx, arcus_mesh_t* mesh,
                                             const arcus_profile_table* table, size_t light_count,
                                             const arcus_directional_light* lights,
                                             const arcus_translucency_render_params* params, arcus_job_t** job) {
  translucency::ProfileSource profile;
  profile.table = table;
  return render_with(ctx, mesh, profile, true, light_count, lights, params, job);
}

arcus_status arcus_job_get_translucency_stats(arcus_job_t* job, arcus_translucency_render_stats* stats) {
  return on_job<RenderJob>(job, "a translucency render", [&](RenderJob* j) {
    require_pointer(stats, "stats");
    *stats = j->render;
  });
}

arcus_status arcus_job_get_translucency_image(arcus_job_t* job, float* rgb, float* subsurface, uint8_t* covered) {
  return on_job<RenderJob>(job, "a translucency render", [&](RenderJob* j) {
    copy_out(j->rgb, rgb);
    copy_out(j->subsurface, subsurface);
    copy_out(j->covered, covered);
  });
}

arcus_status arcus_translucency_estimate_params_init(arcus_translucency_estimate_params* params) {
  return without_context([&] {
    require_pointer(params, "params");
    arcus_translucency_render_params render{};
    arcus_translucency_render_params_init(&render);
    arcus_translucency_estimate_params p{};
    p.camera = render.camera;
    p.mm_per_unit = 1;
    p.eta = 1.3;
    p.exit = ARCUS_EXIT_THESIS;
    p.basis_count = 24;
    p.basis = ARCUS_BASIS_PIECEWISE_CONSTANT;
    p.max_side = 200;
    p.remove_highlights = 1;
    p.subtract_minimum = 1;
    *params = p;
  });
}

arcus_status arcus_translucency_estimate(arcus_context_t* ctx, arcus_mesh_t* mesh, uint32_t width, uint32_t height,
                                         const float* photo, const uint8_t* matte, size_t light_count,
                                         const arcus_directional_light* lights,
                                         const arcus_translucency_estimate_params* params, arcus_job_t** job) {
  return on<arcus_context_s>(ctx, kContextHandle, "ctx", [&](arcus_context_s*, std::string* message) {
    require_pointer(job, "job");
    *job = nullptr;
    const auto* m = object_of<arcus_mesh_s>(ctx, mesh, geometry::kMeshHandle, "mesh");
    require_pointer(params, "params");
    require_pointer(photo, "photo");
    require(light_count <= 64, "light_count = " + std::to_string(light_count) + " is not 1..64");
    if (light_count > 0) require_pointer(lights, "lights");
    const std::vector<arcus_directional_light> list(lights, lights + light_count);
    bool cancelled = false;
    auto j = translucency::estimate(ctx, m->mesh, width, height, photo, matte, list, *params, &cancelled);
    retain_context(ctx);  // the job's reference
    *job = j.release();
    if (!cancelled) return ARCUS_SUCCESS;
    *message = "the progress callback cancelled the estimate: the profile is incomplete";
    return ARCUS_ERROR_CANCELLED;
  });
}

arcus_status arcus_translucency_detect_lights(arcus_context_t* ctx, uint32_t width, uint32_t height,
                                              const float* photo, const uint8_t* matte,
                                              arcus_light_detection* result) {
  return on<arcus_context_s>(ctx, kContextHandle, "ctx", [&](arcus_context_s*, std::string*) {
    require_pointer(result, "result");
    require_pointer(photo, "photo");
    *result = translucency::detect_lights(width, height, photo, matte);
    return ARCUS_SUCCESS;
  });
}

arcus_status arcus_translucency_photo_shape_params_init(arcus_photo_shape_params* params) {
  return without_context([&] {
    require_pointer(params, "params");
    *params = arcus_photo_shape_params{};
    params->method = ARCUS_DEPTH_BASE_DETAIL;
    params->sigma_spatial = 0.09;  // thesis §3.4: 0.08–0.1
    params->sigma_intensity = 0.4; // 0.3–0.5
    params->base_weight = 0.8;     // "usually 0.8 and 0.2"
    params->detail_weight = 0.2;
    params->inflation = 0;         // off: on one-light photos it costs 2–5° of normal (docs)
    params->relief = 1;
  });
}

arcus_status arcus_translucency_estimate_shape(arcus_context_t* ctx, uint32_t width, uint32_t height,
                                               const float* photo, const uint8_t* matte,
                                               const arcus_photo_shape_params* params, double* depth,
                                               double* normals, uint8_t* mask) {
  return on<arcus_context_s>(ctx, kContextHandle, "ctx", [&](arcus_context_s*, std::string*) {
    require_pointer(photo, "photo");
    require_pointer(params, "params");
    require_pointer(depth, "depth");
    require_pointer(normals, "normals");
    check_shape_params(*params);
    const PhotoObject object = find_object(width, height, photo, matte);
    const PhotoShape shape = estimate_shape(object, *params);
    const std::vector<double> photo_depth = at_photo_size(object, shape.depth, 1, object.scale);
    const std::vector<double> photo_normals = at_photo_size(object, shape.normals, 3, 1);
    std::copy(photo_depth.begin(), photo_depth.end(), depth);
    std::copy(photo_normals.begin(), photo_normals.end(), normals);
    if (mask) {
      const std::vector<uint8_t> photo_mask = at_photo_size(object, object.mask);
      std::copy(photo_mask.begin(), photo_mask.end(), mask);
    }
    return ARCUS_SUCCESS;
  });
}

arcus_status arcus_translucency_auto_params_init(arcus_translucency_auto_params* params) {
  return without_context([&] {
    require_pointer(params, "params");
    arcus_translucency_auto_params p{};
    arcus_translucency_estimate_params_init(&p.estimate);
    arcus_translucency_photo_shape_params_init(&p.shape);
    p.estimate.nonnegative = 1;        // a plausible profile: no oscillating bins
    p.estimate.remove_highlights = 0;  // the cut finds highlights in photos without one (docs)
    p.mm_per_pixel = 1;
    p.irradiance[0] = p.irradiance[1] = p.irradiance[2] = 1;
    *params = p;
  });
}

arcus_status arcus_translucency_estimate_auto(arcus_context_t* ctx, uint32_t width, uint32_t height,
                                              const float* photo, const uint8_t* matte,
                                              const arcus_translucency_auto_params* params, arcus_job_t** job) {
  return on<arcus_context_s>(ctx, kContextHandle, "ctx", [&](arcus_context_s*, std::string* message) {
    require_pointer(job, "job");
    *job = nullptr;
    require_pointer(params, "params");
    require_pointer(photo, "photo");
    bool cancelled = false;
    auto j = translucency::estimate_automatic(ctx, width, height, photo, matte, *params, &cancelled);
    retain_context(ctx);  // the job's reference
    *job = j.release();
    if (!cancelled) return ARCUS_SUCCESS;
    *message = "the progress callback cancelled the estimate: the profile is incomplete";
    return ARCUS_ERROR_CANCELLED;
  });
}

arcus_status arcus_job_get_translucency_auto(arcus_job_t* job, arcus_light_detection* lights, double* depth,
                                             double* normals, uint8_t* mask, size_t* vertex_count,
                                             size_t* triangle_count, double* positions, uint32_t* triangles) {
  return on_job<EstimateJob>(job, "a translucency estimate", [&](EstimateJob* j) {
    require(j->automatic, "job: an estimate given a mesh and lights, not one from the photo alone "
                          "(arcus_translucency_estimate_auto)");
    if (lights) *lights = j->lights;
    if (depth) std::copy(j->depth.begin(), j->depth.end(), depth);
    if (normals) std::copy(j->normals.begin(), j->normals.end(), normals);
    if (mask) std::copy(j->mask.begin(), j->mask.end(), mask);
    if (vertex_count) *vertex_count = j->relief.vertex_count();
    if (triangle_count) *triangle_count = j->relief.triangle_count();
    if (positions) std::copy(j->relief.positions.begin(), j->relief.positions.end(), positions);
    if (triangles) std::copy(j->relief.triangles.begin(), j->relief.triangles.end(), triangles);
  });
}

arcus_status arcus_job_get_translucency_estimate(arcus_job_t* job, arcus_translucency_estimate_result* result) {
  return on_job<EstimateJob>(job, "a translucency estimate", [&](EstimateJob* j) {
    require_pointer(result, "result");
    *result = j->result;
  });
}

arcus_status arcus_job_get_translucency_profile(arcus_job_t* job, double* edges, double* weights) {
  return on_job<EstimateJob>(job, "a translucency estimate", [&](EstimateJob* j) {
    copy_out(j->edges, edges);
    copy_out(j->weights, weights);
  });
}

arcus_status arcus_job_get_translucency_hermite(arcus_job_t* job, uint32_t count, double* values) {
  return on_job<EstimateJob>(job, "a translucency estimate", [&](EstimateJob* j) {
    require(count >= 2 && count <= 65536, "count = " + std::to_string(count) + " is not 2..65536");
    require_pointer(values, "values");
    const size_t m = j->result.basis_count;
    for (int c = 0; c < 3; ++c) {
      std::vector<double> averages(m);
      for (size_t h = 0; h < m; ++h) averages[h] = j->weights[h * 3 + size_t(c)];
      const std::vector<double> curve = translucency::monotone_hermite_profile(j->edges, averages, count);
      for (uint32_t k = 0; k < count; ++k) values[3 * size_t(k) + size_t(c)] = curve[k];
    }
  });
}

arcus_status arcus_job_get_translucency_system(arcus_job_t* job, uint32_t channel, double* a, double* b, double* x) {
  return on_job<EstimateJob>(job, "a translucency estimate", [&](EstimateJob* j) {
    require(channel < 3, "channel = " + std::to_string(channel) + " is not 0, 1 or 2");
    const size_t n = j->result.equation_pixels, m = j->result.basis_count;
    auto part = [&](const std::vector<double>& all, size_t size) {
      return std::vector<double>(all.begin() + long(channel * size), all.begin() + long((channel + 1) * size));
    };
    copy_out(part(j->a, n * m), a);
    copy_out(part(j->b, n), b);
    copy_out(part(j->x, m), x);
  });
}

arcus_status arcus_job_get_translucency_sources(arcus_job_t* job, double* rows, double* sources,
                                                double* source_weights, double* near_irradiance) {
  return on_job<EstimateJob>(job, "a translucency estimate", [&](EstimateJob* j) {
    copy_out(j->rows, rows);
    copy_out(j->sources, sources);
    copy_out(j->source_weights, source_weights);
    copy_out(j->near, near_irradiance);
  });
}

arcus_status arcus_job_get_translucency_sub_sources(arcus_job_t* job, double* points, double* weights) {
  return on_job<EstimateJob>(job, "a translucency estimate", [&](EstimateJob* j) {
    copy_out(j->sub_sources, points);
    copy_out(j->sub_source_weights, weights);
  });
}

arcus_status arcus_translucency_genetic_params_init(int32_t model, arcus_genetic_params* params) {
  return without_context([&] {
    require_pointer(params, "params");
    require(model == ARCUS_GENETIC_DIPOLE || model == ARCUS_GENETIC_PHONG,
            "model = " + std::to_string(model) + " is not ARCUS_GENETIC_DIPOLE (0) or ARCUS_GENETIC_PHONG (1)");
    arcus_translucency_render_params render{};
    arcus_translucency_render_params_init(&render);
    arcus_genetic_params p{};
    p.camera = render.camera;
    p.mm_per_unit = 1;
    p.model = model;
    p.population = 40;
    p.generations = 50;
    p.replacement = p.crossover = p.mutation = 0.8;
    p.mutation_range = 0.3;
    p.polish_steps = 20;
    p.fitness_space = ARCUS_FITNESS_YCBCR;
    translucency::genetic_defaults(model, &p);
    *params = p;
  });
}

arcus_status arcus_translucency_genetic(arcus_context_t* ctx, arcus_mesh_t* mesh, uint32_t width, uint32_t height,
                                        const float* target, size_t light_count, const arcus_directional_light* lights,
                                        const arcus_genetic_params* params, arcus_job_t** job) {
  return on<arcus_context_s>(ctx, kContextHandle, "ctx", [&](arcus_context_s*, std::string* message) {
    require_pointer(job, "job");
    *job = nullptr;
    const auto* m = object_of<arcus_mesh_s>(ctx, mesh, geometry::kMeshHandle, "mesh");
    require_pointer(params, "params");
    require_pointer(target, "target");
    require(light_count <= 64, "light_count = " + std::to_string(light_count) + " is not 1..64");
    if (light_count > 0) require_pointer(lights, "lights");
    const std::vector<arcus_directional_light> list(lights, lights + light_count);
    bool cancelled = false;
    auto j = translucency::genetic_inverse(ctx, m->mesh, width, height, target, list, *params, &cancelled);
    retain_context(ctx);  // the job's reference
    *job = j.release();
    if (!cancelled) return ARCUS_SUCCESS;
    *message = "the search was cancelled: the history so far is kept";
    return ARCUS_ERROR_CANCELLED;
  });
}

arcus_status arcus_job_get_translucency_genetic(arcus_job_t* job, arcus_genetic_result* result) {
  return on_job<translucency::GeneticJob>(job, "a genetic search", [&](translucency::GeneticJob* j) {
    require_pointer(result, "result");
    *result = j->result;
  });
}

arcus_status arcus_job_get_translucency_genetic_history(arcus_job_t* job, double* best_fitness, double* mean_fitness,
                                                        double* best_genes) {
  return on_job<translucency::GeneticJob>(job, "a genetic search", [&](translucency::GeneticJob* j) {
    copy_out(j->best_fitness, best_fitness);
    copy_out(j->mean_fitness, mean_fitness);
    copy_out(j->best_genes, best_genes);
  });
}

arcus_status arcus_job_get_translucency_genetic_image(arcus_job_t* job, float* rgb) {
  return on_job<translucency::GeneticJob>(job, "a genetic search", [&](translucency::GeneticJob* j) {
    require_pointer(rgb, "rgb");
    copy_out(j->image, rgb);
  });
}

}  // extern "C"
