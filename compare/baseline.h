// Holding a comparison to an earlier one (--baseline): the figures of a JSON report written
// before (compare --json, or one scene of check --json), and the warnings of those that grew
// by more than a factor. A gate that passes can hide an error that grew; a CI that keeps the
// last good report hears of it without setting a limit per figure by hand.
#pragma once

#include <cstddef>
#include <map>
#include <optional>
#include <string>
#include <vector>

#include <nlohmann/json_fwd.hpp>

#include "compare/compare.h"

namespace rc {

// What one report measured, in the units the warnings take: a family's max and p99.9 error (of
// its range for an attribute that has one) and, when it was gated against the bounds, its
// largest error / bound; the pixel fractions of the disagreements. A figure the report wrote
// as "nan" or "inf" is kept as such and holds nothing to it.
struct BaselineFigures {
  struct Family {
    double max = 0.0, p999 = 0.0;
    std::optional<double> boundRatio;
  };
  int width = 0, height = 0;
  std::string camera;  // its rastercheck.camera line; empty when it recorded none
  std::optional<std::size_t> triangles;  // the scene's, from a check report
  std::map<std::string, Family> families;  // by family name: "bary", "depth", "attr.uv"
  double disagreement = 0.0, coverage = 0.0;
};

// Reads the figures of `report`, a compare report as reportToJson writes it; `where` names it in
// messages ("old.json", "old.json: /scenes/2/report"). Throws badInput naming where and the
// field for one that is missing, mistyped or negative.
BaselineFigures baselineFigures(const nlohmann::json& report, const std::string& where);

// A baseline's figures by scene name, in the order its report lists them: a scene given twice to
// check (`check cube cube`) has two. A compare report's are under the name "".
using Baseline = std::map<std::string, std::vector<BaselineFigures>>;

// Reads a baseline report from `path`: a compare report (`perScene` false) or a check report
// (`perScene` true), whose scenes come with their triangle counts. Throws ioError when the file
// cannot be read and badInput naming the file and field when it is not such a report.
Baseline readBaseline(const std::string& path, bool perScene);

// The figures of `now` that exceed `factor` times the baseline's, one line each ("bary: max
// error 5.1e-05, 2.11x the baseline's 2.42e-05"). A baseline figure below a floor is held as the
// floor: an error of 2^-24 (half a float ulp of 1), a fraction of one covered pixel; so a figure
// the baseline had at 0 warns from `factor` times the floor up ("where the baseline's was 0"). A
// family the baseline lacks is said once, and so is a baseline of another image size or rendered
// through another camera, whose figures are then not held to.
std::vector<std::string> baselineWarnings(const CompareReport& now, const BaselineFigures& before, double factor);

// Adds baselineWarnings(report, before, use.factor) to the report's warnings and records `use`.
void holdReportToBaseline(CompareReport& report, const BaselineFigures& before, const BaselineUse& use);

}  // namespace rc
