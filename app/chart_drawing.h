// A chart as a list of lines, dots and texts in page units (an SVG pixel, y down), written as
// SVG text or drawn into an image; text is measured and drawn with the font the PNG uses.
#pragma once

#include <map>
#include <memory>
#include <string>
#include <utility>
#include <variant>
#include <vector>

#include "core/png_io.h"
#include "core/text.h"

namespace rc::app::chart {

// The ink of text, the Pareto front and the dots' rings.
inline constexpr Rgb8 kInk{0x22, 0x22, 0x22};

struct Line {
  double x0, y0, x1, y1;
  Rgb8 colour;
  double width;
  double dash;  // length of each dash and gap; 0: solid
  Line(double x0_, double y0_, double x1_, double y1_, Rgb8 colour_, double width_, double dash_ = 0)
      : x0(x0_), y0(y0_), x1(x1_), y1(y1_), colour(colour_), width(width_), dash(dash_) {}
};
struct Dot {
  double x, y, radius;
  Rgb8 fill;
  double ring;        // width of a dark outline; 0: none
  std::string title;  // the SVG's tooltip
  Dot(double x_, double y_, double radius_, Rgb8 fill_, double ring_ = 0, std::string title_ = "")
      : x(x_), y(y_), radius(radius_), fill(fill_), ring(ring_), title(std::move(title_)) {}
};
enum class Anchor { kStart, kMiddle, kEnd };
struct Text {
  double x, y;  // y: the baseline
  std::string text;
  int size;
  Rgb8 colour;
  Anchor anchor;
  Text(double x_, double y_, std::string text_, int size_, Rgb8 colour_, Anchor anchor_ = Anchor::kStart)
      : x(x_), y(y_), text(std::move(text_)), size(size_), colour(colour_), anchor(anchor_) {}
};
using Item = std::variant<Line, Dot, Text>;

struct Drawing {
  int width = 0, height = 0;
  std::vector<Item> items;  // in drawing order
};

// Text widths from the font the PNG is drawn in (DejaVu Sans), one renderer per size.
class Fonts {
 public:
  const TextRenderer& at(int size) {
    auto& slot = renderers_[size];
    if (!slot) slot = std::make_unique<TextRenderer>(size);
    return *slot;
  }
  double width(const std::string& text, int size) { return at(size).measure(text); }

 private:
  std::map<int, std::unique_ptr<TextRenderer>> renderers_;
};

// The drawing as an SVG document.
std::string toSvg(const Drawing& d);
// The drawing as an image of its page size.
Rgb8Image toImage(const Drawing& d, Fonts& fonts);

}  // namespace rc::app::chart
