#include "curved/fields.h"
#include "curved/scene_desc.h"

#include <algorithm>
#include <cmath>
#include <string>

#include "core/error.h"
#include "core/files.h"
#include "core/format.h"
#include "core/limits.h"
#include "sky/us1976.h"

namespace arcus::curved {

const HandleKind kFieldHandle("field");

namespace {

// The US Standard Atmosphere 1976 is src/sky/us1976.h; its extension here.
constexpr double kTopGeometric = 84000.0;          // inversions must end below the table's top
constexpr double kMinTemperature = 50.0;           // K: colder air is no air for this model
constexpr double kBelowSeaLevel = -1000.0;         // geopotential m: the base of the segment below sea level

struct Layer {
  double base_H, top_H, delta_t;
};

// Temperature offset of the inversion layers: delta_t below the base, fading
// linearly to 0 at the top (arcus_curved.h, arcus_inversion).
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

void require_finite(double v, const char* name) {
  require(std::isfinite(v), std::string(name) + " = " + number(v) + " is not finite");
}

void require_finite3(const double* v, const char* name) {
  require_pointer(v, name);
  for (int a = 0; a < 3; ++a)
    require(std::isfinite(v[a]), std::string(name) + "[" + std::to_string(a) + "] = " + number(v[a]) + " is not finite");
}

// The kernels use 1/R²: it must be finite and non-zero, which R alone does not ensure
// (R = 1e-200 squares to 0, R = 1e200 to infinity).
double inverse_square_radius(double radius) {
  require(finite_positive(radius), "radius = " + number(radius) + " must be positive and finite");
  const double inv = 1.0 / (radius * radius);
  require(std::isfinite(inv) && inv > 0,
          "radius = " + number(radius) + " is too " + (radius < 1 ? "small" : "large") +
              ": 1/radius² is not a finite non-zero number");
  return inv;
}

FieldBuild with_kind(int32_t kind) {
  FieldBuild b;
  b.desc.kind = kind;
  return b;
}

}  // namespace

FieldBuild constant(double n) {
  require(finite_positive(n), "n = " + number(n) + " must be positive and finite");
  FieldBuild b = with_kind(ARCUS_KIND_CONSTANT);
  b.desc.n0 = n;
  return b;
}

FieldBuild linear(double n0, const double* gradient) {
  require_finite(n0, "n0");
  require_finite3(gradient, "gradient");
  FieldBuild b = with_kind(ARCUS_KIND_LINEAR);
  b.desc.n0 = n0;
  std::copy(gradient, gradient + 3, b.desc.vec);
  return b;
}

FieldBuild linear_n2(double a, const double* k) {
  require_finite(a, "a");
  require_finite3(k, "k");
  FieldBuild b = with_kind(ARCUS_KIND_LINEAR_N2);
  b.desc.n0 = a;
  std::copy(k, k + 3, b.desc.vec);
  return b;
}

FieldBuild luneburg(const double* center, double radius) {
  require_finite3(center, "center");
  FieldBuild b = with_kind(ARCUS_KIND_LUNEBURG);
  b.desc.inv_radius2 = inverse_square_radius(radius);
  std::copy(center, center + 3, b.desc.vec);
  return b;
}

FieldBuild fisheye(const double* center, double radius, double n0) {
  require_finite3(center, "center");
  require(finite_positive(n0), "n0 = " + number(n0) + " must be positive and finite");
  FieldBuild b = with_kind(ARCUS_KIND_FISHEYE);
  b.desc.n0 = n0;
  b.desc.inv_radius2 = inverse_square_radius(radius);
  std::copy(center, center + 3, b.desc.vec);
  return b;
}

namespace {

void check_atmosphere(const arcus_atmosphere_desc& desc) {
  require(desc.spherical == 0 || desc.spherical == 1, "atmosphere: spherical must be 0 or 1");
  require(std::isfinite(desc.wavelength) && desc.wavelength >= ARCUS_MIN_WAVELENGTH &&
              desc.wavelength <= ARCUS_MAX_WAVELENGTH,
          "atmosphere: wavelength " + number(desc.wavelength) + " nm is outside Ciddor's range of 300..1690 nm");
  require(std::isfinite(desc.sea_level_temperature) && desc.sea_level_temperature > 150.0 &&
              desc.sea_level_temperature < 400.0,
          "atmosphere: sea_level_temperature = " + number(desc.sea_level_temperature) +
              " must be a temperature in kelvin between 150 and 400");
  require(finite_positive(desc.sea_level_pressure), "atmosphere: sea_level_pressure = " +
                                                        number(desc.sea_level_pressure) + " must be positive (Pa)");
  require(desc.inversion_count == 0 || desc.inversions, "atmosphere: inversions is NULL but inversion_count > 0");
  // The kernels scan every layer at every evaluation (a few are the rule in nature).
  require(desc.inversion_count <= ARCUS_MAX_INVERSIONS,
          "atmosphere: inversion_count = " + std::to_string(desc.inversion_count) + " exceeds " +
              std::to_string(ARCUS_MAX_INVERSIONS) + " layers");
}

// The inversions as layers in geopotential height, checked; *out gets every height where
// the temperature profile bends (the standard breaks and the layers' ends), sorted.
std::vector<Layer> inversion_layers(const arcus_atmosphere_desc& desc, std::vector<double>* out) {
  std::vector<Layer> layers;
  std::vector<double>& breaks = *out;
  breaks.assign(sky::kStandardBase, sky::kStandardBase + sky::kStandardLayers);
  for (uint32_t i = 0; i < desc.inversion_count; ++i) {
    const arcus_inversion& inv = desc.inversions[i];
    const std::string which = "atmosphere: inversions[" + std::to_string(i) + "]";
    require(std::isfinite(inv.base) && std::isfinite(inv.top) && std::isfinite(inv.delta_t),
            which + " has a non-finite value");
    require(inv.base >= 0 && inv.top > inv.base && inv.top <= kTopGeometric,
            which + ": need 0 <= base < top <= 84000 m (base " + number(inv.base) + ", top " + number(inv.top) + ")");
    require(std::fabs(inv.delta_t) <= 100.0, which + ": |delta_t| = " + number(std::fabs(inv.delta_t)) +
                                                 " K exceeds 100 K");
    layers.push_back({sky::geopotential_height(inv.base), sky::geopotential_height(inv.top), inv.delta_t});
    breaks.push_back(layers.back().base_H);
    breaks.push_back(layers.back().top_H);
  }
  std::sort(breaks.begin(), breaks.end());
  breaks.erase(std::unique(breaks.begin(), breaks.end()), breaks.end());
  // Below the lowest break the kernels extend the lowest segment downward; below sea
  // level this profile continues the first standard lapse rate with every inversion's
  // full offset (inversions start at 0 m or higher).  A segment from kBelowSeaLevel to 0
  // carries exactly that, so host and kernels keep one n(h) below sea level too.  (The
  // lowest segment used to be the surface inversion's own, whose steep gradient,
  // extended down, reached 0 K at -2975 m: rays there crawled and bent wrongly.)
  breaks.insert(breaks.begin(), kBelowSeaLevel);
  return layers;
}

// The limits DP45's steps keep to in b (field.h), from the segments' breaks.
void set_step_limits(const std::vector<double>& breaks, const std::vector<Layer>& layers, FieldBuild* out) {
  FieldBuild& b = *out;
  // The thinnest layer in geometric height, and the height of the last break (above it
  // the air is isothermal and smooth): DP45's steps span at most half of it (field.h).
  const auto geometric = sky::geometric_height;
  double inversions_top_H = 0;
  for (const Layer& l : layers) inversions_top_H = std::max(inversions_top_H, l.top_H);
  b.desc.inversions_top = geometric(inversions_top_H);
  b.desc.layer = b.desc.layer_above = INFINITY;
  for (size_t k = 1; k + 1 < breaks.size(); ++k) {  // from sea level: the segment below is no layer
    const double thickness = geometric(breaks[k + 1]) - geometric(breaks[k]);
    double& thinnest = breaks[k + 1] <= inversions_top_H ? b.desc.layer : b.desc.layer_above;
    thinnest = std::min(thinnest, thickness);
  }
  // Without inversions every layer is a standard one: the same limit everywhere.
  if (!std::isfinite(b.desc.layer)) b.desc.layer = b.desc.layer_above;
  b.desc.layers_top = geometric(breaks.back());
}

}  // namespace

FieldBuild atmosphere(const arcus_atmosphere_desc& desc) {
  check_atmosphere(desc);
  std::vector<double> breaks;
  const std::vector<Layer> layers = inversion_layers(desc, &breaks);

  auto temperature = [&](double H) {
    return sky::standard_temperature(H, desc.sea_level_temperature) + inversion_offset(H, layers);
  };
  // T is linear between consecutive breaks, so each piece is one segment; pressure
  // follows from the hydrostatic equation in closed form, as in atmosphere_eval.
  FieldBuild b = with_kind(ARCUS_KIND_ATMOSPHERE);
  double p = desc.sea_level_pressure;
  {
    // The pressure at kBelowSeaLevel, from sea level down (the closed form below, reversed).
    const double T_low = temperature(kBelowSeaLevel), lapse = (temperature(0.0) - T_low) / -kBelowSeaLevel;
    p /= sky::pressure_ratio(-kBelowSeaLevel, T_low, lapse);
  }
  for (size_t k = 0; k < breaks.size(); ++k) {
    if (breaks[k] == 0.0) p = desc.sea_level_pressure;  // exactly, not through the round trip
    double H0 = breaks[k], T0 = temperature(H0);
    if (T0 <= kMinTemperature) {
      const std::string where = "atmosphere: the temperature falls to " + number(T0) + " K at geopotential height " +
                                number(H0) + " m";
      fail(ARCUS_ERROR_INVALID_ARGUMENT,
           layers.empty() || sky::standard_temperature(H0, desc.sea_level_temperature) <= kMinTemperature
               ? where + ": the standard lapse rates from a sea-level temperature of " +
                     number(desc.sea_level_temperature) + " K reach below " + number(kMinTemperature) +
                     " K there; raise sea_level_temperature"
               : where + " because of the inversions' delta_t");
    }
    double lapse = 0.0;  // above the last break: isothermal, as the 1976 table
    if (k + 1 < breaks.size()) lapse = (temperature(breaks[k + 1]) - T0) / (breaks[k + 1] - H0);
    b.data.insert(b.data.end(), {H0, T0, lapse, p});
    if (k + 1 < breaks.size()) p *= sky::pressure_ratio(breaks[k + 1] - H0, T0, lapse);
  }

  b.desc.spherical = desc.spherical;
  b.desc.earth_radius = ARCUS_EARTH_RADIUS;
  b.desc.geopotential_radius = sky::kGeopotentialRadius;
  b.desc.count = static_cast<int32_t>(breaks.size());
  set_step_limits(breaks, layers, &b);
  b.desc.refractivity = ciddor_refractivity(desc.wavelength);
  return b;
}

size_t grid_value_count(const uint32_t* dims, const double* origin, const double* spacing) {
  require_pointer(dims, "dims");
  require_pointer(origin, "origin");
  require_pointer(spacing, "spacing");
  size_t count = 1;
  for (int a = 0; a < 3; ++a) {
    const std::string axis = "[" + std::to_string(a) + "]";
    require(dims[a] >= 2 && dims[a] <= (1u << 16),
            "grid: dims" + axis + " = " + std::to_string(dims[a]) + " must be in 2..65536");
    require(std::isfinite(origin[a]), "grid: origin" + axis + " = " + number(origin[a]) + " is not finite");
    require(finite_positive(spacing[a]), "grid: spacing" + axis + " = " + number(spacing[a]) + " must be positive");
    // What the kernels derive: 1/spacing, and the far corner of the grid.
    require(std::isfinite(1.0 / spacing[a]),
            "grid: spacing" + axis + " = " + number(spacing[a]) + " is too small: 1/spacing is not finite");
    require(std::isfinite(origin[a] + (dims[a] - 1) * spacing[a]),
            "grid: spacing" + axis + " = " + number(spacing[a]) + " is too large: the grid's extent is not finite");
    count *= dims[a];
  }
  require(count <= (size_t(1) << 31), "grid: more than 2^31 values");
  return count;
}

FieldBuild grid(std::vector<double> values, const uint32_t* dims, const double* origin, const double* spacing) {
  const size_t count = grid_value_count(dims, origin, spacing);
  require(values.size() == count, "grid: " + std::to_string(values.size()) + " values for " +
                                      std::to_string(count) + " grid points");
  // One pass without building messages (a 256³ grid has 16.7 million values).
  const auto bad = std::find_if(values.begin(), values.end(), [](double v) { return !finite_positive(v); });
  if (bad != values.end())
    fail(ARCUS_ERROR_INVALID_ARGUMENT, "grid: values[" + std::to_string(bad - values.begin()) + "] = " + number(*bad) +
                                           " is not a positive finite index of refraction");
  FieldBuild b = with_kind(ARCUS_KIND_GRID);
  for (int a = 0; a < 3; ++a) {
    b.desc.dims[a] = static_cast<int32_t>(dims[a]);
    b.desc.origin[a] = origin[a];
    b.desc.inv_spacing[a] = 1.0 / spacing[a];
  }
  b.data = std::move(values);
  return b;
}

std::vector<double> read_grid_file(const char* path, int32_t type, size_t count) {
  require_pointer(path, "path");
  require(type == ARCUS_FLOAT32 || type == ARCUS_FLOAT64,
          "type = " + std::to_string(type) + " is not ARCUS_FLOAT32 (0) or ARCUS_FLOAT64 (1)");
  files::RegularFile file(path);  // a FIFO or a device is refused without blocking
  const size_t width = type == ARCUS_FLOAT32 ? 4 : 8;
  if (file.size() != count * width)
    fail(ARCUS_ERROR_IO, std::string(path) + ": holds " + std::to_string(file.size()) + " bytes, but " +
                             std::to_string(count) + " values of " + std::to_string(width) + " bytes need " +
                             std::to_string(count * width));
  limits::require_host_memory(8.0 * double(count), std::string(path) + ": " + std::to_string(count) + " values");
  std::vector<double> values(count);
  // Read straight into the values (float32: through a small buffer), so the file is
  // never held twice.
  if (type == ARCUS_FLOAT64) {
    file.read_exact(reinterpret_cast<char*>(values.data()), count * 8);
  } else {
    std::vector<float> chunk(size_t(1) << 16);
    for (size_t done = 0; done < count;) {
      const size_t n = std::min(chunk.size(), count - done);
      file.read_exact(reinterpret_cast<char*>(chunk.data()), n * 4);
      std::copy(chunk.begin(), chunk.begin() + static_cast<std::ptrdiff_t>(n), values.begin() + static_cast<std::ptrdiff_t>(done));
      done += n;
    }
  }
  return values;
}

bool dispersive(const arcus_field_desc_d& desc) { return desc.kind == ARCUS_KIND_ATMOSPHERE; }

// A scene's medium made into a field (curved and render scenes).
FieldBuild build_field(const MediumDesc& m) {
  switch (m.kind) {
    case ARCUS_FIELD_CONSTANT: return constant(m.n);
    case ARCUS_FIELD_LINEAR: return linear(m.n0, m.gradient.array().data());
    case ARCUS_FIELD_LINEAR_N2: return linear_n2(m.a, m.k.array().data());
    case ARCUS_FIELD_LUNEBURG: return luneburg(m.center.array().data(), m.radius);
    case ARCUS_FIELD_FISHEYE: return fisheye(m.center.array().data(), m.radius, m.n0);
    case ARCUS_FIELD_ATMOSPHERE: {
      arcus_atmosphere_desc a;
      a.spherical = m.atmosphere.spherical ? 1 : 0;
      a.wavelength = m.atmosphere.wavelength;
      a.sea_level_temperature = m.atmosphere.sea_level_temperature;
      a.sea_level_pressure = m.atmosphere.sea_level_pressure;
      a.inversion_count = static_cast<uint32_t>(m.atmosphere.inversions.size());
      a.inversions = m.atmosphere.inversions.data();
      return atmosphere(a);
    }
    case ARCUS_FIELD_GRID: {
      const GridDesc& g = m.grid;
      const size_t count = grid_value_count(g.dims.data(), g.origin.array().data(), g.spacing.array().data());
      return grid(read_grid_file(g.file.c_str(), g.dtype, count), g.dims.data(), g.origin.array().data(), g.spacing.array().data());
    }
  }
  fail(ARCUS_ERROR_INVALID_ARGUMENT, "medium: unknown kind");
}

}  // namespace arcus::curved
