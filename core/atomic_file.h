// Output files appear whole or not at all: writers write to a temporary file in the target's
// folder and rename it into place on success; an abandoned temporary is removed. A target that
// is a symbolic link keeps it: the file it names is replaced. A device or pipe (/dev/null, a
// FIFO) is written in place, since a rename would replace the device itself.
//
// A process stopped by a signal (Ctrl-C) runs no destructor: removeTemporariesOnSignal makes
// SIGINT, SIGTERM, SIGHUP and SIGPIPE remove every temporary being written before the process
// dies of the signal, so an interrupted run leaves no partial file either.
#pragma once

#include <string>

namespace rc {

class AtomicOutput {
 public:
  // Throws ioError naming the path when its folder is missing or not writable, when it is a
  // folder, or when it is a file the user may not write (the rename would replace a read-only
  // file).
  explicit AtomicOutput(std::string finalPath);
  ~AtomicOutput();
  AtomicOutput(const AtomicOutput&) = delete;
  AtomicOutput& operator=(const AtomicOutput&) = delete;

  const std::string& tempPath() const { return tempPath_; }
  const std::string& finalPath() const { return finalPath_; }
  // Renames the temporary over the final path (nothing for a device); throws ioError on failure.
  void commit();

 private:
  std::string finalPath_;
  std::string tempPath_;
  std::string renameTo_;  // finalPath_, or the file it links to
  bool committed_ = false;
  bool direct_ = false;  // a device or pipe, written in place
  int signalSlot_ = -1;  // where removeTemporariesOnSignal finds tempPath_, or -1
};

// Installs the handlers described above (once, from main). A signal the process was started
// with ignored (nohup, a background job) stays ignored. Files already renamed into place stay:
// each is whole.
void removeTemporariesOnSignal();

// Writes `content` to `path` through an AtomicOutput; throws ioError naming the path.
void writeTextFile(const std::string& path, const std::string& content);

}  // namespace rc
