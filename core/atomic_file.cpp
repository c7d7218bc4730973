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
  const fs::file_status status = fs::status(target, ec);  // through symbolic links
  if (fs::is_directory(status)) {
    throw ioError(finalPath_, "cannot write: it is a folder");
  }
  if (fs::exists(status)) {
    // The rename would replace a file its owner made read-only: it must stay as it is.
    if (access(finalPath_.c_str(), W_OK) != 0) {
      throw ioError(finalPath_, std::string("cannot write: ") + std::strerror(errno));
    }
    if (!fs::is_regular_file(status)) {
      // A device, pipe or socket (/dev/null, /dev/stdout on a terminal, a FIFO) is written
      // straight into: renaming over it would replace the device with a file.
      tempPath_ = finalPath_;
      direct_ = true;
      return;
    }
    if (fs::is_symlink(fs::symlink_status(target, ec))) {
      // Write the file the link names, and keep the link.
      target = fs::canonical(target, ec);
      if (ec) throw ioError(finalPath_, "cannot follow the link: " + ec.message());
      folder = target.parent_path();
    }
  }
  // The temporary goes into the folder: one the user may not write fails here, before the work.
  if (access(folder.c_str(), W_OK) != 0) {
    throw ioError(finalPath_, "cannot write into folder '" + folder.string() + "': " + std::strerror(errno));
  }
  tempPath_ = (folder / ("." + target.filename().string() + ".tmp-" + std::to_string(getpid()) +
                         "-" + std::to_string(counter.fetch_add(1))))
                  .string();
  renameTo_ = target.string();
}

AtomicOutput::~AtomicOutput() {
  if (!committed_ && !direct_) std::remove(tempPath_.c_str());
}

void AtomicOutput::commit() {
  if (!direct_ && std::rename(tempPath_.c_str(), renameTo_.c_str()) != 0) {
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
