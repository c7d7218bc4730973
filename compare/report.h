// Turning a CompareReport into the JSON report (docs/compare.md, format_version 1) and a
// human-readable table.
#pragma once

#include <string>

#include <nlohmann/json.hpp>

#include "compare/compare.h"

namespace rc {

inline constexpr int kReportFormatVersion = 1;

nlohmann::json reportToJson(const CompareReport& report);
std::string reportToTable(const CompareReport& report);

// "1.23e-07": compact, locale-independent.
std::string formatNumber(double value);

// "(x,y) test / reference", or "-" when there was no finite error.
std::string formatWorst(const WorstPixel& worst);

}  // namespace rc
