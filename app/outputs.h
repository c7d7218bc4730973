// The files a command writes: checked before the work (names, formats, folders), written all or
// none, and standard output as a document's destination ("-").
#pragma once

#include <set>
#include <string>
#include <vector>

#include "core/atomic_file.h"

namespace rc::app {

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
