// glTF export (rastercheck export): every built-in scene reads back as itself.
#include <gtest/gtest.h>

#include <algorithm>
#include <cstdint>
#include <vector>

#include <nlohmann/json.hpp>

#include "core/error.h"
#include "rasterizer/rasterizer.h"
#include "raytracer_ref/reference.h"
#include "scenes/loaders/gltf_loader.h"
#include "scenes/loaders/gltf_writer.h"
#include "scenes/registry.h"
#include "scenes/scene_loader.h"
#include "tests/same_bits.h"
#include "tests/scenes/gltf_files.h"
#include "tests/test_files.h"

namespace rc {
namespace {

using namespace testing;  // tests/scenes/gltf_files.h, tests/test_files.h

// Every built-in and hard-case scene, written by `rastercheck export` (gltfFromScene) and read
// back: the same mesh and camera, so both renderers give the same bits as for the built-in scene
// (normals may move by the renormalisation every loaded normal gets).
TEST(GltfExport, EveryBuiltinSceneReadsBackAsTheSameSceneAndRendersTheSameBits) {
  TempDir dir;
  std::vector<std::string> specs = hardCaseSpecs();
  for (const std::string& name : defaultSceneNames()) specs.push_back(name == "blob" ? "blob:tris=2000" : name);
  bool binary = false;
  for (const std::string& spec : specs) {
    const Scene scene = makeBuiltinScene(spec);
    binary = !binary;  // both forms, alternately
    const std::string path = dir.write("scene" + std::string(binary ? ".glb" : ".gltf"), gltfFromScene(scene, binary));
    const Scene back = loadScene(path);
    ASSERT_EQ(back.mesh.positions, scene.mesh.positions) << spec;
    ASSERT_EQ(back.mesh.triangles, scene.mesh.triangles) << spec;
    ASSERT_EQ(back.mesh.attributes.size(), scene.mesh.attributes.size()) << spec;
    for (const Attribute& x : scene.mesh.attributes) {
      ASSERT_NE(back.mesh.findAttribute(x.name), nullptr) << spec << " " << x.name;
      const Attribute& y = *back.mesh.findAttribute(x.name);
      ASSERT_EQ(y.components, x.components) << spec << " " << x.name;
      ASSERT_EQ(y.values.size(), x.values.size()) << spec << " " << x.name;
      for (std::size_t i = 0; i < x.values.size(); ++i) {
        if (x.name == "normal") {
          ASSERT_NEAR(y.values[i], x.values[i], 2e-7f) << spec << " normal " << i;
        } else {
          ASSERT_EQ(y.values[i], x.values[i]) << spec << " " << x.name << " " << i;
        }
      }
    }
    const CameraSpec &c = scene.camera.spec(), &d = back.camera.spec();
    EXPECT_EQ(d.eye, c.eye) << spec;
    EXPECT_EQ(d.target, c.target) << spec;
    EXPECT_EQ(d.up, c.up) << spec;
    EXPECT_EQ(d.fovYDegrees, c.fovYDegrees) << spec;
    EXPECT_EQ(d.zNear, c.zNear) << spec;
    EXPECT_EQ(d.zFar, c.zFar) << spec;
    EXPECT_EQ(d.width, c.width) << spec;
    EXPECT_EQ(d.height, c.height) << spec;

    // Where the normals moved, the renders' normal channels may too; every other bit is the same.
    // A closed solid stays one (the file claims it, and the loader checks the claim), so both
    // are drawn with the same back faces culled (culling may move a silhouette pixel's winner).
    Scene same = back;
    same.mesh.attributes = scene.mesh.attributes;
    EXPECT_EQ(back.mesh.closedSolid, scene.mesh.closedSolid) << spec;
    RasterOptions raster;
    raster.threads = 2;
    ReferenceOptions reference;
    reference.threads = 2;
    EXPECT_EQ(testing::differingChannels(rasterize(same, raster), rasterize(scene, raster)), std::vector<std::string>{})
        << spec << ": rasterizer";
    EXPECT_EQ(testing::differingChannels(renderReference(same, reference), renderReference(scene, reference)),
              std::vector<std::string>{})
        << spec << ": reference";
  }
}

TEST(GltfExport, AClosedSolidIsBelievedOnlyWhereTheMeshPassesTheCheck) {
  TempDir dir;
  const Scene cube = makeBuiltinScene("cube");
  ASSERT_TRUE(cube.mesh.closedSolid);
  nlohmann::json doc = nlohmann::json::parse(gltfFromScene(cube, false));
  EXPECT_EQ(doc["meshes"][0]["extras"]["rastercheck_closed_solid"], true);
  EXPECT_TRUE(loadScene(dir.write("cube.gltf", doc.dump())).mesh.closedSolid);
  doc["meshes"][0]["extras"]["rastercheck_closed_solid"] = "yes";  // not the boolean true
  EXPECT_FALSE(loadScene(dir.write("cube-string.gltf", doc.dump())).mesh.closedSolid);
  // The claim on a mesh that does not bound a solid (the floor, an open quad) is not believed.
  const Scene floor = makeBuiltinScene("floor");
  ASSERT_FALSE(floor.mesh.closedSolid);
  doc = nlohmann::json::parse(gltfFromScene(floor, false));
  EXPECT_FALSE(doc["meshes"][0].contains("extras"));
  doc["meshes"][0]["extras"]["rastercheck_closed_solid"] = true;
  EXPECT_FALSE(loadScene(dir.write("floor.gltf", doc.dump())).mesh.closedSolid);
  // Nor on a solid put in twice by a second node: closed and outward, but it wraps its centre twice.
  doc = nlohmann::json::parse(gltfFromScene(cube, false));
  doc["scenes"][0]["nodes"].push_back(2);
  doc["nodes"].push_back({{"mesh", 0}});
  EXPECT_FALSE(loadScene(dir.write("twice.gltf", doc.dump())).mesh.closedSolid);
}

TEST(GltfExport, ACameraEditedAfterExportWinsOverTheExactOneKeptInExtras) {
  TempDir dir;
  const Scene scene = makeBuiltinScene("cube");
  nlohmann::json doc = nlohmann::json::parse(gltfFromScene(scene, false));
  ASSERT_TRUE(doc["cameras"][0]["extras"].contains("rastercheck_camera"));
  // Moved: the node's pose no longer agrees with the extras, so the glTF camera is used, with
  // the image 600 pixels high as for any glTF camera.
  doc["nodes"][1]["matrix"][12] = 3.0;
  const Scene moved = loadScene(dir.write("moved.gltf", doc.dump()));
  EXPECT_EQ(moved.camera.spec().eye.x, 3.0);
  EXPECT_EQ(moved.camera.height(), 600);
  // A wider field of view, likewise.
  doc = nlohmann::json::parse(gltfFromScene(scene, false));
  doc["cameras"][0]["perspective"]["yfov"] = 1.0;
  const Scene wider = loadScene(dir.write("wider.gltf", doc.dump()));
  EXPECT_NEAR(wider.camera.spec().fovYDegrees, 180.0 / M_PI, 1e-12);
  EXPECT_EQ(wider.camera.height(), 600);
  // A camera node whose matrix flattens its view direction is refused when used (it divided by zero).
  doc = nlohmann::json::parse(gltfFromScene(scene, false));
  for (int i = 8; i < 11; ++i) doc["nodes"][1]["matrix"][i] = 0.0;
  testing::expectError([&] { loadScene(dir.write("flat.gltf", doc.dump())); }, ExitCode::kBadInput,
                       {"flat.gltf: nodes[1]", "collapses its view or up direction to zero"}, "flat camera");
  // Untouched, the extras give back the exact camera.
  EXPECT_EQ(loadScene(dir.write("kept.gltf", gltfFromScene(scene, false))).camera.height(), scene.camera.height());
}

}  // namespace
}  // namespace rc
