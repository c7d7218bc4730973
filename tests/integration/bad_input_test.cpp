// Hostile and broken input, tried through the CLI as a user or an attacker would: each case
// must give its documented exit code, a stderr message naming the file and the place, and
// leave no output file behind (docs/security.md lists the cases and limits). Broken EXR files
// are in bad_exr_input_test.cpp.
#include <gtest/gtest.h>

#include <ImfChannelList.h>
#include <ImfFrameBuffer.h>
#include <ImfHeader.h>
#include <ImfOutputFile.h>

#include <unistd.h>

#include <filesystem>
#include <iterator>
#include <string>
#include <vector>

#include "tests/integration/bad_input.h"
#include "tests/run_command.h"
#include "tests/test_files.h"

namespace {

using namespace rc::testing::bad_input;

// Runs `check INPUT` with every output aimed into OUT, and checks code, message and no output.
void expectRefusedCheck(const TempDir& dir, const std::string& input, int code, const std::string& fragment,
                        const std::string& extra = "") {
  const fs::path out = dir.path() / "out";
  fs::remove_all(out);
  const Outcome r = rastercheck("check " + input + " " + extra + " -q --out " + out.string() + " --report " +
                                (out / "report").string() + " --json " + (out / "r.json").string());
  EXPECT_EQ(r.exitCode, code) << input << "\n" << r.output;
  EXPECT_NE(r.output.find(fragment), std::string::npos) << "'" << fragment << "' not named:\n" << r.output;
  EXPECT_NE(r.output.find("rastercheck: error: "), std::string::npos) << r.output;
  EXPECT_FALSE(fs::exists(out)) << "output left behind, if only the folder: " << input;
}

TEST(BadInput, SceneFiles) {
  TempDir dir;
  dir.write("tri.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n");
  const std::string ok = R"("meshes": [{"path": "tri.obj"}])";
  const struct { const char* name; std::string json; int code; const char* fragment; } cases[] = {
      {"empty.json", "", 3, "empty.json"},
      {"bom.json", "\xEF\xBB\xBF{" + ok + "}", 0, ""},  // a byte-order mark is accepted (nlohmann skips it)
      {"truncated.json", "{" + ok + ", \"camera\": {\"eye\": [0, 0", 3, "truncated.json"},
      {"nested.json", std::string(100000, '[') + std::string(100000, ']'), 3, "nested.json"},
      {"nan.json", "{" + ok + ", \"camera\": {\"near\": NaN}}", 3, "nan.json"},
      {"infinity.json", "{" + ok + ", \"camera\": {\"near\": Infinity}}", 3, "infinity.json"},
      {"huge.json", "{" + ok + ", \"camera\": {\"near\": 1e999}}", 3, "huge.json"},
      {"width.json", "{" + ok + ", \"image\": {\"width\": -3}}", 3, "/image/width"},
      {"zero.json", "{" + ok + ", \"image\": {\"height\": 0}}", 3, "/image/height"},
      {"enormous.json", "{" + ok + ", \"image\": {\"width\": 1000000000}}", 3, "/image/width"},
      {"big63.json", "{" + ok + ", \"image\": {\"width\": 9223372036854775808}}", 3, "/image/width"},
      {"fov0.json", "{" + ok + ", \"camera\": {\"fov_y_degrees\": 0}}", 3, "field of view"},
      {"fov180.json", "{" + ok + ", \"camera\": {\"fov_y_degrees\": 180}}", 3, "field of view"},
      {"near.json", "{" + ok + ", \"camera\": {\"near\": -1}}", 3, "near"},
      {"nearfar.json", "{" + ok + ", \"camera\": {\"near\": 2, \"far\": 1}}", 3, "far"},
      {"eye.json", "{" + ok + ", \"camera\": {\"eye\": [1, 1, 1], \"target\": [1, 1, 1]}}", 3, "same point"},
      {"up.json", "{" + ok + ", \"camera\": {\"up\": [0, 0, 0]}}", 3, "up vector"},
      {"duplicate.json", "{" + ok + ", " + ok + "}", 3, "duplicate key"},
      {"unknown.json", "{" + ok + ", \"lights\": []}", 3, "/lights"},
      {"escape.json", R"({"meshes": [{"path": "../../etc/passwd.obj"}]})", 3, "/meshes/0/path"},
      {"absolute.json", R"({"meshes": [{"path": "/etc/passwd.obj"}]})", 3, "/meshes/0/path"},
      {"missing.json", R"({"meshes": [{"path": "gone.obj"}]})", 4, "gone.obj"},
      {"directory.json", R"({"meshes": [{"path": "sub.obj"}]})", 4, "sub.obj"},
  };
  fs::create_directories(dir.path() / "sub.obj");
  for (const auto& c : cases) {
    const std::string path = dir.write(c.name, c.json);
    if (c.code == 0) {
      EXPECT_EQ(rastercheck("check -q " + path).exitCode, 0) << c.name;
      continue;
    }
    expectRefusedCheck(dir, path, c.code, c.fragment);
  }
  // A link that leaves the folder is refused even though its name looks local.
  fs::create_symlink("/etc", dir.path() / "link");
  expectRefusedCheck(dir, dir.write("link.json", R"({"meshes": [{"path": "link/passwd.obj"}]})"), 3, "outside");
}

TEST(BadInput, ObjFiles) {
  TempDir dir;
  const std::string v = "v 0 0 0\nv 1 0 0\nv 0 1 0\n";
  const struct { const char* name; std::string text; const char* fragment; } cases[] = {
      {"index0.obj", v + "f 0 1 2\n", "index0.obj:4: '0' is a face corner with an index of 0"},
      {"range.obj", v + "f 1 2 4\n", "range.obj:4"},
      {"negative.obj", v + "f -99 1 2\n", "negative.obj"},
      {"two.obj", v + "f 1 2\n", "two.obj"},
      {"mixed.obj", v + "vt 0 0\nf 1/1 2/1 3/1\nf 1 2 3\n", "mixed.obj:6"},
      {"word.obj", v + "v one 0 0\nf 1 2 3\n", "word.obj:4"},
      {"nan.obj", v + "v nan 0 0\nf 1 2 4\n", "nan.obj:4"},
      {"inf.obj", v + "v 0 inf 0\nf 1 2 4\n", "inf.obj:4"},
      {"big.obj", v + "v 0 0 1e39\nf 1 2 4\n", "big.obj:4"},
      {"longline.obj", "v " + std::string(10'000'000, '7') + " 0 0\n" + v + "f 2 3 4\n", "longline.obj:1"},
      {"nofaces.obj", v, "nofaces.obj"},
  };
  for (const auto& c : cases) expectRefusedCheck(dir, dir.write(c.name, c.text), 3, c.fragment);
  // --max-triangles is applied while the file loads (it was applied to the loaded scene).
  const Outcome limit = rastercheck("scenes " + dir.write("quad.obj", "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nf 1 2 3 4\n") +
                                    " --max-triangles 1");
  EXPECT_EQ(limit.exitCode, 3) << limit.output;
  EXPECT_NE(limit.output.find("quad.obj:5: this face takes the scene past 1 triangles"), std::string::npos) << limit.output;
  // A built-in scene is made whole, then held to both limits.
  for (const auto& [args, message] : std::vector<std::pair<std::string, std::string>>{
           {"blob:tris=100000 --max-triangles 1000", "blob:tris=100000: 100488 triangles exceed --max-triangles 1000"},
           {"cube --size 600x400 --max-image-side 512", "cube: image 600x400 exceeds --max-image-side 512"}}) {
    const Outcome r = rastercheck("scenes " + args);
    EXPECT_EQ(r.exitCode, 3) << args << "\n" << r.output;
    EXPECT_NE(r.output.find(message), std::string::npos) << args << "\n" << r.output;
  }
  // CR-only line endings (classic Mac OS) are line endings, as tinyobjloader reads them: the
  // file loads, and a bad value after a lone CR is found on the line the parser reads it from.
  EXPECT_EQ(rastercheck("check -q " + dir.write("cr.obj", "v 0 0 0\rv 1 0 0\rv 0 1 0\rf 1 2 3\r")).exitCode, 0);
  expectRefusedCheck(dir, dir.write("crnan.obj", "v 0 0 0\rv 1 0 0\r# a note\rv 0 nan 0\rf 1 2 3\r"), 3, "crnan.obj:4");
  // A file's bytes quoted in a message are printed with control bytes escaped: an escape
  // sequence in a token never reaches the terminal.
  const Outcome escape = rastercheck("scenes " + dir.write("escape.obj", v + "v 1\x1b[2J 0 0\nf 1 2 4\n"));
  EXPECT_EQ(escape.exitCode, 3) << escape.output;
  EXPECT_NE(escape.output.find("escape.obj:4: '1\\x1b[2J' is not a finite float"), std::string::npos) << escape.output;
  EXPECT_EQ(escape.output.find('\x1b'), std::string::npos) << escape.output;
}

std::string uint32le(std::uint32_t v) { return std::string(reinterpret_cast<const char*>(&v), 4); }

TEST(BadInput, GltfAndGlbFiles) {
  TempDir dir;
  const std::string buffer =
      "data:application/octet-stream;base64,AAAAAAAAAAAAAAAAAACAPwAAAAAAAAAAAAAAAAAAgD8AAAAAAAABAAIAAAA=";
  const auto gltf = [&](const std::string& uri, int count, int lastIndexAccessorCount) {
    return R"({"asset": {"version": "2.0"}, "scenes": [{"nodes": [0]}], "nodes": [{"mesh": 0}],
      "meshes": [{"primitives": [{"attributes": {"POSITION": 0}, "indices": 1}]}],
      "buffers": [{"uri": ")" + uri + R"(", "byteLength": 44}],
      "bufferViews": [{"buffer": 0, "byteLength": 36}, {"buffer": 0, "byteOffset": 36, "byteLength": 6}],
      "accessors": [{"bufferView": 0, "componentType": 5126, "count": )" + std::to_string(count) + R"(, "type": "VEC3"},
                    {"bufferView": 1, "componentType": 5123, "count": )" + std::to_string(lastIndexAccessorCount) +
           R"(, "type": "SCALAR"}]})";
  };
  EXPECT_EQ(rastercheck("check -q " + dir.write("ok.gltf", gltf(buffer, 3, 3))).exitCode, 0);
  expectRefusedCheck(dir, dir.write("accessor.gltf", gltf(buffer, 1000, 3)), 3, "accessors[0]");
  expectRefusedCheck(dir, dir.write("indices.gltf", gltf(buffer, 2, 3)), 3, "accessors[1]");
  for (const char* uri : {"../x.bin", "/etc/passwd", "file:///etc/passwd", "http://127.0.0.1/x.bin",
                          "x$(id).bin", "x`id`.bin", "x;rm.bin"}) {
    expectRefusedCheck(dir, dir.write("uri.gltf", gltf(uri, 3, 3)), 3, "/buffers/0/uri");
  }
  // What a real file may store, refused where it breaks the rules (docs/scene-file.md).
  const auto edited = [&](const std::string& from, const std::string& to) {
    std::string text = gltf(buffer, 3, 3);
    text.replace(text.find(from), from.size(), to);
    return text;
  };
  expectRefusedCheck(dir, dir.write("quantised.gltf", edited(R"("componentType": 5126)", R"("componentType": 5122)")), 3,
                     "accessors[0]: SHORT components are not allowed for POSITION unless the file lists KHR_mesh_quantization");
  expectRefusedCheck(dir,
                     dir.write("sparse.gltf", edited(R"("type": "VEC3"})", R"("type": "VEC3", "sparse": {"count": 4,
                         "indices": {"bufferView": 1, "componentType": 5123}, "values": {"bufferView": 0}}})")),
                     3, "accessors[0].sparse: count 4 is not between 1 and the accessor's count 3");
  expectRefusedCheck(dir, dir.write("draco.gltf", edited(R"("scenes")", R"("extensionsRequired": ["KHR_draco_mesh_compression"], "scenes")")),
                     3, "/extensionsRequired: needs extensions rastercheck does not read: KHR_draco_mesh_compression");
  // The camera in use must be one rastercheck can render through; --camera must name one.
  const std::string cameras = dir.write(
      "cameras.gltf", edited(R"("nodes": [{"mesh": 0}])",
                             R"("nodes": [{"mesh": 0, "children": [1, 2]}, {"camera": 0, "translation": [0, 0, 3]}, {"camera": 1, "translation": [0, 0, 3]}],
                                "cameras": [{"type": "perspective", "perspective": {"yfov": 0.7, "znear": 0.1}},
                                            {"name": "top", "type": "orthographic", "orthographic": {"xmag": 1, "ymag": 1, "znear": 0.1, "zfar": 9}}])"));
  EXPECT_EQ(rastercheck("check -q " + cameras + " --camera 0").exitCode, 0);
  expectRefusedCheck(dir, cameras, 3, "cameras.gltf: cameras[1]: is orthographic", "--camera top");
  expectRefusedCheck(dir, cameras, 2, "--camera 2: " + cameras + " places no such camera; it places 0, 1 \"top\" (orthographic)", "--camera 2");
  std::string json = gltf("x.bin", 3, 3);
  while (json.size() % 4) json += ' ';
  const std::string glbBody = uint32le(std::uint32_t(json.size())) + "JSON" + json;
  const std::string header = "glTF" + uint32le(2);
  expectRefusedCheck(dir, dir.write("length.glb", header + uint32le(7) + glbBody), 3, "length.glb: byte 8");
  expectRefusedCheck(dir, dir.write("version.glb", "glTF" + uint32le(1) + uint32le(std::uint32_t(12 + glbBody.size())) + glbBody),
                     3, "version.glb: byte 4");
  expectRefusedCheck(dir, dir.write("chunk.glb", header + uint32le(24) + uint32le(0xFFFFFFFFu) + "JSON{}  "), 3,
                     "chunk.glb: byte 12");
  expectRefusedCheck(dir, dir.write("magic.glb", "glTX" + uint32le(2) + uint32le(std::uint32_t(12 + glbBody.size())) + glbBody),
                     3, "magic.glb");
}

TEST(BadInput, OutputPaths) {
  TempDir dir;
  const std::string exr = dir.file("cube.exr");
  ASSERT_EQ(rastercheck("render cube -o " + exr).exitCode, 0);
  const Outcome missing = rastercheck("compare " + exr + " " + exr + " --json " + dir.file("no/such/folder/r.json"));
  EXPECT_EQ(missing.exitCode, 4) << missing.output;
  EXPECT_NE(missing.output.find("no/such/folder"), std::string::npos);
  // /proc refuses new files even to root: a read-only folder that CI (as root) cannot bypass.
  const Outcome readOnly = rastercheck("render cube -o /proc/rastercheck.exr");
  EXPECT_EQ(readOnly.exitCode, 4) << readOnly.output;
  EXPECT_NE(readOnly.output.find("/proc/rastercheck.exr"), std::string::npos);
  const Outcome readOnlyDir = rastercheck("check cube -q --out /proc/rastercheck-out");
  EXPECT_EQ(readOnlyDir.exitCode, 4) << readOnlyDir.output;
  const std::uintmax_t size = fs::file_size(exr);
  const Outcome same = rastercheck("compare " + exr + " " + exr + " --json " + exr);
  EXPECT_EQ(same.exitCode, 2) << same.output;
  EXPECT_EQ(fs::file_size(exr), size) << "the input was overwritten";
  const Outcome folder = rastercheck("render cube -o " + dir.path().string());
  EXPECT_EQ(folder.exitCode, 4) << folder.output;
  // A name that says another format than the one written (an EXR in out.png) is a usage error;
  // a name without an extension takes what is written.
  for (const std::string& args : {"render cube -o " + dir.file("out.png"),
                                  "compare " + exr + " " + exr + " --heatmap " + dir.file("h.png"),
                                  "compare " + exr + " " + exr + " --heatmap-png " + dir.file("h.exr")}) {
    const Outcome wrong = rastercheck(args);
    EXPECT_EQ(wrong.exitCode, 2) << args << "\n" << wrong.output;
    EXPECT_NE(wrong.output.find("the file is written as"), std::string::npos) << wrong.output;
  }
  // OpenEXR seeks in its file: an EXR into a pipe is refused before the work (it failed after
  // writing a part into the reader), where a PNG or JSON goes through.
  const std::string fifo = dir.file("fifo");
  ASSERT_EQ(mkfifo(fifo.c_str(), 0600), 0);
  for (const std::string& args : {"render cube -o " + fifo, "compare " + exr + " " + exr + " --heatmap " + fifo}) {
    const Outcome pipe = rastercheck(args, "timeout 60");  // a write would wait for a reader
    EXPECT_EQ(pipe.exitCode, 2) << args << "\n" << pipe.output;
    EXPECT_NE(pipe.output.find("an EXR cannot go into a pipe"), std::string::npos) << pipe.output;
  }
  EXPECT_FALSE(fs::exists(dir.file("out.png")));
  EXPECT_FALSE(fs::exists(dir.file("h.png")));
  EXPECT_FALSE(fs::exists(dir.file("h.exr")));
  EXPECT_EQ(rastercheck("render cube -o " + dir.file("result") + " && " + rc::testing::rastercheckExe() + " render cube -o " +
                        dir.file("upper.EXR")).exitCode, 0);
}

// A full disk: the write fails, the command exits 4 naming the file and the cause, and nothing
// is left on the disk (the temporary is removed, and the folder --out made with it). The disk
// is a 1 MB tmpfs in a mount namespace of the command's own (unshare, from util-linux), so
// nothing stays mounted. Where a tmpfs cannot be mounted (no CAP_SYS_ADMIN, or a chroot whose
// root is no mount point) a file size limit fails the writes the same way, with EFBIG
// (SIGXFSZ ignored, so that the write returns the error instead of killing the process).
TEST(BadInput, AFullDiskLeavesNothingBehind) {
  TempDir dir;
  const std::string disk = dir.file("disk");
  fs::create_directories(disk);
  const std::string mount = "unshare --mount sh -c 'mount -t tmpfs -o size=1m tmpfs " + disk;
  const bool tmpfs = rc::testing::runCommand(mount + "'").exitCode == 0;
  const std::string shell = tmpfs ? mount + " && " : "sh -c 'trap \"\" XFSZ; ulimit -f 1024; ";
  const std::string cause = tmpfs ? "No space left on device" : "File too large";
  for (const std::string& args : {"check blob -q --out " + disk + "/out", "render blob -o " + disk + "/blob.exr",
                                  "check blob -q --report " + disk + "/report"}) {
    const Outcome full = rc::testing::runCommand(shell + rc::testing::rastercheckExe() + " " + args +
                                                 "; echo exit=$?; echo left:; ls -A " + disk + "'");
    EXPECT_NE(full.output.find("exit=4\nleft:\n"), std::string::npos) << args << "\n" << full.output;
    EXPECT_EQ(full.output.substr(full.output.find("left:\n") + 6), "") << args << ": left on the disk";
    EXPECT_NE(full.output.find(cause), std::string::npos) << args << "\n" << full.output;
  }
}

// An image too large for the memory there is: the message names it and what it holds, and the
// exit code is 4, a resource like a full disk (until session 52: "invalid EXR: std::bad_alloc",
// exit 3, for a valid file). The image is 8000x8000 pixels in 6 FLOAT channels (1.5 GB) of one
// row written again and again, 24 MB with RLE; the command runs in 1 GB of address space
// (ulimit -v), in which it compares two small images.
TEST(BadInput, AnImageTooLargeForTheMemoryIsNamed) {
  TempDir dir;
  const std::string small = dir.file("small.exr"), big = dir.file("big.exr");
  ASSERT_EQ(rc::testing::runCommand(rc::testing::rastercheckExe() + " render cube -o " + small).exitCode, 0);
  const std::string limited = "sh -c 'ulimit -v 1000000; " + rc::testing::rastercheckExe() + " compare ";
  const Outcome fits = rc::testing::runCommand(limited + small + " " + small + "'");
  if (fits.exitCode != 0) {
    GTEST_SKIP() << "two small images do not compare in 1 GB of address space here (a sanitizer reserves more): "
                 << fits.output;
  }
  constexpr int kSide = 8000;
  Imf::Header header(kSide, kSide);
  header.compression() = Imf::RLE_COMPRESSION;
  std::vector<float> row(kSide, 0.25f);
  Imf::FrameBuffer slices;
  for (const char* name : {"bary.b0", "bary.b1", "bary.b2", "depth.z", "edge.dist", "bound.bary"}) {
    header.channels().insert(name, Imf::Channel(Imf::FLOAT));
    slices.insert(name, Imf::Slice(Imf::FLOAT, reinterpret_cast<char*>(row.data()), 4, 0));
  }
  {
    Imf::OutputFile file(big.c_str(), header);
    file.setFrameBuffer(slices);
    file.writePixels(kSide);
  }
  const Outcome r = rc::testing::runCommand(limited + big + " " + small + "'");
  EXPECT_EQ(r.exitCode, 4) << r.output;
  EXPECT_NE(r.output.find(big + ": out of memory reading 8000x8000 pixels in 6 channels (1536000000 bytes)"),
            std::string::npos)
      << r.output;
}

// A file its owner made read-only stays as it is: outputs are written by renaming a temporary
// over the target, which replaces the file whatever its mode, so the write is refused first.
// A folder the user may not write is refused before the work. Root may write anything: as
// root, the commands run as nobody (setpriv, from util-linux).
TEST(BadInput, ReadOnlyOutputsAreRefusedFirst) {
  TempDir dir;
  fs::permissions(dir.path(), fs::perms::all);  // the folder is writable by all: only the file is protected
  const std::string target = dir.write("old.exr", "keep");
  fs::permissions(target, fs::perms::owner_read | fs::perms::group_read | fs::perms::others_read);
  const std::string as = geteuid() == 0 ? "setpriv --reuid 65534 --regid 65534 --clear-groups " : "";
  if (!as.empty() && rc::testing::runCommand(as + rc::testing::rastercheckExe() + " --version").exitCode != 0) {
    GTEST_SKIP() << "root here cannot run the binary as nobody (no setpriv, no CAP_SETUID, or a private build folder)";
  }
  const Outcome render = rc::testing::runCommand(as + rc::testing::rastercheckExe() + " render cube -o " + target);
  EXPECT_EQ(render.exitCode, 4) << render.output;
  EXPECT_NE(render.output.find(target + ": cannot write"), std::string::npos) << render.output;
  const Outcome check = rc::testing::runCommand(as + rc::testing::rastercheckExe() + " check cube -q --json " + target);
  EXPECT_EQ(check.exitCode, 4) << check.output;
  EXPECT_EQ(readAll(target), "keep");
  // The same user writes a new file there: the refusal is the file's, not the folder's.
  const Outcome fresh = rc::testing::runCommand(as + rc::testing::rastercheckExe() + " render cube -o " + dir.file("new.exr"));
  EXPECT_EQ(fresh.exitCode, 0) << fresh.output;
  // A folder the user may not write (r-x for all) fails before the work: bench would otherwise
  // time every setting first.
  fs::create_directories(dir.path() / "closed");
  fs::permissions(dir.path() / "closed", fs::perms::owner_read | fs::perms::owner_exec | fs::perms::group_read |
                                             fs::perms::group_exec | fs::perms::others_read | fs::perms::others_exec);
  const std::string closed = (dir.path() / "closed" / "b.json").string();
  const Outcome bench = rc::testing::runCommand(as + rc::testing::rastercheckExe() + " bench cube --runs 1 -q --json " + closed);
  EXPECT_EQ(bench.exitCode, 4) << bench.output;
  EXPECT_NE(bench.output.find("cannot write into folder"), std::string::npos) << bench.output;
  EXPECT_EQ(bench.output.find("timed in turn"), std::string::npos) << "fails before timing anything";
  const Outcome out = rc::testing::runCommand(as + rc::testing::rastercheckExe() + " check cube -q --out " +
                                              (dir.path() / "closed").string());
  EXPECT_EQ(out.exitCode, 4) << out.output;
  EXPECT_NE(out.output.find("cannot write into the output folder"), std::string::npos) << out.output;
  EXPECT_EQ(out.output.find("PASS"), std::string::npos) << "fails before rendering";
}

TEST(BadInput, Options) {
  for (const char* args : {"check --frobnicate", "check --max-bary", "check --max-bary -1", "check --max-bary nan",
                           "check --max-bary 1e309", "check --max-bary ''", "check --threads -1",
                           "check --threads 1000000000", "check --size 0x0", "check --size 99999x10",
                           "check --size 10", "check --fov 180", "check --eye 1,2", "check --eye 1,2,nan",
                           "check --max-triangles 0", "check --mode affine --mode", "render cube -o",
                           "check --subpixel-bits 0", "check --embree-isa neon",
                           // a choice's name only, not the number behind it (CLI11 took `--mode 1` as affine)
                           "check --mode 1", "check --precision 0", "check --raster-isa 3", "check --cull 1",
                           "compare a.exr b.exr --heatmap-shows 2", "render cube --backend 1 -o x.exr",
                           "render cube --backend gpu -o x.exr",
                           // --max-attr: LIMIT or NAME=LIMIT, each once
                           "check --max-attr uv", "check --max-attr =1", "check --max-attr uv=", "check --max-attr uv=-1",
                           "check --max-attr uv=nan", "check --max-attr 1,2", "compare a.exr b.exr --max-attr uv=1,uv=2",
                           "check --warn-bary -1", "check --warn-depth nan", "check --warn-attr uv=x",
                           "compare a.exr b.exr --warn-coverage",
                           // --baseline-factor: >= 1, and only with --baseline
                           "check --baseline-factor 3", "check --baseline b.json --baseline-factor 0.99",
                           "check --baseline b.json --baseline-factor inf", "compare a.exr b.exr --baseline"}) {
    const Outcome r = rastercheck(args);
    EXPECT_EQ(r.exitCode, 2) << args << "\n" << r.output;
  }
  // --threads 0 is documented as "all cores", not an error.
  EXPECT_EQ(rastercheck("check cube -q --threads 0").exitCode, 0);
}

// The options that take a list (--attributes, --max-attr and --warn-attr, bench's --settings)
// take one argument each time they are given: the scene after one is a scene. An empty item is
// refused by name; CLI11 skipped it and took the next argument in its place ("--attributes ,
// cube" read cube as an attribute, of the default scenes).
TEST(BadInput, ListOptionsTakeOneArgumentAndNoEmptyItem) {
  for (const char* args : {"check --attributes , cube", "check --attributes uv,,normal sphere", "check --attributes uv, cube",
                           "compare --attributes ,uv a.exr b.exr", "check --max-attr uv=1,,normal=2 sphere",
                           "check --warn-attr , cube", "bench --settings default,, cube --runs 1"}) {
    const Outcome r = rastercheck(args);
    EXPECT_EQ(r.exitCode, 2) << args << "\n" << r.output;
    EXPECT_NE(r.output.find("has an empty item; separate the items with single commas"), std::string::npos)
        << args << "\n" << r.output;
  }
  for (const char* args : {"check --attributes uv cube -q", "check --attributes uv --attributes normal sphere -q",
                           "check --max-attr 1 cube -q", "check --warn-attr uv=1,normal=2 sphere -q"}) {
    const Outcome r = rastercheck(args);
    EXPECT_EQ(r.exitCode, 0) << args << "\n" << r.output;
    EXPECT_NE(r.output.find("1 scene(s): all pass"), std::string::npos) << args << "\n" << r.output;
  }
}

// `--name=` with nothing after '=' (an unset shell variable in `--out=$DIR`) is refused, naming
// it, before anything runs: CLI11 took the next argument as the value, so `check --out= cube`
// checked the default scenes into a folder named cube. After "--" an argument is a scene.
TEST(BadInput, AnOptionWithNothingAfterItsEqualsSignIsRefused) {
  TempDir dir;
  const std::string obj = dir.write("quad.obj", "v 0 0 0\nv 1 0 0\nv 1 1 0\nf 1 2 3\n");
  for (const std::string& args : {"check --out= " + obj, "check --json= " + obj, "check --attributes= " + obj,
                                  "render --output= " + obj, "compare --heatmap= " + obj + " " + obj,
                                  "bench --runs= " + obj}) {
    const Outcome r = rastercheck(args + " -q");
    EXPECT_EQ(r.exitCode, 2) << args << "\n" << r.output;
    const std::string option = args.substr(args.find("--"), args.find('=') + 1 - args.find("--"));
    EXPECT_NE(r.output.find(option + ": nothing follows '='"), std::string::npos) << args << "\n" << r.output;
  }
  EXPECT_EQ(std::distance(fs::directory_iterator(dir.path()), fs::directory_iterator()), 1) << "nothing written";
  EXPECT_EQ(rc::testing::readFile(obj).substr(0, 6), "v 0 0 ") << "the OBJ is as it was";
  const Outcome given = rastercheck("check " + obj + " --eye=0.5,0.5,3 --target=0.5,0.5,0 --json=" + dir.file("r.json") + " -q");
  EXPECT_EQ(given.exitCode, 0) << given.output;
  const Outcome afterDashes = rastercheck("check -q -- --odd=");
  EXPECT_EQ(afterDashes.output.find("nothing follows"), std::string::npos) << afterDashes.output;
  EXPECT_NE(afterDashes.output.find("--odd="), std::string::npos) << "a scene of that name: " << afterDashes.output;
}

// A --baseline that is not a report of the command: refused before anything is rendered or read.
TEST(BadInput, BaselineReports) {
  TempDir dir;
  const std::string compareReport = dir.write("c.json", R"({"format_version": 1, "width": 8, "height": 8,
      "disagreement_fraction": 0, "coverage_fraction": 0, "families": {}})");
  const std::string checkReport = dir.write("k.json", R"({"format_version": 1, "scenes": [{"scene": "cube",
      "triangles": 12, "report": {"format_version": 1, "width": 640, "height": 480, "disagreement_fraction": 0,
      "coverage_fraction": 0, "families": {"bary": {"max": "nan", "p999": -2}}}}]})");
  expectRefusedCheck(dir, "cube --baseline " + compareReport, 3, compareReport + ": is a report of rastercheck compare --json");
  expectRefusedCheck(dir, "cube --baseline " + checkReport, 3, checkReport + ": /scenes/0/report/families/bary/p999: is -2");
  expectRefusedCheck(dir, "cube --baseline " + dir.write("t.json", "{\"format_version\": 1, \"scenes\": [}"), 3,
                     "t.json: invalid JSON");
  expectRefusedCheck(dir, "cube --baseline " + dir.file("absent.json"), 4, "absent.json: cannot read baseline report");

  const std::string json = dir.file("r.json"), heatmap = dir.file("h.exr");
  const Outcome r = rastercheck("compare a.exr b.exr --baseline " + checkReport + " --json " + json + " --heatmap " + heatmap);
  EXPECT_EQ(r.exitCode, 3) << r.output;
  EXPECT_NE(r.output.find(checkReport + ": is a report of rastercheck check --json"), std::string::npos) << r.output;
  EXPECT_FALSE(fs::exists(json) || fs::exists(heatmap));
}

TEST(BadInput, CommaDecimalLocaleChangesNothing) {
  if (std::system("locale -a 2>/dev/null | grep -qi '^de_DE.utf8$'") != 0) {
    GTEST_SKIP() << "the de_DE.UTF-8 locale is not installed (scripts/setup.sh --test generates it)";
  }
  TempDir dir;
  dir.write("s.json", R"({"meshes": [{"path": "t.obj", "transform": {"scale": 0.5}}], "camera": {"eye": [0.25, 0.5, 2.5]}})");
  dir.write("t.obj", "v -1.5 -1.25 0.5\nv 1.5 -1.0 0.25\nv 0.0 1.75 -0.5\nvt 0.5 0.25\nvt 0.75 0.5\nvt 0.125 0.875\nf 1/1 2/2 3/3\n");
  std::string reports[2];
  const char* locales[2] = {"LC_ALL=C", "LC_ALL=de_DE.UTF-8 LANG=de_DE.UTF-8"};
  for (int i = 0; i < 2; ++i) {
    const std::string exr = dir.file("r.exr");  // same names in both runs: reports hold paths
    const Outcome render = rastercheck("render " + dir.file("s.json") + " -o " + exr + " --max-bary 0.5", locales[i]);
    ASSERT_EQ(render.exitCode, 2) << "--max-bary is not a render option: " << render.output;
    ASSERT_EQ(rastercheck("render " + dir.file("s.json") + " -o " + exr, locales[i]).exitCode, 0);
    const Outcome compare = rastercheck("compare " + exr + " " + exr + " --max-bary 0.5 --json " + dir.file("c.json"), locales[i]);
    ASSERT_EQ(compare.exitCode, 0) << compare.output;
    reports[i] = readAll(dir.file("c.json")) + readAll(exr);
    EXPECT_NE(reports[i].find("\"bary\": 0.5"), std::string::npos) << "threshold 0.5 read as " << reports[i].substr(0, 400);
  }
  EXPECT_TRUE(reports[0] == reports[1]) << "the JSON report or the EXR differs between the C and de_DE locales";
}

}  // namespace
