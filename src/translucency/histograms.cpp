#include "translucency/histograms.h"

#include <string>

#include "core/buffer.h"
#include "core/error.h"
#include "core/kernel_source.h"
#include "core/launch.h"
#include "core/layout.h"

#include "common/real.h"
#include "translucency/translucency_desc.h"

namespace arcus::translucency {
namespace {

const KernelSource kHistogram{"translucency/histogram",
                              {"common/real.h", "translucency/translucency_desc.h", "translucency/histogram.cl"}, ""};
ARCUS_KERNEL_ARGS(HistogramArg, "arcus_translucency_histogram", ARCUS_TRANSLUCENCY_HISTOGRAM_ARGS);

}  // namespace

std::vector<double> distance_histograms(arcus_context_t* ctx, arcus_job_s& job, const HistogramRequest& q,
                                        bool* cancelled) {
  const size_t n = q.rows->size() / 3, cells = size_t(q.bins) * q.weights_per_source;
  require(cells >= 1 && cells <= ARCUS_MAX_HISTOGRAM_CELLS,
          "distance histograms of " + std::to_string(cells) + " cells: more than the kernel keeps (" +
              std::to_string(ARCUS_MAX_HISTOGRAM_CELLS) + ")");
  job.features |= ARCUS_FEATURE_TRANSLUCENCY_HISTOGRAM;
  const BuiltProgram built = build_job_program(ctx, job, kHistogram, Layout{1, 1});
  DeviceBuffer out(ctx, n * cells * sizeof(double), "the distance histograms");
  Launch<HistogramArg> launch(ctx, built.program);
  launch.upload(HistogramArg::rows, *q.rows, "the row points");
  launch.upload(HistogramArg::sources, *q.sources, "the source points");
  launch.upload(HistogramArg::weights, *q.weights, "the sources' weights");
  launch.bind(HistogramArg::histograms, &out);
  launch.bind_value(HistogramArg::source_count, static_cast<cl_uint>(q.sources->size() / 3));
  launch.bind_value(HistogramArg::bins, static_cast<cl_uint>(q.bins));
  launch.bind_value(HistogramArg::weights_per_source, static_cast<cl_uint>(q.weights_per_source));
  launch.bind_value(HistogramArg::reach, q.reach);
  launch.bind_value(HistogramArg::sqrt_bins, static_cast<cl_uint>(q.sqrt_bins));
  SliceRange slices;
  slices.total = n;
  slices.first_units = 64;
  slices.progress = q.progress;
  slices.progress_user = q.progress_user;
  *cancelled = launch.run_slices(slices, [&](uint64_t first, uint64_t end) {
    launch.bind_value(HistogramArg::first, static_cast<cl_uint>(first));
    launch.bind_value(HistogramArg::count, static_cast<cl_uint>(end - first));
    return size_t(end - first);
  }, &job.stats);
  std::vector<double> h(n * cells, 0.0);
  out.read(ctx, 0, h.size() * sizeof(double), h.data());
  return h;
}

}  // namespace arcus::translucency
