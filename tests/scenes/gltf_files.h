// Small glTF files built in memory for the loader's tests: one triangle, GLB containers, and a
// builder of buffers, views and accessors.
#pragma once

#include <gtest/gtest.h>

#include <cstdint>
#include <cstring>
#include <initializer_list>
#include <string>
#include <vector>

#include <glm/glm.hpp>

#include "core/base64.h"
#include "scenes/mesh.h"

namespace rc::testing {

// Three float3 positions (36 bytes) followed by three uint16 indices and 2 bytes of padding.
inline std::string triangleBytes(std::uint16_t lastIndex = 2) {
  const float p[9] = {0, 0, 0, 1, 0, 0, 0, 1, 0};
  const std::uint16_t idx[4] = {0, 1, lastIndex, 0};
  std::string bytes(44, '\0');
  std::memcpy(bytes.data(), p, 36);
  std::memcpy(bytes.data() + 36, idx, 8);
  return bytes;
}

// A one-triangle glTF whose buffer is `uri`; `extra` is spliced into the top-level object.
inline std::string gltfText(const std::string& uri, const std::string& extra = "", int positionCount = 3,
                     const std::string& nodes = R"("nodes": [{"mesh": 0}])") {
  return R"({"asset": {"version": "2.0"}, "scene": 0, "scenes": [{"nodes": [0]}], )" + nodes +
         R"(, "meshes": [{"primitives": [{"attributes": {"POSITION": 0}, "indices": 1}]}],
  "buffers": [{"uri": ")" + uri + R"(", "byteLength": 44}],
  "bufferViews": [{"buffer": 0, "byteOffset": 0, "byteLength": 36}, {"buffer": 0, "byteOffset": 36, "byteLength": 6}],
  "accessors": [{"bufferView": 0, "componentType": 5126, "count": )" + std::to_string(positionCount) +
         R"(, "type": "VEC3"},
                {"bufferView": 1, "componentType": 5123, "count": 3, "type": "SCALAR"}])" + extra + "}";
}

inline std::string dataUri(const std::string& bytes) { return "data:application/octet-stream;base64," + base64(bytes); }

inline std::string glb(const std::string& json, const std::string& bin, std::uint32_t declaredLength = 0) {
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

// The bytes of `values` as the type T stores them (little-endian, as glTF).
template <typename T>
inline std::string bytesOf(std::initializer_list<T> values) {
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
inline std::string dense(int view, int count, const char* type, int componentType = 5126, const std::string& more = "") {
  return R"({"bufferView": )" + std::to_string(view) + R"(, "componentType": )" + std::to_string(componentType) +
         R"(, "count": )" + std::to_string(count) + R"(, "type": ")" + type + "\"" + more + "}";
}

inline std::string denseVec3(int view, int count, int componentType = 5126, const std::string& more = "") {
  return dense(view, count, "VEC3", componentType, more);
}

inline std::string sparse(int count, int indicesView, int indexType, int valuesView) {
  return R"(, "sparse": {"count": )" + std::to_string(count) + R"(, "indices": {"bufferView": )" + std::to_string(indicesView) +
         R"(, "componentType": )" + std::to_string(indexType) + R"(}, "values": {"bufferView": )" +
         std::to_string(valuesView) + "}}";
}

inline void expectPositions(const Mesh& mesh, std::initializer_list<glm::vec3> expected, const std::string& what) {
  ASSERT_EQ(mesh.positions.size(), expected.size()) << what;
  std::size_t i = 0;
  for (const glm::vec3& e : expected) {
    EXPECT_EQ(mesh.positions[i].x, e.x) << what << ", vertex " << i;
    EXPECT_EQ(mesh.positions[i].y, e.y) << what << ", vertex " << i;
    EXPECT_EQ(mesh.positions[i].z, e.z) << what << ", vertex " << i;
    ++i;
  }
}

}  // namespace rc::testing
