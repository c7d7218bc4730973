// glTF loading: the sample file's camera and transforms, GLB, the topologies, sparse accessors,
// and hostile files refused naming their place.
#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <functional>
#include <limits>
#include <vector>

#include <nlohmann/json.hpp>

#include "core/base64.h"
#include "core/error.h"
#include "scenes/loaders/gltf_loader.h"
#include "scenes/scene_loader.h"
#include "tests/scenes/gltf_files.h"
#include "tests/test_files.h"

namespace rc {
namespace {

using namespace testing;  // tests/scenes/gltf_files.h, tests/test_files.h

TEST(GltfLoader, SampleCamerasFileHonoursItsCameraAndNodeTransform) {
  const std::string data = testing::sharedData();
  if (data.empty()) GTEST_SKIP() << "../shared/data is absent: Cameras.gltf not tested";
  const GltfContent content = loadGltf(data + "/gltf/Cameras.gltf");
  ASSERT_EQ(content.cameras.size(), 2u);
  ASSERT_TRUE(content.cameras[0].spec.has_value());
  const CameraSpec& c = *content.cameras[0].spec;
  EXPECT_NEAR(c.eye.x, 0.5, 1e-12);
  EXPECT_NEAR(c.eye.y, 0.5, 1e-12);
  EXPECT_NEAR(c.eye.z, 3.0, 1e-12);
  EXPECT_NEAR(c.target.z, 2.0, 1e-12);  // looking down -Z
  EXPECT_NEAR(c.fovYDegrees, 0.7 * 180.0 / M_PI, 1e-9);
  EXPECT_EQ(c.zNear, 0.01);
  EXPECT_EQ(c.zFar, 100.0);
  EXPECT_EQ(c.width, 600);  // aspectRatio 1
  EXPECT_EQ(c.height, 600);
  EXPECT_FALSE(content.cameras[1].spec.has_value());  // the sample's second camera is orthographic
  EXPECT_NE(content.cameras[1].refusal.find("cameras[1]: is orthographic"), std::string::npos);
  ASSERT_EQ(content.mesh.triangleCount(), 2u);
  // Node 0 rotates by about -45 degrees around x: (0, 1, 0) goes to (0, 0.707, -0.707).
  bool found = false;
  for (const glm::vec3& p : content.mesh.positions) {
    if (std::fabs(p.x) < 1e-6 && std::fabs(p.y - 0.7071) < 2e-3 && std::fabs(p.z + 0.7071) < 2e-3) found = true;
  }
  EXPECT_TRUE(found);
}

TEST(GltfLoader, EmbeddedAndNeighbouringBuffersLoad) {
  TempDir dir;
  EXPECT_EQ(loadGltf(dir.write("embedded.gltf", gltfText(dataUri(triangleBytes())))).mesh.triangleCount(), 1u);
  dir.write("sub/tri.bin", triangleBytes());
  EXPECT_EQ(loadGltf(dir.write("neighbour.gltf", gltfText("sub/tri.bin"))).mesh.triangleCount(), 1u);
}

TEST(GltfLoader, UrisOutsideTheFolderOrWithSchemesOrShellCharactersAreRefused) {
  TempDir dir;
  dir.write("tri.bin", triangleBytes());
  for (const char* uri : {"../tri.bin", "/etc/passwd", "file:///etc/passwd", "http://example.invalid/x.bin",
                          "$(touch pwned).bin", "`id`.bin", "~/x.bin", "sub/../../tri.bin", "..%2Ftri.bin",
                          "C:\\\\x.bin"}) {
    const std::string path = dir.write("bad.gltf", gltfText(uri));
    testing::expectError([&] { loadGltf(path); }, ExitCode::kBadInput, {"bad.gltf", "/buffers/0/uri"}, uri);
  }
  EXPECT_FALSE(std::filesystem::exists(dir.path() / "pwned"));
}

TEST(GltfLoader, OutOfRangeAccessorsIndicesAndCyclesAreRefused) {
  TempDir dir;
  const std::string tooMany = dir.write("count.gltf", gltfText(dataUri(triangleBytes()), "", 4));
  testing::expectError([&] { loadGltf(tooMany); }, ExitCode::kBadInput, {"accessors[0]", "exceeds"}, "count");
  const std::string badIndex = dir.write("index.gltf", gltfText(dataUri(triangleBytes(7))));
  testing::expectError([&] { loadGltf(badIndex); }, ExitCode::kBadInput, {"accessors[1]", "index 7"}, "index");
  const std::string cycle = dir.write(
      "cycle.gltf", gltfText(dataUri(triangleBytes()), "", 3, R"("nodes": [{"mesh": 0, "children": [1]}, {"children": [0]}])"));
  testing::expectError([&] { loadGltf(cycle); }, ExitCode::kBadInput, {"cycle"}, "cycle");
  // A node matrix must be affine (glTF: it decomposes into translation, rotation and scale);
  // the mesh is placed without a division by w.
  const std::string projective = dir.write(
      "projective.gltf", gltfText(dataUri(triangleBytes()), "", 3, R"("nodes": [{"mesh": 0, "matrix": [1,0,0,0, 0,1,0,0.5, 0,0,1,0, 0,0,0,1]}])"));
  testing::expectError([&] { loadGltf(projective); }, ExitCode::kBadInput,
                       {"projective.gltf: nodes[0]: matrix: is not affine: elements 3, 7, 11 and 15 (its last row) must be 0, 0, 0, 1"},
                       "projective");
}

TEST(GltfLoader, CameraOptionChoosesAmongTheFilesCamerasAndAnUnusableOneIsRefusedOnlyWhenUsed) {
  TempDir dir;
  // cameras[0] is orthographic and placed first; cameras[1] ("side") is perspective. Node 3
  // places cameras[1] again, later: the first placement counts.
  const std::string path = dir.write(
      "two.gltf",
      gltfText(dataUri(triangleBytes()),
               R"(, "cameras": [{"name": "flat", "type": "orthographic", "orthographic": {"xmag": 1, "ymag": 1, "znear": 0.1, "zfar": 10}},
                                {"name": "side", "type": "perspective", "perspective": {"yfov": 0.5, "znear": 0.1, "aspectRatio": 2}}])",
               3, R"("nodes": [{"mesh": 0, "children": [1, 2, 3]}, {"camera": 0, "translation": [0, 0, 3]},
                               {"camera": 1, "translation": [0.25, 0.25, 4]}, {"camera": 1, "translation": [9, 9, 9]}])"));
  const GltfContent content = loadGltf(path);
  ASSERT_EQ(content.cameras.size(), 2u);
  EXPECT_FALSE(content.cameras[0].spec.has_value());
  EXPECT_NE(content.cameras[0].refusal.find("cameras[0]: is orthographic"), std::string::npos) << content.cameras[0].refusal;

  // By default the first camera placed: orthographic, so refused, saying what to do instead.
  testing::expectError([&] { loadScene(path); }, ExitCode::kBadInput, {"two.gltf: cameras[0]", "orthographic", "--camera", "--eye"},
                       "first camera");
  SceneOverrides o;
  for (const char* selector : {"1", "side"}) {
    o.camera = selector;
    const Scene scene = loadScene(path, o);
    EXPECT_EQ(scene.camera.spec().eye, glm::dvec3(0.25, 0.25, 4)) << selector;
    EXPECT_EQ(scene.camera.width(), 1200) << selector;
    EXPECT_NE(scene.description.find("cameras[1] \"side\""), std::string::npos) << scene.description;
  }
  for (const char* selector : {"flat", "0"}) {
    o.camera = selector;
    testing::expectError([&] { loadScene(path, o); }, ExitCode::kBadInput, {"cameras[0]", "orthographic"}, selector);
  }
  for (const char* selector : {"2", "Side", "-1"}) {
    o.camera = selector;
    testing::expectError([&] { loadScene(path, o); }, ExitCode::kUsage,
                         {std::string("--camera ") + selector, "two.gltf", "it places 0 \"flat\" (orthographic), 1 \"side\""}, selector);
  }
  // --eye and --target replace the unusable camera's pose: the mesh is framed from there.
  o.camera.clear();
  o.eye = glm::dvec3(0.5, 0.5, 5);
  o.target = glm::dvec3(0.5, 0.5, 0);
  const Scene framed = loadScene(path, o);
  EXPECT_EQ(framed.camera.spec().eye, glm::dvec3(0.5, 0.5, 5));
  EXPECT_EQ(framed.mesh.triangleCount(), 1u);

  // A scene file takes only the meshes: the orthographic camera does not stop it.
  const std::string sceneFile = dir.write("uses.json", R"({"meshes": [{"path": "two.gltf"}]})");
  EXPECT_EQ(loadScene(sceneFile).mesh.triangleCount(), 1u);
  // --camera is for glTF files only.
  SceneOverrides other;
  other.camera = "0";
  testing::expectError([&] { loadScene(sceneFile, other); }, ExitCode::kUsage, {"--camera 0", "uses.json", "not a glTF file"}, "json");
  testing::expectError([&] { loadScene("cube", other); }, ExitCode::kUsage, {"cube", "not a glTF file"}, "builtin");
  // A file that places no camera has none to choose.
  const std::string bare = dir.write("bare.gltf", gltfText(dataUri(triangleBytes())));
  EXPECT_EQ(loadScene(bare).mesh.triangleCount(), 1u);
  testing::expectError([&] { loadScene(bare, other); }, ExitCode::kUsage, {"bare.gltf", "places none"}, "bare");
  // A file may place any number of cameras; a message lists 16 and counts the rest.
  nlohmann::json many = nlohmann::json::parse(gltfText(dataUri(triangleBytes())));
  for (int i = 0; i < 20; ++i) {
    many["cameras"].push_back({{"type", "perspective"}, {"perspective", {{"yfov", 0.5}, {"znear", 0.1}}}});
    many["nodes"].push_back({{"camera", i}, {"translation", {0, 0, 3}}});
    many["scenes"][0]["nodes"].push_back(i + 1);
  }
  many["cameras"][1]["name"] = "a\nb" + std::string(100, 'x');  // shown quoted, on one line, cut at 64 bytes
  other.camera = "20";
  testing::expectError([&] { loadScene(dir.write("many.gltf", many.dump()), other); }, ExitCode::kUsage,
                       {"it places 0, 1 \"a?b" + std::string(61, 'x') + "...\", 2, 3, 4, 5, 6, 7, 8, 9, 10, 11, 12, 13, 14, 15 and 4 more"},
                       "many");
  other.camera = "19";
  EXPECT_EQ(loadScene(dir.path() / "many.gltf", other).camera.spec().eye, glm::dvec3(0, 0, 3));
}

TEST(GltfLoader, GlbLoadsAndBadHeadersAreRefusedWithTheirByteOffset) {
  TempDir dir;
  std::string json = gltfText("");
  json.replace(json.find(R"("uri": "", )"), std::string(R"("uri": "", )").size(), "");
  EXPECT_EQ(loadGltf(dir.write("ok.glb", glb(json, triangleBytes()))).mesh.triangleCount(), 1u);
  std::string wrongMagic = glb(json, triangleBytes());
  wrongMagic[0] = 'X';
  // Without the magic it is not recognised as binary, so it fails as JSON; either way, exit 3.
  testing::expectError([&] { loadGltf(dir.write("magic.glb", wrongMagic)); }, ExitCode::kBadInput, {"magic.glb"}, "magic");
  testing::expectError([&] { loadGltf(dir.write("length.glb", glb(json, triangleBytes(), 9999))); }, ExitCode::kBadInput,
                       {"length.glb: byte 8", "declared length"}, "length");
}

TEST(GltfLoader, SparseAccessorsReplaceTheElementsTheyName) {
  TempDir dir;
  GltfBuilder b;
  const int base = b.view(bytesOf<float>({0, 0, 0, 1, 0, 0, 0, 1, 0, 5, 5, 5}));
  const int indices = b.view(bytesOf<std::uint16_t>({1, 3}));
  const int values = b.view(bytesOf<float>({2, 0, 0, 1, 1, 0}));
  b.accessor(denseVec3(base, 4, 5126, sparse(2, indices, 5123, values)));
  Mesh mesh = loadGltf(dir.write("sparse.gltf", b.text(R"("attributes": {"POSITION": 0}, "mode": 6)"))).mesh;  // a fan of 4
  expectPositions(mesh, {{0, 0, 0}, {2, 0, 0}, {0, 1, 0}, {1, 1, 0}}, "sparse over a buffer view");

  // Without a bufferView the accessor is zeros, which the sparse values then replace.
  GltfBuilder z;
  const int zi = z.view(bytesOf<std::uint8_t>({1, 2}));
  const int zv = z.view(bytesOf<float>({1, 0, 0, 0, 1, 0}));
  z.accessor(R"({"componentType": 5126, "count": 3, "type": "VEC3")" + sparse(2, zi, 5121, zv) + "}");
  mesh = loadGltf(dir.write("zeros.gltf", z.text(R"("attributes": {"POSITION": 0})"))).mesh;
  expectPositions(mesh, {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}}, "sparse over zeros");
  EXPECT_EQ(mesh.triangleCount(), 1u);
}

// Writes `text` as `name` in `dir` and expects loadGltf to refuse it as bad input, with every fragment.
void expectRefusedGltf(TempDir& dir, const std::string& name, const std::string& text, const std::vector<std::string>& fragments) {
  const std::string path = dir.write(name, text);
  testing::expectError([&] { loadGltf(path); }, ExitCode::kBadInput, fragments, name);
}

// Each triangle's vertex indices, as a list of triples.
std::vector<std::array<unsigned, 3>> trianglesOf(const Mesh& mesh) {
  std::vector<std::array<unsigned, 3>> out;
  for (const glm::uvec3& t : mesh.triangles) out.push_back({t.x, t.y, t.z});
  return out;
}

// Twice the signed area of a triangle's projection on the xy plane (> 0: counter-clockwise).
double signedAreaXy(const Mesh& mesh, const glm::uvec3& t) {
  const glm::dvec3 a = mesh.positions[t.x], b = mesh.positions[t.y], c = mesh.positions[t.z];
  return (b.x - a.x) * (c.y - a.y) - (b.y - a.y) * (c.x - a.x);
}

// A primitive of `mode` over `positions` (x, y pairs at z = 0), indexed by `indices` if any.
std::string topologyGltf(int mode, std::initializer_list<float> xy, std::initializer_list<std::uint16_t> indices = {}) {
  GltfBuilder b;
  std::vector<float> xyz;
  for (auto it = xy.begin(); it != xy.end(); it += 2) xyz.insert(xyz.end(), {it[0], it[1], 0.0f});
  std::string bytes(xyz.size() * sizeof(float), '\0');
  std::memcpy(bytes.data(), xyz.data(), bytes.size());
  b.accessor(denseVec3(b.view(bytes), int(xyz.size() / 3)));
  std::string primitive = R"("attributes": {"POSITION": 0}, "mode": )" + std::to_string(mode);
  if (indices.size() > 0) {
    b.accessor(dense(b.view(bytesOf<std::uint16_t>(indices)), int(indices.size()), "SCALAR", 5123));
    primitive += R"(, "indices": 1)";
  }
  return b.text(primitive);
}

// glTF 2.0, 3.7.2.1: strip triangle i is (v_i, v_i+1+i%2, v_i+2-i%2), fan triangle i is
// (v_i+1, v_i+2, v_0). The barycentrics follow a triangle's vertex order, so a renderer that
// assembles them as OpenGL does (strip (v_i+1, v_i, v_i+2) on odd i, fan (v_0, v_i+1, v_i+2))
// writes the same surface with its barycentric channels permuted.
TEST(GltfLoader, StripsAndFansMakeTheSpecificationsTrianglesInItsVertexOrder) {
  TempDir dir;
  using Triangles = std::vector<std::array<unsigned, 3>>;
  // A zigzag strip of four triangles, counter-clockwise seen from +z.
  const Mesh strip = loadGltf(dir.write("strip.gltf", topologyGltf(5, {0, 0, 1, 0, 0, 1, 1, 1, 0, 2, 1, 2}))).mesh;
  EXPECT_EQ(trianglesOf(strip), (Triangles{{0, 1, 2}, {1, 3, 2}, {2, 3, 4}, {3, 5, 4}}));
  for (const glm::uvec3& t : strip.triangles) EXPECT_GT(signedAreaXy(strip, t), 0.0) << "every strip triangle keeps the winding";
  // Indexed, as the Khronos MeshPrimitiveModes sample draws its hexagon: indices 2 3 1 4 6 5.
  const std::initializer_list<float> hexagon = {0, 0, 1, -0.5f, 1, 0.5f, 0, 1, -1, 0.5f, -1, -0.5f, 0, -1};
  const Mesh indexed = loadGltf(dir.write("indexed.gltf", topologyGltf(5, hexagon, {2, 3, 1, 4, 6, 5}))).mesh;
  EXPECT_EQ(trianglesOf(indexed), (Triangles{{2, 3, 1}, {3, 4, 1}, {1, 4, 6}, {4, 5, 6}}));
  for (const glm::uvec3& t : indexed.triangles) EXPECT_GT(signedAreaXy(indexed, t), 0.0);
  // A fan around vertex 0, closed on vertex 1, and the same fan's first triangles without indices.
  const Mesh fan = loadGltf(dir.write("fan.gltf", topologyGltf(6, hexagon, {0, 1, 2, 3, 4, 5, 6, 1}))).mesh;
  EXPECT_EQ(trianglesOf(fan), (Triangles{{1, 2, 0}, {2, 3, 0}, {3, 4, 0}, {4, 5, 0}, {5, 6, 0}, {6, 1, 0}}));
  for (const glm::uvec3& t : fan.triangles) EXPECT_GT(signedAreaXy(fan, t), 0.0);
  const Mesh plain = loadGltf(dir.write("plain.gltf", topologyGltf(6, hexagon))).mesh;
  EXPECT_EQ(trianglesOf(plain), (Triangles{{1, 2, 0}, {2, 3, 0}, {3, 4, 0}, {4, 5, 0}, {5, 6, 0}}));
  // A list without a mode is TRIANGLES.
  const Mesh list = loadGltf(dir.write("list.gltf", topologyGltf(4, hexagon, {0, 1, 2, 0, 2, 3}))).mesh;
  EXPECT_EQ(trianglesOf(list), (Triangles{{0, 1, 2}, {0, 2, 3}}));
}

TEST(GltfLoader, VertexCountsAndModesTheSpecificationForbidsAreRefused) {
  TempDir dir;
  const std::initializer_list<float> square = {0, 0, 1, 0, 1, 1, 0, 1};
  expectRefusedGltf(dir, "four.gltf", topologyGltf(4, square),
                    {"four.gltf: meshes[0].primitives[0]: 4 vertices do not make whole triangles", "multiple of 3"});
  expectRefusedGltf(dir, "seven.gltf", topologyGltf(4, square, {0, 1, 2, 0, 2, 3, 1}), {"meshes[0].primitives[0]", "7 vertices"});
  expectRefusedGltf(dir, "short-strip.gltf", topologyGltf(5, square, {0, 1}),
                    {"meshes[0].primitives[0]: 2 vertices are too few for mode TRIANGLE_STRIP (it takes 3 or more)"});
  expectRefusedGltf(dir, "short-fan.gltf", topologyGltf(6, square, {3, 2}), {"2 vertices are too few for mode TRIANGLE_FAN"});
  expectRefusedGltf(dir, "mode7.gltf", topologyGltf(7, square), {"mode7.gltf: /meshes/0/primitives/0/mode: 7 is not a topology (a whole number from 0 to 6)"});
  expectRefusedGltf(dir, "negative.gltf", topologyGltf(-1, square), {"/primitives/0/mode: -1 is not a topology"});
  // Points and lines carry no surface and are passed over, whatever their count.
  GltfBuilder b;
  b.accessor(denseVec3(b.view(bytesOf<float>({0, 0, 0, 1, 0, 0, 0, 1, 0, 1, 1, 0})), 4));
  const std::string mixed = R"("attributes": {"POSITION": 0}, "mode": 1}, {"attributes": {"POSITION": 0}, "mode": 4, "indices": 1)";
  b.accessor(dense(b.view(bytesOf<std::uint16_t>({0, 1, 2})), 3, "SCALAR", 5123));
  EXPECT_EQ(loadGltf(dir.write("lines.gltf", b.text(mixed))).mesh.triangleCount(), 1u);
  // So is a primitive without POSITION, as the specification says (3.7.2.1); its attributes
  // take no part in which attributes every primitive carries.
  const std::string positionless = R"("attributes": {"NORMAL": 0}, "mode": 4}, {"attributes": {"POSITION": 0}, "mode": 4, "indices": 1)";
  const Mesh drawn = loadGltf(dir.write("positionless.gltf", b.text(positionless))).mesh;
  EXPECT_EQ(drawn.triangleCount(), 1u);
  EXPECT_TRUE(drawn.attributes.empty());
  expectRefusedGltf(dir, "nothing.gltf", b.text(R"("attributes": {"NORMAL": 0}, "mode": 4)"), {"nothing.gltf: no triangle primitives in the scene (points, lines and primitives without POSITION draw none)"});
}

TEST(GltfLoader, BadAccessorsAndAttributesAreRefusedNamingTheirPlace) {
  TempDir dir;
  const std::string triangle = bytesOf<float>({0, 0, 0, 1, 0, 0, 0, 1, 0});
  {  // NORMAL with two elements for three positions
    GltfBuilder b;
    b.accessor(denseVec3(b.view(triangle), 3));
    b.accessor(denseVec3(b.view(bytesOf<float>({0, 0, 1, 0, 0, 1})), 2));
    expectRefusedGltf(dir, "normals.gltf", b.text(R"("attributes": {"POSITION": 0, "NORMAL": 1})"),
                      {"normals.gltf: meshes[0].primitives[0]: NORMAL count differs from POSITION count"});
  }
  {  // an application-specific attribute with four elements for three positions
    GltfBuilder b;
    b.accessor(denseVec3(b.view(triangle), 3));
    b.accessor(dense(b.view(bytesOf<float>({1, 2, 3, 4})), 4, "SCALAR"));
    expectRefusedGltf(dir, "custom.gltf", b.text(R"("attributes": {"POSITION": 0, "_heat": 1})"),
                      {"meshes[0].primitives[0]: _heat count differs from POSITION count"});
  }
  {  // a NaN in an application-specific attribute, and an infinite position
    GltfBuilder b;
    b.accessor(denseVec3(b.view(triangle), 3));
    b.accessor(dense(b.view(bytesOf<float>({1, std::nanf(""), 3})), 3, "SCALAR"));
    expectRefusedGltf(dir, "nan.gltf", b.text(R"("attributes": {"POSITION": 0, "_heat": 1})"),
                      {"nan.gltf: attribute 'heat', vertex 1: value is not finite"});
    GltfBuilder c;
    c.accessor(denseVec3(c.view(bytesOf<float>({0, 0, 0, 1, 0, 0, 0, std::numeric_limits<float>::infinity(), 0})), 3));
    expectRefusedGltf(dir, "inf.gltf", c.text(R"("attributes": {"POSITION": 0})"), {"inf.gltf: vertex 2: position is not finite"});
  }
  {  // POSITION as VEC2
    GltfBuilder b;
    b.accessor(dense(b.view(bytesOf<float>({0, 0, 1, 0, 0, 1})), 3, "VEC2"));
    expectRefusedGltf(dir, "vec2.gltf", b.text(R"("attributes": {"POSITION": 0})"), {"vec2.gltf: accessors[0]: has 2 components, expected 3"});
  }
  {  // float indices
    GltfBuilder b;
    b.accessor(denseVec3(b.view(triangle), 3));
    b.accessor(dense(b.view(bytesOf<float>({0, 1, 2})), 3, "SCALAR", 5126));
    expectRefusedGltf(dir, "float-indices.gltf", b.text(R"("attributes": {"POSITION": 0}, "indices": 1)"),
                      {"float-indices.gltf: accessors[1]: unsupported index component type 5126 (FLOAT)"});
  }
  {  // a stride below the element's size, and one above glTF's 252
    GltfBuilder b;
    b.accessor(denseVec3(b.view(triangle + std::string(12, '\0'), 8), 3));
    expectRefusedGltf(dir, "stride8.gltf", b.text(R"("attributes": {"POSITION": 0})"),
                      {"stride8.gltf: accessors[0]: byteStride 8 is not between the element size 12 and 252"});
    GltfBuilder c;
    c.accessor(denseVec3(c.view(triangle + std::string(3 * 256 - 36, '\0'), 256), 3));
    expectRefusedGltf(dir, "stride256.gltf", c.text(R"("attributes": {"POSITION": 0})"), {"stride256.gltf: /bufferViews/0/byteStride: 256 is not a byteStride (a multiple of 4 from 4 to 252)"});
  }
  {  // an accessor index past the file's accessors, refused at its pointer before tinygltf reads the file
    GltfBuilder b;
    b.accessor(denseVec3(b.view(triangle), 3));
    expectRefusedGltf(dir, "no-accessor.gltf", b.text(R"("attributes": {"POSITION": 0}, "indices": 4)"),
                      {"no-accessor.gltf: /meshes/0/primitives/0/indices: 4 is past the end of /accessors (it holds 1 element)"});
  }
  {  // an attribute, a morph target, a skin or an instance field naming an accessor the file has not
    GltfBuilder b;
    b.accessor(denseVec3(b.view(triangle), 3));
    const nlohmann::json base = nlohmann::json::parse(b.text(R"("attributes": {"POSITION": 0})"));
    const struct {
      std::function<void(nlohmann::json&)> edit;
      std::string message;
    } cases[] = {
        {[](nlohmann::json& d) { d["meshes"][0]["primitives"][0]["attributes"]["NORMAL"] = 7; },
         "/meshes/0/primitives/0/attributes/NORMAL: 7 is past the end of /accessors (it holds 1 element)"},
        {[](nlohmann::json& d) { d["meshes"][0]["primitives"][0]["attributes"]["_heat"] = 2; },
         "/meshes/0/primitives/0/attributes/_heat: 2 is past the end of /accessors"},
        {[](nlohmann::json& d) { d["meshes"][0]["primitives"][0]["targets"] = nlohmann::json::parse(R"([{"POSITION": 3}])"); },
         "/meshes/0/primitives/0/targets/0/POSITION: 3 is past the end of /accessors"},
        {[](nlohmann::json& d) {
           d["skins"] = nlohmann::json::parse(R"([{"joints": [0], "inverseBindMatrices": 5}])");
           d["nodes"][0]["skin"] = 0;
         },
         "/skins/0/inverseBindMatrices: 5 is past the end of /accessors"},
        {[](nlohmann::json& d) {
           d["extensionsUsed"] = {"EXT_mesh_gpu_instancing"};
           d["nodes"][0]["extensions"]["EXT_mesh_gpu_instancing"]["attributes"]["TRANSLATION"] = 6;
         },
         "/nodes/0/extensions/EXT_mesh_gpu_instancing/attributes/TRANSLATION: 6 is past the end of /accessors"},
    };
    for (const auto& c : cases) {
      nlohmann::json doc = base;
      c.edit(doc);
      expectRefusedGltf(dir, "missing.gltf", doc.dump(), {"missing.gltf: ", c.message});
    }
  }
}

// tinygltf reads a negative index as absent: a node's "mesh": -2 drew nothing and "indices": -2
// drew the vertices in order, without a word. Every index rastercheck follows is checked first.
TEST(GltfLoader, AnIndexThatIsNotAWholeNumberFromZeroIsRefusedAtItsPointer) {
  TempDir dir;
  GltfBuilder b;
  b.accessor(denseVec3(b.view(bytesOf<float>({0, 0, 0, 1, 0, 0, 0, 1, 0})), 3));
  const nlohmann::json base = nlohmann::json::parse(b.text(R"("attributes": {"POSITION": 0})"));
  EXPECT_EQ(loadGltf(dir.write("plain.gltf", base.dump())).mesh.triangleCount(), 1u);
  const struct {
    const char* pointer;  // where the value is put
    nlohmann::json value;
    const char* refused;  // the pointer and value the refusal names
  } cases[] = {
      {"/scene", -1, "/scene: -1"},
      {"/scenes/0/nodes/0", 0.5, "/scenes/0/nodes/0: 0.5"},
      {"/nodes/0/mesh", -2, "/nodes/0/mesh: -2"},
      {"/nodes/0/skin", -3, "/nodes/0/skin: -3"},
      {"/nodes/0/camera", "0", "/nodes/0/camera: \"0\""},
      {"/nodes/0/children", nlohmann::json::array({-1}), "/nodes/0/children/0: -1"},
      {"/meshes/0/primitives/0/indices", -2, "/meshes/0/primitives/0/indices: -2"},
      {"/meshes/0/primitives/0/attributes/NORMAL", -5, "/meshes/0/primitives/0/attributes/NORMAL: -5"},
      // a member name spelled as RFC 6901 spells it: "~" as "~0", "/" as "~1"
      {"/meshes/0/primitives/0/attributes/_a~1b~0c", -6, "/meshes/0/primitives/0/attributes/_a~1b~0c: -6"},
      {"/meshes/0/primitives/0/targets", nlohmann::json::array({{{"POSITION", 1.0}}}), "/meshes/0/primitives/0/targets/0/POSITION: 1.0"},
      {"/accessors/0/bufferView", -4, "/accessors/0/bufferView: -4"},
      {"/bufferViews/0/buffer", nullptr, "/bufferViews/0/buffer: null"},
      {"/skins", nlohmann::json::array({{{"joints", {0}}, {"skeleton", {{"index", 0}}}}}), "/skins/0/skeleton: an object"},
  };
  for (const auto& c : cases) {
    nlohmann::json doc = base;
    doc[nlohmann::json::json_pointer(c.pointer)] = c.value;
    expectRefusedGltf(dir, "bad.gltf", doc.dump(), {std::string("bad.gltf: ") + c.refused + " is not an index (a whole number from 0)"});
  }
}

// tinygltf dropped a node's translation of two numbers, a byteOffset of -4 or a normalized of
// "yes" without a word (and read the data as if they were absent), and refused a missing count
// without saying which accessor's. Each field rastercheck reads is checked at its pointer first.
TEST(GltfLoader, AFieldMissingOrMalformedIsRefusedAtItsPointer) {
  TempDir dir;
  GltfBuilder b;
  b.accessor(denseVec3(b.view(bytesOf<float>({0, 0, 0, 1, 0, 0, 0, 1, 0})), 3));
  const nlohmann::json base = nlohmann::json::parse(b.text(R"("attributes": {"POSITION": 0})"));
  nlohmann::json packed = base;  // glTF 1.0's byteStride 0, tightly packed, means what none does
  packed["bufferViews"][0]["byteStride"] = 0;
  EXPECT_EQ(loadGltf(dir.write("packed.gltf", packed.dump())).mesh.triangleCount(), 1u);
  const nlohmann::json erase;  // a case's value: the field is taken out
  const struct {
    const char* pointer;
    nlohmann::json value;
    const char* refused;  // what follows "bad.gltf: "
  } cases[] = {
      {"/asset/version", erase, "/asset/version: is missing; glTF requires a string here"},
      {"/accessors/0/count", erase, "/accessors/0/count: is missing; glTF requires a count (a whole number from 1) here"},
      {"/accessors/0/componentType", erase, "/accessors/0/componentType: is missing; glTF requires a componentType (5120 BYTE,"},
      {"/bufferViews/0/byteLength", erase, "/bufferViews/0/byteLength: is missing; glTF requires a count"},
      {"/meshes/0/primitives/0/attributes", erase, "/meshes/0/primitives/0/attributes: is missing; glTF requires an object here"},
      {"/accessors/0/sparse", {{"count", 1}, {"indices", {{"bufferView", 0}, {"componentType", 5125}}}},
       "/accessors/0/sparse/values: is missing; glTF requires an object here"},
      {"/accessors/0/count", 0, "/accessors/0/count: 0 is not a count (a whole number from 1)"},
      {"/accessors/0/byteOffset", -4, "/accessors/0/byteOffset: -4 is not a whole number from 0"},
      {"/bufferViews/0/byteOffset", 2.5, "/bufferViews/0/byteOffset: 2.5 is not a whole number from 0"},
      {"/bufferViews/0/byteStride", 6, "/bufferViews/0/byteStride: 6 is not a byteStride (a multiple of 4 from 4 to 252)"},
      {"/accessors/0/componentType", 5124, "/accessors/0/componentType: 5124 is not a componentType"},
      {"/accessors/0/type", "VEC5", "/accessors/0/type: \"VEC5\" is not an accessor type (SCALAR, VEC2, VEC3, VEC4, MAT2, MAT3 or MAT4)"},
      {"/accessors/0/normalized", "yes", "/accessors/0/normalized: \"yes\" is not true or false"},
      {"/meshes/0/primitives/0/mode", "4", "/meshes/0/primitives/0/mode: \"4\" is not a topology (a whole number from 0 to 6)"},
      {"/meshes/0/primitives", nlohmann::json::array(), "/meshes/0/primitives: [] is not an array of at least one element"},
      {"/meshes/0/weights", "x", "/meshes/0/weights: \"x\" is not an array of numbers"},
      {"/nodes/0/translation", {1, 2}, "/nodes/0/translation: [1,2] is not an array of 3 numbers"},
      {"/nodes/0/rotation", {0, 0, 0, "1"}, "/nodes/0/rotation: [0,0,0,\"1\"] is not an array of 4 numbers"},
      {"/nodes/0/scale", {1, 1, 1, 1}, "/nodes/0/scale: [1,1,1,1] is not an array of 3 numbers"},
      {"/nodes/0/matrix", std::vector<int>(15, 0), "/nodes/0/matrix: [0,0,0,0,0,0,0,0,0,0,0,0,0,0,0] is not an array of 16 numbers"},
      {"/nodes", {{"a", 1}}, "/nodes: an object is not an array"},
      {"/scenes/0", 0, "/scenes/0: 0 is not an object"},
      {"/scene", 3, "/scene: 3 is past the end of /scenes (it holds 1 element)"},
      {"/nodes/0/camera", 0, "/nodes/0/camera: 0 is past the end of /cameras (it holds 0 elements)"},
      {"/accessors/0/bufferView", 1, "/accessors/0/bufferView: 1 is past the end of /bufferViews (it holds 1 element)"},
      // read as no extension at all: a file that needs Draco loaded, its compressed accessors read as zeros
      {"/extensionsRequired", "KHR_draco_mesh_compression", "/extensionsRequired: \"KHR_draco_mesh_compression\" is not an array"},
      {"/extensionsUsed", {"KHR_mesh_quantization", 5}, "/extensionsUsed/1: 5 is not a string"},
  };
  for (const auto& c : cases) {
    nlohmann::json doc = base;
    const nlohmann::json::json_pointer pointer(c.pointer);
    if (c.value.is_null()) {
      doc[pointer.parent_pointer()].erase(pointer.back());
    } else {
      doc[pointer] = c.value;
    }
    expectRefusedGltf(dir, "bad.gltf", doc.dump(), {std::string("bad.gltf: ") + c.refused});
  }
}

// Without `scenes`, every node that is nobody's child is drawn: a library of meshes still loads.
TEST(GltfLoader, AFileWithoutScenesDrawsItsRootNodes) {
  TempDir dir;
  GltfBuilder b;
  b.accessor(denseVec3(b.view(bytesOf<float>({0, 0, 0, 1, 0, 0, 0, 1, 0})), 3));
  nlohmann::json doc = nlohmann::json::parse(b.text(R"("attributes": {"POSITION": 0})"));
  doc.erase("scene");
  doc.erase("scenes");
  // Node 0 (the mesh, at x + 10) is node 1's child; node 2 draws it again at z - 5.
  doc["nodes"] = nlohmann::json::parse(R"([{"mesh": 0, "translation": [10, 0, 0]}, {"children": [0]}, {"mesh": 0, "translation": [0, 0, -5]}])");
  const Mesh mesh = loadGltf(dir.write("library.gltf", doc.dump())).mesh;
  ASSERT_EQ(mesh.triangleCount(), 2u);
  expectPositions(mesh, {{10, 0, 0}, {11, 0, 0}, {10, 1, 0}, {0, 0, -5}, {1, 0, -5}, {0, 1, -5}}, "roots 1 and 2, in node order");
}

TEST(GltfLoader, BadSparseStorageIsRefusedNamingItsPlace) {
  TempDir dir;
  struct Case { std::vector<std::uint32_t> indices; int count; int indexType; std::vector<std::string> fragments; };
  const Case cases[] = {
      {{2, 1}, 2, 5125, {"bad.gltf: accessors[0].sparse.indices", "element 1 (1) does not increase strictly"}},
      {{1, 1}, 2, 5125, {"accessors[0].sparse.indices", "does not increase strictly"}},
      {{0, 3}, 2, 5125, {"accessors[0].sparse.indices", "index 3 at element 1", "count 3"}},
      {{0, 1}, 0, 5125, {"accessors[0].sparse", "count 0 is not between 1 and the accessor's count 3"}},
      {{0, 1}, 4, 5125, {"accessors[0].sparse", "count 4"}},
      {{0, 1}, 2, 5126, {"accessors[0].sparse.indices", "component type 5126"}},
      {{0, 1, 2}, 3, 5125, {"accessors[0].sparse.values", "range of 3 elements exceeds"}},
  };
  for (const Case& c : cases) {
    GltfBuilder b;
    const int base = b.view(bytesOf<float>({0, 0, 0, 1, 0, 0, 0, 1, 0}));
    std::string indexBytes;
    for (std::uint32_t i : c.indices) indexBytes += bytesOf<std::uint32_t>({i});
    const int indices = b.view(indexBytes);
    const int values = b.view(bytesOf<float>({1, 1, 1, 2, 2, 2}));  // two elements
    b.accessor(denseVec3(base, 3, 5126, sparse(c.count, indices, c.indexType, values)));
    const std::string path = dir.write("bad.gltf", b.text(R"("attributes": {"POSITION": 0})"));
    testing::expectError([&] { loadGltf(path); }, ExitCode::kBadInput, c.fragments, c.fragments.back());
  }
  // A huge count of zeros needs no bytes in the file, so it is bounded on its own; a huge count
  // over a small buffer view is refused before anything is allocated.
  GltfBuilder huge;
  huge.view(bytesOf<float>({0}));  // tinygltf refuses an empty buffer
  huge.accessor(R"({"componentType": 5126, "count": 16777217, "type": "VEC3"})");
  testing::expectError([&] { loadGltf(dir.write("huge.gltf", huge.text(R"("attributes": {"POSITION": 0})"))); },
                       ExitCode::kBadInput, {"accessors[0]", "count 16777217 of elements without a bufferView is over 16777216"},
                       "huge zeros");
  huge.accessors[0] = R"({"bufferView": 0, "componentType": 5126, "count": 4000000000, "type": "VEC3"})";
  testing::expectError([&] { loadGltf(dir.write("huge.gltf", huge.text(R"("attributes": {"POSITION": 0})"))); },
                       ExitCode::kBadInput, {"accessors[0]", "range of 4000000000 elements exceeds"}, "huge over a view");
}

}  // namespace
}  // namespace rc
