// The CLI's output files as a user meets them: written all or none, never over an input, into
// devices, standard output and terminals as each allows, and nothing left behind by an error or
// Ctrl-C (the rest of the CLI in cli_test.cpp).
#include <gtest/gtest.h>

#include <fcntl.h>
#include <signal.h>
#include <spawn.h>
#include <sys/stat.h>
#include <sys/sysmacros.h>
#include <sys/wait.h>

#include <algorithm>
#include <cstdint>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>
#include <vector>
#include <nlohmann/json.hpp>

#include "tests/integration/cli_run.h"
#include "tests/run_command.h"
#include "tests/test_files.h"

namespace {

using namespace rc::testing::cli;

// check's files are renamed into place together once all are written; when it stops with an
// error part way, every file is as it was (a previous run's too) and the folders it made are
// gone, and a bad scene or bench file makes no folder at all.
TEST(Cli, CheckThatFailsPartWayLeavesNothingItWrote) {
  const rc::testing::TempDir temp;
  const fs::path& dir = temp.path();
  fs::create_directories(dir / "out" / "floor.heatmap.png");  // the second scene's last image cannot be written
  std::ofstream(dir / "out" / "cube.raster.exr") << "a previous run's";
  const CliRun r = run("check cube floor -q --out " + (dir / "out").string() + " --report " + (dir / "rep" / "new").string() +
                       " --json " + (dir / "r.json").string());
  EXPECT_EQ(r.exitCode, 4) << r.output;
  EXPECT_NE(r.output.find("floor.heatmap.png"), std::string::npos) << r.output;
  std::vector<std::string> left;
  for (const auto& entry : fs::recursive_directory_iterator(dir)) left.push_back(fs::relative(entry.path(), dir).string());
  std::sort(left.begin(), left.end());
  EXPECT_EQ(left, (std::vector<std::string>{"out", "out/cube.raster.exr", "out/floor.heatmap.png"}))
      << "cube's files, the report and its folders";
  std::ifstream previous(dir / "out" / "cube.raster.exr");
  EXPECT_EQ(std::string((std::istreambuf_iterator<char>(previous)), {}), "a previous run's");
  for (const std::string& args : {std::string("check cube nosuch"), "check cube --bench-json " + (dir / "none.json").string()}) {
    const CliRun bad = run(args + " -q --out " + (dir / "o2").string() + " --report " + (dir / "r2").string());
    EXPECT_NE(bad.exitCode, 0) << args;
    EXPECT_FALSE(fs::exists(dir / "o2")) << args;
    EXPECT_FALSE(fs::exists(dir / "r2")) << args;
  }
  // A gate that fails is a verdict, not an error: its heatmaps are what the user needs.
  const CliRun failed = run("check floor -q --mode affine --out " + (dir / "o3").string());
  EXPECT_EQ(failed.exitCode, 1) << failed.output;
  EXPECT_TRUE(fs::exists(dir / "o3" / "floor.heatmap.png"));
}

// An output whose folder is missing fails before the work, and before any other output is
// written: compare's heatmap is not left behind when its --json cannot be written.
TEST(Cli, OutputInAMissingFolderFailsFirstAndWritesNothing) {
  const rc::testing::TempDir temp;
  const fs::path& dir = temp.path();
  const std::string exr = (dir / "cube.exr").string(), missing = (dir / "nodir" / "x.json").string();
  ASSERT_EQ(run("render cube -o " + exr).exitCode, 0);
  const CliRun compare = run("compare " + exr + " " + exr + " --heatmap " + (dir / "h.exr").string() + " --json " + missing);
  EXPECT_EQ(compare.exitCode, 4) << compare.output;
  EXPECT_NE(compare.output.find(missing + ": cannot write: folder"), std::string::npos) << compare.output;
  EXPECT_FALSE(fs::exists(dir / "h.exr"));
  const CliRun render = run("render cube -o " + (dir / "nodir" / "c.exr").string());
  EXPECT_EQ(render.exitCode, 4) << render.output;
  const CliRun bench = run("bench cube --runs 1 -q --json " + (dir / "b.json").string() + " --csv " + missing);
  EXPECT_EQ(bench.exitCode, 4) << bench.output;
  EXPECT_EQ(bench.output.find("timed in turn"), std::string::npos) << "fails before timing anything";
  EXPECT_FALSE(fs::exists(dir / "b.json"));
  // check's --json may go into its --out folder, which check makes.
  const CliRun check = run("check cube -q --out " + (dir / "out").string() + " --json " + (dir / "out" / "r.json").string());
  EXPECT_EQ(check.exitCode, 0) << check.output;
  EXPECT_TRUE(fs::exists(dir / "out" / "r.json"));
}

TEST(Cli, OutputThatIsAlsoAnInputIsRefused) {
  const rc::testing::TempDir temp;  // removed at the end of the test
  const fs::path& dir = temp.path();
  const std::string exr = (dir / "cube.exr").string();
  ASSERT_EQ(run("render cube -o " + exr).exitCode, 0);
  const std::uintmax_t size = fs::file_size(exr);
  const CliRun r = run("compare " + exr + " " + exr + " --heatmap " + exr);
  EXPECT_EQ(r.exitCode, 2) << r.output;
  EXPECT_EQ(fs::file_size(exr), size);
  // Two outputs naming one file, the second spelled another way: the first would be lost.
  const std::string png = (dir / "h.png").string(), samePng = (dir / "." / "h.png").string();
  const CliRun twice = run("compare " + exr + " " + exr + " --heatmap-png " + png + " --json " + samePng);
  EXPECT_EQ(twice.exitCode, 2) << twice.output;
  EXPECT_NE(twice.output.find("--heatmap-png and --json name the same file"), std::string::npos) << twice.output;
  EXPECT_FALSE(fs::exists(png));
  // bench: its outputs are checked against each other and against the scene files it reads.
  const CliRun benchTwice = run("bench cube --runs 1 -q --json " + (dir / "b.json").string() + " --csv " +
                                (dir / "b.json").string());
  EXPECT_EQ(benchTwice.exitCode, 2) << benchTwice.output;
  EXPECT_NE(benchTwice.output.find("--json and --csv name the same file"), std::string::npos) << benchTwice.output;
  EXPECT_FALSE(fs::exists(dir / "b.json"));
  const fs::path obj = dir / "tri.obj";
  std::ofstream(obj) << "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n";
  const std::uintmax_t objSize = fs::file_size(obj);
  const CliRun overScene = run("bench " + obj.string() + " --runs 1 -q --csv " + obj.string());
  EXPECT_EQ(overScene.exitCode, 2) << overScene.output;
  EXPECT_NE(overScene.output.find("is also an input"), std::string::npos) << overScene.output;
  EXPECT_EQ(fs::file_size(obj), objSize);
  // render and check do not write over the scene file they read either.
  for (const std::string& command : {"render " + obj.string() + " -o " + obj.string(),
                                     "check " + obj.string() + " -q --json " + obj.string()}) {
    const CliRun over = run(command);
    EXPECT_EQ(over.exitCode, 2) << command << "\n" << over.output;
    EXPECT_NE(over.output.find("is also an input"), std::string::npos) << over.output;
    EXPECT_EQ(fs::file_size(obj), objSize) << command;
  }
}

// Outputs sent to a device (here a null device of our own: as root, a regression would
// replace /dev/null itself) go into it, and it stays a device; two outputs may share it.
TEST(Cli, OutputsIntoADeviceLeaveItADevice) {
  const rc::testing::TempDir temp;
  const fs::path null = temp.path() / "null";
  if (mknod(null.c_str(), S_IFCHR | 0666, makedev(1, 3)) != 0) {
    GTEST_SKIP() << "cannot make a device node here (not root): " << std::strerror(errno);
  }
  const std::string exr = (temp.path() / "cube.exr").string();
  for (const std::string& command :
       {"render cube -o " + null.string(), "bench cube --runs 1 -q --json " + null.string() + " --csv " + null.string(),
        "render cube -o " + exr, "compare " + exr + " " + exr + " --heatmap " + null.string() + " --json " + null.string()}) {
    const CliRun r = run(command);
    EXPECT_EQ(r.exitCode, 0) << command << "\n" << r.output;
    EXPECT_TRUE(fs::is_character_file(null)) << command;
  }
}

// Ctrl-C while outputs are being written: the tool dies of SIGINT, as a shell expects, and
// leaves nothing behind: not render's temporary (a 1920x1080 EXR takes hundreds of
// milliseconds), and not check's temporaries waiting for the others, nor the folders it made.
TEST(Cli, InterruptedWriteLeavesNoPartialFile) {
  const rc::testing::TempDir temp;
  const std::string exe = rc::testing::rastercheckExe();
  const std::vector<std::vector<std::string>> commands = {
      {exe, "render", "blob:tris=1000", "--backend", "raster", "--size", "1920x1080", "-o", (temp.path() / "blob.exr").string()},
      {exe, "check", "cube", "blob:tris=1000", "-q", "--out", (temp.path() / "new" / "out").string()}};
  for (std::vector<std::string> args : commands) {
    std::vector<char*> argv;
    for (std::string& a : args) argv.push_back(a.data());
    argv.push_back(nullptr);
    posix_spawn_file_actions_t actions;
    posix_spawn_file_actions_init(&actions);
    posix_spawn_file_actions_addopen(&actions, 1, "/dev/null", O_WRONLY, 0);
    posix_spawn_file_actions_addopen(&actions, 2, "/dev/null", O_WRONLY, 0);
    pid_t pid = 0;
    ASSERT_EQ(posix_spawn(&pid, exe.c_str(), &actions, nullptr, argv.data(), environ), 0);
    posix_spawn_file_actions_destroy(&actions);
    // Wait for a temporary to appear, then interrupt.
    bool seen = false;
    int status = 0;
    for (int i = 0; i < 120000 && !seen; ++i) {
      std::error_code ec;
      for (fs::recursive_directory_iterator it(temp.path(), ec), end; !ec && it != end; it.increment(ec)) {
        seen = seen || it->path().filename().string().find(".tmp-") != std::string::npos;
      }
      if (!seen) {
        ASSERT_EQ(waitpid(pid, &status, WNOHANG), 0) << args[1] << " ended before a temporary was seen";
        usleep(1000);
      }
    }
    ASSERT_TRUE(seen) << args[1] << ": no temporary appeared in 120 s";
    ASSERT_EQ(kill(pid, SIGINT), 0);
    ASSERT_EQ(waitpid(pid, &status, 0), pid);
    ASSERT_TRUE(WIFSIGNALED(status)) << args[1] << ": exit status " << status;
    EXPECT_EQ(WTERMSIG(status), SIGINT);
    EXPECT_TRUE(fs::is_empty(temp.path())) << args[1] << " left something in " << temp.path();
  }
}

// "-" sends a text document (--json, --csv) to standard output, whole, and the command's own
// text to stderr, so that stdout parses; "-" for an image output, or for two outputs, is refused.
TEST(Cli, TextOutputsGoToStandardOutputAndTheTableToStderr) {
  const rc::testing::TempDir temp;
  const std::string exe = rc::testing::rastercheckExe();
  const std::string err = (temp.path() / "stderr.txt").string();
  // stdout alone through the pipe; stderr into a file.
  const auto split = [&](const std::string& args) {
    return rc::testing::runCommand("( " + exe + " " + args + " 2>" + err + " )");
  };
  const auto stderrText = [&] {
    std::ifstream in(err);
    return std::string((std::istreambuf_iterator<char>(in)), {});
  };
  const std::string exr = (temp.path() / "cube.exr").string();
  ASSERT_EQ(run("render cube -o " + exr).exitCode, 0);

  const CliRun bench = split("bench cube --runs 1 -q --json -");
  ASSERT_EQ(bench.exitCode, 0) << bench.output;
  const nlohmann::json rows = nlohmann::json::parse(bench.output)["rows"];
  EXPECT_GE(rows.size(), 10u);
  EXPECT_EQ(rows[0]["scene"], "cube");
  EXPECT_NE(stderrText().find("perspective-float-8bit *"), std::string::npos) << "the table goes to stderr";

  const CliRun csv = split("bench cube --runs 1 -q --csv -");
  ASSERT_EQ(csv.exitCode, 0) << csv.output;
  EXPECT_EQ(csv.output.rfind("scene,triangles,", 0), 0u) << csv.output;

  const CliRun compare = split("compare " + exr + " " + exr + " --json -");
  ASSERT_EQ(compare.exitCode, 0) << compare.output;
  EXPECT_EQ(nlohmann::json::parse(compare.output)["verdict"], "pass");
  EXPECT_NE(stderrText().find("reference " + exr), std::string::npos);

  // A failed gate still writes its report; the verdict goes to stderr.
  const CliRun gate = split("check cube -q --mode affine --json -");
  EXPECT_EQ(gate.exitCode, 1) << gate.output;
  EXPECT_EQ(nlohmann::json::parse(gate.output)["verdict"], "fail");
  EXPECT_NE(stderrText().find("GATE FAILED"), std::string::npos);

  // An error leaves stdout empty.
  const CliRun bad = split("check nosuchscene --json -");
  EXPECT_EQ(bad.exitCode, 2);
  EXPECT_EQ(bad.output, "");

  for (const std::string& args : {std::string("bench cube --json - --csv -"), std::string("render cube -o -"), "compare " + exr + " " + exr + " --heatmap -",
                                  "compare " + exr + " " + exr + " --heatmap-png -", std::string("bench cube --chart -")}) {
    const CliRun refused = run(args);
    EXPECT_EQ(refused.exitCode, 2) << args << "\n" << refused.output;
    EXPECT_NE(refused.output.find("standard output"), std::string::npos) << refused.output;
  }
  EXPECT_FALSE(fs::exists("-")) << "a file named '-' was written";
}

// A text output named by a path to what stdout already is (/dev/stdout, or the file's own
// name) is taken as "-": `--json /dev/stdout >> log` appends to the log instead of replacing it,
// and through a pipe the document comes alone. An image output named so is refused.
TEST(Cli, StandardOutputNamedByAPathIsTakenAsDash) {
  const rc::testing::TempDir temp;
  const std::string exe = rc::testing::rastercheckExe();
  const std::string exr = (temp.path() / "cube.exr").string();
  ASSERT_EQ(run("render cube -o " + exr).exitCode, 0);
  const auto text = [](const fs::path& path) { return rc::testing::readFile(path); };

  const fs::path log = temp.path() / "log.txt";
  std::ofstream(log) << "an earlier line\n";
  const CliRun appended =
      rc::testing::runCommand("( " + exe + " compare " + exr + " " + exr + " --json /dev/stdout >> " + log.string() + " )");
  ASSERT_EQ(appended.exitCode, 0) << appended.output;
  const std::string logged = text(log);
  ASSERT_EQ(logged.rfind("an earlier line\n{", 0), 0u) << logged;
  EXPECT_EQ(nlohmann::json::parse(logged.substr(logged.find('{')))["verdict"], "pass");
  EXPECT_NE(appended.output.find("verdict: PASS"), std::string::npos) << "the table goes to stderr";

  // The file's own name, with `>`.
  const fs::path report = temp.path() / "report.json";
  const CliRun named =
      rc::testing::runCommand("( " + exe + " check cube --json " + report.string() + " > " + report.string() + " )");
  ASSERT_EQ(named.exitCode, 0) << named.output;
  EXPECT_EQ(nlohmann::json::parse(text(report))["verdict"], "pass");
  EXPECT_NE(named.output.find("all pass"), std::string::npos) << named.output;

  // Through a pipe: the document alone.
  const std::string err = (temp.path() / "stderr.txt").string();
  const CliRun piped = rc::testing::runCommand("( " + exe + " bench cube --runs 1 -q --csv /dev/stdout 2>" + err + " ) | cat");
  ASSERT_EQ(piped.exitCode, 0) << piped.output;
  EXPECT_EQ(piped.output.rfind("scene,triangles,", 0), 0u) << piped.output;
  EXPECT_EQ(piped.output.find("perspective-float-8bit *"), std::string::npos) << piped.output;

  for (const std::string& args : {std::string("bench cube --runs 1 --chart /dev/stdout"),
                                  "compare " + exr + " " + exr + " --heatmap-png /dev/stdout"}) {
    const fs::path into = temp.path() / "into.txt";
    const CliRun refused = rc::testing::runCommand("( " + exe + " " + args + " > " + into.string() + " )");
    EXPECT_EQ(refused.exitCode, 2) << args << "\n" << refused.output;
    EXPECT_NE(refused.output.find("is standard output"), std::string::npos) << refused.output;
    EXPECT_EQ(text(into), "") << args;
  }
}

// An image into a terminal would garble it: refused, as any wrong output is, before anything
// runs. /dev/null, a device too, still takes one.
TEST(Cli, ImageIntoATerminalIsRefused) {
  if (std::system("command -v script > /dev/null 2>&1") != 0) GTEST_SKIP() << "util-linux script is absent: no terminal test";
  if (std::system("script -qec true /dev/null > /dev/null 2>&1") != 0) {
    GTEST_SKIP() << "no pseudo-terminal can be created here (/dev/pts): the terminal was not tested";
  }
  const rc::testing::TempDir temp;
  const std::string exe = rc::testing::rastercheckExe();
  const std::string exr = (temp.path() / "cube.exr").string();
  ASSERT_EQ(run("render cube -o " + exr).exitCode, 0);
  for (const std::string& args : {"compare " + exr + " " + exr + " --heatmap-png /dev/stdout",
                                  "compare " + exr + " " + exr + " --heatmap /dev/tty", std::string("render cube -o /dev/tty")}) {
    const std::string tty =
        rc::testing::runCommand("script -qec '" + exe + " " + args + "; echo exit=$?' /dev/null").output;
    EXPECT_NE(tty.find("is a terminal, which an image would only garble; name a file"), std::string::npos) << args << "\n" << tty;
    EXPECT_NE(tty.find("exit=2"), std::string::npos) << args << "\n" << tty;
    EXPECT_EQ(tty.find("\x89PNG"), std::string::npos) << args;
  }
  const CliRun toNull = run("compare " + exr + " " + exr + " --heatmap-png /dev/null");
  EXPECT_EQ(toNull.exitCode, 0) << toNull.output;
}

}  // namespace
