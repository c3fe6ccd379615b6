// arcus_view: a live preview of a render scene (a scene file with a "camera") in a GLFW
// window, rendered progressively through the library's C API.
//
//   arcus_view SCENE.json [--frames N] [--screenshot OUT.png] [--device N]
//
// Interactive: a frame at 1/4 of the camera's resolution first, then 1/2 and full while
// the camera rests; any input cancels the frame in flight and starts over at 1/4.
//   drag: orbit about look_at   scroll, W/S: forward/back   A/D: strafe   arrows: pan
//   1-4: smart_step, symmetry, undersample, path_cache   M: integrator method
//   H: the scene's camera   Shift: finer moves   Esc: quit
// The title shows the last frame's time, steps and tests per ray, the techniques, the
// method and the library's message when it refuses a change.
//
// With --frames or --screenshot it renders N frames (default 1) at full resolution in
// the window with the camera at rest, then writes what the window shows to OUT.png —
// the same bytes as `arcus_render SCENE.json -o x.exr --png OUT.png`.
// Exit status: 0 on success, 2 on any error (a bad scene, no display).
#include <GLFW/glfw3.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <iostream>
#include <iterator>
#include <nlohmann/json.hpp>
#include <stdexcept>
#include <string>
#include <vector>

#include "arcus/arcus.h"
#include "display.h"
#include "navigation.h"

namespace {

using arcus_view::Pixels;

const char* kUsage =
    "usage: arcus_view SCENE.json [--frames N] [--screenshot OUT.png] [--device N]\n"
    "  --frames N            render N full-resolution frames with the camera at rest, then exit\n"
    "  --screenshot OUT.png  then write what the window shows (implies --frames 1 if not given)\n"
    "  --device N            OpenCL device index (default: ARCUS_DEVICE, else the first GPU, else CPU)\n"
    "keys: drag orbit, scroll/W/S forward/back, A/D strafe, arrows pan, Shift finer,\n"
    "      1-4 smart_step/symmetry/undersample/path_cache, M integrator method, H reset camera, Esc quit\n";

struct Failure : std::runtime_error {
  using std::runtime_error::runtime_error;
};

struct Options {
  std::string scene, screenshot;
  int frames = 0;  // 0: interactive
  int32_t device = ARCUS_DEVICE_DEFAULT;
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
    if (a == "--frames" || a == "--screenshot" || a == "--device") {
      if (i + 1 == args.size()) throw Failure(a + ": missing value\n" + std::string(kUsage));
      const std::string& v = args[++i];
      if (a == "--frames") o.frames = static_cast<int>(parse_count(a, v, 1, 100000));
      if (a == "--screenshot") o.screenshot = v;
      if (a == "--device") o.device = static_cast<int32_t>(parse_count(a, v, 0, INT32_MAX));
      continue;
    }
    if (!a.empty() && a[0] == '-') throw Failure("unknown option " + a + "\n" + std::string(kUsage));
    if (!o.scene.empty()) throw Failure(std::string("more than one scene given\n") + kUsage);
    o.scene = a;
  }
  if (o.scene.empty()) throw Failure(std::string("a scene is required\n") + kUsage);
  if (!o.screenshot.empty() && o.frames == 0) o.frames = 1;
  return o;
}

const char* const kTechniqueNames[] = {"smart_step", "symmetry", "undersample", "path_cache"};
const char* const kMethodNames[] = {"Euler", "RK2", "RK4", "DP45"};

std::string technique_list(uint32_t bits) {
  std::string s;
  for (int t = 0; t < 4; ++t)
    if (bits & (1u << t)) s += std::string(s.empty() ? "" : "+") + kTechniqueNames[t];
  return s.empty() ? "no techniques" : s;
}

bool same(const arcus_camera& a, const arcus_camera& b) {
  return std::equal(a.position, a.position + 3, b.position) && std::equal(a.look_at, a.look_at + 3, b.look_at) &&
         std::equal(a.up, a.up + 3, b.up) && a.vfov_deg == b.vfov_deg && a.width == b.width && a.height == b.height;
}

// The view's state.  GLFW's input callbacks run inside glfwPollEvents, which the loop
// also calls from the frame's progress callback while the context's lock is held, so
// they only record what was asked for (no arcus calls); the loop applies it between
// frames.
struct App {
  arcus_context_t* ctx = nullptr;
  arcus_renderer_t* renderer = nullptr;
  GLFWwindow* window = nullptr;
  bool interactive = true;
  std::string name;
  double exposure = 1;
  arcus_camera home{}, accepted{}, wanted{};  // the scene's, the renderer's, the user's
  arcus_advance_params scene_integrator{};
  uint32_t flip_techniques = 0;  // technique bits to toggle
  int method_steps = 0;          // presses of M not yet applied
  bool dragging = false;
  double drag_x = 0, drag_y = 0;
  Pixels shown;
  std::string figures, message, activity;  // parts of the title
  std::string title;                       // as last set

  bool pending() const {
    return flip_techniques != 0 || method_steps != 0 || !same(wanted, accepted);
  }
};

App& app_of(GLFWwindow* w) { return *static_cast<App*>(glfwGetWindowUserPointer(w)); }

void check(App& app, arcus_status s, const char* what) {
  if (s != ARCUS_SUCCESS)
    throw Failure(std::string(what) + ": " + arcus_status_string(s) + ": " +
                  (app.ctx ? arcus_context_last_error(app.ctx) : arcus_last_error()));
}

// Setting a title sends the window an X event, which would wake glfwWaitEvents at once:
// set it only when it changes, or the resting view spins.
void set_title(App& app, const std::string& title) {
  if (title == app.title) return;
  app.title = title;
  glfwSetWindowTitle(app.window, title.c_str());
}

void update_title(App& app) {
  uint32_t techniques = 0;
  arcus_advance_params p;
  std::string title = "arcus_view: " + app.name;
  if (!app.activity.empty()) title += " | " + app.activity;
  if (!app.figures.empty()) title += " | " + app.figures;
  // Cheap getters, but never from inside a frame: update_title runs between frames only.
  if (arcus_renderer_get_techniques(app.renderer, &techniques) == ARCUS_SUCCESS &&
      arcus_renderer_get_integrator(app.renderer, &p) == ARCUS_SUCCESS)
    title += " | " + technique_list(techniques) + " | " + kMethodNames[p.method];
  if (!app.message.empty()) title += " | " + app.message;
  set_title(app, title);
}

void present(App& app) {
  int w = 0, h = 0;
  glfwGetFramebufferSize(app.window, &w, &h);
  arcus_view::draw(app.shown, w, h);
  glfwSwapBuffers(app.window);
}

// ---- input: records requests only (see App) ----------------------------------------

void on_key(GLFWwindow* w, int key, int, int action, int mods) {
  App& app = app_of(w);
  if (key == GLFW_KEY_ESCAPE && action == GLFW_PRESS) glfwSetWindowShouldClose(w, GLFW_TRUE);
  if (!app.interactive || action == GLFW_RELEASE) return;
  const double fine = (mods & GLFW_MOD_SHIFT) ? 0.1 : 1.0;
  const double step = 0.05 * fine;                                      // of the distance to look_at
  const double angle = fine * app.home.vfov_deg / 8 * M_PI / 180.0;     // an eighth of the view
  arcus_camera& c = app.wanted;
  switch (key) {
    case GLFW_KEY_W: arcus_view::move(c, step, 0); break;
    case GLFW_KEY_S: arcus_view::move(c, -step, 0); break;
    case GLFW_KEY_A: arcus_view::move(c, 0, -step); break;
    case GLFW_KEY_D: arcus_view::move(c, 0, step); break;
    case GLFW_KEY_LEFT: arcus_view::turn(c, angle, 0); break;
    case GLFW_KEY_RIGHT: arcus_view::turn(c, -angle, 0); break;
    case GLFW_KEY_UP: arcus_view::turn(c, 0, angle); break;
    case GLFW_KEY_DOWN: arcus_view::turn(c, 0, -angle); break;
    default: break;
  }
  if (action != GLFW_PRESS) return;  // toggles ignore key repeat
  if (key >= GLFW_KEY_1 && key <= GLFW_KEY_4) app.flip_techniques ^= 1u << (key - GLFW_KEY_1);
  if (key == GLFW_KEY_M) ++app.method_steps;
  if (key == GLFW_KEY_H) c = app.home;
}

void on_scroll(GLFWwindow* w, double, double dy) {
  App& app = app_of(w);
  if (app.interactive) arcus_view::move(app.wanted, 0.05 * dy, 0);
}

void on_button(GLFWwindow* w, int button, int action, int) {
  App& app = app_of(w);
  if (button != GLFW_MOUSE_BUTTON_LEFT) return;
  app.dragging = app.interactive && action == GLFW_PRESS;
  glfwGetCursorPos(w, &app.drag_x, &app.drag_y);
}

void on_cursor(GLFWwindow* w, double x, double y) {
  App& app = app_of(w);
  if (!app.dragging) return;
  // A quarter degree per pixel: a drag across a small window turns the camera a half
  // circle about look_at; Shift holds it to a fortieth of a degree for narrow views.
  const double rate = (glfwGetKey(w, GLFW_KEY_LEFT_SHIFT) == GLFW_PRESS ? 0.025 : 0.25) * M_PI / 180.0;
  // Grab and turn: dragging right swings the camera left, dragging down raises it.
  arcus_view::orbit(app.wanted, -(x - app.drag_x) * rate, (y - app.drag_y) * rate);
  app.drag_x = x;
  app.drag_y = y;
}

void on_refresh(GLFWwindow* w) { present(app_of(w)); }

// Keeps the window responsive while a frame renders (slices of about 0.25 s) and
// cancels the frame as soon as there is input to apply.
int on_progress(void* user, double fraction) {
  App& app = *static_cast<App*>(user);
  glfwPollEvents();
  if (!app.interactive) return 0;
  char buf[64];
  std::snprintf(buf, sizeof buf, "%.0f%%", 100 * fraction);
  set_title(app, "arcus_view: " + app.name + " | " + app.activity + " " + buf);
  return app.pending() || glfwWindowShouldClose(app.window) ? 1 : 0;
}

// ---- between frames -------------------------------------------------------------------

// Applies what the input asked for; true if the image must be rendered again.  A change
// the library refuses leaves the previous setting, and its message goes to the title.
bool apply_requests(App& app) {
  bool changed = false;
  if (!same(app.wanted, app.accepted)) {
    if (arcus_renderer_set_camera(app.renderer, &app.wanted) == ARCUS_SUCCESS) {
      app.accepted = app.wanted;
      app.message.clear();
      changed = true;
    } else {
      app.message = arcus_context_last_error(app.ctx);
      app.wanted = app.accepted;
    }
  }
  if (app.flip_techniques) {
    uint32_t techniques = 0;
    arcus_renderer_get_techniques(app.renderer, &techniques);
    if (arcus_renderer_set_techniques(app.renderer, techniques ^ app.flip_techniques) == ARCUS_SUCCESS) {
      app.message.clear();
      changed = true;
    } else {
      app.message = arcus_context_last_error(app.ctx);
    }
    app.flip_techniques = 0;
  }
  if (app.method_steps) {
    arcus_advance_params p;
    arcus_renderer_get_integrator(app.renderer, &p);
    const int32_t method = (p.method + app.method_steps) % 4;
    // The scene's own settings for its method; another fixed-step method takes 200
    // steps over the scene's length.
    p = app.scene_integrator;
    if (method != p.method) {
      p.method = method;
      if (method != ARCUS_METHOD_DP45) p.step = p.length / 200;
    }
    if (arcus_renderer_set_integrator(app.renderer, &p) == ARCUS_SUCCESS) {
      app.message.clear();
      changed = true;
    } else {
      app.message = arcus_context_last_error(app.ctx);
    }
    app.method_steps = 0;
  }
  return changed;
}

// Renders one frame at 1/scale of the camera's resolution; false if it was cancelled.
bool render(App& app, uint32_t scale, arcus_job_t** job) {
  arcus_camera c = app.accepted;
  c.width = std::max<uint32_t>(1, c.width / scale);
  c.height = std::max<uint32_t>(1, c.height / scale);
  // The same camera at another size drops the renderer's previous frame; keep it for
  // repeated full-resolution frames, whose hit steps smart step predicts from.
  arcus_camera current;
  check(app, arcus_renderer_get_camera(app.renderer, &current), "camera");
  if (!same(current, c)) check(app, arcus_renderer_set_camera(app.renderer, &c), "camera");
  app.activity = scale == 1 ? "rendering" : "rendering 1/" + std::to_string(scale);
  const arcus_status s = arcus_render_frame(app.renderer, on_progress, &app, job);
  if (s == ARCUS_ERROR_CANCELLED) return false;
  check(app, s, "render");

  arcus_render_stats st;
  uint32_t width = 0, height = 0;
  check(app, arcus_job_get_render_stats(*job, &st), "stats");
  check(app, arcus_job_get_image_size(*job, &width, &height), "image size");
  std::vector<float> rgb(static_cast<size_t>(width) * height * 3);
  check(app, arcus_job_get_image(*job, rgb.data()), "image");
  app.shown = arcus_view::to_srgb8(rgb, width, height, app.exposure);
  char buf[160];
  std::snprintf(buf, sizeof buf, "%ux%u%s | %.3f s | %.1f steps/ray | %.1f tests/ray", width, height,
                scale == 1 ? "" : (" (1/" + std::to_string(scale) + ")").c_str(), st.total_seconds,
                double(st.steps) / st.pixels, double(st.tests) / st.pixels);
  app.figures = buf;
  app.activity.clear();
  return true;
}

struct Job {
  arcus_job_t* job = nullptr;
  ~Job() { reset(); }
  void reset() {
    if (job) arcus_job_release(job);
    job = nullptr;
  }
};

void run_interactive(App& app) {
  const uint32_t kScales[] = {4, 2, 1};
  size_t level = 0;  // the next scale to render; past the end: the camera rests, wait
  Job job;
  while (!glfwWindowShouldClose(app.window)) {
    if (apply_requests(app)) level = 0;
    if (level == std::size(kScales)) {
      update_title(app);
      glfwWaitEvents();
      continue;
    }
    job.reset();
    try {
      if (!render(app, kScales[level], &job.job)) continue;  // input arrived: apply it
      ++level;
    } catch (const Failure& e) {
      // A frame the library refuses (say, out of device memory) stops the refinement
      // until the next change; the message stays in the title.
      app.message = e.what();
      std::fprintf(stderr, "arcus_view: %s\n", e.what());
      level = std::size(kScales);
    }
    present(app);
    update_title(app);
  }
}

void run_frames(App& app, int frames, const std::string& screenshot) {
  Job job;
  for (int f = 1; f <= frames; ++f) {
    job.reset();
    render(app, 1, &job.job);
    present(app);
    update_title(app);
    std::printf("frame %d: %s\n", f, app.figures.c_str());
  }
  if (screenshot.empty()) return;
  int w = 0, h = 0;
  glfwGetFramebufferSize(app.window, &w, &h);
  // Draw once more and read the back buffer before it is swapped: that is the image
  // the window shows (a swapped-out buffer's contents are undefined).
  arcus_view::draw(app.shown, w, h);
  const Pixels pixels = arcus_view::read_back(w, h);
  glfwSwapBuffers(app.window);
  try {
    arcus_view::write_png(screenshot, pixels);
  } catch (const std::runtime_error& e) {
    throw Failure(e.what());
  }
  std::printf("wrote %s (%dx%d)\n", screenshot.c_str(), w, h);
}

std::string glfw_error;
void on_glfw_error(int, const char* description) { glfw_error = description; }

// A window of the camera's aspect: its size, or shrunk to fit the screen.  Frames for a
// screenshot must be shown 1:1, so there the window must fit as it is.
GLFWwindow* open_window(const App& app, bool fixed_size) {
  int width = static_cast<int>(app.home.width), height = static_cast<int>(app.home.height);
  int x = 0, y = 0, area_w = 0, area_h = 0;
  if (GLFWmonitor* monitor = glfwGetPrimaryMonitor()) glfwGetMonitorWorkarea(monitor, &x, &y, &area_w, &area_h);
  if (area_w > 0 && area_h > 0 && (width > area_w || height > area_h)) {
    if (fixed_size)
      throw Failure("the screen (" + std::to_string(area_w) + "x" + std::to_string(area_h) +
                    ") is too small to show the camera's " + std::to_string(width) + "x" + std::to_string(height) +
                    " pixels 1:1");
    const double shrink = std::min(double(area_w) / width, double(area_h) / height);
    width = std::max(1, static_cast<int>(width * shrink));
    height = std::max(1, static_cast<int>(height * shrink));
  }
  glfwWindowHint(GLFW_RESIZABLE, fixed_size ? GLFW_FALSE : GLFW_TRUE);
  GLFWwindow* w = glfwCreateWindow(width, height, ("arcus_view: " + app.name).c_str(), nullptr, nullptr);
  if (!w) throw Failure("cannot open a window: " + glfw_error);
  if (!fixed_size) glfwSetWindowAspectRatio(w, static_cast<int>(app.home.width), static_cast<int>(app.home.height));
  return w;
}

}  // namespace

int main(int argc, char** argv) {
  App app;
  arcus_scene_t* scene = nullptr;
  bool glfw = false;
  int code = 0;
  try {
    const Options o = parse_options(argc, argv);
    app.interactive = o.frames == 0;
    check(app, arcus_context_create(o.device, &app.ctx), "context");
    check(app, arcus_scene_load(app.ctx, o.scene.c_str(), &scene), "scene");
    check(app, arcus_renderer_create(scene, &app.renderer), "renderer");
    const char* text = nullptr;
    check(app, arcus_scene_get_name(scene, &text), "scene");
    app.name = text;
    // The exposure is not in the C API; read it from the document as the library did.
    check(app, arcus_scene_get_document(scene, &text), "scene");
    app.exposure = nlohmann::json::parse(text).value("exposure", 1.0);
    check(app, arcus_renderer_get_camera(app.renderer, &app.home), "camera");
    check(app, arcus_renderer_get_integrator(app.renderer, &app.scene_integrator), "integrator");
    app.accepted = app.wanted = app.home;

    glfwSetErrorCallback(on_glfw_error);
    if (!glfwInit()) throw Failure("cannot open a window: " + glfw_error);
    glfw = true;
    app.window = open_window(app, !app.interactive);
    glfwSetWindowUserPointer(app.window, &app);
    glfwMakeContextCurrent(app.window);
    glfwSwapInterval(1);
    glfwSetKeyCallback(app.window, on_key);
    glfwSetScrollCallback(app.window, on_scroll);
    glfwSetMouseButtonCallback(app.window, on_button);
    glfwSetCursorPosCallback(app.window, on_cursor);
    glfwSetWindowRefreshCallback(app.window, on_refresh);
    if (!app.interactive) {
      int w = 0, h = 0;
      glfwGetFramebufferSize(app.window, &w, &h);
      if (w != static_cast<int>(app.home.width) || h != static_cast<int>(app.home.height))
        throw Failure("the window's framebuffer is " + std::to_string(w) + "x" + std::to_string(h) +
                      ", not the camera's " + std::to_string(app.home.width) + "x" + std::to_string(app.home.height));
    }
    if (app.interactive)
      run_interactive(app);
    else
      run_frames(app, o.frames, o.screenshot);
  } catch (const Failure& e) {
    std::fprintf(stderr, "arcus_view: %s\n", e.what());
    code = 2;
  } catch (const nlohmann::json::exception& e) {
    std::fprintf(stderr, "arcus_view: scene document: %s\n", e.what());
    code = 2;
  }
  if (app.window) glfwDestroyWindow(app.window);
  if (glfw) glfwTerminate();
  if (app.renderer) arcus_renderer_release(app.renderer);
  if (scene) arcus_scene_release(scene);
  if (app.ctx) arcus_context_release(app.ctx);
  return code;
}
