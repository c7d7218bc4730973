// Outputs appear whole or not at all.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>

#include "core/atomic_file.h"
#include "core/error.h"
#include "tests/test_files.h"

namespace rc {
namespace {

namespace fs = std::filesystem;

TEST(AtomicOutput, AbandonedOutputLeavesNoFile) {
  const testing::TempDir temp;  // removed at the end of the test
  const fs::path& dir = temp.path();
  {
    AtomicOutput out((dir / "result.json").string());
    std::ofstream(out.tempPath()) << "partial";
  }  // never committed
  EXPECT_TRUE(fs::is_empty(dir));
}

TEST(AtomicOutput, CommitReplacesTheTarget) {
  const testing::TempDir temp;  // removed at the end of the test
  const fs::path& dir = temp.path();
  std::ofstream(dir / "result.json") << "old";
  writeTextFile((dir / "result.json").string(), "new");
  std::ifstream in(dir / "result.json");
  std::string text;
  in >> text;
  EXPECT_EQ(text, "new");
  EXPECT_EQ(std::distance(fs::directory_iterator(dir), fs::directory_iterator()), 1);
}

}  // namespace
}  // namespace rc
