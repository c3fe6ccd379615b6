// The generator on the device gives the host's numbers (kernels/common/philox.h is one
// text for both), whatever the lane/group layout, the precision or the batch split:
// a number depends on (seed, index, draw) alone.
#include <gtest/gtest.h>

#include <cstdint>
#include <vector>

#include "common/philox.h"
#include "core/layout.h"
#include "core/rng.h"
#include "unit_util.h"

namespace {

using arcus_unit::Context;
using arcus_unit::ScopedEnv;

constexpr uint64_t kSeed = 0x0123456789abcdefull;

std::vector<double> host(uint64_t first, uint32_t draws, uint32_t count, bool single) {
  std::vector<double> v;
  for (uint64_t i = first; i < first + count; ++i)
    for (uint32_t d = 0; d < draws; ++d)
      v.push_back(single ? arcus_rng_uniform_float(kSeed, i, d) : arcus_rng_uniform_double(kSeed, i, d));
  return v;
}

TEST(RngDevice, EveryLayoutAndPrecisionGivesTheHostsNumbers) {
  Context ctx;
  const uint32_t draws = 5, count = 1000;  // odd draws; a count that fills no layout evenly
  const uint64_t first = (uint64_t(1) << 32) - 300;  // the index crosses 2^32
  for (bool single : {false, true}) {
    const std::vector<double> want = host(first, draws, count, single);
    for (arcus::Layout layout : {arcus::Layout{8, 2}, arcus::Layout{1, 1}, arcus::Layout{16, 4}, arcus::Layout{4, 3}}) {
      const std::vector<double> got = arcus::rng_fill(ctx, layout, single, kSeed, first, draws, count);
      ASSERT_EQ(got.size(), want.size());
      size_t mismatches = 0;
      for (size_t i = 0; i < got.size(); ++i) mismatches += got[i] != want[i];
      EXPECT_EQ(mismatches, 0u) << layout.lanes << " lanes × " << layout.groups << " groups, "
                                << (single ? "float" : "double");
      for (double u : got) ASSERT_TRUE(u >= 0.0 && u < 1.0) << u;
    }
  }
}

TEST(RngDevice, TheDefaultLayoutAndOneRayPerWorkItemAgreeAndBatchesSplitAnywhere) {
  Context ctx;
  const uint32_t draws = 4, count = 777;
  const arcus::DeviceEntry& device = ctx.ctx->runtime->entry();
  const arcus::Layout native = arcus::choose_layout(device, 4);
  std::vector<double> scalar;
  {
    ScopedEnv lanes("ARCUS_LANES", "1"), groups("ARCUS_GROUPS", "1");
    const arcus::Layout one = arcus::choose_layout(device, 4);
    ASSERT_EQ(one.per_item(), 1u);
    scalar = arcus::rng_fill(ctx, one, false, kSeed, 0, draws, count);
  }
  EXPECT_EQ(arcus::rng_fill(ctx, native, false, kSeed, 0, draws, count), scalar);
  // The same items in two batches, cut at an odd place.
  std::vector<double> split = arcus::rng_fill(ctx, native, false, kSeed, 0, draws, 333);
  const std::vector<double> rest = arcus::rng_fill(ctx, native, false, kSeed, 333, draws, count - 333);
  split.insert(split.end(), rest.begin(), rest.end());
  EXPECT_EQ(split, scalar);
}

}  // namespace
