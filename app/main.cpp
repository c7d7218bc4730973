// rastercheck: the one CLI. Parses, runs the chosen subcommand, maps errors to exit codes
// (README.md, "Exit codes"). This is the only place errors are caught.
#include <cstdio>
#include <new>

#include "app/commands.h"
#include "app/options.h"
#include "core/atomic_file.h"
#include "core/error.h"

int main(int argc, char** argv) {
  rc::removeTemporariesOnSignal();
  CLI::App root{"rastercheck: a CPU rasterizer checked pixel by pixel against an Embree reference"};
  root.require_subcommand(1);
  root.set_version_flag("--version", "rastercheck " RASTERCHECK_VERSION);
  rc::app::Action action;
  rc::app::registerScenes(root, action);
  rc::app::registerRender(root, action);
  rc::app::registerCompare(root, action);
  rc::app::registerCheck(root, action);
  rc::app::registerBench(root, action);
  rc::app::registerExport(root, action);
  try {
    rc::app::refuseEmptyAssignments(argc, argv);
    root.parse(argc, argv);
  } catch (const CLI::CallForHelp& e) {
    return root.exit(e);
  } catch (const CLI::CallForAllHelp& e) {
    return root.exit(e);
  } catch (const CLI::CallForVersion& e) {
    return root.exit(e);
  } catch (const CLI::ParseError& e) {
    root.exit(e);
    return int(rc::ExitCode::kUsage);
  }
  try {
    return action();
  } catch (const rc::Error& e) {
    std::fprintf(stderr, "rastercheck: error: %s\n", e.what());
    return int(e.code());
  } catch (const std::bad_alloc&) {
    std::fprintf(stderr, "rastercheck: error: out of memory\n");
    return int(rc::ExitCode::kIo);
  } catch (const std::exception& e) {
    std::fprintf(stderr, "rastercheck: internal error: %s\n", e.what());
    return int(rc::ExitCode::kInternal);
  }
}
