// glTF loading of what a mesh carries beyond its positions: quantized and morphed attributes,
// tangents, further uv and colour sets, GPU instances, meshopt-compressed views and skins.
#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <cstdint>
#include <functional>
#include <vector>

#include <meshoptimizer.h>
#include <nlohmann/json.hpp>

#include "core/base64.h"
#include "core/error.h"
#include "scenes/loaders/gltf_loader.h"
#include "scenes/loaders/gltf_writer.h"
#include "scenes/scene_loader.h"
#include "tests/scenes/gltf_files.h"
#include "tests/test_files.h"

namespace rc {
namespace {

using namespace testing;  // tests/scenes/gltf_files.h, tests/test_files.h

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

}  // namespace
}  // namespace rc
