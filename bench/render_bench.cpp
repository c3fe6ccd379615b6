// arcus_bench_render: the thesis' Table 5.2 (§5.4.2.2) for arcus' renderer.  Per test
// scene: the time of a frame and the mean hit-point error (km) against the ground truth
// (Dormand–Prince, atol 1e-6 km, no optimization) for each of the thesis' techniques
// alone and combined, beside the thesis' own figures, with the work per ray (steps,
// intersection tests) and its rate, so the roofline stays visible.  Markdown tables on
// stdout and in bench/results/render.md (git-ignored), then PASS/MISS lines for the
// issue's targets.
//
//   arcus_bench_render [--scenes a.json,b.json] [--quick] [--repeats N] [--budget S] [--frame-limit S]
//                      [--no-paths] [--out FILE]
//
// Default scenes: scenes/{inferior_mirage,novaya_zemlya,fata_morgana}.json and, if it
// exists and renders, scenes/cross_room.json (photon mapped); a missing one is skipped
// with a note.  --quick renders every scene at half its width and height (a copy of the
// scene file in a temporary directory, its relative file names made absolute).
// Timings are of arcus_render_frame, warm (every kernel the scene needs is built by
// untimed frames first), the median of --repeats runs (3) unless one run takes longer
// than --budget seconds (20), then one run.  A frame past --frame-limit seconds (300) is
// cancelled and its row says so.  --no-paths skips the techniques that record paths
// (symmetry, undersampling, path caching and the combinations).
#include <arcus/arcus.h>

#include "render_bench_io.h"

#include <nlohmann/json.hpp>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <ctime>
#include <filesystem>
#include <fstream>
#include <map>
#include <memory>
#include <sstream>
#include <string>
#include <thread>
#include <vector>

namespace {

namespace fs = std::filesystem;
using json = nlohmann::ordered_json;
using namespace render_bench;

constexpr uint32_t kSmart = ARCUS_TECHNIQUE_SMART_STEP, kSym = ARCUS_TECHNIQUE_SYMMETRY,
                   kUnder = ARCUS_TECHNIQUE_UNDERSAMPLE, kCache = ARCUS_TECHNIQUE_PATH_CACHE;

// ---- the thesis' Table 5.2 -------------------------------------------------------------
struct ThesisFigures {
  const char* scene;
  // m:s of ground truth, parallelization, symmetries, undersampling, path caching,
  // smart step selection, combination; errors (km) of undersampling and combination.
  const char *gt, *parallel, *symmetry, *under, *cache, *smart, *combo;
  double under_err, combo_err;
};
constexpr ThesisFigures kThesis[] = {
    {"inferior_mirage", "8:15", "4:32", "6:04", "5:54", "4:12", "3:57", "1:55", 0.005, 0.019},
    {"novaya_zemlya", "10:12", "5:58", "8:14", "8:01", "4:42", "4:21", "2:51", 0.230, 0.032},
    {"fata_morgana", "9:42", "5:11", "7:32", "6:58", "4:22", "3:56", "2:02", 0.011, 0.042},
    {"cross_room", "14:10", "11:32", "12:26", "11:51", "11:05", "11:10", "9:31", 0.004, 0.002},
};
constexpr const char* kDefaultScenes[] = {"inferior_mirage", "novaya_zemlya", "fata_morgana", "cross_room"};

const ThesisFigures* thesis_for(const std::string& name) {
  for (const ThesisFigures& t : kThesis)
    if (name == t.scene) return &t;
  return nullptr;
}

double ms_seconds(const char* ms) {  // "8:15" -> 495
  int m = 0, s = 0;
  return ms && std::sscanf(ms, "%d:%d", &m, &s) == 2 ? 60.0 * m + s : NAN;
}

// ---- timing ----------------------------------------------------------------------------
using Clock = std::chrono::steady_clock;
double since(Clock::time_point t) { return std::chrono::duration<double>(Clock::now() - t).count(); }

// ---- measurements ----------------------------------------------------------------------
struct Frame {
  double wall = NAN;
  arcus_render_stats stats{};
  std::vector<double> points;
  std::vector<int32_t> objects;
};

struct Series {  // one configuration: its frame 1 and (if asked) frame 2, over runs
  std::string refused;  // UNSUPPORTED: the library's reason
  std::string error;    // any other failure
  std::vector<double> wall[2], total[2];
  Frame last[2];  // the hits and stats of the last run
  int runs = 0;
};

std::string last_error(arcus_context_t* ctx) {
  const char* e = arcus_context_last_error(ctx);
  return e && *e ? e : "(no message)";
}

// A frame running past --frame-limit seconds is cancelled (its progress callback, between
// the frame's slices), so one pathological technique does not stall the whole run.
double g_frame_limit = 300;
bool g_no_paths = false;  // --no-paths: skip the techniques that record paths
struct FrameLimit {
  Clock::time_point start;
  double seconds;
};
int32_t cancel_late(void* user, double) {
  const auto* l = static_cast<const FrameLimit*>(user);
  return since(l->start) > l->seconds ? 1 : 0;
}

// Renders `frames` (1 or 2) frames on a fresh renderer per run.  Stops repeating once a
// run's first frame took longer than `budget` seconds.
Series measure(arcus_context_t* ctx, arcus_scene_t* scene, uint32_t techniques, int frames, int repeats,
               double budget) {
  Series s;
  for (int run = 0; run < repeats; ++run) {
    arcus_renderer_t* r = nullptr;
    if (arcus_renderer_create(scene, &r) != ARCUS_SUCCESS) {
      s.error = "renderer: " + last_error(ctx);
      return s;
    }
    const arcus_status st = arcus_renderer_set_techniques(r, techniques);
    if (st != ARCUS_SUCCESS) {
      (st == ARCUS_ERROR_UNSUPPORTED ? s.refused : s.error) = last_error(ctx);
      arcus_renderer_release(r);
      return s;
    }
    for (int f = 0; f < frames; ++f) {
      arcus_job_t* job = nullptr;
      const auto t0 = Clock::now();
      FrameLimit limit{t0, g_frame_limit};
      const arcus_status fs_ = arcus_render_frame(r, cancel_late, &limit, &job);
      const double wall = since(t0);
      if (fs_ != ARCUS_SUCCESS) {
        (fs_ == ARCUS_ERROR_UNSUPPORTED ? s.refused : s.error) =
            fs_ == ARCUS_ERROR_CANCELLED ? "cancelled after " + fmt("%.0f", wall) + " s (--frame-limit)" : last_error(ctx);
        if (job) arcus_job_release(job);
        arcus_renderer_release(r);
        return s;
      }
      Frame& fr = s.last[f];
      fr.wall = wall;
      arcus_job_get_render_stats(job, &fr.stats);
      fr.points.assign(3 * fr.stats.pixels, NAN);
      fr.objects.assign(fr.stats.pixels, -1);
      arcus_job_get_render_hits(job, fr.points.data(), fr.objects.data(), nullptr, nullptr, nullptr, nullptr);
      std::fprintf(stderr, "  frame %d: %.3f s (trace %.3f, walk %.3f, photons %.3f, shade %.3f)\n", f + 1, wall,
                   fr.stats.trace_seconds, fr.stats.walk_seconds, fr.stats.photon_seconds, fr.stats.shade_seconds);
      s.wall[f].push_back(wall);
      s.total[f].push_back(fr.stats.total_seconds);
      arcus_job_release(job);
    }
    arcus_renderer_release(r);
    ++s.runs;
    if (s.wall[0].back() > budget) break;
  }
  return s;
}

struct Errors {
  double mean_km = NAN, max_km = NAN, differs = NAN;  // differs: fraction of pixels
};

Errors compare(const Frame& gt, const Frame& f) {
  Errors e;
  const size_t n = gt.objects.size();
  if (f.objects.size() != n || n == 0) return e;
  size_t differ = 0, both = 0;
  double sum = 0, worst = 0;
  for (size_t p = 0; p < n; ++p) {
    if (gt.objects[p] != f.objects[p]) {
      ++differ;
      continue;
    }
    if (gt.objects[p] < 0) continue;  // both missed: no hit point
    double d2 = 0;
    for (int a = 0; a < 3; ++a) d2 += (gt.points[3 * p + a] - f.points[3 * p + a]) * (gt.points[3 * p + a] - f.points[3 * p + a]);
    if (!std::isfinite(d2)) continue;
    const double d = std::sqrt(d2) * 1e-3;  // km
    sum += d;
    worst = std::max(worst, d);
    ++both;
  }
  e.differs = static_cast<double>(differ) / n;
  if (both) e.mean_km = sum / both, e.max_km = worst;
  return e;
}

// Rows of a scene's table, in run_scene's order: the ones the targets read.
constexpr size_t kSmartRow = 6, kComboRow = 8, kExactComboRow = 12;

// A row of a scene's table.
struct Row {
  std::string label, thesis_time, note;
  double thesis_err = NAN;
  const Series* series = nullptr;
  int frame = 0;  // 0: frame 1, 1: frame 2
  // filled by finish()
  double time = NAN, total = NAN, speedup = NAN, thesis_speedup = NAN;
  Errors err;
  double steps_per_ray = NAN, tests_per_ray = NAN, steps_per_s = NAN, tests_per_s = NAN;
  bool ok = false;
};

struct SceneResult {
  SceneFile file;
  std::string skipped;  // why the scene was not measured
  uint32_t width = 0, height = 0;
  std::string integrator;  // the scene's, the ground truth's
  std::vector<Row> rows;
  double gt_time = NAN, gt_tests = NAN;
  std::string notes;
  std::vector<std::unique_ptr<Series>> keep;  // what the rows point to
};

void finish(Row& row, const Frame& gt, double gt_time, double thesis_gt) {
  const Series& s = *row.series;
  if (!s.refused.empty()) {
    row.note = "refused: " + s.refused;
    return;
  }
  if (!s.error.empty()) {
    row.note = s.error.rfind("skipped", 0) == 0 ? s.error : "failed: " + s.error;
    return;
  }
  const Frame& f = s.last[row.frame];
  row.ok = true;
  row.time = median(s.wall[row.frame]);
  row.total = median(s.total[row.frame]);
  row.speedup = gt_time / row.time;
  row.thesis_speedup = thesis_gt / ms_seconds(row.thesis_time.c_str());
  row.err = compare(gt, f);
  const double px = static_cast<double>(f.stats.pixels);
  row.steps_per_ray = f.stats.steps / px;
  row.tests_per_ray = f.stats.tests / px;
  row.steps_per_s = f.stats.steps / row.time;
  row.tests_per_s = f.stats.tests / row.time;
}

std::string table(const SceneResult& sr, int repeats) {
  std::ostringstream md;
  md << "### " << sr.file.name << " (" << sr.width << "×" << sr.height << " pixels";
  if (sr.file.photons) md << ", photon mapped";
  md << "; " << sr.integrator << ")\n\n";
  md << "| technique | thesis time | thesis × | thesis err km | time s | runs | frame s | × vs GT | mean err km "
        "| max err km | object differs | steps/ray | tests/ray | Msteps/s | Mtests/s | rays traced / mirrored / interpolated / cached |\n"
        "|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|\n";
  for (const Row& r : sr.rows) {
    md << "| " << r.label << " | " << (r.thesis_time.empty() ? "–" : r.thesis_time) << " | "
       << fmt("%.2f×", r.thesis_speedup) << " | " << km(r.thesis_err) << " | ";
    if (!r.ok) {
      md << r.note << " | | | | | | | | | | | |\n";
      continue;
    }
    const Frame& f = r.series->last[r.frame];
    md << fmt("%.3f", r.time) << " | " << r.series->runs << " | " << fmt("%.3f", r.total) << " | "
       << fmt("%.2f×", r.speedup) << " | " << km(r.err.mean_km) << " | " << km(r.err.max_km) << " | "
       << fmt("%.3f %%", 100 * r.err.differs) << " | " << fmt("%.1f", r.steps_per_ray) << " | "
       << fmt("%.1f", r.tests_per_ray) << " | " << fmt("%.2f", r.steps_per_s * 1e-6) << " | "
       << fmt("%.2f", r.tests_per_s * 1e-6) << " | " << f.stats.rays_traced << " / " << f.stats.rays_mirrored << " / "
       << f.stats.rays_interpolated << " / " << f.stats.rays_cached << " |\n";
  }
  md << "\ntime s: wall time of arcus_render_frame, median of the runs (up to " << repeats
     << "), warm (every kernel built by untimed frames first); frame s: the frame's own total_seconds; "
        "errors: distance between each pixel's hit point and the ground truth's, over pixels where both hit the "
        "same object; object differs: pixels whose object (or hit/miss) differs; steps and tests per ray: per "
        "pixel, primary rays; rates over the wall time.  Thesis × = the thesis' ground-truth time ÷ its row's.\n";
  if (!sr.notes.empty()) md << sr.notes;
  return md.str();
}

SceneResult run_scene(arcus_context_t* ctx, const SceneFile& file, int repeats, double budget) {
  SceneResult sr;
  sr.file = file;
  arcus_scene_t* scene = nullptr;
  if (arcus_scene_load(ctx, file.path.c_str(), &scene) != ARCUS_SUCCESS) {
    sr.skipped = "cannot load: " + last_error(ctx);
    return sr;
  }
  const ThesisFigures* th = thesis_for(file.name);
  auto t = [&](const char* ThesisFigures::*m) { return th ? std::string(th->*m) : std::string(); };

  // Warm-up: one untimed frame per kind of kernel (the exhaustive trace, the predicted
  // trace, recording and walking paths), so no timed frame pays for a build.
  std::fprintf(stderr, "%s: warm-up\n", file.name.c_str());
  const Series warm = measure(ctx, scene, 0, 1, 1, 0);
  if (!warm.error.empty() || !warm.refused.empty()) {
    sr.skipped = "does not render: " + warm.error + warm.refused;
    arcus_scene_release(scene);
    return sr;
  }
  measure(ctx, scene, kSmart, 2, 1, 0);
  Series sym_probe;
  if (!g_no_paths) sym_probe = measure(ctx, scene, kSmart | kSym | kUnder | kCache, 2, 1, 0);
  const bool symmetric = sym_probe.refused.empty();
  if (!symmetric) measure(ctx, scene, kSmart | kUnder | kCache, 2, 1, 0);

  // The series, in the thesis' order.
  auto& keep = sr.keep;
  auto series = [&](const char* what, uint32_t tech, int frames) {
    std::fprintf(stderr, "%s: %s\n", file.name.c_str(), what);
    if (g_no_paths && (tech & (kSym | kUnder | kCache))) {
      keep.push_back(std::make_unique<Series>());
      keep.back()->error = "skipped (--no-paths)";
      return keep.back().get();
    }
    keep.push_back(std::make_unique<Series>(measure(ctx, scene, tech, frames, repeats, budget)));
    return keep.back().get();
  };
  const Series* gt = series("ground truth", 0, 1);
  if (!gt->error.empty() || gt->runs == 0) {
    sr.skipped = "ground truth failed: " + gt->error;
    arcus_scene_release(scene);
    return sr;
  }
  const Series* smart = series("smart step", kSmart, 2);
  const Series* sym = series("symmetry", kSym, 1);
  const Series* under = series("undersampling", kUnder, 1);
  const Series* cache = series("path caching", kCache, 2);
  const Series* combo = series("combination", kSmart | kUnder, 1);
  const uint32_t all = symmetric ? (kSmart | kSym | kUnder | kCache) : (kSmart | kUnder | kCache);
  const Series* every = series("all four", all, 2);
  // The techniques that change no hit, together: what a resting camera gets exactly.
  const uint32_t exact = symmetric ? (kSmart | kSym | kCache) : (kSmart | kCache);
  const Series* exact_combo = series("exact combination", exact, 2);

  const double thesis_gt = th ? ms_seconds(th->gt) : NAN;
  auto add = [&](std::string label, std::string ttime, double terr, const Series* s, int frame) {
    Row r;
    r.label = std::move(label);
    r.thesis_time = std::move(ttime);
    r.thesis_err = terr;
    r.series = s;
    r.frame = frame;
    sr.rows.push_back(r);
  };
  add("ground truth (no technique)", t(&ThesisFigures::gt), NAN, gt, 0);
  add("parallelization (= ground truth: OpenCL on every core, always on)", t(&ThesisFigures::parallel), NAN, gt, 0);
  add("symmetries", t(&ThesisFigures::symmetry), NAN, sym, 0);
  add("undersampling (α = ½)", t(&ThesisFigures::under), th ? th->under_err : NAN, under, 0);
  add("path caching, frame 1 (builds the cache)", "", NAN, cache, 0);
  add("path caching, frame 2", t(&ThesisFigures::cache), NAN, cache, 1);
  add("smart step, frame 1 (spatial prediction)", t(&ThesisFigures::smart), NAN, smart, 0);
  add("smart step, frame 2 (temporal prediction)", "", NAN, smart, 1);
  add("combination (smart step + undersampling), single frame", t(&ThesisFigures::combo),
      th ? th->combo_err : NAN, combo, 0);
  const std::string all_name = symmetric ? "all four" : "all four less symmetry (refused)";
  add(all_name + ", frame 1", "", NAN, every, 0);
  add(all_name + ", frame 2", "", NAN, every, 1);
  const std::string exact_name = symmetric ? "combination, exact (smart step + symmetry + path caching)"
                                           : "combination, exact (smart step + path caching; symmetry refused)";
  add(exact_name + ", frame 1", "", NAN, exact_combo, 0);
  add(exact_name + ", frame 2", "", NAN, exact_combo, 1);

  const Frame& truth = gt->last[0];
  sr.gt_time = median(gt->wall[0]);
  arcus_renderer_t* r = nullptr;
  if (arcus_renderer_create(scene, &r) == ARCUS_SUCCESS) {
    arcus_camera cam{};
    arcus_renderer_get_camera(r, &cam);
    sr.width = cam.width;
    sr.height = cam.height;
    arcus_advance_params p{};
    arcus_renderer_get_integrator(r, &p);
    static const char* kMethods[] = {"Euler", "RK2", "RK4", "DP45"};
    const std::string m = p.method >= 0 && p.method < 4 ? kMethods[p.method] : "method " + std::to_string(p.method);
    sr.integrator = p.method == ARCUS_METHOD_DP45
                        ? m + " rtol " + fmt("%g", p.rtol) + ", atol " + fmt("%g", p.atol) + " m = " + fmt("%g", p.atol * 1e-3) + " km"
                        : m + " step " + fmt("%g", p.step) + " m";
    arcus_renderer_release(r);
  }
  for (Row& row : sr.rows) finish(row, truth, sr.gt_time, thesis_gt);
  sr.gt_tests = sr.rows[0].tests_per_ray;
  if (!symmetric) sr.notes += "\nSymmetry " + std::string("refused by the library: ") + sym_probe.refused + "\n";
  // The hits are compared: drop them (hundreds of MB over a run of full-size scenes).
  for (auto& s : keep)
    for (Frame& f : s->last) {
      std::vector<double>().swap(f.points);
      std::vector<int32_t>().swap(f.objects);
    }
  arcus_scene_release(scene);
  return sr;
}

struct Options {
  std::vector<std::string> scenes;
  bool quick = false;
  int repeats = 3;
  double budget = 20;
  std::string out;
};

void usage() {
  std::fprintf(stderr,
               "usage: arcus_bench_render [--scenes a.json,b.json] [--quick] [--repeats N] [--budget S] [--frame-limit S] [--no-paths] [--out FILE]\n");
}

}  // namespace

int main(int argc, char** argv) {
  Options opt;
  opt.out = ARCUS_SOURCE_DIR "/bench/results/render.md";
  for (int i = 1; i < argc; ++i) {
    const std::string a = argv[i];
    auto value = [&]() -> std::string {
      if (i + 1 >= argc) {
        usage();
        std::exit(2);
      }
      return argv[++i];
    };
    if (a == "--quick") opt.quick = true;
    else if (a == "--scenes") opt.scenes = split(value(), ',');
    else if (a == "--repeats") opt.repeats = std::max(1, std::atoi(value().c_str()));
    else if (a == "--budget") opt.budget = std::atof(value().c_str());
    else if (a == "--out") opt.out = value();
    else if (a == "--frame-limit") g_frame_limit = std::atof(value().c_str());
    else if (a == "--no-paths") g_no_paths = true;
    else if (a == "-h" || a == "--help") {
      usage();
      return 0;
    } else if (a.size() > 5 && a.substr(a.size() - 5) == ".json") opt.scenes.push_back(a);
    else {
      usage();
      return 2;
    }
  }
  const bool defaults = opt.scenes.empty();
  if (defaults)
    for (const char* name : kDefaultScenes) opt.scenes.push_back(ARCUS_SOURCE_DIR "/scenes/" + std::string(name) + ".json");

  arcus_context_t* ctx = nullptr;
  if (arcus_context_create(ARCUS_DEVICE_DEFAULT, &ctx) != ARCUS_SUCCESS) {
    std::fprintf(stderr, "arcus_bench_render: %s\n", arcus_last_error());
    return 1;
  }
  arcus_device_info dev{};
  arcus_context_get_device(ctx, &dev);
  arcus_device_info listed{};
  if (arcus_device_get_info(dev.index, &listed) == ARCUS_SUCCESS) dev = listed;
  int major = 0, minor = 0, patch = 0;
  arcus_get_version(&major, &minor, &patch);

  fs::path tmp;
  if (opt.quick) {
    std::string pattern = (fs::temp_directory_path() / "arcus_bench_render_XXXXXX").string();
    std::vector<char> buf(pattern.begin(), pattern.end());
    buf.push_back('\0');
    if (!mkdtemp(buf.data())) {
      std::perror("mkdtemp");
      return 1;
    }
    tmp = buf.data();
  }

  const std::string load_before = load_average();
  std::ostringstream head;
  head << "# Rendering techniques against the ground truth (thesis §5.4.2.2, Table 5.2)\n\n"
       << "Machine: " << cpu_model() << ", " << std::thread::hardware_concurrency() << " cores; OpenCL device "
       << dev.name << " (" << dev.platform << ", " << dev.version << ", " << dev.compute_units
       << " compute units); arcus " << major << "." << minor << "." << patch << "; " << utc_now()
       << "; load average before " << load_before << ".\n\n";
  if (opt.quick) head << "**--quick**: every scene at half its width and height (¼ of the pixels; a photon map with ¼ of "
                         "its photons).\n\n";
  head << "The thesis' figures (time m:s, error km) are of its own machine and image sizes; compare the "
          "speed-ups (×), not the times.  The thesis' ground truth: Dormand–Prince at tolerance 1e-6 km; here every "
          "row integrates with the scene's own integrator (named per scene), the ground truth with no technique.\n\n";
  std::fputs(head.str().c_str(), stdout);
  std::fflush(stdout);

  std::string doc = head.str();
  auto save = [&]() {
    std::error_code ec;
    fs::create_directories(fs::path(opt.out).parent_path(), ec);
    std::ofstream o(opt.out);
    o << doc;
    return static_cast<bool>(o);
  };

  std::vector<SceneResult> results;
  for (const std::string& path : opt.scenes) {
    SceneFile f;
    const std::string why = prepare(path, opt.quick, tmp, &f);
    const std::string shown = fs::path(path).filename().string();
    std::string text;
    if (!why.empty()) {
      text = "- " + shown + ": skipped (" + why + ")\n\n";
      std::fprintf(stderr, "%s: skipped (%s)\n", shown.c_str(), why.c_str());
    } else {
      SceneResult sr = run_scene(ctx, f, opt.repeats, opt.budget);
      if (!sr.skipped.empty()) {
        text = "- " + shown + ": skipped (" + sr.skipped + ")\n\n";
        std::fprintf(stderr, "%s: skipped (%s)\n", shown.c_str(), sr.skipped.c_str());
      } else {
        text = table(sr, opt.repeats) + "\n";
        results.push_back(std::move(sr));
      }
    }
    std::fputs(text.c_str(), stdout);
    std::fflush(stdout);
    doc += text;
    save();
  }

  // The targets, on the camera scenes (the photon-mapped cross room is not one).
  std::ostringstream tg;
  tg << "## Targets" << (opt.quick ? " (--quick: scaled scenes, not the targets' size)" : "") << "\n\n";
  auto line = [&](bool pass, const std::string& what) { tg << (pass ? "PASS " : "MISS ") << what << "\n"; };
  size_t checked = 0;
  for (const SceneResult& sr : results) {
    if (sr.file.photons) {
      tg << "(" << sr.file.name << ": photon mapped, not a target scene)\n";
      continue;
    }
    ++checked;
    const ThesisFigures* th = thesis_for(sr.file.name);
    const Row& g = sr.rows[0];
    // The combination target, against the thesis' mean error: on the thesis' own set
    // (one frame), and on the exact set on the camera's second frame at rest.
    auto combination = [&](const Row& c, const std::string& what) {
      if (!c.ok) {
        line(false, sr.file.name + ": " + what + " " + c.note);
        return;
      }
      const bool fast = c.speedup >= 4;
      const bool close = th && c.err.mean_km <= th->combo_err;
      line(fast && close, sr.file.name + ": " + what + " " + fmt("%.2f×", c.speedup) +
                              " faster than ground truth (≥ 4×), mean error " + km(c.err.mean_km) + " km (≤ thesis " +
                              (th ? km(th->combo_err) : std::string("n/a")) + " km)");
    };
    combination(sr.rows[kComboRow], "combination (smart step + undersampling, one frame)");
    combination(sr.rows[kExactComboRow], "combination (smart step + symmetry + path caching, second frame)");
    for (int k = 0; k < 2; ++k) {
      const Row& s = sr.rows[kSmartRow + k];
      if (!s.ok) {
        line(false, sr.file.name + ": smart step " + s.note);
        continue;
      }
      const double cut = sr.gt_tests / s.tests_per_ray;
      line(cut >= 5, sr.file.name + ": smart step frame " + std::to_string(k + 1) + (k ? " (temporal)" : " (spatial)") +
                         " cuts tests per ray " + fmt("%.1f×", cut) + " (" + fmt("%.1f", sr.gt_tests) + " → " +
                         fmt("%.1f", s.tests_per_ray) + "; ≥ 5×)");
    }
    line(g.time < 20, sr.file.name + ": ground truth " + fmt("%.2f", g.time) + " s (< 20 s)");
    for (size_t k : {kComboRow, kExactComboRow}) {
      const Row& c = sr.rows[k];
      if (c.ok) line(c.time < 3, sr.file.name + ": " + c.label + " " + fmt("%.2f", c.time) + " s (< 3 s)");
    }
  }
  if (!checked) tg << "(no camera scene measured)\n";
  tg << "\nLoad average after: " << load_average() << ".\n";
  std::fputs(tg.str().c_str(), stdout);
  doc += tg.str();
  if (save()) std::fprintf(stderr, "wrote %s\n", opt.out.c_str());
  else std::fprintf(stderr, "could not write %s\n", opt.out.c_str());

  if (!tmp.empty()) {
    std::error_code ec;
    fs::remove_all(tmp, ec);
  }
  arcus_context_release(ctx);
  return 0;
}
