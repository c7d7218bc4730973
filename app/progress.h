// Progress of long work on stderr: a bar redrawn in place on a terminal, one plain line per
// step otherwise (logs, CI), nothing at all with --quiet. stdout stays for results.
#pragma once

#include <string>

namespace rc::app {

class Progress {
 public:
  Progress(int totalSteps, bool quiet);
  ~Progress();
  // Announces the step about to run: "[k/total] what".
  void step(const std::string& what);

 private:
  int total_, done_ = 0;
  bool quiet_, terminal_;
};

}  // namespace rc::app
