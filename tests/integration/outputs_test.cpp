// WrittenOutputs: a command's files all or none, and its standard-output document only once
// every file is in place.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>

#include <png.h>

#include "app/outputs.h"
#include "core/png_io.h"
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

// The PNG writer's zlib level and filter are its own choice; what it writes must decode to
// exactly the pixels given, also where the Sub filter's differences wrap around.
TEST(PngIo, WritesExactlyThePixelsGiven) {
  const testing::TempDir temp;
  const std::string path = (temp.path() / "picture.png").string();
  Rgb8Image image(317, 45, {0, 0, 0});
  std::uint32_t state = 12345;
  for (int y = 0; y < image.height; ++y) {
    for (int x = 0; x < image.width; ++x) {
      state = state * 1664525u + 1013904223u;
      const std::uint8_t noise = std::uint8_t(state >> 24);
      // Smooth ramps, hard steps and noise, row by row.
      const std::uint8_t r = std::uint8_t(x), g = std::uint8_t(x % 7 == 0 ? 255 : 3 * y), b = y % 3 == 0 ? noise : std::uint8_t(x ^ y);
      image.set(x, y, {r, g, b});
    }
  }
  writePng(image, path);
  png_image read{};
  read.version = PNG_IMAGE_VERSION;
  ASSERT_TRUE(png_image_begin_read_from_file(&read, path.c_str()));
  read.format = PNG_FORMAT_RGB;
  ASSERT_EQ(read.width, 317u);
  ASSERT_EQ(read.height, 45u);
  std::vector<std::uint8_t> pixels(PNG_IMAGE_SIZE(read));
  ASSERT_TRUE(png_image_finish_read(&read, nullptr, pixels.data(), 0, nullptr));
  EXPECT_EQ(pixels, image.pixels);
}

}  // namespace
}  // namespace rc::app
