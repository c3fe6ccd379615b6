// The render engine's spellings before arcus 0.10, kept for one release
// (include/arcus/arcus_render.h): each forwards to its new name.
#include "arcus/arcus.h"

extern "C" {

arcus_status arcus_job_get_image_size(arcus_job_t* job, uint32_t* width, uint32_t* height) {
  return arcus_job_get_render_image_size(job, width, height);
}

arcus_status arcus_job_get_image(arcus_job_t* job, float* rgb) { return arcus_job_get_render_image(job, rgb); }

arcus_status arcus_job_get_hits(arcus_job_t* job, double* points, int32_t* objects, int32_t* primitives,
                                double* distances, uint32_t* steps, uint32_t* tests) {
  return arcus_job_get_render_hits(job, points, objects, primitives, distances, steps, tests);
}

arcus_status arcus_job_write_image(arcus_job_t* job, const char* exr_path, const char* png_path) {
  return arcus_job_write_render_image(job, exr_path, png_path);
}

}  // extern "C"
