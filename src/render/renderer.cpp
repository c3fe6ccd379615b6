#include "render/renderer.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <limits>

#include "core/error.h"
#include "core/limits.h"
#include "image/image_io.h"
#include "spectral/cie.h"
#include "spectral/srgb.h"
#include "render/photons.h"
#include "render/surface.h"
#include "render/trace.h"

arcus_renderer_s::arcus_renderer_s(arcus_context_t* ctx, arcus::render::RenderScene* s)
    : Handle(arcus::HandleType::Renderer, ctx), scene(s), camera(s->desc.camera), techniques(s->desc.techniques),
      params(s->desc.params) {
  scene->retain();
}

arcus_renderer_s::~arcus_renderer_s() {
  // Deleted under the context's lock (release_object): the scene goes the same way.
  if (scene->drop()) {
    delete scene;
    arcus::release_context(owner());
  }
}

namespace arcus::render {
namespace {

using Clock = std::chrono::steady_clock;
double since(Clock::time_point t) { return std::chrono::duration<double>(Clock::now() - t).count(); }

// The 99.9th percentile of the rays' step counts (0 for none): recorded paths get room
// for it (recorded step by step, the room past a region's longest path is never touched).
uint64_t percentile999(std::vector<uint64_t> steps) {
  if (steps.empty()) return 0;
  const size_t at = steps.size() * 999 / 1000;
  std::nth_element(steps.begin(), steps.begin() + static_cast<std::ptrdiff_t>(at), steps.end());
  return steps[at];
}


// The camera's frame: forward, right and true up.
struct Frame {
  V3 origin, forward, right, up;
  double tan_half, aspect;
};

Frame camera_frame(const CameraDesc& c) {
  Frame f;
  f.origin = v3(c.position);
  f.forward = normalized(v3(c.look_at) - f.origin);
  f.right = normalized(cross(f.forward, v3(c.up)));
  f.up = cross(f.right, f.forward);
  f.tan_half = std::tan(0.5 * c.vfov_deg * M_PI / 180.0);
  f.aspect = static_cast<double>(c.width) / c.height;
  return f;
}

// Pixel (i, j)'s direction: through its centre, rows top to bottom.
V3 pixel_direction(const Frame& f, const CameraDesc& c, uint32_t i, uint32_t j) {
  const double px = (2.0 * (i + 0.5) / c.width - 1.0) * f.tan_half * f.aspect;
  const double py = (1.0 - 2.0 * (j + 0.5) / c.height) * f.tan_half;
  return f.forward + px * f.right + py * f.up;
}

// A batch of rays to trace and where their results go.
struct Batch {
  std::vector<double> origins, directions;
  std::vector<int32_t> predictions;
  std::vector<size_t> pixels;
  void add(V3 o, V3 d, size_t pixel, int32_t prediction) {
    origins.insert(origins.end(), {o.x, o.y, o.z});
    directions.insert(directions.end(), {d.x, d.y, d.z});
    predictions.push_back(prediction);
    pixels.push_back(pixel);
  }
  size_t size() const { return pixels.size(); }
  // The trace's input, predicting with `predictions` if asked.
  TraceInput input(bool predict) const {
    TraceInput in;
    in.count = size();
    in.origins = origins.data();
    in.directions = directions.data();
    in.predictions = predict ? predictions.data() : nullptr;
    return in;
  }
};

// The 99.9th percentile of the steps of a probe's rays, traced directly (time into *seconds).
uint64_t probe_steps(arcus_context_t* ctx, RenderScene* scene, const arcus_advance_params& params, const Batch& probe,
                     double* seconds) {
  const TraceOutput t = trace(ctx, scene, params, probe.input(false));
  *seconds += t.stats.total_seconds;
  return percentile999(t.steps);
}

// A predicted "end step" for a ray that hits nothing: beyond any path.
constexpr int32_t kNoHit = std::numeric_limits<int32_t>::max();

// What smart step selection predicts from a ray's result: the step that hit, kNoHit for
// a ray that left the scene, -1 for a failed ray.
int32_t end_step_of(int32_t status, int32_t hit_step) {
  if (status == ARCUS_STATUS_HIT) return hit_step;
  return status == ARCUS_STATUS_LEFT_BOX || status == ARCUS_STATUS_DONE ? kNoHit : -1;
}

// Room for recorded paths: all but the longest few of paths whose 99.9th percentile of
// steps is `steps`, and a quarter more (a percentile from a sample, or from the last
// frame, is only an estimate).  The memory is count × room, and a path cut short only
// sends the few rays that walk past its end to be traced.
uint32_t path_room(uint64_t steps) {
  return static_cast<uint32_t>(std::min<uint64_t>(steps + steps / 4 + 4, 1u << 20));
}

// Every pixel's primary result.
struct Primary {
  std::vector<int32_t> status, object, primitive, kind, index, hit_step, tests;
  // What smart step selection predicts from: the step that hit, kNoHit for a ray that
  // left the scene (a neighbour expecting no hit skips its tests to its end and proves
  // the steps empty), -1 for a failed ray.
  std::vector<int32_t> end_step;
  std::vector<double> position, direction, length;
  std::vector<double> start;  // the primary ray's initial direction
  arcus_features features = 0;  // compiled by the programs that traced or walked them
  std::vector<uint64_t> steps;
  explicit Primary(size_t n)
      : status(n, ARCUS_STATUS_FAILED), object(n, -1), primitive(n, -1), kind(n, 0), index(n, -1), hit_step(n, -1),
        tests(n, 0), end_step(n, -1), position(3 * n, NAN), direction(3 * n, 0), length(n, 0), start(3 * n, 0),
        steps(n, 0) {}
};

// Stores a trace's or walk's results per pixel.
void store(const TraceOutput& t, const std::vector<size_t>& pixels, Primary* out) {
  for (size_t k = 0; k < pixels.size(); ++k) {
    const size_t p = pixels[k];
    out->tests[p] = t.tests[k];
    out->steps[p] = t.steps[k];
    out->status[p] = t.status[k];
    out->object[p] = t.object[k];
    out->primitive[p] = t.primitive[k];
    out->kind[p] = t.hit_kind[k];
    out->index[p] = t.hit_index[k];
    out->hit_step[p] = t.hit_step[k];
    out->end_step[p] = end_step_of(t.status[k], t.hit_step[k]);
    out->length[p] = t.lengths[k];
    for (int a = 0; a < 3; ++a) {
      out->position[3 * p + a] = t.positions[3 * k + a];
      out->direction[3 * p + a] = t.directions[3 * k + a];
    }
  }
}

// Traces a batch of primary rays, all at `wavelength` (nm; NaN: the medium's own).
void trace_batch(arcus_context_t* ctx, arcus_renderer_s* r, const Batch& b, bool predict, double wavelength,
                 Primary* out, arcus_render_stats* st) {
  TraceInput in = b.input(predict);
  const std::vector<double> wavelengths(std::isnan(wavelength) ? 0 : b.size(), wavelength);
  if (!wavelengths.empty()) in.wavelengths = wavelengths.data();
  const TraceOutput t = trace(ctx, r->scene, r->params, in);
  st->trace_seconds += t.stats.total_seconds;
  st->rays_traced += b.size();
  store(t, b.pixels, out);
  out->features |= t.features;
  for (size_t k = 0; k < b.size(); ++k)
    std::copy(&b.directions[3 * k], &b.directions[3 * k] + 3, &out->start[3 * b.pixels[k]]);
}

// Smart step selection's spatial prediction (thesis §4.3.3), coarse to fine: every
// 16th pixel in each direction is traced first, then every 4th and 2nd predicting from the
// grid around it, down to the rest.  A pixel predicts the least end step of the four
// grid pixels around it: the step that hit, or none (kNoHit) where all four left the
// scene without a hit (the thesis' scenes end every ray on geometry; here rays that
// see the sky skip all their tests, and the proofs cover the skipped steps).
constexpr uint32_t kCoarse = 4;                 // the probe of recorded paths' room
constexpr uint32_t kSpatialStrides[] = {16, 4, 2};  // the grids traced before the rest

int32_t spatial_prediction(const Primary& grid, const CameraDesc& c, uint32_t stride, uint32_t i, uint32_t j) {
  const uint32_t i0 = i / stride * stride, j0 = j / stride * stride;
  const uint32_t i1 = std::min(i0 + stride, (c.width - 1) / stride * stride);
  const uint32_t j1 = std::min(j0 + stride, (c.height - 1) / stride * stride);
  int32_t least = std::numeric_limits<int32_t>::max();
  for (uint32_t jj : {j0, j1})
    for (uint32_t ii : {i0, i1}) {
      const size_t p = static_cast<size_t>(jj) * c.width + ii;
      if (grid.end_step[p] < 0) return -1;
      least = std::min(least, grid.end_step[p]);
    }
  return least;
}

// ---- shading --------------------------------------------------------------------------

V3 sky_radiance(const RenderScene& s, V3 d) {
  const SkyDesc& sky = s.desc.sky;
  switch (sky.kind) {
    case SkyKind::Constant: return v3(sky.color);
    case SkyKind::Gradient: {
      const double t = std::clamp(d.y, 0.0, 1.0);
      return (1 - t) * v3(sky.horizon) + t * v3(sky.zenith);
    }
    case SkyKind::Image: {
      const auto uv = image::equirect_uv(d.x, d.y, d.z);
      const auto c = image::sample_bilinear(s.sky_image, uv[0], uv[1], true);
      return sky.intensity * V3{c[0], c[1], c[2]};
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
      if (t.status[k] == ARCUS_STATUS_UNRESOLVED) unresolved.add(v3(&b.origins[3 * k]), v3(&b.directions[3 * k]), k, -1);
    if (unresolved.size()) {
      const TraceOutput u = trace(ctx, r->scene, p, input(unresolved, false));
      for (size_t k = 0; k < unresolved.size(); ++k) t.copy_ray(unresolved.pixels[k], u, k);
    }
  } else if (cache) {
    uint64_t steps = same ? mem.steps_p999 : 0;
    if (steps == 0) {  // a probe of every 16th ray
      Batch probe;
      for (size_t k = 0; k < b.size(); k += kCoarse * kCoarse)
        probe.add(v3(&b.origins[3 * k]), v3(&b.directions[3 * k]), k, -1);
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

// Direct light at every hit pixel: a curved shadow ray from the hit toward each light
// (starting along the straight direction to it), traced through the medium; the
// light counts where the ray reaches it unblocked.
void shade(arcus_context_t* ctx, arcus_renderer_s* r, const Primary& prim, RenderJob* job) {
  const RenderScene& s = *r->scene;
  const size_t n = prim.status.size();
  job->rgb.assign(3 * n, 0.f);
  std::vector<V3> radiance(n, V3{0, 0, 0}), base(n, V3{0, 0, 0});
  std::vector<Surface> surfaces(n);
  const double scale = std::max({s.hi[0] - s.lo[0], s.hi[1] - s.lo[1], s.hi[2] - s.lo[2]});
  for (size_t p = 0; p < n; ++p) {
    const V3 d = v3(&prim.direction[3 * p]);
    if (prim.status[p] == ARCUS_STATUS_HIT) {
      const ObjectDesc& o = s.desc.objects[static_cast<size_t>(prim.object[p])];
      const MaterialDesc& m = s.desc.materials[static_cast<size_t>(o.material)];
      surfaces[p] = surface_at(s, prim.kind[p], prim.index[p], v3(&prim.position[3 * p]), d);
      base[p] = albedo(s, static_cast<size_t>(o.material), surfaces[p]);
      radiance[p] = v3(m.emission);
    } else if (prim.status[p] == ARCUS_STATUS_LEFT_BOX || prim.status[p] == ARCUS_STATUS_DONE ||
               prim.status[p] == ARCUS_STATUS_STEP_LIMIT) {
      radiance[p] = sky_radiance(s, d);
    }
  }
  if (s.desc.photons.count > 0) {
    // Curved photon mapping (thesis §4.3.4, render/photons.h): the photons' irradiance
    // replaces the direct light of shadow rays.
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
    for (size_t p = 0; p < n; ++p) {
      if (prim.status[p] != ARCUS_STATUS_HIT) continue;
      points.insert(points.end(), &prim.position[3 * p], &prim.position[3 * p] + 3);
      normals.insert(normals.end(), {surfaces[p].normal.x, surfaces[p].normal.y, surfaces[p].normal.z});
      hit_pixels.push_back(p);
    }
    const std::vector<double> e = photon_irradiance(ctx, *map, s, points, normals);
    for (size_t k = 0; k < hit_pixels.size(); ++k) {
      const size_t p = hit_pixels[k];
      radiance[p] = radiance[p] + (1 / M_PI) * V3{base[p].x * e[3 * k], base[p].y * e[3 * k + 1],
                                                  base[p].z * e[3 * k + 2]};
    }
  }
  const size_t lights = s.desc.photons.count > 0 ? 0 : s.desc.lights.size();
  for (size_t li = 0; li < lights; ++li) {
    const LightDesc& light = s.desc.lights[li];
    Batch b;
    std::vector<double> cosine, falloff;
    for (size_t p = 0; p < n; ++p) {
      if (prim.status[p] != ARCUS_STATUS_HIT) continue;
      const V3 hit = v3(&prim.position[3 * p]), nrm = surfaces[p].normal;
      V3 to = light.kind == LightKind::Sun ? v3(light.direction) : v3(light.position) - hit;
      const double dist2 = dot(to, to);
      to = normalized(to);
      const double c = dot(nrm, to);
      if (!(c > 0)) continue;
      // Off the surface by a little more than the crossing tolerance, so the shadow ray
      // does not find its own surface again.
      const double offset = 1e-6 * scale + 1e-4;
      b.add(hit + offset * nrm, to, p, -1);
      cosine.push_back(c);
      falloff.push_back(light.kind == LightKind::Sun ? 1.0 : 1.0 / dist2);
    }
    if (b.size() == 0) continue;
    arcus_advance_params p = r->params;
    if (light.kind == LightKind::Point) p.length = 0;  // set per ray below: one job per light
    std::vector<double> reach(b.size(), p.length);
    if (light.kind == LightKind::Point) {
      // Every shadow ray of a point light stops at the light's distance: the longest one
      // sets the job's length, and a hit beyond a ray's own distance does not block it.
      for (size_t k = 0; k < b.size(); ++k) {
        const V3 o = v3(&b.origins[3 * k]);
        reach[k] = std::sqrt(dot(v3(light.position) - o, v3(light.position) - o));
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
      radiance[px] = radiance[px] + V3{w * base[px].x * light.power[0], w * base[px].y * light.power[1],
                                       w * base[px].z * light.power[2]};
    }
  }
  for (size_t p = 0; p < n; ++p) {
    job->rgb[3 * p] = static_cast<float>(radiance[p].x);
    job->rgb[3 * p + 1] = static_cast<float>(radiance[p].y);
    job->rgb[3 * p + 2] = static_cast<float>(radiance[p].z);
  }
}

}  // namespace

namespace {

// Why the medium is not symmetric about the camera's vertical plane (the plane through
// the camera holding its view and up directions), "" if it is (thesis §4.3.2.2): then
// every path of the image's right half is the mirror image of one of the left half.
std::string asymmetry(const arcus_renderer_s& r) {
  const Frame f = camera_frame(r.camera);
  MirrorPlane plane;
  for (int a = 0; a < 3; ++a) plane.normal[a] = (&f.right.x)[a];
  plane.offset = dot(f.right, f.origin);
  const std::string why = medium_asymmetry(r.scene->field->desc, plane);
  return why.empty() ? "" : why + " (the camera's vertical plane)";
}

// Every pixel's path for the path-based techniques: the traced pixels' paths
// integrated and recorded up to their hits (their results stored in *prim at once),
// the others mirrored (symmetry) or interpolated between their traced neighbours
// (undersampling) as they are walked.  `traced_pixels` lists the traced ones.
PathFrame pixel_paths(arcus_context_t* ctx, arcus_renderer_s* r, const Frame& f, uint32_t capacity_hint,
                      const std::vector<int32_t>* previous, Primary* prim, std::vector<char>* traced_pixels,
                      arcus_render_stats* st) {
  const CameraDesc& c = r->camera;
  const bool symmetric = r->techniques & ARCUS_TECHNIQUE_SYMMETRY;
  const bool under = r->techniques & ARCUS_TECHNIQUE_UNDERSAMPLE;
  const uint32_t half = symmetric ? (c.width + 1) / 2 : c.width;  // the columns computed
  // Undersampling traces a checkerboard (α = ½) and interpolates the others between
  // their left and right neighbours, which must both be traced: the first and last
  // computed columns are traced whole.
  auto traced = [&](uint32_t i, uint32_t j) { return !under || (i + j) % 2 == 0 || i == 0 || i + 1 == half; };
  Batch b;
  std::vector<int32_t> slot(static_cast<size_t>(c.width) * c.height, -1);
  traced_pixels->assign(slot.size(), 0);
  for (uint32_t j = 0; j < c.height; ++j)
    for (uint32_t i = 0; i < half; ++i)
      if (traced(i, j)) {
        const size_t p = static_cast<size_t>(j) * c.width + i;
        slot[p] = static_cast<int32_t>(b.size());
        (*traced_pixels)[p] = 1;
        b.add(f.origin, pixel_direction(f, c, i, j), p, previous ? (*previous)[p] : -1);
      }
  PathFrame frame;
  const TraceOutput t = record_paths(ctx, r->scene, r->params, b.input(previous != nullptr), capacity_hint, &frame.paths);
  frame.features = t.features;
  st->trace_seconds += t.stats.total_seconds;
  st->rays_traced += b.size();
  store(t, b.pixels, prim);
  // The mirror: the plane through the camera normal to its right axis.
  for (int a = 0; a < 3; ++a) frame.plane.normal[a] = (&f.right.x)[a];
  frame.plane.offset = dot(f.right, f.origin);
  frame.rays.resize(slot.size());
  for (uint32_t j = 0; j < c.height; ++j)
    for (uint32_t i = 0; i < c.width; ++i) {
      const size_t p = static_cast<size_t>(j) * c.width + i;
      WalkRay& w = frame.rays[p];
      if (i >= half) {
        w = frame.rays[static_cast<size_t>(j) * c.width + (c.width - 1 - i)];
        w.mirror = 1;
        ++st->rays_mirrored;
      } else if (slot[p] >= 0) {
        w.a = slot[p];
      } else {
        w.a = slot[p - 1];
        w.b = slot[p + 1];
        ++st->rays_interpolated;
      }
    }
  return frame;
}

}  // namespace

namespace {

// The primary rays of a frame traced directly (no stored paths), smart step selection
// predicting from the last frame or from a coarse first pass; at `wavelength` (nm) or,
// for NaN, the medium's own.
void direct_pass(arcus_context_t* ctx, arcus_renderer_s* r, const Frame& f, double wavelength, Primary* prim,
                 arcus_render_stats* st) {
  const CameraDesc& c = r->camera;
  const size_t n = static_cast<size_t>(c.width) * c.height;
  const bool smart = r->techniques & ARCUS_TECHNIQUE_SMART_STEP;
  const bool temporal = smart && r->previous_hit_step.size() == n && std::isnan(wavelength);
  r->cached_paths.reset();
  if (!smart || temporal) {
    Batch all;
    for (uint32_t j = 0; j < c.height; ++j)
      for (uint32_t i = 0; i < c.width; ++i) {
        const size_t p = static_cast<size_t>(j) * c.width + i;
        all.add(f.origin, pixel_direction(f, c, i, j), p, temporal ? r->previous_hit_step[p] : -1);
      }
    trace_batch(ctx, r, all, temporal, wavelength, prim, st);
    return;
  }
  // Coarse to fine: level 0 is the grid of kSpatialStrides[0], traced without
  // prediction; each later level predicts from the one before.
  const size_t levels = std::size(kSpatialStrides) + 1;
  auto level_of = [&](uint32_t i, uint32_t j) {
    for (size_t l = 0; l < std::size(kSpatialStrides); ++l)
      if (i % kSpatialStrides[l] == 0 && j % kSpatialStrides[l] == 0) return l;
    return levels - 1;
  };
  for (size_t level = 0; level < levels; ++level) {
    Batch b;
    for (uint32_t j = 0; j < c.height; ++j)
      for (uint32_t i = 0; i < c.width; ++i)
        if (level_of(i, j) == level)
          b.add(f.origin, pixel_direction(f, c, i, j), static_cast<size_t>(j) * c.width + i,
                level == 0 ? -1 : spatial_prediction(*prim, c, kSpatialStrides[level - 1], i, j));
    trace_batch(ctx, r, b, level > 0, wavelength, prim, st);
  }
}

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

// Pixel p's spectral radiance at `nm` from its RGB shading: a blackbody emitter gives
// Planck's spectrum at its temperature (scaled by its emission's mean), dimmed by
// Rayleigh extinction along the air mass of the ray's apparent elevation when it lies
// beyond the atmosphere (the sun); any other RGB value stands for the band of its
// channel (blue below 490 nm, green to 580 nm, red above).
double spectral_radiance(const RenderScene& s, const Frame& f, const Primary& prim, size_t p, const float* rgb,
                         double nm) {
  if (prim.status[p] == ARCUS_STATUS_HIT) {
    const MaterialDesc& m = s.desc.materials[static_cast<size_t>(s.desc.objects[static_cast<size_t>(prim.object[p])].material)];
    if (m.blackbody_k > 0) {
      double L = (m.emission[0] + m.emission[1] + m.emission[2]) / 3 * planck_relative(nm, m.blackbody_k);
      const bool atmosphere = s.field->desc.kind == ARCUS_KIND_ATMOSPHERE;
      if (atmosphere && prim.length[p] > 1e5) {
        // The apparent elevation: the primary ray's start against the local horizontal.
        const V3 up = s.field->desc.spherical ? normalized(f.origin) : V3{0, 1, 0};
        const V3 d = normalized(v3(&prim.start[3 * p]));
        const double h = std::asin(std::clamp(dot(d, up), -1.0, 1.0)) * 180 / M_PI;
        L *= std::exp(-rayleigh_depth(nm, s.desc.medium.atmosphere.sea_level_pressure) * air_mass(h));
      }
      return L;
    }
  }
  return nm < 490 ? rgb[2] : nm < 580 ? rgb[1] : rgb[0];
}

}  // namespace

std::string technique_problem(const arcus_renderer_s& r, uint32_t techniques) {
  if (techniques & ~static_cast<uint32_t>(ARCUS_TECHNIQUE_ALL))
    return "techniques: unknown bits " + std::to_string(techniques & ~static_cast<uint32_t>(ARCUS_TECHNIQUE_ALL));
  const uint32_t path_based = ARCUS_TECHNIQUE_SYMMETRY | ARCUS_TECHNIQUE_UNDERSAMPLE | ARCUS_TECHNIQUE_PATH_CACHE;
  if ((techniques & path_based) && !r.scene->desc.wavelengths.empty())
    return "techniques: symmetry, undersampling and path caching work on RGB scenes; a spectral scene traces each "
           "wavelength's rays through the dispersive medium (use smart_step)";
  if ((techniques & ARCUS_TECHNIQUE_SYMMETRY) && r.scene->desc.photons.count > 0) {
    const std::string why = photon_asymmetry(*r.scene, nullptr);
    if (!why.empty()) return "techniques: symmetry of the photons: " + why;
  }
  if (techniques & ARCUS_TECHNIQUE_SYMMETRY) {
    const std::string why = asymmetry(r);
    if (!why.empty()) return "techniques: symmetry needs a medium symmetric about the camera's vertical plane: " + why;
  }
  return "";
}

namespace {

// The primary rays of a frame through stored paths: the cached paths walked again, or
// the traced pixels' paths recorded now and the other pixels' walked along mirrored
// and interpolated ones; rays whose walk is unresolved are traced.  Smart step
// selection predicts from the last frame, or from the pixels a walked ray derives from.
void walk_frame(arcus_context_t* ctx, arcus_renderer_s* r, const Frame& f, Primary* prim, arcus_render_stats* st) {
  const CameraDesc& c = r->camera;
  const size_t n = static_cast<size_t>(c.width) * c.height;
  const bool cache = r->techniques & ARCUS_TECHNIQUE_PATH_CACHE;
  const bool smart = r->techniques & ARCUS_TECHNIQUE_SMART_STEP;
  const bool temporal = smart && r->previous_hit_step.size() == n;
  const std::vector<int32_t>* previous = temporal ? &r->previous_hit_step : nullptr;
  std::unique_ptr<PathFrame> fresh;
  const PathFrame* paths = nullptr;
  std::vector<char> done(n, 0);
  if (cache && r->cached_paths && r->cached_paths->rays.size() == n) {
    paths = r->cached_paths.get();
    st->rays_cached = n;
  } else {
    // Room for the paths the last frame saw (else a probe's).
    uint64_t steps = r->previous_steps;
    if (steps == 0) {
      // No frame yet: a coarse probe (every 16th pixel), which costs a sixteenth of a frame.
      Batch probe;
      for (uint32_t j = 0; j < c.height; j += kCoarse)
        for (uint32_t i = 0; i < c.width; i += kCoarse)
          probe.add(f.origin, pixel_direction(f, c, i, j), static_cast<size_t>(j) * c.width + i, -1);
      steps = probe_steps(ctx, r->scene, r->params, probe, &st->trace_seconds);
    }
    const uint32_t hint = path_room(steps);
    fresh = std::make_unique<PathFrame>(pixel_paths(ctx, r, f, hint, previous, prim, &done, st));
    paths = fresh.get();
  }
  prim->features |= paths->features;
  const auto walk_start = Clock::now();
  // The cache's chunks proved once, for the walks of this frame and the later ones.
  if (fresh && cache) prove_chunks(ctx, r->scene, r->params, &fresh->paths);
  auto walk_pixels = [&](const std::vector<size_t>& pixels, const std::vector<int32_t>& predictions) {
    if (pixels.empty()) return;
    std::vector<WalkRay> rays;
    rays.reserve(pixels.size());
    for (size_t p : pixels) rays.push_back(paths->rays[p]);
    const TraceOutput t =
        walk(ctx, r->scene, r->params, paths->paths, rays, paths->plane, smart ? predictions.data() : nullptr);
    store(t, pixels, prim);
    prim->features |= t.features;
  };
  // The left half first: a mirrored pixel predicts its mirror image's end step.
  for (int half = 0; half < 2; ++half) {
    std::vector<size_t> pixels;
    std::vector<int32_t> predictions;
    for (uint32_t j = 0; j < c.height; ++j)
      for (uint32_t i = 0; i < c.width; ++i) {
        const size_t p = static_cast<size_t>(j) * c.width + i;
        const WalkRay& w = paths->rays[p];
        if (done[p] || (w.mirror != 0) != (half == 1)) continue;
        int32_t predicted = -1;
        if (previous) {
          predicted = (*previous)[p];
        } else if (w.mirror) {
          predicted = prim->end_step[static_cast<size_t>(j) * c.width + (c.width - 1 - i)];
        } else if (w.b >= 0) {
          const int32_t a = prim->end_step[p - 1], b = prim->end_step[p + 1];
          predicted = a < 0 || b < 0 ? -1 : std::min(a, b);
        }
        pixels.push_back(p);
        predictions.push_back(predicted);
      }
    walk_pixels(pixels, predictions);
  }
  st->walk_seconds += since(walk_start);
  // Walks that ran past the end of a path cut short by a hit: traced from the start.
  Batch unresolved;
  for (uint32_t j = 0; j < c.height; ++j)
    for (uint32_t i = 0; i < c.width; ++i) {
      const size_t p = static_cast<size_t>(j) * c.width + i;
      if (prim->status[p] == ARCUS_STATUS_UNRESOLVED) unresolved.add(f.origin, pixel_direction(f, c, i, j), p, -1);
    }
  if (unresolved.size()) {
    st->rays_unresolved += unresolved.size();
    std::vector<int32_t> walked_tests;
    for (size_t p : unresolved.pixels) walked_tests.push_back(prim->tests[p]);
    trace_batch(ctx, r, unresolved, false, NAN, prim, st);
    for (size_t k = 0; k < unresolved.size(); ++k) prim->tests[unresolved.pixels[k]] += walked_tests[k];
  }
  if (cache) {
    if (fresh) r->cached_paths = std::move(fresh);
    st->cache_bytes = r->cached_paths->paths.bytes() + r->cached_paths->rays.size() * sizeof(WalkRay);
  } else {
    r->cached_paths.reset();
  }
}

}  // namespace

namespace {

// A trace's progress as a share of the frame's: base + span · fraction.
struct StageProgress {
  arcus_progress_callback callback;
  void* user;
  double base, span;
};

int forward_progress(void* user, double fraction) {
  const StageProgress* s = static_cast<const StageProgress*>(user);
  return s->callback(s->user, std::min(s->base + s->span * fraction, 1.0));
}

// The renderer's integrator reports to `stage` while the frame runs (none: no callback).
class ProgressScope {
 public:
  ProgressScope(arcus_renderer_s* r, StageProgress* stage) : r_(r) {
    r_->params.progress = stage ? forward_progress : nullptr;
    r_->params.progress_user = stage;
  }
  ~ProgressScope() {
    r_->params.progress = nullptr;
    r_->params.progress_user = nullptr;
  }
  ProgressScope(const ProgressScope&) = delete;
  ProgressScope& operator=(const ProgressScope&) = delete;

 private:
  arcus_renderer_s* r_;
};

}  // namespace

std::unique_ptr<RenderJob> render_frame(arcus_renderer_s* r, arcus_progress_callback progress, void* user) {
  const auto start = Clock::now();
  arcus_context_t* ctx = r->owner();
  const CameraDesc& c = r->camera;
  const std::string problem = technique_problem(*r, r->techniques);
  if (!problem.empty()) fail(ARCUS_ERROR_UNSUPPORTED, problem);
  const size_t n = static_cast<size_t>(c.width) * c.height;
  // What a frame holds on the host at once: per pixel its primary ray's state, the
  // traced batch and the job's image and hits (under 512 bytes), per photon its state
  // and its place in the map (under 256).
  limits::require_host_memory(512.0 * n + 256.0 * r->scene->desc.photons.count,
                              "a " + std::to_string(c.width) + " x " + std::to_string(c.height) + " frame" +
                                  (r->scene->desc.photons.count
                                       ? " with " + std::to_string(r->scene->desc.photons.count) + " photons"
                                       : std::string()));
  auto job = std::make_unique<RenderJob>(ctx);
  arcus_render_stats& st = job->render_stats;
  st.techniques = r->techniques;
  st.pixels = n;
  const Frame f = camera_frame(c);
  Primary prim(n);
  auto report = [&](double fraction) {
    if (progress && progress(user, fraction) != 0) fail(ARCUS_ERROR_CANCELLED, "the progress callback cancelled the frame");
  };
  // The traces report to the frame's callback too (as the primary rays' share of the
  // frame), so a long trace shows progress and can be cancelled within.
  StageProgress stage{progress, user, 0.0, 0.8};
  const ProgressScope scope(r, progress ? &stage : nullptr);

  const uint32_t path_based = ARCUS_TECHNIQUE_SYMMETRY | ARCUS_TECHNIQUE_UNDERSAMPLE | ARCUS_TECHNIQUE_PATH_CACHE;
  const std::vector<double>& wavelengths = r->scene->desc.wavelengths;
  report(0.0);
  double shade_seconds = 0;
  if (!wavelengths.empty()) {
    // Spectral (thesis §2.2; README, "Spectral rendering"): each wavelength's rays are
    // traced through the dispersive medium and shaded, and the spectral radiance is
    // integrated against the CIE 1931 colour-matching functions into XYZ, then sRGB.
    r->cached_paths.reset();
    const auto weights = spectral::band_weights(wavelengths);
    std::vector<std::array<double, 3>> xyz(n, std::array<double, 3>{0, 0, 0});
    for (size_t k = 0; k < wavelengths.size(); ++k) {
      Primary pk(n);
      direct_pass(ctx, r, f, wavelengths[k], &pk, &st);
      const auto t = Clock::now();
      shade(ctx, r, pk, job.get());
      for (size_t p = 0; p < n; ++p) {
        const double L = spectral_radiance(*r->scene, f, pk, p, &job->rgb[3 * p], wavelengths[k]);
        for (int c3 = 0; c3 < 3; ++c3) xyz[p][c3] += L * weights[k][c3];
      }
      shade_seconds += since(t);
      job->features |= pk.features;
      if (k == 0) prim = std::move(pk);  // the figures of the first wavelength
      report(0.8 * (k + 1) / wavelengths.size());
      stage.base = 0.8 * (k + 1) / wavelengths.size();
      stage.span = 0.8 / wavelengths.size();
    }
    for (size_t p = 0; p < n; ++p) {
      const auto rgb = spectral::xyz_to_linear_srgb(xyz[p]);
      for (int c3 = 0; c3 < 3; ++c3) job->rgb[3 * p + c3] = static_cast<float>(rgb[c3]);
    }
  } else {
    if (r->techniques & path_based)
      walk_frame(ctx, r, f, &prim, &st);
    else
      direct_pass(ctx, r, f, NAN, &prim, &st);
    report(0.8);
    const auto t = Clock::now();
    shade(ctx, r, prim, job.get());
    shade_seconds = since(t);
  }
  st.shade_seconds = shade_seconds - st.photon_seconds;  // shade() shoots the photons too

  image::require_finite_pixels(job->rgb, static_cast<int>(c.width), "RGB", "the render");
  job->width = c.width;
  job->height = c.height;
  job->exposure = r->scene->desc.exposure;
  job->count = n;
  job->points = std::move(prim.position);
  job->objects = std::move(prim.object);
  job->primitives = std::move(prim.primitive);
  job->distances = std::move(prim.length);
  job->steps.resize(n);
  job->tests.resize(n);
  for (size_t p = 0; p < n; ++p) {
    job->steps[p] = static_cast<uint32_t>(prim.steps[p]);
    job->tests[p] = static_cast<uint32_t>(prim.tests[p]);
    st.steps += prim.steps[p];
    st.tests += static_cast<uint64_t>(prim.tests[p]);
  }
  r->previous_hit_step = std::move(prim.end_step);
  // Room enough in the next frame's recorded paths for all but a few.
  r->previous_steps = percentile999(prim.steps);
  job->features |= prim.features;
  st.total_seconds = since(start);
  job->stats.total_seconds = st.total_seconds;
  report(1.0);
  return job;
}

}  // namespace arcus::render
