// Outputs appear whole or not at all.
#include <gtest/gtest.h>

#include <sys/stat.h>
#include <sys/sysmacros.h>
#include <sys/wait.h>
#include <unistd.h>

#include <csignal>

#include <algorithm>
#include <cerrno>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>
#include <vector>

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

std::string readText(const fs::path& path) { return rc::testing::readFile(path); }

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

std::vector<std::string> filesIn(const fs::path& dir) {
  std::vector<std::string> names;
  for (const fs::directory_entry& entry : fs::directory_iterator(dir)) names.push_back(entry.path().filename().string());
  std::sort(names.begin(), names.end());
  return names;
}

// Ctrl-C (or kill) runs no destructor: the handlers remove the temporary being written, keep
// what was already committed, and the process still dies of the signal, as a shell expects.
TEST(AtomicOutput, ASignalRemovesTheTemporaryBeingWritten) {
  for (int signal : {SIGINT, SIGTERM, SIGHUP, SIGPIPE}) {
    const testing::TempDir temp;
    const pid_t child = fork();
    ASSERT_GE(child, 0);
    if (child == 0) {
      removeTemporariesOnSignal();
      writeTextFile((temp.path() / "done.json").string(), "whole");
      AtomicOutput out((temp.path() / "result.exr").string());
      std::ofstream(out.tempPath()) << "partial";
      std::raise(signal);
      _exit(0);  // not reached
    }
    int status = 0;
    ASSERT_EQ(waitpid(child, &status, 0), child);
    ASSERT_TRUE(WIFSIGNALED(status)) << "signal " << signal << ": the process must die of it";
    EXPECT_EQ(WTERMSIG(status), signal);
    EXPECT_EQ(filesIn(temp.path()), std::vector<std::string>{"done.json"}) << "signal " << signal;
  }
}

// A batch holds its temporaries until it commits, and a check of many scenes with --out and
// --report holds more than a thousand: a signal removes every one.
TEST(OutputBatch, ASignalRemovesEveryTemporaryItHoldsHoweverMany) {
  const testing::TempDir temp;
  constexpr int kFiles = 1500;
  const pid_t child = fork();
  ASSERT_GE(child, 0);
  if (child == 0) {
    removeTemporariesOnSignal();
    OutputBatch batch;
    for (int i = 0; i < kFiles; ++i) writeTextFile((temp.path() / ("f" + std::to_string(i) + ".json")).string(), "x");
    if (filesIn(temp.path()).size() != std::size_t(kFiles)) _exit(3);  // every temporary written
    std::raise(SIGTERM);
    _exit(0);  // not reached
  }
  int status = 0;
  ASSERT_EQ(waitpid(child, &status, 0), child);
  ASSERT_TRUE(WIFSIGNALED(status)) << "exit status " << status;
  EXPECT_EQ(WTERMSIG(status), SIGTERM);
  EXPECT_EQ(filesIn(temp.path()).size(), 0u);
}

// Within a batch nothing is in place until it commits; a batch discarded leaves every file as
// it was, and a signal removes the finished temporaries the batch holds too.
TEST(OutputBatch, RenamesEverythingAtCommitAndNothingOtherwise) {
  const testing::TempDir temp;
  const fs::path& dir = temp.path();
  std::ofstream(dir / "a.json") << "old";
  {
    OutputBatch batch;
    writeTextFile((dir / "a.json").string(), "new");
    writeTextFile((dir / "b.json").string(), "new");
    EXPECT_EQ(readText(dir / "a.json"), "old") << "in place before the commit";
    EXPECT_FALSE(fs::exists(dir / "b.json"));
    EXPECT_EQ(filesIn(dir).size(), 3u) << "a.json and two temporaries";
  }  // discarded
  EXPECT_EQ(filesIn(dir), std::vector<std::string>{"a.json"});
  EXPECT_EQ(readText(dir / "a.json"), "old");
  {
    OutputBatch batch;
    writeTextFile((dir / "a.json").string(), "new");
    writeTextFile((dir / "b.json").string(), "new");
    batch.commit();
    EXPECT_EQ(readText(dir / "a.json"), "new");
    EXPECT_EQ(readText(dir / "b.json"), "new");
    writeTextFile((dir / "c.json").string(), "at once");  // the commit closed the batch
    EXPECT_EQ(readText(dir / "c.json"), "at once");
  }
  EXPECT_EQ(filesIn(dir), (std::vector<std::string>{"a.json", "b.json", "c.json"}));

  const pid_t child = fork();
  ASSERT_GE(child, 0);
  if (child == 0) {
    removeTemporariesOnSignal();
    OutputBatch batch;
    fs::create_directories(dir / "made" / "deeper");
    batch.addFolder((dir / "made" / "deeper").string());
    batch.addFolder((dir / "made").string());
    writeTextFile((dir / "a.json").string(), "interrupted");
    writeTextFile((dir / "made" / "deeper" / "d.json").string(), "interrupted");
    std::raise(SIGTERM);
    _exit(0);  // not reached
  }
  int status = 0;
  ASSERT_EQ(waitpid(child, &status, 0), child);
  ASSERT_TRUE(WIFSIGNALED(status));
  EXPECT_EQ(filesIn(dir), (std::vector<std::string>{"a.json", "b.json", "c.json"})) << "the folders made go too";
  EXPECT_EQ(readText(dir / "a.json"), "new");
}

// The folders made for a batch's outputs go with a discard, where empty, and stay at a commit.
TEST(OutputBatch, FoldersMadeForItGoWhenItIsDiscarded) {
  const testing::TempDir temp;
  const fs::path& dir = temp.path();
  for (bool commit : {false, true}) {
    OutputBatch batch;
    fs::create_directories(dir / "made" / "deeper");
    batch.addFolder((dir / "made" / "deeper").string());
    batch.addFolder((dir / "made").string());
    writeTextFile((dir / "made" / "deeper" / "x.json").string(), "x");
    if (commit) {
      batch.commit();
      EXPECT_EQ(readText(dir / "made" / "deeper" / "x.json"), "x");
    } else {
      batch.discard();
      EXPECT_FALSE(fs::exists(dir / "made"));
    }
  }
  // A folder that is not empty stays.
  fs::create_directories(dir / "kept");
  std::ofstream(dir / "kept" / "theirs.txt") << "theirs";
  {
    OutputBatch batch;
    batch.addFolder((dir / "kept").string());
  }
  EXPECT_EQ(readText(dir / "kept" / "theirs.txt"), "theirs");
}

// A signal the process was started with ignored (nohup, a background job) stays ignored.
TEST(AtomicOutput, ASignalIgnoredAtStartStaysIgnored) {
  const testing::TempDir temp;
  const pid_t child = fork();
  ASSERT_GE(child, 0);
  if (child == 0) {
    std::signal(SIGHUP, SIG_IGN);
    removeTemporariesOnSignal();
    {
      AtomicOutput out((temp.path() / "result.json").string());
      std::ofstream(out.tempPath()) << "whole";
      std::raise(SIGHUP);
      out.commit();
    }
    _exit(7);
  }
  int status = 0;
  ASSERT_EQ(waitpid(child, &status, 0), child);
  ASSERT_TRUE(WIFEXITED(status));
  EXPECT_EQ(WEXITSTATUS(status), 7);
  EXPECT_EQ(filesIn(temp.path()), std::vector<std::string>{"result.json"});
}

}  // namespace
}  // namespace rc
