// arcus_bench_render's text and files (render_bench_io.h).
#include "render_bench_io.h"

#include <nlohmann/json.hpp>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <ctime>
#include <fstream>
#include <sstream>

namespace render_bench {
namespace {

namespace fs = std::filesystem;
using json = nlohmann::ordered_json;

// Relative file names in a scene ("file", "texture") made absolute against its directory.
void absolutize(json& j, const fs::path& base) {
  if (j.is_object()) {
    for (auto it = j.begin(); it != j.end(); ++it) {
      if ((it.key() == "file" || it.key() == "texture") && it.value().is_string()) {
        const fs::path p = it.value().get<std::string>();
        if (p.is_relative()) it.value() = fs::absolute(base / p).lexically_normal().string();
      } else {
        absolutize(it.value(), base);
      }
    }
  } else if (j.is_array()) {
    for (json& e : j) absolutize(e, base);
  }
}

}  // namespace

double median(std::vector<double> v) {
  if (v.empty()) return NAN;
  std::sort(v.begin(), v.end());
  const size_t n = v.size();
  return n % 2 ? v[n / 2] : 0.5 * (v[n / 2 - 1] + v[n / 2]);
}

std::string fmt(const char* f, double v) {
  if (!std::isfinite(v)) return "–";
  char buf[64];
  std::snprintf(buf, sizeof buf, f, v);
  return buf;
}

// Three significant digits, switching to an exponent for small errors (km).
std::string km(double v) {
  if (!std::isfinite(v)) return "–";
  if (v == 0) return "0";
  return fmt(std::fabs(v) >= 1e-3 ? "%.4f" : "%.2e", v);
}

std::string cpu_model() {
  std::ifstream in("/proc/cpuinfo");
  for (std::string line; std::getline(in, line);)
    if (line.rfind("model name", 0) == 0) return line.substr(line.find(':') + 2);
  return "unknown";
}

std::string load_average() {
  std::ifstream in("/proc/loadavg");
  std::string a, b, c;
  in >> a >> b >> c;
  return a.empty() ? "unknown" : a + " " + b + " " + c;
}

std::string utc_now() {
  char date[64];
  const std::time_t now = std::time(nullptr);
  std::strftime(date, sizeof date, "%Y-%m-%d %H:%M UTC", std::gmtime(&now));
  return date;
}

std::vector<std::string> split(const std::string& s, char sep) {
  std::vector<std::string> out;
  std::stringstream in(s);
  for (std::string item; std::getline(in, item, sep);)
    if (!item.empty()) out.push_back(item);
  return out;
}

std::string prepare(const std::string& path, bool quick, const fs::path& tmp, SceneFile* out) {
  std::ifstream in(path);
  if (!in) return "not found";
  json doc;
  try {
    doc = json::parse(in);
  } catch (const std::exception& e) {
    return std::string("not valid JSON: ") + e.what();
  }
  if (!doc.is_object() || !doc.contains("camera")) return "no \"camera\" (not a render scene)";
  out->shown = path;
  out->path = path;
  out->name = doc.value("name", fs::path(path).stem().string());
  out->photons = doc.contains("photons");
  if (quick) {
    json& cam = doc["camera"];
    for (const char* k : {"width", "height"})
      if (cam.contains(k) && cam[k].is_number_integer()) cam[k] = std::max<int64_t>(1, cam[k].get<int64_t>() / 2);
    // A photon map's photons scale with the pixels, so its noise per pixel stays alike.
    if (doc.contains("photons") && doc["photons"].is_object() && doc["photons"].contains("count") &&
        doc["photons"]["count"].is_number_integer())
      doc["photons"]["count"] = std::max<int64_t>(1000, doc["photons"]["count"].get<int64_t>() / 4);
    absolutize(doc, fs::absolute(path).parent_path());
    const fs::path copy = tmp / (out->name + ".json");
    std::ofstream o(copy);
    o << doc.dump(2) << '\n';
    if (!o) return "cannot write the quick copy";
    out->path = copy.string();
  }
  return "";
}

}  // namespace render_bench
