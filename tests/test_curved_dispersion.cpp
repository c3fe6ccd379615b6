// Per-ray wavelengths: a dispersive field (the atmosphere, through Ciddor's formula)
// evaluates n at each ray's own wavelength in one job — what a sunset's dispersion and
// green flash need.  Other fields ignore the wavelengths; a bad one flags only its ray.
#include "test_util.h"

using namespace arcus_test;

namespace {

class Dispersion : public ArcusTest {
 protected:
  // n − 1 of standard air at a vacuum wavelength (nm): Ciddor (1996), eq. 1, written
  // out here again so the test does not take the library's word for it.
  static double ciddor(double nm) {
    const double s2 = (1000.0 / nm) * (1000.0 / nm);
    return 1e-8 * (5792105.0 / (238.0185 - s2) + 167917.0 / (57.362 - s2));
  }
};

TEST_F(Dispersion, RefractionAt400And700NmInOneJobScalesAsCiddorsRefractivity) {
  arcus_atmosphere_desc d;
  arcus_atmosphere_desc_init(&d);
  d.spherical = 1;
  auto air = atmosphere(d);
  ASSERT_TRUE(air);
  // Stars seen at 30° and 45° altitude from sea level, in blue and in red light.
  const V3 o{0.0, ARCUS_EARTH_RADIUS, 0.0};
  const std::vector<double> altitudes{30.0, 45.0, 30.0, 45.0};
  const std::vector<double> wavelengths{400.0, 400.0, 700.0, 700.0};
  Rays rays;
  for (double h : altitudes) rays.add(o, {std::cos(rad(h)), std::sin(rad(h)), 0.0});
  arcus_job_t* job = nullptr;
  const arcus_advance_params p = dp45(3.0e6, 1e-11, 1e-14);
  ASSERT_EQ(arcus_curved_advance(ctx(), air.get(), &p, rays.size(), rays.origins.data(), rays.directions.data(),
                                 wavelengths.data(), &job),
                                 ARCUS_SUCCESS)
      << last_error();
  JobPtr guard(job);
  arcus_features features = 0;
  ASSERT_EQ(arcus_job_get_features(job, &features), ARCUS_SUCCESS);
  EXPECT_TRUE(features & ARCUS_FEATURE_CURVED_DISPERSION);
  std::vector<double> dirs(3 * rays.size());
  std::vector<int32_t> status(rays.size());
  ASSERT_EQ(arcus_job_get_curved_end_states(job, nullptr, dirs.data(), nullptr, status.data(), nullptr), ARCUS_SUCCESS);
  std::vector<double> bending(rays.size());
  for (size_t i = 0; i < rays.size(); ++i) {
    EXPECT_EQ(status[i], ARCUS_RAY_DONE);
    bending[i] = angle_between(normalize(rays.direction(i)), {dirs[3 * i], dirs[3 * i + 1], dirs[3 * i + 2]});
  }
  // Refraction R = (n0 − 1)(1 − β) tan z − (n0 − 1)(β − (n0 − 1)/2) tan³ z + ... (Laplace):
  // linear in n0 − 1 but for the (n0 − 1)²/2 term, whose share differs between 400 and
  // 700 nm by (Δ(n0 − 1)/2)·tan²z ≈ 5e-6.  The integration errs by < 1e-7 relative
  // (steps·rtol).  So R400/R700 = K400/K700 to 2e-5; the refractivities differ by 3 %.
  const double ratio = ciddor(400.0) / ciddor(700.0);
  for (size_t i = 0; i < 2; ++i) {
    const double got = bending[i] / bending[i + 2];
    std::printf("altitude %.0f deg: refraction %.4f\" at 400 nm, %.4f\" at 700 nm, ratio %.7f (Ciddor %.7f)\n",
                altitudes[i], deg(bending[i]) * 3600, deg(bending[i + 2]) * 3600, got, ratio);
    EXPECT_NEAR(got / ratio, 1.0, 2e-5) << "altitude " << altitudes[i];
  }
  EXPECT_GT(ratio, 1.025);  // the test is meaningful: blue is bent 3 % more than red
  // Each ray is what a field made for its wavelength gives (same formulas, evaluated on
  // the host for the field and in the kernel for the ray: 1e-12 relative).
  for (double nm : {400.0, 700.0}) {
    d.wavelength = nm;
    auto mono = atmosphere(d);
    const Trace t = trace(ctx(), mono.get(), p, rays);
    ASSERT_EQ(t.status, ARCUS_SUCCESS);
    for (size_t i = 0; i < rays.size(); ++i) {
      if (wavelengths[i] != nm) continue;
      EXPECT_NEAR(angle_between(normalize(rays.direction(i)), t.dir(i)) / bending[i], 1.0, 1e-9) << i;
    }
  }
}

TEST_F(Dispersion, NonDispersiveFieldsIgnoreTheWavelengths) {
  auto lens = luneburg({0, 0, 0}, 1.0);
  ASSERT_TRUE(lens);
  Rays rays;
  for (int i = 0; i < 5; ++i) rays.add({-2, 0.1 * i, 0}, {1, 0, 0});
  const std::vector<double> garbage{std::nan(""), -1.0, 0.0, 5000.0, 550.0};
  const arcus_advance_params p = dp45(4.0, 1e-10, 1e-13);
  const Trace plain = trace(ctx(), lens.get(), p, rays);
  arcus_job_t* job = nullptr;
  ASSERT_EQ(arcus_curved_advance(ctx(), lens.get(), &p, rays.size(), rays.origins.data(), rays.directions.data(),
                                 garbage.data(), &job),
                                 ARCUS_SUCCESS)
      << last_error();
  JobPtr guard(job);
  std::vector<double> pos(3 * rays.size());
  ASSERT_EQ(arcus_job_get_curved_end_states(job, pos.data(), nullptr, nullptr, nullptr, nullptr), ARCUS_SUCCESS);
  EXPECT_EQ(pos, plain.positions) << "the same program runs: the array is not even read";
  arcus_features features = 0;
  arcus_job_get_features(job, &features);
  EXPECT_FALSE(features & ARCUS_FEATURE_CURVED_DISPERSION);
}

TEST_F(Dispersion, BadWavelengthsFlagTheirRaysAndLeaveTheOthersUnharmed) {
  arcus_atmosphere_desc d;
  arcus_atmosphere_desc_init(&d);
  auto air = atmosphere(d);
  ASSERT_TRUE(air);
  const double nan = std::numeric_limits<double>::quiet_NaN(), inf = std::numeric_limits<double>::infinity();
  const std::vector<double> all{450.0, nan, 0.0, -550.0, 299.9, 1690.5, inf, 650.0, 300.0, 1690.0};
  const std::vector<bool> bad{false, true, true, true, true, true, true, false, false, false};
  Rays rays, good_rays;
  std::vector<double> good_wavelengths;
  for (size_t i = 0; i < all.size(); ++i) {
    const V3 o{0, 10.0 + i, 0}, dir{1, -0.01 * i, 0};
    rays.add(o, dir);
    if (!bad[i]) {
      good_rays.add(o, dir);
      good_wavelengths.push_back(all[i]);
    }
  }
  const arcus_advance_params p = dp45(5000.0, 1e-10, 1e-13);
  auto run = [&](const Rays& r, const std::vector<double>& w, std::vector<double>* pos, std::vector<int32_t>* st) {
    arcus_job_t* job = nullptr;
    const arcus_status status =
        arcus_curved_advance(ctx(), air.get(), &p, r.size(), r.origins.data(), r.directions.data(), w.data(), &job);
    JobPtr guard(job);
    pos->resize(3 * r.size());
    st->resize(r.size());
    if (job) arcus_job_get_curved_end_states(job, pos->data(), nullptr, nullptr, st->data(), nullptr);
    return status;
  };
  std::vector<double> pos, good_pos;
  std::vector<int32_t> st, good_st;
  EXPECT_EQ(run(rays, all, &pos, &st), ARCUS_ERROR_INVALID_RAYS);
  const std::string message = last_error();
  EXPECT_TRUE(contains_ci(message.c_str(), "wavelength")) << message;
  ASSERT_EQ(run(good_rays, good_wavelengths, &good_pos, &good_st), ARCUS_SUCCESS);
  for (size_t i = 0, g = 0; i < all.size(); ++i) {
    if (bad[i]) {
      EXPECT_EQ(st[i], ARCUS_RAY_INVALID_INPUT) << "ray " << i << " at " << all[i] << " nm";
      continue;
    }
    EXPECT_EQ(st[i], ARCUS_RAY_DONE) << "ray " << i;
    EXPECT_EQ(std::memcmp(&pos[3 * i], &good_pos[3 * g], 3 * sizeof(double)), 0) << "ray " << i << " was harmed";
    ++g;
  }
}

}  // namespace
