#include "render/shading.h"

#include <algorithm>
#include <cmath>

#include "image/image_io.h"
#include "render/photons.h"
#include "render/sky_light.h"
#include "render/surface.h"
#include "render/trace.h"

namespace arcus::render {
namespace {

Vec3 sky_radiance(const RenderScene& s, Vec3 d) {
  const SkyDesc& sky = s.desc.sky;
  switch (sky.kind) {
    case SkyKind::Constant: return sky.color;
    case SkyKind::Gradient: {
      const double t = std::clamp(d.y, 0.0, 1.0);
      return (1 - t) * sky.horizon + t * sky.zenith;
    }
    case SkyKind::Image:
    case SkyKind::Daylight: {
      const auto uv = image::equirect_uv(d.x, d.y, d.z);
      const auto c = image::sample_bilinear(s.sky_image, uv[0], uv[1], true);
      // A daylight panorama is made with its intensity (scene.cpp); an image is scaled here.
      return (sky.kind == SkyKind::Image ? sky.intensity : 1.0) * Vec3{c[0], c[1], c[2]};
    }
  }
  return {0, 0, 0};
}

// Light `light`'s shadow rays b (at `p`), traced; or, while the camera and the scene
// rest (the batch the same bit for bit as the last frame's), predicted from the last
// frame's end steps (smart step selection) and, with path caching, walked along the
// paths the last frame recorded (static lights, thesis §4.3.2.4): the same hits without
// integrating.  With either technique b's origins and directions move into that memory.
TraceOutput shadow_rays(arcus_context_t* ctx, arcus_renderer_s* r, size_t light, const arcus_advance_params& p,
                        bool occlusion, Batch& b, arcus_render_stats* st) {
  auto input = [&](const Batch& x, bool predict) {
    TraceInput in = x.input(predict);
    in.occlusion = occlusion;
    in.from_surface = true;
    return in;
  };
  const bool smart = r->techniques & ARCUS_TECHNIQUE_SMART_STEP;
  const bool cache = r->techniques & ARCUS_TECHNIQUE_PATH_CACHE;
  if (!smart && !cache) return trace(ctx, r->scene, p, input(b, false));
  if (r->shadow_memory.size() <= light) r->shadow_memory.resize(light + 1);
  ShadowMemory& mem = r->shadow_memory[light];
  const bool same = mem.origins == b.origins && mem.directions == b.directions;
  const bool predict = same && smart;
  if (predict) b.predictions = mem.end_step;
  TraceOutput t;
  if (same && cache && mem.paths) {
    std::vector<WalkRay> rays(b.size());
    for (size_t k = 0; k < rays.size(); ++k) rays[k].a = static_cast<int32_t>(k);
    t = walk(ctx, r->scene, p, *mem.paths, rays, MirrorPlane{}, predict ? b.predictions.data() : nullptr, occlusion);
    // Walks that came to the end of a path cut short (its room was full): traced.
    Batch unresolved;
    for (size_t k = 0; k < b.size(); ++k)
      if (t.status[k] == ARCUS_STATUS_UNRESOLVED) unresolved.add(vec3(&b.origins[3 * k]), vec3(&b.directions[3 * k]), k, -1);
    if (unresolved.size()) {
      const TraceOutput u = trace(ctx, r->scene, p, input(unresolved, false));
      for (size_t k = 0; k < unresolved.size(); ++k) t.copy_ray(unresolved.pixels[k], u, k);
    }
  } else if (cache) {
    uint64_t steps = same ? mem.steps_p999 : 0;
    if (steps == 0) {  // a probe of every 16th ray
      Batch probe;
      for (size_t k = 0; k < b.size(); k += kCoarse * kCoarse)
        probe.add(vec3(&b.origins[3 * k]), vec3(&b.directions[3 * k]), k, -1);
      double seconds = 0;
      steps = probe_steps(ctx, r->scene, p, probe, &seconds);
    }
    mem.paths = std::make_unique<DevicePaths>();
    t = record_paths(ctx, r->scene, p, input(b, predict), path_room(steps), mem.paths.get());
    prove_chunks(ctx, r->scene, p, mem.paths.get());
  } else {
    t = trace(ctx, r->scene, p, input(b, predict));
  }
  mem.origins = std::move(b.origins);
  mem.directions = std::move(b.directions);
  mem.end_step.resize(b.size());
  for (size_t k = 0; k < b.size(); ++k) mem.end_step[k] = end_step_of(t.status[k], t.hit_step[k]);
  mem.steps_p999 = percentile999(t.steps);
  if (!cache) mem.paths.reset();
  if (mem.paths) st->cache_bytes += mem.paths->bytes();
  return t;
}

}  // namespace

namespace {

// Per pixel: the radiance so far, and at a hit the surface and its albedo.
struct Shading {
  std::vector<Vec3> radiance, albedo;
  std::vector<Surface> surfaces;
};

// Each pixel's surface and its own light (a hit's emission; under a daylight sky, the
// sky's light on it too: sky_light.h), or the sky it sees.  The image is `width` wide.
Shading surfaces_and_sky(const RenderScene& s, const Primary& prim, int width) {
  const size_t n = prim.status.size();
  Shading sh;
  sh.radiance.assign(n, Vec3{0, 0, 0});
  sh.albedo.assign(n, Vec3{0, 0, 0});
  sh.surfaces.resize(n);
  std::vector<int32_t> object(n, -1);
  for (size_t p = 0; p < n; ++p) {
    if (prim.status[p] != ARCUS_STATUS_HIT) continue;
    sh.surfaces[p] = surface_at(s, prim.kind[p], prim.index[p], vec3(&prim.position[3 * p]), vec3(&prim.direction[3 * p]));
    object[p] = prim.object[p];
  }
  set_footprints(object, width, &sh.surfaces);
  const bool sky_light = !s.sky_irradiance.pixels.empty();
  for (size_t p = 0; p < n; ++p) {
    const Vec3 d = vec3(&prim.direction[3 * p]);
    if (prim.status[p] == ARCUS_STATUS_HIT) {
      const ObjectDesc& o = s.desc.objects[static_cast<size_t>(prim.object[p])];
      const MaterialDesc& m = s.desc.materials[static_cast<size_t>(o.material)];
      sh.albedo[p] = albedo(s, static_cast<size_t>(o.material), sh.surfaces[p]);
      sh.radiance[p] = m.emission;
      if (sky_light) {
        const Vec3 e = sky_irradiance(s.sky_irradiance, sh.surfaces[p].normal), a = sh.albedo[p];
        sh.radiance[p] = sh.radiance[p] + (1 / M_PI) * Vec3{a.x * e.x, a.y * e.y, a.z * e.z};
      }
    } else if (prim.status[p] == ARCUS_STATUS_LEFT_BOX || prim.status[p] == ARCUS_STATUS_DONE ||
               prim.status[p] == ARCUS_STATUS_STEP_LIMIT) {
      sh.radiance[p] = sky_radiance(s, d);
    }
  }
  return sh;
}

// Curved photon mapping (thesis §4.3.4, render/photons.h): the photons' irradiance at
// every hit, in place of the direct light of shadow rays.
void add_photon_light(arcus_context_t* ctx, arcus_renderer_s* r, const Primary& prim, Shading* sh, RenderJob* job) {
  const RenderScene& s = *r->scene;
  PhotonStats ps;
  if (!r->photon_cache) r->photon_cache = std::make_unique<PhotonCache>();
  PhotonOptions po;
  po.techniques = r->techniques;  // the renderer's techniques apply to the photons' first generation too
  po.cache = r->photon_cache.get();
  const auto map = shoot_photons(ctx, r->scene, r->params, s.desc.photons.count, /*seed=*/1, &ps, po);
  job->render_stats.photon_seconds = ps.seconds;
  job->render_stats.photons = ps.stored;
  std::vector<double> points, normals;
  std::vector<size_t> hit_pixels;
  for (size_t p = 0; p < prim.status.size(); ++p) {
    if (prim.status[p] != ARCUS_STATUS_HIT) continue;
    const Vec3 normal = sh->surfaces[p].normal;
    points.insert(points.end(), &prim.position[3 * p], &prim.position[3 * p] + 3);
    normals.insert(normals.end(), {normal.x, normal.y, normal.z});
    hit_pixels.push_back(p);
  }
  const std::vector<double> e = photon_irradiance(ctx, *map, s, points, normals);
  for (size_t k = 0; k < hit_pixels.size(); ++k) {
    const size_t p = hit_pixels[k];
    const Vec3 a = sh->albedo[p];
    sh->radiance[p] = sh->radiance[p] + (1 / M_PI) * Vec3{a.x * e[3 * k], a.y * e[3 * k + 1], a.z * e[3 * k + 2]};
  }
}

// Light `li`'s direct light at every hit that faces it, through shadow rays along the
// curved medium.
void add_direct_light(arcus_context_t* ctx, arcus_renderer_s* r, const Primary& prim, size_t li, Shading* sh,
                      RenderJob* job) {
  const RenderScene& s = *r->scene;
  const LightDesc& light = s.desc.lights[li];
  Batch b;
  std::vector<double> cosine, falloff;
  for (size_t p = 0; p < prim.status.size(); ++p) {
    if (prim.status[p] != ARCUS_STATUS_HIT) continue;
    const Vec3 hit = vec3(&prim.position[3 * p]), nrm = sh->surfaces[p].normal;
    Vec3 to = light.kind == LightKind::Sun ? light.direction : light.position - hit;
    const double dist2 = dot(to, to);
    to = normalized(to);
    const double c = dot(nrm, to);
    if (!(c > 0)) continue;
    b.add(hit + surface_offset(s) * nrm, to, p, -1);
    cosine.push_back(c);
    falloff.push_back(light.kind == LightKind::Sun ? 1.0 : 1.0 / dist2);
  }
  if (b.size() == 0) return;
  arcus_advance_params p = r->params;
  if (light.kind == LightKind::Point) p.length = 0;  // set per ray below: one job per light
  std::vector<double> reach(b.size(), p.length);
  if (light.kind == LightKind::Point) {
    // Every shadow ray of a point light stops at the light's distance: the longest one
    // sets the job's length, and a hit beyond a ray's own distance does not block it.
    for (size_t k = 0; k < b.size(); ++k) {
      const Vec3 o = vec3(&b.origins[3 * k]);
      reach[k] = length(light.position - o);
      p.length = std::max(p.length, reach[k]);
    }
  }
  // Toward a sun any hit blocks: where does not matter.  A point light's blocker must
  // lie nearer than the light, so its hits are found exactly.
  const TraceOutput t = shadow_rays(ctx, r, li, p, light.kind == LightKind::Sun, b, &job->render_stats);
  job->features |= t.features;
  job->render_stats.shadow_rays += b.size();
  for (size_t k = 0; k < b.size(); ++k) {
    const bool blocked = t.status[k] == ARCUS_STATUS_HIT && t.lengths[k] < reach[k];
    const bool failed = t.status[k] == ARCUS_STATUS_FAILED || t.status[k] == ARCUS_STATUS_INVALID_INPUT;
    if (blocked || failed) continue;
    const size_t px = b.pixels[k];
    const double w = cosine[k] * falloff[k] / M_PI;
    const Vec3 a = sh->albedo[px];
    sh->radiance[px] =
        sh->radiance[px] + Vec3{w * a.x * light.power[0], w * a.y * light.power[1], w * a.z * light.power[2]};
  }
}

}  // namespace

void shade(arcus_context_t* ctx, arcus_renderer_s* r, const Primary& prim, RenderJob* job) {
  const RenderScene& s = *r->scene;
  Shading sh = surfaces_and_sky(s, prim, static_cast<int>(r->camera.width));
  if (s.desc.photons.count > 0) {
    add_photon_light(ctx, r, prim, &sh, job);
  } else {
    for (size_t li = 0; li < s.desc.lights.size(); ++li) add_direct_light(ctx, r, prim, li, &sh, job);
  }
  const size_t n = prim.status.size();
  job->rgb.assign(3 * n, 0.f);
  for (size_t p = 0; p < n; ++p) {
    job->rgb[3 * p] = static_cast<float>(sh.radiance[p].x);
    job->rgb[3 * p + 1] = static_cast<float>(sh.radiance[p].y);
    job->rgb[3 * p + 2] = static_cast<float>(sh.radiance[p].z);
  }
}

namespace {

// Planck's law, relative: B(λ, T) / B(555 nm, T).
double planck_relative(double nm, double kelvin) {
  const double c2 = 1.438776877e-2;  // m·K, second radiation constant
  auto b = [&](double lambda) { return 1 / (std::pow(lambda, 5) * std::expm1(c2 / (lambda * kelvin))); };
  return b(nm * 1e-9) / b(555e-9);
}

// Rayleigh optical depth of the whole atmosphere at sea level, vertically (Hansen and
// Travis 1974, eq. 2.29, λ in µm), scaled by the sea-level pressure.
double rayleigh_depth(double nm, double pressure) {
  const double l = nm * 1e-3;
  return 0.008569 / std::pow(l, 4) * (1 + 0.0113 / (l * l) + 0.00013 / std::pow(l, 4)) * pressure / 101325.0;
}

// Relative air mass at apparent elevation h (degrees) (Kasten and Young 1989): 1 at the
// zenith, about 38 at the horizon; the formula holds to h = 0 and a little below.
double air_mass(double h_deg) {
  const double h = std::max(h_deg, -2.0);
  return 1 / (std::sin(h * M_PI / 180) + 0.50572 * std::pow(h + 6.07995, -1.6364));
}

}  // namespace

double spectral_radiance(const RenderScene& s, const Frame& f, const Primary& prim, size_t p, const float* rgb,
                         double nm) {
  if (prim.status[p] == ARCUS_STATUS_HIT) {
    const MaterialDesc& m = s.desc.materials[static_cast<size_t>(s.desc.objects[static_cast<size_t>(prim.object[p])].material)];
    if (m.blackbody_k > 0) {
      double L = (m.emission[0] + m.emission[1] + m.emission[2]) / 3 * planck_relative(nm, m.blackbody_k);
      const bool atmosphere = s.field->desc.kind == ARCUS_KIND_ATMOSPHERE;
      if (atmosphere && prim.length[p] > 1e5) {
        // The apparent elevation: the primary ray's start against the local horizontal.
        const Vec3 up = s.field->desc.spherical ? normalized(f.origin) : Vec3{0, 1, 0};
        const Vec3 d = normalized(vec3(&prim.start[3 * p]));
        const double h = std::asin(std::clamp(dot(d, up), -1.0, 1.0)) * 180 / M_PI;
        L *= std::exp(-rayleigh_depth(nm, s.desc.medium.atmosphere.sea_level_pressure) * air_mass(h));
      }
      return L;
    }
  }
  return nm < 490 ? rgb[2] : nm < 580 ? rgb[1] : rgb[0];
}

}  // namespace arcus::render
