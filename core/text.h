// Drawing short labels into 8-bit images with FreeType and DejaVu Sans (Debian
// fonts-dejavu-core), for legends people read without special software.
#pragma once

#include <string>

#include "core/png_io.h"

namespace rc {

inline constexpr const char* kLabelFont = "/usr/share/fonts/truetype/dejavu/DejaVuSans.ttf";

class TextRenderer {
 public:
  // Throws ioError naming the font when it cannot be loaded.
  explicit TextRenderer(int pixelHeight, const std::string& fontPath = kLabelFont);
  ~TextRenderer();
  TextRenderer(const TextRenderer&) = delete;
  TextRenderer& operator=(const TextRenderer&) = delete;

  // Draws ASCII `text` with its baseline at y, starting at x; returns the width drawn.
  int draw(Rgb8Image& image, int x, int baseline, const std::string& text, Rgb8 colour) const;
  int measure(const std::string& text) const;

 private:
  struct Impl;
  Impl* impl_;
};

}  // namespace rc
