// The single-image estimate through the C API (thesis §3.4): a Lambertian sphere drawn
// here in closed form, its light found to within the pixel grid, its depth inflated back
// to a sphere, the automatic estimate's outputs, and each bad argument refused naming
// itself.  The physics across shapes and translucency is tests/python's
// (test_translucency_lights.py, _shape.py, _auto.py).
#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "test_util.h"

namespace {

using arcus_test::ArcusTest;

constexpr uint32_t kSide = 96;
constexpr double kRadius = 36;  // pixels

struct Photo {
  std::vector<float> rgb;
  std::vector<uint8_t> matte;
};

// The sphere's radiance max(0, n·l) at each pixel centre (image rows top first, the
// camera's y up), l = (sinφ cosθ, sinφ sinθ, cosφ).
Photo lambertian_sphere(double azimuth_deg, double zenith_deg) {
  const double t = azimuth_deg * M_PI / 180, p = zenith_deg * M_PI / 180;
  const double l[3] = {std::sin(p) * std::cos(t), std::sin(p) * std::sin(t), std::cos(p)};
  Photo photo{std::vector<float>(3 * kSide * kSide, 0.0f), std::vector<uint8_t>(kSide * kSide, 0)};
  for (uint32_t row = 0; row < kSide; ++row)
    for (uint32_t col = 0; col < kSide; ++col) {
      const double u = (col + 0.5 - kSide / 2.0) / kRadius, v = -(row + 0.5 - kSide / 2.0) / kRadius;
      if (u * u + v * v >= 1) continue;
      const double n[3] = {u, v, std::sqrt(1 - u * u - v * v)};
      const float shade = float(std::max(0.0, n[0] * l[0] + n[1] * l[1] + n[2] * l[2]));
      const size_t i = size_t(row) * kSide + col;
      photo.matte[i] = 1;
      for (int c = 0; c < 3; ++c) photo.rgb[3 * i + c] = shade;
    }
  return photo;
}

class TranslucencyLights : public ArcusTest {};

// The models are exact for this sphere; the pixel grid (a 36-pixel radius) and the
// zenith's 1° steps leave 1.5° at most (measured: 0.2°).
TEST_F(TranslucencyLights, FindsTheLightOfAClosedFormSphere) {
  const Photo photo = lambertian_sphere(145, 45);
  arcus_light_detection found{};
  ASSERT_EQ(arcus_translucency_detect_lights(ctx(), kSide, kSide, photo.rgb.data(), photo.matte.data(), &found),
            ARCUS_SUCCESS)
      << last_error();
  ASSERT_EQ(found.count, 1u);
  const arcus_detected_light& light = found.lights[0];
  const double t = 145 * M_PI / 180, p = 45 * M_PI / 180;
  const double truth[3] = {std::sin(p) * std::cos(t), std::sin(p) * std::sin(t), std::cos(p)};
  const double cosine = light.direction[0] * truth[0] + light.direction[1] * truth[1] + light.direction[2] * truth[2];
  EXPECT_LT(std::acos(std::min(1.0, cosine)) * 180 / M_PI, 1.5);
  EXPECT_DOUBLE_EQ(light.intensity, 1.0);
  EXPECT_EQ(found.segmented, 0);
  EXPECT_GT(found.contour_pixels, 100u);

  // Without the matte: the background is exact zeros, so the same pixels.
  arcus_light_detection segmented{};
  ASSERT_EQ(arcus_translucency_detect_lights(ctx(), kSide, kSide, photo.rgb.data(), nullptr, &segmented),
            ARCUS_SUCCESS)
      << last_error();
  EXPECT_EQ(segmented.segmented, 1);
}

TEST_F(TranslucencyLights, BadArgumentsAreRefusedNamingThemselves) {
  Photo photo = lambertian_sphere(145, 45);
  arcus_light_detection found{};
  expect_invalid(arcus_translucency_detect_lights(ctx(), kSide, kSide, nullptr, nullptr, &found), "photo", "no photo");
  expect_invalid(arcus_translucency_detect_lights(ctx(), kSide, kSide, photo.rgb.data(), nullptr, nullptr), "result",
                 "no result");
  expect_invalid(arcus_translucency_detect_lights(ctx(), 0, kSide, photo.rgb.data(), nullptr, &found), "width",
                 "no width");
  photo.rgb[3 * (40 * kSide + 40)] = -1;
  expect_invalid(arcus_translucency_detect_lights(ctx(), kSide, kSide, photo.rgb.data(), nullptr, &found), "photo",
                 "a negative pixel");
  const std::vector<float> black(3 * kSide * kSide, 0.0f);
  expect_invalid(arcus_translucency_detect_lights(ctx(), kSide, kSide, black.data(), nullptr, &found), "no object",
                 "a black photo");
  const Photo whole = lambertian_sphere(145, 45);
  std::vector<uint8_t> everything(kSide * kSide, 1);
  expect_invalid(arcus_translucency_detect_lights(ctx(), kSide, kSide, whole.rgb.data(), everything.data(), &found),
                 "border", "a matte over the whole photo");
}

// The convex stand-in inflates a disc to the sphere of its radius: the depth at the
// centre is the radius (the Dirichlet boundary half a pixel out: within 3%), and the
// normal there faces the camera.
TEST_F(TranslucencyLights, InflatesTheSphereBack) {
  const Photo photo = lambertian_sphere(145, 45);
  arcus_photo_shape_params params{};
  ASSERT_EQ(arcus_translucency_photo_shape_params_init(&params), ARCUS_SUCCESS);
  std::vector<double> depth(kSide * kSide), normals(3 * kSide * kSide);
  std::vector<uint8_t> mask(kSide * kSide);
  ASSERT_EQ(arcus_translucency_estimate_shape(ctx(), kSide, kSide, photo.rgb.data(), photo.matte.data(), &params,
                                              depth.data(), normals.data(), mask.data()),
            ARCUS_SUCCESS)
      << last_error();
  const size_t centre = size_t(kSide / 2) * kSide + kSide / 2;
  EXPECT_NEAR(depth[centre], kRadius, 0.03 * kRadius);
  EXPECT_GT(normals[3 * centre + 2], 0.999);
  EXPECT_EQ(mask, photo.matte);

  expect_invalid(arcus_translucency_estimate_shape(ctx(), kSide, kSide, photo.rgb.data(), nullptr, &params, nullptr,
                                                   normals.data(), nullptr),
                 "depth", "no depth");
  params.relief = 0;
  expect_invalid(arcus_translucency_estimate_shape(ctx(), kSide, kSide, photo.rgb.data(), nullptr, &params,
                                                   depth.data(), normals.data(), nullptr),
                 "relief", "a flat relief");
}

TEST_F(TranslucencyLights, AutomaticEstimateReportsWhatThePhotoGave) {
  const Photo photo = lambertian_sphere(145, 45);
  arcus_translucency_auto_params params{};
  ASSERT_EQ(arcus_translucency_auto_params_init(&params), ARCUS_SUCCESS);
  arcus_job_t* job = nullptr;
  ASSERT_EQ(arcus_translucency_estimate_auto(ctx(), kSide, kSide, photo.rgb.data(), photo.matte.data(), &params, &job),
            ARCUS_SUCCESS)
      << last_error();
  arcus_light_detection lights{};
  size_t vertices = 0, triangles = 0;
  ASSERT_EQ(arcus_job_get_translucency_auto(job, &lights, nullptr, nullptr, nullptr, &vertices, &triangles, nullptr,
                                            nullptr),
            ARCUS_SUCCESS);
  EXPECT_EQ(lights.count, 1u);
  EXPECT_GT(vertices, 0u);
  std::vector<double> positions(3 * vertices);
  std::vector<uint32_t> faces(3 * triangles);
  ASSERT_EQ(arcus_job_get_translucency_auto(job, nullptr, nullptr, nullptr, nullptr, nullptr, nullptr,
                                            positions.data(), faces.data()),
            ARCUS_SUCCESS);
  for (uint32_t f : faces) ASSERT_LT(f, vertices);
  arcus_translucency_estimate_result result{};
  EXPECT_EQ(arcus_job_get_translucency_estimate(job, &result), ARCUS_SUCCESS);
  EXPECT_GT(result.equation_pixels, 0u);
  arcus_job_release(job);

  params.irradiance[1] = -1;
  expect_invalid(arcus_translucency_estimate_auto(ctx(), kSide, kSide, photo.rgb.data(), nullptr, &params, &job),
                 "irradiance", "a negative irradiance");
  expect_invalid(arcus_translucency_estimate_auto(ctx(), kSide, kSide, photo.rgb.data(), nullptr, nullptr, &job),
                 "params", "no params");
}

}  // namespace
