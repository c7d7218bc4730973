// What the CLI tests share: running rastercheck by a short name, and its result, and reading
// the figures it prints.
#pragma once

#include <cstdio>
#include <filesystem>
#include <iterator>
#include <sstream>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "compare/report.h"

#include "tests/run_command.h"

namespace rc::testing::cli {

namespace fs = std::filesystem;

using CliRun = CommandResult;

inline CliRun run(const std::string& args) { return runRastercheck(args); }

// The whitespace-separated cells of the line of `output` that starts at `at`.
inline std::vector<std::string> cellsOfLine(const std::string& output, std::size_t at) {
  std::istringstream line(output.substr(at, output.find('\n', at) - at));
  return {std::istream_iterator<std::string>(line), {}};
}

// A JSON number as the tables print it: formatNumber's 3 digits, or printf's `format`.
inline std::string printed(const nlohmann::json& value) { return formatNumber(value.get<double>()); }
inline std::string printed(const nlohmann::json& value, const char* format) {
  char text[32];
  std::snprintf(text, sizeof text, format, value.get<double>());
  return text;
}

}  // namespace rc::testing::cli
