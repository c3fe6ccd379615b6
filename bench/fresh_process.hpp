// Measurements that need a new process each: the first job's time with empty and warm
// program caches, and a large grid's creation time and peak memory.  The benchmark runs
// itself as the child (--first-job, --grid-child FILE) and reads its "key value" lines.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

namespace bench {

const char* program_origin_name(int origin);  // "built", "memory cache", "disk cache"

// ---- first job ---------------------------------------------------------------------------
// The first arcus_advance of one headline kernel (double, linear field) in a new process.
struct FirstKernel {
  std::string method;
  double advance_seconds = 0;  // all of arcus_advance (arcus_job_stats.total_seconds)
  double build_seconds = 0;    // getting the program: build or disk-cache load
  double kernel_seconds = 0;   // its launches (PoCL's first-launch code generation included)
  int origin = 0;              // arcus_program_origin
};

struct FirstJob {
  std::string scenario;           // "cold", "warm", "PoCL cache only", "arcus cache only"
  std::string arcus_cache, pocl_cache;  // what each cache held: "empty", "warm", "off"
  double process_seconds = 0;     // spawn to exit, as the parent sees it
  double context_seconds = 0;     // arcus_context_create
  double first_job_seconds = 0;   // context creation + the advances, in the child
  std::vector<FirstKernel> kernels;  // RK4, then DP45
};

struct FirstJobStudy {
  std::vector<FirstJob> runs;
  std::string error;  // why it could not be measured ("" if it was)
};

// Child processes with ARCUS_CACHE_DIR and POCL_CACHE_DIR in fresh temp dirs (removed
// afterwards): cold (both empty), warm (both from the cold run), PoCL cache only
// (ARCUS_CACHE_DIR=off) and arcus cache only (a fresh POCL_CACHE_DIR).
FirstJobStudy measure_first_jobs();
// The child's side (--first-job): context, then the first RK4 and DP45 advance.
int first_job_child();

// ---- grid creation --------------------------------------------------------------------------
// A reliability probe's figures for a 256³ grid before the fixes: 7.7 s to create it (a
// message formatted for every valid value) and a peak of 5.3× a float32 file's size.
constexpr uint32_t kProbeGridSide = 256;
constexpr double kProbeSecondsBefore = 7.7;
constexpr double kProbePeakPerFileBefore = 5.3;

struct GridCreation {
  std::string source;               // "file, float32" | "memory, double"
  double create_seconds = 0;        // wall time of the creating call
  double create_peak_bytes = 0;     // peak RSS growth during it
  double job_seconds = 0;           // the first small RK4 job on the grid: arcus_advance,
  double job_kernel_seconds = 0;    //   its kernel launches,
  double job_peak_bytes = 0;        //   and its peak RSS growth (the upload to the device)
};

struct GridStudy {
  uint32_t side = 0;
  double file_bytes = 0;            // side³ float32 values
  std::vector<GridCreation> rows;   // from the file, then from an in-memory double array
  std::string error;
};

// Writes a side³ float32 grid file to a temp dir (removed afterwards) and measures
// arcus_field_create_grid_from_file and arcus_field_create_grid in child processes.
GridStudy measure_grid_creation(uint32_t side);
// The child's side (--grid-child FILE [--from-memory]).
int grid_child(const std::string& path, bool from_memory);

}  // namespace bench
