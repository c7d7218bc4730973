// Scene files: meshes by relative path with transforms, camera, image and attributes; every
// mistake refused with its JSON pointer.
#include <gtest/gtest.h>

#include "scenes/loaders/scene_file.h"
#include "scenes/scene_loader.h"
#include "tests/test_files.h"

namespace rc {
namespace {

using testing::TempDir;

const char* kTriangleUvNormal =
    "v 0 0 0\nv 1 0 0\nv 0 1 0\nvt 0 0\nvt 1 0\nvt 0 1\nvn 0 0 1\nf 1/1/1 2/2/1 3/3/1\n";
const char* kTriangleUv = "v 0 0 0\nv 1 0 0\nv 0 1 0\nvt 0 0\nvt 1 0\nvt 0 1\nf 1/1 2/2 3/3\n";

TEST(SceneFile, MeshesTransformsCameraImageAndAttributes) {
  TempDir dir;
  dir.write("meshes/a.obj", kTriangleUvNormal);
  dir.write("meshes/b.obj", kTriangleUvNormal);
  const std::string path = dir.write("scene.json", R"({
    "meshes": [
      {"path": "meshes/a.obj"},
      {"path": "meshes/b.obj", "transform": {"translate": [10, 0, 0], "scale": 2}}
    ],
    "camera": {"eye": [5, 0, 20], "target": [5, 0, 0], "fov_y_degrees": 30, "near": 0.5, "far": 100},
    "image": {"width": 320, "height": 200},
    "attributes": ["uv"]
  })");
  const Scene scene = loadSceneFile(path);
  EXPECT_EQ(scene.mesh.triangleCount(), 2u);
  EXPECT_EQ(scene.mesh.positions[4], glm::vec3(12, 0, 0));  // b's (1,0,0), scaled then moved
  EXPECT_NE(scene.mesh.findAttribute("uv"), nullptr);
  EXPECT_EQ(scene.mesh.findAttribute("normal"), nullptr);  // not asked for
  EXPECT_EQ(scene.camera.width(), 320);
  EXPECT_EQ(scene.camera.spec().fovYDegrees, 30.0);
  EXPECT_EQ(scene.camera.zFar(), 100.0);
}

// A matrix places a mesh as the translate, rotate and scale it stands for (column-major).
TEST(SceneFile, AMatrixPlacesAMeshAsItsTranslateRotateAndScaleDo) {
  TempDir dir;
  dir.write("a.obj", kTriangleUvNormal);
  const Scene byMatrix = loadSceneFile(dir.write("m.json", R"({"meshes": [{"path": "a.obj", "transform":
      {"matrix": [0,2,0,0, -2,0,0,0, 0,0,2,0, 10,0,-1,1]}}]})"));
  const Scene byParts = loadSceneFile(dir.write("p.json", R"({"meshes": [{"path": "a.obj", "transform":
      {"translate": [10, 0, -1], "rotate": {"axis": [0, 0, 1], "degrees": 90}, "scale": 2}}]})"));
  ASSERT_EQ(byMatrix.mesh.positions.size(), 3u);
  EXPECT_EQ(byMatrix.mesh.positions[1], glm::vec3(10, 2, -1));  // (1, 0, 0) doubled, turned to +y, moved
  EXPECT_EQ(byMatrix.mesh.positions[2], glm::vec3(8, 0, -1));
  for (std::size_t i = 0; i < 3; ++i) {
    for (int k = 0; k < 3; ++k) EXPECT_NEAR(byMatrix.mesh.positions[i][k], byParts.mesh.positions[i][k], 1e-6) << i << "," << k;
  }
  EXPECT_EQ(byMatrix.mesh.findAttribute("normal")->values[2], 1.0f);  // +z stays +z, renormalised
}

TEST(SceneFile, AttributesAreThoseEveryMeshCarries) {
  TempDir dir;
  dir.write("a.obj", kTriangleUvNormal);
  dir.write("b.obj", kTriangleUv);
  const Scene scene = loadSceneFile(dir.write("s.json", R"({"meshes": [{"path": "a.obj"}, {"path": "b.obj"}]})"));
  EXPECT_NE(scene.mesh.findAttribute("uv"), nullptr);
  EXPECT_EQ(scene.mesh.findAttribute("normal"), nullptr);
  const std::string asks = dir.write("t.json", R"({"meshes": [{"path": "a.obj"}, {"path": "b.obj"}], "attributes": ["normal"]})");
  testing::expectError([&] { loadSceneFile(asks); }, ExitCode::kBadInput, {"t.json: /attributes/0"}, "normal");
}

TEST(SceneFile, MistakesAreRefusedWithTheirJsonPointer) {
  TempDir dir;
  dir.write("a.obj", kTriangleUv);
  const struct { const char* json; const char* fragment; } cases[] = {
      {R"({"meshes": [{"path": "a.obj"}], "camera": {"fov": 30}})", "/camera/fov"},
      {R"({"meshes": [{"path": "a.obj"}], "colour": 1})", "/colour"},
      {R"({"meshes": [{"path": "a.obj"}], "meshes": []})", "duplicate key"},
      {R"({"meshes": [{"path": "../a.obj"}]})", "/meshes/0/path"},
      {R"({"meshes": [{"path": "/etc/passwd"}]})", "/meshes/0/path"},
      {R"({"meshes": [{"path": "a.txt"}]})", "/meshes/0/path"},
      {R"({"meshes": []})", "/meshes"},
      {R"({"meshes": [{"path": "a.obj"}], "image": {"width": 0}})", "/image/width"},
      {R"({"meshes": [{"path": "a.obj"}], "image": {"width": 100000}})", "/image/width"},
      {R"({"meshes": [{"path": "a.obj"}], "image": {"height": -5}})", "/image/height"},
      {R"({"meshes": [{"path": "a.obj"}], "camera": {"eye": [0, 0, 1e999]}})", "s.json"},
      {R"({"meshes": [{"path": "a.obj"}], "camera": {"eye": [0, 0]}})", "/camera/eye"},
      {R"({"meshes": [{"path": "a.obj"}], "camera": {"fov_y_degrees": 180}})", "camera"},
      {R"({"meshes": [{"path": "a.obj"}], "camera": {"near": 0}})", "camera"},
      {R"({"meshes": [{"path": "a.obj"}], "camera": {"near": 5, "far": 1}})", "camera"},
      {R"({"meshes": [{"path": "a.obj"}], "camera": {"eye": [0, 0, 0], "target": [0, 0, 0]}})", "camera"},
      {R"({"meshes": [{"path": "a.obj", "transform": {"scale": 0}}]})", "/meshes/0/transform/scale"},
      {R"({"meshes": [{"path": "a.obj", "transform": {"matrix": [1,0,0,0, 0,1,0,0, 0,0,1,0, 0,0,0,1], "scale": 2}}]})",
       "/meshes/0/transform: give either matrix or translate/rotate/scale, not both"},
      {R"({"meshes": [{"path": "a.obj", "transform": {"matrix": [1,0,0, 0,1,0, 0,0,1]}}]})",
       "/meshes/0/transform/matrix: must be 16 numbers, column-major"},
      {R"({"meshes": [{"path": "a.obj", "transform": {"matrix": [1,0,0,0, 0,1,0,0, 0,0,1,"x", 0,0,0,1]}}]})",
       "/meshes/0/transform/matrix/11"},
      {R"({"meshes": [{"path": "a.obj", "transform": {"matrix": [1,0,0,0.5, 0,1,0,0, 0,0,1,0, 0,0,0,1]}}]})",
       "/meshes/0/transform/matrix: must be affine: elements 3, 7, 11 and 15 (its last row) must be 0, 0, 0, 1"},
      {R"({"meshes": [{"path": "a.obj", "transform": {"matrix": [1,0,0,0, 0,1,0,0, 0,0,1,0, 0,0,0,2]}}]})",
       "/meshes/0/transform/matrix: must be affine"},
      {R"({"meshes": [{"path": "a.obj", "transform": {"matrix": [1,0,0,0, 2,0,0,0, 0,0,1,0, 0,0,0,1]}}]})",
       "/meshes/0/transform/matrix: is singular: it would flatten the mesh"},
      {R"({"meshes": [{"path": "a.obj"}])", "s.json"},
      {"", "s.json"},
  };
  for (const auto& c : cases) {
    const std::string path = dir.write("s.json", c.json);
    testing::expectError([&] { loadSceneFile(path); }, ExitCode::kBadInput, {"s.json", c.fragment}, c.json);
  }
  const std::string deep = dir.write("s.json", std::string(100, '[') + std::string(100, ']'));
  testing::expectError([&] { loadSceneFile(deep); }, ExitCode::kBadInput, {"nesting"}, "deep nesting");
  const std::string missing = dir.write("m.json", R"({"meshes": [{"path": "gone.obj"}]})");
  testing::expectError([&] { loadSceneFile(missing); }, ExitCode::kIo, {"gone.obj"}, "missing mesh");
}

// The limit counts every mesh of the file: each is loaded with the triangles before it.
TEST(SceneFile, TheTriangleLimitCountsTheMeshesBeforeEachOne) {
  TempDir dir;
  dir.write("tri.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n");
  const std::string path = dir.write("three.json", R"({"meshes": [{"path": "tri.obj"}, {"path": "tri.obj"}, {"path": "tri.obj"}]})");
  EXPECT_EQ(loadSceneFile(path, 3).mesh.triangleCount(), 3u);
  testing::expectError([&] { loadSceneFile(path, 2); }, ExitCode::kBadInput,
                       {"tri.obj:4: this face takes the scene past 2 triangles"}, "limit 2");
  SceneOverrides o;
  o.maxTriangles = 2;
  testing::expectError([&] { loadScene(path, o); }, ExitCode::kBadInput, {"past 2 triangles"}, "through loadScene");
}

TEST(SceneLoader, FilesByExtensionAndOverridesApply) {
  TempDir dir;
  const std::string obj = dir.write("Tri.OBJ", kTriangleUvNormal);
  SceneOverrides o;
  o.width = 100;
  o.height = 50;
  o.eye = glm::dvec3(0, 0, 4);
  o.target = glm::dvec3(0.3, 0.3, 0);
  o.attributes = std::vector<std::string>{"normal"};
  const Scene scene = loadScene(obj, o);
  EXPECT_EQ(scene.camera.width(), 100);
  EXPECT_EQ(scene.camera.spec().eye, glm::dvec3(0, 0, 4));
  EXPECT_EQ(scene.mesh.attributes.size(), 1u);
  o.attributes = std::vector<std::string>{"color"};
  testing::expectError([&] { loadScene(obj, o); }, ExitCode::kUsage, {"color", "uv, normal"}, "unknown attribute");
}

}  // namespace
}  // namespace rc
