// Writing and drawing a chart (chart_drawing.h).
#include "app/chart_drawing.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <sstream>

#include "app/html_report.h"

namespace rc::app::chart {

namespace {

std::string hex(Rgb8 c) {
  char text[8];
  std::snprintf(text, sizeof text, "#%02x%02x%02x", c[0], c[1], c[2]);
  return text;
}

}  // namespace

std::string toSvg(const Drawing& d) {
  std::ostringstream svg;
  svg.precision(5);
  svg << "<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"" << d.width << "\" height=\"" << d.height
      << "\" font-family=\"DejaVu Sans, sans-serif\">\n<rect width=\"100%\" height=\"100%\" fill=\"white\"/>\n";
  for (const Item& item : d.items) {
    if (const Line* l = std::get_if<Line>(&item)) {
      svg << "<line x1=\"" << l->x0 << "\" y1=\"" << l->y0 << "\" x2=\"" << l->x1 << "\" y2=\"" << l->y1
          << "\" stroke=\"" << hex(l->colour) << "\" stroke-width=\"" << l->width << "\"";
      if (l->dash > 0) svg << " stroke-dasharray=\"" << l->dash << "\"";
      svg << "/>\n";
    } else if (const Dot* p = std::get_if<Dot>(&item)) {
      svg << "<circle cx=\"" << p->x << "\" cy=\"" << p->y << "\" r=\"" << p->radius << "\" fill=\"" << hex(p->fill)
          << "\"";
      if (p->ring > 0) svg << " stroke=\"" << hex(kInk) << "\" stroke-width=\"" << p->ring << "\"";
      if (p->title.empty()) {
        svg << "/>\n";
      } else {
        svg << "><title>" << escapeMarkup(p->title) << "</title></circle>\n";
      }
    } else {
      const Text& t = std::get<Text>(item);
      svg << "<text x=\"" << t.x << "\" y=\"" << t.y << "\" font-size=\"" << t.size << "\" fill=\"" << hex(t.colour)
          << "\"" << (t.anchor == Anchor::kMiddle ? " text-anchor=\"middle\"" : t.anchor == Anchor::kEnd ? " text-anchor=\"end\"" : "")
          << ">" << escapeMarkup(t.text) << "</text>\n";
    }
  }
  svg << "</svg>\n";
  return svg.str();
}

namespace {

// Drawn at kScale times the page size with coverage from distances, then averaged down: the
// lines and dots come out smooth.
constexpr int kScale = 2;

void blend(Rgb8Image& image, int x, int y, Rgb8 colour, double coverage) {
  if (coverage <= 0 || x < 0 || y < 0 || x >= image.width || y >= image.height) return;
  coverage = std::min(coverage, 1.0);
  std::uint8_t* p = &image.pixels[(std::size_t(y) * std::size_t(image.width) + std::size_t(x)) * 3];
  for (int k = 0; k < 3; ++k) p[k] = std::uint8_t(std::lround(p[k] + (colour[k] - p[k]) * coverage));
}

void drawLine(Rgb8Image& image, const Line& l) {
  const double s = kScale, x0 = l.x0 * s, y0 = l.y0 * s, x1 = l.x1 * s, y1 = l.y1 * s, half = l.width * s / 2;
  const double dx = x1 - x0, dy = y1 - y0, length = std::hypot(dx, dy), dash = l.dash * s;
  for (int y = int(std::floor(std::min(y0, y1) - half - 1)); y <= int(std::ceil(std::max(y0, y1) + half + 1)); ++y) {
    for (int x = int(std::floor(std::min(x0, x1) - half - 1)); x <= int(std::ceil(std::max(x0, x1) + half + 1)); ++x) {
      const double px = x + 0.5 - x0, py = y + 0.5 - y0;
      const double along = length > 0 ? std::clamp((px * dx + py * dy) / length, 0.0, length) : 0.0;
      if (dash > 0 && std::fmod(along, 2 * dash) > dash) continue;
      const double ax = length > 0 ? along * dx / length : 0, ay = length > 0 ? along * dy / length : 0;
      blend(image, x, y, l.colour, half + 0.5 - std::hypot(px - ax, py - ay));
    }
  }
}

void drawDot(Rgb8Image& image, const Dot& dot) {
  const double s = kScale, cx = dot.x * s, cy = dot.y * s, r = dot.radius * s, ring = dot.ring * s / 2;
  for (int y = int(cy - r - ring - 2); y <= int(cy + r + ring + 2); ++y) {
    for (int x = int(cx - r - ring - 2); x <= int(cx + r + ring + 2); ++x) {
      const double distance = std::hypot(x + 0.5 - cx, y + 0.5 - cy);
      blend(image, x, y, dot.fill, r + 0.5 - distance);
      if (ring > 0) blend(image, x, y, kInk, ring + 0.5 - std::abs(distance - r));
    }
  }
}

}  // namespace

Rgb8Image toImage(const Drawing& d, Fonts& fonts) {
  Rgb8Image big(d.width * kScale, d.height * kScale, Rgb8{255, 255, 255});
  for (const Item& item : d.items) {
    if (const Line* l = std::get_if<Line>(&item)) {
      drawLine(big, *l);
    } else if (const Dot* p = std::get_if<Dot>(&item)) {
      drawDot(big, *p);
    } else {
      const Text& t = std::get<Text>(item);
      const TextRenderer& font = fonts.at(t.size * kScale);
      const int width = font.measure(t.text);
      const int x = int(std::lround(t.x * kScale)) -
                    (t.anchor == Anchor::kMiddle ? width / 2 : t.anchor == Anchor::kEnd ? width : 0);
      font.draw(big, x, int(std::lround(t.y * kScale)), t.text, t.colour);
    }
  }
  Rgb8Image image(d.width, d.height, Rgb8{255, 255, 255});
  for (int y = 0; y < d.height; ++y) {
    for (int x = 0; x < d.width; ++x) {
      for (int k = 0; k < 3; ++k) {
        int sum = 0;
        for (int j = 0; j < kScale; ++j) {
          for (int i = 0; i < kScale; ++i) {
            sum += big.pixels[((std::size_t(y) * kScale + j) * std::size_t(big.width) + std::size_t(x) * kScale + i) * 3 + k];
          }
        }
        image.pixels[(std::size_t(y) * std::size_t(d.width) + std::size_t(x)) * 3 + k] =
            std::uint8_t((sum + kScale * kScale / 2) / (kScale * kScale));
      }
    }
  }
  return image;
}

}  // namespace rc::app::chart
