// Heatmap picture with legend.
#include "compare/heatmap_png.h"

#include <algorithm>
#include <cmath>

#include "compare/colormap.h"
#include "core/text.h"

namespace rc {
namespace {

constexpr int kLegendWidth = 760;
constexpr int kLegendHeight = 84;
constexpr Rgb8 kPanel{70, 70, 70};  // lighter than the "empty" grey, so its swatch shows
constexpr Rgb8 kInk{235, 235, 235};

Rgb8 toRgb8(const Rgb& c) {
  // The colour map is already display-referred: quantise directly.
  return {std::uint8_t(std::lround(std::clamp(c[0], 0.f, 1.f) * 255)),
          std::uint8_t(std::lround(std::clamp(c[1], 0.f, 1.f) * 255)),
          std::uint8_t(std::lround(std::clamp(c[2], 0.f, 1.f) * 255))};
}

void fill(Rgb8Image& image, int x0, int y0, int w, int h, Rgb8 c) {
  for (int y = y0; y < y0 + h; ++y) {
    for (int x = x0; x < x0 + w; ++x) image.set(x, y, c);
  }
}

void drawLegend(Rgb8Image& image, int top, const HeatScale& scale) {
  fill(image, 0, top, image.width, kLegendHeight, kPanel);
  const TextRenderer text(13);
  text.draw(image, 10, top + 17, scale.title, kInk);
  // Colour bar: one column per step, decade ticks labelled below.
  const int barX = 10, barY = top + 24, barW = 420, barH = 16;
  for (int i = 0; i < barW; ++i) {
    const Rgb8 c = toRgb8(magma(double(i) / (barW - 1)));
    fill(image, barX + i, barY, 1, barH, c);
  }
  for (int decade = int(scale.logMin); decade <= int(scale.logMax); ++decade) {
    const int x = barX + int(std::lround((decade - scale.logMin) / (scale.logMax - scale.logMin) * (barW - 1)));
    fill(image, x, barY + barH, 1, 4, kInk);
    const std::string label = "1e" + std::to_string(decade);
    text.draw(image, std::clamp(x - text.measure(label) / 2, 0, image.width - 40), barY + barH + 17, label, kInk);
  }
  // Reserved class colours, never produced by the colour map.
  const struct { Rgb colour; const char* label; } swatches[] = {
      {kColourDifferentTriangle, "different triangle"},
      {kColourOneSideOnly, "one side only"},
      {kColourUnexplained, "unexplained"},
      {kColourNonFinite, "NaN or Inf"},
      {kColourBackground, "empty"}};
  int y = top + 14;
  for (int i = 0; i < 5; ++i) {
    const int x = 450 + (i % 2) * 150;
    if (i == 2 || i == 4) y += 22;
    fill(image, x - 1, y - 11, 16, 16, kInk);  // outline
    fill(image, x, y - 10, 14, 14, toRgb8(swatches[i].colour));
    text.draw(image, x + 20, y + 2, swatches[i].label, kInk);
  }
}

}  // namespace

Rgb8Image heatmapImage(const Framebuffer& heatmap) {
  // The heatmap's RGB is linear light (compare.cpp decodes the sRGB colour map); displayImage
  // encodes it back, so the picture shows the colour map's own values.
  const Rgb8Image map = displayImage(heatmap);
  Rgb8Image image(std::max(map.width, kLegendWidth), map.height + kLegendHeight, kPanel);
  image.paste(map, 0, 0);
  const auto it = heatmap.attributes.find("rastercheck.heatmapQuantity");
  drawLegend(image, map.height, heatScaleByKey(it == heatmap.attributes.end() ? "error" : it->second));
  return image;
}

}  // namespace rc
