// The curved engine's spellings before arcus 0.10, kept for one release
// (include/arcus/arcus_curved.h): each forwards to its new name.
#include "arcus/arcus.h"

extern "C" {

arcus_status arcus_advance(arcus_context_t* ctx, arcus_field_t* field, const arcus_advance_params* params,
                           size_t count, const double* origins, const double* directions, const double* wavelengths,
                           arcus_job_t** job) {
  return arcus_curved_advance(ctx, field, params, count, origins, directions, wavelengths, job);
}

arcus_status arcus_scene_advance(arcus_scene_t* scene, arcus_progress_callback progress, void* user,
                                 arcus_job_t** job) {
  return arcus_curved_advance_scene(scene, progress, user, job);
}

arcus_status arcus_job_get_end_states(arcus_job_t* job, double* positions, double* directions, uint64_t* steps,
                                      int32_t* status, double* lengths) {
  return arcus_job_get_curved_end_states(job, positions, directions, steps, status, lengths);
}

arcus_status arcus_job_get_failures(arcus_job_t* job, int32_t* failures) {
  return arcus_job_get_curved_failures(job, failures);
}

arcus_status arcus_job_get_path_size(arcus_job_t* job, size_t* total_points) {
  return arcus_job_get_curved_path_size(job, total_points);
}

arcus_status arcus_job_get_paths(arcus_job_t* job, uint64_t* offsets, double* points, uint64_t* needed) {
  return arcus_job_get_curved_paths(job, offsets, points, needed);
}

}  // extern "C"
