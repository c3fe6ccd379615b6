// arcus_render: renders a render scene (a scene file with a "camera") through its
// medium and writes the image.
//
//   arcus_render SCENE.json -o OUT.exr [--png OUT.png] [--frames N]
//                [--techniques smart_step,symmetry,undersample,path_cache|all|none]
//                [--device N] [--quiet]
//
// The EXR holds linear RGB plus the channels "distance" (arc length to the hit),
// "steps" and "tests" (integrator steps and intersection tests per pixel); the PNG is
// sRGB at the scene's exposure.  With --frames N the camera rests and N frames are
// rendered (the later ones reuse what the earlier left: cached paths, predicted hit
// steps); the image is the last frame's.  A progress bar shows each frame's stages,
// and a closing summary gives the time per stage, steps per ray and tests per ray.
// Exit status: 0 on success, 2 on any error (a scene error names the file and key).
#include <unistd.h>

#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <iostream>
#include <string>
#include <vector>

#include "arcus/arcus.h"

namespace {

const char* kUsage =
    "usage: arcus_render SCENE.json -o OUT.exr [--png OUT.png] [--frames N]\n"
    "                    [--techniques LIST] [--device N] [--quiet]\n"
    "  -o OUT.exr        linear RGB + distance, steps, tests channels\n"
    "  --png OUT.png     an sRGB PNG as well\n"
    "  --frames N        render N frames with the camera at rest (default 1)\n"
    "  --techniques LIST comma-separated: smart_step, symmetry, undersample, path_cache,\n"
    "                    all or none (default: the scene's \"techniques\")\n"
    "  --device N        OpenCL device index (default: ARCUS_DEVICE, else the first GPU, else CPU)\n"
    "  --quiet           no progress bar\n";

struct Failure : std::runtime_error {
  using std::runtime_error::runtime_error;
};

struct Options {
  std::string scene, exr, png, techniques;
  bool has_techniques = false, quiet = false;
  int frames = 1;
  int32_t device = -1;
};

long parse_count(const std::string& flag, const std::string& s, long lo, long hi) {
  char* end = nullptr;
  const long v = std::strtol(s.c_str(), &end, 10);
  if (s.empty() || *end != '\0' || v < lo || v > hi)
    throw Failure(flag + ": expected a whole number in " + std::to_string(lo) + ".." + std::to_string(hi) +
                  ", got \"" + s + "\"");
  return v;
}

Options parse_options(int argc, char** argv) {
  Options o;
  const std::vector<std::string> args(argv + 1, argv + argc);
  for (size_t i = 0; i < args.size(); ++i) {
    const std::string& a = args[i];
    if (a == "-h" || a == "--help") {
      std::cout << kUsage;
      std::exit(0);
    }
    if (a == "--quiet") {
      o.quiet = true;
      continue;
    }
    if (a == "-o" || a == "--png" || a == "--frames" || a == "--techniques" || a == "--device") {
      if (i + 1 == args.size()) throw Failure(a + ": missing value\n" + std::string(kUsage));
      const std::string& v = args[++i];
      if (a == "-o") o.exr = v;
      if (a == "--png") o.png = v;
      if (a == "--frames") o.frames = static_cast<int>(parse_count(a, v, 1, 100000));
      if (a == "--techniques") {
        o.techniques = v;
        o.has_techniques = true;
      }
      if (a == "--device") o.device = static_cast<int32_t>(parse_count(a, v, 0, INT32_MAX));
      continue;
    }
    if (!a.empty() && a[0] == '-') throw Failure("unknown option " + a + "\n" + std::string(kUsage));
    if (!o.scene.empty()) throw Failure(std::string("more than one scene given\n") + kUsage);
    o.scene = a;
  }
  if (o.scene.empty() || o.exr.empty()) throw Failure(std::string("a scene and -o OUT.exr are required\n") + kUsage);
  return o;
}

uint32_t technique_bits(const std::string& list) {
  uint32_t bits = 0;
  size_t start = 0;
  while (start <= list.size()) {
    const size_t end = std::min(list.find(',', start), list.size());
    const std::string t = list.substr(start, end - start);
    if (t == "smart_step") bits |= ARCUS_TECHNIQUE_SMART_STEP;
    else if (t == "symmetry") bits |= ARCUS_TECHNIQUE_SYMMETRY;
    else if (t == "undersample") bits |= ARCUS_TECHNIQUE_UNDERSAMPLE;
    else if (t == "path_cache") bits |= ARCUS_TECHNIQUE_PATH_CACHE;
    else if (t == "all") bits |= ARCUS_TECHNIQUE_ALL;
    else if (t != "none" && !t.empty())
      throw Failure("--techniques: unknown technique \"" + t +
                    "\" (expected smart_step, symmetry, undersample, path_cache, all or none)");
    start = end + 1;
  }
  return bits;
}

void check(arcus_status s, const char* what) {
  if (s != ARCUS_SUCCESS) throw Failure(std::string(what) + ": " + arcus_status_string(s) + ": " + arcus_last_error());
}

struct Bar {
  bool show;
  int frame, frames;
};

int on_progress(void* user, double fraction) {
  const Bar* b = static_cast<const Bar*>(user);
  if (!b->show) return 0;
  const int width = 30, filled = static_cast<int>(fraction * width + 0.5);
  const char* stage = fraction < 0.8 ? "tracing" : fraction < 1.0 ? "shading" : "done   ";
  std::fprintf(stderr, "\rframe %d/%d [%.*s%*s] %3.0f%% %s", b->frame, b->frames, filled,
               "##############################", width - filled, "", 100 * fraction, stage);
  std::fflush(stderr);
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  arcus_context_t* ctx = nullptr;
  arcus_scene_t* scene = nullptr;
  arcus_renderer_t* renderer = nullptr;
  arcus_job_t* job = nullptr;
  int code = 0;
  try {
    const Options o = parse_options(argc, argv);
    check(arcus_context_create(o.device, &ctx), "context");
    check(arcus_scene_load(ctx, o.scene.c_str(), &scene), "scene");
    check(arcus_renderer_create(scene, &renderer), "renderer");
    if (o.has_techniques) check(arcus_renderer_set_techniques(renderer, technique_bits(o.techniques)), "techniques");
    Bar bar{!o.quiet && isatty(STDERR_FILENO), 0, o.frames};
    arcus_render_stats total{};
    double seconds = 0;
    for (int f = 1; f <= o.frames; ++f) {
      bar.frame = f;
      if (job) arcus_job_release(job);
      job = nullptr;
      check(arcus_render_frame(renderer, on_progress, &bar, &job), "render");
      arcus_render_stats st;
      check(arcus_job_get_render_stats(job, &st), "stats");
      seconds += st.total_seconds;
      total = st;
      if (bar.show) std::fprintf(stderr, "\n");
      if (o.frames > 1)
        std::printf("frame %d: %.3f s, %.2f steps/ray, %.2f tests/ray\n", f, st.total_seconds,
                    double(st.steps) / st.pixels, double(st.tests) / st.pixels);
    }
    check(arcus_job_write_render_image(job, o.exr.c_str(), o.png.empty() ? nullptr : o.png.c_str()), "write");
    const char* name = nullptr;
    arcus_scene_get_name(scene, &name);
    uint32_t width = 0, height = 0;
    check(arcus_job_get_render_image_size(job, &width, &height), "image size");
    std::printf("%s: %ux%u px, %d frame(s) in %.3f s\n", name, width, height, o.frames, seconds);
    std::printf("  last frame: trace %.3f s, walk %.3f s, photons %.3f s, shading %.3f s, total %.3f s\n",
                total.trace_seconds, total.walk_seconds, total.photon_seconds, total.shade_seconds,
                total.total_seconds);
    std::printf("  %.2f steps per ray, %.2f intersection tests per ray; rays traced %llu, mirrored %llu, "
                "interpolated %llu, from the cache %llu (%.1f MB); %llu shadow rays\n",
                double(total.steps) / total.pixels, double(total.tests) / total.pixels,
                (unsigned long long)total.rays_traced, (unsigned long long)total.rays_mirrored,
                (unsigned long long)total.rays_interpolated, (unsigned long long)total.rays_cached,
                total.cache_bytes / 1e6, (unsigned long long)total.shadow_rays);
    std::printf("  wrote %s%s%s\n", o.exr.c_str(), o.png.empty() ? "" : " and ", o.png.c_str());
  } catch (const Failure& e) {
    std::fprintf(stderr, "arcus_render: %s\n", e.what());
    code = 2;
  }
  if (job) arcus_job_release(job);
  if (renderer) arcus_renderer_release(renderer);
  if (scene) arcus_scene_release(scene);
  if (ctx) arcus_context_release(ctx);
  return code;
}
