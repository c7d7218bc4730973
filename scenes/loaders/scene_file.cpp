// Scene file parsing and validation. Unknown and duplicate keys are refused, so a typo never
// silently changes what is rendered.
#include "scenes/loaders/scene_file.h"

#include <cmath>
#include <filesystem>
#include <glm/gtc/matrix_transform.hpp>
#include <nlohmann/json.hpp>

#include "core/error.h"
#include "scenes/loaders/framing.h"
#include "scenes/loaders/gltf_loader.h"
#include "scenes/loaders/obj_loader.h"
#include "scenes/loaders/read_file.h"
#include "scenes/scene_loader.h"

namespace rc {
namespace {

namespace fs = std::filesystem;
using Json = nlohmann::json;

constexpr int kMaxNesting = 64;

struct Reader {
  const std::string& path;

  [[noreturn]] void fail(const std::string& pointer, const std::string& what) const {
    throw badInput(path + ": " + (pointer.empty() ? "/" : pointer), what);
  }

  void onlyKeys(const Json& object, const std::string& pointer, std::initializer_list<const char*> keys) const {
    if (!object.is_object()) fail(pointer, "must be an object");
    for (const auto& item : object.items()) {
      const std::string& key = item.key();
      if (std::find_if(keys.begin(), keys.end(), [&](const char* k) { return key == k; }) == keys.end()) {
        fail(pointer + "/" + key, "unknown key");
      }
    }
  }

  double number(const Json& v, const std::string& pointer) const {
    if (!v.is_number()) fail(pointer, "must be a number");
    const double d = v.get<double>();
    if (!std::isfinite(d)) fail(pointer, "must be finite");
    return d;
  }

  glm::dvec3 vec3(const Json& v, const std::string& pointer) const {
    if (!v.is_array() || v.size() != 3) fail(pointer, "must be an array of 3 numbers");
    return {number(v[0], pointer + "/0"), number(v[1], pointer + "/1"), number(v[2], pointer + "/2")};
  }

  int size(const Json& v, const std::string& pointer) const {
    const double d = number(v, pointer);
    if (d != std::floor(d) || d < 1 || d > 16384) fail(pointer, "must be a whole number from 1 to 16384");
    return int(d);
  }

  glm::dmat4 transform(const Json& t, const std::string& pointer) const {
    onlyKeys(t, pointer, {"matrix", "translate", "rotate", "scale"});
    if (t.contains("matrix")) {
      if (t.size() != 1) fail(pointer, "give either matrix or translate/rotate/scale, not both");
      const Json& m = t["matrix"];
      if (!m.is_array() || m.size() != 16) fail(pointer + "/matrix", "must be 16 numbers, column-major");
      glm::dmat4 result;
      for (int i = 0; i < 16; ++i) result[i / 4][i % 4] = number(m[i], pointer + "/matrix/" + std::to_string(i));
      if (!isAffine(result)) fail(pointer + "/matrix", "must be affine: elements 3, 7, 11 and 15 (its last row) must be 0, 0, 0, 1");
      if (!(std::fabs(glm::determinant(glm::dmat3(result))) > 0.0)) fail(pointer + "/matrix", "is singular: it would flatten the mesh");
      return result;
    }
    glm::dmat4 result(1.0);
    if (t.contains("translate")) result = glm::translate(result, vec3(t["translate"], pointer + "/translate"));
    if (t.contains("rotate")) {
      const std::string at = pointer + "/rotate";
      onlyKeys(t["rotate"], at, {"axis", "degrees"});
      if (!t["rotate"].contains("axis") || !t["rotate"].contains("degrees")) fail(at, "needs axis and degrees");
      const glm::dvec3 axis = vec3(t["rotate"]["axis"], at + "/axis");
      if (!(glm::length(axis) > 0.0)) fail(at + "/axis", "must not be zero");
      result = glm::rotate(result, number(t["rotate"]["degrees"], at + "/degrees") * M_PI / 180.0, glm::normalize(axis));
    }
    if (t.contains("scale")) {
      const Json& s = t["scale"];
      const glm::dvec3 factors = s.is_array() ? vec3(s, pointer + "/scale") : glm::dvec3(number(s, pointer + "/scale"));
      if (!(std::fabs(factors.x * factors.y * factors.z) > 0.0)) fail(pointer + "/scale", "must not be zero");
      result = glm::scale(result, factors);
    }
    return result;
  }

  // A mesh path: relative, and inside the scene file's folder even after following links.
  std::string meshPath(const Json& v, const std::string& pointer) const {
    if (!v.is_string() || v.get<std::string>().empty()) fail(pointer, "must be a non-empty string");
    const fs::path relative(v.get<std::string>());
    if (relative.is_absolute()) fail(pointer, "must be relative to the scene file");
    for (const fs::path& part : relative) {
      if (part == "..") fail(pointer, "must stay inside the scene file's folder (no '..')");
    }
    std::error_code ec;
    const fs::path folder = fs::weakly_canonical(fs::absolute(path), ec).parent_path();
    const fs::path full = folder / relative;
    const fs::path resolved = fs::weakly_canonical(full, ec);
    const fs::path inside = resolved.lexically_relative(folder);
    if (ec || inside.empty() || *inside.begin() == "..") fail(pointer, "resolves outside the scene file's folder");
    return full.string();
  }
};

// Parses with a callback that refuses duplicate keys and nesting deeper than kMaxNesting.
Json parseStrict(const std::string& text, const std::string& path) {
  std::vector<std::vector<std::string>> keys;
  std::string pointer;
  const auto callback = [&](int depth, Json::parse_event_t event, Json& parsed) {
    if (depth > kMaxNesting) throw badInput(path, "nesting deeper than " + std::to_string(kMaxNesting) + " levels");
    if (event == Json::parse_event_t::object_start) keys.emplace_back();
    if (event == Json::parse_event_t::object_end && !keys.empty()) keys.pop_back();
    if (event == Json::parse_event_t::key && !keys.empty()) {
      const std::string key = parsed.get<std::string>();
      if (std::find(keys.back().begin(), keys.back().end(), key) != keys.back().end()) {
        throw badInput(path, "duplicate key \"" + key + "\"");
      }
      keys.back().push_back(key);
    }
    return true;
  };
  try {
    return Json::parse(text, callback);
  } catch (const Json::exception& e) {  // syntax errors, and numbers such as 1e999 that overflow
    throw badInput(path, std::string("invalid JSON: ") + e.what());
  }
}

}  // namespace

Scene loadSceneFile(const std::string& path, std::size_t maxTriangles) {
  const Json doc = parseStrict(readInputFile(path), path);
  const Reader r{path};
  r.onlyKeys(doc, "", {"meshes", "camera", "image", "attributes"});
  if (!doc.contains("meshes") || !doc["meshes"].is_array() || doc["meshes"].empty()) {
    r.fail("/meshes", "must be a non-empty array of meshes");
  }
  Mesh mesh;
  for (std::size_t i = 0; i < doc["meshes"].size(); ++i) {
    const std::string at = "/meshes/" + std::to_string(i);
    const Json& entry = doc["meshes"][i];
    r.onlyKeys(entry, at, {"path", "transform"});
    if (!entry.contains("path")) r.fail(at + "/path", "is required");
    const std::string file = r.meshPath(entry["path"], at + "/path");
    const glm::dmat4 transform = entry.contains("transform") ? r.transform(entry["transform"], at + "/transform") : glm::dmat4(1.0);
    const std::string extension = lowerExtension(file);
    if (extension == ".obj") {
      appendMesh(mesh, loadObj(file, {maxTriangles, mesh.triangleCount()}), transform);
    } else if (extension == ".gltf" || extension == ".glb") {
      appendMesh(mesh, loadGltf(file, {maxTriangles, mesh.triangleCount()}).mesh, transform);
    } else {
      r.fail(at + "/path", "must name an .obj, .gltf or .glb file");
    }
  }

  int width = 800, height = 600;
  if (doc.contains("image")) {
    r.onlyKeys(doc["image"], "/image", {"width", "height"});
    if (doc["image"].contains("width")) width = r.size(doc["image"]["width"], "/image/width");
    if (doc["image"].contains("height")) height = r.size(doc["image"]["height"], "/image/height");
  }
  CameraSpec camera = frameMesh(mesh, 45.0, width, height);
  if (doc.contains("camera")) {
    const Json& c = doc["camera"];
    r.onlyKeys(c, "/camera", {"eye", "target", "up", "fov_y_degrees", "near", "far"});
    if (c.contains("eye")) camera.eye = r.vec3(c["eye"], "/camera/eye");
    if (c.contains("target")) camera.target = r.vec3(c["target"], "/camera/target");
    if (c.contains("up")) camera.up = r.vec3(c["up"], "/camera/up");
    if (c.contains("fov_y_degrees")) camera.fovYDegrees = r.number(c["fov_y_degrees"], "/camera/fov_y_degrees");
    if (c.contains("near")) camera.zNear = r.number(c["near"], "/camera/near");
    if (c.contains("far")) {
      camera.zFar = c["far"].is_null() ? std::numeric_limits<double>::infinity() : r.number(c["far"], "/camera/far");
    }
  }
  if (doc.contains("attributes")) {
    const Json& list = doc["attributes"];
    if (!list.is_array()) r.fail("/attributes", "must be an array of attribute names");
    std::vector<std::string> names;
    for (std::size_t i = 0; i < list.size(); ++i) {
      if (!list[i].is_string()) r.fail("/attributes/" + std::to_string(i), "must be a string");
      names.push_back(list[i].get<std::string>());
      if (!mesh.findAttribute(names.back())) {
        r.fail("/attributes/" + std::to_string(i), "'" + names.back() + "' is not carried by every mesh of the scene");
      }
    }
    selectAttributes(mesh, names, path);
  }
  validateMesh(mesh, path);
  return Scene{path, "scene file", std::move(mesh), Camera(camera, path)};
}

}  // namespace rc
