// glTF data: URIs taken out of the JSON before parsing (scenes/loaders/gltf_data_uris.h): what
// is taken and what is left, the base64 decoder against core/base64.h, the messages for bad
// data, and files that load the same whether or not their URIs are taken out.
#include <gtest/gtest.h>

#include <cstdint>
#include <nlohmann/json.hpp>
#include <random>
#include <string>
#include <vector>

#include "core/base64.h"
#include "core/error.h"
#include "scenes/loaders/gltf_checks.h"
#include "scenes/loaders/gltf_data_uris.h"
#include "scenes/loaders/gltf_loader.h"
#include "tests/test_files.h"

namespace rc {
namespace {

using gltf::EmbeddedData;
using gltf::takeDataUris;
using testing::readFile;
using testing::TempDir;

const std::string kOctet = "data:application/octet-stream;base64,";

std::vector<unsigned char> bytesOf(const std::string& s) { return {s.begin(), s.end()}; }

// The value at a JSON pointer of a text after parsing.
std::string stringAt(const std::string& json, const char* pointer) {
  return nlohmann::json::parse(json).at(nlohmann::json::json_pointer(pointer)).get<std::string>();
}

TEST(GltfDataUris, BuffersAndImagesLoseTheirDataAndEverythingElseStays) {
  const std::string image = "data:image/png;base64," + base64("not a png at all");
  const std::string json = R"({"asset": {"version": "2.0", "uri": ")" + kOctet + base64("asset") + R"("},
    "buffers": [{"byteLength": 5, "uri": ")" + kOctet + base64("first") + R"("}, {"uri": "side.bin", "byteLength": 4},
                {"uri" : ")" + "data:application/gltf-buffer;BASE64," + base64("third!") + R"(", "extras": {"uri": ")" + kOctet + R"(AAAA"}}],
    "images": [{"uri": ")" + image + R"("}, {"uri": "data:image/svg+xml,<svg/>"}],
    "meshes": [{"uri": ")" + kOctet + R"(AAAA", "buffers": [{"uri": ")" + kOctet + R"(AAAA"}]}]})";
  const EmbeddedData taken = takeDataUris(json, "f.gltf");
  ASSERT_TRUE(taken.changed());
  ASSERT_EQ(taken.buffers.size(), 2u);
  const std::string first = stringAt(taken.json, "/buffers/0/uri"), third = stringAt(taken.json, "/buffers/2/uri");
  EXPECT_EQ(first[0], '*');
  EXPECT_EQ(taken.buffers.at(first), bytesOf("first"));
  EXPECT_EQ(taken.buffers.at(third), bytesOf("third!"));  // any media type, ";base64" in any case
  EXPECT_NE(first, third);
  EXPECT_EQ(stringAt(taken.json, "/buffers/1/uri"), "side.bin");
  EXPECT_EQ(stringAt(taken.json, "/images/0/uri"), "data:image/png;base64,AA==");  // images are never read
  EXPECT_EQ(stringAt(taken.json, "/images/1/uri"), "data:image/svg+xml,<svg/>");   // not base64: left as it is
  // Everything not at /buffers/N/uri or /images/N/uri is the same text.
  for (const char* pointer : {"/asset/uri", "/buffers/2/extras/uri", "/meshes/0/uri", "/meshes/0/buffers/0/uri"}) {
    EXPECT_EQ(stringAt(taken.json, pointer), stringAt(json, pointer)) << pointer;
  }
  nlohmann::json expected = nlohmann::json::parse(json), got = nlohmann::json::parse(taken.json);
  for (const char* pointer : {"/buffers/0/uri", "/buffers/2/uri", "/images/0/uri"}) {
    expected[nlohmann::json::json_pointer(pointer)] = got[nlohmann::json::json_pointer(pointer)];
  }
  EXPECT_EQ(got, expected);
}

TEST(GltfDataUris, TextTheScanCannotFollowIsLeftForTheParsers) {
  const std::string uri = kOctet + base64("abc");
  for (const std::string& json : {
           R"({"buffers": [{"uri": ")" + uri + R"("}])",                       // unclosed
           R"({"buffers": [{"uri": ")" + uri + R"("},]})",                     // trailing comma
           R"({"buffers": [{"uri": ")" + uri + R"(" "byteLength": 3}]})",      // missing comma
           R"({"buffers": [{"uri": ")" + uri + R"("}]} x)",                    // text after the end
           R"({"buffers": [{"uri": ")" + uri + R"(", "byteLength": 3]})",      // mismatched bracket
           R"({"buffers": [{"uri": ")" + uri + R"(\/"}]})",                    // an escape in the URI
           R"({"buff\u0065rs": [{"uri": ")" + uri + R"("}]})",                 // a key spelled with an escape
           R"({"buffers": [{"uri": ")" + uri + R"("}], "x": "*rastercheck-embedded-0"})",  // holds the names' prefix
           R"(["buffers", {"uri": ")" + uri + R"("}])",                        // not an object at the top
           R"({"buffers": [{"uri": ")" + uri + R"("}], "deep": )" + std::string(64, '[') + std::string(64, ']') + "}",
       }) {
    const EmbeddedData taken = takeDataUris(json, "f.gltf");
    EXPECT_FALSE(taken.changed()) << json;
    EXPECT_TRUE(taken.buffers.empty()) << json;
  }
  // Nesting up to 64 levels (the top object and 63 arrays) is followed.
  const std::string deep = R"({"buffers": [{"uri": ")" + uri + R"("}], "deep": )" + std::string(63, '[') + std::string(63, ']') + "}";
  EXPECT_EQ(takeDataUris(deep, "f.gltf").buffers.size(), 1u);
  // Escaped quotes and backslashes in other strings do not end them early.
  const std::string json = R"({"extras": "a \"b\" \\", "buffers": [{"name": "q\\\"", "uri": ")" + uri + R"("}]})";
  const EmbeddedData taken = takeDataUris(json, "f.gltf");
  ASSERT_EQ(taken.buffers.size(), 1u);
  EXPECT_EQ(taken.buffers.begin()->second, bytesOf("abc"));
  EXPECT_EQ(nlohmann::json::parse(taken.json)["buffers"][0]["name"], "q\\\"");
}

TEST(GltfDataUris, DecodesWhatCoreBase64EncodesWithAndWithoutPadding) {
  std::mt19937 random(7);
  for (std::size_t size = 1; size < 70; ++size) {
    std::string bytes(size, '\0');
    for (char& c : bytes) c = char(random());
    std::string digits = base64(bytes);
    for (bool padded : {true, false}) {
      if (!padded) {
        while (digits.back() == '=') digits.pop_back();
      }
      const EmbeddedData taken = takeDataUris(R"({"buffers": [{"uri": ")" + kOctet + digits + R"("}]})", "f.gltf");
      ASSERT_EQ(taken.buffers.size(), 1u);
      EXPECT_EQ(taken.buffers.begin()->second, bytesOf(bytes)) << size << (padded ? " padded" : " unpadded");
    }
  }
}

TEST(GltfDataUris, BadBase64IsRefusedAtItsCharacter) {
  const auto refused = [](const std::string& uri, const std::string& why) {
    const std::string json = R"({"buffers": [{"uri": "side.bin"}, {"uri": ")" + uri + R"("}]})";
    testing::expectError([&] { takeDataUris(json, "f.gltf"); }, ExitCode::kBadInput, {"f.gltf: /buffers/1/uri", why}, uri);
  };
  // kOctet is 37 characters, so its data starts at character 38.
  refused(kOctet + "AAAA!AAA", "'!' is not a base64 digit at character 42 of the URI");
  refused(kOctet + "AA=A", "'=' is not a base64 digit at character 40");
  refused(kOctet + "AA AA", "' ' is not a base64 digit at character 40");
  refused(kOctet + "AAAA\x01", "byte 0x01 is not a base64 digit at character 42");
  refused(kOctet + "AAAAA", "a lone digit ends it at character 42");
  refused(kOctet + "AAAAAA=", "its '=' padding does not fill the last group of four at character 44");
  refused("data:application/octet-stream,abc", "without base64 data");
  refused("data:application/octet-stream;base64", "without base64 data");
}

// A one-triangle glTF (three float3 positions, three uint16 indices, padding) whose buffer is
// `uri`, declared `byteLength` long.
std::string triangleGltf(const std::string& uri, std::size_t byteLength) {
  return R"({"asset": {"version": "2.0"}, "scenes": [{"nodes": [0]}], "nodes": [{"mesh": 0}],
    "meshes": [{"primitives": [{"attributes": {"POSITION": 0}, "indices": 1}]}],
    "buffers": [{"uri": ")" + uri + R"(", "byteLength": )" + std::to_string(byteLength) + R"(}],
    "bufferViews": [{"buffer": 0, "byteLength": 36}, {"buffer": 0, "byteOffset": 36, "byteLength": 6}],
    "accessors": [{"bufferView": 0, "componentType": 5126, "count": 3, "type": "VEC3"},
                  {"bufferView": 1, "componentType": 5123, "count": 3, "type": "SCALAR"}]})";
}

// The triangle's 44 bytes and then `tail`: 0xFF bytes make base64 digits '/', which JSON may
// write escaped as "\/".
std::string triangleBytes(std::size_t tail) {
  const float p[9] = {0, 0, 0, 2, 0, 0, 0, 3, 0};
  const std::uint16_t idx[4] = {0, 1, 2, 0};
  std::string bytes(reinterpret_cast<const char*>(p), 36);
  bytes.append(reinterpret_cast<const char*>(idx), 8);
  return bytes + std::string(tail, '\xFF');
}

std::string escapedSlashes(std::string s) {
  for (std::size_t at = s.find('/'); at != std::string::npos; at = s.find('/', at + 2)) s.insert(at, "\\");
  return s;
}

TEST(GltfDataUris, AFileLoadsTheSameWhetherItsUriIsTakenOutOrLeftToTinygltf) {
  TempDir dir;
  const std::string bytes = triangleBytes(30000);
  const std::string digits = base64(bytes);
  ASSERT_NE(digits.find('/'), std::string::npos);
  const std::string taken = dir.write("taken.gltf", triangleGltf(kOctet + digits, bytes.size()));
  const std::string left = dir.write("left.gltf", triangleGltf(escapedSlashes(kOctet + digits), bytes.size()));
  ASSERT_TRUE(takeDataUris(readFile(taken), taken).changed());
  ASSERT_FALSE(takeDataUris(readFile(left), left).changed());
  const Mesh a = loadGltf(taken).mesh, b = loadGltf(left).mesh;
  ASSERT_EQ(a.triangleCount(), 1u);
  EXPECT_EQ(a.positions, b.positions);
  EXPECT_EQ(a.triangles, b.triangles);
  EXPECT_EQ(a.positions[2].y, 3.0f);
  // A GLB may hold a data: URI in its JSON chunk too (and no BIN chunk).
  std::string json = triangleGltf(kOctet + digits, bytes.size());
  while (json.size() % 4) json += ' ';
  const auto u32 = [](std::uint32_t v) { return std::string(reinterpret_cast<const char*>(&v), 4); };
  const std::string glb = dir.write("taken.glb", "glTF" + u32(2) + u32(std::uint32_t(20 + json.size())) +
                                                     u32(std::uint32_t(json.size())) + "JSON" + json);
  const Mesh c = loadGltf(glb).mesh;
  EXPECT_EQ(c.positions, a.positions);
  EXPECT_EQ(c.triangles, a.triangles);

  // A byteLength that is not the data's size, both ways: named exactly where taken out, and
  // tinygltf's message (which quotes the whole URI) cut short where not.
  const std::string wrong = dir.write("wrong.gltf", triangleGltf(kOctet + digits, bytes.size() + 4));
  testing::expectError([&] { loadGltf(wrong); }, ExitCode::kBadInput,
                       {"wrong.gltf: /buffers/0/byteLength: is 30048, but the buffer's data: URI holds 30044 bytes"}, "taken");
  const std::string wrongLeft = dir.write("wrong-left.gltf", triangleGltf(escapedSlashes(kOctet + digits), bytes.size() + 4));
  try {
    loadGltf(wrongLeft);
    ADD_FAILURE() << "wrong-left.gltf loaded";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("wrong-left.gltf: not a valid glTF 2.0 file: Failed to decode 'uri'"), std::string::npos)
        << e.what();
    EXPECT_NE(std::string(e.what()).find(" more characters)"), std::string::npos);
    EXPECT_LT(std::string(e.what()).size(), 600u);
  }
  const std::string empty = dir.write("empty.gltf", triangleGltf(kOctet, 44));
  testing::expectError([&] { loadGltf(empty); }, ExitCode::kBadInput, {"empty.gltf: /buffers/0/uri: is a data: URI that holds no bytes"},
                       "empty");
}

TEST(GltfDataUris, ASyntaxErrorIsReportedWhereItIsInTheFilesOwnText) {
  TempDir dir;
  // The scan takes numbers as any run of characters, so it takes the URI out of this file; the
  // parser then fails on the shorter text, and the message must still place the error in the
  // file as written: on one line (as minified files are), after the URI, it moves.
  std::string text = triangleGltf(kOctet + base64(triangleBytes(3000)), 3044);
  for (char& c : text) c = c == '\n' ? ' ' : c;
  text.replace(text.find(R"("count": 3, "type": "SCALAR")"), 10, R"("count": 3.3.3)");
  const std::string path = dir.write("syntax.gltf", text);
  ASSERT_TRUE(takeDataUris(text, path).changed());
  std::string expected;
  try {
    const nlohmann::json parsed = nlohmann::json::parse(text);
    ADD_FAILURE() << "the text parsed: " << parsed.size();
  } catch (const nlohmann::json::exception& e) {
    expected = e.what();
  }
  ASSERT_NE(expected.find("column"), std::string::npos);
  testing::expectError([&] { loadGltf(path); }, ExitCode::kBadInput, {"syntax.gltf: invalid JSON: " + expected}, "syntax");
}

TEST(GltfDataUris, AnImageIsNeverDecodedSoItsDataCannotStopAScene) {
  TempDir dir;
  std::string text = triangleGltf(kOctet + base64(triangleBytes(0)), 44);
  text.insert(text.rfind('}'), R"(, "images": [{"uri": "data:image/png;base64,!!!! not base64 !!!!"}])");
  EXPECT_EQ(loadGltf(dir.write("image.gltf", text)).mesh.triangleCount(), 1u);
}

}  // namespace
}  // namespace rc
