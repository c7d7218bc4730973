// What the CLI tests share: running rastercheck by a short name, and its result.
#pragma once

#include <filesystem>
#include <string>

#include "tests/run_command.h"

namespace rc::testing::cli {

namespace fs = std::filesystem;

using CliRun = CommandResult;

inline CliRun run(const std::string& args) { return runRastercheck(args); }

}  // namespace rc::testing::cli
