// Building index-of-refraction fields on the host (validation, atmosphere tables).
#pragma once

#include <vector>

#include "arcus/arcus.h"
#include "field.h"

namespace arcus {

// n − 1 of standard dry air (15 °C, 101 325 Pa, 450 ppm CO2) at a vacuum wavelength in
// nm: Ciddor (1996), Appl. Opt. 35, 1566, eq. 1.  Valid 300–1690 nm.
double ciddor_standard_refractivity(double wavelength_nm);

// The atmosphere's field description and segment table (field.h's layout): the US
// Standard Atmosphere 1976 temperature profile, shifted to the given sea-level
// temperature, plus the inversion layers (thesis §3.1.1).  Throws on bad input.
void build_atmosphere(const arcus_atmosphere_desc& desc, arcus_field_desc_d* field, std::vector<double>* segments);

// Checks a grid's dims (each 2..65536), origin and spacing; returns the value count.
size_t grid_value_count(const uint32_t dims[3], const double origin[3], const double spacing[3]);

// Checks a grid's description and values (finite, positive) and fills `field`.
void build_grid(const double* values, const uint32_t dims[3], const double origin[3], const double spacing[3],
                arcus_field_desc_d* field, std::vector<double>* data);

}  // namespace arcus
