#include "core/progress.h"

#include <algorithm>

#include "core/error.h"

namespace isoquad {

void Progress::report(const std::string& stage, double fraction) const {
  if (!callback_) return;
  const double f = begin_ + (end_ - begin_) * std::clamp(fraction, 0.0, 1.0);
  if (!callback_(stage, f)) throw Error(ErrorClass::internal, stage, "cancelled");
}

Progress Progress::slice(double begin, double end) const {
  Progress p(callback_);
  p.begin_ = begin_ + (end_ - begin_) * begin;
  p.end_ = begin_ + (end_ - begin_) * end;
  return p;
}

}  // namespace isoquad
