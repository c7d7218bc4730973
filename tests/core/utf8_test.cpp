// validUtf8: names that may be any bytes, made fit for JSON, SVG, HTML and XML.
#include <gtest/gtest.h>

#include <string>

#include "core/utf8.h"

namespace {

const std::string kFffd = "\xEF\xBF\xBD";

TEST(Utf8, ValidTextComesBackUnchanged) {
  for (const std::string& text : {std::string("blob:tris=1000"), std::string("caf\xC3\xA9.obj"),
                                 std::string("\xE2\x82\xAC \xF0\x9F\x99\x82 \xEF\xBF\xBF \xF4\x8F\xBF\xBF"),
                                 std::string("tab\tline\ncr\r"), std::string()}) {
    EXPECT_EQ(rc::validUtf8(text), text);
  }
}

TEST(Utf8, EachBadByteBecomesOneReplacementCharacter) {
  EXPECT_EQ(rc::validUtf8("bad\xFFname"), "bad" + kFffd + "name");
  EXPECT_EQ(rc::validUtf8("\x80"), kFffd);                                  // a stray continuation byte
  EXPECT_EQ(rc::validUtf8("\xC0\xAF"), kFffd + kFffd);                      // overlong '/'
  EXPECT_EQ(rc::validUtf8("\xE0\x80\xAF"), kFffd + kFffd + kFffd);          // overlong, three bytes
  EXPECT_EQ(rc::validUtf8("\xED\xA0\x80"), kFffd + kFffd + kFffd);          // a surrogate, U+D800
  EXPECT_EQ(rc::validUtf8("\xF4\x90\x80\x80"), kFffd + kFffd + kFffd + kFffd);  // past U+10FFFF
  EXPECT_EQ(rc::validUtf8("\xC3"), kFffd);                                  // truncated at the end
  EXPECT_EQ(rc::validUtf8("\xE2\x82x"), kFffd + kFffd + "x");               // cut short by ASCII
  EXPECT_EQ(rc::validUtf8("a\x01" "b\x1F" "c\x7F"), "a" + kFffd + "b" + kFffd + "c\x7F");  // C0 controls
}

}  // namespace
