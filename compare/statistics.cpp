// Error statistics.
#include "compare/statistics.h"

#include <algorithm>
#include <cmath>

namespace rc {

void StatsAccumulator::addError(double error, int x, int y, double test, double reference) {
  errors_.push_back(float(error));
  sum_ += error;
  sumSquares_ += error * error;
  if (error > max_) {
    max_ = error;
    worst_ = {x, y, test, reference};
  }
}

double percentile(std::vector<float>& values, double p) {
  if (values.empty()) return 0.0;
  // Nearest rank: the smallest value with at least p of the values at or below it.
  std::size_t rank = std::size_t(std::ceil(p * double(values.size())));
  rank = std::clamp<std::size_t>(rank, 1, values.size());
  std::nth_element(values.begin(), values.begin() + (rank - 1), values.end());
  return values[rank - 1];
}

FamilyStats StatsAccumulator::finish() {
  FamilyStats s;
  s.count = errors_.size();
  s.nanCount = nan_;
  s.infCount = inf_;
  if (s.count > 0) {
    s.max = max_;
    s.mean = sum_ / double(s.count);
    s.rms = std::sqrt(sumSquares_ / double(s.count));
    s.worst = worst_;
    // Each call re-partitions the whole set, so the order of these calls does not matter.
    s.p999 = percentile(errors_, 0.999);
    s.p99 = percentile(errors_, 0.99);
    s.p50 = percentile(errors_, 0.50);
  }
  errors_.clear();
  errors_.shrink_to_fit();
  return s;
}

}  // namespace rc
