// HTML report: a summary line, then per scene its verdict and reasons, three images and its
// statistics. Inline CSS only.
#include "app/html_report.h"

#include <filesystem>
#include <sstream>

#include "app/bench_files.h"
#include "app/bench_chart.h"
#include "compare/report.h"
#include "core/atomic_file.h"
#include "core/utf8.h"

namespace rc::app {

std::string escapeMarkup(const std::string& text) {
  std::string out;
  for (char c : validUtf8(text)) {
    switch (c) {
      case '&': out += "&amp;"; break;
      case '<': out += "&lt;"; break;
      case '>': out += "&gt;"; break;
      case '"': out += "&quot;"; break;
      case '\'': out += "&#39;"; break;
      default: out += c;
    }
  }
  return out;
}

namespace {

// Image file names are stems we made (alphanumerics, '-', '_', '.'); still, percent-encode
// anything else so a name can never break out of the attribute.
std::string urlEncode(const std::string& name) {
  std::string out;
  for (unsigned char c : name) {
    if (std::isalnum(c) || c == '-' || c == '_' || c == '.') {
      out += char(c);
    } else {
      char buf[4];
      std::snprintf(buf, sizeof buf, "%%%02X", c);
      out += buf;
    }
  }
  return out;
}

const char* kStyle = R"(
body { font-family: sans-serif; margin: 24px; background: #fafafa; color: #222; }
h1 { margin-bottom: 4px; }
.summary { font-size: 1.2em; margin: 8px 0 20px; }
.pass { color: #fff; background: #2e7d32; padding: 2px 8px; border-radius: 4px; }
.fail { color: #fff; background: #c62828; padding: 2px 8px; border-radius: 4px; }
.warnings { color: #8a5a00; }
.scene { background: #fff; border: 1px solid #ddd; border-radius: 6px; padding: 12px 16px; margin-bottom: 20px; }
.images { display: flex; gap: 12px; flex-wrap: wrap; }
figure { margin: 0; }
figure img { max-width: 420px; border: 1px solid #ccc; display: block; }
figure.chart img { max-width: 100%; width: 1000px; }
figcaption { font-size: 0.85em; color: #555; }
table { border-collapse: collapse; margin-top: 10px; font-size: 0.9em; }
th, td { border: 1px solid #ddd; padding: 3px 8px; text-align: right; }
th:first-child, td:first-child { text-align: left; }
.settings { color: #555; }
)";

void sceneSection(std::ostringstream& html, const ReportScene& s) {
  const CompareReport& r = s.report;
  html << "<section class=\"scene\">\n<h2>" << escapeMarkup(s.name) << " <span class=\"" << (r.pass ? "pass" : "fail")
       << "\">" << (r.pass ? "PASS" : "FAIL") << "</span></h2>\n";
  html << "<p>" << s.triangles << " triangles, " << r.width << "x" << r.height << "; raster "
       << formatNumber(s.rasterMs) << " ms, reference " << formatNumber(s.referenceMs) << " ms.</p>\n";
  if (!s.audit.empty()) html << "<p>" << escapeMarkup(s.audit) << ".</p>\n";
  if (r.pass) {
    html << "<p>Every family is within its threshold and no NaN or Inf was seen.</p>\n";
  } else {
    html << "<ul>\n";
    for (const std::string& reason : r.reasons) html << "<li>" << escapeMarkup(reason) << "</li>\n";
    html << "</ul>\n";
  }
  if (!r.warnings.empty()) {
    html << "<ul class=\"warnings\">\n";
    for (const std::string& warning : r.warnings) html << "<li>warning: " << escapeMarkup(warning) << "</li>\n";
    html << "</ul>\n";
  }
  html << "<div class=\"images\">\n";
  const std::pair<const char*, const char*> images[] = {
      {"raster", "rasterizer (preview)"}, {"reference", "reference (preview)"}, {"heatmap", "error heatmap"}};
  for (const auto& [kind, caption] : images) {
    const std::string file = urlEncode(s.stem + "." + kind + ".png");
    html << "<figure><a href=\"" << file << "\"><img src=\"" << file << "\" alt=\"" << caption << " of "
         << escapeMarkup(s.name) << "\"></a><figcaption>" << caption << "</figcaption></figure>\n";
  }
  html << "</div>\n<table>\n<tr><th>pixels</th><th>same triangle</th><th>different triangle</th>"
       << "<th>test only</th><th>reference only</th><th>disagreement</th><th>one side only</th></tr>\n<tr><td>"
       << r.coveredEither << " covered</td><td>" << r.classCounts[int(PixelClass::kSameTriangle)] << "</td><td>"
       << r.classCounts[int(PixelClass::kDifferentTriangle)] << "</td><td>" << r.classCounts[int(PixelClass::kTestOnly)]
       << "</td><td>" << r.classCounts[int(PixelClass::kReferenceOnly)] << "</td><td>"
       << formatNumber(r.disagreementFraction)
       << (r.explained ? std::string() : " (limit " + formatNumber(r.thresholds.disagreement) + ")") << "</td><td>"
       << formatNumber(r.coverageFraction)
       << (r.explained ? std::string() : " (limit " + formatNumber(r.thresholds.coverage) + ")")
       << "</td></tr>\n</table>\n";
  html << "<p>Disagreements: " << disagreementCounts(r) << " (the gate allows none).</p>\n";
  html << "<table>\n<tr><th>family</th><th>max</th><th>mean</th><th>rms</th><th>p50</th><th>p99</th><th>p99.9</th>"
       << "<th>NaN+Inf</th><th>gated value</th><th>limit</th><th>largest error at: test / reference</th></tr>\n";
  for (const FamilyReport& f : r.families) {
    const FamilyStats& st = f.stats;
    const std::string worst = formatWorst(st.worst);
    html << "<tr><td>" << escapeMarkup(f.name) << "</td><td>" << formatNumber(st.max) << "</td><td>" << formatNumber(st.mean)
         << "</td><td>" << formatNumber(st.rms) << "</td><td>" << formatNumber(st.p50) << "</td><td>"
         << formatNumber(st.p99) << "</td><td>" << formatNumber(st.p999) << "</td><td>" << st.nanCount + st.infCount
         << "</td><td>" << formatNumber(f.gated) << (f.bounded ? " of bound" : f.range > 0 ? " of range" : "")
         << "</td><td>" << formatNumber(f.threshold) << "</td><td>" << escapeMarkup(worst) << "</td></tr>\n";
  }
  html << "</table>\n</section>\n";
}

// The share of the CPUs' time that other work (other processes and steal) took while the row's
// scene was measured, in bold where that made the machine busy; "-" where not measured.
std::string otherWork(const BenchRow& r) {
  if (!r.load) return "-";
  const std::string share = percentOf(r.load->others + r.load->steal);
  return busyNote(*r.load).empty() ? share : "<strong>" + share + "</strong>";
}

// The row's frame over its scene's default's: "1.99 (1.91 to 2.10)", the medians' ratio and each
// round's least and greatest; "-" for the default's own row and where it was not measured.
std::string overDefault(const BenchRow& r) {
  if (r.isDefault || !(r.overDefault > 0)) return "-";
  return formatNumber(r.overDefault) + " (" + formatNumber(r.overDefaultMin) + " to " + formatNumber(r.overDefaultMax) + ")";
}

void benchSection(std::ostringstream& html, const std::string& dir, const BenchResults& bench) {
  const std::vector<BenchRow>& rows = bench.rows;
  writeTextFile((std::filesystem::path(dir) / "bench.svg").string(),
                benchChartSvg(rows, bench.machine ? &*bench.machine : nullptr, bench.load ? &*bench.load : nullptr));
  html << "<section class=\"scene\">\n<h2>Speed against error</h2>\n"
       << "<p>From bench results: medians over runs in one process; floor ms is the time to write the setting's "
       << "output planes alone (memory's floor under raster ms); per round is the least and greatest of each "
       << "round's reference trace over the same round's frame; x default is the row's frame over its scene's "
       << "default's (medians; in brackets each round's least and greatest, a round's two frames taken within "
       << "about a second of each other). The chart sets each scene's frame times against "
       << "the p99.9 barycentric error and against the fraction of pixels in disagreement with the reference; "
       << "dashed lines and ringed dots mark each panel's Pareto front; other work is the share of the CPUs' "
       << "time that other processes and the hypervisor's other guests took while the row's scene was measured, "
       << "in bold where that made the machine busy.</p>\n";
  if (bench.machine) html << "<p class=\"settings\">Measured on: " << escapeMarkup(describe(*bench.machine)) << "</p>\n";
  if (bench.load) {
    const std::string note = busyNote(*bench.load);
    html << "<p class=\"settings\">Load during the run: " << escapeMarkup(describe(*bench.load))
         << (note.empty() ? "" : ": <strong>" + escapeMarkup(note) + "</strong>") << "</p>\n";
  }
  html << "<figure class=\"chart\"><a href=\"bench.svg\"><img src=\"bench.svg\" alt=\"frame time against error\"></a>"
       << "<figcaption>click the chart to open it at full size</figcaption></figure>\n<table>\n"
       << "<tr><th>scene</th><th>setting</th><th>threads</th><th>raster ms</th><th>x default</th><th>floor ms</th>"
       << "<th>reference trace ms</th>"
       << "<th>speedup</th><th>per round</th><th>bary max</th><th>bary p99.9</th><th>disagreement</th>"
       << "<th>one side only</th><th>other work</th></tr>\n";
  for (const BenchRow& r : rows) {
    html << "<tr><td>" << escapeMarkup(r.scene) << "</td><td>" << escapeMarkup(r.setting) << (r.isDefault ? " (default)" : "")
         << "</td><td>" << r.threads << "</td><td>" << formatNumber(r.rasterMs) << "</td><td>" << overDefault(r) << "</td><td>"
         << (r.storeFloorMs > 0 ? formatNumber(r.storeFloorMs) : std::string("-")) << "</td><td>"
         << formatNumber(r.referenceTraceMs) << "</td><td>" << formatNumber(r.speedup) << "</td><td>"
         << (r.speedupMax > 0 ? formatNumber(r.speedupMin) + " to " + formatNumber(r.speedupMax) : std::string("-"))
         << "</td><td>" << formatNumber(r.baryMax) << "</td><td>" << formatNumber(r.baryP999) << "</td><td>"
         << formatNumber(r.disagreementFraction) << "</td><td>"
         << (r.coverageFraction >= 0 ? formatNumber(r.coverageFraction) : std::string("-")) << "</td><td>" << otherWork(r)
         << "</td></tr>\n";
  }
  html << "</table>\n</section>\n";
}

}  // namespace

void writeHtmlReport(const std::string& dir, const std::vector<ReportScene>& scenes, const std::string& settings,
                     const BenchResults& bench) {
  std::size_t failed = 0, warned = 0;
  for (const ReportScene& s : scenes) {
    failed += s.report.pass ? 0 : 1;
    warned += s.report.warnings.empty() ? 0 : 1;
  }
  std::ostringstream html;
  html << "<!DOCTYPE html>\n<html lang=\"en\">\n<head>\n<meta charset=\"utf-8\">\n"
       << "<title>rastercheck report</title>\n<style>" << kStyle << "</style>\n</head>\n<body>\n"
       << "<h1>rastercheck report</h1>\n<p class=\"summary\"><span class=\"" << (failed ? "fail" : "pass") << "\">"
       << (failed ? "FAIL" : "PASS") << "</span> "
       << (scenes.size() == 1 ? std::string(failed ? "the scene fails the gate" : "the scene passes the gate")
           : failed             ? std::to_string(failed) + " of " + std::to_string(scenes.size()) + " scenes fail the gate"
                                : "all " + std::to_string(scenes.size()) + " scenes pass the gate")
       << (warned ? "; " + std::to_string(warned) + " with warnings" : std::string())
       << "</p>\n<p class=\"settings\">" << escapeMarkup(settings) << "</p>\n"
       << "<p class=\"settings\">Heatmaps: barycentric error on a log10 magma scale from 1e-8 (dark) to 1e-1 "
       << "(bright); green: different triangle; cyan: covered by one side only; magenta: NaN or Inf; grey: "
       << "empty. Thresholds and their origin: docs/compare.md.</p>\n";
  for (const ReportScene& s : scenes) sceneSection(html, s);
  if (!bench.rows.empty()) benchSection(html, dir, bench);
  html << "</body>\n</html>\n";
  writeTextFile((std::filesystem::path(dir) / "index.html").string(), html.str());
}

}  // namespace rc::app
