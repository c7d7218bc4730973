// libFuzzer target: --baseline reports (compare --json, check --json), read and held to.
#include <limits>

#include "compare/baseline.h"
#include "core/error.h"
#include "fuzz/fuzz_input.h"

namespace {

// A report of the seeds' size (8x6) with every kind of family, so that a baseline read is also
// held to: its figures against a finite error, a NaN and a bounded family's ratio.
rc::CompareReport report() {
  rc::CompareReport r;
  r.width = 8;
  r.height = 6;
  r.coveredEither = 40;
  r.disagreementFraction = 0.05;
  r.coverageFraction = 0.025;
  for (const char* name : {"bary", "depth", "attr.uv", "attr.normal"}) {
    rc::FamilyReport f;
    f.name = name;
    f.stats.max = f.stats.p999 = 1e-6;
    f.range = 2.0;
    f.bounded = f.name == "bary";
    f.ratio.max = 0.25;
    r.families.push_back(f);
  }
  r.families[3].stats.max = std::numeric_limits<double>::quiet_NaN();
  return r;
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  static const rc::CompareReport now = report();
  const std::string path = rc::fuzz::writeInput("baseline.json", data, size);
  for (const bool perScene : {false, true}) {
    try {
      for (const auto& [scene, each] : rc::readBaseline(path, perScene)) {
        for (const rc::BaselineFigures& figures : each) {
          for (const double factor : {1.0, 2.0}) rc::baselineWarnings(now, figures, factor);
        }
      }
    } catch (const rc::Error&) {
    }
  }
  return 0;
}
