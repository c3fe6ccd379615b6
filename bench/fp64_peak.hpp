// The device's practical FP64 peak, measured in raw OpenCL: many independent FMA chains
// in wide double vectors, so neither latency nor memory limits the rate.
#pragma once

#include <string>
#include <vector>

namespace bench {

struct PeakResult {
  int vector_width = 0;  // doubleN
  int chains = 0;        // independent accumulators per work-item
  double gflops = 0;     // 2 × FMAs per second / 1e9
};

// Runs the microkernel on the OpenCL device whose platform and device names match
// arcus' device, once per (vector width, chains) variant; each variant is sized to run
// about target_seconds and reports its best of five.
std::vector<PeakResult> measure_fp64_peak(const std::string& platform_name, const std::string& device_name,
                                          double target_seconds);

}  // namespace bench
