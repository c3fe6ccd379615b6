// API basics: version, status names, devices, ARCUS_DEVICE selection, reference counting.
// The calls on jobs are in test_curved_jobs.cpp.
#include "scoped_env.h"
#include "test_util.h"

#include <cstring>

using namespace arcus_test;

namespace {

TEST(Version, MacrosMatchTheLoadedLibrary) {
  int major = -1, minor = -1, patch = -1;
  ASSERT_EQ(arcus_get_version(&major, &minor, &patch), ARCUS_SUCCESS);
  EXPECT_EQ(major, ARCUS_VERSION_MAJOR);
  EXPECT_EQ(minor, ARCUS_VERSION_MINOR);
  EXPECT_EQ(patch, ARCUS_VERSION_PATCH);
  EXPECT_EQ(ARCUS_VERSION, major * 10000 + minor * 100 + patch);
}

TEST(StatusString, EveryStatusHasItsName) {
  const std::vector<std::pair<arcus_status, const char*>> names{
      {ARCUS_SUCCESS, "ARCUS_SUCCESS"},
      {ARCUS_ERROR_INVALID_ARGUMENT, "ARCUS_ERROR_INVALID_ARGUMENT"},
      {ARCUS_ERROR_OUT_OF_MEMORY, "ARCUS_ERROR_OUT_OF_MEMORY"},
      {ARCUS_ERROR_DEVICE_NOT_FOUND, "ARCUS_ERROR_DEVICE_NOT_FOUND"},
      {ARCUS_ERROR_UNSUPPORTED, "ARCUS_ERROR_UNSUPPORTED"},
      {ARCUS_ERROR_KERNEL_BUILD, "ARCUS_ERROR_KERNEL_BUILD"},
      {ARCUS_ERROR_OPENCL, "ARCUS_ERROR_OPENCL"},
      {ARCUS_ERROR_IO, "ARCUS_ERROR_IO"},
      {ARCUS_ERROR_INVALID_RAYS, "ARCUS_ERROR_INVALID_RAYS"},
      {ARCUS_ERROR_PATH_OVERFLOW, "ARCUS_ERROR_PATH_OVERFLOW"}};
  for (const auto& n : names) EXPECT_STREQ(arcus_status_string(n.first), n.second);
  // Never NULL, even for a value outside the enumeration.
  EXPECT_NE(arcus_status_string(static_cast<arcus_status>(12345)), nullptr);
}

TEST(Devices, EnumerationDescribesEveryDevice) {
  uint32_t count = 0;
  ASSERT_EQ(arcus_device_count(&count), ARCUS_SUCCESS);
  ASSERT_GE(count, 1u) << "these tests need an OpenCL device (PoCL)";
  for (uint32_t i = 0; i < count; ++i) {
    arcus_device_info info;
    std::memset(&info, 0xff, sizeof info);
    ASSERT_EQ(arcus_device_get_info(i, &info), ARCUS_SUCCESS);
    EXPECT_EQ(info.index, i);
    EXPECT_GT(std::strlen(info.name), 0u);
    EXPECT_LT(std::strlen(info.name), sizeof info.name);
    EXPECT_GT(std::strlen(info.platform), 0u);
    EXPECT_LT(std::strlen(info.platform), sizeof info.platform);
    EXPECT_TRUE(contains_ci(info.version, "OpenCL")) << info.version;
    EXPECT_TRUE(info.is_gpu == 0 || info.is_gpu == 1);
    EXPECT_TRUE(info.fp64 == 0 || info.fp64 == 1);
    EXPECT_GE(info.compute_units, 1u);
    EXPECT_GT(info.global_memory, 0u);
    EXPECT_GE(info.lanes, 1u);
    std::printf("device %u: %s / %s / %s, gpu %d, fp64 %d, %u CUs, %u lanes\n", i, info.name, info.platform,
                info.version, info.is_gpu, info.fp64, info.compute_units, info.lanes);
  }
  // One past the end is not a device.
  arcus_device_info info;
  EXPECT_NE(arcus_device_get_info(count, &info), ARCUS_SUCCESS);
}

TEST(Devices, ContextReportsItsDevice) {
  arcus_context_t* c = nullptr;
  ASSERT_EQ(arcus_context_create(0, &c), ARCUS_SUCCESS) << arcus_last_error();
  ContextPtr guard(c);
  arcus_device_info a, b;
  ASSERT_EQ(arcus_context_get_device(c, &a), ARCUS_SUCCESS);
  ASSERT_EQ(arcus_device_get_info(0, &b), ARCUS_SUCCESS);
  EXPECT_EQ(a.index, 0u);
  EXPECT_STREQ(a.name, b.name);
  EXPECT_STREQ(a.platform, b.platform);
  // A fresh context has no error yet.
  EXPECT_STREQ(arcus_context_last_error(c), "");
}

TEST(DeviceSelection, EnvironmentIndexSelectsThatDevice) {
  ScopedEnv env("ARCUS_DEVICE", "0");
  arcus_context_t* c = nullptr;
  ASSERT_EQ(arcus_context_create(ARCUS_DEVICE_DEFAULT, &c), ARCUS_SUCCESS) << arcus_last_error();
  ContextPtr guard(c);
  arcus_device_info info;
  ASSERT_EQ(arcus_context_get_device(c, &info), ARCUS_SUCCESS);
  EXPECT_EQ(info.index, 0u);
}

TEST(DeviceSelection, EnvironmentNamePartSelectsCaseInsensitively) {
  arcus_device_info want;
  ASSERT_EQ(arcus_device_get_info(0, &want), ARCUS_SUCCESS);
  // The whole device name in upper case must match (a part of it, case-insensitively).
  std::string upper = want.name;
  for (char& ch : upper) ch = static_cast<char>(std::toupper(static_cast<unsigned char>(ch)));
  ScopedEnv env("ARCUS_DEVICE", upper.c_str());
  arcus_context_t* c = nullptr;
  ASSERT_EQ(arcus_context_create(ARCUS_DEVICE_DEFAULT, &c), ARCUS_SUCCESS) << arcus_last_error();
  ContextPtr guard(c);
  arcus_device_info got;
  ASSERT_EQ(arcus_context_get_device(c, &got), ARCUS_SUCCESS);
  EXPECT_STREQ(got.name, want.name);
}

TEST(DeviceSelection, UnknownEnvironmentNameIsDeviceNotFound) {
  ScopedEnv env("ARCUS_DEVICE", "no-such-device-xyzzy");
  arcus_context_t* c = nullptr;
  EXPECT_EQ(arcus_context_create(ARCUS_DEVICE_DEFAULT, &c), ARCUS_ERROR_DEVICE_NOT_FOUND);
  EXPECT_EQ(c, nullptr);
  EXPECT_GT(std::strlen(arcus_last_error()), 0u);
  if (c) arcus_context_release(c);
}

TEST(DeviceSelection, OutOfRangeEnvironmentIndexIsDeviceNotFound) {
  ScopedEnv env("ARCUS_DEVICE", "999");
  arcus_context_t* c = nullptr;
  EXPECT_EQ(arcus_context_create(ARCUS_DEVICE_DEFAULT, &c), ARCUS_ERROR_DEVICE_NOT_FOUND);
  EXPECT_EQ(c, nullptr);
  if (c) arcus_context_release(c);
}

TEST(ReferenceCounting, RetainKeepsHandlesAliveAndOwnersKeepTheirContext) {
  arcus_context_t* c = nullptr;
  ASSERT_EQ(arcus_context_create(ARCUS_DEVICE_DEFAULT, &c), ARCUS_SUCCESS) << arcus_last_error();
  // Context: two references, release one, still usable.
  ASSERT_EQ(arcus_context_retain(c), ARCUS_SUCCESS);
  ASSERT_EQ(arcus_context_release(c), ARCUS_SUCCESS);
  arcus_device_info info;
  ASSERT_EQ(arcus_context_get_device(c, &info), ARCUS_SUCCESS);

  const double g[3] = {0, 0.1, 0};
  arcus_field_t* f = nullptr;
  ASSERT_EQ(arcus_field_create_linear(c, 1.0, g, &f), ARCUS_SUCCESS);
  ASSERT_EQ(arcus_field_retain(f), ARCUS_SUCCESS);
  ASSERT_EQ(arcus_field_release(f), ARCUS_SUCCESS);
  arcus_field_kind kind;
  ASSERT_EQ(arcus_field_get_kind(f, &kind), ARCUS_SUCCESS);
  EXPECT_EQ(kind, ARCUS_FIELD_LINEAR);

  arcus_advance_params p = dp45(1.0, 1e-9, 1e-12);
  const double o[3] = {0, 0, 0}, d[3] = {1, 0, 0};
  arcus_job_t* j = nullptr;
  ASSERT_EQ(arcus_curved_advance(c, f, &p, 1, o, d, nullptr, &j), ARCUS_SUCCESS) << arcus_context_last_error(c);
  ASSERT_EQ(arcus_job_retain(j), ARCUS_SUCCESS);
  ASSERT_EQ(arcus_job_release(j), ARCUS_SUCCESS);

  // Drop the context and the field: the job keeps what it needs alive.
  ASSERT_EQ(arcus_context_release(c), ARCUS_SUCCESS);
  ASSERT_EQ(arcus_field_release(f), ARCUS_SUCCESS);
  size_t count = 0;
  ASSERT_EQ(arcus_job_get_count(j, &count), ARCUS_SUCCESS);
  EXPECT_EQ(count, 1u);
  double pos[3];
  int32_t st = -1;
  ASSERT_EQ(arcus_job_get_curved_end_states(j, pos, nullptr, nullptr, &st, nullptr), ARCUS_SUCCESS);
  EXPECT_EQ(st, ARCUS_RAY_DONE);
  // DP45 at rtol 1e-9 over 1 m of a catenary that turns by 0.1 rad: dp45_bound.
  const RayState want = catenary_end(1.0, {0, 0.1, 0}, {0, 0, 0}, {1, 0, 0}, 1.0);
  PathScale scale{norm(want.pos), 1.0};
  scale.turning = angle_between({1, 0, 0}, want.dir);
  EXPECT_LT(distance({pos[0], pos[1], pos[2]}, want.pos), dp45_bound(1e-9, 1e-12, scale));
  ASSERT_EQ(arcus_job_release(j), ARCUS_SUCCESS);
}

TEST(ReferenceCounting, FieldKeepsItsContextAlive) {
  arcus_context_t* c = nullptr;
  ASSERT_EQ(arcus_context_create(ARCUS_DEVICE_DEFAULT, &c), ARCUS_SUCCESS) << arcus_last_error();
  const double center[3] = {0, 0, 0};
  arcus_field_t* f = nullptr;
  ASSERT_EQ(arcus_field_create_luneburg(c, center, 2.0, &f), ARCUS_SUCCESS);
  ASSERT_EQ(arcus_context_release(c), ARCUS_SUCCESS);
  // Host evaluation still works: n = sqrt(2 − (r/R)²) = sqrt(2 − 1/4) at r = 1.
  const double p[3] = {1, 0, 0};
  double n = 0, g[3];
  ASSERT_EQ(arcus_field_evaluate(f, 1, p, &n, g), ARCUS_SUCCESS);
  EXPECT_NEAR(n, std::sqrt(1.75), 1e-15);
  // ∇n = −r/(R² n).
  EXPECT_NEAR(g[0], -1.0 / (4.0 * std::sqrt(1.75)), 1e-15);
  ASSERT_EQ(arcus_field_release(f), ARCUS_SUCCESS);
}

}  // namespace
