// OBJ loading: tinyobjloader parses, this file validates, splits face-varying corners and
// triangulates.
#include "scenes/loaders/obj_loader.h"

#include <tiny_obj_loader.h>

#include <algorithm>
#include <charconv>
#include <cmath>
#include <istream>
#include <sstream>
#include <streambuf>
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

// Calls fn(line, statement) for every line of the text, split where tinyobjloader splits it
// (its safeGetline): at "\n", at "\r\n" and at a lone "\r". The checks below must see the
// statements the parser sees: split at "\n" alone, "# note\rv 0 nan 0" was a comment to them
// and a vertex at (0, 0, 0) to the parser, and a file with classic Mac line endings one long
// line. The next "\n" and "\r" are each found once (memchr), so a run of lone "\r" costs no
// rescans.
template <typename Fn>
void forEachLine(std::string_view text, Fn&& fn) {
  constexpr std::size_t npos = std::string_view::npos;
  std::size_t nextNewline = text.find('\n'), nextReturn = text.find('\r');
  std::size_t line = 1;
  for (std::size_t start = 0; start < text.size(); ++line) {
    if (nextNewline < start) nextNewline = text.find('\n', start);
    if (nextReturn < start) nextReturn = text.find('\r', start);
    std::size_t end = std::min(nextNewline, nextReturn);
    if (end == npos) end = text.size();
    fn(line, text.substr(start, end - start));
    start = end + 1;
    if (end == nextReturn && start == nextNewline) ++start;  // "\r\n" ends one line
  }
}

// How many v, vt and vn statements come before a line: a negative index counts back from the
// last of them.
struct Defined {
  std::size_t v = 0, vt = 0, vn = 0;
};

// What is wrong with a face corner, or nullptr. tinyobjloader's parseTriple reads v, v/vt,
// v//vn or v/vt/vn, each index with atoi, which takes "1.5" as 1, "x" as 0 and "4294967297"
// as 1: so each index must be an optional sign and digits that fit an int, and not 0 (OBJ
// counts from 1; negative indices count back from the end). A negative index must not count
// back past the first of its kind: the parser kept -5 with one vt defined as -4, which then
// read as "no vt", so the face lost its texture coordinates without a word.
const char* faceCornerProblem(std::string_view corner, const Defined& defined) {
  constexpr const char* kNotACorner =
      "is not a face corner (v, v/vt, v//vn or v/vt/vn, each a whole number)";
  constexpr const char* kZero = "is a face corner with an index of 0 (indices start at 1; negative ones count back)";
  constexpr const char* kTooLarge = "is a face corner with an index beyond the 32-bit range";
  const auto index = [&](std::string_view field, std::size_t before, const char* pastFirst) -> const char* {
    if (!field.empty() && field[0] == '+') {
      field.remove_prefix(1);
      if (!field.empty() && field[0] == '-') return kNotACorner;  // atoi reads "+-1" as 0
    }
    int value = 0;
    const auto [ptr, ec] = std::from_chars(field.data(), field.data() + field.size(), value);
    if (ptr != field.data() + field.size() || ptr == field.data()) return kNotACorner;
    if (ec == std::errc::result_out_of_range) return kTooLarge;
    if (ec != std::errc()) return kNotACorner;
    if (value < 0 && std::size_t(-static_cast<long long>(value)) > before) return pastFirst;
    return value == 0 ? kZero : nullptr;
  };
  constexpr const char* kPastV = "is a face corner whose negative v index counts back past the first v above it";
  constexpr const char* kPastVt = "is a face corner whose negative vt index counts back past the first vt above it";
  constexpr const char* kPastVn = "is a face corner whose negative vn index counts back past the first vn above it";
  const std::size_t first = corner.find('/');
  if (first == std::string_view::npos) return index(corner, defined.v, kPastV);
  if (const char* problem = index(corner.substr(0, first), defined.v, kPastV)) return problem;
  const std::string_view rest = corner.substr(first + 1);
  const std::size_t second = rest.find('/');
  if (second == std::string_view::npos) return index(rest, defined.vt, kPastVt);  // v/vt
  if (second > 0) {
    if (const char* problem = index(rest.substr(0, second), defined.vt, kPastVt)) return problem;
  }
  return index(rest.substr(second + 1), defined.vn, kPastVn);
}

// What a v, vt or vn statement of `count` numbers should have been, or nullptr if it is one the
// parser reads in full. It reads a vertex's x, y and z and then a colour (r g b) or nothing, so
// "v 0 0" is (0, 0, 0) to it and w (OBJ's weight for rational curves, which polygons ignore) a
// colour cut short; vt's u and optional v and w; vn's x, y and z, taking what is missing as 0.
const char* numbersProblem(std::string_view keyword, std::size_t count) {
  if (keyword == "v") return count == 3 || count == 4 || count == 6 ? nullptr : "3 (x y z), 4 (x y z w) or 6 (x y z r g b)";
  if (keyword == "vt") return count >= 1 && count <= 3 ? nullptr : "1 to 3 (u [v [w]])";
  return count == 3 ? nullptr : "3 (x y z)";
}

// Checks, in one pass over the lines, what tinyobjloader would misread without a word, and
// returns the line numbers of the face statements ("f ..."), to name the place of a bad face:
// - every number of a v, vt or vn statement must parse completely, with std::from_chars (the
//   locale never matters), and be finite as a float (the parser reads "nan" or "abc" as 0),
//   and the statement must have as many as numbersProblem accepts;
// - every corner of a face must be one faceCornerProblem accepts, and a face must have 3 to
//   kMaxCorners corners (the parser drops a face of 2);
// - the triangles (n - 2 for a face of n corners) must not take the scene past the budget.
std::vector<std::size_t> checkStatements(std::string_view text, const std::string& path, TriangleBudget budget) {
  const auto blank = [](char c) { return c == ' ' || c == '\t'; };
  std::vector<std::size_t> faceLines;
  std::size_t triangles = budget.have;
  Defined defined;
  forEachLine(text, [&](std::size_t line, std::string_view statement) {
    // The keyword, and the tokens after it, split at spaces and tabs as the parser splits them.
    const std::size_t size = statement.size();
    std::size_t start = 0;
    while (start < size && blank(statement[start])) ++start;
    std::size_t keywordEnd = start;
    while (keywordEnd < size && !blank(statement[keywordEnd])) ++keywordEnd;
    if (keywordEnd == size) return;  // blank, or a keyword alone: nothing the parser reads
    const std::string_view keyword = statement.substr(start, keywordEnd - start);
    const bool face = keyword == "f";
    if (!face && keyword != "v" && keyword != "vt" && keyword != "vn") return;
    if (face) faceLines.push_back(line);
    const auto where = [&] { return path + ":" + std::to_string(line); };
    std::size_t items = 0;  // numbers, or a face's corners
    for (std::size_t k = keywordEnd; k < size;) {
      while (k < size && blank(statement[k])) ++k;
      if (k == size) break;
      std::size_t end = k;
      while (end < size && !blank(statement[end])) ++end;
      const std::string_view token = statement.substr(k, end - k);
      if (face) {
        if (const char* problem = faceCornerProblem(token, defined)) {
          throw badInput(where(), "'" + std::string(token.substr(0, 40)) + "' " + problem);
        }
      } else {
        float value = 0.0f;
        const auto [ptr, ec] = std::from_chars(token.data(), token.data() + token.size(), value);
        if (ec != std::errc() || ptr != token.data() + token.size() || !std::isfinite(value)) {
          throw badInput(where(), "'" + std::string(token.substr(0, 40)) + "' is not a finite float");
        }
      }
      ++items;
      k = end;
    }
    if (!face) {
      if (const char* takes = numbersProblem(keyword, items)) {
        throw badInput(where(), std::string(keyword) + " has " + std::to_string(items) + (items == 1 ? " number" : " numbers") +
                                    "; it takes " + takes);
      }
      ++(keyword == "v" ? defined.v : keyword == "vt" ? defined.vt : defined.vn);
      return;
    }
    const std::size_t corners = items;
    if (corners < 3) throw badInput(where(), "face has " + std::to_string(corners) + (corners == 1 ? " corner" : " corners") + "; 3 or more are needed");
    if (corners > kMaxCorners) {
      throw badInput(where(), "face has " + std::to_string(corners) + " corners; at most " + std::to_string(kMaxCorners) +
                                  " are read (split it)");
    }
    const std::size_t adding = corners - 2;
    checkTriangleBudget(triangles, adding, budget.limit, where, [] { return std::string("this face"); });
    triangles += adding;
  });
  return faceLines;
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

// What tinyobjloader read: positions, texture coordinates and normals, and the faces of each
// shape as corner counts and corner indices.
struct ParsedObj {
  tinyobj::attrib_t attrib;
  std::vector<tinyobj::shape_t> shapes;
};

ParsedObj parseObj(std::string_view text, const std::string& path) {
  ParsedObj parsed;
  std::vector<tinyobj::material_t> materials;
  std::string warning, error;
  TextBuffer objText(text);
  std::istream objStream(&objText);
  std::stringbuf noMaterials;  // mtllib is never opened: the parser gets no material text
  std::istream materialStream(&noMaterials);
  tinyobj::MaterialStreamReader materialReader(materialStream);
  // Not triangulated (that is done below, polygon.h, so every face keeps its line); no colours.
  if (!tinyobj::LoadObj(&parsed.attrib, &parsed.shapes, &materials, &warning, &error, &objStream, &materialReader,
                        false, false)) {
    while (!error.empty() && (error.back() == '\n' || error.back() == ' ')) error.pop_back();
    throw badInput(path, "not a valid OBJ file: " + error);
  }
  return parsed;
}

// Where face f (counted from 0 over every shape) is: its line where checkStatements found one
// line per face, else its number.
struct FacePlaces {
  std::string path;
  std::vector<std::size_t> lines;
  bool linesKnown;
  std::string operator()(std::size_t f) const {
    return linesKnown ? path + ":" + std::to_string(lines[f]) : path + ": face " + std::to_string(f + 1);
  }
};

// Calls fn(face, corners, arity) for every face of every shape, in file order: corners points
// at the face's first corner index.
template <typename Fn>
void forEachFace(const std::vector<tinyobj::shape_t>& shapes, Fn&& fn) {
  std::size_t face = 0;
  for (const tinyobj::shape_t& shape : shapes) {
    std::size_t offset = 0;
    for (const unsigned char arity : shape.mesh.num_face_vertices) {
      fn(face++, &shape.mesh.indices[offset], unsigned(arity));
      offset += arity;
    }
  }
}

// The attributes every corner of every face has. An attribute is kept when every corner has it;
// a file where only some faces have it is refused, naming the first face without it.
struct CornerAttributes {
  bool uv = false, normal = false;
};

CornerAttributes cornerAttributes(const std::vector<tinyobj::shape_t>& shapes, const FacePlaces& where) {
  CornerAttributes any;
  for (const tinyobj::shape_t& shape : shapes) {
    for (const tinyobj::index_t& index : shape.mesh.indices) {
      any.uv = any.uv || index.texcoord_index >= 0;
      any.normal = any.normal || index.normal_index >= 0;
    }
  }
  forEachFace(shapes, [&](std::size_t face, const tinyobj::index_t* corners, unsigned arity) {
    for (unsigned k = 0; k < arity; ++k) {
      const tinyobj::index_t& index = corners[k];
      if ((any.uv && index.texcoord_index < 0) || (any.normal && index.normal_index < 0)) {
        throw badInput(where(face), std::string("this face lacks the ") +
                                        (any.uv && index.texcoord_index < 0 ? "texture coordinate (vt)" : "normal (vn)") +
                                        " index that other faces have");
      }
    }
  });
  return any;
}

}  // namespace

Mesh loadObj(const std::string& path, TriangleBudget budget) {
  const PlaneVector<char> bytes = readLargeInputFile(path);
  const std::string_view text(bytes.data(), bytes.size());
  std::vector<std::size_t> lines = checkStatements(text, path, budget);
  const ParsedObj parsed = parseObj(text, path);
  const tinyobj::attrib_t& attrib = parsed.attrib;
  std::size_t faceCount = 0;
  for (const tinyobj::shape_t& shape : parsed.shapes) faceCount += shape.mesh.num_face_vertices.size();
  const bool linesKnown = lines.size() == faceCount;
  const FacePlaces where{path, std::move(lines), linesKnown};
  const CornerAttributes all = cornerAttributes(parsed.shapes, where);

  const int vertexCount = int(attrib.vertices.size() / 3);
  const int uvCount = int(attrib.texcoords.size() / 2);
  const int normalCount = int(attrib.normals.size() / 3);
  Mesh mesh;
  HugeVector<float> uvs, normals;
  // A corner is its (v, vt, vn): corners that share all three share a vertex of the mesh.
  std::unordered_map<CornerKey, unsigned, CornerHash> corners;
  forEachFace(parsed.shapes, [&](std::size_t face, const tinyobj::index_t* faceCorners, unsigned arity) {
    std::vector<unsigned> polygon;
    for (unsigned k = 0; k < arity; ++k) {
      const tinyobj::index_t& index = faceCorners[k];
      if (index.vertex_index < 0 || index.vertex_index >= vertexCount) {
        throw badInput(where(face), "vertex index out of range (the file has " + std::to_string(vertexCount) +
                                        " vertices; indices start at 1, negative ones count back)");
      }
      if (all.uv && index.texcoord_index >= uvCount) {
        throw badInput(where(face), "texture coordinate (vt) index out of range (the file has " + std::to_string(uvCount) + ")");
      }
      if (all.normal && index.normal_index >= normalCount) {
        throw badInput(where(face), "normal (vn) index out of range (the file has " + std::to_string(normalCount) + ")");
      }
      const CornerKey key{index.vertex_index, all.uv ? index.texcoord_index : -1, all.normal ? index.normal_index : -1};
      auto [it, inserted] = corners.try_emplace(key, unsigned(mesh.positions.size()));
      if (inserted) {
        const float* p = &attrib.vertices[3 * std::size_t(key.v)];
        mesh.positions.push_back({p[0], p[1], p[2]});
        if (all.uv) uvs.insert(uvs.end(), &attrib.texcoords[2 * std::size_t(key.vt)], &attrib.texcoords[2 * std::size_t(key.vt) + 2]);
        if (all.normal) normals.insert(normals.end(), &attrib.normals[3 * std::size_t(key.vn)], &attrib.normals[3 * std::size_t(key.vn) + 3]);
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
  });
  if (mesh.triangles.empty()) throw badInput(path, "no faces");
  if (all.uv) mesh.attributes.push_back({"uv", 2, std::move(uvs)});
  if (all.normal) mesh.attributes.push_back({"normal", 3, std::move(normals)});
  validateMesh(mesh, path);
  return mesh;
}

}  // namespace rc
