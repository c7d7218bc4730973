// Error statistics.
#include "compare/statistics.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <stdexcept>

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

namespace {

// Fewer values than this are partitioned per rank; the radix select's histograms (256 KB
// each) would cost more.
constexpr std::size_t kRadixSelectFrom = std::size_t(1) << 16;

// A float's bits turned so that unsigned order is the floats' order (-Inf < -0 < +0 < +Inf < NaN).
std::uint32_t orderedKey(float value) {
  std::uint32_t bits;
  std::memcpy(&bits, &value, 4);
  return bits & 0x80000000u ? ~bits : bits | 0x80000000u;
}

float valueOfKey(std::uint32_t key) {
  const std::uint32_t bits = key & 0x80000000u ? key & 0x7FFFFFFFu : ~key;
  float value;
  std::memcpy(&value, &bits, 4);
  return value;
}

}  // namespace

std::vector<double> percentiles(std::span<const float> values, const std::vector<double>& p) {
  std::vector<double> result(p.size(), 0.0);
  const std::size_t n = values.size();
  if (n == 0) return result;
  if (n > 0xFFFFFFFFu) throw std::length_error("percentiles: more than 2^32 values");
  if (p.size() > 255) throw std::length_error("percentiles: more than 255 at once");
  // The 0-based rank of each wanted value: nearest rank ceil(p n), at least 1.
  std::vector<std::size_t> ranks(p.size());
  for (std::size_t j = 0; j < p.size(); ++j) {
    const double rank = std::ceil(p[j] * double(n));  // p outside [0, 1] or NaN: clamped before any cast
    ranks[j] = !(rank >= 1.0) ? 0 : rank >= double(n) ? n - 1 : std::size_t(rank) - 1;
  }
  if (n < kRadixSelectFrom) {  // a copy partitioned per rank costs less than the histograms
    std::vector<std::uint32_t> keys(n);
    for (std::size_t i = 0; i < n; ++i) keys[i] = orderedKey(values[i]);
    for (std::size_t j = 0; j < p.size(); ++j) {
      std::nth_element(keys.begin(), keys.begin() + std::ptrdiff_t(ranks[j]), keys.end());
      result[j] = valueOfKey(keys[ranks[j]]);
    }
    return result;
  }
  // Pass 1: how many keys share each top 16 bits; each rank falls in one such bin.
  std::vector<std::uint32_t> high(1u << 16, 0);
  for (const float v : values) ++high[orderedKey(v) >> 16];
  // The top-16-bit bins holding a wanted rank (at most one per rank), and each rank's slot.
  std::vector<std::uint32_t> bins;
  std::vector<std::size_t> slotOfRank(p.size());
  for (std::size_t j = 0; j < p.size(); ++j) {
    std::size_t below = 0;
    std::uint32_t bin = 0;
    while (below + high[bin] <= ranks[j]) below += high[bin++];
    const auto found = std::find(bins.begin(), bins.end(), bin);
    slotOfRank[j] = std::size_t(found - bins.begin()) + 1;
    if (found == bins.end()) bins.push_back(bin);
    ranks[j] -= below;  // now the rank within its bin
  }
  // Pass 2: how many keys of each wanted bin share each low 16 bits. Every key is counted
  // without a branch: its bin's slot (0 for a bin nobody wants, whose counts are dropped)
  // picks the histogram. Looping over the wanted bins per key instead, a mispredicted branch
  // each, took four fifths of the time.
  std::vector<std::uint8_t> slotOfBin(std::size_t(1) << 16, 0);
  for (std::size_t w = 0; w < bins.size(); ++w) slotOfBin[bins[w]] = std::uint8_t(w + 1);
  std::vector<std::uint32_t> low((bins.size() + 1) << 16, 0);
  for (const float v : values) {
    const std::uint32_t key = orderedKey(v);
    ++low[std::size_t(slotOfBin[key >> 16]) << 16 | (key & 0xFFFFu)];
  }
  for (std::size_t j = 0; j < p.size(); ++j) {
    const std::uint32_t* counts = low.data() + (slotOfRank[j] << 16);
    std::size_t below = 0;
    std::uint32_t lowBits = 0;
    while (below + counts[lowBits] <= ranks[j]) below += counts[lowBits++];
    result[j] = valueOfKey(bins[slotOfRank[j] - 1] << 16 | lowBits);
  }
  return result;
}

double percentile(std::span<const float> values, double p) { return percentiles(values, {p})[0]; }

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
    const std::vector<double> p = percentiles(errors_, {0.999, 0.99, 0.50});
    s.p999 = p[0];
    s.p99 = p[1];
    s.p50 = p[2];
  }
  errors_.clear();
  errors_.shrink_to_fit();
  return s;
}

}  // namespace rc
