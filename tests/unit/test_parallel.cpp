// parallel_for (src/core/parallel.h): every index once, and an exception from any call
// reaches the caller after the others have finished.
#include <gtest/gtest.h>

#include <atomic>
#include <stdexcept>
#include <vector>

#include "core/parallel.h"

namespace {

TEST(ParallelFor, CallsEveryIndexOnce) {
  std::vector<std::atomic<int>> calls(1000);
  arcus::parallel_for(calls.size(), [&](size_t i) { ++calls[i]; });
  for (const auto& c : calls) EXPECT_EQ(c.load(), 1);
  arcus::parallel_for(0, [](size_t) { FAIL() << "no index to call"; });
}

TEST(ParallelFor, RethrowsTheFirstFailureAfterAllCallsEnd) {
  std::atomic<int> done{0};
  EXPECT_THROW(arcus::parallel_for(100,
                                   [&](size_t i) {
                                     ++done;
                                     if (i == 37) throw std::runtime_error("index 37");
                                   }),
               std::runtime_error);
  EXPECT_EQ(done.load(), 100);
}

}  // namespace
