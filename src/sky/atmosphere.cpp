#include "sky/atmosphere.h"

#include <algorithm>
#include <cmath>

#include "core/error.h"
#include "core/format.h"
#include "sky/paths.h"
#include "sky/rayleigh.h"
#include "sky/sun.h"
#include "common/real.h"
#include "sky/air.h"  // kernels/sky/air.h: Ciddor's index

namespace arcus::sky {
namespace {
#include "sky/sky_data.inc"

constexpr double kOzoneBottom = 10000, kOzonePeak = 25000, kOzoneTop = 40000;  // m

// The tent's integral over height is (top − bottom)/2 = 15 km: 1 DU of column.
double ozone_shape(double h) {
  if (h <= kOzoneBottom || h >= kOzoneTop) return 0;
  return h < kOzonePeak ? (h - kOzoneBottom) / (kOzonePeak - kOzoneBottom) : (kOzoneTop - h) / (kOzoneTop - kOzonePeak);
}

const double kPathEndsNm[2] = {kDaylightMinNm, kDaylightMaxNm};

}  // namespace

void check_atmosphere(const Atmosphere& a, const std::string& prefix) {
  const struct {
    const char* name;
    double value, lo, hi;
  } fields[] = {{"site_height", a.site_height_m, 0, 80000},
                {"ozone_du", a.ozone_du, 0, 1000},
                {"aerosol_depth_500", a.aerosol_depth_500, 0, 10},
                {"angstrom_exponent", a.angstrom_exponent, -1, 4},
                {"aerosol_scale_height", a.aerosol_scale_height_m, 100, 20000},
                {"co2_ppm", a.co2_ppm, 0, 10000},
                {"aerosol_albedo", a.aerosol_albedo, 0, 1},
                {"aerosol_asymmetry", a.aerosol_asymmetry, -0.99, 0.99},
                {"ground_albedo", a.ground_albedo, 0, 1}};
  for (const auto& f : fields) require_within(f.value, f.lo, f.hi, prefix + f.name);
}

void require_within(double value, double lo, double hi, const std::string& name) {
  require(std::isfinite(value) && value >= lo && value <= hi,
          name + " must lie in [" + number(lo) + ", " + number(hi) + "], got " + number(value));
}

double ozone_profile(double height_m) {
  return kDobsonUnit * ozone_shape(height_m) / (0.5 * (kOzoneTop - kOzoneBottom));
}

double ozone_cross_section(double wavelength_nm) {
  const int n = embedded::kOzoneBins;
  auto centre = [](int i) { return 0.5 * (embedded::kOzoneBinStartNm[i] + embedded::kOzoneBinEndNm[i]); };
  if (wavelength_nm <= centre(0)) return embedded::kOzoneCrossSection[0];
  if (wavelength_nm >= centre(n - 1)) return embedded::kOzoneCrossSection[n - 1];
  int i = 0;
  while (centre(i + 1) < wavelength_nm) ++i;
  const double t = (wavelength_nm - centre(i)) / (centre(i + 1) - centre(i));
  return (1 - t) * embedded::kOzoneCrossSection[i] + t * embedded::kOzoneCrossSection[i + 1];
}

// Ozone per DU and the aerosol's relative density (1 at the site, so its column is in
// metres and τ_a = τ_a(vertical)·column/H) along the path, with the air's column.
SlantPath::SlantPath(const Atmosphere& atmosphere, double zenith) : atmosphere_(atmosphere) {
  Densities densities;
  densities.count = 2;
  densities.at = [&](double h, double* d) {
    d[0] = ozone_profile(h);
    d[1] = std::exp(-(h - atmosphere.site_height_m) / atmosphere.aerosol_scale_height_m);
  };
  for (int e = 0; e < 2; ++e) {
    refractivity_[e] = ciddor_refractivity(kPathEndsNm[e]);
    refracted_columns(atmosphere.site_height_m, zenith, kPathEndsNm[e], densities, columns_[e]);
  }
}

OpticalDepths SlantPath::depths(double wavelength_nm) const {
  const double t = (ciddor_refractivity(wavelength_nm) - refractivity_[0]) / (refractivity_[1] - refractivity_[0]);
  double c[3];
  for (int k = 0; k < 3; ++k) c[k] = (1 - t) * columns_[0][k] + t * columns_[1][k];
  const Atmosphere& a = atmosphere_;
  OpticalDepths d;
  d.rayleigh = rayleigh_cross_section(wavelength_nm, a.co2_ppm) * c[0];
  d.ozone = ozone_cross_section(wavelength_nm) * a.ozone_du * c[1];
  // The exponential's integral from the site up is H (the top's e^{−86 km/H} is nothing).
  d.aerosol = a.aerosol_depth_500 * std::pow(wavelength_nm / 500.0, -a.angstrom_exponent) * c[2] /
              a.aerosol_scale_height_m;
  return d;
}

OpticalDepths vertical_depths(const Atmosphere& atmosphere, double wavelength_nm) {
  return SlantPath(atmosphere, 0).depths(wavelength_nm);
}

}  // namespace arcus::sky
