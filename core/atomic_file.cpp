// AtomicOutput: temporary file in the target folder, then rename.
#include "core/atomic_file.h"

#include <unistd.h>

#include <atomic>
#include <cerrno>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>

#include "core/error.h"

namespace rc {
namespace fs = std::filesystem;

AtomicOutput::AtomicOutput(std::string finalPath) : finalPath_(std::move(finalPath)) {
  static std::atomic<unsigned> counter{0};
  fs::path target(finalPath_);
  fs::path folder = target.parent_path();
  if (folder.empty()) folder = ".";
  std::error_code ec;
  if (!fs::is_directory(folder, ec)) {
    throw ioError(finalPath_, "cannot write: folder '" + folder.string() + "' does not exist");
  }
  if (fs::is_directory(target, ec)) {
    throw ioError(finalPath_, "cannot write: it is a folder");
  }
  // The rename would replace a file its owner made read-only: it must stay as it is.
  if (fs::exists(target, ec) && access(finalPath_.c_str(), W_OK) != 0) {
    throw ioError(finalPath_, std::string("cannot write: ") + std::strerror(errno));
  }
  tempPath_ = (folder / ("." + target.filename().string() + ".tmp-" + std::to_string(getpid()) +
                         "-" + std::to_string(counter.fetch_add(1))))
                  .string();
}

AtomicOutput::~AtomicOutput() {
  if (!committed_) std::remove(tempPath_.c_str());
}

void AtomicOutput::commit() {
  if (std::rename(tempPath_.c_str(), finalPath_.c_str()) != 0) {
    int err = errno;
    std::remove(tempPath_.c_str());
    throw ioError(finalPath_, std::string("cannot write: ") + std::strerror(err));
  }
  committed_ = true;
}

void writeTextFile(const std::string& path, const std::string& content) {
  AtomicOutput out(path);
  {
    std::ofstream stream(out.tempPath(), std::ios::binary | std::ios::trunc);
    if (!stream) throw ioError(path, std::string("cannot write: ") + std::strerror(errno));
    stream << content;
    stream.flush();
    if (!stream) throw ioError(path, "write failed (disk full?)");
  }
  out.commit();
}

}  // namespace rc
