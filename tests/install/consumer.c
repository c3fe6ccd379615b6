/* A user's program, built against an installed arcus (find_package or pkg-config):
 * checks the runtime version against the header and advances a few rays. */
#include <arcus/arcus.h>
#include <math.h>
#include <stdio.h>

static int check(arcus_status s, const char* what, arcus_context_t* ctx) {
  if (s == ARCUS_SUCCESS) return 0;
  fprintf(stderr, "%s: %s: %s\n", what, arcus_status_string(s), ctx ? arcus_context_last_error(ctx) : arcus_last_error());
  return 1;
}

int main(void) {
  int major, minor, patch;
  if (check(arcus_get_version(&major, &minor, &patch), "arcus_get_version", NULL)) return 1;
  if (major != ARCUS_VERSION_MAJOR || minor != ARCUS_VERSION_MINOR || patch != ARCUS_VERSION_PATCH) {
    fprintf(stderr, "header %d.%d.%d but library %d.%d.%d\n", ARCUS_VERSION_MAJOR, ARCUS_VERSION_MINOR,
            ARCUS_VERSION_PATCH, major, minor, patch);
    return 1;
  }
  arcus_context_t* ctx = NULL;
  if (check(arcus_context_create(ARCUS_DEVICE_DEFAULT, &ctx), "arcus_context_create", NULL)) return 1;
  const double gradient[3] = {0.0, 0.1, 0.0};
  arcus_field_t* field = NULL;
  if (check(arcus_field_create_linear(ctx, 1.0, gradient, &field), "arcus_field_create_linear", ctx)) return 1;
  arcus_advance_params params;
  arcus_advance_params_init(&params);
  params.length = 10.0;
  double origins[4 * 3] = {0}, directions[4 * 3] = {0};
  for (int i = 0; i < 4; ++i) directions[3 * i] = 1.0, directions[3 * i + 1] = 0.1 * i;
  arcus_job_t* job = NULL;
  if (check(arcus_curved_advance(ctx, field, &params, 4, origins, directions, NULL, &job), "arcus_curved_advance", ctx)) return 1;
  double end[4 * 3];
  int32_t status[4];
  double lengths[4];
  if (check(arcus_job_get_curved_end_states(job, end, NULL, NULL, status, lengths), "arcus_job_get_curved_end_states", ctx)) return 1;
  int bad = 0;
  for (int i = 0; i < 4; ++i) {
    printf("ray %d: status %d, end (%.6f, %.6f, %.6f), length %.6f\n", i, status[i], end[3 * i], end[3 * i + 1],
           end[3 * i + 2], lengths[i]);
    bad |= status[i] != ARCUS_RAY_DONE || fabs(lengths[i] - 10.0) > 1e-12;
  }
  arcus_job_release(job);
  arcus_field_release(field);
  arcus_context_release(ctx);
  if (bad) fprintf(stderr, "unexpected ray status or length\n");
  return bad;
}
