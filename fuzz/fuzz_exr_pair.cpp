// libFuzzer target: two EXR files given to compare. The input holds both, split at the first
// "--RC-SPLIT--" (seeds: scripts/fuzz.sh renders a raster and a reference EXR and joins them).
#include <cstring>
#include <string_view>

#include "compare/compare.h"
#include "core/error.h"
#include "core/exr_io.h"
#include "fuzz/fuzz_input.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string_view all(reinterpret_cast<const char*>(data), size);
  const std::size_t split = all.find("--RC-SPLIT--");
  const std::string_view first = all.substr(0, split);
  const std::string_view second = split == std::string_view::npos ? all : all.substr(split + 12);
  const std::string a = rc::fuzz::writeInput("test.exr", reinterpret_cast<const std::uint8_t*>(first.data()), first.size());
  const std::string b = rc::fuzz::writeInput("ref.exr", reinterpret_cast<const std::uint8_t*>(second.data()), second.size());
  try {
    const rc::Framebuffer test = rc::readExr(a);
    const rc::Framebuffer reference = rc::readExr(b);
    rc::Framebuffer heatmap;
    rc::Thresholds thresholds;  // every warning limit at 0, so that the warnings are made too
    thresholds.warn = {0.0, 0.0, 0.0, 0.0, 0.0};
    rc::compareImages(test, a, reference, b, thresholds, &heatmap);
  } catch (const rc::Error&) {
  }
  return 0;
}
