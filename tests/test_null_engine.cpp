// The null engine (include/arcus/arcus_null.h, built with -DARCUS_WITH_NULL_ENGINE=ON):
// proof that an engine added as docs/adding-an-engine.md says plugs into the core alone.
// Its handle kind is checked like every other, its feature is reported by name and
// compiled in, its job is the core's job, and it fills exactly the colour it was given.
#include "arcus/arcus_null.h"  // not in arcus.h: a test-only engine
#include "test_util.h"

using namespace arcus_test;

namespace {

class NullEngine : public ArcusTest {};

TEST_F(NullEngine, FillsEveryPixelWithTheSwatchOnTheDevice) {
  const float colour[3] = {0.25f, 0.5f, 2.0f};
  arcus_swatch_t* swatch = nullptr;
  ASSERT_EQ(arcus_swatch_create(ctx(), colour, &swatch), ARCUS_SUCCESS) << last_error();
  arcus_job_t* job = nullptr;
  ASSERT_EQ(arcus_null_fill(swatch, 7, 5, &job), ARCUS_SUCCESS) << last_error();
  std::vector<float> rgb(7 * 5 * 3, -1.0f);
  ASSERT_EQ(arcus_job_get_null_image(job, rgb.data()), ARCUS_SUCCESS);
  for (size_t i = 0; i < rgb.size(); ++i) EXPECT_EQ(rgb[i], colour[i % 3]) << i;  // copied, so exact
  size_t count = 0;
  ASSERT_EQ(arcus_job_get_count(job, &count), ARCUS_SUCCESS);
  EXPECT_EQ(count, 35u);
  arcus_features features = 0;
  ASSERT_EQ(arcus_job_get_features(job, &features), ARCUS_SUCCESS);
  EXPECT_EQ(features, ARCUS_FEATURE_NULL_FILL);
  char names[64];
  ASSERT_EQ(arcus_features_to_string(features, names, sizeof names), ARCUS_SUCCESS);
  EXPECT_STREQ(names, "NULL_FILL");
  arcus_job_stats stats{};
  ASSERT_EQ(arcus_job_get_stats(job, &stats), ARCUS_SUCCESS);
  EXPECT_EQ(stats.launches, 1u);
  arcus_job_release(job);
  arcus_swatch_release(swatch);
}

TEST_F(NullEngine, ItsHandlesAreCheckedAsEveryEnginesAre) {
  const float colour[3] = {1, 1, 1};
  arcus_swatch_t* swatch = nullptr;
  ASSERT_EQ(arcus_swatch_create(ctx(), colour, &swatch), ARCUS_SUCCESS);
  arcus_job_t* job = nullptr;
  ASSERT_EQ(arcus_null_fill(swatch, 1, 1, &job), ARCUS_SUCCESS);
  // A job where a swatch belongs, and another engine's getter on its job, are named.
  expect_invalid(arcus_null_fill(reinterpret_cast<arcus_swatch_t*>(job), 1, 1, &job), "swatch", "a job as swatch");
  float rgb[3];
  expect_invalid(arcus_job_get_null_image(nullptr, rgb), "job", "a null job");
  arcus_job_release(job);
  ASSERT_EQ(arcus_swatch_release(swatch), ARCUS_SUCCESS);
  EXPECT_EQ(arcus_swatch_retain(swatch), ARCUS_ERROR_INVALID_ARGUMENT);  // released
}

TEST_F(NullEngine, BadInputIsRefusedWithItsName) {
  const float nan_colour[3] = {0, NAN, 0};
  arcus_swatch_t* swatch = nullptr;
  expect_invalid(arcus_swatch_create(ctx(), nan_colour, &swatch), "rgb", "a NaN colour");
  EXPECT_EQ(swatch, nullptr);
  const float colour[3] = {0, 0, 0};
  ASSERT_EQ(arcus_swatch_create(ctx(), colour, &swatch), ARCUS_SUCCESS);
  arcus_job_t* job = nullptr;
  expect_invalid(arcus_null_fill(swatch, 0, 4, &job), "width", "no pixels");
  expect_invalid(arcus_null_fill(swatch, 4, 5000, &job), "height", "too many pixels");
  EXPECT_EQ(job, nullptr);
  arcus_swatch_release(swatch);
}

}  // namespace
