#include "translucency/estimate.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <string>
#include <tuple>
#include <utility>

#include "bvh/bvh.h"
#include "bvh/device_bvh.h"
#include "core/error.h"
#include "core/format.h"
#include "translucency/basis.h"
#include "translucency/dipole.h"
#include "translucency/fit.h"
#include "translucency/histograms.h"
#include "translucency/least_squares.h"
#include "translucency/surface.h"

// Fresnel and the histogram's arguments: scalar host code after common/real.h.
#include "common/real.h"
#include "common/fresnel.h"
#include "translucency/translucency_desc.h"

namespace arcus::translucency {
namespace {

// |c·n| below this is taken as this: ΔA = pixel area / |c·n| diverges at the
// silhouette, where a pixel holds a sliver of surface turning away (thesis eq. 3.12).
constexpr double kMinCosine = 0.05;

// The near field, in pixels at the object (estimate() says why): within kNearPixels a
// disc lit by the row's own irradiance; out to kRefinedPixels the front sources summed
// over kSubPixels² points a pixel; beyond, one point a pixel.
constexpr double kNearPixels = 4, kRefinedPixels = 12;
constexpr uint32_t kSubPixels = 3;

double seconds_since(std::chrono::steady_clock::time_point start) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

double luminance(const double rgb[3]) { return 0.2126 * rgb[0] + 0.7152 * rgb[1] + 0.0722 * rgb[2]; }

void check_params(const arcus_translucency_estimate_params& p, uint32_t width, uint32_t height) {
  check_view(p.camera, p.ortho_height, p.mm_per_unit, p.exit);
  check_eta(p.eta, "params->eta");
  require(p.basis_count >= 2 && p.basis_count <= 64,
          "params->basis_count = " + std::to_string(p.basis_count) + " is not 2..64");
  require(p.basis >= ARCUS_BASIS_PIECEWISE_CONSTANT && p.basis <= ARCUS_BASIS_LEGENDRE,
          "params->basis = " + std::to_string(p.basis) + " is not an arcus_profile_basis (0..4)");
  require(std::isfinite(p.tikhonov) && p.tikhonov >= 0,
          "params->tikhonov = " + number(p.tikhonov) + " is not a finite λ >= 0 (0: off)");
  require(p.nonnegative == 0 || p.nonnegative == 1,
          "params->nonnegative = " + std::to_string(p.nonnegative) + " is not 0 or 1");
  require(std::isfinite(p.r_max_mm) && p.r_max_mm >= 0,
          "params->r_max_mm = " + number(p.r_max_mm) + " is not a finite distance >= 0 (0: the object's diagonal)");
  require(p.max_side >= 8 && p.max_side <= 4096, "params->max_side = " + std::to_string(p.max_side) + " is not 8..4096");
  require(p.remove_highlights == 0 || p.remove_highlights == 1,
          "params->remove_highlights = " + std::to_string(p.remove_highlights) + " is not 0 or 1");
  require(p.subtract_minimum == 0 || p.subtract_minimum == 1,
          "params->subtract_minimum = " + std::to_string(p.subtract_minimum) + " is not 0 or 1");
  require(p.fit == ARCUS_FIT_IMAGE || p.fit == ARCUS_FIT_PROFILE,
          "params->fit = " + std::to_string(p.fit) + " is not ARCUS_FIT_IMAGE (0) or ARCUS_FIT_PROFILE (1)");
  require(width >= 1 && width <= scene::kMaxSide && height >= 1 && height <= scene::kMaxSide,
          "width × height = " + std::to_string(width) + " × " + std::to_string(height) + " is not 1..16384 a side");
  require(width == p.camera.width && height == p.camera.height,
          "the photo's " + std::to_string(width) + " × " + std::to_string(height) + " is not params->camera's " +
              std::to_string(p.camera.width) + " × " + std::to_string(p.camera.height));
}

// The object's diameter, the largest distance between two of its points, by the double
// sweep: the vertex farthest from the centroid, then the vertex farthest from that one
// (exact for spheres and boxes; never more than the true diameter).
double diameter(const Surface& s) {
  const size_t n = s.mesh.vertex_count();
  Vec3 centre{};
  for (size_t v = 0; v < n; ++v) centre = centre + vec3(&s.mesh.positions[3 * v]);
  centre = (1.0 / double(n)) * centre;
  auto farthest = [&](Vec3 from) {
    Vec3 best = from;
    for (size_t v = 0; v < n; ++v)
      if (length(vec3(&s.mesh.positions[3 * v]) - from) > length(best - from)) best = vec3(&s.mesh.positions[3 * v]);
    return best;
  };
  const Vec3 a = farthest(centre);
  return length(farthest(a) - a);
}

// Whether a coarse pixel belongs to 𝕆: the mesh is seen there, and the matte (if any)
// covers at least half of it.
bool in_object_of(const Views& front, const std::vector<double>& matte_share, const uint8_t* matte, size_t px) {
  return front.triangle[px] >= 0 && (!matte || matte_share[px] >= 0.5);
}

// The profile Σ_h x_h B_h (constant on each of `bins` fine bins) averaged over the area
// of each of m equal bins: the rings' overlaps, in closed form.
std::vector<double> bin_averages(const std::vector<double>& basis, uint32_t m, uint32_t bins,
                                 const std::vector<double>& x) {
  std::vector<double> sum(m, 0.0);
  for (uint32_t k = 0; k < bins; ++k) {
    double value = 0;
    for (uint32_t h = 0; h < m; ++h) value += basis[size_t(k) * m + h] * x[h];
    const double lo = double(k) / bins, hi = double(k + 1) / bins;
    for (uint32_t j = uint32_t(lo * m); j < m && double(j) / m < hi; ++j) {
      const double from = std::max(lo, double(j) / m), to = std::min(hi, double(j + 1) / m);
      if (to > from) sum[j] += value * (to * to - from * from);
    }
  }
  for (uint32_t j = 0; j < m; ++j) {
    const double lo = double(j) / m, hi = double(j + 1) / m;
    sum[j] /= hi * hi - lo * lo;
  }
  return sum;
}

// Surface points standing for pixels (eq. 3.12): where, on which triangle, facing
// where, and how much surface ΔA each stands for (mm²).
struct SourcePoints {
  std::vector<double> points;  // 3 each, mm
  std::vector<uint32_t> triangles;
  std::vector<Vec3> normals;
  std::vector<double> area;
  void add(Vec3 at, int32_t triangle, Vec3 n, double a) {
    points.insert(points.end(), {at.x, at.y, at.z});
    triangles.push_back(static_cast<uint32_t>(triangle));
    normals.push_back(n);
    area.push_back(a);
  }
};

// The surface a pixel sees at `at` along `eye` (toward the camera): its footprint on a
// plane square to the ray over |c·n|, with |c·n| taken as at least kMinCosine.  The
// footprint: orthographic, the pixel's side squared; pinhole, its solid angle (cos³ off
// the axis) times the distance squared.
double pixel_area(const scene::Frame& frame, double ortho, double pixel_side, double pixel_angle, Vec3 at, Vec3 eye,
                  Vec3 n) {
  double footprint = pixel_side * pixel_side;
  if (ortho == 0) {
    const double cos_axis = -dot(eye, frame.forward), dist = length(at - frame.origin);
    footprint = pixel_angle * pixel_angle * cos_axis * cos_axis * cos_axis * dist * dist;
  }
  return footprint / std::max(kMinCosine, std::fabs(dot(eye, n)));
}

// E·ΔA per source and channel (eq. 3.8, 3.12): Σ over the lights it sees of
// F_t(η, θ_l) E_l cos θ_l, times its area.
std::vector<double> lit_weights(arcus_context_t* ctx, const bvh::DeviceBvh& bvh, const Surface& surface,
                                const SourcePoints& s, const std::vector<Light>& lights, double eta) {
  const std::vector<uint8_t> visible = visibility(ctx, bvh, surface, s.points, s.triangles, lights);
  std::vector<double> weights(3 * s.area.size(), 0.0);
  for (size_t k = 0; k < s.area.size(); ++k)
    for (size_t l = 0; l < lights.size(); ++l) {
      if (!visible[k * lights.size() + l]) continue;
      const double cos_i = std::max(0.0, dot(s.normals[k], lights[l].toward));
      const double through = cos_i * (1 - arcus_fresnel_reflectance(cos_i, 1.0, eta)) * s.area[k];
      for (int c = 0; c < 3; ++c) weights[3 * k + c] += through * lights[l].irradiance[c];
    }
  return weights;
}

// What refine_near_rings reads.
struct NearRings {
  arcus_camera coarse_camera;  // the photo's camera at the coarse pixels
  double mm_per_unit = 1, ortho = 0;
  const std::vector<uint8_t>* in_object = nullptr;
  const Views* front = nullptr;
  const std::vector<size_t>* front_source = nullptr;  // per coarse pixel of 𝕆: its front source
  const std::vector<double>* weights = nullptr;       // the sources' E·ΔA, 3 each
  const std::vector<size_t>* equations = nullptr;     // the rows' pixels
  const std::vector<double>* rows = nullptr;          // the rows' points
  uint32_t bins = 0, first_bin = 0, end_bin = 0;      // the bins refined: [first_bin, end_bin)
  double reach = 0;                                   // the last bin's far edge, mm
  const std::vector<Light>* lights = nullptr;
  double eta = 1.3;
};

// In each row's bins [first_bin, end_bin), the front sources' sums over one point a
// pixel replaced by sums over kSubPixels² points a pixel (estimate() says why); returns
// the sub-pixel points and their E·ΔA.  A projection brings no two points closer, so
// the front points within end_bin's distance of a row lie within as many pixels of it
// on the image (for a pinhole, pixels at the object's nearest depth).
std::pair<std::vector<double>, std::vector<double>> refine_near_rings(arcus_context_t* ctx, const bvh::DeviceBvh& bvh,
                                                                      const Surface& surface, const NearRings& q,
                                                                      std::vector<double>* hist) {
  const uint32_t s = kSubPixels, w = q.coarse_camera.width, h = q.coarse_camera.height;
  arcus_camera fine_camera = q.coarse_camera;
  fine_camera.width = w * s;
  fine_camera.height = h * s;
  const scene::CameraDesc camera = camera_in_mm(fine_camera, q.mm_per_unit);
  const Views fine = camera_hits(ctx, bvh, surface, camera, q.ortho);
  const scene::Frame frame = scene::camera_frame(camera);
  const double pixel_angle = 2 * frame.tan_half / (h * s), pixel_side = q.ortho / (h * s);
  SourcePoints sub;
  std::vector<size_t> first(size_t(w) * h + 1, 0);
  double nearest = INFINITY;  // the nearest object point's distance from a pinhole
  for (size_t px = 0; px < size_t(w) * h; ++px) {
    first[px] = sub.area.size();
    if (!(*q.in_object)[px]) continue;
    nearest = std::min(nearest, length(vec3(&q.front->points[3 * px]) - frame.origin));
    const size_t x = px % w, y = px / w;
    for (uint32_t sy = 0; sy < s; ++sy)
      for (uint32_t sx = 0; sx < s; ++sx) {
        const size_t f = (y * s + sy) * size_t(w) * s + x * s + sx;
        if (fine.triangle[f] < 0) continue;
        const Vec3 at = vec3(&fine.points[3 * f]), n = vec3(&fine.normals[3 * f]);
        sub.add(at, fine.triangle[f], n,
                pixel_area(frame, q.ortho, pixel_side, pixel_angle, at, vec3(&fine.toward_eye[3 * f]), n));
      }
  }
  first.back() = sub.area.size();
  const std::vector<double> sub_weights = lit_weights(ctx, bvh, surface, sub, *q.lights, q.eta);
  const double coarse_pixel = q.ortho > 0 ? q.ortho / h : 2 * frame.tan_half / h * nearest;
  const double inverse = 1 / q.reach;
  const long window = long(std::ceil(q.end_bin * (q.reach / q.bins) / coarse_pixel)) + 1;
  // The bin of a distance as the histogram kernel computes it.
  auto bin_of = [&](Vec3 a, const double* b) {
    const double dx = a.x - b[0], dy = a.y - b[1], dz = a.z - b[2];
    const double r = std::sqrt(dx * dx + dy * dy + dz * dz) * inverse;
    return uint32_t(std::min(r * q.bins, double(q.bins)));
  };
  for (size_t i = 0; i < q.equations->size(); ++i) {
    const Vec3 row = vec3(&(*q.rows)[3 * i]);
    const long x = long((*q.equations)[i] % w), y = long((*q.equations)[i] / w);
    double* out = &(*hist)[i * q.bins * 3];
    for (long yy = std::max(0L, y - window); yy <= std::min(long(h) - 1, y + window); ++yy)
      for (long xx = std::max(0L, x - window); xx <= std::min(long(w) - 1, x + window); ++xx) {
        const size_t px = size_t(yy) * w + size_t(xx);
        if (!(*q.in_object)[px]) continue;
        const size_t own = (*q.front_source)[px];
        const uint32_t k = bin_of(row, &q.front->points[3 * px]);
        if (k >= q.first_bin && k < q.end_bin)
          for (int c = 0; c < 3; ++c) out[k * 3 + c] -= (*q.weights)[3 * own + c];
        for (size_t j = first[px]; j < first[px + 1]; ++j) {
          const uint32_t kj = bin_of(row, &sub.points[3 * j]);
          if (kj >= q.first_bin && kj < q.end_bin)
            for (int c = 0; c < 3; ++c) out[kj * 3 + c] += sub_weights[3 * j + c];
        }
      }
  }
  return {sub.points, sub_weights};
}

}  // namespace

double highlight_cut(const std::vector<double>& lum) {
  if (lum.empty()) return INFINITY;
  const double top = *std::max_element(lum.begin(), lum.end());
  if (!(top > 0)) return INFINITY;
  constexpr int kBins = 256, kSpan = 9;
  std::vector<double> h(kBins, 0.0), sum(kBins, 0.0);
  for (double y : lum) h[size_t(std::min(kBins - 1, int(y / top * kBins)))] += 1;
  // Counts over 9 neighbouring bins: still counts, so their noise is about their root.
  for (int k = 0; k < kBins; ++k)
    for (int d = -kSpan / 2; d <= kSpan / 2; ++d)
      if (k + d >= 0 && k + d < kBins) sum[size_t(k)] += h[size_t(k + d)];
  const int peak = int(std::max_element(sum.begin(), sum.end()) - sum.begin());
  int steepest = peak;
  for (int k = peak; k + 1 < kBins; ++k)
    if (sum[size_t(k + 1)] - sum[size_t(k)] < sum[size_t(steepest + 1)] - sum[size_t(steepest)]) steepest = k;
  // From the steepest fall on, the lowest count so far is the valley's floor; a bump is
  // a count above it by more than counting noise allows (8 standard deviations: the
  // floor is itself the lowest of many noisy counts), and the cut is where the floor
  // was reached.
  double floor = sum[size_t(steepest)];
  int floor_at = steepest;
  for (int k = steepest + 1; k < kBins; ++k) {
    if (sum[size_t(k)] < floor) {
      floor = sum[size_t(k)];
      floor_at = k;
    }
    if (sum[size_t(k)] > floor + 8 * std::sqrt(floor + 1) + 1) return top * (floor_at + 1) / kBins;
  }
  return INFINITY;  // it falls to its end: no highlight
}

std::unique_ptr<EstimateJob> estimate(arcus_context_t* ctx, const geometry::Mesh& mesh, uint32_t width,
                                      uint32_t height, const float* photo, const uint8_t* matte,
                                      const std::vector<arcus_directional_light>& lights,
                                      const arcus_translucency_estimate_params& p, bool* cancelled) {
  const auto start = std::chrono::steady_clock::now();
  check_params(p, width, height);
  const std::vector<Light> light_list = lights_of(lights);
  const size_t full = size_t(width) * height;
  check_radiance(photo, width, height, "photo");
  *cancelled = false;
  auto job = std::make_unique<EstimateJob>(ctx);
  arcus_translucency_estimate_result& res = job->result;

  // Downscale by a whole factor f (box filter): the thesis' ~200 × 200.
  const uint32_t f = std::max(1u, (std::max(width, height) + p.max_side - 1) / p.max_side);
  const uint32_t w = std::max(1u, width / f), h = std::max(1u, height / f);
  const size_t pixels = size_t(w) * h;
  std::vector<double> rgb(3 * pixels, 0.0), matte_share(pixels, 0.0);
  for (uint32_t y = 0; y < h * f; ++y)
    for (uint32_t x = 0; x < w * f; ++x) {
      const size_t coarse = size_t(y / f) * w + x / f, fine = size_t(y) * width + x;
      for (int c = 0; c < 3; ++c) rgb[3 * coarse + c] += photo[3 * fine + c] / double(f * f);
      if (matte) matte_share[coarse] += (matte[fine] != 0) / double(f * f);
    }

  // Geometry at the coarse pixels: front and back points, normals, irradiance.
  arcus_camera coarse_camera = p.camera;
  coarse_camera.width = w;
  coarse_camera.height = h;
  const scene::CameraDesc camera = camera_in_mm(coarse_camera, p.mm_per_unit);
  const Surface surface = make_surface(mesh, p.mm_per_unit);
  const size_t open = open_edges(surface);
  require(open == 0, "mesh: " + std::to_string(open) + " edges are not shared by exactly two triangles: the estimate "
                     "needs a closed surface (every view ray's back point)");
  const bvh::DeviceBvh bvh(ctx, bvh::build_triangles(surface.mesh), false);
  const double ortho = p.ortho_height * p.mm_per_unit;
  const Views front = camera_hits(ctx, bvh, surface, camera, ortho);
  const Views back = back_hits(ctx, bvh, surface, front);
  std::vector<size_t> object;  // 𝕆: the coarse pixels of the object
  std::vector<uint8_t> in_object(pixels, 0);
  for (size_t px = 0; px < pixels; ++px)
    if (back.triangle[px] >= 0 && in_object_of(front, matte_share, matte, px)) {
      object.push_back(px);
      in_object[px] = 1;
    }
  require(!object.empty(), matte ? "matte: it covers no pixel where the mesh is seen (is the camera right?)"
                                 : "mesh: the camera sees no part of it (params->camera)");
  if (matte) {
    // The matte against the mesh's projection: a misplaced camera or mesh shows here.
    size_t both = 0, either = 0;
    for (size_t px = 0; px < pixels; ++px) {
      const bool seen = front.triangle[px] >= 0, marked = matte_share[px] >= 0.5;
      both += seen && marked;
      either += seen || marked;
    }
    const double iou = either ? double(both) / double(either) : 0;
    require(iou >= 0.9, "matte: it overlaps the mesh's projection by IoU " + number(iou) +
                            " < 0.9: the mesh, the camera and the photo do not line up");
  }
  {
    // A clipped exposure: many of the object's pixels at one maximum value.
    float top[3] = {0, 0, 0};
    for (size_t i = 0; i < full; ++i)
      for (int c = 0; c < 3; ++c) top[c] = std::max(top[c], photo[3 * i + c]);
    size_t at_top = 0, inside = 0;
    for (uint32_t y = 0; y < h * f; ++y)
      for (uint32_t x = 0; x < w * f; ++x) {
        if (!in_object_of(front, matte_share, matte, size_t(y / f) * w + x / f)) continue;
        ++inside;
        const float* px = &photo[3 * (size_t(y) * width + x)];
        at_top += (top[0] > 0 && px[0] == top[0]) || (top[1] > 0 && px[1] == top[1]) || (top[2] > 0 && px[2] == top[2]);
      }
    require(at_top <= inside / 100, "photo: " + std::to_string(at_top) + " of the object's " + std::to_string(inside) +
                                        " pixels sit at the largest value (clipped?): give an HDR exposure that "
                                        "keeps them below it");
  }

  // Sources: every object pixel's front and back point, weighted by E·ΔA (eq. 3.12).
  const scene::Frame frame = scene::camera_frame(camera);
  const double pixel_angle = 2 * frame.tan_half / h, pixel_side = ortho / h;
  SourcePoints sources;
  for (const Views* side : {&front, &back})
    for (size_t px : object) {
      const Vec3 at = vec3(&side->points[3 * px]), n = vec3(&side->normals[3 * px]);
      sources.add(at, side->triangle[px], n,
                  pixel_area(frame, ortho, pixel_side, pixel_angle, at, vec3(&front.toward_eye[3 * px]), n));
    }
  const std::vector<double>& source_points = sources.points;
  const std::vector<double>& source_area = sources.area;
  const std::vector<double> weights = lit_weights(ctx, bvh, surface, sources, light_list, p.eta);
  double total_light = 0;
  for (double x : weights) total_light += x;
  require(total_light > 0, "lights: no light reaches the object's seen or back surface (is the light behind it?)");

  // Equations 𝕀: object pixels off the matte's rim, below the highlights' cut.
  std::vector<double> lum;
  size_t darkest = object[0];
  for (size_t px : object) {
    lum.push_back(luminance(&rgb[3 * px]));
    if (lum.back() < luminance(&rgb[3 * darkest])) darkest = px;
  }
  res.highlight_cut = p.remove_highlights ? highlight_cut(lum) : INFINITY;
  for (int c = 0; c < 3; ++c) res.minimum_subtracted[c] = p.subtract_minimum ? rgb[3 * darkest + c] : 0;
  std::vector<size_t> equations;
  for (size_t px : object) {
    const size_t x = px % w, y = px / w;
    const bool rim = x == 0 || y == 0 || x + 1 == w || y + 1 == h || !in_object[px - 1] || !in_object[px + 1] ||
                     !in_object[px - w] || !in_object[px + w];
    if (!rim && luminance(&rgb[3 * px]) <= res.highlight_cut) equations.push_back(px);
  }
  require(!equations.empty(), "photo: no object pixel is left for the equations once the matte's rim and the "
                              "highlights are dropped (the object covers too few pixels)");
  std::vector<double> rows;
  for (size_t px : equations) rows.insert(rows.end(), &front.points[3 * px], &front.points[3 * px] + 3);
  res.geometry_seconds = seconds_since(start);

  // The histograms, then per channel A (bins summed into basis functions) and b.
  const auto histogram_start = std::chrono::steady_clock::now();
  const uint32_t m = p.basis_count, bins = fine_bins_for(p.basis, m);
  res.r_max_mm = p.r_max_mm > 0 ? p.r_max_mm : diameter(surface);
  HistogramRequest request;
  request.rows = &rows;
  request.sources = &source_points;
  request.weights = &weights;
  request.bins = bins;
  request.reach = res.r_max_mm;
  request.progress = p.progress;
  request.progress_user = p.progress_user;
  std::vector<double> hist = distance_histograms(ctx, *job, request, cancelled);

  // The near field.  One point a pixel is too coarse a sum of R_d where R_d falls by
  // most of itself across a pixel: within a few pixels of the row, and on a 40 mm sphere
  // at 200² it cost ℓ_d −85 to −98% in three channels whose ℓ_d is 2–5 mm.  So:
  //  - within ρ (kNearPixels) the fine bins are left out and replaced by the row's own
  //    irradiance over a flat disc, E_i ∫₀^ρ 2πr R_d dr (fit.h; closed form for the
  //    dipole): exact where E is even, and its error grows as ρ² where E curves;
  //  - from ρ out to kRefinedPixels the front sources are summed over sub-pixels
  //    (refine_near_rings).
  // A smaller ρ needs finer sub-pixels, a larger one errs where E curves; docs/
  // translucency.md tabulates the choice on the sphere and the torus.
  const double fine_width = res.r_max_mm / bins;
  const double pixel_mm = ortho > 0 ? pixel_side : pixel_angle * length(camera.look_at - camera.position);
  const uint32_t near_bins =
      std::min(bins - 1, std::max(1u, uint32_t(std::ceil(kNearPixels * pixel_mm / fine_width))));
  const double near_radius = near_bins * fine_width;
  std::vector<size_t> front_source(pixels, 0);
  for (size_t k = 0; k < object.size(); ++k) front_source[object[k]] = k;
  {
    NearRings q;
    q.coarse_camera = coarse_camera;
    q.mm_per_unit = p.mm_per_unit;
    q.ortho = ortho;
    q.in_object = &in_object;
    q.front = &front;
    q.front_source = &front_source;
    q.weights = &weights;
    q.equations = &equations;
    q.rows = &rows;
    q.bins = bins;
    q.first_bin = near_bins;
    q.end_bin = std::max(near_bins, std::min(bins, uint32_t(std::ceil(kRefinedPixels * pixel_mm / fine_width))));
    q.reach = res.r_max_mm;
    q.lights = &light_list;
    q.eta = p.eta;
    std::tie(job->sub_sources, job->sub_source_weights) = refine_near_rings(ctx, bvh, surface, q, &hist);
    res.refined_radius_mm = q.end_bin * fine_width;
    res.sub_source_count = static_cast<uint32_t>(job->sub_source_weights.size() / 3);
  }
  res.histogram_seconds = seconds_since(histogram_start);

  const auto solve_start = std::chrono::steady_clock::now();
  const double exit_scale = (1 / M_PI) / (p.exit == ARCUS_EXIT_NORMALIZED ? exit_transmittance(p.eta) : 1.0);
  const size_t n = equations.size();
  std::vector<double> fine_edges(bins + 1);
  for (uint32_t k = 0; k <= bins; ++k) fine_edges[k] = res.r_max_mm * k / bins;
  job->edges.resize(m + 1);
  for (uint32_t k = 0; k <= m; ++k) job->edges[k] = res.r_max_mm * k / m;
  // A column of A is the fine bins weighted by B_h at their middles (basis.h); within ρ
  // the disc's rings, weighted the same way.
  const std::vector<double> basis = basis_matrix(p.basis, m, bins);
  std::vector<double> near_disc(m, 0.0);
  for (uint32_t k = 0; k < near_bins; ++k)
    for (uint32_t h = 0; h < m; ++h)
      near_disc[h] += M_PI * (fine_edges[k + 1] * fine_edges[k + 1] - fine_edges[k] * fine_edges[k]) *
                      basis[size_t(k) * m + h];
  job->rows = rows;
  job->sources = source_points;
  job->source_weights = weights;
  job->near.assign(n * 3, 0.0);
  job->a.assign(3 * n * m, 0.0);
  job->b.assign(3 * n, 0.0);
  job->x.assign(3 * size_t(m), 0.0);
  job->weights.assign(size_t(m) * 3, 0.0);
  LeastSquaresOptions options;
  options.tikhonov = p.tikhonov;
  options.nonnegative = p.nonnegative != 0;
  for (int c = 0; c < 3; ++c) {
    double* a = &job->a[size_t(c) * n * m];
    double* b = &job->b[size_t(c) * n];
    std::vector<double> near(n);
    for (size_t i = 0; i < n; ++i) {
      const size_t px = equations[i];
      const double cos_o = std::fabs(dot(vec3(&front.normals[3 * px]), vec3(&front.toward_eye[3 * px])));
      b[i] = (rgb[3 * px + c] - res.minimum_subtracted[c]) /
             (exit_scale * (1 - arcus_fresnel_reflectance(cos_o, 1.0, p.eta)));
      const size_t own = front_source[px];
      near[i] = weights[3 * own + size_t(c)] / source_area[own];
      job->near[3 * i + size_t(c)] = near[i];
      for (uint32_t h = 0; h < m; ++h) a[i * m + h] = near[i] * near_disc[h];
      for (uint32_t k = near_bins; k < bins; ++k) {
        const double in_bin = hist[(i * bins + k) * 3 + size_t(c)];
        if (in_bin == 0) continue;
        for (uint32_t h = 0; h < m; ++h) a[i * m + h] += in_bin * basis[size_t(k) * m + h];
      }
    }
    const std::vector<double> a_channel(a, a + n * m), b_channel(b, b + n);
    LeastSquaresReport report;
    const std::vector<double> x = solve_least_squares(a_channel, n, m, b_channel, options, &report);
    std::copy(x.begin(), x.end(), job->x.begin() + size_t(c) * m);
    const std::vector<double> averages = bin_averages(basis, m, bins, x);
    for (uint32_t k = 0; k < m; ++k) job->weights[size_t(k) * 3 + size_t(c)] = averages[k];
    double misfit = 0, total = 0;
    for (size_t i = 0; i < n; ++i) {
      double predicted = 0;
      for (uint32_t h = 0; h < m; ++h) predicted += a[i * m + h] * x[h];
      misfit += std::fabs(predicted - b[i]);
      total += std::fabs(b[i]);
    }
    res.image_error[c] = total > 0 ? misfit / total : 0;
    res.iterations[c] = report.iterations;
    res.residual[c] = report.residual;
    res.condition_a[c] = report.condition_a;
    res.condition_normal[c] = report.condition_normal;
    res.dropped_columns[c] = static_cast<uint32_t>(report.dropped.size());
    DipoleFit fit;
    if (p.fit == ARCUS_FIT_PROFILE) {
      fit = fit_to_profile(job->edges, averages, p.eta);
    } else {
      std::vector<double> channel_hist(n * bins);
      for (size_t i = 0; i < n * bins; ++i) channel_hist[i] = hist[i * 3 + size_t(c)];
      fit = fit_to_image(fine_edges, channel_hist, near_bins, near, near_radius, b_channel, p.eta);
    }
    res.dipole.sigma_a[c] = fit.channel.sigma_a;
    res.dipole.sigma_s_prime[c] = fit.channel.sigma_s_prime;
    res.fit_error[c] = fit.error;
  }
  res.dipole.eta = p.eta;
  res.terms = dipole_terms(res.dipole);
  res.solve_seconds = seconds_since(solve_start);
  res.width = w;
  res.height = h;
  res.object_pixels = static_cast<uint32_t>(object.size());
  res.equation_pixels = static_cast<uint32_t>(n);
  res.basis_count = m;
  res.basis = p.basis;
  res.near_radius_mm = near_radius;
  job->count = n;
  job->stats.total_seconds = seconds_since(start);
  return job;
}

}  // namespace arcus::translucency
