// Index-of-refraction fields on the host: the object behind arcus_field_t, and the
// building and checking of field descriptions (atmosphere tables, grids).
#pragma once

#include <memory>
#include <string>
#include <vector>

#include "arcus/arcus_curved.h"
#include "core/buffer.h"
#include "core/handle.h"
#include "curved/field.h"  // kernels/curved/field.h: the description shared with the kernels

namespace arcus::curved {
extern const HandleKind kFieldHandle;  // "field"
}  // namespace arcus::curved

struct arcus_field_s : arcus::Handle {
  explicit arcus_field_s(arcus_context_t* ctx) : Handle(arcus::curved::kFieldHandle, ctx) {}
  arcus_field_desc_d desc{};  // kind, parameters (double)
  std::vector<double> data;   // atmosphere segments or grid values
  // The data on the device, per precision (double, float), uploaded on first use and
  // kept for every later job.
  std::shared_ptr<arcus::DeviceBuffer> device_data[2];
};

namespace arcus::curved {

// A description and its data, built and checked, before it becomes a field.
struct FieldBuild {
  arcus_field_desc_d desc{};
  std::vector<double> data;
};

FieldBuild constant(double n);
FieldBuild linear(double n0, const double* gradient);
FieldBuild linear_n2(double a, const double* k);
FieldBuild luneburg(const double* center, double radius);
FieldBuild fisheye(const double* center, double radius, double n0);

// The US Standard Atmosphere 1976 temperature profile shifted to the sea-level
// temperature, plus the inversion layers (thesis §3.1.1), as segments (field.h).
FieldBuild atmosphere(const arcus_atmosphere_desc& desc);

// Checks a grid's dims (each 2..65536), origin and spacing, and what the kernels derive
// from them; returns the value count.
size_t grid_value_count(const uint32_t* dims, const double* origin, const double* spacing);

// A grid from its values (moved in: a grid may be large), each checked to be a
// positive finite n.
FieldBuild grid(std::vector<double> values, const uint32_t* dims, const double* origin, const double* spacing);

// The values of a raw little-endian grid file (type: arcus_scalar_type), read without
// any arcus lock held.  Not a regular file, or the wrong size: ARCUS_ERROR_IO.
std::vector<double> read_grid_file(const char* path, int32_t type, size_t count);

// Whether n depends on the wavelength (per-ray wavelengths apply).
bool dispersive(const arcus_field_desc_d& desc);

// The field a scene file's medium describes (scene_desc.h); reads a grid's file.
struct MediumDesc;
FieldBuild build_field(const MediumDesc& medium);

}  // namespace arcus::curved
