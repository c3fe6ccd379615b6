// The estimate's highlight cut (src/translucency/estimate.h, thesis §3.3.1 after Khan et
// al. 2006) on luminance distributions whose answer is known: diffuse pixels spread
// evenly below 1 and a highlight's bump well above them are cut between the two; the
// diffuse pixels alone, however noisy their histogram, lose nothing.
#include <gtest/gtest.h>

#include <cmath>
#include <random>
#include <vector>

#include "translucency/estimate.h"

namespace {

using arcus::translucency::highlight_cut;

// n luminances: a falling ramp on [0, 1) (more dark pixels than bright, as a lit
// sphere's), drawn at random.
std::vector<double> diffuse(size_t n, unsigned seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> u(0, 1);
  std::vector<double> y(n);
  for (double& v : y) v = 1 - std::sqrt(u(rng));
  return y;
}

TEST(TranslucencyHighlights, ABumpAboveTheDiffusePixelsIsCutOff) {
  for (unsigned seed = 1; seed <= 5; ++seed) {
    std::vector<double> y = diffuse(20000, seed);
    std::mt19937 rng(seed + 100);
    std::normal_distribution<double> bump(2.0, 0.1);
    for (int i = 0; i < 600; ++i) y.push_back(bump(rng));
    const double cut = highlight_cut(y);
    EXPECT_GT(cut, 0.9) << seed;  // keeps (nearly) every diffuse pixel
    EXPECT_LT(cut, 1.7) << seed;  // drops the bump's
  }
}

TEST(TranslucencyHighlights, DiffusePixelsAloneLoseNothing) {
  for (unsigned seed = 1; seed <= 5; ++seed) {
    for (size_t n : {3000, 20000}) {
      const std::vector<double> y = diffuse(n, seed);
      const double cut = highlight_cut(y);
      size_t dropped = 0;
      for (double v : y) dropped += v > cut;
      EXPECT_LT(dropped, n / 100) << "seed " << seed << ", " << n << " pixels: cut at " << cut;
    }
  }
  EXPECT_TRUE(std::isinf(highlight_cut({})));
  EXPECT_TRUE(std::isinf(highlight_cut({0, 0, 0})));
}

}  // namespace
