// Progress reporting kept apart from the UI: stages report through this interface and
// the CLI decides how (and whether) to render it.
#pragma once

#include <functional>
#include <string>

namespace isoquad {

// Called with the stage name and a fraction in [0,1] of the whole job. Returns false to
// cancel; the stage then throws.
using ProgressCallback = std::function<bool(const std::string& stage, double fraction)>;

// A slice [begin, end] of the whole job's progress, handed to one stage.
class Progress {
 public:
  Progress() = default;
  explicit Progress(ProgressCallback callback) : callback_(std::move(callback)) {}

  // Reports `fraction` of this slice done for `stage`. Throws Error when cancelled.
  void report(const std::string& stage, double fraction) const;
  // A sub-slice [begin, end] (fractions of this slice).
  Progress slice(double begin, double end) const;

 private:
  ProgressCallback callback_;
  double begin_ = 0.0;
  double end_ = 1.0;
};

}  // namespace isoquad
