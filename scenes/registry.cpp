// Scene registry and parameter parsing.
#include "scenes/registry.h"

#include <charconv>
#include <cmath>

#include "core/error.h"
#include "scenes/builtin/builtin.h"

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
    throw usageError("scene " + scene_ + ": " + key + "=" + text + " is outside [" +
                     std::to_string(min) + ", " + std::to_string(max) + "]");
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
       "", true, builtin::makeFloor},
      {"cube", "cube with per-face UVs, three faces in perspective", "", true, builtin::makeCube},
      {"sphere", "UV sphere with normals and UVs", "segments=N (4..1024, default 32)", true,
       builtin::makeSphere},
      {"blob", "scalable bumpy ellipsoid filling most of a 1920x1080 frame, normals and UVs",
       "tris=N (8..4000000, default 100000)", true, builtin::makeBlob},
  };
  return kScenes;
}

std::vector<std::string> defaultSceneNames() {
  std::vector<std::string> names;
  for (const BuiltinScene& s : builtinScenes()) {
    if (s.inDefaultSet) names.push_back(s.name);
  }
  return names;
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
