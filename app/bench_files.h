// bench's rows as files: JSON (written and read back, for the report and the chart) and CSV.
#pragma once

#include <optional>
#include <string>
#include <vector>

#include "app/bench.h"
#include "app/bench_conditions.h"

namespace rc::app {

// `load`, where measured, goes in as "load": {"other_processes", "steal"}.
std::string benchJson(const std::vector<BenchRow>& rows, const BenchMachine& machine,
                      const std::optional<BenchLoad>& load = std::nullopt);

// What benchJson wrote: the rows, the machine where the file has one (bench wrote none before
// session 17), and the load where it has one (none before session 43, or where bench could not
// read /proc/stat).
struct BenchResults {
  std::vector<BenchRow> rows;
  std::optional<BenchMachine> machine;
  std::optional<BenchLoad> load;
};
// Reads what benchJson wrote, the rows' loads too; throws ioError / badInput naming the file
// and the JSON pointer (a load share outside 0 to 1 too).
BenchResults readBenchJson(const std::string& path);
std::string benchCsv(const std::vector<BenchRow>& rows);

}  // namespace rc::app
