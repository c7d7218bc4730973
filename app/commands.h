// The subcommands of the one CLI. Each registers itself on the root app and, when chosen,
// stores the action main() runs; the action returns the process exit code.
#pragma once

#include <CLI/CLI.hpp>
#include <functional>

namespace rc::app {

using Action = std::function<int()>;

void registerScenes(CLI::App& root, Action& action);
void registerRender(CLI::App& root, Action& action);
void registerCompare(CLI::App& root, Action& action);
void registerCheck(CLI::App& root, Action& action);
void registerBench(CLI::App& root, Action& action);
void registerExport(CLI::App& root, Action& action);

}  // namespace rc::app
