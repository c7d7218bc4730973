// `rastercheck scenes`: the built-in scenes, one line each.
#include <cstdio>

#include "app/commands.h"
#include "scenes/registry.h"

namespace rc::app {

void registerScenes(CLI::App& root, Action& action) {
  CLI::App* command = root.add_subcommand("scenes", "list the built-in scenes");
  command->callback([&action] {
    action = [] {
      for (const BuiltinScene& s : builtinScenes()) {
        std::printf("%-8s %s%s\n", s.name, s.description, s.inDefaultSet ? "" : " (not in the default set)");
        if (*s.parameters) std::printf("%-8s   parameters: %s\n", "", s.parameters);
      }
      std::printf("\nParameters are given as NAME:key=value,key=value, e.g. blob:tris=1000000.\n");
      return 0;
    };
  });
}

}  // namespace rc::app
