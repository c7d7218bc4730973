// Options shared by several subcommands, declared once: rasterizer settings, the reference's
// settings, gate thresholds and output-path checks (the settings themselves: settings.h).
#pragma once

#include <CLI/CLI.hpp>
#include <functional>
#include <set>
#include <string>
#include <utility>
#include <vector>

#include "app/settings.h"
#include "compare/compare.h"
#include "core/atomic_file.h"
#include "core/exr_io.h"

namespace rc::app {

std::string lowerCase(std::string text);

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

// An output file and the option that names it ("--json"); an empty path: not asked for.
// `extension` (".exr"): the format written, which a name with another extension contradicts.
// `text`: a text document (--json, --csv), which "-" sends to standard output.
struct OutputOption {
  std::string option, path;
  std::string extension = {};
  bool text = false;
};
// "-" as a text output's path: standard output. The document is written there whole, at the
// end (WrittenOutputs::keep), and the command's own text (the table, the statistics) goes to stderr
// instead, so that stdout carries the document alone (`bench --json - | jq`).
inline constexpr const char* kStandardOutput = "-";
// A text output named by a path to the file or pipe that standard output already is
// (/dev/stdout, /proc/self/fd/1, or the file's own name with `> file` or `>> file`) becomes "-":
// written there whole, at the end, with the table on stderr, instead of renamed over the file
// (which would drop what the shell appends to) or mixed with the table in the pipe. A terminal
// or another device is left as named.
void takeStandardOutputByName(std::string& path);
// Throws usageError when an output names the same file as one of `inputs`, or as another
// output (written one after the other, the last would silently replace the first), or when
// its name ends in another format's extension (an EXR written to out.png). A name without
// an extension, or a device, takes any format.
// "-" is refused for any output but a text one, and for two of them; so is an image output that
// names the file or pipe standard output is, where the command's text goes too.
void checkOutputs(const std::vector<OutputOption>& outputs, const std::vector<std::string>& inputs);
// When one of the outputs is "-": from here on the command's text goes to stderr. Call it once
// the outputs are checked, before the command prints anything.
void routeTextAwayFromStandardOutput(const std::vector<OutputOption>& outputs);

// Throws ioError naming the output when its folder is missing or not writable, it is a folder
// itself, or it is a file its owner made read-only (AtomicOutput's checks): called before the
// work, so that a typo fails now rather than after minutes of rendering.
void checkOutputFolders(const std::vector<OutputOption>& outputs);

// The files and folders one command writes, all or none: each file waits as a hidden temporary
// (an OutputBatch) and keep(), once everything is written, renames them all into place. A
// command that stops with an error part way (one file written, the disk full at the next)
// leaves every file as it was, the ones it would have replaced included, and no folder it made.
class WrittenOutputs {
 public:
  WrittenOutputs() = default;
  WrittenOutputs(const WrittenOutputs&) = delete;
  WrittenOutputs& operator=(const WrittenOutputs&) = delete;

  // Makes the folder and any missing level above it; throws ioError naming it, also when the
  // user may not write into it.
  void makeFolder(const std::string& dir);
  // Writes `path` through write(path) unless the path is empty (not asked for).
  template <class Write>
  void write(const std::string& path, Write&& write) {
    if (!path.empty()) write(path);
  }
  // Writes a text document to `path`, or for "-" to standard output, which keep() does last,
  // once every file is in place.
  void writeText(const std::string& path, const std::string& content);
  // Renames every file into place, then writes the standard output's document; throws ioError
  // naming a file that cannot be written.
  void keep();

 private:
  // Also holds the folder levels makeFolder made. Destroyed without keep(), it discards them
  // all: the temporaries, then the folders made, where empty.
  OutputBatch batch_;
  std::string standardOutput_;  // the document for "-", if any
};

// Output file stem of a scene: a file's own stem ("../data/spot.obj" -> "spot"), a built-in
// scene's spec made safe ("blob:tris=1000" -> "blob_tris-1000"); "-2", "-3"... on collisions.
std::string fileStem(const std::string& scene, std::set<std::string>& used);

}  // namespace rc::app
