// glTF loading: the sample file's camera and transforms, GLB, and hostile files refused.
#include <gtest/gtest.h>

#include <cmath>
#include <cstring>

#include "scenes/loaders/gltf_loader.h"
#include "tests/test_files.h"

namespace rc {
namespace {

using testing::TempDir;

std::string base64(const std::string& in) {
  static const char* k = "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
  std::string out;
  for (std::size_t i = 0; i < in.size(); i += 3) {
    unsigned n = (unsigned char)in[i] << 16;
    if (i + 1 < in.size()) n |= (unsigned char)in[i + 1] << 8;
    if (i + 2 < in.size()) n |= (unsigned char)in[i + 2];
    out += k[(n >> 18) & 63];
    out += k[(n >> 12) & 63];
    out += i + 1 < in.size() ? k[(n >> 6) & 63] : '=';
    out += i + 2 < in.size() ? k[n & 63] : '=';
  }
  return out;
}

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
  ASSERT_TRUE(content.camera.has_value());
  const CameraSpec& c = *content.camera;
  EXPECT_NEAR(c.eye.x, 0.5, 1e-12);
  EXPECT_NEAR(c.eye.y, 0.5, 1e-12);
  EXPECT_NEAR(c.eye.z, 3.0, 1e-12);
  EXPECT_NEAR(c.target.z, 2.0, 1e-12);  // looking down -Z
  EXPECT_NEAR(c.fovYDegrees, 0.7 * 180.0 / M_PI, 1e-9);
  EXPECT_EQ(c.zNear, 0.01);
  EXPECT_EQ(c.zFar, 100.0);
  EXPECT_EQ(c.width, 600);  // aspectRatio 1
  EXPECT_EQ(c.height, 600);
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
}

TEST(GltfLoader, OrthographicCameraIsRefusedClearly) {
  TempDir dir;
  const std::string path = dir.write(
      "ortho.gltf",
      gltfText(dataUri(triangleBytes()),
               R"(, "cameras": [{"type": "orthographic", "orthographic": {"xmag": 1, "ymag": 1, "znear": 0.1, "zfar": 10}}])",
               3, R"("nodes": [{"mesh": 0, "children": [1]}, {"camera": 0, "translation": [0, 0, 3]}])"));
  testing::expectError([&] { loadGltf(path); }, ExitCode::kBadInput, {"cameras[0]", "orthographic"}, "ortho");
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

}  // namespace
}  // namespace rc
