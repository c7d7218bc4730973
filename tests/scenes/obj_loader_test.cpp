// OBJ loading: face-varying corners, triangulation, and bad files refused with their line.
#include <gtest/gtest.h>
#include <sys/inotify.h>
#include <unistd.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <map>
#include <sstream>

#include "scenes/loaders/obj_loader.h"
#include "tests/test_files.h"

namespace rc {
namespace {

using testing::TempDir;

TEST(ObjLoader, FaceVaryingCornersBecomeSeparateVerticesWithTheirOwnUv) {
  TempDir dir;
  // Two triangles share the edge v2-v3, but each face gives it different texture coordinates.
  const std::string path = dir.write("seam.obj",
                                     "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\n"
                                     "vt 0 0\nvt 1 0\nvt 1 1\nvt 0.5 0.5\nvt 0.25 0.75\n"
                                     "f 1/1 2/2 3/3\nf 1/4 3/5 4/1\n");
  const Mesh mesh = loadObj(path);
  ASSERT_EQ(mesh.triangleCount(), 2u);
  EXPECT_EQ(mesh.vertexCount(), 6u);  // (1,1) (2,2) (3,3) (1,4) (3,5) (4,1)
  const Attribute* uv = mesh.findAttribute("uv");
  ASSERT_NE(uv, nullptr);
  const glm::uvec3 second = mesh.triangles[1];
  EXPECT_EQ(mesh.positions[second.x], mesh.positions[mesh.triangles[0].x]);  // same v, split by vt
  EXPECT_EQ(uv->values[2 * second.x], 0.5f);
  EXPECT_EQ(uv->values[2 * second.y + 1], 0.75f);
  EXPECT_EQ(mesh.findAttribute("normal"), nullptr);
}

// Opens of a file seen by an inotify watch on it since the last call.
class OpenWatch {
 public:
  explicit OpenWatch(const std::string& file) : fd_(inotify_init1(IN_NONBLOCK | IN_CLOEXEC)) {
    ok_ = fd_ >= 0 && inotify_add_watch(fd_, file.c_str(), IN_OPEN) >= 0;
  }
  ~OpenWatch() {
    if (fd_ >= 0) close(fd_);
  }
  bool ok() const { return ok_; }
  int opens() {
    int n = 0;
    alignas(inotify_event) char buffer[4096];
    for (ssize_t got; (got = read(fd_, buffer, sizeof buffer)) > 0;) {
      for (ssize_t at = 0; at < got;) {
        const auto* event = reinterpret_cast<const inotify_event*>(buffer + at);
        n += (event->mask & IN_OPEN) != 0;
        at += ssize_t(sizeof(inotify_event) + event->len);
      }
    }
    return n;
  }

 private:
  int fd_;
  bool ok_ = false;
};

TEST(ObjLoader, MtllibIsNeverOpened) {
  TempDir dir;
  const std::string mtl = dir.write("look.mtl", "newmtl red\nKd 1 0 0\n");
  const std::string path = dir.write("lib.obj", "mtllib look.mtl\nv 0 0 0\nv 1 0 0\nv 0 1 0\nusemtl red\nf 1 2 3\n");
  OpenWatch watch(mtl);
  ASSERT_TRUE(watch.ok()) << "inotify is not available";
  EXPECT_EQ(loadObj(path).triangleCount(), 1u);
  EXPECT_EQ(watch.opens(), 0) << "loading lib.obj opened look.mtl";
  std::ifstream(mtl).get();
  EXPECT_EQ(watch.opens(), 1) << "the watch does not see an open";
}

TEST(ObjLoader, ConvexPolygonsAreFannedAndNormalsRead) {
  TempDir dir;
  const std::string path = dir.write("quad.obj",
                                     "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nvn 0 0 1\n"
                                     "f 1//1 2//1 3//1 4//1\n");
  const Mesh mesh = loadObj(path);
  ASSERT_EQ(mesh.triangleCount(), 2u);
  EXPECT_EQ(mesh.triangles[0], glm::uvec3(0, 1, 2));
  EXPECT_EQ(mesh.triangles[1], glm::uvec3(0, 2, 3));
  ASSERT_NE(mesh.findAttribute("normal"), nullptr);
  EXPECT_EQ(mesh.findAttribute("uv"), nullptr);
}

TEST(ObjLoader, ConcavePolygonsAreTriangulatedInsideThemselves) {
  TempDir dir;
  // An L in the plane y = 1, wound clockwise seen from +y (its normal points down), starting
  // at the reflex corner's neighbour: a fan from the first corner would cover (1, 1, 1)'s notch.
  const std::string path = dir.write("l.obj",
                                     "v 2 1 1\nv 1 1 1\nv 1 1 2\nv 0 1 2\nv 0 1 0\nv 2 1 0\n"
                                     "f 1 2 3 4 5 6\n");
  const Mesh mesh = loadObj(path);
  ASSERT_EQ(mesh.triangleCount(), 4u);
  double area = 0.0;
  for (const glm::uvec3& t : mesh.triangles) {
    const glm::dvec3 a(mesh.positions[t.x]), b(mesh.positions[t.y]), c(mesh.positions[t.z]);
    const glm::dvec3 n = glm::cross(b - a, c - a);
    EXPECT_LE(n.y, 0.0) << "wound as the face is";
    area += 0.5 * glm::length(n);
    const glm::dvec3 centre = (a + b + c) / 3.0;
    EXPECT_FALSE(centre.x > 1.0 && centre.z > 1.0) << "a triangle covers the notch";
  }
  EXPECT_DOUBLE_EQ(area, 3.0);  // the L's area: the triangles neither overlap nor leave it
}

TEST(ObjLoader, NegativeIndicesCountBackFromTheEnd) {
  TempDir dir;
  const Mesh mesh = loadObj(dir.write("neg.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf -3 -2 -1\n"));
  ASSERT_EQ(mesh.triangleCount(), 1u);
  EXPECT_EQ(mesh.positions[mesh.triangles[0].y], glm::vec3(1, 0, 0));
}

TEST(ObjLoader, BadFilesAreRefusedNamingFileAndLine) {
  TempDir dir;
  const std::string v = "v 0 0 0\nv 1 0 0\nv 0 1 0\n";
  const struct { const char* name; std::string text; const char* fragment; } cases[] = {
      {"zero.obj", v + "f 0 1 2\n", "zero.obj:4: '0' is a face corner with an index of 0"},
      {"zerovt.obj", v + "vt 0 0\nf 1/1 2/0 3/1\n", "zerovt.obj:5: '2/0' is a face corner with an index of 0"},
      {"zerovn.obj", v + "vn 0 0 1\nf 1//1 2//1 3//0\n", "zerovn.obj:5: '3//0'"},
      // atoi would read these as 1, 1, 0 and 0: refused, never misread
      {"fraction.obj", v + "f 1.5 2 3\n", "fraction.obj:4: '1.5' is not a face corner"},
      {"wide.obj", v + "f 4294967297 2 3\n", "wide.obj:4: '4294967297' is a face corner with an index beyond the 32-bit range"},
      {"word.obj", v + "f one 2 3\n", "word.obj:4: 'one' is not a face corner"},
      {"signs.obj", v + "f +-1 2 3\n", "signs.obj:4: '+-1' is not a face corner"},
      {"slash.obj", v + "vt 0 0\nf 1/1/ 2/1 3/1\n", "slash.obj:5: '1/1/' is not a face corner"},
      {"slashes.obj", v + "f 1/1/1/1 2 3\n", "slashes.obj:4: '1/1/1/1' is not a face corner"},
      {"range.obj", v + "\n\nf 1 2 9\n", "range.obj:6"},
      {"behind.obj", v + "f -99 1 2\n", "behind.obj:4: '-99' is a face corner whose negative v index counts back past the first v above it"},
      {"two.obj", v + "f 1 2\n", "two.obj:4: face has 2 corners; 3 or more are needed"},
      {"twolater.obj", v + "f 1 2 3\nf 3 1\n", "twolater.obj:5: face has 2 corners"},  // the parser dropped it
      // the parser reads a missing coordinate as 0 and a seventh number not at all
      {"vshort.obj", "v 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n", "vshort.obj:1: v has 2 numbers; it takes 3 (x y z), 4 (x y z w) or 6 (x y z r g b)"},
      {"vlong.obj", "v 0 0 0 1 1 1 1\nv 1 0 0\nv 0 1 0\nf 1 2 3\n", "vlong.obj:1: v has 7 numbers"},
      {"vnshort.obj", v + "vn 0 1\nf 1//1 2//1 3//1\n", "vnshort.obj:4: vn has 2 numbers; it takes 3 (x y z)"},
      {"vtlong.obj", v + "vt 0 0 0 0\nf 1/1 2/1 3/1\n", "vtlong.obj:4: vt has 4 numbers; it takes 1 to 3 (u [v [w]])"},
      {"vtrange.obj", v + "vt 0 0\nf 1/1 2/2 3/1\n", "vtrange.obj:5: texture coordinate (vt) index out of range (the file has 1)"},
      {"vnrange.obj", v + "vn 0 0 1\nf 1//1 2//1 3//2\n", "vnrange.obj:5: normal (vn) index out of range (the file has 1)"},
      // the parser kept -5 with one vt above as -4, which read as "no vt": the uv went without a word
      {"vtback.obj", v + "vt 0 0\nf 1/-5 2/-5 3/-5\n", "vtback.obj:5: '1/-5' is a face corner whose negative vt index counts back past the first vt above it"},
      {"vnback.obj", v + "vn 0 0 1\nf 1//-1 2//-1 3//-2\n", "vnback.obj:5: '3//-2' is a face corner whose negative vn index counts back past the first vn above it"},
      {"vback.obj", v + "f -1 -2 -4\n", "vback.obj:4: '-4' is a face corner whose negative v index counts back past the first v above it"},
      // counted back from the statements above the face, not from the end of the file
      {"vtlater.obj", v + "vt 0 0\nf 1/-1 2/-2 3/-1\nvt 1 1\n", "vtlater.obj:5: '2/-2' is a face corner whose negative vt index"},
      {"mixed.obj", v + "vt 0 0\nf 1/1 2/1 3/1\nf 1 2 3\n", "mixed.obj:6"},
      {"nan.obj", "v nan 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n", "nan.obj:1"},
      {"inf.obj", "v 0 0 0\nv inf 0 0\nv 0 1 0\nf 1 2 3\n", "inf.obj:2"},
      {"huge.obj", "v 0 0 0\nv 1 0 0\nv 0 1e39 0\nf 1 2 3\n", "huge.obj:3"},
      {"vword.obj", "v 0 0 0\nv 1 zero 0\nv 0 1 0\nf 1 2 3\n", "vword.obj:2"},
      {"uvword.obj", v + "vt 0 x\nf 1/1 2/1 3/1\n", "uvword.obj:4"},
      {"empty.obj", "", "empty.obj"},
  };
  for (const auto& c : cases) {
    const std::string path = dir.write(c.name, c.text);
    testing::expectError([&] { loadObj(path); }, ExitCode::kBadInput, {c.fragment}, c.name);
  }
  testing::expectError([&] { loadObj(dir.file("absent.obj")); }, ExitCode::kIo, {"absent.obj: cannot read: no such file"},
                       "missing file");
  // A look-up that fails for another reason says which, not "no such file".
  std::filesystem::create_symlink("loop2.obj", dir.path() / "loop1.obj");
  std::filesystem::create_symlink("loop1.obj", dir.path() / "loop2.obj");
  testing::expectError([&] { loadObj(dir.file("loop1.obj")); }, ExitCode::kIo,
                       {"loop1.obj: cannot read: Too many levels of symbolic links"}, "symbolic link loop");
  // A face of 255 corners is read; one of 256, which tinyobjloader would read as a face of 0
  // corners with its indices shifted into the next face, is refused naming its line.
  std::string ring;
  for (int i = 0; i < 256; ++i) ring += "v " + std::to_string(std::cos(i * 0.0245)) + " " + std::to_string(std::sin(i * 0.0245)) + " 0\n";
  std::string face = "f";
  for (int i = 1; i <= 255; ++i) face += " " + std::to_string(i);
  EXPECT_EQ(loadObj(dir.write("255.obj", ring + face + "\n")).triangleCount(), 253u);
  testing::expectError([&] { loadObj(dir.write("256.obj", ring + face + " 256\nf 1 2 3\n")); }, ExitCode::kBadInput,
                       {"256.obj:257", "face has 256 corners; at most 255 are read"}, "256 corners");
}

// What OBJ lets a statement leave out or add is read as OBJ says: a vertex's w (which only
// rational curves use) and a colour (which rastercheck does not read) are ignored, and a
// texture coordinate's missing v is 0.
TEST(ObjLoader, OptionalNumbersAreReadAsObjDefinesThem) {
  TempDir dir;
  const Mesh mesh = loadObj(dir.write("optional.obj", "v 0 0 0 2\nv 1 0 0 1 0 0\nv 0 1 0\nvt 0.25\nvt 1 0 0\nvt 0 1\nf 1/1 2/2 3/3\n"));
  EXPECT_EQ(std::vector<glm::vec3>(mesh.positions.begin(), mesh.positions.end()),
            (std::vector<glm::vec3>{{0, 0, 0}, {1, 0, 0}, {0, 1, 0}}))
      << "w and colour ignored";
  const Attribute* uv = mesh.findAttribute("uv");
  ASSERT_NE(uv, nullptr);
  EXPECT_EQ(std::vector<float>(uv->values.begin(), uv->values.end()), (std::vector<float>{0.25f, 0, 1, 0, 0, 1}));
}

// Lines end where tinyobjloader ends them: at "\n", "\r\n" or a lone "\r". The checks number
// lines and find statements the same way, so a value the parser would read as 0 cannot hide
// behind a lone CR, and a bad line is named as the parser counts it.
TEST(ObjLoader, LinesEndAtLfCrLfOrALoneCr) {
  TempDir dir;
  const std::string lines[] = {"v 0 0 0", "vt 0 0", "v 2 0 0", "vt 1 0", "# a note", "v 0 1 0", "vt 0 1",
                               "f 1/1 2/2 3/3", "f 3/3 2/2 1/1"};
  std::map<std::string, std::string> texts;
  for (const char* end : {"\n", "\r\n", "\r"}) {
    std::string text;
    for (const std::string& line : lines) text += line + end;
    texts[end] = text;
  }
  const Mesh lf = loadObj(dir.write("lf.obj", texts["\n"]));
  ASSERT_EQ(lf.triangleCount(), 2u);
  for (const char* end : {"\r\n", "\r"}) {
    const Mesh mesh = loadObj(dir.write("other.obj", texts[end]));
    EXPECT_EQ(mesh.triangles, lf.triangles) << int(end[0]) << " " << int(end[1]);
    EXPECT_EQ(mesh.positions, lf.positions);
    ASSERT_EQ(mesh.attributes.size(), 1u);
    EXPECT_EQ(mesh.attributes[0].values, lf.attributes[0].values);
  }
  // Mixed endings, and a value after a lone CR: line 4 as the parser counts ("\r\n" is one end).
  const std::string v = "v 0 0 0\r\nv 1 0 0\n# note\rv 0 nan 0\nf 1 2 3\n";
  testing::expectError([&] { loadObj(dir.write("hidden.obj", v)); }, ExitCode::kBadInput, {"hidden.obj:4: 'nan'"}, "hidden");
  // A face after a lone CR is a face: 256 corners are refused there too.
  std::string ring = "# ring\r";
  for (int i = 0; i < 256; ++i) ring += "v " + std::to_string(std::cos(i * 0.0245)) + " " + std::to_string(std::sin(i * 0.0245)) + " 0\n";
  std::string face = "f";
  for (int i = 1; i <= 256; ++i) face += " " + std::to_string(i);
  testing::expectError([&] { loadObj(dir.write("ring.obj", ring + "# faces\r" + face + "\n")); }, ExitCode::kBadInput,
                       {"ring.obj:259", "256 corners"}, "256 corners after a lone CR");
}

// The triangles a file's faces make (n - 2 for n corners) are counted before it is parsed: a
// few bytes a face would otherwise ask tinyobjloader for some 45 bytes a face, unbounded.
TEST(ObjLoader, TheTriangleLimitIsCheckedBeforeTheFileIsParsed) {
  TempDir dir;
  const std::string path =
      dir.write("limit.obj", "v 0 0 0\nv 2 0 0\nv 2 1 0\nv 1 2 0\nv 0 1 0\nf 1 2 3\n\nf 1 2 3 4 5\n");
  EXPECT_EQ(loadObj(path).triangleCount(), 4u);
  EXPECT_EQ(loadObj(path, {4}).triangleCount(), 4u);
  EXPECT_EQ(loadObj(path, {6, 2}).triangleCount(), 4u);
  testing::expectError([&] { loadObj(path, {3}); }, ExitCode::kBadInput,
                       {"limit.obj:8: this face takes the scene past 3 triangles"}, "limit 3");
  testing::expectError([&] { loadObj(path, {6, 3}); }, ExitCode::kBadInput, {"limit.obj:8"}, "3 triangles before the file's");
}

// Spot's UVs, against an independent reading of the file: every triangle corner carries the
// vt its face statement names, so UVs stay right on both sides of every texture seam.
TEST(ObjLoader, SpotCornersCarryExactlyTheirFaceStatementsUv) {
  const std::string data = testing::sharedData();
  if (data.empty()) GTEST_SKIP() << "../shared/data is absent: spot.obj not tested";
  const std::string path = data + "/obj/spot.obj";
  std::ifstream in(path);
  std::vector<glm::vec3> v;
  std::vector<glm::vec2> vt;
  std::vector<std::pair<int, int>> corners;  // (v, vt), 1-based, in face order
  std::string line;
  while (std::getline(in, line)) {
    std::istringstream s(line);
    std::string tag;
    s >> tag;
    if (tag == "v") {
      glm::vec3 p;
      s >> p.x >> p.y >> p.z;
      v.push_back(p);
    } else if (tag == "vt") {
      glm::vec2 t;
      s >> t.x >> t.y;
      vt.push_back(t);
    } else if (tag == "f") {
      std::string corner;
      while (s >> corner) corners.push_back({std::stoi(corner), std::stoi(corner.substr(corner.find('/') + 1))});
    }
  }
  const Mesh mesh = loadObj(path);
  ASSERT_EQ(mesh.triangleCount() * 3, corners.size());  // spot is all triangles
  const Attribute* uv = mesh.findAttribute("uv");
  ASSERT_NE(uv, nullptr);
  std::map<int, int> vtPerV;
  int seamVertices = 0;
  for (std::size_t i = 0; i < corners.size(); ++i) {
    const unsigned index = mesh.triangles[i / 3][int(i % 3)];
    ASSERT_EQ(mesh.positions[index], v[corners[i].first - 1]) << "corner " << i;
    ASSERT_EQ(uv->values[2 * index], vt[corners[i].second - 1].x) << "corner " << i;
    ASSERT_EQ(uv->values[2 * index + 1], vt[corners[i].second - 1].y) << "corner " << i;
    auto [it, fresh] = vtPerV.emplace(corners[i].first, corners[i].second);
    if (!fresh && it->second != corners[i].second) ++seamVertices;
  }
  EXPECT_GT(seamVertices, 0) << "spot has texture seams: some v appear with several vt";
}

}  // namespace
}  // namespace rc
