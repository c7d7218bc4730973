// Pooled error statistics of one channel family (FLIP and idiff style): sums in double,
// exact nearest-rank percentiles, the worst pixel with both values, non-finite values counted.
#pragma once

#include <cstddef>
#include <cstdint>
#include <span>
#include <vector>

#include "core/plane_allocator.h"

namespace rc {

struct WorstPixel {
  int x = -1, y = -1;     // -1 when there was no finite error
  double test = 0.0;      // the test image's value there (the component with the largest error)
  double reference = 0.0;
};

struct FamilyStats {
  std::size_t count = 0;     // finite errors pooled
  std::size_t nanCount = 0;  // pixels where either image holds a NaN in this family
  std::size_t infCount = 0;  // pixels where either image holds +-Inf (and no NaN)
  double max = 0.0, mean = 0.0, rms = 0.0, p50 = 0.0, p99 = 0.0, p999 = 0.0;
  WorstPixel worst;
};

// Accumulates per-pixel errors, then summarises them.
class StatsAccumulator {
 public:
  void reserve(std::size_t count) { errors_.reserve(count); }  // the most errors to come
  void addError(double error, int x, int y, double test, double reference);
  void addNan() { ++nan_; }
  void addInf() { ++inf_; }
  FamilyStats finish();  // consumes the stored errors

 private:
  // A million errors at 1920x1080, per statistic: in huge pages where the kernel allows, since
  // faulting them in 4 KB pages took most of compare's page faults (65% of `check`'s).
  PlaneVector<float> errors_;
  double sum_ = 0.0, sumSquares_ = 0.0;
  std::size_t nan_ = 0, inf_ = 0;
  WorstPixel worst_;
  double max_ = -1.0;
};

// Nearest-rank percentile (p in [0, 1]; outside it or NaN, the nearest end) of `values`: the smallest value with at least p of the
// values at or below it; 0 for an empty set. NaN sorts above +Inf, and -0 below +0.
double percentile(std::span<const float> values, double p);
// The same for several p at once, in two passes over the values whatever their count (a radix
// select on the values' bits) instead of a partition of the whole set for each.
std::vector<double> percentiles(std::span<const float> values, const std::vector<double>& p);

}  // namespace rc
