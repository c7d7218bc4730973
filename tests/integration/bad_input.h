// What the bad-input tests share (bad_input_test.cpp, bad_exr_input_test.cpp): running
// rastercheck, and looking at what it left.
#pragma once

#include <filesystem>
#include <string>

#include "tests/run_command.h"
#include "tests/test_files.h"

namespace rc::testing::bad_input {

namespace fs = std::filesystem;
using rc::testing::TempDir;
using Outcome = rc::testing::CommandResult;

inline Outcome rastercheck(const std::string& args, const std::string& env = "") { return runRastercheck(args, env); }

inline bool emptyOrAbsent(const fs::path& dir) { return !fs::exists(dir) || fs::is_empty(dir); }

inline std::string readAll(const std::string& path) { return readFile(path); }

}  // namespace rc::testing::bad_input
