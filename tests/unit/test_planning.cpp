// Planning an advance job: which features it compiles (only what the job calls for),
// its layout, and the fixed-step arithmetic that makes the last step end at `length`.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdlib>

#include "core/device.h"
#include "core/error.h"
#include "curved/advance.h"
#include "curved/fields.h"

namespace {

using arcus::curved::fixed_steps;
using arcus::curved::FixedSteps;
using arcus::curved::plan_advance;

arcus::DeviceEntry cpu() {
  arcus::DeviceEntry d{};
  d.info.lanes = 8;
  d.info.fp64 = 1;
  return d;
}

arcus_advance_params params(int32_t method) {
  arcus_advance_params p;
  arcus::curved::default_advance_params(&p);
  p.method = method;
  p.step = 0.1;
  return p;
}

TEST(FixedSteps, LastStepEndsExactlyAtTheLength) {
  // 10 / 0.1 is not exactly 100 in binary: the count must still make n·h >= L.
  for (double L : {10.0, 1.0, 1000.0, 0.35, 196.71196784464513}) {
    for (double h : {0.1, 0.01, 0.007210077602228678, 0.3}) {
      const FixedSteps d = fixed_steps<double>(L, h, 1u << 30);
      ASSERT_GE(d.steps, 1);
      EXPECT_FALSE(d.capped);
      EXPECT_GE(d.steps * h, L) << L << " / " << h;
      EXPECT_LT((d.steps - 1) * h, L) << L << " / " << h;
      EXPECT_GT(d.last_step, 0.0);
      EXPECT_LE(d.last_step, h * (1 + 1e-12));  // L − (n−1)·h, rounded, may exceed h by an ulp
      EXPECT_EQ((d.steps - 1) * h + d.last_step, L) << "the steps must sum to L exactly";
      // In float the count follows float arithmetic (the kernel's).
      const FixedSteps f = fixed_steps<float>(L, h, 1u << 30);
      EXPECT_GE(static_cast<float>(f.steps) * static_cast<float>(h), static_cast<float>(L));
      EXPECT_LT(static_cast<float>(f.steps - 1) * static_cast<float>(h), static_cast<float>(L));
    }
  }
  const FixedSteps one = fixed_steps<double>(1.0, 5.0, 10);  // a step longer than the path
  EXPECT_EQ(one.steps, 1);
  EXPECT_EQ(one.last_step, 1.0);
}

TEST(FixedSteps, MaxStepsCapsTheCountAndTheLastStepStaysFull) {
  const FixedSteps d = fixed_steps<double>(1e4, 1e-4, 10);  // 10^8 steps wanted
  EXPECT_TRUE(d.capped);
  EXPECT_EQ(d.steps, 10);
  EXPECT_EQ(d.last_step, 1e-4);
  // More steps than an int holds: capped at 2^31 - 1, computed without overflow.
  const FixedSteps huge = fixed_steps<double>(1.0, 1e-12, ~0ull);
  EXPECT_TRUE(huge.capped);
  EXPECT_EQ(huge.steps, 2147483647);
}

TEST(Planning, AJobCompilesOnlyTheFeaturesItCallsFor) {
  const std::vector<double> none;
  const arcus::DeviceEntry device = cpu();
  auto plan = [&](const arcus::curved::FieldBuild& f, const arcus_advance_params& p, bool wavelengths = false) {
    return plan_advance(p, f.desc, f.data, device.info, device, wavelengths);
  };
  const double g[3] = {0, 0.1, 0}, c[3] = {0, 0, 0};
  arcus_atmosphere_desc a;
  arcus_atmosphere_desc_init(&a);
  const auto lin = arcus::curved::linear(1.0, g);
  const auto atm = arcus::curved::atmosphere(a);
  // A constant field: the straight segment, no integrator, no field code, one group.
  const auto straight = plan(arcus::curved::constant(1.33), params(ARCUS_METHOD_DP45));
  EXPECT_EQ(straight.features, ARCUS_FEATURE_CURVED_STRAIGHT);
  EXPECT_EQ(straight.layout.groups, 1u);
  EXPECT_EQ(plan(lin, params(ARCUS_METHOD_RK4)).features, ARCUS_FEATURE_CURVED_RK4 | ARCUS_FEATURE_CURVED_FIELD_LINEAR);
  EXPECT_EQ(plan(lin, params(ARCUS_METHOD_RK4)).layout.groups, 4u);
  EXPECT_EQ(plan(lin, params(ARCUS_METHOD_DP45)).layout.groups, 2u);
  // Each field kind has its own bit, as it has its own program.
  EXPECT_EQ(plan(arcus::curved::luneburg(c, 1.0), params(ARCUS_METHOD_EULER)).features,
            ARCUS_FEATURE_CURVED_EULER | ARCUS_FEATURE_CURVED_FIELD_LUNEBURG);
  EXPECT_EQ(plan(arcus::curved::fisheye(c, 1.0, 1.0), params(ARCUS_METHOD_RK2)).features,
            ARCUS_FEATURE_CURVED_RK2 | ARCUS_FEATURE_CURVED_FIELD_FISHEYE);
  EXPECT_EQ(plan(arcus::curved::linear_n2(1.0, g), params(ARCUS_METHOD_RK2)).features,
            ARCUS_FEATURE_CURVED_RK2 | ARCUS_FEATURE_CURVED_FIELD_LINEAR_N2);
  // Wavelengths compile dispersion only for a dispersive field.
  EXPECT_EQ(plan(atm, params(ARCUS_METHOD_DP45), true).features,
            ARCUS_FEATURE_CURVED_DP45 | ARCUS_FEATURE_CURVED_FIELD_ATMOSPHERE | ARCUS_FEATURE_CURVED_DISPERSION);
  EXPECT_EQ(plan(lin, params(ARCUS_METHOD_DP45), true).features, ARCUS_FEATURE_CURVED_DP45 | ARCUS_FEATURE_CURVED_FIELD_LINEAR);
  EXPECT_EQ(plan(atm, params(ARCUS_METHOD_DP45), false).features, ARCUS_FEATURE_CURVED_DP45 | ARCUS_FEATURE_CURVED_FIELD_ATMOSPHERE);
  arcus_advance_params p = params(ARCUS_METHOD_EULER);
  p.use_box = 1;
  p.box_max[0] = p.box_max[1] = p.box_max[2] = 1;
  p.record_path = 1;
  p.precision = ARCUS_PRECISION_FLOAT;
  EXPECT_EQ(plan(lin, p).features, ARCUS_FEATURE_FLOAT | ARCUS_FEATURE_CURVED_EULER | ARCUS_FEATURE_CURVED_FIELD_LINEAR |
                                       ARCUS_FEATURE_CURVED_BOX | ARCUS_FEATURE_CURVED_RECORD_PATH);
}

TEST(Planning, EnumerationsOutOfRangeAreRejectedAsIntegers) {
  const arcus::DeviceEntry device = cpu();
  const double g[3] = {0, 0.1, 0};
  const auto lin = arcus::curved::linear(1.0, g);
  arcus_advance_params p = params(ARCUS_METHOD_RK4);
  for (int32_t bad : {-1, 4, 1 << 30}) {
    p.method = bad;
    EXPECT_THROW(plan_advance(p, lin.desc, lin.data, device.info, device, false), arcus::Error) << bad;
  }
  p = params(ARCUS_METHOD_RK4);
  p.precision = 7;
  EXPECT_THROW(plan_advance(p, lin.desc, lin.data, device.info, device, false), arcus::Error);
}

}  // namespace
