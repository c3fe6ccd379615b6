// The rainbow engine's C API tests' handles: a context, a particle and a job, each
// released when it goes out of scope (test_rainbow_api.cpp, test_rainbow_flat_meshes.cpp).
#ifndef ARCUS_TESTS_RAINBOW_HANDLES_H
#define ARCUS_TESTS_RAINBOW_HANDLES_H

#include <gtest/gtest.h>

#include "arcus/arcus.h"

namespace rainbow_test {

struct Ctx {
  arcus_context_t* ctx = nullptr;
  Ctx() { EXPECT_EQ(arcus_context_create(ARCUS_DEVICE_DEFAULT, &ctx), ARCUS_SUCCESS) << arcus_last_error(); }
  ~Ctx() {
    if (ctx) arcus_context_release(ctx);
  }
};

struct Particle {
  arcus_particle_t* p = nullptr;
  ~Particle() {
    if (p) arcus_particle_release(p);
  }
};

struct Job {
  arcus_job_t* job = nullptr;
  ~Job() {
    if (job) arcus_job_release(job);
  }
};

}  // namespace rainbow_test

#endif
