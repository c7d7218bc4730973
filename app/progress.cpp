// Progress on stderr.
#include "app/progress.h"

#include <unistd.h>

#include <cstdio>

namespace rc::app {

Progress::Progress(int totalSteps, bool quiet)
    : total_(totalSteps), quiet_(quiet), terminal_(isatty(STDERR_FILENO) == 1) {}

Progress::~Progress() {
  if (!quiet_ && terminal_ && done_ > 0) std::fprintf(stderr, "\r\033[K");  // leave a clean line
}

void Progress::step(const std::string& what) {
  ++done_;
  if (quiet_) return;
  if (!terminal_) {
    std::fprintf(stderr, "rastercheck: [%d/%d] %s\n", done_, total_, what.c_str());
    return;
  }
  constexpr int kWidth = 30;
  const int filled = total_ > 0 ? (done_ - 1) * kWidth / total_ : 0;
  std::string bar(std::size_t(filled), '=');
  bar.resize(kWidth, ' ');
  std::fprintf(stderr, "\r\033[K[%s] %d/%d %s", bar.c_str(), done_, total_, what.substr(0, 60).c_str());
  std::fflush(stderr);
}

}  // namespace rc::app
