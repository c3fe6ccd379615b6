// arcus_trace — runs a scene file through arcus and writes what happened to each ray.
//
//   arcus_trace SCENE.json [--out DIR] [--device N] [--quiet]
//
// The library reads and checks the scene (arcus_scene_load; schema in scenes/README.md),
// advances its rays (arcus_curved_advance_scene, with a progress bar on a terminal) and this
// tool writes into DIR (default out/<scene name>):
//   rays.csv    ray, origin xyz, initial direction xyz (as given), wavelength (if given),
//               end position xyz, end direction xyz (unit), arc length, accepted steps,
//               status, failure reason
//   paths.csv   ray, point, x, y, z          (only when the scene records paths)
//   summary.md  scene, device, compiled kernel features, timings, rays per status
//   scene.json  the scene as read, so that the outputs carry their input (the
//               plotting script apps/plot_paths.py reads it for the plane of the fan)
// Exit status: 0 on success (partial library results are written, with a warning),
// 2 on any error; a scene error names the file and the JSON path ("$.medium.radius").
#include <unistd.h>

#include <cstdio>
#include <cstdlib>
#include <iostream>
#include <memory>
#include <optional>

#include "trace.h"

namespace {

namespace fs = std::filesystem;
using trace::Failure;
using trace::Results;

constexpr int kExitError = 2;

template <class T, arcus_status (*Release)(T*)>
struct Releaser {
  void operator()(T* handle) const { Release(handle); }
};
using Context = std::unique_ptr<arcus_context_t, Releaser<arcus_context_t, arcus_context_release>>;
using Scene = std::unique_ptr<arcus_scene_t, Releaser<arcus_scene_t, arcus_scene_release>>;
using Field = std::unique_ptr<arcus_field_t, Releaser<arcus_field_t, arcus_field_release>>;
using Job = std::unique_ptr<arcus_job_t, Releaser<arcus_job_t, arcus_job_release>>;

// Throws unless status is a success; `what` says which step failed.
void check(arcus_status status, arcus_context_t* ctx, const std::string& what) {
  if (status == ARCUS_SUCCESS) return;
  throw Failure(what + ": " + trace::library_failure(status, ctx ? arcus_context_last_error(ctx) : arcus_last_error()));
}

struct Options {
  fs::path scene;
  std::optional<fs::path> out;
  int32_t device = ARCUS_DEVICE_DEFAULT;
  bool quiet = false;
};

const char* const kUsage =
    "usage: arcus_trace SCENE.json [--out DIR] [--device N] [--quiet]\n"
    "  --out DIR    where to write rays.csv, paths.csv, summary.md (default out/<scene name>)\n"
    "  --device N   OpenCL device index (default: ARCUS_DEVICE, else the first GPU, else CPU)\n"
    "  --quiet      no progress bar\n"
    "The scene schema is described in scenes/README.md.\n";

int32_t parse_device(const std::string& s) {
  char* end = nullptr;
  const long v = std::strtol(s.c_str(), &end, 10);
  if (s.empty() || *end != '\0' || v < 0 || v > INT32_MAX)
    throw Failure("--device: expected a device index, got \"" + s + "\"");
  return static_cast<int32_t>(v);
}

// Returns nullopt when the usage was asked for.
std::optional<Options> parse_options(int argc, char** argv) {
  Options o;
  const std::vector<std::string> args(argv + 1, argv + argc);
  for (size_t i = 0; i < args.size(); ++i) {
    const std::string& a = args[i];
    if (a == "-h" || a == "--help") return std::nullopt;
    if (a == "--quiet") {
      o.quiet = true;
    } else if (a == "--out" || a == "--device") {
      if (i + 1 == args.size()) throw Failure(a + ": missing value\n" + kUsage);
      const std::string& value = args[++i];
      if (a == "--out")
        o.out = value;
      else
        o.device = parse_device(value);
    } else if (!a.empty() && a[0] == '-') {
      throw Failure("unknown option " + a + "\n" + kUsage);
    } else if (o.scene.empty()) {
      o.scene = a;
    } else {
      throw Failure(std::string("more than one scene file given\n") + kUsage);
    }
  }
  if (o.scene.empty()) throw Failure(std::string("no scene file given\n") + kUsage);
  return o;
}

// A progress bar on stderr, redrawn as the fraction grows.
int32_t show_progress(void*, double fraction) {
  std::fprintf(stderr, "\rarcus_trace: %5.1f %%", 100.0 * fraction);
  if (fraction >= 1.0) std::fprintf(stderr, "\n");
  std::fflush(stderr);
  return 0;
}

const char* medium_name(arcus_field_kind kind) {
  static const char* const names[] = {"constant", "linear", "linear_n2", "luneburg", "fisheye", "atmosphere", "grid"};
  return kind >= 0 && kind < 7 ? names[kind] : "unknown";
}

Results describe(arcus_context_t* ctx, arcus_scene_t* scene, const fs::path& file) {
  Results r;
  r.scene_file = file;
  const char *name = nullptr, *description = nullptr, *document = nullptr;
  check(arcus_scene_get_name(scene, &name), ctx, "reading the scene's name");
  check(arcus_scene_get_description(scene, &description), ctx, "reading the scene's description");
  check(arcus_scene_get_document(scene, &document), ctx, "reading the scene");
  r.name = name;
  r.description = description;
  r.document = document;
  arcus_field_t* raw = nullptr;
  check(arcus_scene_get_field(scene, &raw), ctx, "reading the scene's field");
  Field field(raw);
  arcus_field_kind kind;
  check(arcus_field_get_kind(field.get(), &kind), ctx, "reading the medium's kind");
  r.medium = medium_name(kind);
  check(arcus_scene_get_ray_count(scene, &r.count), ctx, "reading the scene's rays");
  r.origins.resize(3 * r.count);
  r.directions.resize(3 * r.count);
  r.wavelengths.resize(r.count);
  int32_t has_wavelengths = 0;
  check(arcus_scene_get_rays(scene, r.origins.data(), r.directions.data(), r.wavelengths.data(), &has_wavelengths),
        ctx, "reading the scene's rays");
  if (!has_wavelengths) r.wavelengths.clear();
  return r;
}

void read_results(arcus_context_t* ctx, arcus_job_t* job, Results* r) {
  const size_t n = r->count;
  r->end_positions.resize(3 * n);
  r->end_directions.resize(3 * n);
  r->lengths.resize(n);
  r->steps.resize(n);
  r->ray_status.resize(n);
  r->failures.resize(n);
  check(arcus_job_get_curved_end_states(job, r->end_positions.data(), r->end_directions.data(), r->steps.data(),
                                        r->ray_status.data(), r->lengths.data()),
                                        ctx, "reading the end states");
  check(arcus_job_get_curved_failures(job, r->failures.data()), ctx, "reading the failure reasons");
  check(arcus_job_get_features(job, &r->features), ctx, "reading the job's features");
  check(arcus_job_get_stats(job, &r->stats), ctx, "reading the job's statistics");
  size_t total = 0;
  if (arcus_job_get_curved_path_size(job, &total) != ARCUS_SUCCESS) return;  // no record_path
  r->path_offsets.resize(n + 1);
  r->path_needed.resize(n);
  r->path_points.resize(total * 3);
  check(arcus_job_get_curved_paths(job, r->path_offsets.data(), r->path_points.data(), r->path_needed.data()), ctx,
                                   "reading the paths");
}

bool partial_result(arcus_status s) {
  return s == ARCUS_ERROR_INVALID_RAYS || s == ARCUS_ERROR_PATH_OVERFLOW || s == ARCUS_ERROR_CANCELLED;
}

void run(const Options& options) {
  arcus_context_t* raw_ctx = nullptr;
  check(arcus_context_create(options.device, &raw_ctx), nullptr, "creating the OpenCL context");
  Context ctx(raw_ctx);
  arcus_scene_t* raw_scene = nullptr;
  const arcus_status loaded = arcus_scene_load(ctx.get(), options.scene.c_str(), &raw_scene);
  if (loaded != ARCUS_SUCCESS) throw Failure(arcus_context_last_error(ctx.get()));  // names file and key path
  Scene scene(raw_scene);
  Results r = describe(ctx.get(), scene.get(), options.scene);
  check(arcus_context_get_device(ctx.get(), &r.device), ctx.get(), "querying the device");

  std::cout << "arcus_trace: " << r.name << ": " << r.count << " rays through " << r.medium << " on "
            << r.device.name << std::endl;
  const bool bar = !options.quiet && isatty(STDERR_FILENO);
  arcus_job_t* raw_job = nullptr;
  const arcus_status s = arcus_curved_advance_scene(scene.get(), bar ? show_progress : nullptr, nullptr, &raw_job);
  Job job(raw_job);
  if (!partial_result(s)) check(s, ctx.get(), "advancing the rays ($.integrator, $.rays)");
  r.status = s;
  if (s != ARCUS_SUCCESS) {
    r.message = arcus_context_last_error(ctx.get());
    std::cerr << "arcus_trace: warning: partial results: " << trace::library_failure(s, r.message) << "\n";
  }
  read_results(ctx.get(), job.get(), &r);

  const fs::path dir = options.out ? *options.out : fs::path("out") / r.name;
  const std::vector<std::string> written = trace::write_outputs(dir, r);
  std::cout << "arcus_trace: wrote";
  for (const std::string& f : written) std::cout << ' ' << (dir / f).string();
  std::cout << std::endl;
}

}  // namespace

int main(int argc, char** argv) {
  try {
    const std::optional<Options> options = parse_options(argc, argv);
    if (!options) {
      std::cout << kUsage;
      return 0;
    }
    run(*options);
    return 0;
  } catch (const Failure& e) {
    std::cerr << "arcus_trace: " << e.what() << "\n";
  } catch (const std::exception& e) {  // e.g. out of memory, filesystem errors
    std::cerr << "arcus_trace: unexpected error: " << e.what() << "\n";
  }
  return kExitError;
}
