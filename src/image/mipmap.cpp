#include "image/mipmap.h"

#include <algorithm>
#include <cmath>

namespace arcus::image {

MipPyramid::MipPyramid(const Image& base) {
  Image level;
  level.width = base.width;
  level.height = base.height;
  level.channels = {"R", "G", "B"};
  const size_t stride = base.channels.size(), n = static_cast<size_t>(base.width) * base.height;
  level.pixels.resize(3 * n);
  for (size_t p = 0; p < n; ++p)
    for (size_t c = 0; c < 3; ++c) level.pixels[3 * p + c] = base.pixels[stride * p + std::min(c, stride - 1)];
  levels_.push_back(std::move(level));
  while (levels_.back().width > 1 || levels_.back().height > 1) {
    const Image& fine = levels_.back();
    Image coarse;
    coarse.width = (fine.width + 1) / 2;
    coarse.height = (fine.height + 1) / 2;
    coarse.channels = fine.channels;
    coarse.pixels.assign(3 * static_cast<size_t>(coarse.width) * coarse.height, 0.f);
    for (int y = 0; y < coarse.height; ++y)
      for (int x = 0; x < coarse.width; ++x) {
        // The 2×2 texels below (an odd edge repeats its last texel).
        for (int dy = 0; dy < 2; ++dy)
          for (int dx = 0; dx < 2; ++dx) {
            const int fx = std::min(2 * x + dx, fine.width - 1), fy = std::min(2 * y + dy, fine.height - 1);
            const float* f = &fine.pixels[3 * (static_cast<size_t>(fy) * fine.width + fx)];
            float* c = &coarse.pixels[3 * (static_cast<size_t>(y) * coarse.width + x)];
            for (int k = 0; k < 3; ++k) c[k] += 0.25f * f[k];
          }
      }
    levels_.push_back(std::move(coarse));
  }
}

std::array<float, 3> MipPyramid::bilinear(size_t level, double u, double v) const {
  const Image& im = levels_[level];
  const double x = u * im.width - 0.5, y = v * im.height - 0.5;
  const double x0 = std::floor(x), y0 = std::floor(y);
  const double fx = x - x0, fy = y - y0;
  auto wrap = [](double i, int n) {
    const double m = std::fmod(i, static_cast<double>(n));
    return static_cast<size_t>(m < 0 ? m + n : m);
  };
  const size_t xa = wrap(x0, im.width), xb = wrap(x0 + 1, im.width);
  const size_t ya = wrap(y0, im.height), yb = wrap(y0 + 1, im.height);
  auto at = [&](size_t xi, size_t yi, int c) { return im.pixels[3 * (yi * im.width + xi) + c]; };
  std::array<float, 3> out{};
  for (int c = 0; c < 3; ++c)
    out[c] = static_cast<float>((1 - fy) * ((1 - fx) * at(xa, ya, c) + fx * at(xb, ya, c)) +
                                fy * ((1 - fx) * at(xa, yb, c) + fx * at(xb, yb, c)));
  return out;
}

std::array<float, 3> MipPyramid::trilinear(double level, double u, double v) const {
  const double top = static_cast<double>(levels_.size() - 1);
  level = std::clamp(level, 0.0, top);
  const size_t lo = static_cast<size_t>(std::floor(level));
  const double t = level - lo;
  const auto a = bilinear(lo, u, v);
  if (t == 0) return a;
  const auto b = bilinear(std::min(lo + 1, levels_.size() - 1), u, v);
  return {static_cast<float>((1 - t) * a[0] + t * b[0]), static_cast<float>((1 - t) * a[1] + t * b[1]),
          static_cast<float>((1 - t) * a[2] + t * b[2])};
}

std::array<float, 3> MipPyramid::sample(double u, double v, double du_x, double dv_x, double du_y,
                                        double dv_y) const {
  constexpr int kMaxSamples = 16;
  // The footprint's axes in texels of the full image.
  const double w = width(), h = height();
  const double ax = du_x * w, ay = dv_x * h, bx = du_y * w, by = dv_y * h;
  double major = std::hypot(ax, ay), minor = std::hypot(bx, by);
  double mx = ax, my = ay;  // the long axis, in texels
  if (minor > major) {
    std::swap(major, minor);
    mx = bx;
    my = by;
  }
  if (!(major > 1e-12)) return trilinear(0, u, v);
  if (!std::isfinite(major)) return trilinear(static_cast<double>(levels_.size() - 1), u, v);  // the mean
  minor = std::max(minor, major / kMaxSamples);
  const int n = std::clamp(static_cast<int>(std::ceil(major / minor)), 1, kMaxSamples);
  const double level = std::log2(std::max(minor, 1.0));
  std::array<double, 3> sum{};
  for (int i = 0; i < n; ++i) {
    const double s = (i + 0.5) / n - 0.5;  // spread over the long axis, centred
    const auto c = trilinear(level, u + s * mx / w, v + s * my / h);
    for (int k = 0; k < 3; ++k) sum[k] += c[k];
  }
  return {static_cast<float>(sum[0] / n), static_cast<float>(sum[1] / n), static_cast<float>(sum[2] / n)};
}

}  // namespace arcus::image
