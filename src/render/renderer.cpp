#include "render/renderer.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <functional>
#include <limits>

#include "core/error.h"
#include "core/limits.h"
#include "image/image_io.h"
#include "spectral/cie.h"
#include "spectral/srgb.h"
#include "render/frame_rays.h"
#include "render/photons.h"
#include "render/shading.h"
#include "render/trace.h"

namespace arcus::render {
const HandleKind kRendererHandle("renderer");
}  // namespace arcus::render

arcus_renderer_s::arcus_renderer_s(arcus_context_t* ctx, arcus::render::RenderScene* s)
    : Handle(arcus::render::kRendererHandle, ctx), scene(s), camera(s->desc.camera), techniques(s->desc.techniques),
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
// The frame's paths: the cache's when it holds this frame's, else recorded now for the
// traced pixels (then *fresh owns them and `done` marks the pixels already traced).
const PathFrame* frame_paths(arcus_context_t* ctx, arcus_renderer_s* r, const Frame& f,
                             const std::vector<int32_t>* previous, Primary* prim, std::vector<char>* done,
                             arcus_render_stats* st, std::unique_ptr<PathFrame>* fresh) {
  const CameraDesc& c = r->camera;
  const size_t n = static_cast<size_t>(c.width) * c.height;
  if ((r->techniques & ARCUS_TECHNIQUE_PATH_CACHE) && r->cached_paths && r->cached_paths->rays.size() == n) {
    st->rays_cached = n;
    return r->cached_paths.get();
  }
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
  *fresh = std::make_unique<PathFrame>(pixel_paths(ctx, r, f, path_room(steps), previous, prim, done, st));
  return fresh->get();
}

// Walks that ran past the end of a path cut short by a hit: traced from the start, the
// tests of the walk counted too.
void trace_unresolved(arcus_context_t* ctx, arcus_renderer_s* r, const Frame& f, Primary* prim,
                      arcus_render_stats* st) {
  const CameraDesc& c = r->camera;
  Batch unresolved;
  for (uint32_t j = 0; j < c.height; ++j)
    for (uint32_t i = 0; i < c.width; ++i) {
      const size_t p = static_cast<size_t>(j) * c.width + i;
      if (prim->status[p] == ARCUS_STATUS_UNRESOLVED) unresolved.add(f.origin, pixel_direction(f, c, i, j), p, -1);
    }
  if (!unresolved.size()) return;
  st->rays_unresolved += unresolved.size();
  std::vector<int32_t> walked_tests;
  for (size_t p : unresolved.pixels) walked_tests.push_back(prim->tests[p]);
  trace_batch(ctx, r, unresolved, false, NAN, prim, st);
  for (size_t k = 0; k < unresolved.size(); ++k) prim->tests[unresolved.pixels[k]] += walked_tests[k];
}

void walk_frame(arcus_context_t* ctx, arcus_renderer_s* r, const Frame& f, Primary* prim, arcus_render_stats* st) {
  const CameraDesc& c = r->camera;
  const size_t n = static_cast<size_t>(c.width) * c.height;
  const bool cache = r->techniques & ARCUS_TECHNIQUE_PATH_CACHE;
  const bool smart = r->techniques & ARCUS_TECHNIQUE_SMART_STEP;
  const bool temporal = smart && r->previous_hit_step.size() == n;
  const std::vector<int32_t>* previous = temporal ? &r->previous_hit_step : nullptr;
  std::unique_ptr<PathFrame> fresh;
  std::vector<char> done(n, 0);
  const PathFrame* paths = frame_paths(ctx, r, f, previous, prim, &done, st, &fresh);
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
  trace_unresolved(ctx, r, f, prim, st);
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

namespace {

// Spectral (thesis §2.2; README, "Spectral rendering"): each wavelength's rays are
// traced through the dispersive medium and shaded, and the spectral radiance is
// integrated against the CIE 1931 colour-matching functions into XYZ, then sRGB.
// *prim gets the first wavelength's figures; returns the seconds spent shading.
double spectral_frame(arcus_context_t* ctx, arcus_renderer_s* r, const Frame& f, RenderJob* job, Primary* prim,
                      arcus_render_stats* st, StageProgress* stage, const std::function<void(double)>& report) {
  const std::vector<double>& wavelengths = r->scene->desc.wavelengths;
  const size_t n = prim->status.size();
  r->cached_paths.reset();
  const auto weights = spectral::band_weights(wavelengths);
  std::vector<std::array<double, 3>> xyz(n, std::array<double, 3>{0, 0, 0});
  double shade_seconds = 0;
  for (size_t k = 0; k < wavelengths.size(); ++k) {
    Primary pk(n);
    direct_pass(ctx, r, f, wavelengths[k], &pk, st);
    const auto t = Clock::now();
    shade(ctx, r, pk, job);
    for (size_t p = 0; p < n; ++p) {
      const double L = spectral_radiance(*r->scene, f, pk, p, &job->rgb[3 * p], wavelengths[k]);
      for (int c3 = 0; c3 < 3; ++c3) xyz[p][c3] += L * weights[k][c3];
    }
    shade_seconds += since(t);
    job->features |= pk.features;
    if (k == 0) *prim = std::move(pk);  // the figures of the first wavelength
    report(0.8 * (k + 1) / wavelengths.size());
    stage->base = 0.8 * (k + 1) / wavelengths.size();
    stage->span = 0.8 / wavelengths.size();
  }
  for (size_t p = 0; p < n; ++p) {
    const auto rgb = spectral::xyz_to_linear_srgb(xyz[p]);
    for (int c3 = 0; c3 < 3; ++c3) job->rgb[3 * p + c3] = static_cast<float>(rgb[c3]);
  }
  return shade_seconds;
}

// The frame's image and per-pixel figures into the job; what the next frame predicts
// from stays with the renderer.
void keep_results(arcus_renderer_s* r, Primary* prim, RenderJob* job) {
  const CameraDesc& c = r->camera;
  const size_t n = static_cast<size_t>(c.width) * c.height;
  arcus_render_stats& st = job->render_stats;
  image::require_finite_pixels(job->rgb, static_cast<int>(c.width), "RGB", "the render");
  job->width = c.width;
  job->height = c.height;
  job->exposure = r->scene->desc.exposure;
  job->count = n;
  job->points = std::move(prim->position);
  job->objects = std::move(prim->object);
  job->primitives = std::move(prim->primitive);
  job->distances = std::move(prim->length);
  job->steps.resize(n);
  job->tests.resize(n);
  for (size_t p = 0; p < n; ++p) {
    job->steps[p] = static_cast<uint32_t>(prim->steps[p]);
    job->tests[p] = static_cast<uint32_t>(prim->tests[p]);
    st.steps += prim->steps[p];
    st.tests += static_cast<uint64_t>(prim->tests[p]);
  }
  r->previous_hit_step = std::move(prim->end_step);
  // Room enough in the next frame's recorded paths for all but a few.
  r->previous_steps = percentile999(prim->steps);
  job->features |= prim->features;
}

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
    shade_seconds = spectral_frame(ctx, r, f, job.get(), &prim, &st, &stage, report);
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
  keep_results(r, &prim, job.get());
  st.total_seconds = since(start);
  job->stats.total_seconds = st.total_seconds;
  report(1.0);
  return job;
}

}  // namespace arcus::render
