// The rainbow engine's spellings before arcus 0.10, kept for one release
// (include/arcus/arcus_rainbow.h): each forwards to its new name, converting the old
// unit where there was one (°C).
#include "arcus/arcus.h"

extern "C" {

arcus_status arcus_refractive_index(int32_t material, double wavelength_nm, double temperature_c, double* n) {
  return arcus_rainbow_refractive_index(material, wavelength_nm, temperature_c + 273.15, n);
}

arcus_status arcus_job_rainbow_phase(arcus_job_t* job, size_t count, const double* theta_deg, const double* phi_deg,
                                     int32_t coherent, double* parallel, double* perpendicular, double* per_bounce) {
  return arcus_job_get_rainbow_phase(job, count, theta_deg, phi_deg, coherent, parallel, perpendicular, per_bounce);
}

arcus_status arcus_job_rainbow_phasors(arcus_job_t* job, size_t count, const double* theta_deg, const double* phi_deg,
                                       double* phasors) {
  return arcus_job_get_rainbow_phasors(job, count, theta_deg, phi_deg, phasors);
}

arcus_status arcus_mie(double radius, double wavelength_nm, double n_re, double n_im, size_t count,
                       const double* theta_deg, double* s1, double* s2, double* parallel, double* perpendicular,
                       arcus_mie_efficiencies* efficiencies) {
  return arcus_rainbow_mie(radius, wavelength_nm, n_re, n_im, count, theta_deg, s1, s2, parallel, perpendicular,
                           efficiencies);
}

arcus_status arcus_mie_debye(double radius, double wavelength_nm, double n_re, double n_im, uint32_t max_p,
                             size_t count, const double* theta_deg, double* s1, double* s2, double* parallel,
                             double* perpendicular) {
  return arcus_rainbow_mie_debye(radius, wavelength_nm, n_re, n_im, max_p, count, theta_deg, s1, s2, parallel,
                                 perpendicular);
}

}  // extern "C"
