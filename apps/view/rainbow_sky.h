// arcus_view's preview of a rainbow sky: the file arcus.sky.export writes (JSON with
// "arcus_rainbow_sky": 1, the members of arcus_rainbow_sky under "sky" and those of
// arcus_rainbow_table under "table", β in a file of little-endian float64 beside it),
// rendered with arcus_rainbow_render; the window's input turns the view and changes
// its field.
#pragma once

#include <memory>
#include <string>

#include "preview.h"

namespace arcus_view {

// True if the file at `path` is a JSON object with the key "arcus_rainbow_sky" (false
// for anything else, unreadable or not JSON: the render scene's loader reports those).
bool is_rainbow_sky_file(const std::string& path);

// Reads the sky and its table (β once, its size checked); throws Failure naming the
// file and what is wrong with it.
std::unique_ptr<Preview> open_rainbow_sky(arcus_context_t* ctx, const std::string& path);

}  // namespace arcus_view
