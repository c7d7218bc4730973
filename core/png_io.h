// 8-bit RGB images for people: PNG output of previews and heatmaps (EXR stays the data).
#pragma once

#include <array>
#include <cstdint>
#include <string>
#include <vector>

#include "core/framebuffer.h"

namespace rc {

using Rgb8 = std::array<std::uint8_t, 3>;

struct Rgb8Image {
  int width = 0, height = 0;
  std::vector<std::uint8_t> pixels;  // RGB, row 0 at the top

  Rgb8Image() = default;
  Rgb8Image(int w, int h, Rgb8 fill);
  void set(int x, int y, Rgb8 c);
  // Copies `other` with its top-left corner at (x, y), clipped to this image.
  void paste(const Rgb8Image& other, int x, int y);
};

// sRGB-encoded 8-bit image of the linear channels R, G, B (clamped to [0, 1]); throws
// internalError when the framebuffer has no R, G, B.
Rgb8Image displayImage(const Framebuffer& fb);

// Writes an RGB PNG through a temporary file renamed into place; throws ioError.
void writePng(const Rgb8Image& image, const std::string& path);

}  // namespace rc
