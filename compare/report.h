// Turning a CompareReport into the JSON report (docs/compare.md, format_version 1) and a
// human-readable table.
#pragma once

#include <string>

#include <nlohmann/json.hpp>

#include "compare/compare.h"

namespace rc {

inline constexpr int kReportFormatVersion = 1;

nlohmann::json reportToJson(const CompareReport& report);

// A JSON document as the commands write it: indented, ending in a newline. A string that is
// not valid UTF-8 (a file name may be any bytes) has its bad bytes replaced by U+FFFD, where
// nlohmann::json would otherwise throw after all the work was done.
inline std::string jsonDocument(const nlohmann::json& j) {
  return j.dump(2, ' ', false, nlohmann::json::error_handler_t::replace) + "\n";
}
std::string reportToTable(const CompareReport& report);

// "1.23e-07": compact, locale-independent.
std::string formatNumber(double value);

// "(x,y) test / reference", or "-" when there was no finite error.
std::string formatWorst(const WorstPixel& worst);

}  // namespace rc
