// What the commands share apart from their command lines: the render settings, loading a
// scene with them, and the clock. Kept apart from options.h, so that the code that runs a
// check or a bench (and its tests) compiles without CLI11.
#pragma once

#include <string>
#include <vector>

#include "rasterizer/rasterizer.h"
#include "raytracer_ref/reference.h"
#include "scenes/scene.h"

namespace rc::app {

struct RenderSettings {
  RasterOptions raster;
  ReferenceOptions reference;
  int threads = 0;
  std::string size;        // "WxH" override of the scene's image size, or empty
  std::string eye, target, up;  // "x,y,z" camera overrides, or empty
  double fovYDegrees = 0;  // vertical field of view override; 0 keeps the scene's
  std::string camera;      // a glTF file's camera (index or name); empty: the first it places
  std::vector<std::string> attributes;  // narrows the attributes written; empty keeps all
  long long maxTriangles = 20'000'000;  // larger scenes are refused (memory stays bounded)
  int maxImageSide = 16384;             // larger images are refused (OpenEXR's limit is 16384)
};

// Propagates the thread count and checks the combination; throws usageError.
void finishRenderSettings(RenderSettings& settings);

// A built-in scene (NAME[:key=value,...]), an OBJ or glTF file or a scene file, with the
// command line's camera, size and attribute overrides applied.
Scene loadScene(const std::string& spec, const RenderSettings& settings);

}  // namespace rc::app
