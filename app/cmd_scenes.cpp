// `rastercheck scenes`: the built-in scenes, one line each.
#include <cstdio>

#include "app/commands.h"
#include "scenes/registry.h"

namespace rc::app {

void registerScenes(CLI::App& root, Action& action) {
  CLI::App* command = root.add_subcommand("scenes", "list the built-in scenes");
  command->callback([&action] {
    action = [] {
      for (SceneGroup group : {SceneGroup::kDefault, SceneGroup::kHardCase}) {
        std::printf(group == SceneGroup::kDefault
                        ? "Default set (`rastercheck check` with no scene, or the group name \"default\"):\n"
                        : "\nHard cases (the group name \"hard\"; each file in scenes/hard/ says what must hold):\n");
        for (const BuiltinScene& s : builtinScenes()) {
          if (s.group != group) continue;
          std::printf("  %-12s %s\n", s.name, s.description);
          if (*s.parameters) std::printf("  %-12s   parameters: %s\n", "", s.parameters);
        }
      }
      std::printf("\nParameters are given as NAME:key=value,key=value, e.g. blob:tris=1000000.\n");
      return 0;
    };
  });
}

}  // namespace rc::app
