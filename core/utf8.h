// Text that must be valid UTF-8 (JSON, SVG, HTML, XML) made so from names that need not be: a
// Linux file name is any bytes but '/' and NUL.
#pragma once

#include <string>

namespace rc {

// `text` with each byte that does not start a well-formed UTF-8 sequence (a stray continuation
// byte, an overlong form, a surrogate, a code point past U+10FFFF, a truncated sequence)
// replaced by U+FFFD, as are the C0 controls other than tab, line feed and carriage return,
// which XML 1.0 does not allow. Valid text comes back unchanged.
inline std::string validUtf8(const std::string& text) {
  static const char kReplacement[] = "\xEF\xBF\xBD";
  std::string out;
  out.reserve(text.size());
  const auto byte = [&](std::size_t i) { return static_cast<unsigned char>(text[i]); };
  for (std::size_t i = 0; i < text.size();) {
    const unsigned char c = byte(i);
    if (c < 0x80) {
      const bool allowed = c >= 0x20 || c == '\t' || c == '\n' || c == '\r';
      out += allowed ? std::string(1, char(c)) : std::string(kReplacement);
      ++i;
      continue;
    }
    // The length of the sequence c starts, and the range its second byte must lie in (which
    // rules out overlong forms, surrogates and code points past U+10FFFF).
    std::size_t length = 0;
    unsigned char low = 0x80, high = 0xBF;
    if (c >= 0xC2 && c <= 0xDF) {
      length = 2;
    } else if (c >= 0xE0 && c <= 0xEF) {
      length = 3;
      if (c == 0xE0) low = 0xA0;
      if (c == 0xED) high = 0x9F;
    } else if (c >= 0xF0 && c <= 0xF4) {
      length = 4;
      if (c == 0xF0) low = 0x90;
      if (c == 0xF4) high = 0x8F;
    }
    bool ok = length > 0 && i + length <= text.size() && byte(i + 1) >= low && byte(i + 1) <= high;
    for (std::size_t k = 2; ok && k < length; ++k) ok = byte(i + k) >= 0x80 && byte(i + k) <= 0xBF;
    if (ok) {
      out.append(text, i, length);
      i += length;
    } else {
      out += kReplacement;
      ++i;
    }
  }
  return out;
}

}  // namespace rc
