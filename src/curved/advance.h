// Advancing a batch of rays through a field (arcus_curved_advance): the job object, its
// planning (features, layout, step counts) and its run in slices on the device.
#pragma once

#include <functional>
#include <memory>
#include <string>
#include <vector>

#include "arcus/arcus_curved.h"
#include "core/buffer.h"
#include "core/features.h"
#include "core/job.h"
#include "core/kernel_source.h"
#include "core/launch.h"
#include "core/layout.h"
#include "curved/params.h"
#include "curved/advance_desc.h"  // kernels/curved/advance_desc.h: shared with the kernel
#include "curved/field.h"  // kernels/curved/field.h: the field description shared with the kernels

namespace arcus::curved {

ARCUS_KERNEL_ARGS(AdvanceArg, "arcus_advance", ARCUS_ADVANCE_ARGS);

// The curved engine's feature table and kernel source (features.cpp).
const FeatureTable& feature_table();
const KernelSource& advance_source();

// The results of an advance: every ray's end state, status and path.
struct AdvanceJob : arcus_job_s {
  explicit AdvanceJob(arcus_context_t* ctx) : arcus_job_s(ctx, "advance") {}
  std::vector<double> positions, directions, lengths;  // count×3, count×3, count
  std::vector<uint64_t> steps;
  std::vector<int32_t> status, failures;
  uint32_t path_capacity = 0;          // points kept per ray
  std::vector<uint64_t> path_offsets;  // count+1 (empty without record_path)
  std::vector<uint64_t> path_needed;   // count
  std::vector<double> path_points;     // path_offsets[count]×3
};

// The least n with n·step >= length in the kernel's arithmetic (so the last step ends
// exactly at `length`), capped at max_steps; and that last step.
struct FixedSteps {
  int32_t steps = 0;
  double last_step = 0;
  bool capped = false;  // max_steps stops the rays before `length`
};
template <class Real>
FixedSteps fixed_steps(double length, double step, uint64_t max_steps);

// Checks the parameters on their own (no field, no device): throws INVALID_ARGUMENT
// naming the member.  `straight`: a constant field, which needs no integrator settings.
void check_advance_params(const arcus_advance_params& params, bool straight);

// What a job compiles and how it is laid out.
struct Plan {
  arcus_features features = 0;
  Layout layout;
  bool straight = false, dp45 = false, single = false, dispersion = false;
};
// Throws INVALID_ARGUMENT or UNSUPPORTED for parameters the job cannot run with.
// `with_wavelengths`: the call gave per-ray wavelengths.
Plan plan_advance(const arcus_advance_params& params, const arcus_field_desc_d& field, const std::vector<double>& data,
                  const arcus_device_info& device, const DeviceEntry& entry, bool with_wavelengths);

// The field's data on ctx's device in the kernels' precision (uploaded on first use and
// kept with the field); null for a field without data.
DeviceBuffer* field_data_on_device(arcus_context_t* ctx, arcus_field_t* field, bool single);

// Binds a kernel's field description, field data and job description as the advance
// kernel takes them (ARCUS_FIELD_JOB_ARGS): for other kernels of the same program (the
// renderer's walk over stored paths), which name their indices.
void bind_field_and_job(KernelLaunch& launch, unsigned field_arg, unsigned data_arg, unsigned job_arg,
                        arcus_context_t* ctx, arcus_field_t* field, const arcus_advance_params& params,
                        const Plan& plan, size_t stride);

// What another engine adds to an advance (the renderer's per-step hook against its
// geometry, render/hits.h): features and the kernel source that compiles them, kernel
// arguments (the geometry's), and a look at its buffers after the run.
// `stride` is the entries per component of the ray buffers.
struct AdvanceExtension {
  arcus_features features = 0;
  const KernelSource* source = nullptr;  // includes curved/advance.cl after the hook
  uint32_t record_components = 3;        // reals per recorded path point (x y z)
  std::function<void(Launch<AdvanceArg>& launch, size_t stride, bool single)> bind_args;
  std::function<void(size_t stride, bool single)> finished;  // after the last slice
  // The recorded paths (record_path), as the kernel wrote them: count × capacity ×
  // record_components reals, ray by ray; with record_components 7 (whole states,
  // ARCUS_USE_RECORD_STATE) stride × capacity points step by step, ray r's point k at
  // k·stride + r.  If set, the path buffer is handed over instead of read.
  std::function<void(std::unique_ptr<DeviceBuffer> paths, uint32_t capacity, size_t stride)> take_paths;
};

// The body of arcus_curved_advance: plans, builds (or reuses) the kernel, runs it in slices
// and fills a new job.  Returns SUCCESS or a partial status (INVALID_RAYS,
// PATH_OVERFLOW, CANCELLED) with *message set; throws on other errors.
arcus_status advance(arcus_context_t* ctx, arcus_field_t* field, const arcus_advance_params& params, size_t count,
                     const double* origins, const double* directions, const double* wavelengths, arcus_job_t** job,
                     std::string* message, const AdvanceExtension* extension = nullptr);

}  // namespace arcus::curved
