// The colour-matching functions (src/spectral/cie, embedded from
// data/spectra/cie1931_2deg_5nm.csv), the band weights a spectral renderer sums with,
// and sRGB (src/spectral/srgb): pure host code.  The table is checked the way
// data/spectra/README.md describes: ȳ(555) = 1, the three functions enclose the same
// area, the published sums and spectral-locus chromaticities.
#include <gtest/gtest.h>

#include <cmath>
#include <fstream>
#include <functional>
#include <sstream>
#include <string>
#include <vector>

#include "core/error.h"
#include "spectral/cie.h"
#include "spectral/srgb.h"

#ifndef ARCUS_SOURCE_DIR
#define ARCUS_SOURCE_DIR "."
#endif

namespace {

using namespace arcus::spectral;
using Xyz = std::array<double, 3>;

double chroma_x(const Xyz& v) { return v[0] / (v[0] + v[1] + v[2]); }
double chroma_y(const Xyz& v) { return v[1] / (v[0] + v[1] + v[2]); }
Xyz cmf(double nm) { return {cmf_x(nm), cmf_y(nm), cmf_z(nm)}; }

// Sum of each function over the table's rows (360, 365, ..., 830 nm).
Xyz row_sums() {
  Xyz s{0, 0, 0};
  for (int nm = 360; nm <= 830; nm += 5)
    for (int c = 0; c < 3; ++c) s[c] += cmf(nm)[c];
  return s;
}

// n wavelengths at the centres of n equal bands over 360–830 nm (how a renderer
// stratifies them).
std::vector<double> centred(int n) {
  std::vector<double> nm(n);
  for (int i = 0; i < n; ++i) nm[i] = 360.0 + (i + 0.5) * 470.0 / n;
  return nm;
}

Xyz flat_xyz(const std::vector<double>& nm) {
  std::vector<double> ones(nm.size(), 1.0);
  Xyz xyz;
  spectrum_to_xyz(nm.data(), ones.data(), nm.size(), xyz.data());
  return xyz;
}

arcus_status status_of(const std::function<void()>& f) {
  try {
    f();
  } catch (const arcus::Error& e) {
    return e.status();
  }
  return ARCUS_SUCCESS;
}

TEST(Cmf, EmbeddedTableIsTheCsv) {
  std::ifstream in(std::string(ARCUS_SOURCE_DIR) + "/data/spectra/cie1931_2deg_5nm.csv");
  ASSERT_TRUE(in) << "data/spectra/cie1931_2deg_5nm.csv";
  std::string line;
  std::getline(in, line);
  EXPECT_EQ(line, "wavelength_nm,x_bar,y_bar,z_bar");
  int rows = 0;
  while (std::getline(in, line)) {
    std::istringstream s(line);
    std::string field[4];
    for (auto& f : field) std::getline(s, f, ',');
    const double nm = std::stod(field[0]);
    EXPECT_EQ(nm, 360.0 + 5.0 * rows) << line;
    // The generated .inc holds the CSV's own text, so the doubles are identical.
    EXPECT_EQ(cmf_x(nm), std::stod(field[1])) << line;
    EXPECT_EQ(cmf_y(nm), std::stod(field[2])) << line;
    EXPECT_EQ(cmf_z(nm), std::stod(field[3])) << line;
    ++rows;
  }
  EXPECT_EQ(rows, 95);
}

TEST(Cmf, PeakOfYIsOneAt555) {
  EXPECT_EQ(cmf_y(555), 1.0);
  for (int nm = 360; nm <= 830; nm += 5) EXPECT_LE(cmf_y(nm), 1.0) << nm;
}

TEST(Cmf, EqualEnergyWhiteAndPublishedSums) {
  const Xyz s = row_sums();
  const double mean = (s[0] + s[1] + s[2]) / 3;
  for (double v : s) EXPECT_NEAR(v / mean, 1.0, 1e-3);
  // Σȳ·Δλ = 106.857 nm, the area under V(λ) at 5 nm; x̄ and z̄ enclose 106.866 and 106.893.
  EXPECT_NEAR(s[1] * 5, 106.857, 1e-3);
  EXPECT_NEAR(s[0] * 5, 106.866, 1e-3);
  EXPECT_NEAR(s[2] * 5, 106.893, 1e-3);
  EXPECT_NEAR(chroma_x(s), 1.0 / 3, 1e-3);
  EXPECT_NEAR(chroma_y(s), 1.0 / 3, 1e-3);
}

TEST(Cmf, SpectralLocusMatchesPublishedChromaticities) {
  // CIE 15:2004's spectral locus (x, y), to 4 digits.
  const struct {
    double nm, x, y;
  } locus[] = {{380, 0.1741, 0.0050}, {450, 0.1566, 0.0177}, {520, 0.0743, 0.8338},
               {600, 0.6270, 0.3725}, {700, 0.7347, 0.2653}};
  for (const auto& p : locus) {
    EXPECT_NEAR(chroma_x(cmf(p.nm)), p.x, 1e-3) << p.nm;
    EXPECT_NEAR(chroma_y(cmf(p.nm)), p.y, 1e-3) << p.nm;
  }
}

TEST(Cmf, InterpolatesLinearlyAndIsZeroOutside) {
  EXPECT_DOUBLE_EQ(cmf_y(557.5), 0.5 * (1.0 + 0.995));
  EXPECT_DOUBLE_EQ(cmf_x(601), 0.8 * 1.0622 + 0.2 * 1.0456);
  EXPECT_EQ(cmf_x(830), 0.000001251141);
  for (double nm : {359.999, 830.001, -1.0, 1e300, std::nan("")}) {
    EXPECT_EQ(cmf_x(nm), 0.0) << nm;
    EXPECT_EQ(cmf_y(nm), 0.0) << nm;
    EXPECT_EQ(cmf_z(nm), 0.0) << nm;
  }
}

TEST(Cmf, IntegralIsExactForTheInterpolatedFunctions) {
  // Whole table: the row sums by the trapezoid rule, less half of each end row.
  const Xyz all = cmf_integral(360, 830), s = row_sums();
  for (int c = 0; c < 3; ++c) EXPECT_NEAR(all[c], 5 * s[c] - 2.5 * (cmf(360)[c] + cmf(830)[c]), 1e-12);
  // Additive over any split, including inside a row; zero outside and for empty ranges.
  for (double cut : {362.5, 500.0, 555.3, 829.0}) {
    const Xyz lo = cmf_integral(300, cut), hi = cmf_integral(cut, 900);
    for (int c = 0; c < 3; ++c) EXPECT_NEAR(lo[c] + hi[c], all[c], 1e-12) << cut;
  }
  // Within one row the function is a line: the area is the width times the midpoint value.
  EXPECT_NEAR(cmf_integral(556, 559)[1], 3 * cmf_y(557.5), 1e-15);
  EXPECT_EQ(cmf_integral(200, 359)[1], 0.0);
  EXPECT_EQ(cmf_integral(500, 500)[1], 0.0);
  EXPECT_EQ(cmf_integral(600, 500)[1], 0.0);
}

TEST(BandWeights, FlatSpectrumIsEqualEnergyWhiteWithAnyNumberOfSamples) {
  std::vector<double> grid_81;  // 380, 385, ..., 780 nm
  for (int nm = 380; nm <= 780; nm += 5) grid_81.push_back(nm);
  for (const auto& nm : {centred(8), centred(16), grid_81, centred(3), std::vector<double>{550}}) {
    const Xyz xyz = flat_xyz(nm);
    EXPECT_NEAR(xyz[1], 1.0, 1e-12) << nm.size() << " samples";
    EXPECT_NEAR(chroma_x(xyz), 1.0 / 3, 1e-4) << nm.size() << " samples";
    EXPECT_NEAR(chroma_y(xyz), 1.0 / 3, 1e-4) << nm.size() << " samples";
    // The same through band_weights directly, as the renderer sums.
    const auto w = band_weights(nm);
    ASSERT_EQ(w.size(), nm.size());
    double y = 0;
    for (const auto& b : w) y += b[1];
    EXPECT_NEAR(y, 1.0, 1e-12);
  }
}

TEST(BandWeights, EachBandIsTheIntegralBetweenMidpoints) {
  const std::vector<double> nm = {400, 500, 600, 700};
  const auto w = band_weights(nm);
  const double total = cmf_integral(360, 830)[1];
  const double edges[] = {360, 450, 550, 650, 830};
  for (int i = 0; i < 4; ++i)
    for (int c = 0; c < 3; ++c) EXPECT_NEAR(w[i][c], cmf_integral(edges[i], edges[i + 1])[c] / total, 1e-15);
  // Samples outside the table: bands wholly outside it are empty, the rest still add
  // up to the whole.
  const auto out = band_weights({300, 310, 550, 900, 950});
  EXPECT_EQ(out[0][1], 0.0);  // 360 to 305 nm
  EXPECT_NEAR(out[1][1], cmf_integral(360, 430)[1] / total, 1e-15);
  EXPECT_EQ(out[4][1], 0.0);  // 925 to 830 nm
  double sum = 0;
  for (const auto& b : out) sum += b[1];
  EXPECT_NEAR(sum, 1.0, 1e-12);
}

TEST(BandWeights, DenseSamplesConvergeToTheIntegral) {
  // A smooth spectrum (a Gaussian around 530 nm): at 5 nm the band rule agrees with a
  // 0.05 nm reference to 1e-3, and at 8 samples it is still the right colour roughly.
  auto spectrum = [](double nm) { return std::exp(-0.5 * std::pow((nm - 530) / 40, 2)); };
  auto xyz_of = [&](double step) {
    std::vector<double> nm, v;
    for (double l = 360; l <= 830 + 1e-9; l += step) {
      nm.push_back(l);
      v.push_back(spectrum(l));
    }
    Xyz xyz;
    spectrum_to_xyz(nm.data(), v.data(), nm.size(), xyz.data());
    return xyz;
  };
  const Xyz reference = xyz_of(0.05), coarse = xyz_of(5);
  for (int c = 0; c < 3; ++c) EXPECT_NEAR(coarse[c] / reference[c], 1.0, 1e-3) << c;
  std::vector<double> nm = centred(8), v;
  for (double l : nm) v.push_back(spectrum(l));
  Xyz few;
  spectrum_to_xyz(nm.data(), v.data(), nm.size(), few.data());
  EXPECT_NEAR(chroma_x(few), chroma_x(reference), 0.03);
  EXPECT_NEAR(chroma_y(few), chroma_y(reference), 0.03);
}

TEST(BandWeights, RejectsBadWavelengths) {
  EXPECT_EQ(status_of([] { band_weights({}); }), ARCUS_ERROR_INVALID_ARGUMENT);
  EXPECT_EQ(status_of([] { band_weights({500, 500}); }), ARCUS_ERROR_INVALID_ARGUMENT);
  EXPECT_EQ(status_of([] { band_weights({600, 500}); }), ARCUS_ERROR_INVALID_ARGUMENT);
  EXPECT_EQ(status_of([] { band_weights({500, std::nan("")}); }), ARCUS_ERROR_INVALID_ARGUMENT);
  EXPECT_EQ(status_of([] { band_weights({-INFINITY, 500}); }), ARCUS_ERROR_INVALID_ARGUMENT);
  double xyz[3], one = 1;
  EXPECT_EQ(status_of([&] { spectrum_to_xyz(nullptr, &one, 1, xyz); }), ARCUS_ERROR_INVALID_ARGUMENT);
  EXPECT_EQ(status_of([&] { spectrum_to_xyz(&one, &one, 0, xyz); }), ARCUS_ERROR_INVALID_ARGUMENT);
  try {
    band_weights({400, 450, 420});
    ADD_FAILURE() << "no error";
  } catch (const arcus::Error& e) {
    EXPECT_NE(std::string(e.what()).find("450 then 420"), std::string::npos) << e.what();
  }
}

TEST(Srgb, D65WhiteIsOne) {
  const Xyz rgb = xyz_to_linear_srgb(kD65White);
  for (double v : rgb) EXPECT_NEAR(v, 1.0, 1e-12);
  // The D65 the printed chromaticity (0.3127, 0.3290) gives lands within 3e-4.
  const Xyz printed{0.3127 / 0.3290, 1.0, (1 - 0.3127 - 0.3290) / 0.3290};
  for (double v : xyz_to_linear_srgb(printed)) EXPECT_NEAR(v, 1.0, 3e-4);
}

TEST(Srgb, PrimariesAndLuminances) {
  // IEC 61966-2-1: chromaticities of R, G, B and their luminances (0.2126, 0.7152, 0.0722).
  const double xy[3][2] = {{0.64, 0.33}, {0.30, 0.60}, {0.15, 0.06}};
  const double luminance[3] = {0.2126, 0.7152, 0.0722};
  for (int c = 0; c < 3; ++c) {
    Xyz rgb{0, 0, 0};
    rgb[c] = 1;
    const Xyz xyz = linear_srgb_to_xyz(rgb);
    EXPECT_NEAR(chroma_x(xyz), xy[c][0], 1e-12) << c;
    EXPECT_NEAR(chroma_y(xyz), xy[c][1], 1e-12) << c;
    EXPECT_NEAR(xyz[1], luminance[c], 1e-4) << c;
    const Xyz back = xyz_to_linear_srgb(xyz);
    for (int k = 0; k < 3; ++k) EXPECT_NEAR(back[k], rgb[k], 1e-12) << c << k;
  }
}

TEST(Srgb, MatrixAgreesWithThePrintedOne) {
  const double printed[3][3] = {{3.2406, -1.5372, -0.4986}, {-0.9689, 1.8758, 0.0415}, {0.0557, -0.2040, 1.0570}};
  for (int c = 0; c < 3; ++c) {
    Xyz unit{0, 0, 0};
    unit[c] = 1;
    const Xyz column = xyz_to_linear_srgb(unit);
    for (int r = 0; r < 3; ++r) EXPECT_NEAR(column[r], printed[r][c], 5e-4) << r << c;
  }
}

TEST(Srgb, TransferFunctionRoundTrips) {
  EXPECT_EQ(srgb_encode(0), 0.0);
  EXPECT_NEAR(srgb_encode(1), 1.0, 1e-15);
  EXPECT_NEAR(srgb_decode(1), 1.0, 1e-15);
  EXPECT_NEAR(srgb_encode(0.0031308), 0.0031308 * 12.92, 1e-12);
  EXPECT_NEAR(srgb_encode(0.0031308 * (1 + 1e-9)), 0.04045, 1e-6);  // continuous at the knee
  EXPECT_NEAR(srgb_encode(0.18), 0.461356, 1e-6);                     // middle grey
  double last = -1e9;
  for (double x = -2; x <= 4; x += 1.0 / 1024) {
    const double e = srgb_encode(x);
    EXPECT_GT(e, last) << x;
    last = e;
    EXPECT_NEAR(srgb_decode(e), x, 1e-13 * std::max(1.0, std::fabs(x))) << x;
    EXPECT_NEAR(srgb_encode(srgb_decode(x)), x, 1e-13 * std::max(1.0, std::fabs(x))) << x;
  }
}

TEST(Srgb, EightBitEncodingRoundsAndClamps) {
  EXPECT_EQ(srgb_encode_8bit(0), 0);
  EXPECT_EQ(srgb_encode_8bit(1), 255);
  EXPECT_EQ(srgb_encode_8bit(7.5), 255);
  EXPECT_EQ(srgb_encode_8bit(-0.5), 0);
  EXPECT_EQ(srgb_encode_8bit(std::nan("")), 0);
  EXPECT_EQ(srgb_encode_8bit(INFINITY), 255);
  EXPECT_EQ(srgb_encode_8bit(0.5), 188);  // 0.7354 · 255 = 187.5
  for (int k = 0; k < 256; ++k) EXPECT_EQ(srgb_encode_8bit(srgb_decode(k / 255.0)), k) << k;
  // Half a step either side of a code rounds to it.
  for (int k = 1; k < 255; ++k) {
    EXPECT_EQ(srgb_encode_8bit(srgb_decode((k - 0.49) / 255.0)), k) << k;
    EXPECT_EQ(srgb_encode_8bit(srgb_decode((k + 0.49) / 255.0)), k) << k;
  }
}

TEST(Srgb, EqualEnergySpectrumIsWhitishThroughTheWholeChain) {
  // Equal-energy white (E) is not D65: in sRGB it is a little pink, the same for any
  // number of samples.
  for (int n : {8, 16, 81}) {
    const Xyz xyz = flat_xyz(centred(n));
    const Xyz rgb = xyz_to_linear_srgb(xyz);
    EXPECT_NEAR(rgb[0], 1.2050, 2e-3) << n;
    EXPECT_NEAR(rgb[1], 0.9482, 2e-3) << n;
    EXPECT_NEAR(rgb[2], 0.9092, 2e-3) << n;
  }
}

// The RGB → spectrum basis: each S_c's colour under the grid's own band weights is
// primary c (so an image round-trips), for coarse and fine grids over 380–700 nm; the
// spectra are non-negative there (what the header promises: an in-gamut colour gives a
// physical spectrum); and a grid that misses the red Gaussian is refused.  Tolerance:
// the colours come from a 3 × 3 solve in double, 1e-12.
TEST(SrgbBasis, SpectraHaveThePrimariesColoursAndAreNonNegative) {
  for (int count : {8, 12, 16, 33, 66, 100, 200}) {
    std::vector<double> nm;
    for (int i = 0; i < count; ++i) nm.push_back(380 + 320.0 * i / (count - 1));
    const auto basis = srgb_basis_spectra(nm);
    const auto weights = band_weights(nm);
    for (int c = 0; c < 3; ++c) {
      std::array<double, 3> xyz{};
      for (int l = 0; l < count; ++l)
        for (int j = 0; j < 3; ++j) xyz[j] += basis[l][c] * weights[l][j];
      const auto rgb = xyz_to_linear_srgb(xyz);
      for (int k = 0; k < 3; ++k) EXPECT_NEAR(rgb[k], k == c ? 1.0 : 0.0, 1e-12) << count << " samples, primary " << c;
      for (int l = 0; l < count; ++l) EXPECT_GE(basis[l][c], 0.0) << count << " samples at " << nm[l] << " nm";
    }
  }
  EXPECT_THROW(srgb_basis_spectra({400, 450, 500, 550}), arcus::Error);  // no red
  EXPECT_THROW(srgb_basis_spectra({450, 550}), arcus::Error);
}

}  // namespace
