// libFuzzer target: glTF and GLB (the loader tells them apart by the magic).
#include "core/error.h"
#include "fuzz/fuzz_input.h"
#include "scenes/loaders/gltf_loader.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  try {
    rc::loadGltf(rc::fuzz::writeInput("input.gltf", data, size));
  } catch (const rc::Error&) {
  }
  return 0;
}
