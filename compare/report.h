// Turning a CompareReport into the JSON report (docs/compare.md, format_version 1) and a
// human-readable table.
#pragma once

#include <string>
#include <utility>

#include <nlohmann/json_fwd.hpp>

#include "compare/compare.h"

namespace rc {

inline constexpr int kReportFormatVersion = 1;

nlohmann::json reportToJson(const CompareReport& report);

// A JSON document as the commands write it: indented, ending in a newline. A string that is
// not valid UTF-8 (a file name may be any bytes) has its bad bytes replaced by U+FFFD, where
// nlohmann::json would otherwise throw after all the work was done.
std::string jsonDocument(const nlohmann::json& j);
std::string reportToTable(const CompareReport& report);
// Why the disagreements are allowed, as the table and the HTML report say it: "11 in the edge
// band (0.0055 px), 13 depth ties, 17 unexplained" with the diagnostics, else "8 at an edge of
// the ids, 0 depth ties (within the depth limit), 1 unexplained".
std::string disagreementCounts(const CompareReport& report);

// "1.23e-07": compact, locale-independent.
std::string formatNumber(double value);
// Two numbers in as few significant digits as tell them apart, at least 3 ("1.91e-07" and
// "1e-09"; 17 for two a ulp apart): fixed decimals print 1.9e-7 and 1e-9 alike as 0.000000.
std::pair<std::string, std::string> formatApart(double a, double b);

// A JSON document read from `path`; throws ioError when it cannot be read and badInput naming
// the file when it is not JSON. `what` says what it was to be ("bench results").
nlohmann::json readJsonFile(const std::string& path, const std::string& what);

// "(x,y) test / reference", or "-" when there was no finite error.
std::string formatWorst(const WorstPixel& worst);

}  // namespace rc
