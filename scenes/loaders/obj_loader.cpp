// OBJ loading: tinyobjloader parses, this file validates, splits face-varying corners and
// triangulates.
#include "scenes/loaders/obj_loader.h"

#include <tiny_obj_loader.h>

#include <charconv>
#include <istream>
#include <sstream>
#include <streambuf>
#include <cmath>
#include <string_view>
#include <unordered_map>

#include "core/error.h"
#include "scenes/loaders/polygon.h"
#include "scenes/loaders/read_file.h"

namespace rc {
namespace {

// tinyobjloader keeps a face's corner count in a byte: a face of 256 corners or more would be
// read as another face with its indices shifted, so such a face is refused.
constexpr std::size_t kMaxCorners = 255;

// Line numbers of the face statements ("f ..."), to name the place of a bad face. Throws
// badInput for a face of more than kMaxCorners corners.
std::vector<std::size_t> faceLines(std::string_view text, const std::string& path) {
  std::vector<std::size_t> lines;
  const auto blank = [](char c) { return c == ' ' || c == '\t'; };
  std::size_t line = 1;
  for (std::size_t start = 0; start < text.size(); ++line) {
    std::size_t end = text.find('\n', start);
    if (end == std::string_view::npos) end = text.size();
    std::size_t j = start;
    while (j < end && blank(text[j])) ++j;
    if (j + 1 < end && text[j] == 'f' && blank(text[j + 1])) {
      lines.push_back(line);
      std::size_t corners = 0;
      for (std::size_t k = j + 1; k < end && text[k] != '\r'; ++k) {
        if (!blank(text[k]) && blank(text[k - 1])) ++corners;
      }
      if (corners > kMaxCorners) {
        throw badInput(path + ":" + std::to_string(line), "face has " + std::to_string(corners) + " corners; at most " +
                                                              std::to_string(kMaxCorners) + " are read (split it)");
      }
    }
    start = end + 1;
  }
  return lines;
}

// tinyobjloader reads a token it cannot parse ("nan", "abc") as 0 without a word, so every
// number of a v, vt or vn statement is checked here first: it must parse completely, with
// std::from_chars (the locale never matters), and be finite as a float.
void checkNumbers(std::string_view text, const std::string& path) {
  std::size_t line = 1, start = 0;
  while (start < text.size()) {
    std::size_t end = text.find('\n', start);
    if (end == std::string::npos) end = text.size();
    const std::string_view statement(text.data() + start, end - start);
    std::size_t i = statement.find_first_not_of(" \t");
    if (i != std::string_view::npos && statement[i] == 'v' && i + 1 < statement.size() &&
        (statement[i + 1] == ' ' || statement[i + 1] == '\t' ||
         ((statement[i + 1] == 't' || statement[i + 1] == 'n') && i + 2 < statement.size() &&
          (statement[i + 2] == ' ' || statement[i + 2] == '\t')))) {
      i = statement.find_first_of(" \t", i);
      while (true) {
        i = statement.find_first_not_of(" \t\r", i);
        if (i == std::string_view::npos) break;
        std::size_t j = statement.find_first_of(" \t\r", i);
        if (j == std::string_view::npos) j = statement.size();
        const std::string_view token = statement.substr(i, j - i);
        float value = 0.0f;
        const auto [ptr, ec] = std::from_chars(token.data(), token.data() + token.size(), value);
        if (ec != std::errc() || ptr != token.data() + token.size() || !std::isfinite(value)) {
          throw badInput(path + ":" + std::to_string(line),
                         "'" + std::string(token.substr(0, 40)) + "' is not a finite float");
        }
        i = j;
      }
    }
    start = end + 1;
    ++line;
  }
}

// The file's text as a stream, without the copy into a stringbuf that tinyobjloader's
// ParseFromString makes (117 MB for a million triangles; loading such a file took 0.2 to 0.3 s less).
struct TextBuffer : std::streambuf {
  explicit TextBuffer(std::string_view text) {
    char* begin = const_cast<char*>(text.data());  // the get area is only read
    setg(begin, begin, begin + text.size());
  }
};

struct CornerKey {
  int v, vt, vn;
  bool operator==(const CornerKey&) const = default;
};
struct CornerHash {
  std::size_t operator()(const CornerKey& k) const {
    return std::hash<long long>()((static_cast<long long>(k.v) * 1000003LL + k.vt) * 1000003LL + k.vn);
  }
};

}  // namespace

Mesh loadObj(const std::string& path) {
  const PlaneVector<char> bytes = readLargeInputFile(path);
  const std::string_view text(bytes.data(), bytes.size());
  checkNumbers(text, path);
  tinyobj::attrib_t attrib;
  std::vector<tinyobj::shape_t> shapes;
  std::vector<tinyobj::material_t> materials;
  std::string warning, error;
  TextBuffer objText(text);
  std::istream objStream(&objText);
  std::stringbuf noMaterials;  // mtllib is never opened: the parser gets no material text
  std::istream materialStream(&noMaterials);
  tinyobj::MaterialStreamReader materialReader(materialStream);
  // Not triangulated (that is done below, polygon.h, so every face keeps its line); no colours.
  if (!tinyobj::LoadObj(&attrib, &shapes, &materials, &warning, &error, &objStream, &materialReader, false, false)) {
    throw badInput(path, "not a valid OBJ file: " + error);
  }
  const std::vector<std::size_t> lines = faceLines(text, path);

  std::size_t faceCount = 0;
  for (const tinyobj::shape_t& shape : shapes) faceCount += shape.mesh.num_face_vertices.size();
  const bool linesKnown = lines.size() == faceCount;
  std::size_t face = 0;
  const auto where = [&](std::size_t f) {
    return linesKnown ? path + ":" + std::to_string(lines[f]) : path + ": face " + std::to_string(f + 1);
  };

  const int vertexCount = int(attrib.vertices.size() / 3);
  const int uvCount = int(attrib.texcoords.size() / 2);
  const int normalCount = int(attrib.normals.size() / 3);
  // An attribute is kept when every corner of every face has it; a file where only some
  // faces have it is refused, naming the first face without it.
  bool anyUv = false, anyNormal = false;
  for (const tinyobj::shape_t& shape : shapes) {
    for (const tinyobj::index_t& index : shape.mesh.indices) {
      anyUv = anyUv || index.texcoord_index >= 0;
      anyNormal = anyNormal || index.normal_index >= 0;
    }
  }
  {
    std::size_t f = 0;
    for (const tinyobj::shape_t& shape : shapes) {
      std::size_t offset = 0;
      for (const unsigned char arity : shape.mesh.num_face_vertices) {
        for (unsigned k = 0; k < arity; ++k) {
          const tinyobj::index_t& index = shape.mesh.indices[offset + k];
          if ((anyUv && index.texcoord_index < 0) || (anyNormal && index.normal_index < 0)) {
            throw badInput(where(f), std::string("this face lacks the ") +
                                         (anyUv && index.texcoord_index < 0 ? "texture coordinate (vt)" : "normal (vn)") +
                                         " index that other faces have");
          }
        }
        offset += arity;
        ++f;
      }
    }
  }
  const bool allUv = anyUv, allNormal = anyNormal;

  Mesh mesh;
  HugeVector<float> uvs, normals;
  std::unordered_map<CornerKey, unsigned, CornerHash> corners;
  for (const tinyobj::shape_t& shape : shapes) {
    std::size_t offset = 0;
    for (const unsigned char arity : shape.mesh.num_face_vertices) {
      if (arity < 3) throw badInput(where(face), "face has " + std::to_string(arity) + " vertices; 3 or more needed");
      std::vector<unsigned> polygon;
      for (unsigned k = 0; k < arity; ++k) {
        const tinyobj::index_t& index = shape.mesh.indices[offset + k];
        if (index.vertex_index < 0 || index.vertex_index >= vertexCount) {
          throw badInput(where(face), "vertex index out of range (the file has " + std::to_string(vertexCount) +
                                          " vertices; indices start at 1, negative ones count back)");
        }
        if ((allUv && index.texcoord_index >= uvCount) || (allNormal && index.normal_index >= normalCount)) {
          throw badInput(where(face), "texture coordinate or normal index out of range");
        }
        const CornerKey key{index.vertex_index, allUv ? index.texcoord_index : -1,
                            allNormal ? index.normal_index : -1};
        auto [it, inserted] = corners.try_emplace(key, unsigned(mesh.positions.size()));
        if (inserted) {
          const float* p = &attrib.vertices[3 * std::size_t(key.v)];
          mesh.positions.push_back({p[0], p[1], p[2]});
          if (allUv) uvs.insert(uvs.end(), &attrib.texcoords[2 * std::size_t(key.vt)], &attrib.texcoords[2 * std::size_t(key.vt) + 2]);
          if (allNormal) normals.insert(normals.end(), &attrib.normals[3 * std::size_t(key.vn)], &attrib.normals[3 * std::size_t(key.vn) + 3]);
        }
        polygon.push_back(it->second);
      }
      if (arity == 3) {
        mesh.triangles.push_back({polygon[0], polygon[1], polygon[2]});
      } else {
        std::vector<glm::dvec3> at(arity);
        for (unsigned k = 0; k < arity; ++k) at[k] = glm::dvec3(mesh.positions[polygon[k]]);
        for (const auto& [a, b, c] : triangulatePolygon(at)) mesh.triangles.push_back({polygon[a], polygon[b], polygon[c]});
      }
      offset += arity;
      ++face;
    }
  }
  if (mesh.triangles.empty()) throw badInput(path, "no faces");
  if (allUv) mesh.attributes.push_back({"uv", 2, std::move(uvs)});
  if (allNormal) mesh.attributes.push_back({"normal", 3, std::move(normals)});
  validateMesh(mesh, path);
  return mesh;
}

}  // namespace rc
