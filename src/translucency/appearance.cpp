#include "translucency/appearance.h"

#include <algorithm>
#include <cmath>

#include "bvh/bvh.h"
#include "core/error.h"
#include "translucency/dipole.h"
#include "translucency/fit.h"
#include "translucency/histograms.h"
#include "translucency/render.h"

namespace arcus::translucency {
namespace {

// Lagrange weights of the nodes at η (degree kEtaNodes − 1).
void lagrange(const double nodes[kEtaNodes], double eta, double out[kEtaNodes]) {
  for (uint32_t j = 0; j < kEtaNodes; ++j) {
    out[j] = 1;
    for (uint32_t k = 0; k < kEtaNodes; ++k)
      if (k != j) out[j] *= (eta - nodes[k]) / (nodes[j] - nodes[k]);
  }
}

// Phong's lobe k_s (n + 2)/(2π) cos^n α cos θ_i E per channel, k_s(cos θ_i) given (the
// renderer's highlight takes the Fresnel reflectance F_r(η, θ_i)).
template <typename Specular>
void add_highlight(const AppearanceCache& c, size_t p, double b_deg, Specular specular, double* rgb) {
  if (b_deg <= 0) return;
  const double n = phong_exponent(b_deg);
  for (size_t l = 0; l < c.lights.size(); ++l) {
    const double cos_i = c.light_cos[p * c.lights.size() + l];
    if (cos_i <= 0) continue;
    const double k_s = specular(cos_i);
    const double lobe = k_s * (n + 2) / (2 * M_PI) * std::pow(c.mirror_cos[p * c.lights.size() + l], n) * cos_i;
    for (int ch = 0; ch < 3; ++ch) rgb[ch] += lobe * c.lights[l].irradiance[ch];
  }
}

}  // namespace

AppearanceCache appearance_cache(arcus_context_t* ctx, arcus_job_s& job, const geometry::Mesh& mesh,
                                 const arcus_camera& camera_units, double ortho_height, double mm_per_unit,
                                 const std::vector<Light>& lights, double eta_low, double eta_high,
                                 arcus_progress_callback progress, void* progress_user, bool* cancelled) {
  AppearanceCache c;
  c.width = camera_units.width;
  c.height = camera_units.height;
  c.lights = lights;
  for (uint32_t j = 0; j < kEtaNodes; ++j)  // Chebyshev nodes: no Runge wiggle at the ends
    c.eta_nodes[j] = 0.5 * (eta_low + eta_high) +
                     0.5 * (eta_high - eta_low) * std::cos(M_PI * (2 * j + 1) / (2 * kEtaNodes));
  const Surface surface = make_surface(mesh, mm_per_unit);
  const bvh::DeviceBvh bvh(ctx, bvh::build_triangles(surface.mesh), false);
  const scene::CameraDesc camera = camera_in_mm(camera_units, mm_per_unit);
  const double ortho = ortho_height * mm_per_unit;
  const Views views = camera_hits(ctx, bvh, surface, camera, ortho);

  std::vector<double> points;
  std::vector<uint32_t> triangles;
  for (size_t px = 0; px < size_t(c.width) * c.height; ++px)
    if (views.triangle[px] >= 0) {
      c.pixels.push_back(px);
      triangles.push_back(static_cast<uint32_t>(views.triangle[px]));
      points.insert(points.end(), &views.points[3 * px], &views.points[3 * px] + 3);
    }
  require(!c.pixels.empty(), "mesh: the camera sees no part of it (params->camera)");
  const size_t n = c.pixels.size(), nl = lights.size();
  const std::vector<uint8_t> lit = visibility(ctx, bvh, surface, points, triangles, lights);
  c.cos_out.resize(n);
  c.light_cos.assign(n * nl, 0.0);
  c.mirror_cos.assign(n * nl, 0.0);
  c.own.assign(n * kEtaNodes * 3, 0.0);
  for (size_t p = 0; p < n; ++p) {
    const size_t px = c.pixels[p];
    const Vec3 normal = vec3(&views.normals[3 * px]), eye = vec3(&views.toward_eye[3 * px]);
    c.cos_out[p] = std::fabs(dot(normal, eye));
    for (size_t l = 0; l < nl; ++l) {
      const double cos_i = std::max(0.0, dot(normal, lights[l].toward));
      if (!lit[p * nl + l] || cos_i <= 0) continue;
      c.light_cos[p * nl + l] = cos_i;
      c.mirror_cos[p * nl + l] = std::max(0.0, dot((2 * cos_i) * normal - lights[l].toward, eye));
      for (uint32_t j = 0; j < kEtaNodes; ++j) {
        const double through = cos_i * (1 - fresnel_reflectance(cos_i, 1.0, c.eta_nodes[j]));
        for (int ch = 0; ch < 3; ++ch) c.own[(p * kEtaNodes + j) * 3 + size_t(ch)] += through * lights[l].irradiance[ch];
      }
    }
  }

  // Samples half a pixel apart at the object (the view's height over its rows; a
  // pinhole's at the distance to what it looks at), fewer if they would not fit.
  const double pixel = ortho > 0 ? ortho / c.height
                                 : 2 * std::tan(camera.vfov_deg * M_PI / 360) *
                                       length(camera.look_at - camera.position) / c.height;
  c.spacing = 0.5 * pixel;
  for (uint64_t count; (count = sample_count(surface, c.spacing)) > kMaxSamples;)
    c.spacing *= 1.05 * std::sqrt(double(count) / double(kMaxSamples));
  const Samples samples = make_samples(surface, c.spacing);
  c.samples = samples.size();
  std::vector<double> weights(samples.size() * kEtaNodes * 3);
  for (uint32_t j = 0; j < kEtaNodes; ++j) {
    const std::vector<double> e = sample_irradiance(ctx, bvh, surface, samples, lights, c.eta_nodes[j]);
    for (size_t s = 0; s < samples.size(); ++s)
      for (int ch = 0; ch < 3; ++ch) weights[(s * kEtaNodes + j) * 3 + size_t(ch)] = e[3 * s + size_t(ch)] * samples.areas[s];
  }

  // Bins uniform in √r up to the bounding diagonal (no two points are farther apart);
  // the near field ρ: two spacings, in whole bins.
  c.edges.resize(kCacheBins + 1);
  for (uint32_t k = 0; k <= kCacheBins; ++k) c.edges[k] = surface.diagonal * std::pow(double(k) / kCacheBins, 2);
  c.near_bins = 1;
  while (c.near_bins < kCacheBins && c.edges[c.near_bins] < 2 * c.spacing) ++c.near_bins;
  c.near_radius = c.edges[c.near_bins];
  HistogramRequest request;
  request.rows = &points;
  request.sources = &samples.positions;
  request.weights = &weights;
  request.weights_per_source = kEtaNodes * 3;
  request.bins = kCacheBins;
  request.reach = surface.diagonal;
  request.sqrt_bins = true;
  request.progress = progress;
  request.progress_user = progress_user;
  const std::vector<double> h = distance_histograms(ctx, job, request, cancelled);
  c.bins.assign(h.begin(), h.end());
  return c;
}

std::vector<double> dipole_image(const AppearanceCache& c, const arcus_dipole& d, double highlight_deg) {
  double lambda[kEtaNodes];
  lagrange(c.eta_nodes, d.eta, lambda);
  // v[k][j][c] = λ_j R_d,c(bin k): the vector each pixel's cache row is multiplied by.
  const size_t row = size_t(kCacheBins) * kEtaNodes * 3;
  std::vector<float> v(row, 0.0f);
  double disc[3];
  for (int ch = 0; ch < 3; ++ch) {
    const Terms t = terms(Channel{d.sigma_a[ch], d.sigma_s_prime[ch], d.eta});
    disc[ch] = reflectance_within(t, c.near_radius);
    for (uint32_t k = c.near_bins; k < kCacheBins; ++k) {
      const double rd = bin_average(t, c.edges[k], c.edges[k + 1]);
      for (uint32_t j = 0; j < kEtaNodes; ++j) v[(size_t(k) * kEtaNodes + j) * 3 + size_t(ch)] = float(lambda[j] * rd);
    }
  }
  const size_t n = c.pixels.size();
  std::vector<double> image(3 * n, 0.0);
  for (size_t p = 0; p < n; ++p) {
    const float* cache = &c.bins[p * row];
    double sum[3] = {0, 0, 0};
    for (size_t k = size_t(c.near_bins) * kEtaNodes * 3; k < row; k += 3) {
      sum[0] += double(cache[k] * v[k]);
      sum[1] += double(cache[k + 1] * v[k + 1]);
      sum[2] += double(cache[k + 2] * v[k + 2]);
    }
    const double exit = (1 - fresnel_reflectance(c.cos_out[p], 1.0, d.eta)) / M_PI;
    for (int ch = 0; ch < 3; ++ch) {
      double own = 0;
      for (uint32_t j = 0; j < kEtaNodes; ++j) own += lambda[j] * c.own[(p * kEtaNodes + j) * 3 + size_t(ch)];
      image[3 * p + size_t(ch)] = exit * (sum[ch] + own * disc[ch]);
    }
    add_highlight(c, p, highlight_deg, [&](double cos_i) { return fresnel_reflectance(cos_i, 1.0, d.eta); },
                  &image[3 * p]);
  }
  return image;
}

std::vector<double> phong_image(const AppearanceCache& c, const double k_d[3], double k_s, double b_deg) {
  const size_t n = c.pixels.size(), nl = c.lights.size();
  std::vector<double> image(3 * n, 0.0);
  for (size_t p = 0; p < n; ++p) {
    for (size_t l = 0; l < nl; ++l)
      for (int ch = 0; ch < 3; ++ch)
        image[3 * p + size_t(ch)] += k_d[ch] / M_PI * c.light_cos[p * nl + l] * c.lights[l].irradiance[ch];
    add_highlight(c, p, b_deg, [k_s](double) { return k_s; }, &image[3 * p]);
  }
  return image;
}

}  // namespace arcus::translucency
