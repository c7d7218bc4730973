// libFuzzer target: JSON scene files (mesh paths resolve inside the fuzzer's own folder).
#include "core/error.h"
#include "fuzz/fuzz_input.h"
#include "scenes/loaders/scene_file.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  try {
    rc::loadSceneFile(rc::fuzz::writeInput("input.json", data, size));
  } catch (const rc::Error&) {
  }
  return 0;
}
