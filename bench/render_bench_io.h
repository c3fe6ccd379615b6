// arcus_bench_render's text and files (render_bench.cpp): figures as the tables print
// them, the machine's description, and the scene files as the benchmark loads them.
#pragma once

#include <filesystem>
#include <string>
#include <vector>

namespace render_bench {

double median(std::vector<double> v);              // NaN for none
std::string fmt(const char* f, double v);          // printf's, "–" for a non-finite v
std::string km(double v);                          // an error in km, three digits
std::string cpu_model();                           // /proc/cpuinfo's model name
std::string load_average();                        // /proc/loadavg's three
std::string utc_now();                             // "2026-11-28 02:40 UTC"
std::vector<std::string> split(const std::string& s, char sep);  // empty items dropped

struct SceneFile {
  std::string path;  // what is loaded (the quick copy under --quick)
  std::string shown; // as given
  std::string name;
  bool photons = false;
};

// Reads the scene's JSON (name, camera, photons); under `quick` writes a copy at half
// the width and height into `tmp`, its relative file names made absolute.  Returns ""
// or why the scene is skipped.
std::string prepare(const std::string& path, bool quick, const std::filesystem::path& tmp, SceneFile* out);

}  // namespace render_bench
