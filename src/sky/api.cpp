// The shared sun and sky's C API (include/arcus/arcus_daylight.h): host code, no context.
#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

#include "arcus/arcus_daylight.h"
#include "core/call.h"
#include "core/format.h"
#include "sky/atmosphere.h"
#include "sky/scattering.h"
#include "sky/sun.h"

using namespace arcus;
using namespace arcus::api;

namespace {

using sky::require_within;

// Arrays of count values, each within [lo, hi].
void require_array(size_t count, const double* values, double lo, double hi, const char* name) {
  require(count == 0 || values, std::string(name) + " is NULL");
  for (size_t i = 0; i < count; ++i)
    require_within(values[i], lo, hi, std::string(name) + "[" + std::to_string(i) + "]");
}

sky::Atmosphere atmosphere_of(const arcus_daylight_desc* desc) {
  require_pointer(desc, "desc");
  sky::Atmosphere a;
  a.site_height_m = desc->site_height;
  a.ozone_du = desc->ozone_du;
  a.aerosol_depth_500 = desc->aerosol_depth_500;
  a.angstrom_exponent = desc->angstrom_exponent;
  a.aerosol_scale_height_m = desc->aerosol_scale_height;
  a.co2_ppm = desc->co2_ppm;
  a.aerosol_albedo = desc->aerosol_albedo;
  a.aerosol_asymmetry = desc->aerosol_asymmetry;
  a.ground_albedo = desc->ground_albedo;
  sky::check_atmosphere(a, "desc.");
  return a;
}

}  // namespace

arcus_status arcus_daylight_desc_init(arcus_daylight_desc* desc) {
  return without_context([&] {
    require_pointer(desc, "desc");
    const sky::Atmosphere a;
    *desc = arcus_daylight_desc{a.site_height_m,     a.ozone_du, a.aerosol_depth_500, a.angstrom_exponent,
                                a.aerosol_scale_height_m, a.co2_ppm,          a.aerosol_albedo, a.aerosol_asymmetry,
                                a.ground_albedo};
  });
}

arcus_status arcus_daylight_optical_depths(const arcus_daylight_desc* desc, double apparent_zenith_deg, size_t count,
                                           const double* wavelength_nm, arcus_optical_depths* depths) {
  return without_context([&] {
    const sky::Atmosphere a = atmosphere_of(desc);
    require_within(apparent_zenith_deg, 0, 90, "apparent_zenith_deg");
    require_array(count, wavelength_nm, sky::kDaylightMinNm, sky::kDaylightMaxNm, "wavelength_nm");
    require(count == 0 || depths, "depths is NULL");
    if (count == 0) return;  // what a caller checking its desc asks
    const sky::SlantPath path(a, apparent_zenith_deg * M_PI / 180);
    for (size_t i = 0; i < count; ++i) {
      const sky::OpticalDepths d = path.depths(wavelength_nm[i]);
      depths[i] = arcus_optical_depths{d.rayleigh, d.ozone, d.aerosol};
    }
  });
}

arcus_status arcus_daylight_sky_radiance(const arcus_daylight_desc* desc, double sun_zenith_deg,
                                         size_t direction_count, const double* view_zenith_deg,
                                         const double* view_azimuth_deg, size_t wavelength_count,
                                         const double* wavelength_nm, double* radiance) {
  return without_context([&] {
    const sky::Atmosphere a = atmosphere_of(desc);
    require_within(sun_zenith_deg, 0, 120, "sun_zenith_deg");
    require_array(direction_count, view_zenith_deg, 0, 180, "view_zenith_deg");
    require_array(direction_count, view_azimuth_deg, -360, 360, "view_azimuth_deg");
    require_array(wavelength_count, wavelength_nm, sky::kDaylightMinNm, sky::kDaylightMaxNm, "wavelength_nm");
    require(direction_count == 0 || wavelength_count == 0 || radiance, "radiance is NULL");
    // ~1 ms a direction: bounded so that one call cannot run for hours.
    require(direction_count <= 1000000, "direction_count is " + std::to_string(direction_count) + ", at most 1000000");
    const sky::ClearSky sky(a, sun_zenith_deg * M_PI / 180);
    const std::vector<double> nm(wavelength_nm, wavelength_nm + wavelength_count);
    for (size_t d = 0; d < direction_count; ++d)
      sky.radiance(view_zenith_deg[d] * M_PI / 180, view_azimuth_deg[d] * M_PI / 180, nm,
                   radiance + d * wavelength_count);
  });
}

arcus_status arcus_daylight_sky_image(const arcus_daylight_desc* desc, double sun_zenith_deg, double sun_azimuth_deg,
                                      uint32_t width, uint32_t height, float* rgb) {
  return without_context([&] {
    const sky::Atmosphere a = atmosphere_of(desc);
    require_within(sun_zenith_deg, 0, 120, "sun_zenith_deg");
    require_within(sun_azimuth_deg, -360, 360, "sun_azimuth_deg");
    require(width >= 1 && width <= 8192 && height >= 1 && height <= 8192,
            "width and height must be 1 to 8192, got " + std::to_string(width) + " × " + std::to_string(height));
    require_pointer(rgb, "rgb");
    const std::vector<float> image =
        sky::sky_panorama(a, sun_zenith_deg * M_PI / 180, sun_azimuth_deg * M_PI / 180, int(width), int(height));
    std::copy(image.begin(), image.end(), rgb);
  });
}

arcus_status arcus_daylight_ground_irradiance(const arcus_daylight_desc* desc, double sun_zenith_deg, size_t count,
                                              const double* wavelength_nm, double* direct, double* diffuse) {
  return without_context([&] {
    const sky::Atmosphere a = atmosphere_of(desc);
    require_within(sun_zenith_deg, 0, 120, "sun_zenith_deg");
    require_array(count, wavelength_nm, sky::kDaylightMinNm, sky::kDaylightMaxNm, "wavelength_nm");
    const std::vector<double> nm(wavelength_nm, wavelength_nm + count);
    std::vector<double> d(count), s(count);
    sky::ground_irradiance(a, sun_zenith_deg * M_PI / 180, nm, d.data(), s.data());
    if (direct) std::copy(d.begin(), d.end(), direct);
    if (diffuse) std::copy(s.begin(), s.end(), diffuse);
  });
}

arcus_status arcus_daylight_solar_irradiance(size_t count, const double* wavelength_nm, double band_nm,
                                             double* irradiance) {
  return without_context([&] {
    require_within(band_nm, 0, 100, "band_nm");
    require_array(count, wavelength_nm, 300 + band_nm / 2, 1000 - band_nm / 2, "wavelength_nm");
    require(count == 0 || irradiance, "irradiance is NULL");
    for (size_t i = 0; i < count; ++i)
      irradiance[i] = band_nm > 0 ? sky::solar_irradiance_band(wavelength_nm[i] - band_nm / 2,
                                                               wavelength_nm[i] + band_nm / 2)
                                  : sky::solar_irradiance(wavelength_nm[i]);
  });
}

arcus_status arcus_daylight_limb_darkening(size_t count, const double* wavelength_nm, const double* mu,
                                           double* ratio) {
  return without_context([&] {
    require_array(count, wavelength_nm, 300, 1100, "wavelength_nm");
    require_array(count, mu, 0, 1, "mu");
    require(count == 0 || ratio, "ratio is NULL");
    for (size_t i = 0; i < count; ++i) ratio[i] = sky::limb_darkening(wavelength_nm[i], mu[i]);
  });
}
