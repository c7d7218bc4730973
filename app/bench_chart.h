// bench's chart for people: frame time against error on log axes, drawn once and written as
// SVG or PNG. One row of two panels per scene: the p99.9 barycentric error (how wrong the
// values are) and the fraction of pixels in disagreement with the reference (how wrong the
// coverage is), since the settings trade speed for one or the other. Every point is labelled
// with its setting; each panel marks its Pareto front.
#pragma once

#include <cstddef>
#include <string>
#include <vector>

#include "app/bench.h"
#include "core/png_io.h"

namespace rc::app {

enum class ChartFormat { kSvg, kPng };

// The format `path` asks for by its extension, `.svg` or `.png` in any case; anything else is a
// usage error naming the path, so that a chart is never written in a format its name denies.
ChartFormat chartFormatOf(const std::string& path);
// chartFormatOf, and the font both formats measure their text with loaded once (ioError naming
// it where it cannot be), so that bench fails before its minutes of measuring, not after.
void checkChartCanBeMade(const std::string& path);

// `machine` and `load`, where given, are named under the title, with busyNote's words on a line
// of their own where the load calls the machine busy.
std::string benchChartSvg(const std::vector<BenchRow>& rows, const BenchMachine* machine = nullptr,
                          const BenchLoad* load = nullptr);
Rgb8Image benchChartImage(const std::vector<BenchRow>& rows, const BenchMachine* machine = nullptr,
                          const BenchLoad* load = nullptr);

// The chart in the format its path asks for, ready to write: the SVG text or the PNG image.
struct BenchChart {
  ChartFormat format = ChartFormat::kSvg;
  std::string svg;
  Rgb8Image image;
};
BenchChart makeBenchChart(const std::vector<BenchRow>& rows, const BenchMachine* machine, const BenchLoad* load,
                          const std::string& path);
// Writes it through a temporary file renamed into place; throws ioError.
void writeBenchChart(const BenchChart& chart, const std::string& path);

namespace chart {

struct Point {
  double x = 0, y = 0;
};

// The indices of the points on the Pareto front when smaller is better on both axes: no other
// point is at most as large on both and smaller on one. By increasing x; of points equal on
// both, each is on the front.
std::vector<std::size_t> paretoFront(const std::vector<Point>& points);

struct Box {
  double x0 = 0, y0 = 0, x1 = 0, y1 = 0;
  bool overlaps(const Box& other) const { return x0 < other.x1 && other.x0 < x1 && y0 < other.y1 && other.y0 < y1; }
  bool inside(const Box& area) const { return x0 >= area.x0 && y0 >= area.y0 && x1 <= area.x1 && y1 <= area.y1; }
};

// A label's place: its box, and whether a leader line joins it to its point (it sits away
// from the point's side).
struct LabelPlace {
  Box box;
  bool leader = false;
};

// Places a label of widths[i] by `height` beside each point (screen coordinates, y down; each
// point a dot of radius radii[i]), in the order given: the first free place in `area` among
// right, left, above, below and then right and left, further up and down by a line at a time.
// Free means clear of every label placed before (with a gap of 3 either side), of every dot and
// of every line segment in `lines`. A label with no free place goes to the right of its point.
struct Segment {
  Point a, b;
};
std::vector<LabelPlace> placeLabels(const std::vector<Point>& points, const std::vector<double>& radii,
                                    const std::vector<double>& widths, double height, const Box& area,
                                    const std::vector<Segment>& lines = {});
// Whether the segment passes through the box's inside.
bool crosses(const Segment& segment, const Box& box);

// A setting's name less the words it shares with the default's: "affine", "4bit", "1thread",
// "double nosnap"; "default" for the default.
std::string shortSettingName(const std::string& setting, const std::string& defaultSetting);

// `text` cut to at most `keep` bytes by replacing its middle with "...": the first third and the
// last two thirds of what is kept (a path's file name is at its end), each cut on a UTF-8
// character boundary. Text no longer than `keep` comes back unchanged.
std::string elideMiddle(const std::string& text, std::size_t keep);

}  // namespace chart
}  // namespace rc::app
