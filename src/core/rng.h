// The counter-based generator shared by the engines (kernels/common/philox.h: Philox
// 4x32-10, the same code on host and device): its fill kernel, for tests and the
// benchmark, run through the program registry like any engine's kernel.
#pragma once

#include <cstdint>
#include <vector>

#include "core/context.h"
#include "core/kernel_source.h"
#include "core/layout.h"

namespace arcus {

const KernelSource& rng_fill_source();

// Draws `draws` uniform numbers in [0, 1) for each of `count` items from first_index,
// item-major, on ctx's device in the given layout (double, or float when `single`).
std::vector<double> rng_fill(arcus_context_t* ctx, Layout layout, bool single, uint64_t seed, uint64_t first_index,
                             uint32_t draws, uint32_t count, double* kernel_seconds = nullptr);

}  // namespace arcus
