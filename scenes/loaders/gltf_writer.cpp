// glTF 2.0 output through nlohmann-json: the buffer, its views and accessors, one mesh, one camera.
#include "scenes/loaders/gltf_writer.h"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <limits>
#include <nlohmann/json.hpp>

#include "core/base64.h"
#include "core/error.h"

namespace rc {
namespace {

using nlohmann::json;

constexpr int kFloat = 5126, kUnsignedInt = 5125;
constexpr int kArrayBuffer = 34962, kElementArrayBuffer = 34963;

const char* typeOf(int components) {
  static const char* types[] = {"SCALAR", "VEC2", "VEC3", "VEC4"};
  return types[std::clamp(components, 1, 4) - 1];
}

// The set number n of an attribute named "uv" (0) or "uv<n>" (n in 1..7) whose components glTF
// allows for the set (TEXCOORD_n: 2, COLOR_n: 3 or 4), or -1.
int setOf(const Attribute& a, const std::string& stem) {
  const bool fits = stem == "uv" ? a.components == 2 : a.components == 3 || a.components == 4;
  if (!fits) return -1;
  if (a.name == stem) return 0;
  if (a.name.size() != stem.size() + 1 || a.name.compare(0, stem.size(), stem) != 0) return -1;
  const char digit = a.name.back();
  return digit >= '1' && digit <= '7' ? digit - '0' : -1;
}

// glTF's name for an attribute, as the loader names them back: NORMAL, TANGENT, TEXCOORD_n ("uv",
// "uv1"...), COLOR_n ("color", "color1"...), else application-specific ("_name"). The
// specification numbers sets from 0 without a gap (3.7.2.1), so a set takes glTF's name only
// when every set below it is in the mesh; one past a gap keeps its own ("_uv1" alone).
std::string semanticOf(const Attribute& a, const Mesh& mesh) {
  if (a.name == "normal" && a.components == 3) return "NORMAL";
  if (a.name == "tangent" && a.components == 4) return "TANGENT";
  for (const auto& [stem, semantic] : {std::pair{"uv", "TEXCOORD_"}, std::pair{"color", "COLOR_"}}) {
    const int set = setOf(a, stem);
    if (set < 0) continue;
    for (int below = 0; below < set; ++below) {
      bool present = false;  // (a loop, not a lambda: Clang 14 cannot capture `stem`, a structured binding)
      for (const Attribute& b : mesh.attributes) present = present || setOf(b, stem) == below;
      if (!present) return "_" + a.name;
    }
    return semantic + std::to_string(set);
  }
  return "_" + a.name;
}

json vec3(const glm::dvec3& v) { return json::array({v.x, v.y, v.z}); }

struct Document {
  std::string bin;
  json views = json::array(), accessors = json::array();

  // Appends the bytes as a buffer view (4-byte aligned) and an accessor over it.
  int add(const void* data, std::size_t bytes, json accessor, int target) {
    while (bin.size() % 4) bin += '\0';
    views.push_back({{"buffer", 0}, {"byteOffset", bin.size()}, {"byteLength", bytes}, {"target", target}});
    bin.append(static_cast<const char*>(data), bytes);
    accessor["bufferView"] = views.size() - 1;
    accessors.push_back(std::move(accessor));
    return int(accessors.size()) - 1;
  }
};

// The mesh as one triangle-list primitive: float positions (with min and max), each attribute
// under semanticOf's name, 32-bit indices in the mesh's triangle order.
json primitiveOf(const Mesh& mesh, Document& d) {
  glm::vec3 low(std::numeric_limits<float>::infinity()), high(-std::numeric_limits<float>::infinity());
  for (const glm::vec3& p : mesh.positions) low = glm::min(low, p), high = glm::max(high, p);
  json attributes;
  attributes["POSITION"] =
      d.add(mesh.positions.data(), mesh.positions.size() * sizeof(glm::vec3),
            {{"componentType", kFloat}, {"count", mesh.positions.size()}, {"type", "VEC3"},
             {"min", {low.x, low.y, low.z}}, {"max", {high.x, high.y, high.z}}},
            kArrayBuffer);
  for (const Attribute& a : mesh.attributes) {
    attributes[semanticOf(a, mesh)] = d.add(a.values.data(), a.values.size() * sizeof(float),
                                            {{"componentType", kFloat}, {"count", mesh.positions.size()}, {"type", typeOf(a.components)}},
                                            kArrayBuffer);
  }
  const int indices = d.add(mesh.triangles.data(), mesh.triangles.size() * sizeof(glm::uvec3),
                            {{"componentType", kUnsignedInt}, {"count", 3 * mesh.triangles.size()}, {"type", "SCALAR"}},
                            kElementArrayBuffer);
  return {{"attributes", attributes}, {"indices", indices}, {"mode", 4}};
}

// The camera's node matrix, column-major (glTF looks down -Z with +Y up): right, up, -forward, eye.
json cameraMatrix(const Camera& camera) {
  json matrix = json::array();
  for (const glm::dvec3& column : {camera.right(), camera.up(), -camera.forward()}) {
    matrix.insert(matrix.end(), {column.x, column.y, column.z, 0.0});
  }
  const glm::dvec3& eye = camera.spec().eye;
  matrix.insert(matrix.end(), {eye.x, eye.y, eye.z, 1.0});
  return matrix;
}

// A perspective camera, with rastercheck's own description in its extras (the loader takes it
// when it agrees with the glTF camera, so eye, target and up survive exactly).
json cameraOf(const CameraSpec& spec) {
  json perspective = {{"yfov", spec.fovYDegrees * M_PI / 180.0},
                      {"aspectRatio", double(spec.width) / double(spec.height)},
                      {"znear", spec.zNear}};
  if (std::isfinite(spec.zFar)) perspective["zfar"] = spec.zFar;
  const json exact = {{"eye", vec3(spec.eye)},
                      {"target", vec3(spec.target)},
                      {"up", vec3(spec.up)},
                      {"fov_y_degrees", spec.fovYDegrees},
                      {"near", spec.zNear},
                      {"far", std::isfinite(spec.zFar) ? json(spec.zFar) : json(nullptr)},
                      {"width", spec.width},
                      {"height", spec.height}};
  return {{"type", "perspective"}, {"perspective", perspective}, {"extras", {{"rastercheck_camera", exact}}}};
}

// GLB: the 12-byte header, the JSON chunk padded with spaces, the BIN chunk padded with zeros.
std::string glbOf(std::string text, std::string bin, const std::string& name) {
  while (text.size() % 4) text += ' ';
  while (bin.size() % 4) bin += '\0';
  const std::uint64_t total = 12 + 8 + std::uint64_t(text.size()) + 8 + bin.size();
  if (total > 0xFFFFFFFFu) throw badInput(name, "is too large for a GLB file (4 GiB at most); write a .gltf");
  const std::uint32_t header[3] = {0x46546C67u, 2, std::uint32_t(total)};
  const std::uint32_t jsonChunk[2] = {std::uint32_t(text.size()), 0x4E4F534Au};
  const std::uint32_t binChunk[2] = {std::uint32_t(bin.size()), 0x004E4942u};
  std::string out(reinterpret_cast<const char*>(header), sizeof header);
  out.append(reinterpret_cast<const char*>(jsonChunk), sizeof jsonChunk).append(text);
  out.append(reinterpret_cast<const char*>(binChunk), sizeof binChunk).append(bin);
  return out;
}

}  // namespace

std::string gltfFromScene(const Scene& scene, bool binary) {
  Document d;
  json gltfMesh = {{"name", scene.name}, {"primitives", {primitiveOf(scene.mesh, d)}}};
  // A claim the loader checks (closedSolidProblem) before it culls back faces.
  if (scene.mesh.closedSolid) gltfMesh["extras"] = {{"rastercheck_closed_solid", true}};
  json buffer = {{"byteLength", d.bin.size()}};
  if (!binary) buffer["uri"] = "data:application/octet-stream;base64," + base64(d.bin);
  const json doc = {
      {"asset", {{"version", "2.0"}, {"generator", "rastercheck " RASTERCHECK_VERSION " (rastercheck export)"}}},
      {"scene", 0},
      {"scenes", {{{"name", scene.name}, {"nodes", {0, 1}}}}},
      {"nodes", {{{"name", scene.name}, {"mesh", 0}}, {{"name", "camera"}, {"camera", 0}, {"matrix", cameraMatrix(scene.camera)}}}},
      {"meshes", {gltfMesh}},
      {"cameras", {cameraOf(scene.camera.spec())}},
      {"buffers", {buffer}},
      {"bufferViews", d.views},
      {"accessors", d.accessors}};
  // Names may hold any bytes a file name does: invalid UTF-8 becomes U+FFFD.
  std::string text = doc.dump(binary ? -1 : 1, ' ', false, json::error_handler_t::replace);
  return binary ? glbOf(std::move(text), std::move(d.bin), scene.name) : text + "\n";
}

}  // namespace rc
