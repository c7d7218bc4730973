// The registry of built-in procedural scenes, addressed as NAME or NAME:key=value,key=value
// (for example "blob:tris=1000000"). Each scene lives in its own file under scenes/builtin/.
#pragma once

#include <map>
#include <set>
#include <string>
#include <vector>

#include "scenes/scene.h"

namespace rc {

// Typed access to a scene's key=value parameters. Numbers are parsed with std::from_chars,
// so the locale never matters; a missing key takes its default, a malformed or out-of-range
// value or a key no scene reads is a usage error naming the scene and the key.
class SceneArgs {
 public:
  SceneArgs(std::string scene, std::map<std::string, std::string> values);
  long long getInt(const std::string& key, long long fallback, long long min, long long max);
  double getDouble(const std::string& key, double fallback, double min, double max);
  void checkAllUsed() const;

 private:
  std::string scene_;
  std::map<std::string, std::string> values_;
  std::set<std::string> used_;
};

enum class SceneGroup {
  kDefault,   // run by `rastercheck check` without scene arguments
  kHardCase,  // the numerical hard cases (scenes/hard/), run by `rastercheck check hard`
};

struct BuiltinScene {
  const char* name;
  const char* description;  // one line, for `rastercheck scenes`
  const char* parameters;   // "tris=N (8..4000000, default 100000)" or ""
  SceneGroup group;
  Scene (*make)(SceneArgs& args);
};

const std::vector<BuiltinScene>& builtinScenes();
std::vector<std::string> defaultSceneNames();
// Every hard case, parametrised ones at each value that matters (faroffset at 1e3, 1e5, 1e7).
std::vector<std::string> hardCaseSpecs();
// Replaces the group names "default" and "hard" in a scene list by their members.
std::vector<std::string> expandSceneGroups(const std::vector<std::string>& specs);
bool isBuiltinSceneSpec(const std::string& spec);

// Builds and validates a built-in scene; throws usageError for an unknown name or parameter.
Scene makeBuiltinScene(const std::string& spec);

}  // namespace rc
