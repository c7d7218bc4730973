// WrittenOutputs: a command's files all or none, and its standard-output document only once
// every file is in place.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <string>

#include "app/options.h"
#include "core/error.h"
#include "tests/test_files.h"

namespace rc::app {
namespace {

namespace fs = std::filesystem;

TEST(WrittenOutputs, StandardOutputGetsTheDocumentOnlyOnceEveryFileIsInPlace) {
  const testing::TempDir temp;
  const std::string file = (temp.path() / "report.json").string();

  ::testing::internal::CaptureStdout();
  {
    WrittenOutputs outputs;
    outputs.writeText(kStandardOutput, "document\n");
    outputs.writeText(file, "{}\n");
  }  // failed part way: never kept
  EXPECT_EQ(::testing::internal::GetCapturedStdout(), "");
  EXPECT_FALSE(fs::exists(file));

  ::testing::internal::CaptureStdout();
  {
    WrittenOutputs outputs;
    outputs.writeText(kStandardOutput, "document\n");
    outputs.writeText(file, "{}\n");
    outputs.keep();
  }
  EXPECT_EQ(::testing::internal::GetCapturedStdout(), "document\n");
  EXPECT_TRUE(fs::exists(file));

  // A file that cannot be put in place at the end (a folder now stands at its name): the
  // command fails, and the document is not written.
  const std::string late = (temp.path() / "late.json").string();
  ::testing::internal::CaptureStdout();
  {
    WrittenOutputs outputs;
    outputs.writeText(kStandardOutput, "document\n");
    outputs.writeText(late, "{}\n");
    fs::create_directories(fs::path(late) / "in the way");
    EXPECT_THROW(outputs.keep(), Error);
  }
  EXPECT_EQ(::testing::internal::GetCapturedStdout(), "");
  EXPECT_TRUE(fs::is_directory(late));
}

}  // namespace
}  // namespace rc::app
