// Every file in ../shared/data through both paths and the gate, directly and through a scene
// file; the channels written are exactly what each file carries.
#include <gtest/gtest.h>

#include <filesystem>

#include "app/check.h"
#include "scenes/scene_loader.h"
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

}  // namespace
}  // namespace rc
