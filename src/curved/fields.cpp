#include "curved/fields.h"

#include <algorithm>
#include <cmath>
#include <string>

#include "core/error.h"

namespace arcus {
namespace {

// US Standard Atmosphere 1976 (NOAA-S/T 76-1562), table 4: base geopotential heights
// (m) and lapse rates (K/m) of its layers up to 84.852 km; isothermal above.
constexpr double kStdBase[] = {0.0, 11000.0, 20000.0, 32000.0, 47000.0, 51000.0, 71000.0, 84852.0};
constexpr double kStdLapse[] = {-0.0065, 0.0, 0.001, 0.0028, 0.0, -0.0028, -0.002, 0.0};
constexpr int kStdLayers = 8;
constexpr double kTopGeometric = 84000.0;  // inversions must end below the table's top
constexpr double kGeopotentialRadius = 6356766.0;  // r0 of the 1976 standard's H = r0·h/(r0 + h)

double geopotential(double h, double r0) { return r0 * h / (r0 + h); }

// Standard temperature at geopotential height H for a given sea-level temperature.
double standard_temperature(double H, double t0) {
  double T = t0;
  for (int i = 0; i < kStdLayers; ++i) {
    double top = i + 1 < kStdLayers ? kStdBase[i + 1] : INFINITY;
    double span = std::min(std::max(H, kStdBase[i]), top) - kStdBase[i];
    if (i == 0 && H < 0) span = H;  // below sea level the first lapse rate continues
    T += kStdLapse[i] * span;
    if (H < top) break;
  }
  return T;
}

struct Layer {
  double base_H, top_H, delta_t;
};

// Temperature offset of the inversion layers: delta_t below the base, fading
// linearly to 0 at the top (arcus.h, arcus_inversion).
double inversion_offset(double H, const std::vector<Layer>& layers) {
  double d = 0;
  for (const Layer& l : layers) {
    if (H <= l.base_H)
      d += l.delta_t;
    else if (H < l.top_H)
      d += l.delta_t * (l.top_H - H) / (l.top_H - l.base_H);
  }
  return d;
}

bool finite_positive(double v) { return std::isfinite(v) && v > 0; }

}  // namespace

double ciddor_standard_refractivity(double wavelength_nm) {
  const double sigma2 = std::pow(1000.0 / wavelength_nm, 2);  // (1/µm)²
  return 1e-8 * (5792105.0 / (238.0185 - sigma2) + 167917.0 / (57.362 - sigma2));
}

void build_atmosphere(const arcus_atmosphere_desc& desc, arcus_field_desc_d* field, std::vector<double>* segments) {
  require(desc.spherical == 0 || desc.spherical == 1, "atmosphere: spherical must be 0 or 1");
  require(std::isfinite(desc.wavelength) && desc.wavelength >= 300.0 && desc.wavelength <= 1690.0,
          "atmosphere: wavelength " + std::to_string(desc.wavelength) +
              " nm is outside Ciddor's range of 300..1690 nm");
  require(std::isfinite(desc.sea_level_temperature) && desc.sea_level_temperature > 150.0 &&
              desc.sea_level_temperature < 400.0,
          "atmosphere: sea_level_temperature must be a temperature in kelvin between 150 and 400");
  require(finite_positive(desc.sea_level_pressure), "atmosphere: sea_level_pressure must be positive (Pa)");
  require(desc.inversion_count == 0 || desc.inversions, "atmosphere: inversions is NULL but inversion_count > 0");

  const double R = kGeopotentialRadius;
  std::vector<Layer> layers;
  std::vector<double> breaks(kStdBase, kStdBase + kStdLayers);
  for (uint32_t i = 0; i < desc.inversion_count; ++i) {
    const arcus_inversion& inv = desc.inversions[i];
    const std::string which = "atmosphere: inversions[" + std::to_string(i) + "]";
    require(std::isfinite(inv.base) && std::isfinite(inv.top) && std::isfinite(inv.delta_t),
            which + " has a non-finite value");
    require(inv.base >= 0 && inv.top > inv.base && inv.top <= kTopGeometric,
            which + ": need 0 <= base < top <= 84000 m");
    require(std::fabs(inv.delta_t) <= 100.0, which + ": |delta_t| must be at most 100 K");
    layers.push_back({geopotential(inv.base, R), geopotential(inv.top, R), inv.delta_t});
    breaks.push_back(layers.back().base_H);
    breaks.push_back(layers.back().top_H);
  }
  std::sort(breaks.begin(), breaks.end());
  breaks.erase(std::unique(breaks.begin(), breaks.end()), breaks.end());

  auto temperature = [&](double H) {
    return standard_temperature(H, desc.sea_level_temperature) + inversion_offset(H, layers);
  };
  // T is linear between consecutive breaks, so each piece is one segment; pressure
  // follows from the hydrostatic equation in closed form, as in atmosphere_eval.
  segments->clear();
  double p = desc.sea_level_pressure;
  for (size_t k = 0; k < breaks.size(); ++k) {
    double H0 = breaks[k], T0 = temperature(H0);
    require(T0 > 50.0, "atmosphere: the inversions make the temperature at geopotential height " +
                           std::to_string(H0) + " m fall to " + std::to_string(T0) + " K");
    double lapse = 0.0;  // above the last break: isothermal, as the 1976 table
    if (k + 1 < breaks.size()) lapse = (temperature(breaks[k + 1]) - T0) / (breaks[k + 1] - H0);
    segments->insert(segments->end(), {H0, T0, lapse, p});
    if (k + 1 < breaks.size()) {
      double dH = breaks[k + 1] - H0, x = lapse * dH / T0;
      double integral = std::fabs(x) < 1e-12 ? dH / T0 : std::log1p(x) / lapse;
      p *= std::exp(-ARCUS_ATM_G_M_OVER_R * integral);
    }
  }

  *field = arcus_field_desc_d{};
  field->kind = ARCUS_KIND_ATMOSPHERE;
  field->spherical = desc.spherical;
  field->earth_radius = ARCUS_EARTH_RADIUS;
  field->geopotential_radius = kGeopotentialRadius;
  field->count = static_cast<int32_t>(breaks.size());
  // n − 1 = K·p/T: Ciddor's standard refractivity scaled by density (ideal gas; the
  // compressibility of air changes n − 1 by < 0.05 %).
  field->refractivity = ciddor_standard_refractivity(desc.wavelength) * 288.15 / 101325.0;
}

size_t grid_value_count(const uint32_t dims[3], const double origin[3], const double spacing[3]) {
  require_pointer(dims, "dims");
  require_pointer(origin, "origin");
  require_pointer(spacing, "spacing");
  size_t count = 1;
  for (int a = 0; a < 3; ++a) {
    require(dims[a] >= 2 && dims[a] <= (1u << 16), "grid: dims[" + std::to_string(a) + "] = " +
                                                        std::to_string(dims[a]) + " must be in 2..65536");
    require(std::isfinite(origin[a]), "grid: origin[" + std::to_string(a) + "] is not finite");
    require(finite_positive(spacing[a]), "grid: spacing[" + std::to_string(a) + "] must be positive");
    count *= dims[a];
  }
  require(count <= (size_t(1) << 31), "grid: more than 2^31 values");
  return count;
}

void build_grid(const double* values, const uint32_t dims[3], const double origin[3], const double spacing[3],
                arcus_field_desc_d* field, std::vector<double>* data) {
  const size_t count = grid_value_count(dims, origin, spacing);
  require_pointer(values, "values");
  for (size_t i = 0; i < count; ++i)
    require(finite_positive(values[i]), "grid: values[" + std::to_string(i) + "] = " + std::to_string(values[i]) +
                                            " is not a positive finite index of refraction");
  *field = arcus_field_desc_d{};
  field->kind = ARCUS_KIND_GRID;
  for (int a = 0; a < 3; ++a) {
    field->dims[a] = static_cast<int32_t>(dims[a]);
    field->origin[a] = origin[a];
    field->inv_spacing[a] = 1.0 / spacing[a];
  }
  data->assign(values, values + count);
}

}  // namespace arcus
