// The device's practical FP64 rates, measured in raw OpenCL: many independent chains of
// one operation in wide double vectors, so neither latency nor memory limits the rate.
// The FMA rate is the FP64 peak; the division rate bounds kernels that divide (RK4's
// 1/n in every derivative).
#pragma once

#include <string>
#include <vector>

namespace bench {

struct PeakResult {
  int vector_width = 0;  // doubleN
  int chains = 0;        // independent accumulators per work-item
  double gflops = 0;     // 2 × FMAs per second / 1e9
};

// Runs the FMA microkernel on the OpenCL device whose platform and device names match
// arcus' device, once per (vector width, chains) variant; each variant is sized to run
// about target_seconds and reports its best of five.
std::vector<PeakResult> measure_fp64_peak(const std::string& platform_name, const std::string& device_name,
                                          double target_seconds);

struct DivisionResult {
  int vector_width = 0;
  int chains = 0;
  double per_second = 0;  // double divisions per second, the device's every compute unit
};

// The same for x = a / x chains: the device's double-division throughput.
std::vector<DivisionResult> measure_fp64_division(const std::string& platform_name, const std::string& device_name,
                                                  double target_seconds);

}  // namespace bench
