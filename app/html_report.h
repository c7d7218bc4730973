// The self-contained HTML report of `check --report DIR`: index.html with its PNG images
// beside it, no script and nothing fetched from a network.
#pragma once

#include <string>
#include <vector>

#include "app/bench_files.h"
#include "compare/compare.h"

namespace rc::app {

struct ReportScene {
  std::string name;       // as given on the command line
  std::string stem;       // file stem of its images: STEM.raster.png, .reference.png, .heatmap.png
  std::size_t triangles = 0;
  double rasterMs = 0.0, referenceMs = 0.0;
  CompareReport report;
  std::string audit;  // check's coverage audit in a line (auditLine); empty: none
};

// Writes DIR/index.html (atomically). `settings` is one line describing the run. With bench
// rows, it also writes DIR/bench.svg and shows it with a table of the rows, under the machine
// they were measured on where the results name it.
void writeHtmlReport(const std::string& dir, const std::vector<ReportScene>& scenes, const std::string& settings,
                     const BenchResults& bench = {});

// `text` with & < > " ' as character references: safe in HTML and SVG text and attributes.
std::string escapeMarkup(const std::string& text);

}  // namespace rc::app
