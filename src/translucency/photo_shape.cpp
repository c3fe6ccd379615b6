#include "translucency/photo_shape.h"

#include <algorithm>
#include <cmath>
#include <string>

#include <opencv2/core.hpp>
#include <opencv2/imgproc.hpp>

#include "core/error.h"
#include "core/format.h"

namespace arcus::translucency {
namespace {

void require_in(double value, double lo, double hi, const char* name) {
  require(std::isfinite(value) && value >= lo && value <= hi,
          std::string("params->") + name + " = " + number(value) + " is not " + number(lo) + ".." + number(hi));
}

// The luminance over the object's 99th percentile, clamped to 0..1; 0 outside.
std::vector<float> normalized_luminance(const PhotoObject& o) {
  std::vector<double> inside;
  for (size_t i = 0; i < o.mask.size(); ++i)
    if (o.mask[i]) inside.push_back(o.luminance[i]);
  std::nth_element(inside.begin(), inside.begin() + long(inside.size() * 99 / 100), inside.end());
  const double top = inside[inside.size() * 99 / 100];
  std::vector<float> out(o.mask.size(), 0.0f);
  for (size_t i = 0; i < o.mask.size(); ++i)
    if (o.mask[i] && top > 0) out[i] = float(std::clamp(o.luminance[i] / top, 0.0, 1.0));
  return out;
}

}  // namespace

void check_shape_params(const arcus_photo_shape_params& p) {
  require(p.method >= ARCUS_DEPTH_BASE_DETAIL && p.method <= ARCUS_DEPTH_LUMINANCE,
          "params->method = " + std::to_string(p.method) + " is not an arcus_depth_method (0..2)");
  require_in(p.sigma_spatial, 0.005, 1, "sigma_spatial");
  require_in(p.sigma_intensity, 0.01, 10, "sigma_intensity");
  require_in(p.base_weight, 1e-3, 1e3, "base_weight");
  require_in(p.detail_weight, 0, 1e3, "detail_weight");
  require_in(p.inflation, 0, 1, "inflation");
  require_in(p.relief, 1e-3, 1e3, "relief");
}

PhotoShape estimate_shape(const PhotoObject& o, const arcus_photo_shape_params& p) {
  check_shape_params(p);
  const int w = int(o.width), h = int(o.height);
  std::vector<float> luminance = normalized_luminance(o);
  cv::Mat lum(h, w, CV_32F, luminance.data());
  const std::vector<double> convex = convex_depth(o);
  const double radius = *std::max_element(convex.begin(), convex.end());
  // The bilateral filter (Tomasi & Manduchi 1998) keeps the luminance's edges and drops
  // its texture: its spatial σ a fraction of the object's diameter (that of a disc of its
  // area), its range σ in the normalized luminance.
  const double diameter = 2 * std::sqrt(double(o.pixels) / M_PI);
  cv::Mat base_luminance;
  cv::bilateralFilter(lum, base_luminance, -1, p.sigma_intensity, std::max(0.5, p.sigma_spatial * diameter));

  PhotoShape shape;
  shape.depth.assign(o.mask.size(), 0.0);
  double sum = 0;
  for (size_t i = 0; i < o.mask.size(); ++i) {
    if (!o.mask[i]) continue;
    const double b = base_luminance.at<float>(int(i));
    const double inflate = 1 - p.inflation + p.inflation * b * b * (3 - 2 * b);  // monotone cubic Hermite
    const double base = convex[i] * inflate, detail = (luminance[i] - b) * radius;
    double z = base;
    if (p.method == ARCUS_DEPTH_BASE_DETAIL) z = base + p.detail_weight / p.base_weight * detail;
    if (p.method == ARCUS_DEPTH_LUMINANCE) z = radius * luminance[i];
    shape.depth[i] = p.relief * z;
    sum += shape.depth[i];
  }
  // The bas-relief ambiguity also leaves Z's sign: the object bulges toward the camera.
  if (sum < 0)
    for (double& z : shape.depth) z = -z;

  shape.normals = depth_normals(o, shape.depth);
  return shape;
}

}  // namespace arcus::translucency
