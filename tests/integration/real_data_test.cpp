// Every file in ../shared/data through both paths and the gate, directly and through a scene
// file; the channels written are exactly what each file carries.
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <filesystem>

#include "app/check.h"
#include "scenes/scene_loader.h"
#include "tests/run_command.h"
#include "tests/test_files.h"

namespace rc {
namespace {

namespace fs = std::filesystem;

const char* kFiles[] = {"obj/spot.obj", "obj/stanford-bunny.obj", "obj/teapot.obj", "obj/fandisk.obj",
                        "obj/suzanne.obj", "gltf/Cameras.gltf"};

app::RenderSettings defaults() {
  app::RenderSettings s;
  s.threads = 2;
  app::finishRenderSettings(s);
  return s;
}

class RealFile : public ::testing::TestWithParam<const char*> {};

TEST_P(RealFile, PassesTheGateWithItsDefaultCamera) {
  const std::string data = testing::sharedData();
  if (data.empty()) GTEST_SKIP() << "../shared/data is absent: " << GetParam() << " not tested";
  const Scene scene = loadScene(data + "/" + GetParam());
  const app::CheckResult r = app::checkScene(scene, defaults(), Thresholds{}, false);
  std::string reasons;
  for (const std::string& reason : r.report.reasons) reasons += "\n  " + reason;
  EXPECT_TRUE(r.report.pass) << GetParam() << reasons;
  EXPECT_GT(r.report.classCounts[int(PixelClass::kSameTriangle)], 1000u) << "the default camera sees the mesh";
}

INSTANTIATE_TEST_SUITE_P(SharedData, RealFile, ::testing::ValuesIn(kFiles),
                         [](const ::testing::TestParamInfo<const char*>& p) {
                           std::string name = fs::path(p.param).stem().string();
                           std::erase(name, '-');
                           return name;
                         });

std::vector<std::string> attributeChannels(const Framebuffer& fb) {
  std::vector<std::string> names;
  for (const Channel& c : fb.channels()) {
    if (c.name.rfind("attr.", 0) == 0) names.push_back(c.name);
  }
  return names;
}

TEST(SharedData, ChannelsWrittenAreExactlyWhatEachFileCarries) {
  const std::string data = testing::sharedData();
  if (data.empty()) GTEST_SKIP() << "../shared/data is absent";
  const std::pair<const char*, std::vector<std::string>> expected[] = {
      {"obj/spot.obj", {"attr.uv.x", "attr.uv.y"}},
      {"obj/suzanne.obj", {"attr.normal.x", "attr.normal.y", "attr.normal.z"}},
      {"obj/teapot.obj", {}},
      {"gltf/Cameras.gltf", {}}};
  for (const auto& [file, channels] : expected) {
    const app::CheckResult r = app::checkScene(loadScene(data + "/" + file), defaults(), Thresholds{}, false);
    EXPECT_EQ(attributeChannels(r.raster), channels) << file;
    EXPECT_EQ(attributeChannels(r.reference), channels) << file;
  }
}

TEST(SharedData, AllFilesTogetherThroughASceneFilePassTheGate) {
  const std::string data = testing::sharedData();
  if (data.empty()) GTEST_SKIP() << "../shared/data is absent";
  testing::TempDir dir;
  for (const char* file : {"obj/spot.obj", "obj/suzanne.obj", "gltf/Cameras.gltf"}) {
    fs::create_directories(dir.path() / fs::path(file).parent_path());
    fs::copy_file(data + "/" + file, dir.path() / file);
  }
  const std::string path = dir.write("scene.json", R"({
    "meshes": [
      {"path": "obj/spot.obj"},
      {"path": "obj/suzanne.obj", "transform": {"translate": [2.5, 0, 0], "rotate": {"axis": [0, 1, 0], "degrees": -30}}},
      {"path": "gltf/Cameras.gltf", "transform": {"translate": [-2, -0.5, 0]}}
    ],
    "camera": {"eye": [0.5, 1.5, 6], "target": [0.5, 0, 0], "fov_y_degrees": 45, "near": 0.1},
    "image": {"width": 640, "height": 360}
  })");
  const Scene scene = loadScene(path);
  EXPECT_TRUE(scene.mesh.attributes.empty()) << "Cameras.gltf carries no attributes, so none survive";
  const app::CheckResult r = app::checkScene(scene, defaults(), Thresholds{}, false);
  EXPECT_TRUE(r.report.pass);
  EXPECT_GT(r.report.classCounts[int(PixelClass::kSameTriangle)], 10000u);
}

// A triangle's corners, each as its position and normal (if any), turned so that the smallest
// corner comes first: the same triangle whichever corner an index codec starts it from.
using Corner = std::array<float, 6>;
using CornerTriangle = std::array<Corner, 3>;

std::vector<CornerTriangle> cornerTriangles(const Mesh& mesh) {
  const Attribute* normal = mesh.findAttribute("normal");
  std::vector<CornerTriangle> out;
  for (const glm::uvec3& t : mesh.triangles) {
    CornerTriangle c;
    for (int k = 0; k < 3; ++k) {
      const glm::vec3& p = mesh.positions[t[k]];
      c[k] = {p.x, p.y, p.z, 0, 0, 0};
      if (normal) std::copy_n(normal->values.begin() + 3 * std::ptrdiff_t(t[k]), 3, c[k].begin() + 3);
    }
    std::rotate(c.begin(), std::min_element(c.begin(), c.end()), c.end());
    out.push_back(c);
  }
  return out;
}

// The largest difference between two triangle lists, corner by corner: positions in [0], normals in [1].
std::array<float, 2> largestDifference(const std::vector<CornerTriangle>& a, const std::vector<CornerTriangle>& b) {
  std::array<float, 2> worst{0, 0};
  for (std::size_t i = 0; i < std::min(a.size(), b.size()); ++i) {
    for (int k = 0; k < 3; ++k) {
      for (int c = 0; c < 6; ++c) worst[c / 3] = std::max(worst[c / 3], std::fabs(a[i][k][c] - b[i][k][c]));
    }
  }
  return worst;
}

// The list in the order of the triangles' positions (corner by corner), for codecs that reorder.
std::vector<CornerTriangle> byPosition(std::vector<CornerTriangle> list) {
  auto positions = [](const CornerTriangle& t) {
    return std::array<float, 9>{t[0][0], t[0][1], t[0][2], t[1][0], t[1][1], t[1][2], t[2][0], t[2][1], t[2][2]};
  };
  std::sort(list.begin(), list.end(), [&](const CornerTriangle& a, const CornerTriangle& b) { return positions(a) < positions(b); });
  return list;
}

// Bounding box corners and the sum of the triangles' areas.
std::array<double, 7> extentAndArea(const std::vector<CornerTriangle>& list) {
  std::array<double, 7> r{1e30, 1e30, 1e30, -1e30, -1e30, -1e30, 0};
  for (const CornerTriangle& t : list) {
    for (const Corner& c : t) {
      for (int a = 0; a < 3; ++a) r[a] = std::min(r[a], double(c[a])), r[3 + a] = std::max(r[3 + a], double(c[a]));
    }
    const glm::dvec3 p0(t[0][0], t[0][1], t[0][2]), p1(t[1][0], t[1][1], t[1][2]), p2(t[2][0], t[2][1], t[2][2]);
    r[6] += 0.5 * glm::length(glm::cross(p1 - p0, p2 - p0));
  }
  return r;
}

// gltfpack (meshoptimizer's glTF packer, a Debian package) writes what web pipelines ship:
// positions and normals quantised (KHR_mesh_quantization) and, with -c or -cc, buffer views
// compressed (EXT_meshopt_compression, with the octahedral filter for normals under -cc).
// Compressed variants must load as exactly the triangles of the quantised one (in the same order
// for -c, in another for -cc, whose octahedral filter re-encodes the normals); quantised ones as
// the float original's within the quantisation.
TEST(SharedData, GltfpackOutputLoadsAsTheSameTrianglesQuantisedOrCompressed) {
  const std::string data = testing::sharedData();
  if (data.empty()) GTEST_SKIP() << "../shared/data is absent";
  if (testing::runCommand("gltfpack -h").output.find("gltfpack") == std::string::npos) {
    GTEST_SKIP() << "gltfpack is absent (scripts/setup.sh --test installs it)";
  }
  testing::TempDir dir;
  for (const char* name : {"suzanne", "spot", "fandisk"}) {
    auto pack = [&](const std::string& options, const std::string& out) {
      const std::string file = dir.file(std::string(name) + out);
      const testing::CommandResult r =
          testing::runCommand("gltfpack -i " + data + "/obj/" + name + ".obj -o " + file + " " + options);
      EXPECT_EQ(r.exitCode, 0) << r.output;
      return cornerTriangles(loadScene(file).mesh);
    };
    const std::vector<CornerTriangle> plain = pack("-noq", ".plain.gltf");
    const std::vector<CornerTriangle> quantised = pack("", ".q.glb");
    const std::vector<CornerTriangle> normalised = pack("-vpn", ".vpn.glb");
    const std::size_t triangles = loadScene(data + "/obj/" + name + ".obj").mesh.triangleCount();
    EXPECT_EQ(plain.size(), triangles) << name;
    ASSERT_EQ(quantised.size(), triangles) << name;
    ASSERT_EQ(normalised.size(), triangles) << name;
    // 14-bit positions over the mesh's extent (the meshes here are at most 2 units across); the
    // packer may order the triangles differently once their vertices are quantised.
    const std::array<double, 7> original = extentAndArea(plain);
    for (const auto* variant : {&quantised, &normalised}) {
      const std::array<double, 7> q = extentAndArea(*variant);
      for (int a = 0; a < 6; ++a) EXPECT_NEAR(q[a], original[a], 2e-4) << name << ", box coordinate " << a;
      EXPECT_NEAR(q[6], original[6], 1e-3 * original[6]) << name << ", area";
    }
    EXPECT_NE(byPosition(plain), byPosition(quantised)) << name << ": the positions were quantised";
    for (const auto& [options, out] : {std::pair{"-c", ".c.glb"}, {"-c", ".c.gltf"}, {"-cf", ".cf.glb"}}) {
      const std::vector<CornerTriangle> packed = pack(options, out);
      ASSERT_EQ(packed.size(), triangles) << name << " " << options;
      EXPECT_EQ(largestDifference(quantised, packed), (std::array<float, 2>{0, 0})) << name << " " << options << out;
    }
    const std::vector<CornerTriangle> packedNormalised = pack("-vpn -c", ".vpnc.glb");
    EXPECT_EQ(largestDifference(normalised, packedNormalised), (std::array<float, 2>{0, 0})) << name;
    const std::vector<CornerTriangle> dense = pack("-cc", ".cc.glb");
    ASSERT_EQ(dense.size(), triangles) << name;
    const std::array<float, 2> d = largestDifference(byPosition(quantised), byPosition(dense));
    EXPECT_EQ(d[0], 0.0f) << name;
    EXPECT_LT(d[1], 0.03f) << name << ": normals through the octahedral filter";
  }
}

}  // namespace
}  // namespace rc
