/* c_api_dump: the C99 reference run that tests/python compares the Python bindings with.
 * Traces 8 rays through n = 1 + 0.1·y with DP45 (rtol 1e-9, atol 1e-12) over 100 m:
 * origins (0, 0.1·i, 0), directions (1, 0.05·i − 0.2, 0), i = 0..7.  Prints one line per
 * ray: "x y z dx dy dz steps status" (%.17g for reals).  Exit status 0 on success. */
#include <arcus/arcus.h>

#include <stdio.h>

#define RAYS 8

int main(void) {
  arcus_context_t* ctx = NULL;
  arcus_field_t* field = NULL;
  arcus_job_t* job = NULL;
  arcus_advance_params params;
  const double gradient[3] = {0.0, 0.1, 0.0};
  double origins[3 * RAYS], directions[3 * RAYS];
  double positions[3 * RAYS], ends[3 * RAYS];
  uint64_t steps[RAYS];
  int32_t status[RAYS];
  arcus_status st;
  int i, rc = 1;

  for (i = 0; i < RAYS; ++i) {
    origins[3 * i] = 0.0;
    origins[3 * i + 1] = 0.1 * i;
    origins[3 * i + 2] = 0.0;
    directions[3 * i] = 1.0;
    directions[3 * i + 1] = 0.05 * i - 0.2;
    directions[3 * i + 2] = 0.0;
  }
  st = arcus_context_create(ARCUS_DEVICE_DEFAULT, &ctx);
  if (st != ARCUS_SUCCESS) {
    fprintf(stderr, "c_api_dump: arcus_context_create: %s: %s\n", arcus_status_string(st), arcus_last_error());
    return 1;
  }
  st = arcus_field_create_linear(ctx, 1.0, gradient, &field);
  if (st != ARCUS_SUCCESS) goto fail;
  st = arcus_advance_params_init(&params);
  if (st != ARCUS_SUCCESS) goto fail;
  params.method = ARCUS_METHOD_DP45;
  params.rtol = 1e-9;
  params.atol = 1e-12;
  params.length = 100.0;
  st = arcus_advance(ctx, field, &params, RAYS, origins, directions, NULL, &job);
  if (st != ARCUS_SUCCESS) goto fail;
  st = arcus_job_get_end_states(job, positions, ends, steps, status, NULL);
  if (st != ARCUS_SUCCESS) goto fail;
  for (i = 0; i < RAYS; ++i)
    printf("%.17g %.17g %.17g %.17g %.17g %.17g %llu %d\n", positions[3 * i], positions[3 * i + 1],
           positions[3 * i + 2], ends[3 * i], ends[3 * i + 1], ends[3 * i + 2], (unsigned long long)steps[i],
           (int)status[i]);
  rc = 0;
  goto done;
fail:
  fprintf(stderr, "c_api_dump: %s: %s\n", arcus_status_string(st), arcus_context_last_error(ctx));
done:
  if (job) arcus_job_release(job);
  if (field) arcus_field_release(field);
  arcus_context_release(ctx);
  return rc;
}
