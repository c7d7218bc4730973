// Factories of the built-in scenes, one file each; registered in scenes/registry.cpp.
#pragma once

#include "scenes/registry.h"

namespace rc::builtin {

Scene makeFloor(SceneArgs& args);
Scene makeCube(SceneArgs& args);
Scene makeSphere(SceneArgs& args);
Scene makeBlob(SceneArgs& args);

}  // namespace rc::builtin
