/* c_api_dump: the C99 reference runs that tests/python compares the Python bindings with
 * (tests/python/test_determinism.py, tests/python/test_c_and_python.py): the same library
 * reached through its C API, so Python must print the same numbers.
 *
 *   c_api_dump [curved]       Traces 8 rays through n = 1 + 0.1·y with DP45 (rtol 1e-9,
 *                             atol 1e-12) over 100 m: origins (0, 0.1·i, 0), directions
 *                             (1, 0.05·i − 0.2, 0), i = 0..7.  One line per ray:
 *                             "x y z dx dy dz steps status".
 *   c_api_dump rainbow        Water's refractive index at 283.15 K at 450, 550 and 650 nm
 *                             ("n WAVELENGTH N"), then Lorenz–Mie for a sphere of radius
 *                             10 µm at 550 nm with that n (n_im = 0) at θ = 10, 90, 137.5
 *                             and 170°: "mie THETA S1re S1im S2re S2im PARALLEL
 *                             PERPENDICULAR", then "efficiencies Q_EXT Q_SCA Q_BACK G".
 *   c_api_dump ocean          The "baltic" bio-optical preset's water on the grid
 *                             400, 450, ..., 700 nm: "events K V0 V1 ..." for the 10
 *                             events, then "absorption C ..." and "scattering C ..." for
 *                             the 4 constituents (one value per wavelength).
 *   c_api_dump render SCENE   One frame of the render scene file SCENE with the scene's own
 *                             camera, integrator and techniques: "size WIDTH HEIGHT", then
 *                             one line per pixel, top row first: "R G B" (%.9g: each
 *                             float exactly).
 *   c_api_dump translucency   Marble (arcus_translucency_dipole_from_material): "terms
 *                             NAME R G B" for albedo, diffuse_length and
 *                             total_reflectance; R_d at r = 0, 0.5, 1, 2 and 5 mm
 *                             ("rd R R G B"); then the dipole of apple's R_total and ℓ_d
 *                             at η = 1.3 ("inverse sigma_a R G B", "inverse
 *                             sigma_s_prime R G B").
 *
 * Reals print with %.17g (a double exactly).  Exit status 0 on success, 1 on a library
 * error (the message on stderr), 2 for unknown arguments. */
#include <arcus/arcus.h>

/* Which engines' dumps to build: tests/CMakeLists.txt says which the library has. */
#ifndef ARCUS_DUMP_RAINBOW
#define ARCUS_DUMP_RAINBOW 1
#endif
#ifndef ARCUS_DUMP_OCEAN
#define ARCUS_DUMP_OCEAN 1
#endif
#ifndef ARCUS_DUMP_RENDER
#define ARCUS_DUMP_RENDER 1
#endif
#ifndef ARCUS_DUMP_TRANSLUCENCY
#define ARCUS_DUMP_TRANSLUCENCY 1
#endif

#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#define RAYS 8

static int dump_curved(arcus_context_t* ctx) {
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
  st = arcus_field_create_linear(ctx, 1.0, gradient, &field);
  if (st != ARCUS_SUCCESS) goto fail;
  st = arcus_advance_params_init(&params);
  if (st != ARCUS_SUCCESS) goto fail;
  params.method = ARCUS_METHOD_DP45;
  params.rtol = 1e-9;
  params.atol = 1e-12;
  params.length = 100.0;
  st = arcus_curved_advance(ctx, field, &params, RAYS, origins, directions, NULL, &job);
  if (st != ARCUS_SUCCESS) goto fail;
  st = arcus_job_get_curved_end_states(job, positions, ends, steps, status, NULL);
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
  return rc;
}

#if ARCUS_DUMP_RAINBOW
/* Host code without a context: errors are the thread's (arcus_last_error). */
static int dump_rainbow(void) {
  static const double wavelengths[3] = {450.0, 550.0, 650.0};
  static const double theta[4] = {10.0, 90.0, 137.5, 170.0};
  const double temperature_k = 283.15, radius = 10e-6, wavelength = 550.0;
  double n = 0.0, n_550 = 0.0;
  double s1[2 * 4], s2[2 * 4], parallel[4], perpendicular[4];
  arcus_mie_efficiencies eff;
  arcus_status st;
  int i;

  for (i = 0; i < 3; ++i) {
    st = arcus_rainbow_refractive_index(ARCUS_MATERIAL_WATER, wavelengths[i], temperature_k, &n);
    if (st != ARCUS_SUCCESS) goto fail;
    printf("n %.17g %.17g\n", wavelengths[i], n);
    if (wavelengths[i] == wavelength) n_550 = n;
  }
  st = arcus_rainbow_mie(radius, wavelength, n_550, 0.0, 4, theta, s1, s2, parallel, perpendicular, &eff);
  if (st != ARCUS_SUCCESS) goto fail;
  for (i = 0; i < 4; ++i)
    printf("mie %.17g %.17g %.17g %.17g %.17g %.17g %.17g\n", theta[i], s1[2 * i], s1[2 * i + 1], s2[2 * i],
           s2[2 * i + 1], parallel[i], perpendicular[i]);
  printf("efficiencies %.17g %.17g %.17g %.17g\n", eff.q_ext, eff.q_sca, eff.q_back, eff.g);
  return 0;
fail:
  fprintf(stderr, "c_api_dump: %s: %s\n", arcus_status_string(st), arcus_last_error());
  return 1;
}
#endif

#if ARCUS_DUMP_OCEAN
static void print_rows(const char* name, const double* values, int rows, int count) {
  int r, k;
  for (r = 0; r < rows; ++r) {
    printf("%s %d", name, r);
    for (k = 0; k < count; ++k) printf(" %.17g", values[r * count + k]);
    printf("\n");
  }
}

#define OCEAN_COUNT 7

static int dump_ocean(arcus_context_t* ctx) {
  arcus_bio_optical bio;
  arcus_water_t* water = NULL;
  arcus_wavelength_grid grid;
  double events[ARCUS_OCEAN_EVENT_COUNT * OCEAN_COUNT], absorption[4 * OCEAN_COUNT], scattering[4 * OCEAN_COUNT];
  arcus_status st;
  int rc = 1;

  grid.first_nm = 400.0;
  grid.step_nm = 50.0;
  grid.count = OCEAN_COUNT;
  st = arcus_bio_optical_preset("baltic", &bio);
  if (st != ARCUS_SUCCESS) goto fail;
  st = arcus_water_create(ctx, &bio, &water);
  if (st != ARCUS_SUCCESS) goto fail;
  st = arcus_water_get_coefficients(water, &grid, events, absorption, scattering);
  if (st != ARCUS_SUCCESS) goto fail;
  print_rows("events", events, ARCUS_OCEAN_EVENT_COUNT, OCEAN_COUNT);
  print_rows("absorption", absorption, 4, OCEAN_COUNT);
  print_rows("scattering", scattering, 4, OCEAN_COUNT);
  rc = 0;
  goto done;
fail:
  fprintf(stderr, "c_api_dump: %s: %s\n", arcus_status_string(st), arcus_context_last_error(ctx));
done:
  if (water) arcus_water_release(water);
  return rc;
}
#endif

#if ARCUS_DUMP_RENDER
static int dump_render(arcus_context_t* ctx, const char* path) {
  arcus_scene_t* scene = NULL;
  arcus_renderer_t* renderer = NULL;
  arcus_job_t* job = NULL;
  float* rgb = NULL;
  uint32_t width = 0, height = 0;
  size_t i, pixels;
  arcus_status st;
  int rc = 1;

  st = arcus_scene_load(ctx, path, &scene);
  if (st != ARCUS_SUCCESS) goto fail;
  st = arcus_renderer_create(scene, &renderer);
  if (st != ARCUS_SUCCESS) goto fail;
  st = arcus_render_frame(renderer, NULL, NULL, &job);
  if (st != ARCUS_SUCCESS) goto fail;
  st = arcus_job_get_render_image_size(job, &width, &height);
  if (st != ARCUS_SUCCESS) goto fail;
  pixels = (size_t)width * height;
  rgb = (float*)malloc(3 * pixels * sizeof *rgb + 1);
  if (!rgb) {
    fprintf(stderr, "c_api_dump: out of memory\n");
    goto done;
  }
  st = arcus_job_get_render_image(job, rgb);
  if (st != ARCUS_SUCCESS) goto fail;
  printf("size %lu %lu\n", (unsigned long)width, (unsigned long)height);
  for (i = 0; i < pixels; ++i)
    printf("%.9g %.9g %.9g\n", (double)rgb[3 * i], (double)rgb[3 * i + 1], (double)rgb[3 * i + 2]);
  rc = 0;
  goto done;
fail:
  fprintf(stderr, "c_api_dump: %s: %s\n", arcus_status_string(st), arcus_context_last_error(ctx));
done:
  free(rgb);
  if (job) arcus_job_release(job);
  if (renderer) arcus_renderer_release(renderer);
  if (scene) arcus_scene_release(scene);
  return rc;
}
#endif

#if ARCUS_DUMP_TRANSLUCENCY
static void print_rgb(const char* what, const char* name, const double* v) {
  printf("%s %s %.17g %.17g %.17g\n", what, name, v[0], v[1], v[2]);
}

static int dump_translucency(void) {
  arcus_dipole marble, apple, inverse;
  arcus_dipole_terms t, apple_terms;
  const double r[5] = {0, 0.5, 1, 2, 5};
  double rd[15];
  int i;
  if (arcus_translucency_dipole_from_material("marble", &marble) != ARCUS_SUCCESS ||
      arcus_translucency_dipole_get_terms(&marble, &t) != ARCUS_SUCCESS ||
      arcus_translucency_dipole_profile(&marble, 1.0, ARCUS_PROFILE_SCALE_ENERGY, 5, r, rd) != ARCUS_SUCCESS ||
      arcus_translucency_dipole_from_material("apple", &apple) != ARCUS_SUCCESS ||
      arcus_translucency_dipole_get_terms(&apple, &apple_terms) != ARCUS_SUCCESS ||
      arcus_translucency_dipole_from_reflectance(apple_terms.total_reflectance, apple_terms.diffuse_length, 1.3,
                                                 &inverse) != ARCUS_SUCCESS) {
    fprintf(stderr, "c_api_dump: %s\n", arcus_last_error());
    return 1;
  }
  print_rgb("terms", "albedo", t.albedo);
  print_rgb("terms", "diffuse_length", t.diffuse_length);
  print_rgb("terms", "total_reflectance", t.total_reflectance);
  for (i = 0; i < 5; ++i) printf("rd %.17g %.17g %.17g %.17g\n", r[i], rd[3 * i], rd[3 * i + 1], rd[3 * i + 2]);
  print_rgb("inverse", "sigma_a", inverse.sigma_a);
  print_rgb("inverse", "sigma_s_prime", inverse.sigma_s_prime);
  return 0;
}
#endif

#if !ARCUS_DUMP_RAINBOW || !ARCUS_DUMP_OCEAN || !ARCUS_DUMP_RENDER || !ARCUS_DUMP_TRANSLUCENCY
/* An engine this build left out (ARCUS_WITH_<ENGINE>=OFF): its dump is absent. */
static int absent(const char* engine) {
  fprintf(stderr, "c_api_dump: this build has no %s engine\n", engine);
  return 2;
}
#endif
#if !ARCUS_DUMP_RAINBOW
#define dump_rainbow() absent("rainbow")
#endif
#if !ARCUS_DUMP_OCEAN
#define dump_ocean(ctx) absent("ocean")
#endif
#if !ARCUS_DUMP_RENDER
#define dump_render(ctx, path) absent("render")
#endif
#if !ARCUS_DUMP_TRANSLUCENCY
#define dump_translucency() absent("translucency")
#endif

static int usage(void) {
  fprintf(stderr, "usage: c_api_dump [curved | rainbow | ocean | render SCENE | translucency]\n");
  return 2;
}

int main(int argc, char** argv) {
  const char* engine = argc > 1 ? argv[1] : "curved";
  arcus_context_t* ctx = NULL;
  arcus_status st;
  int rc;

  if (strcmp(engine, "render") == 0 ? argc != 3 : argc > 2) return usage();
  if (strcmp(engine, "rainbow") == 0) return dump_rainbow();
  if (strcmp(engine, "translucency") == 0) return dump_translucency();
  if (strcmp(engine, "curved") != 0 && strcmp(engine, "ocean") != 0 && strcmp(engine, "render") != 0)
    return usage();
  st = arcus_context_create(ARCUS_DEVICE_DEFAULT, &ctx);
  if (st != ARCUS_SUCCESS) {
    fprintf(stderr, "c_api_dump: arcus_context_create: %s: %s\n", arcus_status_string(st), arcus_last_error());
    return 1;
  }
  if (strcmp(engine, "curved") == 0)
    rc = dump_curved(ctx);
  else if (strcmp(engine, "ocean") == 0)
    rc = dump_ocean(ctx);
  else
    rc = dump_render(ctx, argv[2]);
  arcus_context_release(ctx);
  return rc;
}
