// Errors that carry what went wrong and where, and the exit codes the CLI maps them to.
// Library code throws these; only app/main.cpp catches them (STYLE.md: no printing or exit()
// in library code). Comparison outcomes are not errors: they are verdicts (compare/gate.h).
#pragma once

#include <stdexcept>
#include <string>
#include <string_view>

namespace rc {

// The documented exit codes of every rastercheck command (README.md, "Exit codes").
enum class ExitCode : int {
  kPass = 0,        // the command did what was asked; for check/compare: the gate passed
  kGateFailed = 1,  // check/compare ran and the accuracy gate failed
  kUsage = 2,       // bad command line: unknown option, missing or out-of-range value
  kBadInput = 3,    // a scene, mesh or image is invalid, or two images are incompatible
  kIo = 4,          // a file could not be read or written (missing, permissions, disk full), or memory ran out
  kInternal = 5,    // a library (Embree, OpenEXR) failed in a way no input explains: a bug
};

// The message with every control byte but newline and tab written as \xNN. Messages quote
// bytes of input files (a token, a URI, a parser's excerpt): raw, a NUL would cut the message
// short where it is printed as a C string, and an escape sequence would reach the terminal.
inline std::string printable(std::string_view message) {
  std::string out;
  out.reserve(message.size());
  for (const char c : message) {
    const auto byte = static_cast<unsigned char>(c);
    if ((byte < 0x20 && c != '\n' && c != '\t') || byte == 0x7f) {
      constexpr char kHex[] = "0123456789abcdef";
      out += "\\x";
      out += kHex[byte >> 4];
      out += kHex[byte & 15];
    } else {
      out += c;
    }
  }
  return out;
}

class Error : public std::runtime_error {
 public:
  Error(ExitCode code, const std::string& message) : std::runtime_error(printable(message)), code_(code) {}
  ExitCode code() const { return code_; }

 private:
  ExitCode code_;
};

// `where` names the file and the place in it (line, channel, JSON pointer, ...).
inline Error usageError(const std::string& what) { return Error(ExitCode::kUsage, what); }
inline Error badInput(const std::string& where, const std::string& what) {
  return Error(ExitCode::kBadInput, where + ": " + what);
}
inline Error ioError(const std::string& where, const std::string& what) {
  return Error(ExitCode::kIo, where + ": " + what);
}
inline Error internalError(const std::string& what) { return Error(ExitCode::kInternal, what); }
// Memory ran out: not the input's fault nor a bug, a resource like a full disk (exit 4).
inline Error outOfMemory(const std::string& where, const std::string& what) {
  return Error(ExitCode::kIo, where + ": out of memory " + what);
}

}  // namespace rc
