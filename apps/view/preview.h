// What arcus_view previews, as the window's loop sees it: a scene that renders a frame
// at a fraction of its resolution, with a cancel flag, and takes the window's input.
// One implementation per kind of file: render scenes (render_scene.h) and rainbow skies
// (rainbow_sky.h); the window, the progressive loop and the screenshot (main.cpp) are
// shared.
#pragma once

#include <cstdint>
#include <stdexcept>
#include <string>

#include "arcus/arcus.h"
#include "display.h"

namespace arcus_view {

// An error that ends the program with exit status 2 (or, for a frame the library
// refuses while the window is open, goes to the title).
struct Failure : std::runtime_error {
  using std::runtime_error::runtime_error;
};

// Throws a Failure "what: status: the library's message" unless s is ARCUS_SUCCESS.
inline void check(arcus_context_t* ctx, arcus_status s, const std::string& what) {
  if (s != ARCUS_SUCCESS)
    throw Failure(what + ": " + arcus_status_string(s) + ": " +
                  (ctx ? arcus_context_last_error(ctx) : arcus_last_error()));
}

// Owns a job until the end of the scope.
struct Job {
  arcus_job_t* job = nullptr;
  Job() = default;
  Job(const Job&) = delete;
  Job& operator=(const Job&) = delete;
  ~Job() {
    if (job) arcus_job_release(job);
  }
};

// One rendered frame: the picture to show and its figures for the title.
struct Frame {
  Pixels pixels;
  std::string figures;
};

// The window's input callbacks run inside glfwPollEvents, which the loop also calls from
// a frame's progress callback while the library holds the context's lock: the input
// members only record what was asked for (no arcus calls), and apply() takes it up
// between frames.
class Preview {
 public:
  virtual ~Preview() = default;

  virtual const std::string& name() const = 0;
  // The full resolution: the window's size and the screenshot's.
  virtual uint32_t width() const = 0;
  virtual uint32_t height() const = 0;

  // ---- input (during a frame too: record only)
  // A key pressed or repeated (GLFW key code); Esc is the window's.
  virtual void key(int key, bool repeat, bool shift) = 0;
  // The cursor moved by (dx, dy) pixels with the left button held, in a window of
  // window_width pixels across.
  virtual void drag(double dx, double dy, bool shift, int window_width) = 0;
  virtual void scroll(double dy) = 0;
  // True while input waits to be applied: the frame in flight is cancelled.
  virtual bool pending() const = 0;

  // ---- between frames
  // Applies what the input asked for; true if the image must be rendered again.  A
  // change the library refuses leaves the previous setting and its message in
  // *message; one it accepts clears *message.
  virtual bool apply(std::string* message) = 0;
  // Renders a frame at 1/scale of the full resolution, calling progress(user, fraction)
  // as it goes (non-zero cancels); false if it was cancelled.  Throws Failure when the
  // library refuses the frame.
  virtual bool render(uint32_t scale, arcus_progress_callback progress, void* user, Frame* frame) = 0;
  // The settings for the title (cheap, called between frames only).
  virtual std::string settings() const = 0;
};

}  // namespace arcus_view
