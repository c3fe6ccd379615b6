#include "rainbow_sky.h"

#include <GLFW/glfw3.h>  // key codes

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <system_error>
#include <vector>

#include "navigation.h"

namespace arcus_view {
namespace {

using nlohmann::json;
namespace fs = std::filesystem;

// A value for an error message, cut short.
std::string shown(const json& v) {
  std::string s = v.dump();
  return s.size() > 40 ? s.substr(0, 37) + "..." : s;
}

// The members of one object of the file ("sky" or "table"), each error naming the file
// and the member.
class Members {
 public:
  Members(const std::string& file, const json& document, const char* section) : file_(file), section_(section) {
    const auto it = document.find(section);
    if (it == document.end() || !it->is_object())
      throw Failure(file_ + ": \"" + section_ + "\" must be an object (is it a file arcus.sky.export wrote?)");
    object_ = &*it;
  }

  [[noreturn]] void fail(const std::string& key, const std::string& what) const {
    throw Failure(file_ + ": " + section_ + "." + key + " " + what);
  }

  const json* find(const char* key) const {
    const auto it = object_->find(key);
    return it == object_->end() || it->is_null() ? nullptr : &*it;
  }

  const json& get(const char* key) const {
    if (const json* v = find(key)) return *v;
    fail(key, "is missing");
  }

  double number(const char* key) const {
    const json& v = get(key);
    if (!v.is_number()) fail(key, "must be a number, got " + shown(v));
    return v.get<double>();
  }

  uint32_t count(const char* key) const {
    const json& v = get(key);
    const double d = v.is_number() ? v.get<double>() : -1;
    if (!(d >= 0 && d <= UINT32_MAX && d == std::floor(d))) fail(key, "must be a whole number >= 0, got " + shown(v));
    return static_cast<uint32_t>(d);
  }

  // An array of numbers: of `size` (0: any size but empty) values.
  std::vector<double> numbers(const char* key, size_t size, const char* size_name = "") const {
    const json& v = get(key);
    if (!v.is_array() || v.empty() || !std::all_of(v.begin(), v.end(), [](const json& x) { return x.is_number(); }))
      fail(key, "must be an array of numbers, got " + shown(v));
    if (size != 0 && v.size() != size)
      fail(key, "holds " + std::to_string(v.size()) + " numbers, not " + std::to_string(size) + " (" + size_name +
                    ")");
    return v.get<std::vector<double>>();
  }

  void vector3(const char* key, double* out) const {
    const std::vector<double> v = numbers(key, 3, "x, y, z");
    std::copy(v.begin(), v.end(), out);
  }

 private:
  std::string file_, section_;
  const json* object_ = nullptr;
};

// β as written by arcus.sky.export: exactly `count` little-endian float64.
// `path` is named by `json_path`'s table.beta_file; `shape` says how `count` comes about.
std::vector<double> read_beta(const std::string& path, const std::string& json_path, size_t count,
                              const std::string& shape) {
  const std::string file = path + " (the beta file of " + json_path + ")";
  std::error_code error;
  const auto bytes = fs::file_size(path, error);
  if (error) throw Failure(file + ": cannot read it: " + error.message());
  const std::string needed = shape + " = " + std::to_string(count) + " float64 values (" +
                             std::to_string(count * 8) + " bytes)";
  if (bytes != count * 8)
    throw Failure(file + ": holds " + std::to_string(bytes) + " bytes, but the table needs " + needed +
                  (bytes < count * 8 ? ": it is too short" : ": it is too long") +
                  " (rewrite it with arcus.sky.export)");
  std::ifstream in(path, std::ios::binary);
  std::vector<unsigned char> raw(count * 8);
  if (!in.read(reinterpret_cast<char*>(raw.data()), static_cast<std::streamsize>(raw.size())))
    throw Failure(file + ": cannot read its " + needed);
  std::vector<double> beta(count);
  for (size_t i = 0; i < count; ++i) {
    uint64_t bits = 0;
    for (int b = 7; b >= 0; --b) bits = bits << 8 | raw[8 * i + b];
    std::memcpy(&beta[i], &bits, sizeof bits);
  }
  return beta;
}

// The PNG's exposure as the library sets it (src/rainbow/sky.cpp): the sky's, or when
// that is 0, the 99.5th percentile of Y brought to 0.9 (1 for a black image).
double job_exposure(double sky_exposure, const std::vector<float>& xyz) {
  if (sky_exposure != 0) return sky_exposure;
  const size_t pixels = xyz.size() / 3;
  std::vector<float> luminance(pixels);
  for (size_t p = 0; p < pixels; ++p) luminance[p] = xyz[3 * p + 1];
  auto nth = luminance.begin() + static_cast<std::ptrdiff_t>(0.995 * (pixels - 1));
  std::nth_element(luminance.begin(), nth, luminance.end());
  return *nth > 0 ? 0.9 / *nth : 1.0;
}

bool same_view(const arcus_rainbow_sky& a, const arcus_rainbow_sky& b) {
  return std::equal(a.camera_forward, a.camera_forward + 3, b.camera_forward) &&
         std::equal(a.camera_up, a.camera_up + 3, b.camera_up) && a.fov_deg == b.fov_deg;
}

constexpr double kDeg = M_PI / 180.0;

// The exported sky file as JSON, or a discarded value when it is no such file.  Only a
// regular file of a sane size is opened: a FIFO would block the viewer for ever and
// /dev/zero never end (the library's scene reader refuses both the same way).
json read_json_file(const std::string& path) {
  std::error_code error;
  if (!fs::is_regular_file(path, error) || fs::file_size(path, error) > (uint64_t(64) << 20) || error)
    return json(json::value_t::discarded);
  std::ifstream in(path);
  return json::parse(in, nullptr, false);
}

class RainbowSky final : public Preview {
 public:
  RainbowSky(arcus_context_t* ctx, const std::string& path) : ctx_(ctx) {
    const json doc = read_json_file(path);
    if (doc.is_discarded() || !doc.is_object())
      throw Failure(path + ": not a JSON object (or not a regular file of at most 64 MiB)");
    const json& version = doc.at("arcus_rainbow_sky");
    if (version != 1)
      throw Failure(path + ": \"arcus_rainbow_sky\" is " + shown(version) + "; this arcus_view reads version 1");
    name_ = fs::path(path).filename().string();
    if (doc.contains("description") && doc.at("description").is_string()) description_ = doc.at("description");

    // ---- the table (arcus_rainbow_table), β read once
    const Members t(path, doc, "table");
    wavelengths_ = t.numbers("wavelengths_nm", 0);
    const size_t L = wavelengths_.size();
    extinction_ = t.numbers("extinction", L, "one per wavelength");
    table_.wavelength_count = static_cast<uint32_t>(L);
    table_.wavelengths_nm = wavelengths_.data();
    table_.theta_first_deg = t.number("theta_first_deg");
    table_.theta_last_deg = t.number("theta_last_deg");
    table_.theta_count = t.count("theta_count");
    table_.phi_count = t.count("phi_count");
    if (table_.theta_count == 0) t.fail("theta_count", "must be at least 1");
    if (table_.phi_count == 0) t.fail("phi_count", "must be at least 1");
    const double values = double(L) * table_.phi_count * table_.theta_count;
    if (values > double(1 << 28))
      throw Failure(path + ": the table holds " + std::to_string(values) + " values, more than the library's 2^28");
    const json& beta_file = t.get("beta_file");
    if (!beta_file.is_string() || beta_file.get<std::string>().empty())
      t.fail("beta_file", "must be a file name, got " + shown(beta_file));
    // Relative to the JSON file's folder (an absolute path stays as it is).
    const std::string beta_path = (fs::path(path).parent_path() / beta_file.get<std::string>()).string();
    beta_ = read_beta(beta_path, path, static_cast<size_t>(values),
                      "wavelength_count × phi_count × theta_count = " + std::to_string(L) + " × " +
                          std::to_string(table_.phi_count) + " × " + std::to_string(table_.theta_count));
    table_.scattering = beta_.data();
    table_.extinction = extinction_.data();

    // ---- the sky (arcus_rainbow_sky); the library checks the ranges when it renders
    const Members s(path, doc, "sky");
    check(nullptr, arcus_rainbow_sky_init(&home_), "sky");
    home_.width = s.count("width");
    home_.height = s.count("height");
    if (home_.width == 0 || home_.height == 0) s.fail("width", "and height must be at least 1");
    s.vector3("camera_position", home_.camera_position);
    s.vector3("camera_forward", home_.camera_forward);
    s.vector3("camera_up", home_.camera_up);
    home_.fov_deg = s.number("fov_deg");
    home_.sun_elevation_deg = s.number("sun_elevation_deg");
    home_.sun_azimuth_deg = s.number("sun_azimuth_deg");
    home_.sun_diameter_deg = s.number("sun_diameter_deg");
    home_.sun_samples = s.count("sun_samples");
    sun_ = s.numbers("sun_irradiance", L, "one per wavelength");
    home_.sun_irradiance = sun_.data();
    // The backgrounds may be left out (null): black.
    if (s.find("sky_radiance")) sky_radiance_ = s.numbers("sky_radiance", L, "one per wavelength");
    if (s.find("ground_radiance")) ground_radiance_ = s.numbers("ground_radiance", L, "one per wavelength");
    home_.sky_radiance = sky_radiance_.empty() ? nullptr : sky_radiance_.data();
    home_.ground_radiance = ground_radiance_.empty() ? nullptr : ground_radiance_.data();
    // A sky image: its file (relative to the JSON file's folder), read by the library.
    if (const json* file = s.find("sky_image_file"); file && !file->is_null()) {
      if (!file->is_string() || file->get<std::string>().empty())
        s.fail("sky_image_file", "must be a file name or null, got " + shown(*file));
      const std::string image_path = (fs::path(path).parent_path() / file->get<std::string>()).string();
      uint32_t w = 0, h = 0;
      check(nullptr, arcus_image_read(image_path.c_str(), &w, &h, nullptr, 0), "sky_image_file");
      sky_image_.resize(size_t(w) * h * 3);
      check(nullptr, arcus_image_read(image_path.c_str(), &w, &h, sky_image_.data(), sky_image_.size()),
            "sky_image_file");
      home_.sky_image = sky_image_.data();
      home_.sky_image_width = w;
      home_.sky_image_height = h;
      home_.sky_image_scale = s.number("sky_image_scale");
    }
    s.vector3("rain_min", home_.rain_min);
    s.vector3("rain_max", home_.rain_max);
    home_.march_steps = s.count("march_steps");
    home_.exposure = s.number("exposure");
    accepted_ = wanted_ = home_;
  }
  RainbowSky(const RainbowSky&) = delete;  // the skies point into the spectra
  RainbowSky& operator=(const RainbowSky&) = delete;

  const std::string& name() const override { return name_; }
  uint32_t width() const override { return home_.width; }
  uint32_t height() const override { return home_.height; }

  void key(int key, bool, bool shift) override {
    const double angle = (shift ? 0.1 : 1.0) * wanted_.fov_deg / 8 * kDeg;  // an eighth of the view
    switch (key) {
      case GLFW_KEY_LEFT: look(wanted_, -angle, 0); break;
      case GLFW_KEY_RIGHT: look(wanted_, angle, 0); break;
      case GLFW_KEY_UP: look(wanted_, 0, angle); break;
      case GLFW_KEY_DOWN: look(wanted_, 0, -angle); break;
      case GLFW_KEY_H: wanted_ = home_; break;
      default: break;  // the render scenes' keys (1-4, M, W/A/S/D) mean nothing here
    }
  }

  void drag(double dx, double dy, bool, int window_width) override {
    // Grab the sky: what is under the cursor at the centre of the view follows it (the
    // pinhole's angle per pixel there), so dragging right turns the view left.
    const double rate = 2 * std::tan(wanted_.fov_deg / 2 * kDeg) / std::max(1, window_width);
    look(wanted_, -dx * rate, dy * rate);
  }

  void scroll(double dy) override { zoom(wanted_, std::pow(0.9, dy)); }  // up: narrower

  bool pending() const override { return !same_view(wanted_, accepted_); }

  bool apply(std::string* message) override {
    if (same_view(wanted_, accepted_)) return false;
    accepted_ = wanted_;  // look and zoom keep it within the library's ranges
    message->clear();
    return true;
  }

  bool render(uint32_t scale, arcus_progress_callback progress, void* user, Frame* frame) override {
    arcus_rainbow_sky sky = accepted_;
    sky.width = std::max<uint32_t>(1, sky.width / scale);
    sky.height = std::max<uint32_t>(1, sky.height / scale);
    sky.progress = progress;
    sky.progress_user = user;
    Job job;
    const arcus_status s = arcus_rainbow_render(ctx_, &table_, &sky, &job.job);
    if (s == ARCUS_ERROR_CANCELLED) return false;
    check(ctx_, s, name_ + ": render");

    uint32_t width = 0, height = 0;
    check(ctx_, arcus_job_get_rainbow_image(job.job, &width, &height, nullptr, nullptr, nullptr), "image");
    std::vector<float> xyz(size_t(width) * height * 3), rgb(xyz.size());
    check(ctx_, arcus_job_get_rainbow_image(job.job, nullptr, nullptr, xyz.data(), rgb.data(), nullptr), "image");
    const double exposure = job_exposure(sky.exposure, xyz);
    frame->pixels = to_srgb8(rgb, width, height, exposure);
    arcus_job_stats st;
    check(ctx_, arcus_job_get_stats(job.job, &st), "stats");
    char buf[160];
    std::snprintf(buf, sizeof buf, "%ux%u%s | %.3f s | exposure %.3g%s", width, height,
                  scale == 1 ? "" : (" (1/" + std::to_string(scale) + ")").c_str(), st.total_seconds, exposure,
                  sky.exposure == 0 ? " (auto)" : "");
    frame->figures = buf;
    return true;
  }

  std::string settings() const override {
    const double* f = accepted_.camera_forward;
    char buf[120];
    std::snprintf(buf, sizeof buf, "fov %.3g° | looking %.3g° az, %.3g° el", accepted_.fov_deg,
                  std::atan2(f[0], f[2]) / kDeg, std::atan2(f[1], std::hypot(f[0], f[2])) / kDeg);
    return description_.empty() ? buf : std::string(buf) + " | " + description_;
  }

 private:
  arcus_context_t* ctx_;
  std::string name_, description_;
  std::vector<double> wavelengths_, extinction_, beta_, sun_, sky_radiance_, ground_radiance_;
  std::vector<float> sky_image_;
  arcus_rainbow_table table_{};
  arcus_rainbow_sky home_{}, accepted_{}, wanted_{};  // the file's, the rendered, the user's
};

}  // namespace

bool is_rainbow_sky_file(const std::string& path) {
  const json doc = read_json_file(path);
  return !doc.is_discarded() && doc.is_object() && doc.contains("arcus_rainbow_sky");
}

std::unique_ptr<Preview> open_rainbow_sky(arcus_context_t* ctx, const std::string& path) {
  return std::make_unique<RainbowSky>(ctx, path);
}

}  // namespace arcus_view
