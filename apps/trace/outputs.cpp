// arcus_trace's output files: the rays and paths as CSV, a summary, the scene as read.
#include <cstdio>
#include <fstream>
#include <map>

#include "trace.h"

namespace trace {
namespace {

namespace fs = std::filesystem;

const char* ray_status_name(int32_t s) {
  static const char* const names[] = {"DONE", "LEFT_BOX", "STEP_LIMIT", "FAILED", "INVALID_INPUT", "CANCELLED"};
  return s >= 0 && s < 6 ? names[s] : "UNKNOWN";
}

const char* failure_name(int32_t f) {
  static const char* const names[] = {"", "TOLERANCE", "NOT_FINITE", "INDEX_NOT_POSITIVE"};
  return f >= 0 && f < 4 ? names[f] : "UNKNOWN";
}

// Full round-trip precision: the CSVs are data for analysis, not for reading.
std::string num(double v) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.17g", v);
  return buf;
}

void write_triple(std::ostream& out, const double* v) {
  out << ',' << num(v[0]) << ',' << num(v[1]) << ',' << num(v[2]);
}

// Opens `file`, lets `body` write it and checks that everything reached the disk.
template <class Body>
void write_file(const fs::path& file, Body&& body) {
  std::ofstream out(file);
  if (!out) throw Failure(file.string() + ": cannot write");
  body(out);
  out.close();
  if (!out) throw Failure(file.string() + ": writing failed");
}

void write_rays_csv(std::ostream& out, const Results& r) {
  out << "ray,origin_x,origin_y,origin_z,dir_x,dir_y,dir_z,wavelength_nm,end_x,end_y,end_z,end_dir_x,end_dir_y,"
         "end_dir_z,length,steps,status,failure\n";
  for (size_t i = 0; i < r.count; ++i) {
    out << i;
    write_triple(out, &r.origins[3 * i]);
    write_triple(out, &r.directions[3 * i]);
    out << ',' << (r.wavelengths.empty() ? std::string() : num(r.wavelengths[i]));
    write_triple(out, &r.end_positions[3 * i]);
    write_triple(out, &r.end_directions[3 * i]);
    out << ',' << num(r.lengths[i]) << ',' << r.steps[i] << ',' << ray_status_name(r.ray_status[i]) << ','
        << failure_name(r.failures[i]) << '\n';
  }
}

void write_paths_csv(std::ostream& out, const Results& r) {
  out << "ray,point,x,y,z\n";
  for (size_t i = 0; i < r.count; ++i)
    for (uint64_t k = r.path_offsets[i]; k < r.path_offsets[i + 1]; ++k) {
      out << i << ',' << k - r.path_offsets[i];
      write_triple(out, &r.path_points[3 * k]);
      out << '\n';
    }
}

std::string features_string(arcus_features features) {
  char buf[512];
  if (arcus_features_to_string(features, buf, sizeof buf) != ARCUS_SUCCESS) return "(unavailable)";
  return buf;
}

size_t truncated_paths(const Results& r) {
  size_t n = 0;
  for (size_t i = 0; i < r.path_needed.size(); ++i) n += r.path_needed[i] > r.path_offsets[i + 1] - r.path_offsets[i];
  return n;
}

void write_summary(std::ostream& out, const Results& r) {
  static const char* const origins[] = {"built", "memory cache", "disk cache"};
  out << "# " << r.name << "\n\n";
  if (!r.description.empty()) out << r.description << "\n\n";
  out << "- scene: `" << r.scene_file.string() << "` (medium: " << r.medium << ")\n"
      << "- device: " << r.device.name << " (" << r.device.platform << ", " << r.device.version << ")\n"
      << "- features compiled: " << features_string(r.features) << "\n"
      << "- rays: " << r.count << (r.wavelengths.empty() ? "" : ", each at its own wavelength") << "\n";
  if (!r.path_offsets.empty())
    out << "- path points kept: " << r.path_offsets.back() << " (" << truncated_paths(r)
        << " paths cut short by path_capacity)\n";
  if (r.status != ARCUS_SUCCESS) out << "- library result: " << library_failure(r.status, r.message) << "\n";
  const int origin = r.stats.program_origin >= 0 && r.stats.program_origin < 3 ? r.stats.program_origin : 0;
  out << "\n## Timing\n\n"
      << "| program | kernel | total (arcus_curved_advance) | launches | lanes | groups |\n"
      << "|---|---|---|---|---|---|\n"
      << "| " << origins[origin] << ", " << r.stats.build_seconds << " s | " << r.stats.kernel_seconds << " s | "
      << r.stats.total_seconds << " s | " << r.stats.launches << " | " << r.stats.lanes << " | " << r.stats.groups
      << " |\n\n## Rays per status\n\n";
  std::map<std::pair<int32_t, int32_t>, size_t> counts;
  for (size_t i = 0; i < r.count; ++i) ++counts[{r.ray_status[i], r.failures[i]}];
  out << "| status | failure | rays |\n|---|---|---|\n";
  for (const auto& c : counts)
    out << "| " << ray_status_name(c.first.first) << " | " << failure_name(c.first.second) << " | " << c.second
        << " |\n";
}

}  // namespace

std::string library_failure(arcus_status status, const std::string& message) {
  return std::string(arcus_status_string(status)) + ": " + message;
}

std::vector<std::string> write_outputs(const fs::path& dir, const Results& r) {
  std::error_code ec;
  fs::create_directories(dir, ec);
  if (ec) throw Failure(dir.string() + ": cannot create the output directory: " + ec.message());
  std::vector<std::string> written{"rays.csv"};
  write_file(dir / "rays.csv", [&](std::ostream& out) { write_rays_csv(out, r); });
  if (!r.path_offsets.empty()) {
    write_file(dir / "paths.csv", [&](std::ostream& out) { write_paths_csv(out, r); });
    written.push_back("paths.csv");
  }
  write_file(dir / "summary.md", [&](std::ostream& out) { write_summary(out, r); });
  write_file(dir / "scene.json", [&](std::ostream& out) { out << r.document << '\n'; });
  written.insert(written.end(), {"summary.md", "scene.json"});
  return written;
}

}  // namespace trace
