// Running the rastercheck binary (or any shell command) from tests, as a user would.
#pragma once

#include <sys/wait.h>

#include <array>
#include <cstdio>
#include <cstdlib>
#include <stdexcept>
#include <string>

namespace rc::testing {

struct CommandResult {
  int exitCode;        // -1 when the command did not exit normally
  std::string output;  // stdout and stderr together
};

inline CommandResult runCommand(const std::string& command) {
  FILE* pipe = popen((command + " 2>&1").c_str(), "r");
  if (!pipe) throw std::runtime_error("cannot run: " + command);
  std::string output;
  std::array<char, 4096> buffer;
  while (std::size_t n = std::fread(buffer.data(), 1, buffer.size(), pipe)) output.append(buffer.data(), n);
  const int status = pclose(pipe);
  return {WIFEXITED(status) ? WEXITSTATUS(status) : -1, output};
}

// The binary ctest points RASTERCHECK_EXE at; `env` is prepended (e.g. "LC_ALL=C").
inline std::string rastercheckExe() {
  const char* exe = std::getenv("RASTERCHECK_EXE");
  if (!exe) throw std::runtime_error("RASTERCHECK_EXE is not set; run through ctest");
  return exe;
}

inline CommandResult runRastercheck(const std::string& args, const std::string& env = "") {
  return runCommand(env + " " + rastercheckExe() + " " + args);
}

}  // namespace rc::testing
