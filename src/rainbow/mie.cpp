// Lorenz–Mie and Debye series for a homogeneous sphere (see mie.h).  References:
// Bohren & Huffman 1983, "Absorption and Scattering of Light by Small Particles",
// ch. 4 (coefficients, amplitudes, efficiencies); Wiscombe 1980, Appl. Opt. 19, 1505,
// and NCAR/TN-140+STR (numerics); Hovenac & Lock 1992, JOSA A 9, 781 (Debye series).
#include "rainbow/mie.h"

#include <algorithm>
#include <cmath>
#include <sstream>
#include <string>
#include <utility>

#include "core/error.h"

namespace arcus::rainbow::mie {

namespace {

constexpr double kPi = 3.14159265358979323846;
const complex kI(0.0, 1.0);

std::string str(double v) {
  std::ostringstream s;
  s.precision(17);
  s << v;
  return s.str();
}

void check_sphere(double x, complex m) {
  require(std::isfinite(x) && x > 0, "mie: size parameter x must be finite and > 0 (got " + str(x) + ")");
  // N ≈ x partial waves are stored and summed; beyond this the arrays alone are gigabytes.
  require(x <= 1e8, "mie: size parameter x must be at most 1e8 (got " + str(x) + ")");
  require(std::isfinite(m.real()), "mie: refractive index m = n + i kappa: n must be finite (got " + str(m.real()) + ")");
  require(std::isfinite(m.imag()),
          "mie: refractive index m = n + i kappa: kappa must be finite (got " + str(m.imag()) + ")");
  require(m.real() > 0, "mie: refractive index m = n + i kappa: n must be > 0 (got " + str(m.real()) + ")");
  // e^{-iωt}: absorption is a positive imaginary part; a negative one would be gain, or
  // a caller using Wiscombe's/van de Hulst's sign convention.
  require(m.imag() >= 0, "mie: refractive index m = n + i kappa: kappa must be >= 0 (convention e^{-i omega t}; got " +
                             str(m.imag()) + ")");
}

void check_mu(const std::vector<double>& mu) {
  for (std::size_t j = 0; j < mu.size(); ++j)
    require(std::isfinite(mu[j]) && std::abs(mu[j]) <= 1.0,
            "mie: mu[" + std::to_string(j) + "] must be a cosine in [-1, 1] (got " + str(mu[j]) + ")");
}

// Σ_n (2n+1)/(n(n+1)) (a_n π_n + b_n τ_n) and (a_n τ_n + b_n π_n) at every μ, for several
// coefficient sets at once so π_n, τ_n are computed once.  n outside, angles inside, on
// contiguous real arrays, in Wiscombe's S± form (two real-times-complex products per set
// and angle).  A null pointer b means b = a (used for diffraction).
struct CoefficientSet {
  const complex* a;
  const complex* b;
  Amplitudes* out;
};

void angular_sums(int terms, const std::vector<CoefficientSet>& sets, const std::vector<double>& mu) {
  const std::size_t count = mu.size(), k_count = sets.size();
  std::vector<double> pi_prev(count, 0.0), pi_cur(count, 1.0), plus(count), minus(count);
  std::vector<double> sp_re(k_count * count, 0.0), sp_im(k_count * count, 0.0);
  std::vector<double> sm_re(k_count * count, 0.0), sm_im(k_count * count, 0.0);
  const double* __restrict mu_p = mu.data();
  for (int n = 1; n <= terms; ++n) {
    const double fn = n, ratio = (n + 1.0) / n;
    double* __restrict pp = pi_prev.data();
    double* __restrict pc = pi_cur.data();
    double* __restrict pl = plus.data();
    double* __restrict mi = minus.data();
    for (std::size_t j = 0; j < count; ++j) {
      const double s = mu_p[j] * pc[j], t = s - pp[j];
      const double tau = fn * t - pp[j];
      pl[j] = pc[j] + tau;
      mi[j] = pc[j] - tau;
      pp[j] = pc[j];
      pc[j] = s + ratio * t;
    }
    const double c = (2.0 * n + 1.0) / (fn * (n + 1.0));
    for (std::size_t k = 0; k < k_count; ++k) {
      const complex a = sets[k].a[n - 1], b = sets[k].b ? sets[k].b[n - 1] : a;
      const complex ap = c * (a + b), bp = c * (a - b);
      if (ap == 0.0 && bp == 0.0) continue;
      const double apr = ap.real(), api = ap.imag(), bpr = bp.real(), bpi = bp.imag();
      double* __restrict spr = sp_re.data() + k * count;
      double* __restrict spi = sp_im.data() + k * count;
      double* __restrict smr = sm_re.data() + k * count;
      double* __restrict smi = sm_im.data() + k * count;
      for (std::size_t j = 0; j < count; ++j) {
        spr[j] += apr * pl[j];
        spi[j] += api * pl[j];
        smr[j] += bpr * mi[j];
        smi[j] += bpi * mi[j];
      }
    }
  }
  for (std::size_t k = 0; k < k_count; ++k) {
    Amplitudes& out = *sets[k].out;
    out.s1.resize(count);
    out.s2.resize(count);
    for (std::size_t j = 0; j < count; ++j) {
      const complex sp(sp_re[k * count + j], sp_im[k * count + j]), sm(sm_re[k * count + j], sm_im[k * count + j]);
      out.s1[j] = 0.5 * (sp + sm);
      out.s2[j] = 0.5 * (sp - sm);
    }
  }
}

// The ratio q_n = ξ_n(z)/ξ_{n−1}(z) of the outgoing Riccati–Hankel function
// ξ^{(1)} = z h^{(1)}, by upward recurrence from q_1 = 1/z − i; ξ'_n/ξ_n = 1/q_n − n/z.
// Stable for Im z ≥ 0: upward, ξ^{(1)} dominates (for real z the χ part grows beyond
// n = z; for absorbing z, |ξ1/ξ2| grows from e^{−2 Im z} towards 1).  ξ^{(2)}(mx) would
// be the minimal solution there, so it is never recurred (see debye_coefficients).
struct HankelRatio {
  complex z_inv, q;
  int n = 1;
  explicit HankelRatio(complex z) : z_inv(1.0 / z), q(z_inv - kI) {}
  void next() {
    ++n;
    q = (2.0 * n - 1.0) * z_inv - 1.0 / q;
  }
  complex log_derivative() const { return 1.0 / q - static_cast<double>(n) * z_inv; }
};

// D_n(z) = ψ'_n(z)/ψ_n(z), n = 0..terms (index n), downward from D = 0.  Starting
// beyond the turning point n = |z| by d, the start's error is damped by about
// exp(−(2√2/3) d^{3/2}/|z|^{1/2}) (Debye asymptotics of ψ/χ) before reaching n ≤ |z|,
// where nothing damps it any more; d = 16 |z|^{1/3} + 16 makes that e^{−60}.  (Bohren &
// Huffman's + 15 alone is not enough for |z| in the thousands.)
std::vector<complex> log_derivative_psi(complex z, int terms) {
  const complex z_inv = 1.0 / z;
  const double az = std::abs(z);
  const int start = static_cast<int>(std::ceil(std::max<double>(terms, az) + 16.0 + 16.0 * std::cbrt(az)));
  std::vector<complex> d(terms + 1);
  complex dn = 0.0;
  for (int n = start; n > terms; --n) dn = static_cast<double>(n) * z_inv - 1.0 / (dn + static_cast<double>(n) * z_inv);
  d[terms] = dn;
  for (int n = terms; n >= 1; --n)
    d[n - 1] = static_cast<double>(n) * z_inv - 1.0 / (d[n] + static_cast<double>(n) * z_inv);
  return d;
}

}  // namespace

int series_terms(double x) {
  // Wiscombe's x + 4.05 x^{1/3} + 2 (1980, eq. R50) stops where |a_n| is still ~1e-7;
  // the backward directions weight term n by ~n², so at x = 10⁴ (water) S(180°) still
  // moves by 2e-5 relative beyond it.  x + 6 x^{1/3} + 2 puts the first omitted |a_n|
  // near 1e-11 (Debye asymptotics: |a_n| ~ exp(−(4√2/3)(n − x)^{3/2}/x^{1/2})), so every
  // direction is converged; it costs ~2 % more terms at x = 10⁴.
  const double n = x + 6.0 * std::cbrt(x) + 2.0;
  return std::max(1, static_cast<int>(n));
}

Coefficients coefficients(double x, complex m) {
  check_sphere(x, m);
  const int terms = series_terms(x);
  const complex z = m * x;
  const std::vector<complex> d = log_derivative_psi(z, terms);

  // ψ_n(x) and χ_n(x) upward (Bohren & Huffman's bhmie; ξ = ψ − iχ = x h^{(1)}); ψ
  // decays for n > x, but only to ~e^{−8} of χ by n = N, so the upward error stays small.
  Coefficients c;
  c.a.resize(terms);
  c.b.resize(terms);
  double psi_prev = std::cos(x), psi = std::sin(x);  // ψ_{−1}, ψ_0
  double chi_prev = -std::sin(x), chi = std::cos(x);
  const complex m_inv = 1.0 / m;
  for (int n = 1; n <= terms; ++n) {
    const double f = (2.0 * n - 1.0) / x;
    const double psi_n = f * psi - psi_prev, chi_n = f * chi - chi_prev;
    const complex xi_n(psi_n, -chi_n), xi_prev(psi, -chi);
    const double nx = n / x;
    const complex da = d[n] * m_inv + nx, db = m * d[n] + nx;
    c.a[n - 1] = (da * psi_n - psi) / (da * xi_n - xi_prev);
    c.b[n - 1] = (db * psi_n - psi) / (db * xi_n - xi_prev);
    psi_prev = psi;
    psi = psi_n;
    chi_prev = chi;
    chi = chi_n;
  }
  return c;
}

Result scatter(double x, complex m, const std::vector<double>& mu) {
  check_sphere(x, m);
  check_mu(mu);
  const Coefficients c = coefficients(x, m);
  const int terms = static_cast<int>(c.a.size());

  Result r;
  r.terms = terms;
  double ext = 0, sca = 0, gsum = 0;
  complex back = 0;
  for (int n = 1; n <= terms; ++n) {
    const complex a = c.a[n - 1], b = c.b[n - 1];
    const double w = 2.0 * n + 1.0;
    ext += w * (a.real() + b.real());
    sca += w * (std::norm(a) + std::norm(b));
    back += ((n % 2) ? -w : w) * (a - b);
    // Bohren & Huffman eq. 4.79 (g Q_sca), with a_{N+1} = b_{N+1} = 0.
    if (n < terms) {
      const complex a1 = c.a[n], b1 = c.b[n];
      gsum += n * (n + 2.0) / (n + 1.0) * (a * std::conj(a1) + b * std::conj(b1)).real();
    }
    gsum += w / (n * (n + 1.0)) * (a * std::conj(b)).real();
  }
  const double x2 = x * x;
  r.q_ext = 2.0 / x2 * ext;
  r.q_sca = 2.0 / x2 * sca;
  r.q_back = std::norm(back) / x2;
  r.g = sca > 0 ? 2.0 * gsum / sca : 0.0;

  angular_sums(terms, {{c.a.data(), c.b.data(), &r}}, mu);
  return r;
}

Polarised polarised_phase_function(const Amplitudes& s, double x, double q_sca) {
  require(std::isfinite(x) && x > 0, "mie: size parameter x must be finite and > 0 (got " + str(x) + ")");
  require(std::isfinite(q_sca) && q_sca > 0, "mie: q_sca must be finite and > 0 (got " + str(q_sca) + ")");
  require(s.s1.size() == s.s2.size(), "mie: s1 and s2 must have the same length");
  const double scale = 1.0 / (2.0 * kPi * x * x * q_sca);
  Polarised p;
  p.parallel.resize(s.s2.size());
  p.perpendicular.resize(s.s1.size());
  for (std::size_t j = 0; j < s.s1.size(); ++j) {
    p.parallel[j] = std::norm(s.s2[j]) * scale;
    p.perpendicular[j] = std::norm(s.s1[j]) * scale;
  }
  return p;
}

std::vector<double> phase_function(const Amplitudes& s, double x, double q_sca) {
  Polarised p = polarised_phase_function(s, x, q_sca);
  for (std::size_t j = 0; j < p.parallel.size(); ++j) p.parallel[j] += p.perpendicular[j];
  return std::move(p.parallel);
}

// One pass over the terms n: the Riccati–Bessel functions at x and m·x come out of one
// shared recurrence, each n's Debye terms need them all, so the pass is kept whole.
DebyeCoefficients debye_coefficients(double x, complex m, int max_p) {
  check_sphere(x, m);
  require(max_p >= 0 && max_p <= 1000, "mie: max_p must be in [0, 1000] (got " + std::to_string(max_p) + ")");
  const int terms = series_terms(x);
  const complex z = m * x;

  DebyeCoefficients dc;
  dc.a_p.assign(max_p + 1, std::vector<complex>(terms));
  dc.b_p.assign(max_p + 1, std::vector<complex>(terms));
  dc.a_rest.resize(terms);
  dc.b_rest.resize(terms);
  dc.a_diffraction.resize(terms);

  // Partial wave n is a ray with impact parameter (n + ½)/k (localization principle);
  // with unit incoming amplitude on ξ^{(2)}, the outgoing ξ^{(1)} amplitude is
  // R_ext + Σ_{p≥1} T_in R_int^{p−1} T_out and a_n, b_n = ½(1 − outgoing) (Hovenac &
  // Lock 1992 eq. 4; their R^{22}, T^{21}, R^{11}, T^{12}).  Matching u and u' across
  // r = a (u'_out = β u'_in, β = 1/m for a_n, m for b_n) gives, with the logarithmic
  // derivatives D1 = ξ1'/ξ1, D2 = ξ2'/ξ2 at x and D1m, D2m at mx, Q = ξ2(x)/ξ1(x),
  // P = ξ1(mx)/ξ2(mx) and den = D1 − β D2m:
  //   R_ext = Q (β D2m − D2)/den,   R_int = −P (D1 − β D1m)/den,
  //   T_in T_out = −Q P β (D1 − D2)(D2m − D1m)/den².
  // Only ratios and logarithmic derivatives appear, all bounded, so nothing overflows
  // where ξ(x) or ξ(mx) themselves would (n ≫ x, n ≫ |mx|).
  //
  // Stability.  Upward, ξ1(mx) dominates ξ2(mx) (|P| grows from e^{−2 Im mx} towards 1),
  // so ξ2(mx) is never recurred: with D = ψ'/ψ (downward, as for Mie) and
  // G = ψ(mx)/ξ1(mx) (a product of stable ratios, kept as a logarithm since it is
  // ~e^{2 Im mx}), P = 1/(2G − 1), 1 + P = 2GP and D2m = D + P (D − D1m), exactly; and
  // the geometric tail uses 1 − R_int = (1 + P)(D1 − β D)/den, so
  //   T_in T_out/(1 − R_int) = −Q β P (D1 − D2)(D − D1m)/(den (D1 − β D)),
  // free of the cancellation in 1 − R_int when |R_int| → 1 (n > |mx|, where ξ1 ≈ ξ2).
  const std::vector<complex> d_psi = log_derivative_psi(z, terms);
  HankelRatio h1x(complex(x, 0.0));  // ξ^{(1)}(x); ξ^{(2)}(x) is its conjugate
  HankelRatio h1z(z);
  // Q_0 = ξ2_0/ξ1_0 = −e^{−2ix}, of modulus 1 for real x.
  complex q_ratio = -std::polar(1.0, -2.0 * x);
  // G_0 = ψ_0/ξ1_0 = (w − 1)/(2w), w = e^{2iz} (|w| ≤ 1, may underflow harmlessly).
  const complex z_inv = 1.0 / z;
  complex w_minus_1 = std::exp(2.0 * kI * z) - 1.0;
  if (w_minus_1 == 0.0) w_minus_1 = 1e-300;  // sin z = 0 exactly: ψ_0 = 0
  complex log_2g = std::log(w_minus_1) - 2.0 * kI * z;  // log(2G)
  for (int n = 1; n <= terms; ++n) {
    if (n > 1) {
      h1x.next();
      h1z.next();
    }
    q_ratio *= std::conj(h1x.q) / h1x.q;
    q_ratio /= std::abs(q_ratio);  // exactly unimodular; stops rounding drift over 10⁴ steps
    // G_n = G_{n−1} (ψ_n/ψ_{n−1}) / (ξ1_n/ξ1_{n−1}), ψ_{n−1}/ψ_n = D_n + n/z.
    log_2g -= std::log((d_psi[n] + static_cast<double>(n) * z_inv) * h1z.q);
    log_2g.imag(std::remainder(log_2g.imag(), 2.0 * kPi));  // keep the phase sum from growing
    complex p_ratio, one_plus_p;  // P = 1/(2G − 1), 1 + P = 2G/(2G − 1)
    if (log_2g.real() > 0) {
      const complex inv = std::exp(-log_2g);  // 1/(2G), |·| < 1
      p_ratio = inv / (1.0 - inv);
      one_plus_p = 1.0 / (1.0 - inv);
    } else {
      const complex two_g = std::exp(log_2g);
      p_ratio = 1.0 / (two_g - 1.0);
      one_plus_p = two_g / (two_g - 1.0);
    }
    const complex d1 = h1x.log_derivative(), d2 = std::conj(d1);
    const complex dm = d_psi[n], d1m = h1z.log_derivative();
    const complex d2m = dm + p_ratio * (dm - d1m);

    for (int pol = 0; pol < 2; ++pol) {
      const complex beta = pol == 0 ? 1.0 / m : m;
      const complex den = d1 - beta * d2m;
      const complex r_ext = q_ratio * (beta * d2m - d2) / den;
      const complex r_int = -p_ratio * (d1 - beta * d1m) / den;
      const complex tt = -q_ratio * p_ratio * one_plus_p * beta * (d1 - d2) * (dm - d1m) / (den * den);
      const complex tail = -q_ratio * beta * p_ratio * (d1 - d2) * (dm - d1m) / (den * (d1 - beta * dm));
      std::vector<std::vector<complex>>& out = pol == 0 ? dc.a_p : dc.b_p;
      out[0][n - 1] = 0.5 * (1.0 - r_ext);
      complex r_pow = 1.0;  // R_int^{p−1}
      for (int p = 1; p <= max_p; ++p) {
        out[p][n - 1] = -0.5 * tt * r_pow;
        r_pow *= r_int;
      }
      // Σ_{p>P} T R^{p−1} T = T T R^P/(1 − R): every remaining p at once.
      (pol == 0 ? dc.a_rest : dc.b_rest)[n - 1] = -0.5 * tail * r_pow;
    }
    dc.a_diffraction[n - 1] = (n + 0.5 <= x) ? 0.5 : 0.0;
  }
  return dc;
}

Debye debye(double x, complex m, const std::vector<double>& mu, int max_p) {
  check_sphere(x, m);
  check_mu(mu);
  const DebyeCoefficients dc = debye_coefficients(x, m, max_p);
  const int terms = static_cast<int>(dc.a_rest.size());

  std::vector<complex> ref_a(terms), ref_b(terms);
  for (int i = 0; i < terms; ++i) {
    ref_a[i] = dc.a_p[0][i] - dc.a_diffraction[i];
    ref_b[i] = dc.b_p[0][i] - dc.a_diffraction[i];
  }

  Debye d;
  d.series_terms = terms;
  d.terms.resize(max_p + 1);
  std::vector<CoefficientSet> sets;
  for (int p = 0; p <= max_p; ++p) sets.push_back({dc.a_p[p].data(), dc.b_p[p].data(), &d.terms[p]});
  sets.push_back({dc.a_rest.data(), dc.b_rest.data(), &d.remainder});
  sets.push_back({dc.a_diffraction.data(), nullptr, &d.diffraction});
  sets.push_back({ref_a.data(), ref_b.data(), &d.reflection});
  angular_sums(terms, sets, mu);
  return d;
}

}  // namespace arcus::rainbow::mie
