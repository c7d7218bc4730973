// The one clock that rastercheck's timings read: the steady clock, as nanoseconds since its
// own epoch, and the milliseconds elapsed since such a reading.
#pragma once

#include <chrono>

namespace rc {

inline long long nowNanoseconds() {
  return std::chrono::duration_cast<std::chrono::nanoseconds>(std::chrono::steady_clock::now().time_since_epoch())
      .count();
}

inline double millisecondsSince(long long startNanoseconds) {
  return double(nowNanoseconds() - startNanoseconds) * 1e-6;
}

}  // namespace rc
