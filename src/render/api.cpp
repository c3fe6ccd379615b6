// The C entry points of arcus_render.h: renderers, frames and render jobs.
#include <memory>
#include <string>

#include "arcus/arcus_render.h"
#include "core/call.h"
#include "image/image_io.h"
#include "curved/advance.h"
#include "render/renderer.h"

using arcus::require;
using arcus::require_pointer;
using arcus::render::RenderJob;
using namespace arcus::api;

namespace {

template <class Body>
arcus_status on_renderer(arcus_renderer_t* r, Body&& body) {
  return simple<arcus_renderer_s>(r, arcus::render::kRendererHandle, "renderer", body);
}

template <class Body>
arcus_status on_render_job(arcus_job_t* job, Body&& body) {
  return on_job<RenderJob>(job, "a render job", body);
}

}  // namespace

extern "C" {

arcus_status arcus_renderer_create(arcus_scene_t* scene, arcus_renderer_t** out) {
  return simple<arcus_scene_s>(scene, arcus::scene::kSceneHandle, "scene", [&](arcus_scene_s* s) {
    require_pointer(out, "out");
    *out = nullptr;
    auto* rs = arcus::render::render_scene(s);
    auto r = std::make_unique<arcus_renderer_s>(s->owner(), rs);
    arcus::retain_context(s->owner());  // the renderer's reference, dropped with it
    *out = r.release();
  });
}

arcus_status arcus_renderer_retain(arcus_renderer_t* r) { return retain(r, arcus::render::kRendererHandle, "renderer"); }
arcus_status arcus_renderer_release(arcus_renderer_t* r) { return release(r, arcus::render::kRendererHandle, "renderer"); }

arcus_status arcus_renderer_set_techniques(arcus_renderer_t* r, uint32_t techniques) {
  return on<arcus_renderer_s>(r, arcus::render::kRendererHandle, "renderer", [&](arcus_renderer_s* x, std::string*) {
    const std::string problem = arcus::render::technique_problem(*x, techniques);
    if (!problem.empty()) arcus::fail(ARCUS_ERROR_UNSUPPORTED, problem);
    x->techniques = techniques;
    return ARCUS_SUCCESS;
  });
}

arcus_status arcus_renderer_get_techniques(arcus_renderer_t* r, uint32_t* techniques) {
  return on_renderer(r, [&](arcus_renderer_s* x) {
    require_pointer(techniques, "techniques");
    *techniques = x->techniques;
  });
}

arcus_status arcus_renderer_set_camera(arcus_renderer_t* r, const arcus_camera* camera) {
  return on_renderer(r, [&](arcus_renderer_s* x) {
    require_pointer(camera, "camera");
    const arcus::scene::CameraDesc d = arcus::scene::camera_desc(*camera);
    arcus::scene::check_camera(d, "camera");
    for (int a = 0; a < 3; ++a)
      require(d.position[a] > x->scene->lo[a] && d.position[a] < x->scene->hi[a],
              "camera: the position must lie inside the scene's bounds");
    x->camera = d;
    x->reset_frames();
  });
}

arcus_status arcus_renderer_get_camera(arcus_renderer_t* r, arcus_camera* camera) {
  return on_renderer(r, [&](arcus_renderer_s* x) {
    require_pointer(camera, "camera");
    *camera = arcus::scene::camera_struct(x->camera);
  });
}

arcus_status arcus_renderer_set_integrator(arcus_renderer_t* r, const arcus_advance_params* params) {
  return on_renderer(r, [&](arcus_renderer_s* x) {
    require_pointer(params, "params");
    arcus_advance_params p = *params;
    p.length = x->scene->desc.params.length;
    p.use_box = 0;
    p.record_path = 0;
    p.progress = nullptr;
    arcus::curved::check_advance_params(p, x->scene->field->desc.kind == ARCUS_KIND_CONSTANT);
    x->params = p;
    x->reset_frames();
  });
}

arcus_status arcus_renderer_get_integrator(arcus_renderer_t* r, arcus_advance_params* params) {
  return on_renderer(r, [&](arcus_renderer_s* x) {
    require_pointer(params, "params");
    *params = x->params;
  });
}

arcus_status arcus_render_frame(arcus_renderer_t* r, arcus_progress_callback progress, void* user, arcus_job_t** job) {
  return on_renderer(r, [&](arcus_renderer_s* x) {
    require_pointer(job, "job");
    *job = nullptr;
    auto j = arcus::render::render_frame(x, progress, user);
    arcus::retain_context(x->owner());  // the job's reference
    *job = j.release();
  });
}

arcus_status arcus_job_get_render_stats(arcus_job_t* job, arcus_render_stats* stats) {
  return on_render_job(job, [&](RenderJob* j) {
    require_pointer(stats, "stats");
    *stats = j->render_stats;
  });
}

arcus_status arcus_job_get_render_image_size(arcus_job_t* job, uint32_t* width, uint32_t* height) {
  return on_render_job(job, [&](RenderJob* j) {
    if (width) *width = j->width;
    if (height) *height = j->height;
  });
}

arcus_status arcus_job_get_render_image(arcus_job_t* job, float* rgb) {
  return on_render_job(job, [&](RenderJob* j) {
    require_pointer(rgb, "rgb");
    copy_out(j->rgb, rgb);
  });
}

arcus_status arcus_job_get_render_hits(arcus_job_t* job, double* points, int32_t* objects, int32_t* primitives,
                                       double* distances, uint32_t* steps, uint32_t* tests) {
  return on_render_job(job, [&](RenderJob* j) {
    copy_out(j->points, points);
    copy_out(j->objects, objects);
    copy_out(j->primitives, primitives);
    copy_out(j->distances, distances);
    copy_out(j->steps, steps);
    copy_out(j->tests, tests);
  });
}

arcus_status arcus_job_write_render_image(arcus_job_t* job, const char* exr_path, const char* png_path) {
  return on_render_job(job, [&](RenderJob* j) {
    arcus::image::Image img;
    img.width = static_cast<int>(j->width);
    img.height = static_cast<int>(j->height);
    img.channels = {"R", "G", "B", "distance", "steps", "tests"};
    const size_t n = static_cast<size_t>(j->width) * j->height;
    img.pixels.resize(n * img.channels.size());
    for (size_t p = 0; p < n; ++p) {
      float* px = &img.pixels[p * img.channels.size()];
      px[0] = j->rgb[3 * p];
      px[1] = j->rgb[3 * p + 1];
      px[2] = j->rgb[3 * p + 2];
      px[3] = static_cast<float>(j->distances[p]);
      px[4] = static_cast<float>(j->steps[p]);
      px[5] = static_cast<float>(j->tests[p]);
    }
    if (exr_path) arcus::image::write_exr(exr_path, img);
    if (png_path) arcus::image::write_png(png_path, img, j->exposure);
  });
}

}  // extern "C"
