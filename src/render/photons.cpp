#include "render/photons.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <string>

#include "core/error.h"
#include "render/photon_cache.h"
#include "render/photon_emission.h"
#include "render/photon_interpolation.h"
#include "render/surface.h"
#include "render/trace.h"

namespace arcus::render {
namespace {

using Clock = std::chrono::steady_clock;

constexpr uint64_t kMaxPhotons = uint64_t(1) << 26;  // the schema's limit ($.photons.count)
// Generations (trace() calls): diffuse bounces plus crossings of window primitives.
constexpr int kMaxGenerations = 2 * (kMaxPhotonBounces + 1);

// The surface at a hit: the normal facing the arriving photon and the albedo (diffuse ×
// texture), as the renderer shades it (render/surface.h).
struct HitSurface {
  Vec3 normal;
  double albedo[3];
  bool window;
};

HitSurface surface_at(const RenderScene& s, int32_t object, int32_t kind, int32_t index, Vec3 p, Vec3 arriving) {
  const size_t material = static_cast<size_t>(s.desc.objects[static_cast<size_t>(object)].material);
  const Surface surface = render::surface_at(s, kind, index, p, arriving);
  const Vec3 a = albedo(s, material, surface);
  return {surface.normal, {a.x, a.y, a.z}, s.desc.materials[material].name == kWindowMaterial};
}

// The step a ray's trace ended on: the hit's, or the last for a ray that left (the
// renderer's end_step); -1 for none.
int32_t end_step(const TraceOutput& t, size_t k) {
  if (t.status[k] == ARCUS_STATUS_HIT) return t.hit_step[k];
  if (t.status[k] == ARCUS_STATUS_LEFT_BOX || t.status[k] == ARCUS_STATUS_DONE)
    return static_cast<int32_t>(std::min<uint64_t>(t.steps[k], INT32_MAX));
  return -1;
}

// A first generation's results, one entry per photon (the trace outputs' layout).
TraceOutput empty_results(size_t n) {
  TraceOutput t;
  t.positions.assign(3 * n, NAN);
  t.directions.assign(3 * n, 0);
  t.lengths.assign(n, 0);
  t.steps.assign(n, 0);
  t.status.assign(n, ARCUS_STATUS_FAILED);
  t.object.assign(n, -1);
  t.primitive.assign(n, -1);
  t.hit_kind.assign(n, ARCUS_HIT_NONE);
  t.hit_index.assign(n, -1);
  t.hit_step.assign(n, -1);
  t.tests.assign(n, 0);
  return t;
}

// A batch of photons to trace.
struct Batch {
  std::vector<double> origins, directions;
  void add(const Live& p) {
    origins.insert(origins.end(), {p.origin.x, p.origin.y, p.origin.z});
    directions.insert(directions.end(), {p.direction.x, p.direction.y, p.direction.z});
  }
  TraceInput input(const int32_t* predictions) const {
    TraceInput in;
    in.count = origins.size() / 3;
    in.origins = origins.data();
    in.directions = directions.data();
    in.predictions = predictions;
    return in;
  }
};

void count_trace(const TraceOutput& t, bool integrated, PhotonStats* st) {
  for (size_t k = 0; k < t.status.size(); ++k) {
    st->tests += static_cast<uint64_t>(std::max(t.tests[k], 0));
    if (integrated) st->steps += t.steps[k];
  }
  if (integrated) st->traced += t.status.size();
}

// ---- the first generation's results, step by step ---------------------------------------

// What the steps of first_results share: the photons, the techniques, and the results
// so far (one slot per photon).
struct FirstPass {
  arcus_context_t* ctx;
  RenderScene* scene;
  const arcus_advance_params& params;
  const Emission& e;
  const PhotonOptions& o;
  const MirrorPlane* plane;              // SYMMETRY's, or null
  const std::vector<int32_t>* previous;  // SMART_STEP's temporal predictions, or null
  bool smart;
  std::vector<int32_t> partner;  // SYMMETRY: each photon's mirror, or -1
  TraceOutput out;
  std::vector<int32_t>* how;
  PhotonStats* st;
  // Photons to trace after all (unresolved mirrors, interpolations off one plane), with
  // their predicted end steps.
  std::vector<uint32_t> fallback;
  std::vector<int32_t> fallback_pred;

  FirstPass(arcus_context_t* c, RenderScene* s, const arcus_advance_params& p, const Emission& em,
            const PhotonOptions& opt, const MirrorPlane* pl, const std::vector<int32_t>* prev,
            std::vector<int32_t>* h, PhotonStats* stats)
      : ctx(c), scene(s), params(p), e(em), o(opt), plane(pl), previous(prev),
        smart(opt.techniques & ARCUS_TECHNIQUE_SMART_STEP), partner(em.live.size(), -1),
        out(empty_results(em.live.size())), how(h), st(stats) {
    how->assign(e.live.size(), kFirstTraced);
    for (size_t i = 0; i < e.live.size(); ++i)
      if (e.mirror_of[i] >= 0) partner[static_cast<size_t>(e.mirror_of[i])] = static_cast<int32_t>(i);
    if (previous && previous->size() != e.live.size()) previous = nullptr;  // another emission
  }
  bool temporal() const { return smart && previous; }
};

// Smart step selection of the computed photons: temporal predictions (the last frame's,
// photon by photon), or a coarse set traced first and the rest predicted from the
// nearest coarse photon within t.
struct SmartSteps {
  std::vector<uint32_t> coarse, rest;
  std::vector<SamplingGrid> grids;  // per light: the coarse photons
  std::vector<double> radius;       // per light: t

  SmartSteps(const FirstPass& f, const std::vector<uint32_t>& computed) {
    if (!f.smart || f.temporal()) {
      coarse = computed;  // one pass
      return;
    }
    const RenderScene& s = *f.scene;
    const size_t lights = s.desc.lights.size();
    grids.resize(lights);
    radius.resize(lights);
    for (size_t l = 0; l < lights; ++l) {
      radius[l] = sampling_radius(s, static_cast<uint32_t>(l), f.o.smart_step_deg);
      grids[l].h = radius[l] / 2;
      grids[l].flat = s.desc.lights[l].kind == LightKind::Sun;
    }
    std::vector<uint32_t> found;
    for (uint32_t i : computed) {
      SamplingGrid& g = grids[f.e.light[i]];
      g.nearest(f.e.key, f.e.key[i], radius[f.e.light[i]], 1, &found);
      if (!found.empty()) {
        rest.push_back(i);
      } else {
        coarse.push_back(i);
        g.insert(f.e.key[i], i);
      }
    }
  }
  // Photon i's predicted end step (-1: none), once the coarse photons are traced.
  int32_t predict(const FirstPass& f, uint32_t i) const {
    if (f.temporal()) return (*f.previous)[i];
    if (!f.smart || grids.empty()) return -1;
    std::vector<uint32_t> nearest;
    grids[f.e.light[i]].nearest(f.e.key, f.e.key[i], radius[f.e.light[i]], 1, &nearest);
    return nearest.empty() ? -1 : end_step(f.out, nearest[0]);
  }
};

// The computed photons: traced; with SYMMETRY traced with their paths recorded
// (record_paths) and their mirrors walked along those mirrored, in chunks that bound
// the recorded paths' memory.  A mirror whose walk is unresolved (the mirrored path
// ended on a hit, the mirror image hits nothing there: the geometry is not symmetric)
// is traced after all.
void trace_computed(FirstPass* f, const SmartSteps& smart) {
  constexpr size_t kChunk = size_t(1) << 15;
  uint32_t hint = 64;
  for (const auto* pass : {&smart.coarse, &smart.rest}) {
    const size_t chunk = f->plane ? kChunk : std::max<size_t>(pass->size(), 1);
    for (size_t c0 = 0; c0 < pass->size(); c0 += chunk) {
      const size_t c1 = std::min(pass->size(), c0 + chunk);
      Batch b;
      std::vector<int32_t> pred;
      for (size_t k = c0; k < c1; ++k) {
        b.add(f->e.live[(*pass)[k]]);
        pred.push_back(smart.predict(*f, (*pass)[k]));
      }
      const TraceInput input = b.input(f->smart ? pred.data() : nullptr);
      DevicePaths paths;
      const TraceOutput t = f->plane ? record_paths(f->ctx, f->scene, f->params, input, hint, &paths)
                                     : trace(f->ctx, f->scene, f->params, input);
      count_trace(t, true, f->st);
      for (size_t k = c0; k < c1; ++k) f->out.copy_ray((*pass)[k], t, k - c0);
      if (!f->plane) continue;
      hint = std::max<uint32_t>(hint, paths.capacity);
      std::vector<WalkRay> rays;
      std::vector<uint32_t> mirrors;
      pred.clear();
      for (size_t k = c0; k < c1; ++k) {
        const int32_t m = f->partner[(*pass)[k]];
        if (m < 0) continue;
        WalkRay w;
        w.a = static_cast<int32_t>(k - c0);
        w.mirror = 1;
        rays.push_back(w);
        mirrors.push_back(static_cast<uint32_t>(m));
        pred.push_back(f->temporal() ? (*f->previous)[static_cast<size_t>(m)] : end_step(t, k - c0));  // the same steps
      }
      if (rays.empty()) continue;
      const TraceOutput mt =
          walk(f->ctx, f->scene, f->params, paths, rays, *f->plane, f->smart ? pred.data() : nullptr);
      count_trace(mt, false, f->st);
      for (size_t k = 0; k < rays.size(); ++k) {
        if (mt.status[k] == ARCUS_STATUS_UNRESOLVED) {
          f->fallback.push_back(mirrors[k]);
          f->fallback_pred.push_back(-1);
          continue;
        }
        f->out.copy_ray(mirrors[k], mt, k);
        (*f->how)[mirrors[k]] = kFirstMirrored;
        ++f->st->mirrored;
      }
    }
  }
}

// The interpolated photons (and their mirrors, from their neighbours' mirrors); those
// whose neighbours do not share a plane are traced after all.
void interpolate_photons(FirstPass* f, const Undersampling& u) {
  for (uint32_t i : u.interpolated) {
    std::vector<std::pair<uint32_t, std::vector<uint32_t>>> pending = {{i, u.neighbours[i]}};
    if (f->partner[i] >= 0) {
      std::vector<uint32_t> mirrored;
      for (uint32_t k : u.neighbours[i]) mirrored.push_back(static_cast<uint32_t>(f->partner[k]));
      pending.push_back({static_cast<uint32_t>(f->partner[i]), mirrored});
    }
    for (const auto& [j, nb] : pending) {
      if (interpolate(*f->scene, f->out, nb, u.weights[i], &f->out, j)) {
        (*f->how)[j] = kFirstInterpolated;
        ++f->st->interpolated;
      } else {
        f->fallback.push_back(j);
        f->fallback_pred.push_back(f->temporal() ? (*f->previous)[j] : end_step(f->out, nb[0]));
      }
    }
  }
}

void trace_fallbacks(FirstPass* f) {
  if (f->fallback.empty()) return;
  Batch b;
  for (uint32_t i : f->fallback) b.add(f->e.live[i]);
  const TraceOutput t = trace(f->ctx, f->scene, f->params, b.input(f->smart ? f->fallback_pred.data() : nullptr));
  count_trace(t, true, f->st);
  for (size_t k = 0; k < f->fallback.size(); ++k) {
    f->out.copy_ray(f->fallback[k], t, k);
    (*f->how)[f->fallback[k]] = kFirstFallback;
  }
}

// PhotonOptions::measure_interpolation: the interpolated hits against the same photons
// traced.
void measure_interpolation(FirstPass* f) {
  PhotonStats* st = f->st;
  Batch b;
  std::vector<uint32_t> which;
  for (size_t i = 0; i < f->e.live.size(); ++i)
    if ((*f->how)[i] == kFirstInterpolated) {
      b.add(f->e.live[i]);
      which.push_back(static_cast<uint32_t>(i));
    }
  const TraceOutput t = trace(f->ctx, f->scene, f->params, b.input(nullptr));
  double sum = 0;
  for (size_t k = 0; k < which.size(); ++k) {
    if (t.status[k] != ARCUS_STATUS_HIT) continue;
    const double err = length(vec3(&t.positions[3 * k]) - vec3(&f->out.positions[3 * which[k]]));
    sum += err;
    st->interpolation_error_max = std::max(st->interpolation_error_max, err);
    ++st->interpolation_measured;
  }
  if (st->interpolation_measured) st->interpolation_error_mean = sum / st->interpolation_measured;
}

// The first generation's results (every photon of e), with the techniques of `o`.
TraceOutput first_results(arcus_context_t* ctx, RenderScene* scene, const arcus_advance_params& params,
                          const Emission& e, const PhotonOptions& o, const MirrorPlane* plane,
                          const std::vector<int32_t>* previous, std::vector<int32_t>* how, PhotonStats* st) {
  FirstPass f(ctx, scene, params, e, o, plane, previous, how, st);
  Undersampling u;
  if (o.techniques & ARCUS_TECHNIQUE_UNDERSAMPLE) {
    u = choose_interpolated(*scene, e, o);
  } else {
    for (size_t i = 0; i < e.live.size(); ++i)
      if (e.mirror_of[i] < 0) u.computed.push_back(static_cast<uint32_t>(i));
  }
  trace_computed(&f, SmartSteps(f, u.computed));
  interpolate_photons(&f, u);
  trace_fallbacks(&f);
  if (o.measure_interpolation && st->interpolated > 0) measure_interpolation(&f);
  return std::move(f.out);
}

// The first generation: from the cache, or emitted and computed (and cached).
void first_generation_of(arcus_context_t* ctx, RenderScene* scene, const arcus_advance_params& params,
                         uint64_t count, uint64_t seed, double offset, const PhotonOptions& o,
                         std::vector<Live>* live, TraceOutput* results, std::vector<int32_t>* how, PhotonStats* st) {
  PhotonCache::Data* cache = o.cache ? o.cache->data.get() : nullptr;
  const auto key = cache_key(scene, params, count, seed, o);
  const bool same = cache && cache->key == key;
  if (cache && !same) {  // another configuration: nothing of the last frame applies
    *cache = PhotonCache::Data{};
    cache->key = key;
  }
  if ((o.techniques & ARCUS_TECHNIQUE_PATH_CACHE) && same && cache->has_paths) {
    *live = cache->live;
    *results = cache->results;
    how->assign(live->size(), kFirstCached);
    st->cached = live->size();
    return;
  }
  MirrorPlane plane;
  const bool symmetric = o.techniques & ARCUS_TECHNIQUE_SYMMETRY;
  if (symmetric) {
    const std::string why = photon_asymmetry(*scene, &plane);
    if (!why.empty()) fail(ARCUS_ERROR_UNSUPPORTED, why);
  }
  Emission e = emit(*scene, count, seed, offset, symmetric ? &plane : nullptr);
  *results = first_results(ctx, scene, params, e, o, symmetric ? &plane : nullptr,
                           same && !cache->previous_end.empty() ? &cache->previous_end : nullptr, how, st);
  *live = std::move(e.live);
  if (cache) {
    cache->previous_end.clear();
    if (o.techniques & ARCUS_TECHNIQUE_SMART_STEP)
      for (size_t k = 0; k < live->size(); ++k) cache->previous_end.push_back(end_step(*results, k));
    cache->has_paths = o.techniques & ARCUS_TECHNIQUE_PATH_CACHE;
    if (cache->has_paths) {
      cache->live = *live;
      cache->results = *results;
    } else {
      cache->live.clear();
      cache->results = TraceOutput{};
    }
  }
}

void check_arguments(arcus_context_t* ctx, RenderScene* scene, uint64_t count) {
  require_pointer(ctx, "ctx");
  require_pointer(scene, "scene");
  require(count >= 1 && count <= kMaxPhotons, "photons: count = " + std::to_string(count) + " is outside 1.." +
                                                  std::to_string(kMaxPhotons) + " (2^26)");
}

}  // namespace

FirstGeneration first_generation(arcus_context_t* ctx, RenderScene* scene, const arcus_advance_params& params,
                                 uint64_t count, uint64_t seed, PhotonStats* stats, const PhotonOptions& options) {
  check_arguments(ctx, scene, count);
  PhotonStats local;
  PhotonStats* st = stats ? stats : &local;
  std::vector<Live> live;
  TraceOutput t;
  FirstGeneration out;
  first_generation_of(ctx, scene, params, count, seed, surface_offset(*scene), options, &live, &t, &out.how, st);
  for (size_t k = 0; k < live.size(); ++k) {
    const Live& p = live[k];
    out.origins.insert(out.origins.end(), {p.origin.x, p.origin.y, p.origin.z});
    out.directions.insert(out.directions.end(), {p.direction.x, p.direction.y, p.direction.z});
    out.ids.push_back(p.id);
    const bool hit = t.status[k] == ARCUS_STATUS_HIT;
    for (int a = 0; a < 3; ++a) out.hits.push_back(hit ? t.positions[3 * k + a] : NAN);
  }
  out.status = t.status;
  out.object = t.object;
  return out;
}

photon::Photons shoot_photon_list(arcus_context_t* ctx, RenderScene* scene, const arcus_advance_params& params,
                                  uint64_t count, uint64_t seed, PhotonStats* stats, const PhotonOptions& options) {
  const auto start = Clock::now();
  check_arguments(ctx, scene, count);
  const RenderScene& s = *scene;
  const double offset = surface_offset(s);
  PhotonStats st;

  std::vector<Live> live;
  TraceOutput first;
  std::vector<int32_t> how;
  first_generation_of(ctx, scene, params, count, seed, offset, options, &live, &first, &how, &st);

  photon::Photons out;
  out.channels = 3;
  for (int generation = 0; generation < kMaxGenerations && !live.empty(); ++generation) {
    TraceOutput traced;
    if (generation > 0) {
      Batch b;
      for (const Live& p : live) b.add(p);
      traced = trace(ctx, scene, params, b.input(nullptr));
      count_trace(traced, true, &st);
    }
    const TraceOutput& t = generation == 0 ? first : traced;
    std::vector<Live> next;
    for (size_t k = 0; k < live.size(); ++k) {
      if (t.status[k] != ARCUS_STATUS_HIT || t.object[k] < 0) continue;  // left, failed: gone
      const Live& p = live[k];
      const Vec3 hit = vec3(&t.positions[3 * k]), d = normalized(vec3(&t.directions[3 * k]));
      const HitSurface surf = surface_at(s, t.object[k], t.hit_kind[k], t.hit_index[k], hit, d);
      if (surf.window) {  // an opening: on through it, unchanged
        next.push_back({hit - offset * surf.normal, d, {p.power[0], p.power[1], p.power[2]}, p.id, p.bounces});
        continue;
      }
      out.positions.insert(out.positions.end(), {hit.x, hit.y, hit.z});
      out.directions.insert(out.directions.end(), {d.x, d.y, d.z});
      out.powers.insert(out.powers.end(), {p.power[0], p.power[1], p.power[2]});
      if (p.bounces >= kMaxPhotonBounces) continue;
      const double survive = std::min(1.0, (surf.albedo[0] + surf.albedo[1] + surf.albedo[2]) / 3);
      if (!(photon_draw(seed, p.id, generation_draw(generation, 0)) < survive)) continue;  // absorbed
      // Cosine-weighted about the normal on the side the photon came from.
      const double phi = 2 * M_PI * photon_draw(seed, p.id, generation_draw(generation, 1));
      const double r2 = photon_draw(seed, p.id, generation_draw(generation, 2));
      const double sin_t = std::sqrt(r2), cos_t = std::sqrt(1 - r2);
      Vec3 tu, tv;
      photon_basis(surf.normal, &tu, &tv);
      const Vec3 dir = (sin_t * std::cos(phi)) * tu + (sin_t * std::sin(phi)) * tv + cos_t * surf.normal;
      Live n{hit + offset * surf.normal, dir, {0, 0, 0}, p.id, p.bounces + 1};
      for (int c = 0; c < 3; ++c) n.power[c] = p.power[c] * surf.albedo[c] / survive;
      next.push_back(n);
    }
    live = std::move(next);
  }

  st.shot = count;
  st.stored = out.positions.size() / 3;
  st.seconds = std::chrono::duration<double>(Clock::now() - start).count();
  if (stats) *stats = st;
  return out;
}

std::unique_ptr<photon::PhotonMap> shoot_photons(arcus_context_t* ctx, RenderScene* scene,
                                                 const arcus_advance_params& params, uint64_t count, uint64_t seed,
                                                 PhotonStats* stats, const PhotonOptions& options) {
  const auto start = Clock::now();
  const photon::Photons photons = shoot_photon_list(ctx, scene, params, count, seed, stats, options);
  auto map = std::make_unique<photon::PhotonMap>(ctx, photons);
  if (stats) stats->seconds = std::chrono::duration<double>(Clock::now() - start).count();
  return map;
}

std::vector<double> photon_irradiance(arcus_context_t* ctx, const photon::PhotonMap& map, const RenderScene& scene,
                                      const std::vector<double>& points, const std::vector<double>& normals) {
  require_pointer(ctx, "ctx");
  require(map.channels() == 3, "photons: the map holds " + std::to_string(map.channels()) + " channels, not RGB");
  photon::Query q;
  q.k = static_cast<int32_t>(std::clamp<uint32_t>(scene.desc.photons.estimate, 1, ARCUS_PHOTON_MAX_K));
  q.max_radius = scene.desc.photons.max_radius;
  q.mode = photon::Mode::surface;
  return photon::estimate(ctx, map, points, normals, q).values;
}

}  // namespace arcus::render
