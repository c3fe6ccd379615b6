// Host tests of kernels/common/philox.h: Philox4x32 known answers, the stream mapping,
// the range and moments of the uniforms, distinct streams, determinism.  The kernels
// compile the same text; a device run must match these host values bit for bit.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <set>
#include <vector>

#include "common/philox.h"

namespace {

struct Kat {
  int rounds;
  arcus_u32 ctr[4], key[2], out[4];
};

// Known-answer vectors of Random123's tests/kat_vectors (Salmon et al., SC11), the
// "philox4x32 7" and "philox4x32 10" lines, as cut and pasted by D. E. Shaw Research into
// github.com/DEShawResearch/Random123-Boost, libs/random/test/test_philox.cpp
// (commit 916db91ae4c6fd8324ef054a518851321ab41f91), test_kat_philox4x32.  The 10-round
// lines agree with copies of kat_vectors quoted in other projects.  Columns: rounds,
// counter[4], key[2], expected output[4].  The 7-round lines pin the key schedule apart
// from the round count.
const Kat kKats[] = {
    {7, {0x00000000, 0x00000000, 0x00000000, 0x00000000}, {0x00000000, 0x00000000},
     {0x5f6fb709, 0x0d893f64, 0x4f121f81, 0x4f730a48}},
    {7, {0xffffffff, 0xffffffff, 0xffffffff, 0xffffffff}, {0xffffffff, 0xffffffff},
     {0x5207ddc2, 0x45165e59, 0x4d8ee751, 0x8c52f662}},
    {7, {0x243f6a88, 0x85a308d3, 0x13198a2e, 0x03707344}, {0xa4093822, 0x299f31d0},
     {0x4dfccaba, 0x190a87f0, 0xc47362ba, 0xb6b5242a}},
    {10, {0x00000000, 0x00000000, 0x00000000, 0x00000000}, {0x00000000, 0x00000000},
     {0x6627e8d5, 0xe169c58d, 0xbc57ac4c, 0x9b00dbd8}},
    {10, {0xffffffff, 0xffffffff, 0xffffffff, 0xffffffff}, {0xffffffff, 0xffffffff},
     {0x408f276d, 0x41c83b0e, 0xa20bc7c6, 0x6d5451fd}},
    {10, {0x243f6a88, 0x85a308d3, 0x13198a2e, 0x03707344}, {0xa4093822, 0x299f31d0},
     {0xd16cfe09, 0x94fdcceb, 0x5001e420, 0x24126ea1}},
};

TEST(Philox, KnownAnswerVectors) {
  for (const Kat& k : kKats) {
    arcus_u32 out[4];
    arcus_philox4x32_r(k.rounds, k.ctr, k.key, out);
    for (int i = 0; i < 4; ++i) EXPECT_EQ(out[i], k.out[i]) << "rounds " << k.rounds << " word " << i;
    if (k.rounds == 10) {
      arcus_philox4x32_10(k.ctr, k.key, out);
      for (int i = 0; i < 4; ++i) EXPECT_EQ(out[i], k.out[i]) << "philox4x32_10 word " << i;
    }
  }
}

// The documented mapping: key {seed lo, seed hi}, counter {index lo, index hi, draw/2, 0}.
TEST(Philox, StreamMappingIsTheDocumentedCounterAndKey) {
  const uint64_t seeds[] = {0, 1, 0x0123456789abcdefull, ~0ull};
  const uint64_t indices[] = {0, 7, 0xfffffffful, 0x100000000ull, ~0ull};
  const uint32_t blocks[] = {0, 1, 12345, 0xffffffffu};
  for (uint64_t s : seeds)
    for (uint64_t i : indices)
      for (uint32_t b : blocks) {
        const arcus_u32 ctr[4] = {(arcus_u32)i, (arcus_u32)(i >> 32), b, 0};
        const arcus_u32 key[2] = {(arcus_u32)s, (arcus_u32)(s >> 32)};
        arcus_u32 want[4], got[4];
        arcus_philox4x32_10(ctr, key, want);
        arcus_rng_block(s, i, b, got);
        for (int w = 0; w < 4; ++w) ASSERT_EQ(got[w], want[w]);
        for (uint32_t half = 0; half < 2; ++half) {
          const uint32_t d = 2 * b + half;  // wraps for b = 2^32 − 1: only check d/2 == b
          if (d / 2 != b) continue;
          const uint64_t word = ((uint64_t)want[2 * half] << 32) | want[2 * half + 1];
          EXPECT_EQ(arcus_rng_uniform_double(s, i, d), (double)(word >> 11) * 0x1.0p-53);
          EXPECT_EQ(arcus_rng_uniform_float(s, i, d), (float)(word >> 40) * 0x1.0p-24f);
        }
      }
  // Seed 0, index 0, draws 0 and 1: counter and key all zero, the first 10-round vector.
  EXPECT_EQ(arcus_rng_uniform_double(0, 0, 0), (double)((0x6627e8d5ull << 21) | (0xe169c58dull >> 11)) * 0x1.0p-53);
  EXPECT_EQ(arcus_rng_uniform_double(0, 0, 1), (double)((0xbc57ac4cull << 21) | (0x9b00dbd8ull >> 11)) * 0x1.0p-53);
  EXPECT_EQ(arcus_rng_uniform_float(0, 0, 0), (float)(0x6627e8d5u >> 8) * 0x1.0p-24f);
}

TEST(Philox, UniformsStayInUnitInterval) {
  // Extreme words: all zeros gives 0, all ones the largest value below 1.
  EXPECT_EQ(arcus_u01_double(0, 0), 0.0);
  EXPECT_EQ(arcus_u01_double(0xffffffffu, 0xffffffffu), 1.0 - 0x1.0p-53);
  EXPECT_LT(arcus_u01_double(0xffffffffu, 0xffffffffu), 1.0);
  EXPECT_EQ(arcus_u01_float(0), 0.0f);
  EXPECT_EQ(arcus_u01_float(0xffffffffu), 1.0f - 0x1.0p-24f);
  EXPECT_LT(arcus_u01_float(0xffffffffu), 1.0f);
  for (uint64_t i = 0; i < 1000; ++i)
    for (uint32_t d = 0; d < 100; ++d) {
      const double u = arcus_rng_uniform_double(99, i, d);
      const float f = arcus_rng_uniform_float(99, i, d);
      ASSERT_TRUE(u >= 0.0 && u < 1.0) << u;
      ASSERT_TRUE(f >= 0.0f && f < 1.0f) << f;
      // The float draw is the double draw rounded down to 24 bits.
      ASSERT_EQ((double)f, std::floor(u * 0x1.0p24) * 0x1.0p-24);
    }
}

// 10^6 draws (1000 items × 1000 draws, so both the index and the draw axis vary).
// For U(0,1): mean 1/2 with standard error sqrt(1/12)/sqrt(N) = 2.9e-4; the sample
// variance 1/12 with standard error sqrt((μ4 − σ⁴)/N) = sqrt(1/80 − 1/144)/1000 = 7.5e-5.
// Bounds at 5 standard errors: a correct generator fails with probability < 1e-6.
TEST(Philox, MomentsMatchUniform) {
  const int n_items = 1000, n_draws = 1000;
  const double n = (double)n_items * n_draws;
  double sum_d = 0, sum2_d = 0, sum_f = 0, sum2_f = 0;
  for (int i = 0; i < n_items; ++i)
    for (int d = 0; d < n_draws; ++d) {
      const double u = arcus_rng_uniform_double(0x5eed, (uint64_t)i, (uint32_t)d);
      const double f = arcus_rng_uniform_float(0xf10a7, (uint64_t)i, (uint32_t)d);
      sum_d += u;
      sum2_d += u * u;
      sum_f += f;
      sum2_f += f * f;
    }
  const double se_mean = std::sqrt(1.0 / 12.0 / n), se_var = std::sqrt((1.0 / 80.0 - 1.0 / 144.0) / n);
  const double mean_d = sum_d / n, var_d = sum2_d / n - mean_d * mean_d;
  const double mean_f = sum_f / n, var_f = sum2_f / n - mean_f * mean_f;
  EXPECT_NEAR(mean_d, 0.5, 5 * se_mean);
  EXPECT_NEAR(var_d, 1.0 / 12.0, 5 * se_var);
  // Floats are rounded down to 2^-24: a bias of 2^-25, far below the tolerance.
  EXPECT_NEAR(mean_f, 0.5, 5 * se_mean);
  EXPECT_NEAR(var_f, 1.0 / 12.0, 5 * se_var);
}

// Every one of the 53 bits of a double draw is a fair coin: catches a word dropped or
// mis-shifted when two 32-bit words become 53 bits, which the moments would not see.
// 10^5 draws: standard error 0.5/sqrt(N) = 1.6e-3, bound at 5 of them.
TEST(Philox, EveryDoubleBitIsRandom) {
  const int n = 100000;
  std::vector<int> ones(53, 0);
  for (int k = 0; k < n; ++k) {
    const uint64_t m = (uint64_t)(arcus_rng_uniform_double(3, (uint64_t)k / 10, (uint32_t)(k % 10)) * 0x1.0p53);
    for (int b = 0; b < 53; ++b) ones[b] += (int)((m >> b) & 1);
  }
  for (int b = 0; b < 53; ++b) EXPECT_NEAR(ones[b] / (double)n, 0.5, 5 * 0.5 / std::sqrt((double)n)) << "bit " << b;
}

// Sample correlation of two sequences; about N(0, 1/N) for independent uniforms.
double correlation(const std::vector<double>& a, const std::vector<double>& b) {
  double ma = 0, mb = 0;
  for (size_t k = 0; k < a.size(); ++k) ma += a[k], mb += b[k];
  ma /= a.size();
  mb /= b.size();
  double sab = 0, saa = 0, sbb = 0;
  for (size_t k = 0; k < a.size(); ++k) {
    sab += (a[k] - ma) * (b[k] - mb);
    saa += (a[k] - ma) * (a[k] - ma);
    sbb += (b[k] - mb) * (b[k] - mb);
  }
  return sab / std::sqrt(saa * sbb);
}

TEST(Philox, DifferentIndicesGiveDifferentStreams) {
  // 10^4 items, including ones differing only in the high index word: the first four
  // draws of every item are distinct (a repeat of 53 random bits: chance ~1e-8).
  std::set<std::vector<double>> seen;
  for (uint64_t i = 0; i < 10000; ++i)
    for (uint64_t hi : {0ull, 1ull << 32, 1ull << 63}) {
      std::vector<double> s;
      for (uint32_t d = 0; d < 4; ++d) s.push_back(arcus_rng_uniform_double(1, i + hi, d));
      EXPECT_TRUE(seen.insert(s).second) << "index " << (i + hi);
    }
  // Neighbouring items are uncorrelated: draw d of items 2k and 2k + 1 over 10^5 pairs,
  // |r| below 5 standard errors (1/sqrt(N) = 3.2e-3).
  const int n = 100000;
  std::vector<double> a(n), b(n);
  for (int k = 0; k < n; ++k) {
    a[k] = arcus_rng_uniform_double(1, 2 * (uint64_t)(k / 8), (uint32_t)(k % 8));
    b[k] = arcus_rng_uniform_double(1, 2 * (uint64_t)(k / 8) + 1, (uint32_t)(k % 8));
  }
  EXPECT_LT(std::fabs(correlation(a, b)), 5 / std::sqrt((double)n));
}

TEST(Philox, DifferentSeedsGiveDifferentStreams) {
  // Seeds differing in one bit of the low or the high key word.
  const uint64_t seeds[] = {0, 1, 2, 1ull << 31, 1ull << 32, 1ull << 63, ~0ull};
  std::set<std::vector<double>> seen;
  for (uint64_t s : seeds)
    for (uint64_t i = 0; i < 1000; ++i) {
      std::vector<double> v;
      for (uint32_t d = 0; d < 4; ++d) v.push_back(arcus_rng_uniform_double(s, i, d));
      EXPECT_TRUE(seen.insert(v).second) << "seed " << s << " index " << i;
    }
  const int n = 100000;
  std::vector<double> a(n), b(n);
  for (int k = 0; k < n; ++k) {
    a[k] = arcus_rng_uniform_double(1000, (uint64_t)(k / 8), (uint32_t)(k % 8));
    b[k] = arcus_rng_uniform_double(1001, (uint64_t)(k / 8), (uint32_t)(k % 8));
  }
  EXPECT_LT(std::fabs(correlation(a, b)), 5 / std::sqrt((double)n));
}

// A draw is a pure function of (seed, index, draw): the same in any order of evaluation
// and however the items are split into batches.
TEST(Philox, Deterministic) {
  const uint64_t seed = 0x0123456789abcdefull, first = 0xfffffff0ull;  // crosses 2^32
  const int n_items = 64, n_draws = 9;
  std::vector<double> forward(n_items * n_draws), backward(n_items * n_draws), split(n_items * n_draws);
  for (int i = 0; i < n_items; ++i)
    for (int d = 0; d < n_draws; ++d) forward[i * n_draws + d] = arcus_rng_uniform_double(seed, first + i, d);
  for (int i = n_items - 1; i >= 0; --i)
    for (int d = n_draws - 1; d >= 0; --d) backward[i * n_draws + d] = arcus_rng_uniform_double(seed, first + i, d);
  // Batches of 5 items, each numbered from its own first index.
  for (int b0 = 0; b0 < n_items; b0 += 5)
    for (int j = 0; j < 5 && b0 + j < n_items; ++j)
      for (int d = 0; d < n_draws; ++d)
        split[(b0 + j) * n_draws + d] = arcus_rng_uniform_double(seed, (first + b0) + j, d);
  for (size_t k = 0; k < forward.size(); ++k) {
    EXPECT_EQ(forward[k], backward[k]);
    EXPECT_EQ(forward[k], split[k]);
  }
  EXPECT_EQ(arcus_rng_uniform_float(seed, first, 3), arcus_rng_uniform_float(seed, first, 3));
}

}  // namespace
