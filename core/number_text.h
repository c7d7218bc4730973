// Numbers in messages and headers: exactly the double, and no longer than it needs to be. A
// whole number below 2^53 in full (4000000, not to_chars' shortest 4e+06), any other as the
// shortest text that reads back as the same double (printf's %g rounds: %.10g printed 2^40 as
// 1.099511628e+12, which a value just above the limit is below, and %.6g read a bound back
// smaller than itself).
#pragma once

#include <charconv>
#include <cmath>
#include <string>

namespace rc {

inline std::string exactNumber(double v) {
  if (v == std::floor(v) && std::fabs(v) < 0x1p53) return std::to_string(static_cast<long long>(v));
  char buf[32];
  return std::string(buf, std::to_chars(buf, buf + sizeof buf, v).ptr);
}

}  // namespace rc
