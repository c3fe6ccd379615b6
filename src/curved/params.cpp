#include "curved/params.h"

namespace arcus::curved {

void default_advance_params(arcus_advance_params* p) {
  *p = arcus_advance_params{};
  p->method = ARCUS_METHOD_DP45;
  p->precision = ARCUS_PRECISION_DOUBLE;
  p->length = 1.0;
  p->step = 0.0;
  p->rtol = 1e-9;
  p->atol = 1e-12;
  p->min_step = 1e-12;
  p->max_step = 0.0;
  p->max_rejections = 64;
  p->max_steps = 10000000;
  p->use_box = 0;
  p->record_path = 0;
  p->path_capacity = 0;
  p->progress = nullptr;
  p->progress_user = nullptr;
}

}  // namespace arcus::curved
