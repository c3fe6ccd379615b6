// Distance histograms on the device (kernels/translucency/histogram.cl): per row point,
// the sources' weights summed by the bin of their distance.  The estimate's eq. 3.16
// (estimate.h) and the genetic search's cache (appearance.h) are both this.
#pragma once

#include <cstdint>
#include <vector>

#include "arcus/arcus_core.h"
#include "core/job.h"

namespace arcus::translucency {

struct HistogramRequest {
  const std::vector<double>* rows = nullptr;     // 3 per row point, mm
  const std::vector<double>* sources = nullptr;  // 3 per source, mm
  const std::vector<double>* weights = nullptr;  // weights_per_source per source
  uint32_t weights_per_source = 3;
  uint32_t bins = 0;       // bins × weights_per_source <= ARCUS_MAX_HISTOGRAM_CELLS
  double reach = 0;        // mm: the last bin's far edge
  bool sqrt_bins = false;  // bins uniform in √r (else in r)
  arcus_progress_callback progress = nullptr;
  void* progress_user = nullptr;
};

// rows × bins × weights_per_source sums; sets the job's feature (TRANSLUCENCY_HISTOGRAM)
// and adds to its stats.  *cancelled when the progress callback stopped it.
std::vector<double> distance_histograms(arcus_context_t* ctx, arcus_job_s& job, const HistogramRequest& request,
                                        bool* cancelled);

}  // namespace arcus::translucency
