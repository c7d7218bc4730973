// The cameras of a glTF file (gltf_cameras.h) and the names messages give them (gltf_loader.h).
#include "scenes/loaders/gltf_cameras.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <optional>

#include "core/error.h"

namespace rc {
namespace {

// The exact camera `rastercheck export` keeps in a camera's extras, if they hold one that
// agrees with the pose and field of view the glTF camera gives (an edited file's node or yfov
// wins over stale extras).
std::optional<CameraSpec> exactCamera(const tinygltf::Value& extras, const CameraSpec& gltf) {
  if (!extras.IsObject() || !extras.Has("rastercheck_camera")) return std::nullopt;
  const tinygltf::Value& e = extras.Get("rastercheck_camera");
  auto number = [&](const char* key, double& out) {
    if (!e.Has(key) || !e.Get(key).IsNumber()) return false;
    out = e.Get(key).GetNumberAsDouble();
    return true;
  };
  auto vector = [&](const char* key, glm::dvec3& out) {
    if (!e.Has(key) || !e.Get(key).IsArray() || e.Get(key).ArrayLen() != 3) return false;
    for (int i = 0; i < 3; ++i) {
      if (!e.Get(key).Get(i).IsNumber()) return false;
      out[i] = e.Get(key).Get(i).GetNumberAsDouble();
    }
    return true;
  };
  CameraSpec spec = gltf;
  double width = 0, height = 0;
  if (!e.IsObject() || !vector("eye", spec.eye) || !vector("target", spec.target) || !vector("up", spec.up) ||
      !number("fov_y_degrees", spec.fovYDegrees) || !number("near", spec.zNear) || !number("width", width) ||
      !number("height", height)) {
    return std::nullopt;
  }
  spec.zFar = std::numeric_limits<double>::infinity();  // null or absent: infinite
  if (e.Has("far") && e.Get("far").IsNumber()) number("far", spec.zFar);
  if (!(width >= 1 && width <= 16384 && height >= 1 && height <= 16384 && width == std::floor(width) &&
        height == std::floor(height))) {
    return std::nullopt;
  }
  spec.width = int(width);
  spec.height = int(height);
  try {
    Camera(spec, "camera");
  } catch (const Error&) {
    return std::nullopt;
  }
  const glm::dvec3 forward = glm::normalize(spec.target - spec.eye), given = glm::normalize(gltf.target - gltf.eye);
  const double scale = 1.0 + glm::length(gltf.eye);
  const bool agrees = glm::length(spec.eye - gltf.eye) <= 1e-9 * scale && glm::length(forward - given) <= 1e-9 &&
                      std::fabs(spec.fovYDegrees - gltf.fovYDegrees) <= 1e-9 * gltf.fovYDegrees &&
                      std::fabs(spec.zNear - gltf.zNear) <= 1e-12 * gltf.zNear &&
                      (std::isinf(spec.zFar) ? std::isinf(gltf.zFar) : std::fabs(spec.zFar - gltf.zFar) <= 1e-12 * gltf.zFar);
  if (!agrees) return std::nullopt;
  return spec;
}

// A file's name for something, as a message shows it: quoted, at most 64 bytes, controls as '?'.
std::string quotedName(const std::string& name) {
  std::string shown = name.substr(0, 64);
  for (char& c : shown) {
    if (static_cast<unsigned char>(c) < 0x20 || c == 0x7F) c = '?';
  }
  return "\"" + shown + (name.size() > 64 ? "...\"" : "\"");
}

}  // namespace

GltfCamera gltfCamera(const tinygltf::Camera& camera, int index, const glm::dmat4& world, const std::string& path,
                      const std::string& where) {
  GltfCamera out;
  out.index = index;
  out.name = camera.name;
  out.type = camera.type;
  const std::string at = path + ": cameras[" + std::to_string(index) + "]";
  if (camera.type != "perspective") {
    out.refusal = at + ": is " + camera.type + "; only perspective cameras are supported";
    return out;
  }
  const tinygltf::PerspectiveCamera& p = camera.perspective;
  CameraSpec spec;
  spec.eye = glm::dvec3(world * glm::dvec4(0, 0, 0, 1));
  const glm::dvec3 forward(world * glm::dvec4(0, 0, -1, 0)), up(world * glm::dvec4(0, 1, 0, 0));
  if (!(glm::length(forward) > 0.0) || !(glm::length(up) > 0.0)) {
    out.refusal = where + ": the camera's transform collapses its view or up direction to zero";
    return out;
  }
  spec.target = spec.eye + glm::normalize(forward);
  spec.up = glm::normalize(up);
  spec.fovYDegrees = p.yfov * 180.0 / M_PI;
  spec.zNear = p.znear;
  spec.zFar = p.zfar > 0.0 ? p.zfar : std::numeric_limits<double>::infinity();  // 0: infinite
  spec.height = 600;
  spec.width = p.aspectRatio > 0.0 && std::isfinite(p.aspectRatio)
                   ? int(std::clamp(std::lround(600.0 * p.aspectRatio), 1L, 16384L))
                   : 800;
  try {
    Camera(spec, at);  // validates, naming the camera
  } catch (const Error& e) {
    out.refusal = e.what();
    return out;
  }
  if (const std::optional<CameraSpec> exact = exactCamera(camera.extras, spec)) spec = *exact;
  out.spec = spec;
  return out;
}

std::string gltfCameraName(const GltfCamera& camera) {
  return "cameras[" + std::to_string(camera.index) + "]" + (camera.name.empty() ? std::string() : " " + quotedName(camera.name));
}

const GltfCamera* selectGltfCamera(const GltfContent& content, const std::string& selector, const std::string& path) {
  if (selector.empty()) return content.cameras.empty() ? nullptr : &content.cameras.front();
  const bool digits = selector.size() <= 9 && std::all_of(selector.begin(), selector.end(), [](char c) { return c >= '0' && c <= '9'; });
  for (const GltfCamera& camera : content.cameras) {
    if (digits ? camera.index == std::stoi(selector) : camera.name == selector) return &camera;
  }
  throw usageError("--camera " + selector + ": " + path + " places no such camera; " +
                   (content.cameras.empty() ? std::string("it places none") : "it places " + listGltfCameras(content)));
}

std::string listGltfCameras(const GltfContent& content) {
  constexpr std::size_t kListed = 16;  // a file may place any number: a message stays one line
  std::string list;
  for (std::size_t i = 0; i < content.cameras.size(); ++i) {
    if (i == kListed) {
      list += " and " + std::to_string(content.cameras.size() - kListed) + " more";
      break;
    }
    const GltfCamera& camera = content.cameras[i];
    list += (list.empty() ? "" : ", ") + std::to_string(camera.index);
    if (!camera.name.empty()) list += " " + quotedName(camera.name);
    if (!camera.spec) list += camera.type != "perspective" ? " (" + camera.type + ")" : std::string(" (unusable)");
  }
  return list;
}

}  // namespace rc
