// Options shared by several subcommands, declared once: rasterizer settings, the reference's
// settings and gate thresholds (the settings themselves: settings.h; the output files'
// checks: outputs.h).
#pragma once

#include <CLI/CLI.hpp>
#include <functional>
#include <string>
#include <utility>
#include <vector>

#include "app/settings.h"
#include "compare/compare.h"
#include "core/exr_io.h"

namespace rc::app {

std::string lowerCase(std::string text);

// Refuses `--name=` with nothing after '=' (an unset shell variable in `--out=$DIR`), throwing
// CLI::ValidationError that names it: CLI11 took the next argument as the value instead, so
// `check --out= cube` checked the default scenes into a folder named cube. Arguments after
// "--" are positionals, left alone. Call it before parsing.
void refuseEmptyAssignments(int argc, const char* const* argv);

// An option that takes one of `choices` by name, in any case, into `target`; its default is
// target's value as given. CLI11's CheckedTransformer also took the enum's number (`--mode 1`
// for affine) and showed a name->number table in the help.
template <class Enum>
void addChoice(CLI::App* command, const std::string& name, Enum& target,
               const std::vector<std::pair<std::string, Enum>>& choices, const std::string& help) {
  std::string names, fallback;
  for (const auto& [choice, value] : choices) {
    names += (names.empty() ? "" : "|") + choice;
    if (value == target) fallback = choice;
  }
  command
      ->add_option_function<std::string>(
          name,
          [&target, choices](const std::string& text) {
            for (const auto& [choice, value] : choices) {
              if (choice == lowerCase(text)) target = value;
            }
          },
          help)
      ->check(CLI::Validator(
          [choices, names](std::string& text) -> std::string {
            for (const auto& choice : choices) {
              if (choice.first == lowerCase(text)) return "";
            }
            return "must be one of " + names + ", got '" + text + "'";
          },
          ""))
      ->type_name(names)
      ->default_str(fallback);
}

// An option that takes a list separated by commas ("uv,normal"), given once or repeated. It
// takes one argument each time, so a scene or file after it stays a positional (CLI11's list
// options took every argument up to the next option: `--attributes uv cube` read cube as an
// attribute), and an empty item ("uv,,normal", a lone ",") is refused rather than skipped
// (CLI11 skipped it and took the next argument in its place). checkItem, where given, says why
// an item is refused ("" where it is not); `take` receives the items of every occurrence.
CLI::Option* addListOption(CLI::App* command, const std::string& name, std::function<void(std::vector<std::string>)> take,
                           const std::string& help, std::function<std::string(const std::string&)> checkItem = {});

void addRenderOptions(CLI::App* command, RenderSettings& settings);
// The options that change the scene itself (camera, size, attributes, limits), which
// addRenderOptions includes; for commands that render nothing.
void addSceneOptions(CLI::App* command, RenderSettings& settings);
void addThresholdOptions(CLI::App* command, Thresholds& thresholds);
// --baseline FILE and --baseline-factor F: hold the figures to an earlier JSON report, the
// command's own (`writtenBy`: "rastercheck check --json").
void addBaselineOptions(CLI::App* command, BaselineUse& baseline, const std::string& writtenBy);
// The fixed limits (--max-bary, --max-depth, --max-attr, --max-disagreement, --max-coverage)
// given on `command`'s line.
std::vector<std::string> givenLimits(const CLI::App& command);
// Says on stderr which of the `given` limits gated nothing in any of `reports`: the images carry
// the bound channels (the bounds gate those families, and the disagreements are explained), or
// no attribute was compared. A limit the user set is never left unused in silence.
void noteUnappliedLimits(const std::vector<std::string>& given, const std::vector<const CompareReport*>& reports);
// Says on stderr that --fail-on-warnings was given without a warning limit or a baseline.
void noteIdleFailOnWarnings(const Thresholds& thresholds, const BaselineUse& baseline);
// --exr-compression, for the commands that write EXR files.
void addExrCompressionOption(CLI::App* command, ExrCompression& compression);
// --threads N, 0..256 (0 = all cores); `what` says what the threads do.
void addThreadsOption(CLI::App* command, int& threads, const std::string& what);

}  // namespace rc::app
