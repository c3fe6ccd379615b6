// arcus_view: a live preview in a GLFW window, rendered progressively through the
// library's C API, of
//   - a render scene (a scene file with a "camera"), rendered with arcus_render_frame;
//   - a rainbow sky (a file from arcus.sky.export: JSON with "arcus_rainbow_sky", its β
//     beside it), rendered with arcus_rainbow_render.
//
//   arcus_view FILE.json [--frames N] [--screenshot OUT.png] [--device N]
//
// Interactive: a frame at 1/4 of the resolution first, then 1/2 and full while the view
// rests; any input cancels the frame in flight and starts over at 1/4.
//   render scenes:
//     drag: orbit about look_at   scroll, W/S: forward/back   A/D: strafe   arrows: pan
//     1-4: smart_step, symmetry, undersample, path_cache   M: integrator method
//     H: the scene's camera   Shift: finer moves
//   rainbow skies (the camera stays put; the horizon stays level):
//     drag: turn the view (the sky follows the cursor)   arrows: turn   scroll: field
//     of view (5°-150°)   H: the file's camera   Shift: finer turns
//   Esc: quit
// The title shows the last frame's time and figures, then the scene's settings
// (techniques and method; a sky's field, direction and description) and the library's
// message when it refuses a change or a frame.
//
// With --frames or --screenshot it renders N frames (default 1) at full resolution in
// the window with the view at rest, then writes what the window shows to OUT.png — the
// same bytes as `arcus_render SCENE.json -o x.exr --png OUT.png` for a render scene, and
// as arcus_job_write_rainbow_image(job, NULL, OUT.png) of the file's sky for a sky.
// Exit status: 0 on success, 2 on any error (a bad scene or sky file, no display).
//
// The window, the progressive loop and the screenshot are shared here; what is
// previewed is a Preview (preview.h): render_scene.cpp, rainbow_sky.cpp.
#include <GLFW/glfw3.h>

#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <iostream>
#include <iterator>
#include <memory>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "arcus/arcus.h"
#include "display.h"
#include "preview.h"
#include "rainbow_sky.h"
#include "render_scene.h"

namespace {

using arcus_view::Failure;
using arcus_view::Frame;
using arcus_view::Preview;

const char* kUsage =
    "usage: arcus_view FILE.json [--frames N] [--screenshot OUT.png] [--device N]\n"
    "  FILE.json             a render scene, or a rainbow sky written by arcus.sky.export\n"
    "  --frames N            render N full-resolution frames with the view at rest, then exit\n"
    "  --screenshot OUT.png  then write what the window shows (implies --frames 1 if not given)\n"
    "  --device N            OpenCL device index (default: ARCUS_DEVICE, else the first GPU, else CPU)\n"
    "keys, render scenes: drag orbit, scroll/W/S forward/back, A/D strafe, arrows pan, Shift finer,\n"
    "      1-4 smart_step/symmetry/undersample/path_cache, M integrator method, H reset camera\n"
    "keys, rainbow skies: drag/arrows turn the view, scroll field of view, Shift finer, H reset camera\n"
    "      Esc quits\n";

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

// The window's state.  GLFW's input callbacks run inside glfwPollEvents, which the loop
// also calls from the frame's progress callback while the context's lock is held, so
// they only record what was asked for (Preview's input members); the loop applies it
// between frames.
struct App {
  Preview* preview = nullptr;
  GLFWwindow* window = nullptr;
  bool interactive = true;
  bool dragging = false;
  double drag_x = 0, drag_y = 0;
  arcus_view::Pixels shown;
  std::string figures, message, activity;  // parts of the title
  std::string title;                       // as last set
};

App& app_of(GLFWwindow* w) { return *static_cast<App*>(glfwGetWindowUserPointer(w)); }

// Setting a title sends the window an X event, which would wake glfwWaitEvents at once:
// set it only when it changes, or the resting view spins.
void set_title(App& app, const std::string& title) {
  if (title == app.title) return;
  app.title = title;
  glfwSetWindowTitle(app.window, title.c_str());
}

// Between frames only (the preview's settings are read from the library).
void update_title(App& app) {
  std::string title = "arcus_view: " + app.preview->name();
  for (const std::string& part : {app.activity, app.figures, app.preview->settings(), app.message})
    if (!part.empty()) title += " | " + part;
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
  if (app.interactive && action != GLFW_RELEASE)
    app.preview->key(key, action == GLFW_REPEAT, (mods & GLFW_MOD_SHIFT) != 0);
}

void on_scroll(GLFWwindow* w, double, double dy) {
  App& app = app_of(w);
  if (app.interactive) app.preview->scroll(dy);
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
  int width = 0, height = 0;
  glfwGetWindowSize(w, &width, &height);  // the cursor's units
  app.preview->drag(x - app.drag_x, y - app.drag_y, glfwGetKey(w, GLFW_KEY_LEFT_SHIFT) == GLFW_PRESS, width);
  app.drag_x = x;
  app.drag_y = y;
}

void on_refresh(GLFWwindow* w) { present(app_of(w)); }

// Keeps the window responsive while a frame renders (slices of about 0.25 s) and
// cancels the frame as soon as there is input to apply.
int32_t on_progress(void* user, double fraction) {
  App& app = *static_cast<App*>(user);
  glfwPollEvents();
  if (!app.interactive) return 0;
  char buf[64];
  std::snprintf(buf, sizeof buf, "%.0f%%", 100 * fraction);
  set_title(app, "arcus_view: " + app.preview->name() + " | " + app.activity + " " + buf);
  return app.preview->pending() || glfwWindowShouldClose(app.window) ? 1 : 0;
}

// ---- frames -----------------------------------------------------------------------------

// Renders one frame at 1/scale of the full resolution into app.shown; false if it was
// cancelled.
bool render(App& app, uint32_t scale) {
  app.activity = scale == 1 ? "rendering" : "rendering 1/" + std::to_string(scale);
  Frame frame;
  bool done = false;
  try {
    done = app.preview->render(scale, on_progress, &app, &frame);
  } catch (...) {
    app.activity.clear();
    throw;
  }
  app.activity.clear();
  if (!done) return false;
  app.shown = std::move(frame.pixels);
  app.figures = std::move(frame.figures);
  return true;
}

void run_interactive(App& app) {
  const uint32_t kScales[] = {4, 2, 1};
  size_t level = 0;  // the next scale to render; past the end: the view rests, wait
  while (!glfwWindowShouldClose(app.window)) {
    if (app.preview->apply(&app.message)) level = 0;
    if (level == std::size(kScales)) {
      update_title(app);
      glfwWaitEvents();
      continue;
    }
    try {
      if (!render(app, kScales[level])) continue;  // input arrived: apply it
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
  for (int f = 1; f <= frames; ++f) {
    render(app, 1);
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
  const arcus_view::Pixels pixels = arcus_view::read_back(w, h);
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

// A window of the preview's aspect: its size, or shrunk to fit the screen.  Frames for a
// screenshot must be shown 1:1, so there the window must fit as it is.
GLFWwindow* open_window(const Preview& preview, bool fixed_size) {
  const int full_w = static_cast<int>(preview.width()), full_h = static_cast<int>(preview.height());
  int width = full_w, height = full_h;
  int x = 0, y = 0, area_w = 0, area_h = 0;
  if (GLFWmonitor* monitor = glfwGetPrimaryMonitor()) glfwGetMonitorWorkarea(monitor, &x, &y, &area_w, &area_h);
  if (area_w > 0 && area_h > 0 && (width > area_w || height > area_h)) {
    if (fixed_size)
      throw Failure("the screen (" + std::to_string(area_w) + "x" + std::to_string(area_h) +
                    ") is too small to show the image's " + std::to_string(width) + "x" + std::to_string(height) +
                    " pixels 1:1");
    const double shrink = std::min(double(area_w) / width, double(area_h) / height);
    width = std::max(1, static_cast<int>(width * shrink));
    height = std::max(1, static_cast<int>(height * shrink));
  }
  glfwWindowHint(GLFW_RESIZABLE, fixed_size ? GLFW_FALSE : GLFW_TRUE);
  GLFWwindow* w = glfwCreateWindow(width, height, ("arcus_view: " + preview.name()).c_str(), nullptr, nullptr);
  if (!w) throw Failure("cannot open a window: " + glfw_error);
  if (!fixed_size) glfwSetWindowAspectRatio(w, full_w, full_h);
  if (fixed_size) {
    int fb_w = 0, fb_h = 0;
    glfwGetFramebufferSize(w, &fb_w, &fb_h);
    if (fb_w != full_w || fb_h != full_h) {
      glfwDestroyWindow(w);
      throw Failure("the window's framebuffer is " + std::to_string(fb_w) + "x" + std::to_string(fb_h) +
                    ", not the image's " + std::to_string(full_w) + "x" + std::to_string(full_h));
    }
  }
  return w;
}

std::unique_ptr<Preview> open_preview(arcus_context_t* ctx, const std::string& path) {
  if (arcus_view::is_rainbow_sky_file(path)) return arcus_view::open_rainbow_sky(ctx, path);
  return arcus_view::open_render_scene(ctx, path);
}

}  // namespace

int main(int argc, char** argv) {
  App app;
  arcus_context_t* ctx = nullptr;
  std::unique_ptr<Preview> preview;
  bool glfw = false;
  int code = 0;
  try {
    const Options o = parse_options(argc, argv);
    app.interactive = o.frames == 0;
    arcus_view::check(nullptr, arcus_context_create(o.device, &ctx), "context");
    preview = open_preview(ctx, o.scene);
    app.preview = preview.get();

    glfwSetErrorCallback(on_glfw_error);
    if (!glfwInit()) throw Failure("cannot open a window: " + glfw_error);
    glfw = true;
    app.window = open_window(*preview, !app.interactive);
    glfwSetWindowUserPointer(app.window, &app);
    glfwMakeContextCurrent(app.window);
    glfwSwapInterval(1);
    glfwSetKeyCallback(app.window, on_key);
    glfwSetScrollCallback(app.window, on_scroll);
    glfwSetMouseButtonCallback(app.window, on_button);
    glfwSetCursorPosCallback(app.window, on_cursor);
    glfwSetWindowRefreshCallback(app.window, on_refresh);
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
  preview.reset();  // its renderer before the context
  if (ctx) arcus_context_release(ctx);
  return code;
}
