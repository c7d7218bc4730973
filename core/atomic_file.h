// Output files appear whole or not at all: writers write to a temporary file in the target's
// folder and rename it into place on success; an abandoned temporary is removed. A target that
// is a symbolic link keeps it: the file it names is replaced. A device or pipe (/dev/null, a
// FIFO) is written in place, since a rename would replace the device itself.
//
// A process stopped by a signal (Ctrl-C) runs no destructor: removeTemporariesOnSignal makes
// SIGINT, SIGTERM, SIGHUP and SIGPIPE remove every temporary being written (and an open
// OutputBatch's, and the folders made for it) before the process dies of the signal, so an
// interrupted run leaves no partial file either.
#pragma once

#include <mutex>
#include <string>
#include <utility>
#include <vector>

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
  // While an OutputBatch is open the temporary stays, and the batch renames it.
  void commit();

 private:
  std::string finalPath_;
  std::string tempPath_;
  std::string renameTo_;  // finalPath_, or the file it links to
  bool committed_ = false;
  bool direct_ = false;  // a device or pipe, written in place
  int signalSlot_ = -1;  // where removeTemporariesOnSignal finds tempPath_, or -1
};

// While an OutputBatch is open, AtomicOutput::commit() leaves each finished temporary where it
// is, and the batch's commit() renames them all into place, in the order they were finished. A
// batch closed without commit() removes them: a command that writes many files and fails part
// way (the disk full at the tenth) leaves every file as it was before it ran, the ones it would
// have replaced included. A device is still written in place, at once. One batch is open at a
// time; commit() and discard() close it, and outputs after that are renamed at once.
class OutputBatch {
 public:
  OutputBatch();
  ~OutputBatch() { discard(); }
  OutputBatch(const OutputBatch&) = delete;
  OutputBatch& operator=(const OutputBatch&) = delete;

  // Renames every finished temporary into place; throws ioError naming the output whose rename
  // failed, and then discards the ones after it (those before it are in place).
  void commit();
  // Removes every temporary not yet renamed, then the folders added, where empty.
  void discard();
  // A folder made for the outputs (add the deepest level first): discard() and a signal remove
  // it when empty; commit() keeps it.
  void addFolder(const std::string& path);

 private:
  friend class AtomicOutput;
  struct Finished {
    std::string temp, target, finalPath;
    int signalSlot;
  };
  void adopt(Finished finished);
  void close();  // no longer the open batch

  std::mutex mutex_;
  std::vector<Finished> finished_;
  std::vector<std::pair<std::string, int>> folders_;  // path, signal slot; deepest first
};

// Installs the handlers described above (once, from main). A signal the process was started
// with ignored (nohup, a background job) stays ignored. Files already renamed into place stay:
// each is whole.
void removeTemporariesOnSignal();

// Writes `content` to `path` through an AtomicOutput; throws ioError naming the path.
void writeTextFile(const std::string& path, const std::string& content);

}  // namespace rc
