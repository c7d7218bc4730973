// --baseline: an earlier report's figures, and the warnings of those that grew.
#include "compare/baseline.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <utility>

#include <nlohmann/json.hpp>

#include "compare/report.h"
#include "core/error.h"

namespace rc {
namespace {

// A figure as reportToJson writes it: a number >= 0, or "nan" / "inf" for one that was not finite.
double figure(const nlohmann::json& j, const std::string& where) {
  if (j.is_number() && j.get<double>() >= 0.0) return j.get<double>();
  if (j == "nan") return std::numeric_limits<double>::quiet_NaN();
  if (j == "inf") return std::numeric_limits<double>::infinity();
  throw badInput(where, "is " + j.dump() + "; a figure is a number >= 0, or \"nan\" or \"inf\"");
}

const nlohmann::json& field(const nlohmann::json& object, const char* name, const std::string& where) {
  if (!object.is_object()) throw badInput(where, "is " + std::string(object.type_name()) + ", not an object");
  const auto it = object.find(name);
  if (it == object.end()) throw badInput(where + "/" + name, "missing");
  return *it;
}

int side(const nlohmann::json& report, const char* name, const std::string& where) {
  const nlohmann::json& j = field(report, name, where);
  if (!j.is_number_integer() || j.get<long long>() < 1 || j.get<long long>() > 1 << 20) {
    throw badInput(where + "/" + name, "is " + j.dump() + "; an image side is a whole number of pixels");
  }
  return j.get<int>();
}

// Below these a figure is rounding, not a measure: an error of half a float ulp of 1 (of the
// value for depth, of the range for an attribute), and one pixel of those covered.
constexpr double kErrorFloor = 0x1p-24;

// head + NOW + tail + ", 2.11x the baseline's BEFORE" when `now` exceeds `factor` times
// `before`, or times `floor` where `before` is smaller ("where the baseline's was 0"), as a NaN
// does; nothing when the baseline's figure was not finite.
void addIfGrown(std::vector<std::string>& to, const std::string& head, double now, const std::string& tail,
                double before, double factor, double floor) {
  if (!std::isfinite(before) || now <= factor * std::max(before, floor)) return;
  if (before < floor) {
    to.push_back(head + formatNumber(now) + tail + ", where the baseline's was " + formatNumber(before));
    return;
  }
  const auto [value, base] = formatApart(now, before);
  to.push_back(head + value + tail + ", " + formatNumber(now / before) + "x the baseline's " + base);
}

// A family's figure in the units of the warnings: of the range for an attribute that has one.
double ofRange(double value, double range) { return range > 0.0 ? value / range : value; }

}  // namespace

BaselineFigures baselineFigures(const nlohmann::json& report, const std::string& where) {
  BaselineFigures b;
  b.width = side(report, "width", where);
  b.height = side(report, "height", where);
  // Reports from before the camera was recorded lack it, as do those of images without the line.
  if (report.contains("camera") && !report["camera"].is_null()) {
    const nlohmann::json& camera = report["camera"];
    if (!camera.is_string()) throw badInput(where + "/camera", "is " + camera.dump() + ", not a string or null");
    b.camera = camera.get<std::string>();
  }
  b.disagreement = figure(field(report, "disagreement_fraction", where), where + "/disagreement_fraction");
  b.coverage = figure(field(report, "coverage_fraction", where), where + "/coverage_fraction");
  const std::string familiesAt = where + "/families";
  const nlohmann::json& families = field(report, "families", where);
  if (!families.is_object()) throw badInput(familiesAt, "is " + std::string(families.type_name()) + ", not an object");
  for (const auto& [name, f] : families.items()) {
    const std::string at = familiesAt + "/" + name;
    const double range = isAttributeFamily(name) && f.is_object() && f.contains("range") ? figure(f["range"], at + "/range") : 0.0;
    BaselineFigures::Family family;
    family.max = ofRange(figure(field(f, "max", at), at + "/max"), range);
    family.p999 = ofRange(figure(field(f, "p999", at), at + "/p999"), range);
    if (f.contains("bound_ratio")) {
      const std::string ratioAt = at + "/bound_ratio";
      family.boundRatio = figure(field(field(f, "bound_ratio", at), "max", ratioAt), ratioAt + "/max");
    }
    b.families[name] = family;
  }
  return b;
}

Baseline readBaseline(const std::string& path, bool perScene) {
  const nlohmann::json doc = readJsonFile(path, "baseline report");
  if (!doc.is_object() || doc.value("format_version", nlohmann::json()) != kReportFormatVersion) {
    throw badInput(path, "not a rastercheck report (a JSON object with \"format_version\": 1)");
  }
  const bool isCheck = doc.contains("scenes");
  if (isCheck != perScene) {
    throw badInput(path, isCheck ? "is a report of rastercheck check --json; compare --baseline takes one of compare --json"
                                 : "is a report of rastercheck compare --json; check --baseline takes one of check --json");
  }
  Baseline figures;
  if (!perScene) {
    figures[""].push_back(baselineFigures(doc, path + ": "));
    return figures;
  }
  const nlohmann::json& scenes = doc["scenes"];
  if (!scenes.is_array()) throw badInput(path + ": /scenes", "is " + std::string(scenes.type_name()) + ", not an array");
  for (std::size_t i = 0; i < scenes.size(); ++i) {
    const std::string at = path + ": /scenes/" + std::to_string(i);
    const nlohmann::json& name = field(scenes[i], "scene", at);
    if (!name.is_string()) throw badInput(at + "/scene", "is " + name.dump() + ", not a string");
    const nlohmann::json& triangles = field(scenes[i], "triangles", at);
    if (!triangles.is_number_unsigned()) throw badInput(at + "/triangles", "is " + triangles.dump() + ", not a count");
    BaselineFigures b = baselineFigures(field(scenes[i], "report", at), at + "/report");
    b.triangles = triangles.get<std::size_t>();
    figures[name.get<std::string>()].push_back(b);
  }
  return figures;
}

std::vector<std::string> baselineWarnings(const CompareReport& now, const BaselineFigures& before, double factor) {
  std::vector<std::string> warnings;
  if (now.width != before.width || now.height != before.height) {
    warnings.push_back("the baseline's images are " + std::to_string(before.width) + "x" +
                       std::to_string(before.height) + ", these " + std::to_string(now.width) + "x" +
                       std::to_string(now.height) + ": not held to it");
    return warnings;
  }
  // Figures measured through another camera are of other pixels (compare refuses such a pair).
  if (!now.camera.empty() && !before.camera.empty() && now.camera != before.camera) {
    warnings.push_back("the baseline's images were rendered through the camera '" + before.camera + "', these through '" +
                       now.camera + "': not held to it");
    return warnings;
  }
  for (const FamilyReport& f : now.families) {
    const auto it = before.families.find(f.name);
    if (it == before.families.end()) {
      warnings.push_back(f.name + ": not in the baseline, not held to it");
      continue;
    }
    const double range = f.isAttribute() ? f.range : 0.0;
    const std::string unit = range > 0.0 ? " of range" : "";
    const BaselineFigures::Family& was = it->second;
    addIfGrown(warnings, f.name + ": max error ", ofRange(f.stats.max, range), unit, was.max, factor, kErrorFloor);
    addIfGrown(warnings, f.name + ": p99.9 error ", ofRange(f.stats.p999, range), unit, was.p999, factor, kErrorFloor);
    // A ratio the baseline had at 0 came of no error at all, which the max error holds.
    if (f.bounded && was.boundRatio && *was.boundRatio > 0.0) {
      addIfGrown(warnings, f.name + ": max error / bound ", f.ratio.max, "", *was.boundRatio, factor, 0.0);
    }
  }
  const std::string ofCovered = " of covered pixels";
  const double onePixel = now.coveredEither > 0 ? 1.0 / double(now.coveredEither) : 0.0;
  addIfGrown(warnings, "different triangle at ", now.disagreementFraction, ofCovered, before.disagreement, factor,
             onePixel);
  addIfGrown(warnings, "one-side-only coverage at ", now.coverageFraction, ofCovered, before.coverage, factor, onePixel);
  return warnings;
}

void holdReportToBaseline(CompareReport& report, const BaselineFigures& before, const BaselineUse& use) {
  for (std::string& warning : baselineWarnings(report, before, use.factor)) report.warnings.push_back(std::move(warning));
  report.baseline = use;
  report.settleWarnings();
}

}  // namespace rc
