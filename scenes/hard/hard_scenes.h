// Factories of the hard-case scenes, one file each (their headers say what each stresses and
// what must hold); registered in scenes/registry.cpp.
#pragma once

#include <cstdint>

#include "scenes/registry.h"

namespace rc::hard {

Scene makeFans(SceneArgs& args);
Scene makeEdges(SceneArgs& args);
Scene makeClosed(SceneArgs& args);
Scene makeSlivers(SceneArgs& args);
Scene makeDegenerate(SceneArgs& args);
Scene makeSubpixel(SceneArgs& args);
Scene makeHuge(SceneArgs& args);
Scene makeNearPlane(SceneArgs& args);
Scene makePerspective(SceneArgs& args);
Scene makeGrazing(SceneArgs& args);
Scene makeFarOffset(SceneArgs& args);
Scene makeDepthPairs(SceneArgs& args);
Scene makeZFight(SceneArgs& args);
Scene makeAttributes(SceneArgs& args);

// A subdivided icosahedron with vertex radii jittered by +-jitter, randomly rotated: closed,
// consistently wound outwards. Shared with the watertightness tests.
Mesh jitteredSphere(std::uint64_t seed, int subdivisions, double jitter);

}  // namespace rc::hard
