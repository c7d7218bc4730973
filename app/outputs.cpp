// The files a command writes (outputs.h).
#include "app/outputs.h"

#include <sys/stat.h>
#include <sys/sysmacros.h>
#include <unistd.h>

#include <algorithm>
#include <cctype>
#include <cerrno>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <string>
#include <vector>

#include "core/error.h"
#include "scenes/scene_loader.h"  // lowerExtension

namespace rc::app {

namespace fs = std::filesystem;

namespace {

// Whether two paths name one file: the same file where both exist, else the same path once
// made absolute and normalised through what exists of it.
bool sameFile(const std::string& a, const std::string& b) {
  std::error_code ec, ea, eb;
  if (fs::exists(a, ec) && fs::exists(b, ec)) return fs::equivalent(a, b, ec);
  const fs::path pa = fs::weakly_canonical(a, ea), pb = fs::weakly_canonical(b, eb);
  return !ea && !eb && pa == pb;
}

// Whether `path` names what standard output is, where that is a file or a pipe (not a
// terminal or another device).
bool namesStandardOutput(const std::string& path) {
  struct stat out {}, named {};
  if (fstat(STDOUT_FILENO, &out) != 0 || stat(path.c_str(), &named) != 0) return false;
  if (!S_ISREG(out.st_mode) && !S_ISFIFO(out.st_mode) && !S_ISSOCK(out.st_mode)) return false;
  return out.st_dev == named.st_dev && out.st_ino == named.st_ino;
}

// Whether `path` is a terminal: the one this process's standard streams are on, or /dev/tty
// (the controlling terminal). Decided from the device numbers alone: opening a device to ask
// it can have effects of its own.
bool namesTerminal(const std::string& path) {
  struct stat named {};
  if (stat(path.c_str(), &named) != 0 || !S_ISCHR(named.st_mode)) return false;
  if (named.st_rdev == makedev(5, 0)) return true;  // /dev/tty
  for (const int fd : {STDIN_FILENO, STDOUT_FILENO, STDERR_FILENO}) {
    struct stat stream {};
    if (isatty(fd) && fstat(fd, &stream) == 0 && stream.st_rdev == named.st_rdev) return true;
  }
  return false;
}

}  // namespace

void takeStandardOutputByName(std::string& path) {
  if (!path.empty() && path != kStandardOutput && namesStandardOutput(path)) path = kStandardOutput;
}

void checkOutputs(const std::vector<OutputOption>& outputs, const std::vector<std::string>& inputs) {
  for (std::size_t i = 0; i < outputs.size(); ++i) {
    const OutputOption& out = outputs[i];
    if (out.path.empty()) continue;
    if (out.path == kStandardOutput) {
      if (!out.text) throw usageError(out.option + ": '-' (standard output) is only for --json and --csv");
      for (std::size_t j = 0; j < i; ++j) {
        if (outputs[j].path == kStandardOutput) {
          throw usageError(outputs[j].option + " and " + out.option + " both name standard output ('-')");
        }
      }
      continue;
    }
    if (!out.text && namesStandardOutput(out.path)) {
      throw usageError(out.option + ": " + out.path +
                       " is standard output, where the command's text goes too; name a file");
    }
    if (!out.text && namesTerminal(out.path)) {
      throw usageError(out.option + ": " + out.path + " is a terminal, which an image would only garble; name a file");
    }
    for (const std::string& input : inputs) {
      if (sameFile(out.path, input)) {
        throw usageError("output " + out.path + " is also an input; refusing to overwrite it");
      }
    }
    const std::string extension = lowerExtension(out.path);
    if (!out.extension.empty() && !extension.empty() && extension != out.extension) {
      std::string format = out.extension.substr(1);
      for (char& ch : format) ch = char(std::toupper(static_cast<unsigned char>(ch)));
      throw usageError(out.option + ": " + out.path + ": the file is written as " + format + "; name it " +
                       out.extension);
    }
    std::error_code ec;
    const fs::file_status status = fs::status(out.path, ec);
    if (out.extension == ".exr" && (fs::is_fifo(status) || fs::is_socket(status))) {
      throw usageError(out.option + ": " + out.path + ": an EXR cannot go into a pipe (OpenEXR seeks in its file); name a file");
    }
    // Two outputs into one device (/dev/null) are harmless; into one file, the last would win.
    if (fs::exists(status) && !fs::is_regular_file(status) && !fs::is_directory(status)) continue;
    for (std::size_t j = 0; j < i; ++j) {
      if (!outputs[j].path.empty() && sameFile(out.path, outputs[j].path)) {
        throw usageError(outputs[j].option + " and " + out.option + " name the same file " + out.path);
      }
    }
  }
}

void checkOutputFolders(const std::vector<OutputOption>& outputs) {
  for (const OutputOption& out : outputs) {
    if (!out.path.empty() && out.path != kStandardOutput) AtomicOutput probe(out.path);  // throws as a write would
  }
}

namespace {
int gDocumentFd = STDOUT_FILENO;  // where "-" writes: the process's standard output
}  // namespace

void routeTextAwayFromStandardOutput(const std::vector<OutputOption>& outputs) {
  const bool taken = std::any_of(outputs.begin(), outputs.end(),
                                 [](const OutputOption& out) { return out.path == kStandardOutput; });
  if (!taken || gDocumentFd != STDOUT_FILENO) return;
  std::fflush(stdout);
  const int document = dup(STDOUT_FILENO);
  if (document < 0 || dup2(STDERR_FILENO, STDOUT_FILENO) < 0) {
    throw ioError("standard output", std::string("cannot set it aside for the document: ") + std::strerror(errno));
  }
  gDocumentFd = document;
}

void WrittenOutputs::writeText(const std::string& path, const std::string& content) {
  if (path == kStandardOutput) {
    standardOutput_ = content;  // checkOutputs allows one
  } else if (!path.empty()) {
    writeTextFile(path, content);
  }
}

void WrittenOutputs::keep() {
  batch_.commit();
  std::fflush(stdout);
  for (std::size_t done = 0; done < standardOutput_.size();) {
    const ssize_t n = ::write(gDocumentFd, standardOutput_.data() + done, standardOutput_.size() - done);
    if (n < 0 && errno == EINTR) continue;
    if (n <= 0) throw ioError("standard output", std::string("cannot write: ") + std::strerror(errno));
    done += std::size_t(n);
  }
}

void WrittenOutputs::makeFolder(const std::string& dir) {
  std::error_code ec;
  std::vector<std::string> missing;
  for (fs::path p = fs::absolute(dir, ec); !ec && !p.empty() && p != p.parent_path(); p = p.parent_path()) {
    if (fs::exists(p, ec) || ec) break;
    missing.push_back(p.string());
  }
  ec.clear();
  fs::create_directories(dir, ec);
  if (!fs::is_directory(dir)) throw ioError(dir, "cannot create the output folder" + (ec ? ": " + ec.message() : ""));
  for (const std::string& level : missing) batch_.addFolder(level);  // deepest first
  if (access(dir.c_str(), W_OK) != 0) {
    throw ioError(dir, std::string("cannot write into the output folder: ") + std::strerror(errno));
  }
}

std::string fileStem(const std::string& scene, std::set<std::string>& used) {
  const fs::path path(scene);
  const std::string source = path.has_extension() ? path.stem().string() : scene;
  std::string stem;
  for (char c : source) {
    const bool plain = std::isalnum(static_cast<unsigned char>(c)) || c == '-' || c == '_' || c == '.';
    stem += plain ? c : (c == '=' ? '-' : '_');
  }
  std::string unique = stem;
  for (int n = 2; !used.insert(unique).second; ++n) unique = stem + "-" + std::to_string(n);
  return unique;
}

}  // namespace rc::app
