// Output files appear whole or not at all: writers write to a temporary file in the target's
// folder and rename it into place on success; an abandoned temporary is removed.
#pragma once

#include <string>

namespace rc {

class AtomicOutput {
 public:
  // Throws ioError naming the path when its folder is missing, when it is a folder, or when
  // it is a file the user may not write (the rename would replace a read-only file).
  explicit AtomicOutput(std::string finalPath);
  ~AtomicOutput();
  AtomicOutput(const AtomicOutput&) = delete;
  AtomicOutput& operator=(const AtomicOutput&) = delete;

  const std::string& tempPath() const { return tempPath_; }
  const std::string& finalPath() const { return finalPath_; }
  // Renames the temporary over the final path; throws ioError on failure.
  void commit();

 private:
  std::string finalPath_;
  std::string tempPath_;
  bool committed_ = false;
};

// Writes `content` to `path` through an AtomicOutput; throws ioError naming the path.
void writeTextFile(const std::string& path, const std::string& content);

}  // namespace rc
