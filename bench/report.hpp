// The report: the CSV files, results.md, the plots (plot_bench.py) and the summary
// lines that end the output (the two headline ratios last).
#pragma once

#include <arcus/arcus.h>

#include <cstdint>
#include <filesystem>
#include <string>
#include <vector>

#include "fresh_process.hpp"
#include "harness.hpp"
#include "studies.hpp"

namespace bench {

struct Machine {
  std::string cpu, date, device, platform, device_version, arcus_version;
  std::string load_before, load_after;  // other work on the cores skews every timing
  unsigned cores = 0;
  uint32_t compute_units = 0, lanes = 0;
};

Machine describe_machine(const arcus_device_info& dev);  // load_before: now
std::string load_average();                             // the 1, 5 and 15 minute load averages

// Everything one run measured.
struct Results {
  std::vector<Row> step, tolerance, peer, distance, gradient, precision, layout;
  DpComparison dp;
  PeakComparison peak;
  std::vector<Row> native;  // native C++ RK4 on 1 thread, then on every core
  FirstJobStudy first_job;
  GridStudy grid;
};

// Every CSV and results.md into out_dir.
void write_outputs(const std::filesystem::path& out_dir, const Machine& m, const Plan& p, const Results& r, bool quick);
void run_plot_script(const std::filesystem::path& out_dir);
// The closing lines: what was written, the comparisons, and the two ratios last.
void print_summary(const std::filesystem::path& out_dir, const Plan& p, const Results& r, bool plotted);

}  // namespace bench
