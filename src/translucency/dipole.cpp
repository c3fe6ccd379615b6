#include "translucency/dipole.h"

#include <cmath>

#include "core/error.h"
#include "core/format.h"

// kernels/common/fresnel.h and kernels/translucency/dipole_rd.h are scalar code the host
// includes after common/real.h.
#include "common/real.h"
#include "common/fresnel.h"
#include "translucency/dipole_rd.h"

namespace arcus::translucency {

double diffuse_fresnel_reflectance(double eta) {
  return -1.440 / (eta * eta) + 0.710 / eta + 0.668 + 0.0636 * eta;
}

double boundary_mismatch(double eta) {
  const double f = diffuse_fresnel_reflectance(eta);
  return (1 + f) / (1 - f);
}

Terms terms(const Channel& c) {
  Terms t;
  t.sigma_t_prime = c.sigma_a + c.sigma_s_prime;
  t.albedo = c.sigma_s_prime / t.sigma_t_prime;
  t.sigma_tr = std::sqrt(3 * c.sigma_a * t.sigma_t_prime);
  t.z_r = 1 / t.sigma_t_prime;
  // Thesis eq. 3.7 prints z_v = 1 + 4A/3: a length equal to a number.  The image
  // source lies 2·z_b = z_r·4A/3 above the extrapolated boundary (Jensen 2001, eq. 5).
  t.z_v = t.z_r * (1 + 4.0 / 3.0 * boundary_mismatch(c.eta));
  return t;
}

double diffuse_reflectance(const Terms& t, double r) {
  return arcus_dipole_rd(r * r, t.z_r, t.z_v, t.sigma_tr, t.albedo / (4 * M_PI));
}

double reflectance_within(const Terms& t, double radius) {
  auto source = [&](double z) {
    const double d = std::sqrt(radius * radius + z * z);
    return z * (std::exp(-t.sigma_tr * z) / z - std::exp(-t.sigma_tr * d) / d);
  };
  return t.albedo / 2 * (source(t.z_r) + source(t.z_v));
}

double total_reflectance(double albedo, double eta) {
  const double s = std::sqrt(3 * (1 - albedo));
  return albedo / 2 * (1 + std::exp(-4.0 / 3.0 * boundary_mismatch(eta) * s)) * std::exp(-s);
}

double albedo_for_reflectance(double total, double eta) {
  // total_reflectance rises from 0 at α′ = 0 to 1 at α′ = 1.
  double lo = 0, hi = 1;
  for (int i = 0; i < 200 && hi - lo > 0; ++i) {
    const double mid = 0.5 * (lo + hi);
    if (mid == lo || mid == hi) break;
    (total_reflectance(mid, eta) < total ? lo : hi) = mid;
  }
  return 0.5 * (lo + hi);
}

double fresnel_reflectance(double cos_i, double n1, double n2) { return arcus_fresnel_reflectance(cos_i, n1, n2); }

double exit_transmittance(double eta) {
  // Composite Simpson over μ = cos θ in [0, 1]: R(μ)μ is smooth for η >= 1 and has one
  // kink (total reflection from outside) for η < 1; 2^14 intervals put the error below
  // 1e-9 either way.
  const int n = 1 << 14;
  double sum = 0;
  for (int i = 0; i <= n; ++i) {
    const double mu = double(i) / n;
    const double w = (i == 0 || i == n) ? 1 : (i % 2 ? 4 : 2);
    sum += w * fresnel_reflectance(mu, 1.0, eta) * mu;
  }
  return 1 - 2 * sum / (3.0 * n);
}

double henyey_greenstein(double g, double cos_theta) {
  // Thesis eq. 3.5 lacks the (1 − g²) factor and folds the angle with |ω_i·ω_o|: it
  // neither integrates to 1 nor has mean cosine g.  This is the standard form.
  const double denominator = 1 + g * g - 2 * g * cos_theta;
  return (1 - g * g) / (4 * M_PI * denominator * std::sqrt(denominator));
}

arcus_dipole_terms dipole_terms(const arcus_dipole& d) {
  arcus_dipole_terms out{};
  for (int c = 0; c < 3; ++c) {
    const Terms t = terms(Channel{d.sigma_a[c], d.sigma_s_prime[c], d.eta});
    out.albedo[c] = t.albedo;
    out.sigma_t_prime[c] = t.sigma_t_prime;
    out.sigma_tr[c] = t.sigma_tr;
    out.diffuse_length[c] = t.sigma_tr > 0 ? 1 / t.sigma_tr : INFINITY;
    out.z_r[c] = t.z_r;
    out.z_v[c] = t.z_v;
    out.total_reflectance[c] = total_reflectance(t.albedo, d.eta);
    out.diffusive[c] = t.albedo >= 0.5;
  }
  out.f_dr = diffuse_fresnel_reflectance(d.eta);
  out.a = boundary_mismatch(d.eta);
  out.exit_transmittance = exit_transmittance(d.eta);
  return out;
}

void check_channel(const Channel& c, const std::string& where, int channel) {
  const std::string at = "[" + std::to_string(channel) + "]";
  require(std::isfinite(c.sigma_a) && c.sigma_a >= 0,
          where + "sigma_a" + at + " = " + number(c.sigma_a) + " is not a finite absorption >= 0 (mm^-1)");
  require(std::isfinite(c.sigma_s_prime) && c.sigma_s_prime > 0,
          where + "sigma_s_prime" + at + " = " + number(c.sigma_s_prime) +
              " is not a finite reduced scattering > 0 (mm^-1)");
}

void check_eta(double eta, const std::string& name) {
  require(eta >= 1 && eta <= 3, name + " = " + number(eta) +
                                    " is outside 1..3, where the dipole's diffuse Fresnel fit (F_dr) holds");
}

}  // namespace arcus::translucency
