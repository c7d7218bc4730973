// TextRenderer: the label font of PNG legends and bench charts.
#include <gtest/gtest.h>

#include <string>

#include "core/error.h"
#include "core/text.h"

namespace {

TEST(TextRenderer, AMissingFontIsAnIoErrorNamingIt) {
  try {
    rc::TextRenderer text(11, "/nonexistent/font.ttf");
    ADD_FAILURE() << "a missing font was loaded";
  } catch (const rc::Error& e) {
    EXPECT_EQ(e.code(), rc::ExitCode::kIo);
    EXPECT_NE(std::string(e.what()).find("/nonexistent/font.ttf"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("fonts-dejavu-core"), std::string::npos) << e.what();
  }
}

TEST(TextRenderer, MeasuresWhatItDraws) {
  const rc::TextRenderer text(22);
  const int one = text.measure("m"), two = text.measure("mm");
  EXPECT_GT(one, 5);
  EXPECT_EQ(two, 2 * one);
  EXPECT_GT(rc::TextRenderer(11).measure("m"), 0);
  EXPECT_LT(rc::TextRenderer(11).measure("m"), one);
  rc::Rgb8Image image(80, 40, rc::Rgb8{255, 255, 255});
  EXPECT_EQ(text.draw(image, 4, 30, "mm", rc::Rgb8{0, 0, 0}), two);
  int inked = 0, beyond = 0;
  for (int y = 0; y < image.height; ++y) {
    for (int x = 0; x < image.width; ++x) {
      const bool ink = image.pixels[(std::size_t(y) * image.width + x) * 3] < 128;
      inked += ink;
      beyond += ink && (x >= 4 + two + 2 || y > 30);
    }
  }
  EXPECT_GT(inked, 50);
  EXPECT_EQ(beyond, 0) << "ink past the measured width or below the baseline";
}

}  // namespace

// Error messages quote bytes of input files: every control byte but newline and tab is written
// as \xNN, so a NUL cannot cut a message short where it is printed as a C string and an escape
// sequence cannot reach the terminal. Text, UTF-8 included, is kept as it is.
TEST(ErrorMessage, ControlBytesAreWrittenAsHex) {
  const std::string quoted = std::string("'1\x1b[2J' \0 \x7f\r", 12) + "\n\tkept: caf\xc3\xa9";
  const rc::Error e = rc::badInput("a.obj:3", quoted);
  EXPECT_EQ(std::string(e.what()), "a.obj:3: '1\\x1b[2J' \\x00 \\x7f\\x0d\n\tkept: caf\xc3\xa9");
  EXPECT_EQ(rc::printable("plain text"), "plain text");
}
