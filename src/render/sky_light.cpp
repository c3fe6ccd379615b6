#include "render/sky_light.h"

#include <algorithm>
#include <cmath>
#include <vector>

namespace arcus::render {
namespace {

// The unit direction at polar angle theta from +y and azimuth phi, as image_io.h's
// equirect_uv counts them (u = ½ + atan2(x, −z)/2π, v = acos(y)/π = theta/π).
Vec3 direction_of(double theta, double phi) {
  return {std::sin(theta) * std::sin(phi), std::cos(theta), -std::sin(theta) * std::cos(phi)};
}

// The map's normals: kColumns azimuths (from −π) by kRows polar angles from 0 to π,
// both poles included, where every column is the same normal (a grid of cell centres
// would read the zenith from normals tilted half a row toward one side).
constexpr int kColumns = 64, kRows = 33;
double row_theta(int j) { return M_PI * j / (kRows - 1); }
double column_phi(int i) { return 2 * M_PI * i / kColumns - M_PI; }

}  // namespace

image::Image sky_irradiance_map(const image::Image& sky, Vec3 sun, double sun_elevation_deg, double ground_albedo) {
  // The panorama averaged into blocks of 8 × 8 (1024 × 512 → 128 × 64, 2.8° a cell):
  // E(n) is a cosine-weighted integral, smooth in n, and a cell's mean is its integral.
  constexpr int kBlock = 8;
  const int w = std::max(1, sky.width / kBlock), h = std::max(1, sky.height / kBlock);
  const size_t stride = sky.channels.size();
  std::vector<Vec3> radiance(static_cast<size_t>(w) * h, Vec3{0, 0, 0});
  for (int j = 0; j < sky.height; ++j)
    for (int i = 0; i < sky.width; ++i) {
      const float* p = &sky.pixels[stride * (static_cast<size_t>(j) * sky.width + i)];
      const size_t cell = static_cast<size_t>(std::min(j * h / sky.height, h - 1)) * w + std::min(i * w / sky.width, w - 1);
      radiance[cell] = radiance[cell] + Vec3{p[0], p[1], p[2]};
    }
  const double per_cell = static_cast<double>(w) * h / (static_cast<double>(sky.width) * sky.height);
  for (Vec3& r : radiance) r = per_cell * r;

  std::vector<Vec3> dirs(radiance.size());
  std::vector<double> solid(radiance.size());
  for (int j = 0; j < h; ++j)
    for (int i = 0; i < w; ++i) {
      dirs[static_cast<size_t>(j) * w + i] = direction_of((j + 0.5) / h * M_PI, ((i + 0.5) / w - 0.5) * 2 * M_PI);
      // The cell's solid angle, exact over its band of latitude.
      solid[static_cast<size_t>(j) * w + i] =
          2 * M_PI / w * (std::cos(M_PI * j / h) - std::cos(M_PI * (j + 1) / h));
    }
  // The sky's share: the cells above the horizon (it lies between two rows).
  auto sky_irradiance_at = [&](Vec3 n) {
    Vec3 e{0, 0, 0};
    for (size_t c = 0; c < dirs.size(); ++c) {
      const double cosine = dot(dirs[c], n);
      if (cosine <= 0 || dirs[c].y <= 0) continue;
      e = e + (cosine * solid[c]) * radiance[c];
    }
    return e;
  };
  // The ground below the horizon: one Lambertian radiance, lit by the sun and the sky.
  const Vec3 up_sky = sky_irradiance_at(Vec3{0, 1, 0});
  const Vec3 ground = (ground_albedo / M_PI) * (up_sky + std::sin(sun_elevation_deg * M_PI / 180) * sun);

  image::Image map;
  map.width = kColumns;
  map.height = kRows;
  map.channels = {"R", "G", "B"};
  map.pixels.resize(3 * static_cast<size_t>(map.width) * map.height);
  for (int j = 0; j < map.height; ++j)
    for (int i = 0; i < map.width; ++i) {
      const Vec3 n = direction_of(row_theta(j), column_phi(i));
      // The lower hemisphere's share of a cosine lobe about n: (1 − n_y)/2 of π.
      const Vec3 e = sky_irradiance_at(n) + (M_PI * 0.5 * (1 - n.y)) * ground;
      float* out = &map.pixels[3 * (static_cast<size_t>(j) * map.width + i)];
      out[0] = static_cast<float>(e.x);
      out[1] = static_cast<float>(e.y);
      out[2] = static_cast<float>(e.z);
    }
  return map;
}

Vec3 sky_irradiance(const image::Image& map, Vec3 n) {
  // Bilinear between the four normals around n; azimuth wraps.
  const double theta = std::acos(std::clamp(n.y, -1.0, 1.0)), phi = std::atan2(n.x, -n.z);
  const double row = std::min(theta / M_PI * (kRows - 1), kRows - 1.0);
  const double column = (phi + M_PI) / (2 * M_PI) * kColumns;
  const int j0 = std::min(static_cast<int>(row), kRows - 2), i0 = static_cast<int>(std::floor(column));
  const double fr = row - j0, fc = column - i0;
  auto at = [&](int i, int j) {
    const float* e = &map.pixels[3 * (static_cast<size_t>(j) * kColumns + ((i % kColumns) + kColumns) % kColumns)];
    return Vec3{e[0], e[1], e[2]};
  };
  return (1 - fr) * ((1 - fc) * at(i0, j0) + fc * at(i0 + 1, j0)) + fr * ((1 - fc) * at(i0, j0 + 1) + fc * at(i0 + 1, j0 + 1));
}

}  // namespace arcus::render
