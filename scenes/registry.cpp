// Scene registry and parameter parsing.
#include "scenes/registry.h"

#include <charconv>
#include <cmath>
#include <string>

#include "core/error.h"
#include "core/number_text.h"
#include "scenes/builtin/builtin.h"
#include "scenes/hard/hard_scenes.h"

namespace rc {

SceneArgs::SceneArgs(std::string scene, std::map<std::string, std::string> values)
    : scene_(std::move(scene)), values_(std::move(values)) {}

long long SceneArgs::getInt(const std::string& key, long long fallback, long long min,
                            long long max) {
  used_.insert(key);
  auto it = values_.find(key);
  if (it == values_.end()) return fallback;
  // Accept plain integers and exact scientific forms such as 1e6.
  const double value = getDouble(key, double(fallback), double(min), double(max));
  if (value != std::floor(value)) {
    throw usageError("scene " + scene_ + ": " + key + "=" + it->second + " is not a whole number");
  }
  return static_cast<long long>(value);
}

double SceneArgs::getDouble(const std::string& key, double fallback, double min, double max) {
  used_.insert(key);
  auto it = values_.find(key);
  if (it == values_.end()) return fallback;
  const std::string& text = it->second;
  double value = 0.0;
  auto [end, ec] = std::from_chars(text.data(), text.data() + text.size(), value);
  if (ec != std::errc() || end != text.data() + text.size() || !std::isfinite(value)) {
    throw usageError("scene " + scene_ + ": " + key + "=" + text + " is not a number");
  }
  if (!(value >= min && value <= max)) {
    throw usageError("scene " + scene_ + ": " + key + "=" + text + " is outside [" + exactNumber(min) + ", " +
                     exactNumber(max) + "]");
  }
  return value;
}

void SceneArgs::checkAllUsed() const {
  for (const auto& [key, value] : values_) {
    if (!used_.count(key)) throw usageError("scene " + scene_ + ": unknown parameter '" + key + "'");
  }
}

const std::vector<BuiltinScene>& builtinScenes() {
  static const std::vector<BuiltinScene> kScenes = {
      {"floor",
       "large checkered floor at a grazing angle (the seed notes' case: affine bends the checker)",
       "", SceneGroup::kDefault, builtin::makeFloor},
      {"cube", "cube with per-face UVs, three faces in perspective", "", SceneGroup::kDefault,
       builtin::makeCube},
      {"sphere", "UV sphere with normals and UVs", "segments=N (4..1024, default 32)",
       SceneGroup::kDefault, builtin::makeSphere},
      {"blob", "scalable bumpy ellipsoid filling most of a 1920x1080 frame, normals and UVs",
       "tris=N (8..4000000, default 100000)", SceneGroup::kDefault, builtin::makeBlob},
      {"fans", "vertex fans of 3..64 triangles around pixel centres, spokes through centres", "",
       SceneGroup::kHardCase, hard::makeFans},
      {"edges", "shared edges exactly through pixel centres at 12 slopes, both windings", "",
       SceneGroup::kHardCase, hard::makeEdges},
      {"closed", "random closed mesh: jittered icosphere, randomly rotated",
       "seed=N (default 1), level=N (0..6 subdivisions, default 3)", SceneGroup::kHardCase,
       hard::makeClosed},
      {"slivers", "needles of screen aspect 10..1e7 in 8 orientations", "", SceneGroup::kHardCase,
       hard::makeSlivers},
      {"degenerate", "zero-area, repeated-vertex and one-ulp-from-collinear triangles", "",
       SceneGroup::kHardCase, hard::makeDegenerate},
      {"subpixel", "triangles smaller than a pixel covering 0, 1 or 2 pixel centres", "",
       SceneGroup::kHardCase, hard::makeSubpixel},
      {"huge", "vertices 1e6 and 1e9 pixels outside the image", "", SceneGroup::kHardCase,
       hard::makeHuge},
      {"nearplane",
       "w just above near, behind near, behind the eye, crossing w = 0; strips cut lengthwise by near and far", "",
       SceneGroup::kHardCase, hard::makeNearPlane},
      {"perspective", "depth ratio w_max / w_min of 1e2, 1e4 and 1e6 within one triangle", "",
       SceneGroup::kHardCase, hard::makePerspective},
      {"grazing", "floor and wall seen at 2 down to 0.005 degrees", "", SceneGroup::kHardCase,
       hard::makeGrazing},
      {"faroffset", "small scene and camera moved far from the world origin",
       "offset=D (0..1e7, default 1e5)", SceneGroup::kHardCase, hard::makeFarOffset},
      {"depthpairs", "parallel quad pairs at z/near 3..1e6, gaps at 4x depth resolution", "",
       SceneGroup::kHardCase, hard::makeDepthPairs},
      {"zfight", "coplanar overlapping and repeated triangles", "", SceneGroup::kHardCase,
       hard::makeZFight},
      {"attributes", "attributes near 1e30, 1e-30, mixed sign, and constant", "",
       SceneGroup::kHardCase, hard::makeAttributes},
  };
  return kScenes;
}

std::vector<std::string> defaultSceneNames() {
  std::vector<std::string> names;
  for (const BuiltinScene& s : builtinScenes()) {
    if (s.group == SceneGroup::kDefault) names.push_back(s.name);
  }
  return names;
}

std::vector<std::string> hardCaseSpecs() {
  std::vector<std::string> specs;
  for (const BuiltinScene& s : builtinScenes()) {
    if (s.group != SceneGroup::kHardCase) continue;
    if (std::string(s.name) == "faroffset") {
      for (const char* offset : {"1e3", "1e5", "1e7"}) specs.push_back(std::string("faroffset:offset=") + offset);
    } else if (std::string(s.name) == "closed") {
      for (const char* seed : {"1", "2", "3"}) specs.push_back(std::string("closed:seed=") + seed);
    } else {
      specs.push_back(s.name);
    }
  }
  return specs;
}

std::vector<std::string> expandSceneGroups(const std::vector<std::string>& specs) {
  std::vector<std::string> out;
  for (const std::string& spec : specs) {
    const std::vector<std::string> group = spec == "default" ? defaultSceneNames()
                                           : spec == "hard"  ? hardCaseSpecs()
                                                             : std::vector<std::string>{spec};
    out.insert(out.end(), group.begin(), group.end());
  }
  return out;
}

namespace {

const BuiltinScene* findScene(const std::string& name) {
  for (const BuiltinScene& s : builtinScenes()) {
    if (name == s.name) return &s;
  }
  return nullptr;
}

}  // namespace

bool isBuiltinSceneSpec(const std::string& spec) {
  return findScene(spec.substr(0, spec.find(':'))) != nullptr;
}

Scene makeBuiltinScene(const std::string& spec) {
  const std::size_t colon = spec.find(':');
  const std::string name = spec.substr(0, colon);
  const BuiltinScene* entry = findScene(name);
  if (!entry) {
    throw usageError("unknown scene '" + name + "' (see `rastercheck scenes`)");
  }
  std::map<std::string, std::string> values;
  if (colon != std::string::npos) {
    std::string rest = spec.substr(colon + 1);
    std::size_t start = 0;
    while (start <= rest.size()) {
      std::size_t comma = rest.find(',', start);
      if (comma == std::string::npos) comma = rest.size();
      const std::string item = rest.substr(start, comma - start);
      const std::size_t eq = item.find('=');
      if (eq == std::string::npos || eq == 0) {
        throw usageError("scene " + spec + ": parameters are key=value pairs separated by ','");
      }
      if (!values.emplace(item.substr(0, eq), item.substr(eq + 1)).second) {
        throw usageError("scene " + spec + ": parameter '" + item.substr(0, eq) + "' given twice");
      }
      start = comma + 1;
    }
  }
  SceneArgs args(spec, values);
  Scene scene = entry->make(args);
  args.checkAllUsed();
  scene.name = spec;
  scene.description = entry->description;
  validateMesh(scene.mesh, "scene " + spec);
  return scene;
}

}  // namespace rc
