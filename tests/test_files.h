// Temporary folders and files for tests, and a check that a call fails with a given exit code
// and a message naming the place.
#pragma once

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <functional>
#include <iterator>
#include <string>
#include <vector>

#include "core/error.h"

namespace rc::testing {

// A fresh folder named after the running test, removed at the end.
class TempDir {
 public:
  TempDir() {
    const auto* info = ::testing::UnitTest::GetInstance()->current_test_info();
    path_ = std::filesystem::temp_directory_path() /
            (std::string("rc_") + info->test_suite_name() + "_" + info->name());
    std::filesystem::remove_all(path_);
    std::filesystem::create_directories(path_);
  }
  ~TempDir() { std::filesystem::remove_all(path_); }
  std::string file(const std::string& name) const { return (path_ / name).string(); }
  std::string write(const std::string& name, const std::string& content) const {
    std::filesystem::create_directories((path_ / name).parent_path());
    std::ofstream(path_ / name, std::ios::binary) << content;
    return file(name);
  }
  const std::filesystem::path& path() const { return path_; }

 private:
  std::filesystem::path path_;
};

// The whole file as bytes ("" when it cannot be read).
inline std::string readFile(const std::filesystem::path& path) {
  std::ifstream in(path, std::ios::binary);
  return std::string((std::istreambuf_iterator<char>(in)), {});
}

// How many times `needle` occurs in `text`, overlaps counted.
inline int occurrences(const std::string& text, const std::string& needle) {
  int n = 0;
  for (std::size_t at = text.find(needle); at != std::string::npos; at = text.find(needle, at + 1)) ++n;
  return n;
}

// Runs fn; expects an rc::Error with `code` whose message contains every fragment.
inline void expectError(const std::function<void()>& fn, ExitCode code, const std::vector<std::string>& fragments,
                        const std::string& what) {
  try {
    fn();
    ADD_FAILURE() << what << ": no error";
  } catch (const Error& e) {
    EXPECT_EQ(int(e.code()), int(code)) << what << ": " << e.what();
    for (const std::string& f : fragments) {
      EXPECT_NE(std::string(e.what()).find(f), std::string::npos) << what << ": '" << f << "' not in: " << e.what();
    }
  }
}

// Where ../shared/data is ($RASTERCHECK_SHARED_DATA, else the folder beside the checkout), or
// empty: tests then skip and say so plainly.
inline std::string sharedData() {
  const char* env = std::getenv("RASTERCHECK_SHARED_DATA");
  const std::string dir = env ? env : RASTERCHECK_SHARED_DATA_DIR;
  return std::filesystem::is_directory(dir) ? dir : "";
}

}  // namespace rc::testing
