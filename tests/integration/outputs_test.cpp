// WrittenOutputs: a command's files all or none, and its standard-output document only once
// every file is in place.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <iterator>
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

  // Failing at the second file: the first is in place, and the error names the second.
  const std::string first = (temp.path() / "first.json").string();
  const std::string second = (temp.path() / "second.json").string();
  {
    WrittenOutputs outputs;
    outputs.writeText(first, "{}\n");
    outputs.writeText(second, "{}\n");
    fs::create_directories(fs::path(second) / "in the way");
    try {
      outputs.keep();
      ADD_FAILURE() << "keep() must fail at " << second;
    } catch (const Error& e) {
      EXPECT_NE(std::string(e.what()).find("second.json"), std::string::npos) << e.what();
    }
  }
  EXPECT_TRUE(fs::exists(first));
  EXPECT_EQ(std::distance(fs::directory_iterator(second), fs::directory_iterator()), 1) << "only the folder in the way";
  EXPECT_EQ(std::distance(fs::directory_iterator(temp.path()), fs::directory_iterator()), 4)
      << "report.json, late.json, first.json, second.json: no temporary left";
}

}  // namespace
}  // namespace rc::app
