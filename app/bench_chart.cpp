// bench's chart: laid out once as a list of lines, dots and texts (text measured with the font
// the PNG draws in), then written as SVG text or drawn into a PNG image (chart_drawing.h).
#include "app/bench_chart.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <functional>
#include <sstream>
#include <utility>

#include "app/chart_drawing.h"
#include "core/atomic_file.h"
#include "core/error.h"
#include "scenes/scene_loader.h"

namespace rc::app {
namespace chart {

std::vector<std::size_t> paretoFront(const std::vector<Point>& points) {
  std::vector<std::size_t> front;
  for (std::size_t i = 0; i < points.size(); ++i) {
    const Point& p = points[i];
    const bool dominated = std::any_of(points.begin(), points.end(), [&](const Point& q) {
      return q.x <= p.x && q.y <= p.y && (q.x < p.x || q.y < p.y);
    });
    if (!dominated) front.push_back(i);
  }
  std::stable_sort(front.begin(), front.end(), [&](std::size_t a, std::size_t b) { return points[a].x < points[b].x; });
  return front;
}

bool crosses(const Segment& segment, const Box& box) {
  // Liang-Barsky: the part of the segment a + t (b - a), t in [0, 1], inside each slab.
  double t0 = 0, t1 = 1;
  const double d[2] = {segment.b.x - segment.a.x, segment.b.y - segment.a.y};
  const double from[2] = {segment.a.x, segment.a.y}, lo[2] = {box.x0, box.y0}, hi[2] = {box.x1, box.y1};
  for (int k = 0; k < 2; ++k) {
    if (d[k] == 0) {
      if (from[k] <= lo[k] || from[k] >= hi[k]) return false;
      continue;
    }
    double ta = (lo[k] - from[k]) / d[k], tb = (hi[k] - from[k]) / d[k];
    if (ta > tb) std::swap(ta, tb);
    t0 = std::max(t0, ta);
    t1 = std::min(t1, tb);
  }
  return t0 < t1;
}

std::vector<LabelPlace> placeLabels(const std::vector<Point>& points, const std::vector<double>& radii,
                                    const std::vector<double>& widths, double height, const Box& area,
                                    const std::vector<Segment>& lines) {
  std::vector<Box> dots;
  for (std::size_t i = 0; i < points.size(); ++i) {
    const double r = radii[i];
    dots.push_back({points[i].x - r, points[i].y - r, points[i].x + r, points[i].y + r});
  }
  constexpr double kGap = 3, kSteps = 10;
  std::vector<LabelPlace> placed;
  std::vector<Box> taken;
  for (std::size_t i = 0; i < points.size(); ++i) {
    const double x = points[i].x, y = points[i].y, r = radii[i], w = widths[i], h = height;
    const auto right = [&](double dy) { return Box{x + r + kGap, y - h / 2 + dy, x + r + kGap + w, y + h / 2 + dy}; };
    const auto left = [&](double dy) { return Box{x - r - kGap - w, y - h / 2 + dy, x - r - kGap, y + h / 2 + dy}; };
    std::vector<LabelPlace> candidates = {{right(0), false},
                                          {left(0), false},
                                          {{x - w / 2, y - r - 1 - h, x + w / 2, y - r - 1}, false},
                                          {{x - w / 2, y + r + 1, x + w / 2, y + r + 1 + h}, false}};
    for (int k = 1; k <= kSteps; ++k) {
      for (const double dy : {-(h + 1) * k, (h + 1) * k}) {
        candidates.push_back({right(dy), true});
        candidates.push_back({left(dy), true});
      }
    }
    LabelPlace chosen = candidates.front();
    for (const LabelPlace& c : candidates) {
      const auto clash = [&](const Box& b) { return b.overlaps(c.box); };
      if (c.box.inside(area) && std::none_of(taken.begin(), taken.end(), clash) &&
          std::none_of(dots.begin(), dots.end(), clash) &&
          std::none_of(lines.begin(), lines.end(), [&](const Segment& l) { return crosses(l, c.box); })) {
        chosen = c;
        break;
      }
    }
    placed.push_back(chosen);
    // Kept a gap's width from the labels after it, so that two labels never read as one.
    taken.push_back({chosen.box.x0 - kGap, chosen.box.y0, chosen.box.x1 + kGap, chosen.box.y1});
  }
  return placed;
}

std::string shortSettingName(const std::string& setting, const std::string& defaultSetting) {
  if (setting == defaultSetting) return "default";
  const auto words = [](const std::string& name) {
    std::vector<std::string> out;
    std::stringstream in(name);
    for (std::string word; std::getline(in, word, '-');) out.push_back(word);
    return out;
  };
  const std::vector<std::string> shared = words(defaultSetting);
  std::string out;
  for (const std::string& word : words(setting)) {
    if (std::find(shared.begin(), shared.end(), word) != shared.end()) continue;
    out += (out.empty() ? "" : " ") + word;
  }
  return out.empty() ? setting : out;
}

std::string elideMiddle(const std::string& text, std::size_t keep) {
  if (text.size() <= keep) return text;
  const std::string dots = "...";
  const std::size_t room = keep > dots.size() ? keep - dots.size() : 0;
  const auto continuation = [&](std::size_t i) { return (static_cast<unsigned char>(text[i]) & 0xC0) == 0x80; };
  std::size_t head = room / 3, tail = text.size() - (room - head);
  while (head > 0 && continuation(head)) --head;            // the head ends before a character
  while (tail < text.size() && continuation(tail)) ++tail;  // the tail starts on one
  return text.substr(0, head) + dots + text.substr(tail);
}

}  // namespace chart

namespace {

using chart::Anchor;
using chart::Box;
using chart::Dot;
using chart::Drawing;
using chart::Fonts;
using chart::kInk;
using chart::Line;
using chart::Point;
using chart::Text;

constexpr Rgb8 kGrey{0x66, 0x66, 0x66}, kGrid{0xdd, 0xdd, 0xdd}, kLeader{0x99, 0x99, 0x99};
constexpr Rgb8 kDefault{0xd6, 0x27, 0x28}, kArithmetic{0x1f, 0x77, 0xb4}, kSameArithmetic{0x8c, 0x8c, 0x8c};

std::string formatTick(double v) {
  char text[32];
  std::snprintf(text, sizeof text, "%g", v);
  return text;
}

std::string withThousands(std::size_t n) {
  std::string digits = std::to_string(n), out;
  for (std::size_t i = 0; i < digits.size(); ++i) {
    if (i > 0 && (digits.size() - i) % 3 == 0) out += ',';
    out += digits[i];
  }
  return out;
}

// Frame-time ticks: the first of 1; 1, 2, 5; 1 to 9 (times powers of ten) that gives three
// ticks in [lo, hi].
std::vector<double> timeTicks(double lo, double hi) {
  const std::vector<std::vector<double>> steps = {{1}, {1, 2, 5}, {1, 1.5, 2, 3, 4, 5, 6, 7, 8, 9}};
  std::vector<double> ticks;
  for (const std::vector<double>& mantissas : steps) {
    ticks.clear();
    for (int e = int(std::floor(std::log10(lo))); e <= int(std::ceil(std::log10(hi))); ++e) {
      for (double m : mantissas) {
        const double v = m * std::pow(10.0, e);
        if (v >= lo * (1 - 1e-12) && v <= hi * (1 + 1e-12)) ticks.push_back(v);
      }
    }
    if (ticks.size() >= 3) break;
  }
  return ticks;
}

struct Panel {
  const char* title;
  double BenchRow::*error;
};
constexpr Panel kPanels[] = {{"barycentric error, p99.9 (log)", &BenchRow::baryP999},
                             {"pixels in disagreement with the reference, fraction (log)", &BenchRow::disagreementFraction}};

constexpr int kWidth = 1000, kHeader = 58, kRowHeight = 332, kFooter = 92;
constexpr int kLabelSize = 11, kTickSize = 11;

// A panel's error axis: decades over the positive errors, an error of 0 on a row of its own at
// the bottom, drawn with its grid; y(e) places an error.
struct ErrorAxis {
  double logBottom, zeroY;
  int lo, hi;
  double y(double e, const Box& plot) const {
    if (e == 0) return zeroY;
    return logBottom - (std::log10(e) - lo) / (hi - lo) * (logBottom - plot.y0 - 6);
  }
};

ErrorAxis drawErrorAxis(Drawing& d, const std::vector<const BenchRow*>& rows, const Panel& panel, const Box& plot) {
  double eMin = INFINITY, eMax = 0;
  bool zero = false;
  for (const BenchRow* r : rows) {
    const double e = r->*panel.error;
    if (e > 0 && std::isfinite(e)) eMin = std::min(eMin, e), eMax = std::max(eMax, e);
    zero = zero || e == 0;
  }
  const bool positive = eMax > 0;
  if (!positive) eMin = eMax = 1e-9;
  const int lo = int(std::floor(std::log10(eMin))), hi = std::max(int(std::ceil(std::log10(eMax))), lo + 1);
  const ErrorAxis axis{plot.y1 - (zero ? 26 : 6), plot.y1 - 7, lo, hi};
  // Without a positive error there are no decades to mark, only the row of 0.
  const int every = hi - lo > 8 ? 2 : 1, last = positive ? hi : lo - 1;
  for (int k = lo; k <= last; k += every) {
    const double y = axis.y(std::pow(10.0, k), plot);
    d.items.push_back(Line{plot.x0, y, plot.x1, y, kGrid, 1});
    d.items.push_back(Text{plot.x0 - 6, y + 4, "1e" + std::to_string(k), kTickSize, kGrey, Anchor::kEnd});
  }
  if (zero) {
    d.items.push_back(Line{plot.x0, axis.zeroY, plot.x1, axis.zeroY, kGrid, 1, 2});
    d.items.push_back(Text{plot.x0 - 6, axis.zeroY + 4, "0", kTickSize, kGrey, Anchor::kEnd});
  }
  return axis;
}

// A panel's points: `shown` at `screen` (their values in `values`), the Pareto front dashed
// and ringed, every point labelled where placeLabels finds room.
void drawPoints(Drawing& d, Fonts& fonts, const std::vector<const BenchRow*>& shown, const std::vector<Point>& values,
                const std::vector<Point>& screen, const Panel& panel, const std::string& defaultName, const Box& plot) {
  const std::vector<std::size_t> front = chart::paretoFront(values);
  std::vector<chart::Segment> frontLines;
  for (std::size_t k = 1; k < front.size(); ++k) {
    const Point a = screen[front[k - 1]], b = screen[front[k]];
    d.items.push_back(Line{a.x, a.y, b.x, b.y, kInk, 1.2, 4});
    frontLines.push_back({a, b});
  }
  // Labels: the default's first, then the front's, then the rest from left to right.
  std::vector<std::size_t> order(shown.size());
  for (std::size_t i = 0; i < order.size(); ++i) order[i] = i;
  const auto rank = [&](std::size_t i) {
    return shown[i]->isDefault ? 0 : std::find(front.begin(), front.end(), i) != front.end() ? 1 : 2;
  };
  std::stable_sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) {
    return rank(a) != rank(b) ? rank(a) < rank(b) : screen[a].x < screen[b].x;
  });
  std::vector<Point> points;
  std::vector<double> radii, widths;
  std::vector<std::string> names;
  for (std::size_t i : order) {
    points.push_back(screen[i]);
    radii.push_back(shown[i]->isDefault ? 6 : 4.5);
    names.push_back(chart::shortSettingName(shown[i]->setting, defaultName));
    widths.push_back(fonts.width(names.back(), kLabelSize));
  }
  const std::vector<chart::LabelPlace> places = chart::placeLabels(points, radii, widths, kLabelSize + 2, plot, frontLines);
  for (std::size_t k = 0; k < order.size(); ++k) {
    const chart::LabelPlace& place = places[k];
    if (place.leader) {
      const double toX = place.box.x0 > points[k].x ? place.box.x0 - 1 : place.box.x1 + 1;
      d.items.push_back(Line{points[k].x, points[k].y, toX, (place.box.y0 + place.box.y1) / 2, kLeader, 0.8});
    }
  }
  for (std::size_t k = order.size(); k-- > 0;) {  // the default last, on top
    const BenchRow& r = *shown[order[k]];
    const bool onFront = std::find(front.begin(), front.end(), order[k]) != front.end();
    const bool sameArithmetic = std::count(r.setting.begin(), r.setting.end(), '-') > 2;
    char title[256];
    std::snprintf(title, sizeof title, "%s %s: %.3g ms, %s %.3g", r.scene.c_str(), r.setting.c_str(), r.rasterMs,
                  panel.error == &BenchRow::baryP999 ? "bary p99.9" : "disagreement", values[order[k]].y);
    d.items.push_back(Dot{points[k].x, points[k].y, radii[k],
                          r.isDefault ? kDefault : sameArithmetic ? kSameArithmetic : kArithmetic, onFront ? 1.6 : 0,
                          title});
  }
  for (std::size_t k = 0; k < order.size(); ++k) {
    d.items.push_back(Text{places[k].box.x0, places[k].box.y1 - 3, names[k], kLabelSize, kInk});
  }
}

// One panel: frame time (shared by the row's panels) against one error.
void drawPanel(Drawing& d, Fonts& fonts, const std::vector<const BenchRow*>& rows, const Panel& panel,
               const std::string& defaultName, double tLo, double tHi, const Box& plot) {
  d.items.push_back(Text{plot.x0, plot.y0 - 10, panel.title, 12, kInk});
  const auto x = [&](double ms) { return plot.x0 + (std::log10(ms / tLo)) / std::log10(tHi / tLo) * (plot.x1 - plot.x0); };
  for (double t : timeTicks(tLo, tHi)) {
    d.items.push_back(Line{x(t), plot.y0, x(t), plot.y1, kGrid, 1});
    d.items.push_back(Text{x(t), plot.y1 + 15, formatTick(t), kTickSize, kGrey, Anchor::kMiddle});
  }
  d.items.push_back(Text{(plot.x0 + plot.x1) / 2, plot.y1 + 33, "frame time, ms (log)", kTickSize, kGrey, Anchor::kMiddle});
  const ErrorAxis axis = drawErrorAxis(d, rows, panel, plot);
  d.items.push_back(Line{plot.x0, plot.y1, plot.x1, plot.y1, kGrey, 1});
  d.items.push_back(Line{plot.x0, plot.y0, plot.x0, plot.y1, kGrey, 1});

  std::vector<const BenchRow*> shown;
  std::vector<Point> values, screen;
  for (const BenchRow* r : rows) {
    const double e = r->*panel.error;
    if (!(r->rasterMs > 0) || !std::isfinite(r->rasterMs) || !(e >= 0) || !std::isfinite(e)) continue;
    shown.push_back(r);
    values.push_back({r->rasterMs, e});
    screen.push_back({x(r->rasterMs), axis.y(e, plot)});
  }
  drawPoints(d, fonts, shown, values, screen, panel, defaultName, plot);
}

// `text`, or it losing its middle a tenth at a time until `fits` holds or 12 characters are left.
std::string elideUntil(const std::string& text, const std::function<bool(const std::string&)>& fits) {
  std::string out = text;
  for (std::size_t keep = text.size(); keep > 12 && !fits(out);) {
    keep -= std::max<std::size_t>(1, keep / 10);
    out = chart::elideMiddle(text, keep);
  }
  return out;
}

// The lines under the title: the machine's, or two where it does not fit (a long CPU name): the
// hardware, then the builds, each losing its middle where even that is too long. Then the load's.
std::vector<std::string> aboutLines(Fonts& fonts, const BenchMachine* machine, const BenchLoad* load) {
  std::vector<std::string> about;
  const auto fits = [&](const std::string& text) { return fonts.width(text, 11) <= kWidth - 40.0; };
  if (machine) {
    about = {"measured on " + describe(*machine)};
    if (!fits(about[0])) about = {"measured on " + describeHardware(*machine), "built with " + describeBuilds(*machine)};
    for (std::string& text : about) text = elideUntil(text, fits);
  }
  if (load) {
    about.push_back("load during the run: " + describe(*load));
    if (const std::string note = busyNote(*load); !note.empty()) about.push_back(note);
  }
  return about;
}

// One scene's row from `top` down: its conditions, and its two panels over a shared time axis.
// `defaultName` becomes the scene's default setting's name, where it has one.
void drawScene(Drawing& d, Fonts& fonts, const std::vector<const BenchRow*>& mine, double top, std::string& defaultName) {
  const BenchRow* head = mine.front();
  for (const BenchRow* r : mine) {
    if (r->isDefault) head = r, defaultName = r->setting;
  }
  char facts[512];
  std::snprintf(facts, sizeof facts,
                ": %s triangles, %dx%d, %d threads%s; reference (Embree %s): trace %.3g ms, BVH build %.3g ms",
                withThousands(head->triangles).c_str(), head->width, head->height, head->threads,
                head->runs > 0 ? (", " + timingPhrase(head->runs)).c_str() : "",
                head->referenceIsa.empty() ? "?" : head->referenceIsa.c_str(), head->referenceTraceMs,
                head->referenceBuildMs);
  std::string conditions = facts;
  // A scene that other work made busy says so, with the share it took (bench's rows carry it).
  if (head->load && !busyNote(*head->load).empty()) {
    conditions += "; busy: other work " + percentOf(head->load->others + head->load->steal);
  }
  // A long scene name (a path) loses its middle rather than the conditions their end.
  const std::string name =
      elideUntil(head->scene, [&](const std::string& n) { return fonts.width(n + conditions, 13) <= kWidth - 40.0; });
  d.items.push_back(Line{20, top + 6, kWidth - 20.0, top + 6, kGrid, 1});
  d.items.push_back(Text{20, top + 26, name + conditions, 13, kInk});
  double tMin = INFINITY, tMax = 0;
  for (const BenchRow* r : mine) {
    if (r->rasterMs > 0 && std::isfinite(r->rasterMs)) tMin = std::min(tMin, r->rasterMs), tMax = std::max(tMax, r->rasterMs);
  }
  if (!(tMax > 0)) tMin = tMax = 1;
  // A margin either side, and at least a factor of 2.5 across, so that close points stay apart
  // from the edges and a narrow spread is not blown up.
  double tLo = tMin / 1.15, tHi = tMax * 1.15;
  if (tHi / tLo < 2.5) {
    const double middle = std::sqrt(tLo * tHi);
    tLo = middle / std::sqrt(2.5), tHi = middle * std::sqrt(2.5);
  }
  for (int p = 0; p < 2; ++p) {
    const Box plot{p * 500.0 + 70, top + 60, p * 500.0 + 482, top + 284};
    drawPanel(d, fonts, mine, kPanels[p], defaultName, tLo, tHi, plot);
  }
}

// The legend at the foot: the three kinds of point and the Pareto front.
void drawLegend(Drawing& d, const std::string& defaultName) {
  const double legend = d.height - kFooter + 18.0;
  d.items.push_back(Line{20, legend - 12, kWidth - 20.0, legend - 12, kGrid, 1});
  d.items.push_back(Dot{30, legend, 6, kDefault});
  d.items.push_back(Text{42, legend + 4, "the default setting (" + defaultName + ")", 11, kInk});
  d.items.push_back(Dot{30, legend + 20, 4.5, kArithmetic});
  d.items.push_back(Text{42, legend + 24, "another arithmetic: interpolation mode, precision or subpixel bits", 11, kInk});
  d.items.push_back(Dot{30, legend + 40, 4.5, kSameArithmetic});
  d.items.push_back(Text{42, legend + 44,
                         "the default's arithmetic run another way: 1 thread, other kernels, no diagnostics, no culling",
                         11, kInk});
  d.items.push_back(Line{520, legend, 560, legend, kInk, 1.2, 4});
  d.items.push_back(Dot{570, legend, 4.5, kArithmetic, 1.6});
  d.items.push_back(Text{582, legend + 4, "Pareto front: nothing else as fast and as accurate", 11, kInk});
  d.items.push_back(Text{520, legend + 24, "an error of 0 sits on the row marked 0", 11, kInk});
}

Drawing layOut(const std::vector<BenchRow>& rows, const BenchMachine* machine, const BenchLoad* load) {
  Fonts fonts;
  std::vector<std::string> scenes;  // in the order bench ran them
  for (const BenchRow& r : rows) {
    if (std::find(scenes.begin(), scenes.end(), r.scene) == scenes.end()) scenes.push_back(r.scene);
  }
  const std::vector<std::string> about = aboutLines(fonts, machine, load);
  const int header = kHeader + 14 * std::max(0, int(about.size()) - 1);
  Drawing d;
  d.width = kWidth;
  d.height = header + kRowHeight * int(scenes.size()) + kFooter;
  d.items.push_back(Text{20, 28, "rastercheck bench: rasterizer frame time against error, per setting", 16, kInk});
  for (std::size_t i = 0; i < about.size(); ++i) d.items.push_back(Text{20, 47 + 14 * double(i), about[i], 11, kGrey});
  std::string defaultName = benchSettingName(Interpolation::kPerspective, Precision::kFloat, 8);
  for (std::size_t s = 0; s < scenes.size(); ++s) {
    std::vector<const BenchRow*> mine;
    for (const BenchRow& r : rows) {
      if (r.scene == scenes[s]) mine.push_back(&r);
    }
    drawScene(d, fonts, mine, header + kRowHeight * double(s), defaultName);
  }
  drawLegend(d, defaultName);
  return d;
}

}  // namespace

ChartFormat chartFormatOf(const std::string& path) {
  const std::string extension = lowerExtension(path);
  if (extension == ".svg") return ChartFormat::kSvg;
  if (extension == ".png") return ChartFormat::kPng;
  throw usageError("--chart: " + path + ": name it .svg or .png, the format to write");
}

void checkChartCanBeMade(const std::string& path) {
  chartFormatOf(path);
  Fonts().at(kLabelSize);
}

std::string benchChartSvg(const std::vector<BenchRow>& rows, const BenchMachine* machine, const BenchLoad* load) {
  return toSvg(layOut(rows, machine, load));
}

Rgb8Image benchChartImage(const std::vector<BenchRow>& rows, const BenchMachine* machine, const BenchLoad* load) {
  Fonts fonts;
  return toImage(layOut(rows, machine, load), fonts);
}

BenchChart makeBenchChart(const std::vector<BenchRow>& rows, const BenchMachine* machine, const BenchLoad* load,
                          const std::string& path) {
  BenchChart chart;
  chart.format = chartFormatOf(path);
  if (chart.format == ChartFormat::kSvg) {
    chart.svg = benchChartSvg(rows, machine, load);
  } else {
    chart.image = benchChartImage(rows, machine, load);
  }
  return chart;
}

void writeBenchChart(const BenchChart& chart, const std::string& path) {
  if (chart.format == ChartFormat::kSvg) {
    writeTextFile(path, chart.svg);
  } else {
    writePng(chart.image, path);
  }
}

}  // namespace rc::app
