// JUnit XML for the accuracy gate (junit.h).
#include "app/junit.h"

#include <cstdio>
#include <sstream>

#include "app/html_report.h"
#include "compare/report.h"

namespace rc::app {

namespace {

std::string seconds(double s) {
  char text[32];
  std::snprintf(text, sizeof text, "%.3f", s);
  return text;
}

}  // namespace

std::string gateFigures(const CompareReport& report) {
  const FamilyStats& bary = report.families[0].stats;
  const FamilyStats& depth = report.families[1].stats;
  return std::to_string(report.width) + "x" + std::to_string(report.height) + ": bary max " + formatNumber(bary.max) +
         ", p99.9 " + formatNumber(bary.p999) + "; depth max " + formatNumber(depth.max) + "; disagreement " +
         formatNumber(report.disagreementFraction);
}

std::string junitXml(const std::string& suite, const std::vector<std::pair<std::string, std::string>>& properties,
                     const std::vector<JUnitCase>& cases) {
  std::size_t failures = 0;
  double total = 0;
  for (const JUnitCase& c : cases) {
    failures += !c.reasons.empty();
    total += c.seconds;
  }
  const std::string counts = " tests=\"" + std::to_string(cases.size()) + "\" failures=\"" + std::to_string(failures) +
                             "\" errors=\"0\"";
  std::string classname = suite;  // dotted, as JUnit's class names are
  for (char& c : classname) c = c == ' ' ? '.' : c;
  std::ostringstream xml;
  xml << "<?xml version=\"1.0\" encoding=\"UTF-8\"?>\n"
      << "<testsuites name=\"" << escapeMarkup(suite) << "\"" << counts << " time=\"" << seconds(total) << "\">\n"
      << "  <testsuite name=\"" << escapeMarkup(suite) << "\"" << counts << " skipped=\"0\" time=\"" << seconds(total)
      << "\">\n"
      << "    <properties>\n";
  for (const auto& [name, value] : properties) {
    xml << "      <property name=\"" << escapeMarkup(name) << "\" value=\"" << escapeMarkup(value) << "\"/>\n";
  }
  xml << "    </properties>\n";
  for (const JUnitCase& c : cases) {
    xml << "    <testcase classname=\"" << escapeMarkup(classname) << "\" name=\"" << escapeMarkup(c.name) << "\" time=\""
        << seconds(c.seconds) << "\">\n";
    if (!c.reasons.empty()) {
      std::string all;
      for (const std::string& reason : c.reasons) all += reason + "\n";
      xml << "      <failure type=\"accuracy gate\" message=\"" << escapeMarkup(c.reasons.front()) << "\">"
          << escapeMarkup(all) << "</failure>\n";
    }
    std::string out = c.summary;
    for (const std::string& warning : c.warnings) out += "\nwarning: " + warning;
    xml << "      <system-out>" << escapeMarkup(out) << "</system-out>\n    </testcase>\n";
  }
  xml << "  </testsuite>\n</testsuites>\n";
  return xml.str();
}

}  // namespace rc::app
