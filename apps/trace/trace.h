// arcus_trace: what the command-line tool holds between reading a scene and writing its
// outputs.  The scene itself is read by the library (arcus_scene_load).
#pragma once

#include <arcus/arcus.h>

#include <filesystem>
#include <stdexcept>
#include <string>
#include <vector>

namespace trace {

// Anything that stops the run: a bad command line, a bad scene, a library failure,
// an unwritable output.  The message is complete; main prints it and exits with 2.
struct Failure : std::runtime_error {
  using std::runtime_error::runtime_error;
};

// The scene's inputs and every ray's result.
struct Results {
  std::filesystem::path scene_file;
  std::string name, description, document, medium;
  arcus_device_info device{};
  size_t count = 0;
  std::vector<double> origins, directions, wavelengths;  // as given (wavelengths may be empty)
  arcus_status status = ARCUS_SUCCESS;  // or a partial-result status, with its message
  std::string message;
  std::vector<double> end_positions, end_directions, lengths;
  std::vector<uint64_t> steps;
  std::vector<int32_t> ray_status, failures;
  std::vector<uint64_t> path_offsets, path_needed;  // empty without record_path
  std::vector<double> path_points;
  arcus_features features = 0;
  arcus_job_stats stats{};
};

// "ARCUS_ERROR_IO: message".
std::string library_failure(arcus_status status, const std::string& message);

// Writes rays.csv, paths.csv (with paths), summary.md and scene.json into dir; returns
// the names written.
std::vector<std::string> write_outputs(const std::filesystem::path& dir, const Results& r);

}  // namespace trace
