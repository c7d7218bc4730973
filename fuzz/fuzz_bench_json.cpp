// libFuzzer target: bench results given to check --bench-json, read and drawn as the SVG chart.
#include "app/bench_files.h"
#include "app/bench_chart.h"
#include "core/error.h"
#include "fuzz/fuzz_input.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  try {
    const rc::app::BenchResults results = rc::app::readBenchJson(rc::fuzz::writeInput("bench.json", data, size));
    rc::app::benchChartSvg(results.rows, results.machine ? &*results.machine : nullptr,
                           results.load ? &*results.load : nullptr);
  } catch (const rc::Error&) {
  }
  return 0;
}
