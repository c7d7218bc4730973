// glTF loading: the sample file's camera and transforms, GLB, and hostile files refused.
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <functional>
#include <limits>
#include <meshoptimizer.h>
#include <nlohmann/json.hpp>
#include <cstdint>
#include <cstring>
#include <vector>

#include "core/base64.h"
#include "core/error.h"
#include "rasterizer/rasterizer.h"
#include "raytracer_ref/reference.h"
#include "scenes/loaders/gltf_loader.h"
#include "scenes/loaders/gltf_writer.h"
#include "scenes/registry.h"
#include "scenes/scene_loader.h"
#include "tests/same_bits.h"
#include "tests/test_files.h"

namespace rc {
namespace {

using testing::TempDir;

// Three float3 positions (36 bytes) followed by three uint16 indices and 2 bytes of padding.
std::string triangleBytes(std::uint16_t lastIndex = 2) {
  const float p[9] = {0, 0, 0, 1, 0, 0, 0, 1, 0};
  const std::uint16_t idx[4] = {0, 1, lastIndex, 0};
  std::string bytes(44, '\0');
  std::memcpy(bytes.data(), p, 36);
  std::memcpy(bytes.data() + 36, idx, 8);
  return bytes;
}

// A one-triangle glTF whose buffer is `uri`; `extra` is spliced into the top-level object.
std::string gltfText(const std::string& uri, const std::string& extra = "", int positionCount = 3,
                     const std::string& nodes = R"("nodes": [{"mesh": 0}])") {
  return R"({"asset": {"version": "2.0"}, "scene": 0, "scenes": [{"nodes": [0]}], )" + nodes +
         R"(, "meshes": [{"primitives": [{"attributes": {"POSITION": 0}, "indices": 1}]}],
  "buffers": [{"uri": ")" + uri + R"(", "byteLength": 44}],
  "bufferViews": [{"buffer": 0, "byteOffset": 0, "byteLength": 36}, {"buffer": 0, "byteOffset": 36, "byteLength": 6}],
  "accessors": [{"bufferView": 0, "componentType": 5126, "count": )" + std::to_string(positionCount) +
         R"(, "type": "VEC3"},
                {"bufferView": 1, "componentType": 5123, "count": 3, "type": "SCALAR"}])" + extra + "}";
}

std::string dataUri(const std::string& bytes) { return "data:application/octet-stream;base64," + base64(bytes); }

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

std::string glb(const std::string& json, const std::string& bin, std::uint32_t declaredLength = 0) {
  std::string j = json;
  while (j.size() % 4) j += ' ';
  std::string b = bin;
  while (b.size() % 4) b += '\0';
  const std::uint32_t total = std::uint32_t(12 + 8 + j.size() + 8 + b.size());
  std::string out(12, '\0');
  const std::uint32_t header[3] = {0x46546C67u, 2, declaredLength ? declaredLength : total};
  std::memcpy(out.data(), header, 12);
  const std::uint32_t jsonHeader[2] = {std::uint32_t(j.size()), 0x4E4F534Au};
  const std::uint32_t binHeader[2] = {std::uint32_t(b.size()), 0x004E4942u};
  out.append(reinterpret_cast<const char*>(jsonHeader), 8).append(j);
  out.append(reinterpret_cast<const char*>(binHeader), 8).append(b);
  return out;
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

// The bytes of `values` as the type T stores them (little-endian, as glTF).
template <typename T>
std::string bytesOf(std::initializer_list<T> values) {
  std::string out;
  for (T v : values) out.append(reinterpret_cast<const char*>(&v), sizeof(T));
  return out;
}

// One buffer (embedded) with a buffer view per chunk, accessors given as JSON objects, and one
// mesh of one primitive on one node.
struct GltfBuilder {
  std::string bin;
  std::vector<std::string> views, accessors;

  int view(std::string bytes, int stride = 0) {
    while (bin.size() % 4) bin += '\0';
    views.push_back(R"({"buffer": 0, "byteOffset": )" + std::to_string(bin.size()) + R"(, "byteLength": )" +
                    std::to_string(bytes.size()) + (stride ? R"(, "byteStride": )" + std::to_string(stride) : "") + "}");
    bin += bytes;
    return int(views.size()) - 1;
  }
  int accessor(const std::string& json) {
    accessors.push_back(json);
    return int(accessors.size()) - 1;
  }
  // `primitive` and `mesh` are spliced into their objects, `top` into the top-level one.
  std::string text(const std::string& primitive, const std::string& mesh = "", const std::string& top = "",
                   const std::string& node = "") const {
    auto join = [](const std::vector<std::string>& items) {
      std::string out;
      for (const std::string& i : items) out += (out.empty() ? "" : ", ") + i;
      return out;
    };
    return R"({"asset": {"version": "2.0"}, "scene": 0, "scenes": [{"nodes": [0]}], "nodes": [{"mesh": 0)" + node +
           R"(}], "meshes": [{"primitives": [{)" + primitive + "}]" + mesh + R"(}], "buffers": [{"uri": ")" +
           dataUri(bin) + R"(", "byteLength": )" + std::to_string(bin.size()) + R"(}], "bufferViews": [)" + join(views) +
           R"(], "accessors": [)" + join(accessors) + "]" + top + "}";
  }
};

// An accessor over a whole buffer view: `count` elements of `type` ("VEC2"...), `more` spliced in.
std::string dense(int view, int count, const char* type, int componentType = 5126, const std::string& more = "") {
  return R"({"bufferView": )" + std::to_string(view) + R"(, "componentType": )" + std::to_string(componentType) +
         R"(, "count": )" + std::to_string(count) + R"(, "type": ")" + type + "\"" + more + "}";
}

std::string denseVec3(int view, int count, int componentType = 5126, const std::string& more = "") {
  return dense(view, count, "VEC3", componentType, more);
}

std::string sparse(int count, int indicesView, int indexType, int valuesView) {
  return R"(, "sparse": {"count": )" + std::to_string(count) + R"(, "indices": {"bufferView": )" + std::to_string(indicesView) +
         R"(, "componentType": )" + std::to_string(indexType) + R"(}, "values": {"bufferView": )" +
         std::to_string(valuesView) + "}}";
}

void expectPositions(const Mesh& mesh, std::initializer_list<glm::vec3> expected, const std::string& what) {
  ASSERT_EQ(mesh.positions.size(), expected.size()) << what;
  std::size_t i = 0;
  for (const glm::vec3& e : expected) {
    EXPECT_EQ(mesh.positions[i].x, e.x) << what << ", vertex " << i;
    EXPECT_EQ(mesh.positions[i].y, e.y) << what << ", vertex " << i;
    EXPECT_EQ(mesh.positions[i].z, e.z) << what << ", vertex " << i;
    ++i;
  }
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

TEST(GltfLoader, QuantizedAttributesLoadWhereTheFileUsesKhrMeshQuantization) {
  TempDir dir;
  GltfBuilder b;
  // Positions: normalised SHORT, padded to 8 bytes a vertex; -32768 and -32767 both give -1.
  const int p = b.view(bytesOf<std::int16_t>({0, 0, 0, 0, 32767, -32768, 0, 0, 0, -32767, 16384, 0}), 8);
  // Normals: normalised BYTE, padded to 4 bytes.
  const int n = b.view(bytesOf<std::int8_t>({0, 0, 127, 0, 0, 0, -127, 0, 0, -128, 0, 0}), 4);
  // UVs: UNSIGNED_SHORT, not normalised (the texture transform would scale them).
  const int t = b.view(bytesOf<std::uint16_t>({0, 0, 1000, 0, 0, 65535}));
  b.accessor(denseVec3(p, 3, 5122, R"(, "normalized": true)"));
  b.accessor(denseVec3(n, 3, 5120, R"(, "normalized": true)"));
  b.accessor(dense(t, 3, "VEC2", 5123));
  const std::string primitive = R"("attributes": {"POSITION": 0, "NORMAL": 1, "TEXCOORD_0": 2})";
  testing::expectError([&] { loadGltf(dir.write("plain.gltf", b.text(primitive))); }, ExitCode::kBadInput,
                       {"plain.gltf: accessors[0]", "normalised SHORT components are not allowed for POSITION",
                        "unless the file lists KHR_mesh_quantization in extensionsUsed"},
                       "quantised without the extension");
  const std::string used = R"(, "extensionsUsed": ["KHR_mesh_quantization", "KHR_materials_unlit"],
      "extensionsRequired": ["KHR_mesh_quantization", "KHR_materials_unlit"])";
  const Mesh mesh = loadGltf(dir.write("quantized.gltf", b.text(primitive, "", used))).mesh;
  expectPositions(mesh, {{0, 0, 0}, {1, -1, 0}, {0, -1, 16384.0f / 32767.0f}}, "quantised positions");
  const Attribute* normal = mesh.findAttribute("normal");
  ASSERT_NE(normal, nullptr);
  EXPECT_EQ(normal->values, (HugeVector<float>{0, 0, 1, 0, 0, -1, 0, -1, 0}));
  const Attribute* uv = mesh.findAttribute("uv");
  ASSERT_NE(uv, nullptr);
  EXPECT_EQ(uv->values, (HugeVector<float>{0, 0, 1000, 0, 0, 65535}));

  // Normals may not be quantised without normalisation, even with the extension.
  GltfBuilder raw = b;
  raw.accessors[1] = denseVec3(n, 3, 5120);
  testing::expectError([&] { loadGltf(dir.write("raw.gltf", raw.text(primitive, "", used))); }, ExitCode::kBadInput,
                       {"accessors[1]", "BYTE components are not allowed for NORMAL"}, "unnormalised normals");
  // Extensions that change the geometry are still refused by name.
  testing::expectError(
      [&] {
        loadGltf(dir.write("draco.gltf",
                           b.text(primitive, "", R"(, "extensionsRequired": ["KHR_mesh_quantization", "KHR_draco_mesh_compression"])")));
      },
      ExitCode::kBadInput, {"/extensionsRequired", "does not read: KHR_draco_mesh_compression"}, "draco");
}

TEST(GltfLoader, MorphTargetsApplyAtTheWeightsInForce) {
  TempDir dir;
  GltfBuilder b;
  const int base = b.view(bytesOf<float>({0, 0, 0, 1, 0, 0, 0, 1, 0}));
  const int uvs = b.view(bytesOf<float>({0, 0, 1, 0, 0, 1}));
  // Target 0 moves vertex 2 up by 2 (sparse, over zeros); target 1 moves every uv by (0.5, 0).
  const int ti = b.view(bytesOf<std::uint8_t>({2}));
  const int tv = b.view(bytesOf<float>({0, 2, 0}));
  const int duv = b.view(bytesOf<float>({0.5f, 0, 0.5f, 0, 0.5f, 0}));
  b.accessor(denseVec3(base, 3));
  b.accessor(dense(uvs, 3, "VEC2"));
  b.accessor(R"({"componentType": 5126, "count": 3, "type": "VEC3")" + sparse(1, ti, 5121, tv) + "}");
  b.accessor(dense(duv, 3, "VEC2"));
  // An application-specific attribute, "_speed", which target 1 displaces too.
  b.accessor(dense(b.view(bytesOf<float>({1, 2, 3})), 3, "SCALAR"));
  b.accessor(dense(b.view(bytesOf<float>({10, 20, -30})), 3, "SCALAR"));
  const std::string primitive =
      R"("attributes": {"POSITION": 0, "TEXCOORD_0": 1, "_speed": 4}, "targets": [{"POSITION": 2}, {"TEXCOORD_0": 3, "_speed": 5}])";

  Mesh mesh = loadGltf(dir.write("rest.gltf", b.text(primitive))).mesh;
  expectPositions(mesh, {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}}, "no weights: the base shape");
  mesh = loadGltf(dir.write("mesh.gltf", b.text(primitive, R"(, "weights": [0.5, 1])"))).mesh;
  expectPositions(mesh, {{0, 0, 0}, {1, 0, 0}, {0, 2, 0}}, "the mesh's weights");
  EXPECT_EQ(mesh.findAttribute("uv")->values, (HugeVector<float>{0.5f, 0, 1.5f, 0, 0.5f, 1}));
  EXPECT_EQ(mesh.findAttribute("speed")->values, (HugeVector<float>{11, 22, -27}));
  mesh = loadGltf(dir.write("node.gltf", b.text(primitive, R"(, "weights": [0.5, 1])", "", R"(, "weights": [1.5, 0])"))).mesh;
  expectPositions(mesh, {{0, 0, 0}, {1, 0, 0}, {0, 4, 0}}, "the node's weights override the mesh's");
  EXPECT_EQ(mesh.findAttribute("uv")->values, (HugeVector<float>{0, 0, 1, 0, 0, 1}));

  testing::expectError([&] { loadGltf(dir.write("count.gltf", b.text(primitive, R"(, "weights": [1])"))); },
                       ExitCode::kBadInput, {"meshes[0].primitives[0]", "has 2 morph targets, but 1 weights are given"},
                       "weights count");
  // A target that is not used (weight 0) is still read, and refused when it is bad.
  GltfBuilder bad = b;
  bad.accessors[3] = dense(duv, 2, "VEC2");
  testing::expectError([&] { loadGltf(dir.write("bad.gltf", bad.text(primitive, R"(, "weights": [1, 0])"))); },
                       ExitCode::kBadInput, {"meshes[0].primitives[0].targets[1]", "TEXCOORD_0 count differs"}, "bad target");
}

// A tangent as glTF stores it: xyz and the bitangent's sign w (the Mesh's "tangent", 4 components).
void expectTangents(const Mesh& mesh, const std::vector<float>& expected, const std::string& what) {
  const Attribute* tangent = mesh.findAttribute("tangent");
  ASSERT_NE(tangent, nullptr) << what;
  ASSERT_EQ(tangent->components, 4) << what;
  ASSERT_EQ(tangent->values.size(), expected.size()) << what;
  for (std::size_t i = 0; i < expected.size(); ++i) EXPECT_NEAR(tangent->values[i], expected[i], 1e-7f) << what << ", value " << i;
}

TEST(GltfLoader, TangentsAreReadMorphedAndMovedAsDirectionsThatKeepTheirBitangentSign) {
  TempDir dir;
  GltfBuilder b;
  const int base = b.view(bytesOf<float>({0, 0, 0, 1, 0, 0, 0, 1, 0}));
  const int tangents = b.view(bytesOf<float>({1, 0, 0, 1, 1, 0, 0, 1, 0, 1, 0, -1}));
  const int displaced = b.view(bytesOf<float>({0, 1, 0, 0, 0, 0, 0, 0, 0}));  // target 0: vertex 0's tangent (VEC3)
  b.accessor(denseVec3(base, 3));
  b.accessor(dense(tangents, 3, "VEC4"));
  b.accessor(denseVec3(displaced, 3));
  const std::string primitive = R"("attributes": {"POSITION": 0, "TANGENT": 1}, "targets": [{"TANGENT": 2}])";
  const float r = float(1 / std::sqrt(2.0)), s = float(1 / std::sqrt(5.0));
  expectTangents(loadGltf(dir.write("plain.gltf", b.text(primitive))).mesh, {1, 0, 0, 1, 1, 0, 0, 1, 0, 1, 0, -1}, "as stored");
  // The displacement moves xyz (renormalised after), never w.
  expectTangents(loadGltf(dir.write("morphed.gltf", b.text(primitive, R"(, "weights": [1])"))).mesh,
                 {r, r, 0, 1, 1, 0, 0, 1, 0, 1, 0, -1}, "morphed");
  // A node that mirrors x (scale -2, 1, 1) turns xyz with it, and flips w so that the bitangent
  // cross(normal, xyz) * w still points where the mirror took it.
  expectTangents(loadGltf(dir.write("mirrored.gltf", b.text(primitive, R"(, "weights": [1])", "", R"(, "scale": [-2, 1, 1])"))).mesh,
                 {-2 * s, s, 0, -1, -1, 0, 0, -1, 0, 1, 0, 1}, "mirrored");
  // A turn a quarter about z keeps w.
  expectTangents(loadGltf(dir.write("turned.gltf", b.text(primitive, "", "", R"(, "rotation": [0, 0, 0.7071067811865476, 0.7071067811865476])"))).mesh,
                 {0, 1, 0, 1, 0, 1, 0, 1, -1, 0, 0, -1}, "turned");
  // Written back by export as TANGENT, and read again.
  const Mesh exported = loadGltf(dir.write("again.gltf", gltfFromScene(loadScene(dir.path() / "plain.gltf"), false))).mesh;
  expectTangents(exported, {1, 0, 0, 1, 1, 0, 0, 1, 0, 1, 0, -1}, "exported and read back");

  // Quantised (normalised BYTE) only where the file uses KHR_mesh_quantization.
  GltfBuilder q;
  q.accessor(denseVec3(q.view(bytesOf<float>({0, 0, 0, 1, 0, 0, 0, 1, 0})), 3));
  q.accessor(dense(q.view(bytesOf<std::int8_t>({127, 0, 0, 127, 0, 127, 0, -127, 0, 0, -128, 127})), 3, "VEC4", 5120, R"(, "normalized": true)"));
  const std::string qp = R"("attributes": {"POSITION": 0, "TANGENT": 1})";
  testing::expectError([&] { loadGltf(dir.write("raw.gltf", q.text(qp))); }, ExitCode::kBadInput,
                       {"accessors[1]", "normalised BYTE components are not allowed for TANGENT"}, "quantised tangent");
  expectTangents(loadGltf(dir.write("quantised.gltf", q.text(qp, "", R"(, "extensionsUsed": ["KHR_mesh_quantization"])"))).mesh,
                 {1, 0, 0, 1, 0, 1, 0, -1, 0, 0, -1, 1}, "quantised");
}

TEST(GltfLoader, FurtherUvAndColorSetsAreReadAndExportedUnderTheirGltfNames) {
  TempDir dir;
  GltfBuilder b;
  const int base = b.view(bytesOf<float>({0, 0, 0, 1, 0, 0, 0, 1, 0}));
  const int uv0 = b.view(bytesOf<float>({0, 0, 1, 0, 0, 1}));
  const int uv1 = b.view(bytesOf<std::uint8_t>({0, 0, 0, 0, 255, 0, 0, 0, 0, 51, 0, 0}), 4);  // padded to 4 bytes
  const int color1 = b.view(bytesOf<float>({1, 0, 0, 1, 0, 1, 0, 1, 0, 0, 1, 0.5f}));
  b.accessor(denseVec3(base, 3));
  b.accessor(dense(uv0, 3, "VEC2"));
  b.accessor(dense(uv1, 3, "VEC2", 5121, R"(, "normalized": true)"));
  b.accessor(dense(color1, 3, "VEC4"));
  const std::string path =
      dir.write("sets.gltf", b.text(R"("attributes": {"POSITION": 0, "TEXCOORD_0": 1, "TEXCOORD_1": 2, "COLOR_1": 3})"));
  const Scene scene = loadScene(path);
  ASSERT_NE(scene.mesh.findAttribute("uv1"), nullptr);
  EXPECT_EQ(scene.mesh.findAttribute("uv1")->values, (HugeVector<float>{0, 0, 1, 0, 0, 0.2f}));
  ASSERT_NE(scene.mesh.findAttribute("color1"), nullptr);
  EXPECT_EQ(scene.mesh.findAttribute("color1")->components, 4);
  EXPECT_EQ(scene.mesh.findAttribute("color"), nullptr);
  const std::string exportedText = gltfFromScene(scene, false);
  const nlohmann::json exported = nlohmann::json::parse(exportedText);
  const nlohmann::json& attributes = exported["meshes"][0]["primitives"][0]["attributes"];
  // COLOR_1 without COLOR_0 breaks the specification's numbering from 0 (3.7.2.1); export keeps
  // the set under its own name, which reads back as the same channel.
  for (const char* name : {"POSITION", "TEXCOORD_0", "TEXCOORD_1", "_color1"}) EXPECT_TRUE(attributes.contains(name)) << name;
  EXPECT_EQ(attributes.size(), 4u);
  const Scene again = loadScene(dir.write("again.gltf", exportedText));
  ASSERT_EQ(again.mesh.attributes.size(), scene.mesh.attributes.size());
  for (const Attribute& a : scene.mesh.attributes) {
    const Attribute* read = again.mesh.findAttribute(a.name);
    ASSERT_NE(read, nullptr) << a.name;
    EXPECT_EQ(read->components, a.components) << a.name;
    EXPECT_EQ(read->values, a.values) << a.name;
  }
  // A set takes glTF's name only when every set below it has one: "uv" with 3 components is not
  // TEXCOORD_0, so "uv1" after it is not TEXCOORD_1; RGB and RGBA colours are both COLOR_n.
  const auto semantics = [&](std::vector<Attribute> declared) {
    Scene s = scene;
    s.mesh.attributes.clear();
    for (Attribute& a : declared) {
      a.values.assign(s.mesh.positions.size() * std::size_t(a.components), 0.5f);
      s.mesh.attributes.push_back(std::move(a));
    }
    std::vector<std::string> names;
    const nlohmann::json doc = nlohmann::json::parse(gltfFromScene(s, false));
    for (const auto& [name, index] : doc["meshes"][0]["primitives"][0]["attributes"].items()) {
      if (name != "POSITION") names.push_back(name);
    }
    return names;
  };
  EXPECT_EQ(semantics({{"uv1", 2, {}}}), (std::vector<std::string>{"_uv1"}));
  EXPECT_EQ(semantics({{"uv", 3, {}}, {"uv1", 2, {}}}), (std::vector<std::string>{"_uv", "_uv1"}));
  EXPECT_EQ(semantics({{"color1", 4, {}}, {"color", 3, {}}, {"uv2", 2, {}}, {"uv", 2, {}}}),
            (std::vector<std::string>{"COLOR_0", "COLOR_1", "TEXCOORD_0", "_uv2"}));

  // Application-specific names that cannot name a channel are skipped: empty, "_" alone, a dash.
  const Scene odd = loadScene(dir.write(
      "odd.gltf", b.text(R"("attributes": {"POSITION": 0, "": 1, "_": 1, "_a-b": 1, "_ok": 1, "TEXCOORD_0": 1})")));
  EXPECT_EQ(odd.mesh.attributes.size(), 2u);
  EXPECT_NE(odd.mesh.findAttribute("ok"), nullptr);
}

// The triangles are counted as the hierarchy places them, before they are allocated: a file of
// a few kilobytes whose nodes place one mesh a hundred thousand times is refused at the node
// that passes the limit (it ran out of memory before).
TEST(GltfLoader, TheTriangleLimitIsCheckedAsNodesPlaceMeshes) {
  TempDir dir;
  std::string nodes = R"("nodes": [{"children": [1, 2, 3, 4, 5]})";
  for (int i = 0; i < 5; ++i) nodes += R"(, {"mesh": 0, "translation": [0, 0, )" + std::to_string(i) + "]}";
  nodes += "]";
  const std::string path = dir.write("five.gltf", gltfText(dataUri(triangleBytes()), "", 3, nodes));
  EXPECT_EQ(loadGltf(path).mesh.triangleCount(), 5u);
  EXPECT_EQ(loadGltf(path, {5}).mesh.triangleCount(), 5u);
  testing::expectError([&] { loadGltf(path, {4}); }, ExitCode::kBadInput,
                       {"five.gltf: nodes[5]: placing meshes[0] takes the scene past 4 triangles"}, "limit 4");
  testing::expectError([&] { loadGltf(path, {6, 2}); }, ExitCode::kBadInput, {"nodes[5]"}, "2 triangles before the file's");
  SceneOverrides o;
  o.maxTriangles = 4;
  testing::expectError([&] { loadScene(path, o); }, ExitCode::kBadInput, {"nodes[5]"}, "through loadScene");
}

TEST(GltfLoader, GpuInstancesEachDrawTheMeshAtTheirTransform) {
  TempDir dir;
  GltfBuilder b;
  const int base = b.view(bytesOf<float>({0, 0, 0, 1, 0, 0, 0, 1, 0}));
  const int translations = b.view(bytesOf<float>({0, 0, 0, 10, 0, 0}));
  // Identity, and a quarter turn about z in normalised SHORTs (23170 / 32767 = 0.7071).
  const int rotations = b.view(bytesOf<std::int16_t>({0, 0, 0, 32767, 0, 0, 23170, 23170}));
  const int scales = b.view(bytesOf<float>({1, 1, 1, 2, 2, 2}));
  b.accessor(denseVec3(base, 3));
  b.accessor(denseVec3(translations, 2));
  b.accessor(dense(rotations, 2, "VEC4", 5122, R"(, "normalized": true)"));
  b.accessor(denseVec3(scales, 2));
  const std::string instancing =
      R"(, "translation": [0, 0, 5], "extensions": {"EXT_mesh_gpu_instancing": {"attributes": {"TRANSLATION": 1, "ROTATION": 2, "SCALE": 3}}})";
  const std::string required = R"(, "extensionsUsed": ["EXT_mesh_gpu_instancing"], "extensionsRequired": ["EXT_mesh_gpu_instancing"])";
  const Mesh mesh = loadGltf(dir.write("instances.gltf", b.text(R"("attributes": {"POSITION": 0})", "", required, instancing))).mesh;
  ASSERT_EQ(mesh.triangleCount(), 2u);
  // Each instance counts against the limit.
  testing::expectError([&] { loadGltf(dir.file("instances.gltf"), {1}); }, ExitCode::kBadInput,
                       {"instances.gltf: nodes[0]: placing meshes[0] takes the scene past 1 triangles"}, "instances, limit 1");
  ASSERT_EQ(mesh.positions.size(), 6u);
  const glm::vec3 expected[6] = {{0, 0, 5}, {1, 0, 5}, {0, 1, 5}, {10, 0, 5}, {10, 2, 5}, {8, 0, 5}};
  for (int i = 0; i < 6; ++i) {
    for (int c = 0; c < 3; ++c) EXPECT_NEAR(mesh.positions[i][c], expected[i][c], 1e-5f) << "vertex " << i << " axis " << c;
  }
  // Instances of different counts are refused.
  GltfBuilder uneven = b;
  uneven.accessors[3] = denseVec3(scales, 1);
  testing::expectError(
      [&] { loadGltf(dir.write("uneven.gltf", uneven.text(R"("attributes": {"POSITION": 0})", "", required, instancing))); },
      ExitCode::kBadInput, {"nodes[0]: extensions/EXT_mesh_gpu_instancing", "SCALE has 1 instances, not 2"}, "uneven");
}

// A glTF of two triangles whose buffer views are compressed with meshoptimizer's encoders (as
// gltfpack -c writes them), the uncompressed views in a fallback buffer that holds no data.
// `edit` changes the JSON document before it is written.
// With `binChunk`, buffer 0 has no URI and its bytes go there instead (for a GLB's BIN chunk).
std::string meshoptGltf(const std::function<void(nlohmann::json&)>& edit = {}, std::string* binChunk = nullptr) {
  const float positions[12] = {0, 0, 0, 1, 0, 0, 0, 1, 0, 1, 1, 0};
  const unsigned indices[6] = {0, 1, 2, 2, 1, 3};
  std::string vertices(meshopt_encodeVertexBufferBound(4, 12), '\0');
  vertices.resize(meshopt_encodeVertexBuffer(reinterpret_cast<unsigned char*>(vertices.data()), vertices.size(), positions, 4, 12));
  std::string triangles(meshopt_encodeIndexBufferBound(6, 4), '\0');
  triangles.resize(meshopt_encodeIndexBuffer(reinterpret_cast<unsigned char*>(triangles.data()), triangles.size(), indices, 6));
  const std::string& packed = triangles;
  std::string bin = vertices;
  while (bin.size() % 4) bin += '\0';
  const std::size_t indexOffset = bin.size();
  bin += packed;
  nlohmann::json doc = {
      {"asset", {{"version", "2.0"}}},
      {"extensionsUsed", {"EXT_meshopt_compression"}},
      {"extensionsRequired", {"EXT_meshopt_compression"}},
      {"scene", 0},
      {"scenes", {{{"nodes", {0}}}}},
      {"nodes", {{{"mesh", 0}}}},
      {"meshes", {{{"primitives", {{{"attributes", {{"POSITION", 0}}}, {"indices", 1}}}}}}},
      {"buffers",
       {{{"uri", dataUri(bin)}, {"byteLength", bin.size()}},
        {{"byteLength", 48 + 24}, {"extensions", {{"EXT_meshopt_compression", {{"fallback", true}}}}}}}},
      {"bufferViews",
       {{{"buffer", 1}, {"byteOffset", 0}, {"byteLength", 48}, {"byteStride", 12},
         {"extensions", {{"EXT_meshopt_compression", {{"buffer", 0}, {"byteOffset", 0}, {"byteLength", vertices.size()},
                                                      {"byteStride", 12}, {"mode", "ATTRIBUTES"}, {"count", 4}}}}}},
        {{"buffer", 1}, {"byteOffset", 48}, {"byteLength", 24},
         {"extensions", {{"EXT_meshopt_compression", {{"buffer", 0}, {"byteOffset", indexOffset}, {"byteLength", packed.size()},
                                                      {"byteStride", 4}, {"mode", "TRIANGLES"}, {"count", 6}}}}}}}},
      {"accessors",
       {{{"bufferView", 0}, {"componentType", 5126}, {"count", 4}, {"type", "VEC3"}},
        {{"bufferView", 1}, {"componentType", 5125}, {"count", 6}, {"type", "SCALAR"}}}}};
  if (binChunk) {
    doc["buffers"][0].erase("uri");
    *binChunk = bin;
  }
  if (edit) edit(doc);
  return doc.dump();
}

TEST(GltfLoader, MeshoptCompressedBufferViewsAreDecoded) {
  TempDir dir;
  const Mesh mesh = loadGltf(dir.write("meshopt.gltf", meshoptGltf())).mesh;
  expectPositions(mesh, {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {1, 1, 0}}, "decoded positions");
  ASSERT_EQ(mesh.triangleCount(), 2u);
  // The index codec may start a triangle at another corner; the triangles stay the same.
  for (std::size_t t = 0; t < 2; ++t) {
    std::array<unsigned, 3> corners{mesh.triangles[t][0], mesh.triangles[t][1], mesh.triangles[t][2]};
    std::rotate(corners.begin(), std::min_element(corners.begin(), corners.end()), corners.end());
    EXPECT_EQ(corners, (t == 0 ? std::array<unsigned, 3>{0, 1, 2} : std::array<unsigned, 3>{1, 3, 2})) << "triangle " << t;
  }
  // The same in a GLB.
  std::string bin;
  const std::string json = meshoptGltf({}, &bin);
  expectPositions(loadGltf(dir.write("meshopt.glb", glb(json, bin))).mesh, {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {1, 1, 0}},
                  "decoded from a GLB");

  const std::string ext = "/bufferViews/0/extensions/EXT_meshopt_compression";
  struct Case { std::function<void(nlohmann::json&)> edit; std::vector<std::string> fragments; };
  const Case cases[] = {
      {[](nlohmann::json& d) { d["bufferViews"][0]["extensions"]["EXT_meshopt_compression"]["mode"] = "VERTICES"; },
       {"bad.gltf: " + ext + "/mode", "is not one of ATTRIBUTES, TRIANGLES, INDICES"}},
      {[](nlohmann::json& d) { d["bufferViews"][0]["extensions"]["EXT_meshopt_compression"]["byteStride"] = 10; },
       {ext + "/byteStride", "10 is not a multiple of 4"}},
      {[](nlohmann::json& d) { d["bufferViews"][1]["extensions"]["EXT_meshopt_compression"]["count"] = 5; },
       {"/bufferViews/1/extensions/EXT_meshopt_compression/count", "5 is not a multiple of 3"}},
      {[](nlohmann::json& d) { d["bufferViews"][0]["extensions"]["EXT_meshopt_compression"]["byteLength"] = -3; },
       {ext + "/byteLength", "is not a non-negative integer"}},
      {[](nlohmann::json& d) { d["bufferViews"][0]["extensions"]["EXT_meshopt_compression"]["byteOffset"] = 1000; },
       {"bad.gltf: bufferViews[0]", "compressed range runs past the end of buffer 0"}},
      {[](nlohmann::json& d) { d["bufferViews"][0]["extensions"]["EXT_meshopt_compression"]["byteLength"] = 4; },
       {"bufferViews[0]", "compressed data is invalid"}},
      {[](nlohmann::json& d) { d["bufferViews"][0]["byteLength"] = 36; },
       {"bufferViews[0]", "byteLength 36 is not count x byteStride (48)"}},
      {[](nlohmann::json& d) { d["bufferViews"][0]["extensions"]["EXT_meshopt_compression"]["buffer"] = 1; },
       {"bufferViews[0]", "names buffer 1, which holds no data"}},
      {[](nlohmann::json& d) { d["bufferViews"][1].erase("extensions"); },
       {"bufferViews[1]", "reads buffer 1, a fallback that holds no data"}},
      {[](nlohmann::json& d) {
         d["bufferViews"][0]["extensions"]["EXT_meshopt_compression"]["count"] = 1u << 24;
         d["bufferViews"][0]["byteLength"] = 12u << 24;
       },
       {"bufferViews[0]", "more than meshoptimizer's codecs can expand"}},
      {[](nlohmann::json& d) { d["bufferViews"][0]["extensions"]["EXT_meshopt_compression"]["filter"] = "OCTAHEDRAL"; },
       {ext + "/byteStride", "does not suit the OCTAHEDRAL filter"}},
      {[](nlohmann::json& d) { d["bufferViews"][0]["extensions"]["EXT_meshopt_compression"].erase("count"); },
       {"bad.gltf: " + ext + ": has no count"}},
  };
  for (const Case& c : cases) {
    const std::string path = dir.write("bad.gltf", meshoptGltf(c.edit));
    testing::expectError([&] { loadGltf(path); }, ExitCode::kBadInput, c.fragments, c.fragments.back());
  }
}

TEST(GltfLoader, SkinnedMeshesStandAsTheirJointsDo) {
  TempDir dir;
  GltfBuilder b;
  const int base = b.view(bytesOf<float>({0, 0, 0, 1, 0, 0, 0, 1, 0}));
  const int normals = b.view(bytesOf<float>({0, 0, 1, 0, 0, 1, 0, 0, 1}));
  // Vertex 0 on joint 0; vertex 1 half on each; vertex 2 on joint 1 (through the second set of
  // four influences, JOINTS_1 / WEIGHTS_1).
  const int joints0 = b.view(bytesOf<std::uint8_t>({0, 0, 0, 0, 0, 1, 0, 0, 0, 0, 0, 0}));
  const int weights0 = b.view(bytesOf<std::uint8_t>({255, 0, 0, 0, 128, 127, 0, 0, 0, 0, 0, 0}));
  const int joints1 = b.view(bytesOf<std::uint16_t>({0, 0, 0, 0, 0, 0, 0, 0, 1, 0, 0, 0}));
  const int weights1 = b.view(bytesOf<float>({0, 0, 0, 0, 0, 0, 0, 0, 1, 0, 0, 0}));
  // Inverse bind matrices: joint 0 identity, joint 1 bound at y = 1 (a translation by -1).
  const int bind = b.view(bytesOf<float>({1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1,  //
                                          1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, -1, 0, 1}));
  b.accessor(denseVec3(base, 3));
  b.accessor(denseVec3(normals, 3));
  b.accessor(dense(joints0, 3, "VEC4", 5121));
  b.accessor(dense(weights0, 3, "VEC4", 5121, R"(, "normalized": true)"));
  b.accessor(dense(joints1, 3, "VEC4", 5123));
  b.accessor(dense(weights1, 3, "VEC4"));
  b.accessor(dense(bind, 2, "MAT4"));
  b.accessor(dense(b.view(bytesOf<float>({1, 0, 0, 1, 1, 0, 0, 1, 0, 1, 0, -1})), 3, "VEC4"));
  std::string primitive =
      R"("attributes": {"POSITION": 0, "NORMAL": 1, "JOINTS_0": 2, "WEIGHTS_0": 3, "JOINTS_1": 4, "WEIGHTS_1": 5, "TANGENT": 7})";
  // Node 0 holds the mesh (its translation must not apply); nodes 1 and 2 are the joints, 2 a
  // child of 1. `joint2` is node 2's transform.
  auto file = [&](const std::string& joint2, const std::string& skin = R"({"joints": [1, 2], "inverseBindMatrices": 6})") {
    std::string text = b.text(primitive, "", R"(, "skins": [)" + skin + "]", R"(, "skin": 0, "translation": [10, 0, 0])");
    const std::string nodes = R"("nodes": [{"mesh": 0)";
    const std::size_t at = text.find(nodes);
    const std::size_t end = text.find("}]", at);
    text.insert(end + 1, R"(, {"children": [2], "translation": [0, 0, 5]}, {)" + joint2 + "}");
    return text;
  };

  // At the bind pose (joint 2 at y = 1 below joint 1) every vertex stays, moved only by joint 1's
  // translation to z = 5, which both joints carry.
  Mesh mesh = loadGltf(dir.write("bind.gltf", file(R"("translation": [0, 1, 0])"))).mesh;
  expectPositions(mesh, {{0, 0, 5}, {1, 0, 5}, {0, 1, 5}}, "bind pose");
  // Joint 2 raised by 2: vertex 2 follows it, vertex 1 half of the way (its weights 128/255 and 127/255).
  mesh = loadGltf(dir.write("raised.gltf", file(R"("translation": [0, 3, 0])"))).mesh;
  expectPositions(mesh, {{0, 0, 5}, {1, float(2.0 * 127 / 255), 5}, {0, 3, 5}}, "joint raised");
  // Joint 2 turned a quarter about x: vertex 2's normal turns with it.
  mesh = loadGltf(dir.write("turned.gltf", file(R"("translation": [0, 1, 0], "rotation": [0.7071067811865476, 0, 0, 0.7071067811865476])"))).mesh;
  const auto& n = mesh.findAttribute("normal")->values;
  EXPECT_NEAR(n[6], 0.0f, 1e-6f);
  EXPECT_NEAR(n[7], -1.0f, 1e-6f);
  EXPECT_NEAR(n[8], 0.0f, 1e-6f);
  EXPECT_EQ(n[2], 1.0f) << "vertex 0 stays on joint 1, which does not turn";
  const auto& t = mesh.findAttribute("tangent")->values;  // vertex 2's (0, 1, 0) turns to +z
  EXPECT_EQ(std::vector<float>(t.begin(), t.begin() + 4), (std::vector<float>{1, 0, 0, 1}));
  EXPECT_NEAR(t[8], 0.0f, 1e-6f);
  EXPECT_NEAR(t[9], 0.0f, 1e-6f);
  EXPECT_NEAR(t[10], 1.0f, 1e-6f);
  EXPECT_EQ(t[11], -1.0f);

  testing::expectError([&] { loadGltf(dir.write("few.gltf", file(R"("translation": [0, 1, 0])", R"({"joints": [1]})"))); },
                       ExitCode::kBadInput, {"accessors[2]", "joint 1 of vertex 1 is not below the skin's 1 joints"},
                       "joint out of range");
  testing::expectError(
      [&] { loadGltf(dir.write("bind.gltf", file(R"("translation": [0, 1, 0])", R"({"joints": [1, 2, 0], "inverseBindMatrices": 6})"))); },
      ExitCode::kBadInput, {"skins[0]", "fewer inverseBindMatrices than joints"}, "too few bind matrices");
  testing::expectError([&] { loadGltf(dir.write("node.gltf", file(R"("translation": [0, 1, 0])", R"({"joints": [1, 9]})"))); },
                       ExitCode::kBadInput, {"node.gltf: /skins/0/joints/1: 9 is past the end of /nodes (it holds 3 elements)"}, "joint node");
  // Joints 3 and 4, outside the scene, each the other's child.
  nlohmann::json cyclic = nlohmann::json::parse(file(R"("translation": [0, 1, 0])", R"({"joints": [3, 2]})"));
  cyclic["nodes"].push_back({{"children", {4}}});
  cyclic["nodes"].push_back({{"children", {3}}});
  testing::expectError([&] { loadGltf(dir.write("cyclic.gltf", cyclic.dump())); }, ExitCode::kBadInput,
                       {"cyclic.gltf: nodes[3]: ancestry deeper than 256 or cyclic"}, "a joint's cyclic ancestry");
  // The second set of influences without its weights, then with weights for two of three vertices.
  primitive = R"("attributes": {"POSITION": 0, "JOINTS_0": 2, "WEIGHTS_0": 3, "JOINTS_1": 4})";
  testing::expectError([&] { loadGltf(dir.write("half.gltf", file(R"("translation": [0, 1, 0])"))); }, ExitCode::kBadInput,
                       {"half.gltf: meshes[0].primitives[0]: has only one of JOINTS_1 and WEIGHTS_1"}, "joints alone");
  b.accessor(dense(weights1, 2, "VEC4"));
  primitive = R"("attributes": {"POSITION": 0, "JOINTS_0": 2, "WEIGHTS_0": 3, "JOINTS_1": 4, "WEIGHTS_1": 8})";
  testing::expectError([&] { loadGltf(dir.write("short.gltf", file(R"("translation": [0, 1, 0])"))); }, ExitCode::kBadInput,
                       {"meshes[0].primitives[0]: JOINTS_1 or WEIGHTS_1 count differs from POSITION count"}, "two weights");
}

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
