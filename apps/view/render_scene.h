// arcus_view's preview of a render scene (a scene file with a "camera"): a renderer of
// the library's, its camera moved by the window's input, its techniques and integrator
// method switched by keys.
#pragma once

#include <memory>
#include <string>

#include "preview.h"

namespace arcus_view {

// Loads the scene at `path` into a renderer on `ctx`; throws Failure with the library's
// message.
std::unique_ptr<Preview> open_render_scene(arcus_context_t* ctx, const std::string& path);

}  // namespace arcus_view
