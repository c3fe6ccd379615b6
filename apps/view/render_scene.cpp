#include "render_scene.h"

#include <GLFW/glfw3.h>  // key codes

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <nlohmann/json.hpp>

#include "navigation.h"

namespace arcus_view {
namespace {

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

class RenderScene final : public Preview {
 public:
  explicit RenderScene(arcus_context_t* ctx) : ctx_(ctx) {}
  RenderScene(const RenderScene&) = delete;
  RenderScene& operator=(const RenderScene&) = delete;
  ~RenderScene() override {
    if (renderer_) arcus_renderer_release(renderer_);
    if (scene_) arcus_scene_release(scene_);
  }

  // Separate from the constructor, so that the destructor releases what a failed load
  // had made.
  void load(const std::string& path) {
    check(ctx_, arcus_scene_load(ctx_, path.c_str(), &scene_), "scene");
    check(ctx_, arcus_renderer_create(scene_, &renderer_), "renderer");
    const char* text = nullptr;
    check(ctx_, arcus_scene_get_name(scene_, &text), "scene");
    name_ = text;
    // The exposure is not in the C API; read it from the document as the library did.
    check(ctx_, arcus_scene_get_document(scene_, &text), "scene");
    try {
      exposure_ = nlohmann::json::parse(text).value("exposure", 1.0);
    } catch (const nlohmann::json::exception& e) {
      throw Failure(std::string("scene document: ") + e.what());
    }
    check(ctx_, arcus_renderer_get_camera(renderer_, &home_), "camera");
    check(ctx_, arcus_renderer_get_integrator(renderer_, &scene_integrator_), "integrator");
    accepted_ = wanted_ = home_;
  }

  const std::string& name() const override { return name_; }
  uint32_t width() const override { return home_.width; }
  uint32_t height() const override { return home_.height; }

  void key(int key, bool repeat, bool shift) override {
    const double fine = shift ? 0.1 : 1.0;
    const double step = 0.05 * fine;                                   // of the distance to look_at
    const double angle = fine * home_.vfov_deg / 8 * M_PI / 180.0;     // an eighth of the view
    arcus_camera& c = wanted_;
    switch (key) {
      case GLFW_KEY_W: move(c, step, 0); break;
      case GLFW_KEY_S: move(c, -step, 0); break;
      case GLFW_KEY_A: move(c, 0, -step); break;
      case GLFW_KEY_D: move(c, 0, step); break;
      case GLFW_KEY_LEFT: turn(c, angle, 0); break;
      case GLFW_KEY_RIGHT: turn(c, -angle, 0); break;
      case GLFW_KEY_UP: turn(c, 0, angle); break;
      case GLFW_KEY_DOWN: turn(c, 0, -angle); break;
      default: break;
    }
    if (repeat) return;  // toggles ignore key repeat
    if (key >= GLFW_KEY_1 && key <= GLFW_KEY_4) flip_techniques_ ^= 1u << (key - GLFW_KEY_1);
    if (key == GLFW_KEY_M) ++method_steps_;
    if (key == GLFW_KEY_H) c = home_;
  }

  void drag(double dx, double dy, bool shift, int) override {
    // A quarter degree per pixel: a drag across a small window turns the camera a half
    // circle about look_at; Shift holds it to a fortieth of a degree for narrow views.
    const double rate = (shift ? 0.025 : 0.25) * M_PI / 180.0;
    // Grab and turn: dragging right swings the camera left, dragging down raises it.
    orbit(wanted_, -dx * rate, dy * rate);
  }

  void scroll(double dy) override { move(wanted_, 0.05 * dy, 0); }

  bool pending() const override { return flip_techniques_ != 0 || method_steps_ != 0 || !same(wanted_, accepted_); }

  bool apply(std::string* message) override {
    bool changed = false;
    if (!same(wanted_, accepted_)) {
      if (arcus_renderer_set_camera(renderer_, &wanted_) == ARCUS_SUCCESS) {
        accepted_ = wanted_;
        message->clear();
        changed = true;
      } else {
        *message = arcus_context_last_error(ctx_);
        wanted_ = accepted_;
      }
    }
    if (flip_techniques_) {
      uint32_t techniques = 0;
      arcus_renderer_get_techniques(renderer_, &techniques);
      if (arcus_renderer_set_techniques(renderer_, techniques ^ flip_techniques_) == ARCUS_SUCCESS) {
        message->clear();
        changed = true;
      } else {
        *message = arcus_context_last_error(ctx_);
      }
      flip_techniques_ = 0;
    }
    if (method_steps_) {
      arcus_advance_params p;
      arcus_renderer_get_integrator(renderer_, &p);
      const int32_t method = (p.method + method_steps_) % 4;
      // The scene's own settings for its method; another fixed-step method takes 200
      // steps over the scene's length.
      p = scene_integrator_;
      if (method != p.method) {
        p.method = method;
        if (method != ARCUS_METHOD_DP45) p.step = p.length / 200;
      }
      if (arcus_renderer_set_integrator(renderer_, &p) == ARCUS_SUCCESS) {
        message->clear();
        changed = true;
      } else {
        *message = arcus_context_last_error(ctx_);
      }
      method_steps_ = 0;
    }
    return changed;
  }

  bool render(uint32_t scale, arcus_progress_callback progress, void* user, Frame* frame) override {
    arcus_camera c = accepted_;
    c.width = std::max<uint32_t>(1, c.width / scale);
    c.height = std::max<uint32_t>(1, c.height / scale);
    // The same camera at another size drops the renderer's previous frame; keep it for
    // repeated full-resolution frames, whose hit steps smart step predicts from.
    arcus_camera current;
    check(ctx_, arcus_renderer_get_camera(renderer_, &current), "camera");
    if (!same(current, c)) check(ctx_, arcus_renderer_set_camera(renderer_, &c), "camera");
    Job job;
    const arcus_status s = arcus_render_frame(renderer_, progress, user, &job.job);
    if (s == ARCUS_ERROR_CANCELLED) return false;
    check(ctx_, s, "render");

    arcus_render_stats st;
    uint32_t width = 0, height = 0;
    check(ctx_, arcus_job_get_render_stats(job.job, &st), "stats");
    check(ctx_, arcus_job_get_render_image_size(job.job, &width, &height), "image size");
    std::vector<float> rgb(static_cast<size_t>(width) * height * 3);
    check(ctx_, arcus_job_get_render_image(job.job, rgb.data()), "image");
    frame->pixels = to_srgb8(rgb, width, height, exposure_);
    char buf[160];
    std::snprintf(buf, sizeof buf, "%ux%u%s | %.3f s | %.1f steps/ray | %.1f tests/ray", width, height,
                  scale == 1 ? "" : (" (1/" + std::to_string(scale) + ")").c_str(), st.total_seconds,
                  double(st.steps) / st.pixels, double(st.tests) / st.pixels);
    frame->figures = buf;
    return true;
  }

  std::string settings() const override {
    uint32_t techniques = 0;
    arcus_advance_params p;
    if (arcus_renderer_get_techniques(renderer_, &techniques) != ARCUS_SUCCESS ||
        arcus_renderer_get_integrator(renderer_, &p) != ARCUS_SUCCESS)
      return "";
    return technique_list(techniques) + " | " + kMethodNames[p.method];
  }

 private:
  arcus_context_t* ctx_;
  arcus_scene_t* scene_ = nullptr;
  arcus_renderer_t* renderer_ = nullptr;
  std::string name_;
  double exposure_ = 1;
  arcus_camera home_{}, accepted_{}, wanted_{};  // the scene's, the renderer's, the user's
  arcus_advance_params scene_integrator_{};
  uint32_t flip_techniques_ = 0;  // technique bits to toggle
  int method_steps_ = 0;          // presses of M not yet applied
};

}  // namespace

std::unique_ptr<Preview> open_render_scene(arcus_context_t* ctx, const std::string& path) {
  auto scene = std::make_unique<RenderScene>(ctx);
  scene->load(path);
  return scene;
}

}  // namespace arcus_view
