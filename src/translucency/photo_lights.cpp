#include "translucency/photo_lights.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <string>

#include <opencv2/core.hpp>
#include <opencv2/imgproc.hpp>

#include "core/error.h"
#include "translucency/least_squares.h"
#include "translucency/surface.h"

namespace arcus::translucency {
namespace {

constexpr double kDegree = M_PI / 180;

// The fewest pixels an object and its contour may have: below, neither a contour's
// normals nor the interior's gradients say anything.
constexpr size_t kMinObjectPixels = 64, kMinContourPixels = 24;

// A further light is taken only where it explains the contour much better (its misfit
// at most kGain of the fewer lights'), carries at least kShare of the strongest's
// intensity and lies at least kApart from every other light: a translucent object's
// light wrapping past the terminator is otherwise fitted as a faint light opposite.
constexpr double kGain = 0.5, kShare = 0.1, kApart = 30;

// The uncertainty of an angle: the angles whose misfit stays within this of the best's.
constexpr double kSpreadMisfit = 1.05;

double wrap_degrees(double a) {
  a = std::fmod(a, 360.0);
  return a < 0 ? a + 360 : a;
}

double angle_between(double a, double b) {
  const double d = std::fabs(wrap_degrees(a - b));
  return std::min(d, 360 - d);
}

// The largest 8-connected region of a 0/255 mask, its small holes (under 1% of its
// area: noise) filled; larger ones are the background seen through the object (a
// torus's), whose contour is the object's too.
cv::Mat largest_region(const cv::Mat& mask) {
  cv::Mat labels, stats, centroids;
  const int count = cv::connectedComponentsWithStats(mask, labels, stats, centroids, 8, CV_32S);
  int best = 0;
  for (int i = 1; i < count; ++i)
    if (best == 0 || stats.at<int>(i, cv::CC_STAT_AREA) > stats.at<int>(best, cv::CC_STAT_AREA)) best = i;
  if (best == 0) return cv::Mat::zeros(mask.size(), CV_8U);
  cv::Mat region = labels == best;
  std::vector<std::vector<cv::Point>> outline;
  std::vector<cv::Vec4i> nesting;
  cv::findContours(region.clone(), outline, nesting, cv::RETR_CCOMP, cv::CHAIN_APPROX_NONE);
  const double area = stats.at<int>(best, cv::CC_STAT_AREA);
  for (size_t i = 0; i < outline.size(); ++i)
    if (nesting[i][3] >= 0 && cv::contourArea(outline[i]) < 0.01 * area)
      cv::drawContours(region, outline, int(i), cv::Scalar(255), cv::FILLED);
  return region;
}

// The object brighter than its background, which the photo's frame shows (the object
// may not touch it): a pixel is the object's where its luminance exceeds the frame's
// 99th percentile by three times that percentile's distance from the frame's median
// (the background's noise), and 10⁻⁴ of the brightest pixel (a render's background of
// exact zeros).  A threshold between the object's levels (Otsu's, say) would cut a
// translucent object's dim side off.  Then an opening drops isolated pixels.
cv::Mat segment(const PhotoObject& o) {
  const double brightest = *std::max_element(o.luminance.begin(), o.luminance.end());
  require(brightest > 0, "photo: no object found: every pixel is black");
  std::vector<double> frame;
  for (uint32_t x = 0; x < o.width; ++x)
    frame.insert(frame.end(), {o.luminance[x], o.luminance[size_t(o.height - 1) * o.width + x]});
  for (uint32_t y = 1; y + 1 < o.height; ++y)
    frame.insert(frame.end(), {o.luminance[size_t(y) * o.width], o.luminance[size_t(y) * o.width + o.width - 1]});
  std::sort(frame.begin(), frame.end());
  const double median = frame[frame.size() / 2], high = frame[frame.size() * 99 / 100];
  const double threshold = std::max(high + 3 * (high - median), 1e-4 * brightest);
  cv::Mat out(int(o.height), int(o.width), CV_8U);
  for (size_t i = 0; i < o.luminance.size(); ++i) out.data[i] = o.luminance[i] > threshold ? 255 : 0;
  cv::morphologyEx(out, out, cv::MORPH_OPEN, cv::getStructuringElement(cv::MORPH_RECT, cv::Size(3, 3)));
  return out;
}

// Non-negative least squares of `columns` (each rows long) against `target`: the misfit
// Σ r², the weights in *x.
double fit_nonnegative(const std::vector<std::vector<double>>& columns, const std::vector<double>& target,
                       std::vector<double>* x) {
  const size_t rows = target.size(), cols = columns.size();
  std::vector<double> a(rows * cols);
  for (size_t r = 0; r < rows; ++r)
    for (size_t c = 0; c < cols; ++c) a[r * cols + c] = columns[c][r];
  LeastSquaresOptions options;
  options.nonnegative = true;
  LeastSquaresReport report;
  *x = solve_least_squares(a, rows, cols, target, options, &report);
  double misfit = 0;
  for (size_t r = 0; r < rows; ++r) {
    double m = 0;
    for (size_t c = 0; c < cols; ++c) m += a[r * cols + c] * (*x)[c];
    misfit += (m - target[r]) * (m - target[r]);
  }
  return misfit;
}

// The contour's luminance as an ambient term plus a wrapped, clamped cosine per light,
// L(α) = a + Σ_j I_j max(0, cos(α − θ_j) + w) / (1 + w): a Lambertian surface facing
// across the view would give w = 0 (each light's sin φ_j folded into I_j), but the
// luminance is read a pixel or two inside, where the surface turns toward the camera,
// and a translucent object carries light past the terminator; both widen every lobe
// alike, which one w shared by the lights takes up.
struct ContourFit {
  std::vector<double> azimuth, intensity;  // degrees; I_j
  double wrap = 0;                         // w
  double misfit = INFINITY;
};

ContourFit fit_contour(const std::vector<ContourSample>& contour, const std::vector<double>& azimuth, double wrap) {
  std::vector<std::vector<double>> columns(azimuth.size() + 1, std::vector<double>(contour.size(), 1.0));
  std::vector<double> target(contour.size());
  for (size_t i = 0; i < contour.size(); ++i) {
    target[i] = contour[i].luminance;
    const double alpha = std::atan2(contour[i].ny, contour[i].nx);
    for (size_t j = 0; j < azimuth.size(); ++j)
      columns[j][i] = std::max(0.0, std::cos(alpha - azimuth[j] * kDegree) + wrap) / (1 + wrap);
  }
  std::vector<double> x;
  ContourFit fit;
  fit.azimuth = azimuth;
  fit.wrap = wrap;
  fit.misfit = fit_nonnegative(columns, target, &x);
  fit.intensity.assign(x.begin(), x.end() - 1);
  return fit;
}

// The wrap w over −0.9..1 in steps of 0.05 that fits best with the azimuths held (w < 0:
// narrower lobes, as lights behind the object light only a rim).
ContourFit best_wrap(const std::vector<ContourSample>& contour, const std::vector<double>& azimuth) {
  ContourFit best;
  for (int step = -18; step <= 20; ++step) {
    ContourFit t = fit_contour(contour, azimuth, 0.05 * step);
    if (t.misfit < best.misfit) best = t;
  }
  return best;
}

// k azimuths from k-means on the luminance-weighted normals L n (the thesis' "pixels of
// the contour clustered by k-means"): a cluster's centre is its Σ L n over its count,
// whose direction a light at θ makes θ where the normals spread evenly.  Then each is
// moved while the contour model fits better (a light's lobe overlaps its neighbours',
// which pulls the centres toward each other), and the wrap fitted again.
ContourFit azimuths_by_kmeans(const std::vector<ContourSample>& contour, int k, double top) {
  cv::Mat data(int(contour.size()), 2, CV_32F);
  for (size_t i = 0; i < contour.size(); ++i) {
    data.at<float>(int(i), 0) = float(contour[i].luminance / top * contour[i].nx);
    data.at<float>(int(i), 1) = float(contour[i].luminance / top * contour[i].ny);
  }
  cv::Mat labels, centers;
  cv::theRNG().state = 0x5eed;  // the same photo gives the same lights
  cv::kmeans(data, k, labels, cv::TermCriteria(cv::TermCriteria::EPS + cv::TermCriteria::COUNT, 100, 1e-6), 5,
             cv::KMEANS_PP_CENTERS, centers);
  std::vector<double> azimuth(static_cast<size_t>(k));
  for (int j = 0; j < k; ++j)
    azimuth[size_t(j)] = wrap_degrees(std::atan2(centers.at<float>(j, 1), centers.at<float>(j, 0)) / kDegree);
  ContourFit fit = best_wrap(contour, azimuth);
  for (double step = 8; step >= 0.25; step /= 2)
    for (bool moved = true; moved;) {
      moved = false;
      for (size_t j = 0; j < fit.azimuth.size(); ++j)
        for (double sign : {-1.0, 1.0}) {
          std::vector<double> trial = fit.azimuth;
          trial[j] = wrap_degrees(trial[j] + sign * step);
          ContourFit t = fit_contour(contour, trial, fit.wrap);
          if (t.misfit < fit.misfit) {
            fit = t;
            moved = true;
          }
        }
    }
  return best_wrap(contour, fit.azimuth);
}

bool acceptable(const ContourFit& more, const ContourFit& fewer) {
  if (!(more.misfit <= kGain * fewer.misfit)) return false;
  const double strongest = *std::max_element(more.intensity.begin(), more.intensity.end());
  for (size_t j = 0; j < more.azimuth.size(); ++j) {
    if (!(more.intensity[j] >= kShare * strongest)) return false;
    for (size_t i = 0; i < j; ++i)
      if (angle_between(more.azimuth[i], more.azimuth[j]) < kApart) return false;
  }
  return true;
}

// The light clusters the contour shows plainly: its runs brighter than halfway between
// its darkest and brightest (averaged over 1/60 of it), at least 1% of it long.  Lights whose lobes
// overlap merge into one run; each run needs at least one light.  A contour within 20%
// of even (a light near the camera's axis) shows one: its ripples are the pixels'.
size_t bright_arcs(const std::vector<ContourSample>& contour) {
  const size_t n = contour.size();
  const size_t half = std::max<size_t>(1, n / 120);
  std::vector<double> level(n, 0.0);
  for (size_t i = 0; i < n; ++i) {
    for (size_t d = 0; d <= 2 * half; ++d) level[i] += contour[(i + n + d - half) % n].luminance;
    level[i] /= double(2 * half + 1);
  }
  const auto [lo, hi] = std::minmax_element(level.begin(), level.end());
  if (*hi - *lo < 0.2 * *hi) return 1;
  const double cut = 0.5 * (*lo + *hi);
  const size_t dark = size_t(lo - level.begin()), shortest = std::max<size_t>(2, n / 100);
  size_t arcs = 0, run = 0;
  for (size_t k = 1; k <= n; ++k) {  // from the darkest pixel round: no run is split at the start
    if (level[(dark + k) % n] > cut) {
      ++run;
    } else {
      arcs += run >= shortest;
      run = 0;
    }
  }
  return arcs;
}

// Half the range of the values whose misfit stays within kSpreadMisfit of the least.
double spread(const std::vector<double>& values, const std::vector<double>& misfits) {
  const double least = *std::min_element(misfits.begin(), misfits.end());
  double lo = INFINITY, hi = -INFINITY;
  for (size_t i = 0; i < values.size(); ++i)
    if (misfits[i] <= kSpreadMisfit * least) {
      lo = std::min(lo, values[i]);
      hi = std::max(hi, values[i]);
    }
  return 0.5 * (hi - lo);
}

// The zenith fit's data: pairs of neighbouring pixels where the stand-in faces the
// camera within 60° (n_z >= 1/2) and their luminance steps.  Nearer the contour the
// stand-in's normals are least sure, a dielectric's exit Fresnel term dims the light
// toward grazing view and a translucent object's edge loses light sideways: none of
// which the Lambertian model knows (with them, two lights' zeniths came out 40° off).
struct Gradients {
  std::vector<size_t> from, to;
  std::vector<double> step;
};

Gradients interior_gradients(const PhotoObject& o, const std::vector<double>& normals) {
  auto facing = [&](size_t p) { return o.mask[p] && normals[3 * p + 2] >= 0.5; };
  Gradients g;
  for (uint32_t y = 0; y < o.height; ++y)
    for (uint32_t x = 0; x < o.width; ++x) {
      const size_t p = size_t(y) * o.width + x;
      if (!facing(p)) continue;
      for (size_t q : {p + 1, p + o.width}) {
        if ((q == p + 1 && x + 1 >= o.width) || q >= o.mask.size() || !facing(q)) continue;
        g.from.push_back(p);
        g.to.push_back(q);
        g.step.push_back(o.luminance[q] - o.luminance[p]);
      }
    }
  return g;
}

// The luminance steps a light toward `l` makes on the stand-in: max(0, n·l) per pixel.
std::vector<double> light_steps(const Gradients& g, const std::vector<double>& normals, const double l[3]) {
  auto shade = [&](size_t p) {
    return std::max(0.0, normals[3 * p] * l[0] + normals[3 * p + 1] * l[1] + normals[3 * p + 2] * l[2]);
  };
  std::vector<double> out(g.step.size());
  for (size_t i = 0; i < out.size(); ++i) out[i] = shade(g.to[i]) - shade(g.from[i]);
  return out;
}

void direction_of(double azimuth_deg, double zenith_deg, double out[3]) {
  const double t = azimuth_deg * kDegree, p = zenith_deg * kDegree;
  out[0] = std::sin(p) * std::cos(t);
  out[1] = std::sin(p) * std::sin(t);
  out[2] = std::cos(p);
}

}  // namespace

PhotoObject find_object(uint32_t width, uint32_t height, const float* photo, const uint8_t* matte) {
  require(width >= 3 && height >= 3 && width <= 16384 && height <= 16384,
          "width × height = " + std::to_string(width) + " × " + std::to_string(height) + " is not 3..16384 a side");
  check_radiance(photo, width, height, "photo");
  PhotoObject o;
  o.photo_width = width;
  o.photo_height = height;
  o.scale = (std::max(width, height) + kWorkingSide - 1) / kWorkingSide;
  const uint32_t f = o.scale;
  o.width = width = (o.photo_width + f - 1) / f;
  o.height = height = (o.photo_height + f - 1) / f;
  const size_t n = size_t(width) * height;
  // Box filters: a working pixel's luminance is its photo pixels' mean, and it is the
  // matte's where at least half of them are.
  o.luminance.assign(n, 0.0);
  std::vector<double> share(n, 0.0), count(n, 0.0);
  for (uint32_t y = 0; y < o.photo_height; ++y)
    for (uint32_t x = 0; x < o.photo_width; ++x) {
      const size_t i = size_t(y) * o.photo_width + x, k = size_t(y / f) * width + x / f;
      o.luminance[k] += 0.2126 * photo[3 * i] + 0.7152 * photo[3 * i + 1] + 0.0722 * photo[3 * i + 2];
      share[k] += matte && matte[i] ? 1 : 0;
      count[k] += 1;
    }
  for (size_t k = 0; k < n; ++k) o.luminance[k] /= count[k];
  cv::Mat mask;
  if (matte) {
    mask = cv::Mat(int(height), int(width), CV_8U);
    for (size_t k = 0; k < n; ++k) mask.data[k] = share[k] >= 0.5 * count[k] ? 255 : 0;
  } else {
    o.segmented = true;
    mask = segment(o);
  }
  const cv::Mat region = largest_region(mask);
  o.mask.resize(n);
  for (size_t i = 0; i < n; ++i) o.pixels += (o.mask[i] = region.data[i] ? 1 : 0);
  const char* source = matte ? "matte" : "photo";
  require(o.pixels >= kMinObjectPixels, std::string(source) + ": no object found (its largest region has " +
                                            std::to_string(o.pixels) + " pixels; at least " +
                                            std::to_string(kMinObjectPixels) + " are needed)");
  size_t on_border = 0;
  for (uint32_t x = 0; x < width; ++x) on_border += o.mask[x] + o.mask[n - width + x];
  for (uint32_t y = 1; y + 1 < height; ++y)
    on_border += o.mask[size_t(y) * width] + o.mask[size_t(y) * width + width - 1];
  require(on_border == 0, std::string(source) + ": the object touches the photo's border at " +
                              std::to_string(on_border) + " pixels: its contour, which shows the lights, is cut off "
                              "(frame the whole object)");
  return o;
}

std::vector<double> at_photo_size(const PhotoObject& o, const std::vector<double>& values, int channels,
                                  double multiply) {
  std::vector<double> out(size_t(o.photo_width) * o.photo_height * size_t(channels));
  for (uint32_t y = 0; y < o.photo_height; ++y)
    for (uint32_t x = 0; x < o.photo_width; ++x)
      for (int c = 0; c < channels; ++c)
        out[(size_t(y) * o.photo_width + x) * size_t(channels) + size_t(c)] =
            multiply * values[(size_t(y / o.scale) * o.width + x / o.scale) * size_t(channels) + size_t(c)];
  return out;
}

std::vector<uint8_t> at_photo_size(const PhotoObject& o, const std::vector<uint8_t>& values) {
  std::vector<uint8_t> out(size_t(o.photo_width) * o.photo_height);
  for (uint32_t y = 0; y < o.photo_height; ++y)
    for (uint32_t x = 0; x < o.photo_width; ++x)
      out[size_t(y) * o.photo_width + x] = values[size_t(y / o.scale) * o.width + x / o.scale];
  return out;
}

std::vector<ContourSample> outer_contour(const PhotoObject& o) {
  cv::Mat mask(int(o.height), int(o.width), CV_8U);
  for (size_t i = 0; i < o.mask.size(); ++i) mask.data[i] = o.mask[i] ? 255 : 0;
  std::vector<std::vector<cv::Point>> outline;
  cv::findContours(mask, outline, cv::RETR_EXTERNAL, cv::CHAIN_APPROX_NONE);
  const auto longest = std::max_element(outline.begin(), outline.end(),
                                        [](const auto& a, const auto& b) { return a.size() < b.size(); });
  require(longest != outline.end() && longest->size() >= kMinContourPixels,
          "photo: the object's contour has too few pixels (at least " + std::to_string(kMinContourPixels) +
              " are needed: is the object too small?)");
  const std::vector<cv::Point>& c = *longest;
  const long n = long(c.size());
  // The tangent across ±s pixels of the contour: a pixel chain's own steps turn by 45°.
  const long s = std::clamp(n / 48, 2L, 12L);
  auto inside = [&](double x, double y) {
    const long xi = std::lround(x), yi = std::lround(y);
    return xi >= 0 && yi >= 0 && xi < long(o.width) && yi < long(o.height) && o.mask[size_t(yi) * o.width + size_t(xi)];
  };
  std::vector<ContourSample> out(static_cast<size_t>(n));
  size_t pointing_in = 0;
  for (long i = 0; i < n; ++i) {
    const cv::Point a = c[size_t((i - s + n) % n)], b = c[size_t((i + s) % n)];
    const double tx = b.x - a.x, ty = b.y - a.y, norm = std::hypot(tx, ty);
    ContourSample& p = out[size_t(i)];
    p.x = c[size_t(i)].x;
    p.y = c[size_t(i)].y;
    p.nx = norm > 0 ? ty / norm : 0;  // image axes (y down) for now
    p.ny = norm > 0 ? -tx / norm : 0;
    pointing_in += inside(p.x + 2 * p.nx, p.y + 2 * p.ny);
  }
  const double flip = pointing_in * 2 > size_t(n) ? -1 : 1;
  for (ContourSample& p : out) {
    p.nx *= flip;
    p.ny *= flip;
    // The luminance one and two pixels in: a photo's contour pixels mix in the background.
    double sum = 0;
    int count = 0;
    for (double d : {1.0, 2.0})
      if (inside(p.x - d * p.nx, p.y - d * p.ny)) {
        sum += o.luminance[size_t(std::lround(p.y - d * p.ny)) * o.width + size_t(std::lround(p.x - d * p.nx))];
        ++count;
      }
    p.luminance = count ? sum / count : o.luminance[size_t(p.y) * o.width + size_t(p.x)];
    p.ny = -p.ny;  // to the camera's frame, y up
  }
  return out;
}

std::vector<double> convex_depth(const PhotoObject& o) {
  // ∇²u = −1 by successive over-relaxation (the 5-point Laplacian, u = 0 at the pixels
  // outside), at the over-relaxation that is best for a square of the object's span.
  const long w = long(o.width), h = long(o.height);
  long x0 = w, x1 = 0, y0 = h, y1 = 0;
  for (long y = 0; y < h; ++y)
    for (long x = 0; x < w; ++x)
      if (o.mask[size_t(y * w + x)]) {
        x0 = std::min(x0, x), x1 = std::max(x1, x), y0 = std::min(y0, y), y1 = std::max(y1, y);
      }
  const long span = std::max(x1 - x0, y1 - y0) + 1;
  const double omega = 2 / (1 + std::sin(M_PI / double(span + 1)));
  std::vector<double> u(o.mask.size(), 0.0);
  auto at = [&](long x, long y) { return x < 0 || y < 0 || x >= w || y >= h ? 0.0 : u[size_t(y * w + x)]; };
  for (long sweep = 0; sweep < 40 * span; ++sweep) {
    double change = 0, largest = 0;
    for (long y = y0; y <= y1; ++y)
      for (long x = x0; x <= x1; ++x) {
        const size_t i = size_t(y * w + x);
        if (!o.mask[i]) continue;
        const double next = 0.25 * (at(x - 1, y) + at(x + 1, y) + at(x, y - 1) + at(x, y + 1) + 1);
        const double step = omega * (next - u[i]);
        u[i] += step;
        change = std::max(change, std::fabs(step));
        largest = std::max(largest, u[i]);
      }
    if (change <= 1e-9 * largest) break;
  }
  for (double& z : u) z = std::sqrt(4 * std::max(z, 0.0));
  return u;
}

std::vector<double> depth_normals(const PhotoObject& o, const std::vector<double>& depth) {
  const long w = long(o.width), h = long(o.height);
  auto z_at = [&](long x, long y) { return x < 0 || y < 0 || x >= w || y >= h ? 0.0 : depth[size_t(y * w + x)]; };
  std::vector<double> normals(3 * o.mask.size(), 0.0);
  for (long y = 0; y < h; ++y)
    for (long x = 0; x < w; ++x) {
      const size_t i = size_t(y * w + x);
      if (!o.mask[i]) continue;
      const double dzdx = 0.5 * (z_at(x + 1, y) - z_at(x - 1, y));
      const double dzdy = -0.5 * (z_at(x, y + 1) - z_at(x, y - 1));  // rows run down, y up
      const double norm = std::sqrt(dzdx * dzdx + dzdy * dzdy + 1);
      normals[3 * i] = -dzdx / norm;
      normals[3 * i + 1] = -dzdy / norm;
      normals[3 * i + 2] = 1 / norm;
    }
  return normals;
}

arcus_light_detection detect_lights(uint32_t width, uint32_t height, const float* photo, const uint8_t* matte) {
  return detect_lights(find_object(width, height, photo, matte));
}

arcus_light_detection detect_lights(const PhotoObject& object) {
  const auto start = std::chrono::steady_clock::now();
  const std::vector<ContourSample> contour = outer_contour(object);
  double top = 0;
  for (const ContourSample& p : contour) top = std::max(top, p.luminance);
  require(top > 0, "photo: the object's contour is black: no light shows where the lights' directions are read");

  // Azimuths: one light, then more where they explain the contour much better.
  ContourFit fit = azimuths_by_kmeans(contour, 1, top);
  const size_t arcs = bright_arcs(contour);
  require(arcs <= ARCUS_MAX_DETECTED_LIGHTS,
          "photo: its contour shows " + std::to_string(arcs) + " separate bright arcs, more than the " +
              std::to_string(ARCUS_MAX_DETECTED_LIGHTS) + " light clusters the estimate takes (many lights, or "
              "highlights on the rim)");
  for (int k = 2; k <= ARCUS_MAX_DETECTED_LIGHTS; ++k) {  // every k: one may fail where a larger one fits
    ContourFit more = azimuths_by_kmeans(contour, k, top);
    if (acceptable(more, fit)) fit = more;
  }
  const size_t lights = fit.azimuth.size();

  // Zeniths: each in turn over 0..90°, the others held, fitted to the luminance steps
  // between neighbouring interior pixels (the gradients: no ambient term to fit).
  const std::vector<double> normals = depth_normals(object, convex_depth(object));
  const Gradients gradients = interior_gradients(object, normals);
  require(gradients.step.size() >= kMinObjectPixels,
          "photo: the object has too few pixels inside its contour to read the lights' zeniths");
  std::vector<double> zenith(lights, 45.0), zenith_spread(lights, 0.0), weights;
  std::vector<std::vector<double>> columns(lights);
  for (size_t j = 0; j < lights; ++j) {
    double l[3];
    direction_of(fit.azimuth[j], zenith[j], l);
    columns[j] = light_steps(gradients, normals, l);
  }
  for (int sweep = 0; sweep < 3; ++sweep)
    for (size_t j = 0; j < lights; ++j) {
      std::vector<double> angles, misfits;
      for (double phi = 0; phi <= 90; phi += 1) {
        double l[3];
        direction_of(fit.azimuth[j], phi, l);
        columns[j] = light_steps(gradients, normals, l);
        angles.push_back(phi);
        misfits.push_back(fit_nonnegative(columns, gradients.step, &weights));
      }
      const size_t best = size_t(std::min_element(misfits.begin(), misfits.end()) - misfits.begin());
      zenith[j] = angles[best];
      zenith_spread[j] = spread(angles, misfits);
      double l[3];
      direction_of(fit.azimuth[j], zenith[j], l);
      columns[j] = light_steps(gradients, normals, l);
    }
  fit_nonnegative(columns, gradients.step, &weights);

  // The azimuths' spread: each light turned alone, the contour refitted.
  arcus_light_detection out{};
  double total = 0;
  for (double w : weights) total += w;
  std::vector<size_t> order(lights);
  for (size_t j = 0; j < lights; ++j) order[j] = j;
  std::sort(order.begin(), order.end(), [&](size_t a, size_t b) { return weights[a] > weights[b]; });
  for (size_t rank = 0; rank < lights; ++rank) {
    const size_t j = order[rank];
    std::vector<double> angles, misfits;
    for (double d = -45; d <= 45; d += 0.5) {
      std::vector<double> trial = fit.azimuth;
      trial[j] = wrap_degrees(trial[j] + d);
      angles.push_back(d);
      misfits.push_back(fit_contour(contour, trial, fit.wrap).misfit);
    }
    arcus_detected_light& light = out.lights[rank];
    light.azimuth_deg = fit.azimuth[j];
    light.zenith_deg = zenith[j];
    direction_of(light.azimuth_deg, light.zenith_deg, light.direction);
    light.intensity = total > 0 ? weights[j] / total : 1.0 / double(lights);
    light.azimuth_spread_deg = spread(angles, misfits);
    light.zenith_spread_deg = zenith_spread[j];
  }
  double contour_square = 0;
  for (const ContourSample& p : contour) contour_square += p.luminance * p.luminance;
  out.count = uint32_t(lights);
  out.object_pixels = uint32_t(object.pixels);
  out.contour_pixels = uint32_t(contour.size());
  out.segmented = object.segmented ? 1 : 0;
  out.contour_misfit = std::sqrt(fit.misfit / contour_square);
  out.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return out;
}

}  // namespace arcus::translucency
