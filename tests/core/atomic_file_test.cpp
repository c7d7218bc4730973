// Outputs appear whole or not at all.
#include <gtest/gtest.h>

#include <sys/stat.h>
#include <sys/sysmacros.h>

#include <cerrno>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>

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

std::string readText(const fs::path& path) {
  std::ifstream in(path);
  return std::string((std::istreambuf_iterator<char>(in)), {});
}

// A link stays a link: the file it names gets the output.
TEST(AtomicOutput, ALinkKeepsPointingAtTheFileItNames) {
  const testing::TempDir temp;
  const fs::path& dir = temp.path();
  fs::create_directories(dir / "elsewhere");
  std::ofstream(dir / "elsewhere" / "result.json") << "old";
  fs::create_symlink(dir / "elsewhere" / "result.json", dir / "link.json");
  writeTextFile((dir / "link.json").string(), "new");
  EXPECT_TRUE(fs::is_symlink(dir / "link.json"));
  EXPECT_EQ(readText(dir / "elsewhere" / "result.json"), "new");
  EXPECT_EQ(std::distance(fs::directory_iterator(dir / "elsewhere"), fs::directory_iterator()), 1) << "no temporary left";
}

// A device is written in place, and an abandoned write leaves it there: renaming over
// /dev/null, as root, would replace the device with a file (and removing it, delete it).
TEST(AtomicOutput, ADeviceIsWrittenInPlaceNeverReplaced) {
  const testing::TempDir temp;
  const fs::path null = temp.path() / "null";
  if (mknod(null.c_str(), S_IFCHR | 0666, makedev(1, 3)) != 0) {
    GTEST_SKIP() << "cannot make a device node here (not root): " << std::strerror(errno);
  }
  writeTextFile(null.string(), "into the void");
  EXPECT_TRUE(fs::is_character_file(null));
  {
    AtomicOutput out(null.string());
    EXPECT_EQ(out.tempPath(), null.string());
  }  // never committed
  EXPECT_TRUE(fs::is_character_file(null));
  EXPECT_EQ(std::distance(fs::directory_iterator(temp.path()), fs::directory_iterator()), 1);
}

}  // namespace
}  // namespace rc
