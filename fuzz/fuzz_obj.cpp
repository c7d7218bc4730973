// libFuzzer target: OBJ meshes.
#include "core/error.h"
#include "fuzz/fuzz_input.h"
#include "scenes/loaders/obj_loader.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  try {
    rc::loadObj(rc::fuzz::writeInput("input.obj", data, size));
  } catch (const rc::Error&) {
  }
  return 0;
}
