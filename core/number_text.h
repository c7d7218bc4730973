// Numbers in messages: the shortest text that reads back as the same double, so that a value
// or a limit is printed exactly (printf's %g rounds 2^40 to 1.099511628e+12, and a value just
// above the limit then reads as below it) and no longer than it needs to be.
#pragma once

#include <charconv>
#include <string>

namespace rc {

inline std::string exactNumber(double v) {
  char buf[32];
  return std::string(buf, std::to_chars(buf, buf + sizeof buf, v).ptr);
}

}  // namespace rc
