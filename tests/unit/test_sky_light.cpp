// A daylight sky's light on surfaces (src/render/sky_light.h) and textures filtered over
// a pixel's footprint (src/image/mipmap.h), against closed forms and an independent
// quadrature: a uniform sky of radiance L gives E(n) = πL(1 + n_y)/2 from above and
// π(1 − n_y)/2 times the ground's radiance from below (the view factors of a tilted
// plane); the clear sky's E(up) is sky::ground_irradiance's diffuse light, which
// integrates ClearSky by Gauss–Legendre without the panorama; a pyramid's every level
// keeps the image's mean; a footprint long along stripes keeps them, one across blurs
// them to their mean.
#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "image/mipmap.h"
#include "render/sky_light.h"
#include "sky/scattering.h"
#include "sky/sun.h"
#include "spectral/cie.h"
#include "spectral/srgb.h"

namespace {

using arcus::Vec3;
using arcus::image::Image;
using arcus::image::MipPyramid;
using arcus::render::sky_irradiance;
using arcus::render::sky_irradiance_map;

Image flat_image(int w, int h, float r, float g, float b) {
  Image im;
  im.width = w;
  im.height = h;
  im.channels = {"R", "G", "B"};
  for (int p = 0; p < w * h; ++p) im.pixels.insert(im.pixels.end(), {r, g, b});
  return im;
}

TEST(SkyLight, AUniformSkyAndGroundGiveTheTiltedPlanesViewFactors) {
  const Image sky = flat_image(1024, 512, 0.1f, 0.2f, 0.3f);
  const Vec3 sun{1.0, 0.9, 0.8};
  const double elevation = 30, albedo = 0.25;
  const Image map = sky_irradiance_map(sky, sun, elevation, albedo);
  const double L[3] = {0.1, 0.2, 0.3}, E_sun[3] = {1.0, 0.9, 0.8};
  for (double tilt = 0; tilt <= 180; tilt += 15)
    for (double azimuth : {0.0, 70.0, 200.0}) {
      const double t = tilt * M_PI / 180, a = azimuth * M_PI / 180;
      const Vec3 n{std::sin(t) * std::sin(a), std::cos(t), std::sin(t) * std::cos(a)};
      const Vec3 e = sky_irradiance(map, n);
      const double got[3] = {e.x, e.y, e.z};
      for (int c = 0; c < 3; ++c) {
        const double ground = albedo / M_PI * (M_PI * L[c] + E_sun[c] * std::sin(elevation * M_PI / 180));
        const double want = M_PI * L[c] * (1 + n.y) / 2 + M_PI * (1 - n.y) / 2 * ground;
        // Tolerance: the sky is integrated over cells 2.8° across, whose cosine weight
        // is cut at the plane through them, and the map is read bilinearly between
        // normals 5.6° apart, where E varies smoothly: 0.5 % (measured: 0.1 %).
        EXPECT_NEAR(got[c], want, 0.005 * want) << "tilt " << tilt << "°, azimuth " << azimuth << "°, channel " << c;
      }
    }
}

TEST(SkyLight, TheClearSkysLightOnTheGroundIsTheSkysHemisphericalIntegral) {
  arcus::sky::Atmosphere air;  // the defaults: 300 DU, τ(500) = 0.1
  for (double elevation : {10.0, 33.0, 60.0}) {
    const double zenith = (90 - elevation) * M_PI / 180;
    Image sky;
    sky.width = 1024;
    sky.height = 512;
    sky.channels = {"R", "G", "B"};
    sky.pixels = arcus::sky::sky_panorama(air, zenith, 0.0, sky.width, sky.height);
    const Vec3 e = sky_irradiance(sky_irradiance_map(sky, Vec3{0, 0, 0}, elevation, 0.0), Vec3{0, 1, 0});
    // The reference: the diffuse light in the panorama's 10 nm bands, in sRGB.
    std::vector<double> nm, direct, diffuse;
    for (double w = 365; w < 830; w += 10) nm.push_back(w);
    direct.resize(nm.size());
    diffuse.resize(nm.size());
    arcus::sky::ground_irradiance(air, zenith, nm, direct.data(), diffuse.data());
    for (size_t k = 0; k < nm.size(); ++k)  // under the band's mean sun, as the panorama's
      diffuse[k] *= arcus::sky::solar_irradiance_band(nm[k] - 5, nm[k] + 5) / arcus::sky::solar_irradiance(nm[k]);
    double xyz[3];
    arcus::spectral::spectrum_to_xyz(nm.data(), diffuse.data(), nm.size(), xyz);
    const auto want = arcus::spectral::xyz_to_linear_srgb({xyz[0], xyz[1], xyz[2]});
    const double got[3] = {e.x, e.y, e.z};
    for (int c = 0; c < 3; ++c)
      // Tolerance: the panorama interpolates the sky from 61 × 61 directions (dense at
      // the horizon) and the map sums it over 2.8° cells; the reference takes 16 × 24
      // Gauss–Legendre directions of the sky itself (converged: 48 × 91 changes it by
      // 10⁻⁶).  1 % (measured: 0.23 %, the sun low, at 10°).
      EXPECT_NEAR(got[c], want[c], 0.01 * want[c]) << "sun at " << elevation << "°, channel " << c;
  }
}

TEST(MipPyramid, EveryLevelKeepsTheImagesMeanAndAFlatTextureStaysFlat) {
  Image checker = flat_image(64, 32, 0, 0, 0);
  for (int y = 0; y < 32; ++y)
    for (int x = 0; x < 64; ++x)
      for (int c = 0; c < 3; ++c) checker.pixels[3 * (y * 64 + x) + c] = static_cast<float>((x + y) % 2);
  const MipPyramid mip(checker);
  EXPECT_EQ(mip.level_count(), 7u);  // 64×32, 32×16, ..., 1×1
  // A footprint 4 texels each way reads level 2, where 2×2 means of a checker are ½.
  const auto c = mip.sample(0.3, 0.6, 4.0 / 64, 0, 0, 4.0 / 32);
  for (int k = 0; k < 3; ++k) EXPECT_NEAR(c[k], 0.5, 1e-6);
  // An endless footprint reads the 1×1 level: the image's mean.
  EXPECT_NEAR(mip.sample(0.3, 0.6, INFINITY, 0, 0, 1.0)[0], 0.5, 1e-6);
  const MipPyramid flat(flat_image(50, 30, 0.2f, 0.4f, 0.6f));  // odd sizes: the edge repeats
  for (double size : {0.0, 0.01, 0.3, 5.0}) {
    const auto f = flat.sample(0.91, 0.07, size, 0.3 * size, -0.2 * size, size);
    EXPECT_NEAR(f[0], 0.2, 1e-6);
    EXPECT_NEAR(f[1], 0.4, 1e-6);
    EXPECT_NEAR(f[2], 0.6, 1e-6);
  }
}

TEST(MipPyramid, AFootprintAlongStripesKeepsThemAndOneAcrossAveragesThem) {
  // Rows 0–15 dark, 16–31 bright, repeating: stripes along u.
  Image stripes = flat_image(256, 256, 0, 0, 0);
  for (int y = 0; y < 256; ++y)
    for (int x = 0; x < 256; ++x)
      for (int c = 0; c < 3; ++c) stripes.pixels[3 * (y * 256 + x) + c] = (y / 16) % 2 ? 1.f : 0.f;
  const MipPyramid mip(stripes);
  const double v_bright = 24.0 / 256;  // the middle of a bright stripe
  // 64 texels along the stripes, 1 across: anisotropic, the stripe stays bright (the
  // blur across is 64/16 = 4 texels at most, inside the stripe's 16).
  EXPECT_NEAR(mip.sample(0.5, v_bright, 64.0 / 256, 0, 0, 1.0 / 256)[0], 1.0, 1e-6);
  // 64 texels across the stripes: two periods, their mean.
  EXPECT_NEAR(mip.sample(0.5, v_bright, 0, 64.0 / 256, 1.0 / 256, 0)[0], 0.5, 0.05);
}

}  // namespace
