// JSON and table renderings of a comparison.
#include "compare/report.h"

#include <cmath>
#include <cstdio>
#include <fstream>
#include <sstream>
#include <string_view>

#include <nlohmann/json.hpp>

#include "core/error.h"

namespace rc {

std::string jsonDocument(const nlohmann::json& j) {
  return j.dump(2, ' ', false, nlohmann::json::error_handler_t::replace) + "\n";
}

std::string formatNumber(double value) {
  if (std::isnan(value)) return "nan";
  if (std::isinf(value)) return value > 0 ? "inf" : "-inf";
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.3g", value);
  return buf;
}

std::pair<std::string, std::string> formatApart(double a, double b) {
  char textA[40], textB[40];
  for (int digits = 3; digits <= 17; ++digits) {
    std::snprintf(textA, sizeof textA, "%.*g", digits, a);
    std::snprintf(textB, sizeof textB, "%.*g", digits, b);
    if (std::string_view(textA) != textB) break;
  }
  return {textA, textB};
}

nlohmann::json readJsonFile(const std::string& path, const std::string& what) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw ioError(path, "cannot read " + what);
  try {
    return nlohmann::json::parse(in);
  } catch (const nlohmann::json::exception& e) {
    throw badInput(path, std::string("invalid JSON: ") + e.what());
  }
}

std::string formatWorst(const WorstPixel& worst) {
  if (worst.x < 0) return "-";
  return "(" + std::to_string(worst.x) + "," + std::to_string(worst.y) + ") " + formatNumber(worst.test) + " / " +
         formatNumber(worst.reference);
}

namespace {

// JSON has no NaN or Inf: they are written as strings so no reader mistakes them for numbers.
nlohmann::json number(double value) {
  if (std::isfinite(value)) return value;
  return formatNumber(value);
}

// Why each disagreement is allowed: by the diagnostics (edge band, depth tie within the
// resolutions) or, without them, by the ids and depths (id edge, depth tie within the limit).
nlohmann::json disagreementsJson(const CompareReport& r) {
  nlohmann::json e = {{"by", r.explained ? "diagnostics" : "ids"}};
  for (int c = 0; c < kExplanationCount; ++c) {
    if (Explanation(c) == (r.explained ? Explanation::kIdEdge : Explanation::kEdgeBand)) continue;
    e[explanationName(Explanation(c))] = r.explanationCounts[c];
  }
  if (r.explained) {
    e["edge_band_pixels"] = number(r.edgeBand);
  } else {
    e["untied_disagreement_fraction"] = number(r.untiedDisagreementFraction);
    e["untied_coverage_fraction"] = number(r.untiedCoverageFraction);
  }
  if (r.firstUnexplained.x >= 0) e["first_unexplained"] = {{"x", r.firstUnexplained.x}, {"y", r.firstUnexplained.y}};
  return e;
}

// The limits gated and those warned at (null where not set).
nlohmann::json thresholdsJson(const Thresholds& t) {
  nlohmann::json j = {{"bary", t.bary},
                      {"depth", t.depth},
                      {"attribute", t.attribute},
                      {"disagreement", t.disagreement},
                      {"coverage", t.coverage},
                      {"allow_empty", t.allowEmpty},
                      {"attributes", t.attributes},
                      {"attribute_by_name", t.attributeByName}};
  const Thresholds::Warnings& w = t.warn;
  const auto limit = [](const std::optional<double>& v) { return v ? nlohmann::json(*v) : nlohmann::json(nullptr); };
  j["warn"] = {{"bary", limit(w.bary)},
               {"depth", limit(w.depth)},
               {"attribute", limit(w.attribute)},
               {"disagreement", limit(w.disagreement)},
               {"coverage", limit(w.coverage)},
               {"attribute_by_name", w.attributeByName},
               {"fail", w.fail}};
  return j;
}

// One family's statistics, its ulps and bound ratio, and its worst pixel.
nlohmann::json familyJson(const FamilyReport& f) {
  const FamilyStats& s = f.stats;
  nlohmann::json fj = {{"unit", f.unit},        {"count", s.count},     {"nan", s.nanCount},
                       {"inf", s.infCount},     {"max", number(s.max)}, {"mean", number(s.mean)},
                       {"rms", number(s.rms)},  {"p50", number(s.p50)}, {"p99", number(s.p99)},
                       {"p999", number(s.p999)}, {"threshold", f.threshold},
                       {"gated", number(f.gated)}};
  if (f.isAttribute()) fj["range"] = number(f.range);
  fj["bounded"] = f.bounded;
  fj["ulps"] = {{"max", number(f.ulps.max)}, {"p999", number(f.ulps.p999)}};
  if (f.bounded) {
    fj["bound_ratio"] = {{"max", number(f.ratio.max)}, {"p999", number(f.ratio.p999)}};
    if (f.ratio.worst.x >= 0) fj["bound_ratio"]["worst"] = {{"x", f.ratio.worst.x}, {"y", f.ratio.worst.y}};
  }
  if (s.worst.x >= 0) {
    fj["worst"] = {{"x", s.worst.x}, {"y", s.worst.y}, {"test", number(s.worst.test)},
                   {"reference", number(s.worst.reference)}};
  }
  return fj;
}

}  // namespace

nlohmann::json reportToJson(const CompareReport& r) {
  nlohmann::json j;
  j["format_version"] = kReportFormatVersion;
  j["verdict"] = r.pass ? "pass" : "fail";
  j["reasons"] = r.reasons;
  j["warnings"] = r.warnings;
  j["test"] = r.testPath;
  j["reference"] = r.referencePath;
  j["width"] = r.width;
  j["height"] = r.height;
  j["camera"] = r.camera.empty() ? nlohmann::json(nullptr) : nlohmann::json(r.camera);
  nlohmann::json pixels;
  for (int c = 0; c < kPixelClassCount; ++c) pixels[pixelClassName(PixelClass(c))] = r.classCounts[c];
  pixels["covered_either"] = r.coveredEither;
  j["pixels"] = pixels;
  j["disagreement_fraction"] = number(r.disagreementFraction);
  j["coverage_fraction"] = number(r.coverageFraction);
  j["disagreements"] = disagreementsJson(r);
  j["thresholds"] = thresholdsJson(r.thresholds);
  j["baseline"] = r.baseline ? nlohmann::json{{"file", r.baseline->file}, {"factor", r.baseline->factor}}
                             : nlohmann::json(nullptr);
  j["left_out"] = r.leftOut;
  nlohmann::json families = nlohmann::json::object();
  for (const FamilyReport& f : r.families) families[f.name] = familyJson(f);
  j["families"] = families;
  return j;
}

std::string disagreementCounts(const CompareReport& r) {
  const std::string edges = r.explained ? "in the edge band (" + formatNumber(r.edgeBand) + " px)" : "at an edge of the ids";
  return std::to_string(r.explanationCounts[int(r.explained ? Explanation::kEdgeBand : Explanation::kIdEdge)]) + " " +
         edges + ", " + std::to_string(r.explanationCounts[int(Explanation::kDepthTie)]) + " depth ties" +
         (r.explained ? "" : " (within the depth limit)") + ", " +
         std::to_string(r.explanationCounts[int(Explanation::kUnexplained)]) + " unexplained";
}

std::string reportToTable(const CompareReport& r) {
  std::ostringstream out;
  const auto& cc = r.classCounts;
  char line[320];
  std::snprintf(line, sizeof line,
                "pixels %dx%d: %zu covered by either; same triangle %zu, different %zu (%s), "
                "test only %zu, reference only %zu\n",
                r.width, r.height, r.coveredEither, cc[int(PixelClass::kSameTriangle)],
                cc[int(PixelClass::kDifferentTriangle)], formatNumber(r.disagreementFraction).c_str(),
                cc[int(PixelClass::kTestOnly)], cc[int(PixelClass::kReferenceOnly)]);
  out << line;
  out << "disagreements: " << disagreementCounts(r) << "\n";
  std::snprintf(line, sizeof line, "%-14s %9s %9s %9s %9s %9s %5s %9s %9s  %s\n", "family", "max",
                "mean", "p99.9", "max ulps", "max/bound", "n+i", "limit", "p99.9/bnd", "largest error at: test / ref");
  out << line;
  for (const FamilyReport& f : r.families) {
    const FamilyStats& s = f.stats;
    const std::string worst = formatWorst(s.worst);
    std::string limit = f.bounded ? "bound" : formatNumber(f.threshold);
    if (!f.bounded && f.range > 0.0) limit += "*" + formatNumber(f.range);
    std::snprintf(line, sizeof line, "%-14s %9s %9s %9s %9s %9s %5zu %9s %9s  %s\n", f.name.c_str(),
                  formatNumber(s.max).c_str(), formatNumber(s.mean).c_str(), formatNumber(s.p999).c_str(),
                  formatNumber(f.ulps.max).c_str(), f.bounded ? formatNumber(f.ratio.max).c_str() : "-",
                  s.nanCount + s.infCount, limit.c_str(), f.bounded ? formatNumber(f.ratio.p999).c_str() : "-",
                  worst.c_str());
    out << line;
  }
  if (!r.leftOut.empty()) {
    out << "left out (--attributes):";
    for (const std::string& name : r.leftOut) out << " " << name;
    out << "\n";
  }
  out << "verdict: " << (r.pass ? "PASS" : "FAIL") << "\n";
  for (const std::string& reason : r.reasons) out << "  - " << reason << "\n";
  for (const std::string& warning : r.warnings) out << "warning: " << warning << "\n";
  return out.str();
}

}  // namespace rc
