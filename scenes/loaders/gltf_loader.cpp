// glTF loading: tinygltf parses (confined by gltf_checks), this file walks the node hierarchy,
// gathers triangle primitives in world space, and lists the cameras it places (read by
// gltf_cameras).
#include "scenes/loaders/gltf_loader.h"

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <glm/gtc/matrix_transform.hpp>
#include <glm/gtc/quaternion.hpp>
#include <set>

#include "core/error.h"
#include "scenes/loaders/gltf_accessors.h"
#include "scenes/loaders/gltf_cameras.h"
#include "scenes/loaders/gltf_checks.h"
#include "scenes/loaders/gltf_meshopt.h"
#include "scenes/loaders/read_file.h"

namespace rc {
namespace {

constexpr int kMaxNodeDepth = 256;
// TEXCOORD_n and COLOR_n sets read (n < 8): "uv", "uv1"..., "color", "color1"...
constexpr int kMaxSets = 8;
// The most triangles one node's instances (EXT_mesh_gpu_instancing) may make: a few instance
// transforms in a small file could otherwise ask for any amount of memory.
constexpr std::size_t kMaxInstancedTriangles = std::size_t(1) << 26;

// A node's own transform; where() names the node, made only for the error (the ancestry walk of
// every skin joint comes here). A matrix must be affine: glTF requires one that decomposes into
// translation, rotation and scale.
template <typename Where>
glm::dmat4 localMatrix(const tinygltf::Node& node, const Where& where) {
  if (node.matrix.size() == 16) {
    glm::dmat4 m;
    for (int c = 0; c < 4; ++c) {
      for (int r = 0; r < 4; ++r) m[c][r] = node.matrix[std::size_t(c * 4 + r)];  // column-major
    }
    if (!isAffine(m)) throw badInput(where() + ": matrix", "is not affine: elements 3, 7, 11 and 15 (its last row) must be 0, 0, 0, 1");
    return m;
  }
  glm::dmat4 m(1.0);
  if (node.translation.size() == 3) {
    m = glm::translate(m, glm::dvec3(node.translation[0], node.translation[1], node.translation[2]));
  }
  if (node.rotation.size() == 4) {  // glTF stores x, y, z, w; GLM's constructor takes w first
    m *= glm::mat4_cast(glm::normalize(glm::dquat(node.rotation[3], node.rotation[0], node.rotation[1], node.rotation[2])));
  }
  if (node.scale.size() == 3) m = glm::scale(m, glm::dvec3(node.scale[0], node.scale[1], node.scale[2]));
  return m;
}

bool finiteMatrix(const glm::dmat4& m) {
  for (int c = 0; c < 4; ++c) {
    for (int r = 0; r < 4; ++r) {
      if (!std::isfinite(m[c][r])) return false;
    }
  }
  return true;
}

// The triangles of a primitive's vertex order (its indices, or 0, 1, 2, ... without), each
// with its vertices in the order glTF 2.0 defines (3.7.2.1, "Topology types"), since a
// triangle's barycentrics follow its vertex order: triangle i of a list is (v_3i, v_3i+1,
// v_3i+2), of a strip (v_i, v_i+1+i%2, v_i+2-i%2), which keeps every triangle's winding, and
// of a fan (v_i+1, v_i+2, v_0). A count the topology cannot take is refused, as the
// specification requires: a list's must be a non-zero multiple of 3, a strip's or fan's 3 or more.
HugeVector<glm::uvec3> assembleTriangles(const HugeVector<unsigned>& order, int mode, const std::string& where) {
  const std::size_t n = order.size();
  HugeVector<glm::uvec3> triangles;
  if (mode == TINYGLTF_MODE_TRIANGLES) {
    if (n == 0 || n % 3 != 0) {
      throw badInput(where, std::to_string(n) + " vertices do not make whole triangles (mode TRIANGLES takes a non-zero multiple of 3)");
    }
    triangles.reserve(n / 3);
    for (std::size_t i = 0; i < n; i += 3) triangles.push_back({order[i], order[i + 1], order[i + 2]});
    return triangles;
  }
  const bool strip = mode == TINYGLTF_MODE_TRIANGLE_STRIP;
  if (n < 3) {
    throw badInput(where, std::to_string(n) + " vertices are too few for mode " +
                              (strip ? "TRIANGLE_STRIP" : "TRIANGLE_FAN") + " (it takes 3 or more)");
  }
  triangles.reserve(n - 2);
  for (std::size_t i = 0; i + 2 < n; ++i) {
    const std::size_t odd = i % 2;
    triangles.push_back(strip ? glm::uvec3(order[i], order[i + 1 + odd], order[i + 2 - odd])
                              : glm::uvec3(order[i + 1], order[i + 2], order[0]));
  }
  return triangles;
}

// Extensions a file may require that rastercheck can honour: KHR_mesh_quantization,
// EXT_meshopt_compression and EXT_mesh_gpu_instancing are read; the
// others concern materials, textures and lights, which rastercheck never uses (it interpolates
// the stored TEXCOORD_n, before any texture transform).
bool honouredExtension(const std::string& e) {
  return e == "KHR_mesh_quantization" || e == "EXT_meshopt_compression" || e == "EXT_mesh_gpu_instancing" ||
         e == "KHR_texture_transform" || e == "KHR_texture_basisu" || e == "EXT_texture_webp" || e == "EXT_texture_avif" ||
         e == "KHR_lights_punctual" || e.rfind("KHR_materials_", 0) == 0;
}

struct Walker {
  const tinygltf::Model& model;
  const std::string& path;
  gltf::AccessorReader reader;
  GltfContent content;
  std::set<int> onPath;  // nodes on the current root-to-node path: a repeat is a cycle
  std::vector<char> cameraPlaced;  // per camera: already met in the hierarchy

  // Adds the primitive's morph targets' displacements of `name` to `values` at `weights` (every
  // target is read, so a bad one is refused even at weight 0). A displacement has `components`
  // values a vertex, added to the first of the vertex's `stride` (TANGENT's displacements leave
  // its w alone).
  void morph(const tinygltf::Primitive& primitive, const std::vector<double>& weights, const char* name, gltf::Use use,
             int components, HugeVector<float>& values, const std::string& where, int stride = 0) const {
    if (stride == 0) stride = components;
    std::vector<double> sum;
    for (std::size_t t = 0; t < primitive.targets.size(); ++t) {
      auto it = primitive.targets[t].find(name);
      if (it == primitive.targets[t].end()) continue;
      const HugeVector<float> d = reader.floats(it->second, use, components, true);
      if (d.size() / std::size_t(components) != values.size() / std::size_t(stride)) {
        throw badInput(where + ".targets[" + std::to_string(t) + "]", std::string(name) + " count differs from the primitive's");
      }
      const double w = t < weights.size() ? weights[t] : 0.0;
      if (w == 0.0) continue;
      if (sum.empty()) sum.assign(values.begin(), values.end());
      for (std::size_t i = 0; i < d.size(); ++i) sum[i / std::size_t(components) * std::size_t(stride) + i % std::size_t(components)] += w * double(d[i]);
    }
    for (std::size_t i = 0; i < sum.size(); ++i) values[i] = float(sum[i]);
  }

  // `weights`: the morph target weights in force (the node's, else the mesh's; empty: all 0).
  Mesh readPrimitive(const tinygltf::Primitive& primitive, const std::vector<double>& weights, const std::string& where) const {
    const auto& attrs = primitive.attributes;
    const auto position = attrs.find("POSITION");  // there: visit skips primitives without one
    if (!weights.empty() && weights.size() != primitive.targets.size()) {
      throw badInput(where, "has " + std::to_string(primitive.targets.size()) + " morph targets, but " +
                                std::to_string(weights.size()) + " weights are given");
    }
    Mesh part;
    HugeVector<float> p = reader.floats(position->second, gltf::Use::kPosition, 3);
    morph(primitive, weights, "POSITION", gltf::Use::kPosition, 3, p, where);
    for (std::size_t i = 0; i + 2 < p.size(); i += 3) part.positions.push_back({p[i], p[i + 1], p[i + 2]});
    struct Known {
      std::string gltf, name;
      int components[2];  // the usual count, and another the specification allows (COLOR_n: RGB or RGBA)
      gltf::Use use;
      int displaced = 0;  // components a morph target displaces, if not all
    };
    std::vector<Known> known = {{"NORMAL", "normal", {3, 3}, gltf::Use::kNormal},
                                {"TANGENT", "tangent", {4, 4}, gltf::Use::kTangent, 3}};
    for (int set = 0; set < kMaxSets; ++set) {  // uv, uv1, ..., color, color1, ...
      const std::string suffix = set ? std::to_string(set) : "";
      known.push_back({"TEXCOORD_" + std::to_string(set), "uv" + suffix, {2, 2}, gltf::Use::kTexcoord});
      known.push_back({"COLOR_" + std::to_string(set), "color" + suffix, {3, 4}, gltf::Use::kColor});
    }
    for (const Known& spec : known) {
      auto it = attrs.find(spec.gltf);
      if (it == attrs.end()) continue;
      const int n = (it->second >= 0 && std::size_t(it->second) < model.accessors.size())
                        ? tinygltf::GetNumComponentsInType(std::uint32_t(model.accessors[std::size_t(it->second)].type))
                        : spec.components[0];
      const int components = (n == spec.components[1]) ? n : spec.components[0];
      HugeVector<float> values = reader.floats(it->second, spec.use, components);
      if (values.size() != part.positions.size() * std::size_t(components)) {
        throw badInput(where, spec.gltf + " count differs from POSITION count");
      }
      morph(primitive, weights, spec.gltf.c_str(), spec.use, spec.displaced ? spec.displaced : components, values, where, components);
      part.attributes.push_back({spec.name, components, std::move(values)});
    }
    // Application-specific attributes ("_name", as rastercheck export writes them) whose name
    // can be a channel name and is not taken, in the order of their accessors (the order they
    // were written in).
    std::vector<std::pair<int, std::string>> custom;
    for (const auto& [semantic, index] : attrs) custom.emplace_back(index, semantic);
    std::sort(custom.begin(), custom.end());
    for (const auto& [index, semantic] : custom) {
      if (semantic.size() < 2 || semantic[0] != '_') continue;
      const std::string name = semantic.substr(1);
      if (!validAttributeName(name) || part.findAttribute(name)) continue;
      const int components = index >= 0 && std::size_t(index) < model.accessors.size()
                                 ? tinygltf::GetNumComponentsInType(std::uint32_t(model.accessors[std::size_t(index)].type))
                                 : 1;
      if (components < 1 || components > 4) continue;
      HugeVector<float> values = reader.floats(index, gltf::Use::kCustom, components);
      if (values.size() != part.positions.size() * std::size_t(components)) {
        throw badInput(where, semantic + " count differs from POSITION count");
      }
      morph(primitive, weights, semantic.c_str(), gltf::Use::kCustom, components, values, where);
      part.attributes.push_back({name, components, std::move(values)});
    }
    HugeVector<unsigned> order;
    if (primitive.indices >= 0) {
      order = reader.indices(primitive.indices, part.positions.size());
    } else {
      for (unsigned i = 0; i < part.positions.size(); ++i) order.push_back(i);
    }
    part.triangles = assembleTriangles(order, primitive.mode, where);
    return part;
  }

  std::vector<int> parents;  // each node's parent (-1: a root), made on first use
  TriangleBudget budget;  // placing more is refused (checkTriangleBudget)

  // A node's world transform, from its ancestors (a skin's joints need not lie on the walk).
  glm::dmat4 worldOf(int index) {
    if (parents.empty()) {
      parents.assign(model.nodes.size(), -1);
      for (std::size_t i = 0; i < model.nodes.size(); ++i) {
        for (int c : model.nodes[i].children) {
          if (c >= 0 && std::size_t(c) < parents.size()) parents[std::size_t(c)] = int(i);
        }
      }
    }
    glm::dmat4 m(1.0);
    int depth = 0;
    for (int n = index; n >= 0; n = parents[std::size_t(n)]) {
      if (++depth > kMaxNodeDepth) {
        throw badInput(path + ": nodes[" + std::to_string(index) + "]", "ancestry deeper than " + std::to_string(kMaxNodeDepth) + " or cyclic");
      }
      m = localMatrix(model.nodes[std::size_t(n)], [&] { return path + ": nodes[" + std::to_string(n) + "]"; }) * m;
    }
    return m;
  }

  // Poses a skinned primitive as its joints' nodes stand (no animation is played): each vertex by
  // the weighted sum of its joints' world transform times inverse bind matrix, as glTF specifies;
  // the mesh node's own transform does not apply. Positions, normals and tangents end in world space.
  void applySkin(int skinIndex, const tinygltf::Primitive& primitive, Mesh& part, const std::string& where) {
    gltf::requireChecked(skinIndex, model.skins.size(), where + ": skin");
    const tinygltf::Skin& skin = model.skins[std::size_t(skinIndex)];
    const std::string at = path + ": skins[" + std::to_string(skinIndex) + "]";
    HugeVector<float> inverseBind;
    if (skin.inverseBindMatrices >= 0) {
      inverseBind = reader.floats(skin.inverseBindMatrices, gltf::Use::kMatrix, 16);
      if (inverseBind.size() < 16 * skin.joints.size()) throw badInput(at, "has fewer inverseBindMatrices than joints");
    }
    std::vector<glm::dmat4> joints;
    for (std::size_t j = 0; j < skin.joints.size(); ++j) {
      const int node = skin.joints[j];
      gltf::requireChecked(node, model.nodes.size(), at + ": joint");
      glm::dmat4 bind(1.0);
      for (std::size_t k = 0; k < 16 && !inverseBind.empty(); ++k) bind[int(k / 4)][int(k % 4)] = inverseBind[16 * j + k];
      joints.push_back(worldOf(node) * bind);
      if (!finiteMatrix(joints.back())) throw badInput(at, "joint " + std::to_string(j) + "'s transform is not finite");
    }
    const std::size_t vertices = part.positions.size();
    std::vector<HugeVector<float>> indices, weights;  // per set of four influences
    for (int set = 0;; ++set) {
      const auto j = primitive.attributes.find("JOINTS_" + std::to_string(set));
      const auto w = primitive.attributes.find("WEIGHTS_" + std::to_string(set));
      if (j == primitive.attributes.end() && w == primitive.attributes.end()) break;
      if (j == primitive.attributes.end() || w == primitive.attributes.end()) {
        throw badInput(where, "has only one of JOINTS_" + std::to_string(set) + " and WEIGHTS_" + std::to_string(set));
      }
      indices.push_back(reader.floats(j->second, gltf::Use::kJoints, 4));
      weights.push_back(reader.floats(w->second, gltf::Use::kWeights, 4));
      if (indices.back().size() != 4 * vertices || weights.back().size() != 4 * vertices) {
        throw badInput(where, "JOINTS_" + std::to_string(set) + " or WEIGHTS_" + std::to_string(set) + " count differs from POSITION count");
      }
      for (std::size_t i = 0; i < 4 * vertices; ++i) {
        if (weights.back()[i] != 0.0f && indices.back()[i] >= float(joints.size())) {
          throw badInput(path + ": accessors[" + std::to_string(j->second) + "]",
                         "joint " + std::to_string(unsigned(indices.back()[i])) + " of vertex " + std::to_string(i / 4) +
                             " is not below the skin's " + std::to_string(joints.size()) + " joints");
        }
      }
    }
    if (indices.empty()) throw badInput(where, "is skinned (its node names a skin) but has no JOINTS_0 and WEIGHTS_0");
    Attribute *normal = nullptr, *tangent = nullptr;
    for (Attribute& a : part.attributes) {
      if (a.name == "normal" && a.components == 3) normal = &a;
      if (a.name == "tangent" && a.components == 4) tangent = &a;
    }
    for (std::size_t v = 0; v < vertices; ++v) {
      glm::dmat4 blend(0.0);
      for (std::size_t set = 0; set < indices.size(); ++set) {
        for (std::size_t k = 4 * v; k < 4 * v + 4; ++k) {
          if (weights[set][k] != 0.0f) blend += double(weights[set][k]) * joints[std::size_t(indices[set][k])];
        }
      }
      part.positions[v] = glm::vec3(blend * glm::dvec4(glm::dvec3(part.positions[v]), 1.0));
      const glm::dmat3 linear(blend);
      if (tangent) {
        float* t = tangent->values.data() + 4 * v;
        const glm::dvec4 moved = movedTangent(linear, glm::dvec4(t[0], t[1], t[2], t[3]));
        for (int c = 0; c < 4; ++c) t[c] = float(moved[c]);  // appendMesh renormalises
      }
      if (!normal || !(std::fabs(glm::determinant(linear)) > 0.0)) continue;
      float* n = normal->values.data() + 3 * v;
      const glm::dvec3 moved = glm::transpose(glm::inverse(linear)) * glm::dvec3(n[0], n[1], n[2]);
      for (int c = 0; c < 3; ++c) n[c] = float(moved[c]);  // appendMesh renormalises
    }
  }

  // EXT_mesh_gpu_instancing: the node's mesh drawn once per instance, at the node's world
  // transform times the instance's translation, rotation and scale; without it, once.
  std::vector<glm::dmat4> instancesOf(const tinygltf::Node& node, const glm::dmat4& world, std::size_t triangles,
                                      const std::string& where) const {
    const auto it = node.extensions.find("EXT_mesh_gpu_instancing");
    if (it == node.extensions.end()) return {world};
    const std::string at = where + ": extensions/EXT_mesh_gpu_instancing";
    const tinygltf::Value& e = it->second;
    if (!e.IsObject() || !e.Has("attributes") || !e.Get("attributes").IsObject()) throw badInput(at, "has no attributes object");
    const tinygltf::Value& attributes = e.Get("attributes");
    HugeVector<float> values[3];  // translation, rotation, scale
    const struct { const char* name; gltf::Use use; int components; } kFields[] = {
        {"TRANSLATION", gltf::Use::kMatrix, 3}, {"ROTATION", gltf::Use::kRotation, 4}, {"SCALE", gltf::Use::kMatrix, 3}};
    std::size_t count = 0;
    bool any = false;
    for (int f = 0; f < 3; ++f) {
      if (!attributes.Has(kFields[f].name)) continue;
      const tinygltf::Value& index = attributes.Get(kFields[f].name);
      if (!index.IsInt()) throw badInput(at + "/attributes/" + kFields[f].name, "is not an accessor index");
      values[f] = reader.floats(index.Get<int>(), kFields[f].use, kFields[f].components);
      const std::size_t n = values[f].size() / std::size_t(kFields[f].components);
      if (any && n != count) throw badInput(at, std::string(kFields[f].name) + " has " + std::to_string(n) + " instances, not " + std::to_string(count));
      count = n;
      any = true;
    }
    if (!any) throw badInput(at, "has none of TRANSLATION, ROTATION and SCALE");
    if (count * std::max<std::size_t>(triangles, 1) > kMaxInstancedTriangles) {
      throw badInput(at, std::to_string(count) + " instances of " + std::to_string(triangles) + " triangles are more than " +
                             std::to_string(kMaxInstancedTriangles) + " triangles");
    }
    std::vector<glm::dmat4> matrices;
    for (std::size_t i = 0; i < count; ++i) {
      glm::dmat4 m = world;
      if (!values[0].empty()) m = glm::translate(m, glm::dvec3(values[0][3 * i], values[0][3 * i + 1], values[0][3 * i + 2]));
      if (!values[1].empty()) {
        const glm::dquat q(values[1][4 * i + 3], values[1][4 * i], values[1][4 * i + 1], values[1][4 * i + 2]);
        if (!(glm::length(q) > 0.0)) throw badInput(at, "ROTATION of instance " + std::to_string(i) + " is zero");
        m *= glm::mat4_cast(glm::normalize(q));
      }
      if (!values[2].empty()) m = glm::scale(m, glm::dvec3(values[2][3 * i], values[2][3 * i + 1], values[2][3 * i + 2]));
      if (!finiteMatrix(m) || !(std::fabs(glm::determinant(glm::dmat3(m))) > 0.0)) {
        throw badInput(at, "instance " + std::to_string(i) + "'s transform is not finite and invertible");
      }
      matrices.push_back(m);
    }
    return matrices;
  }

  void readCamera(int index, const glm::dmat4& world, const std::string& where) {
    gltf::requireChecked(index, model.cameras.size(), where + ": camera");
    if (cameraPlaced.empty()) cameraPlaced.assign(model.cameras.size(), 0);
    if (cameraPlaced[std::size_t(index)]) return;  // placed again by a later node: the first placement counts
    cameraPlaced[std::size_t(index)] = 1;
    content.cameras.push_back(gltfCamera(model.cameras[index], index, world, path, where));
  }

  void visit(int index, const glm::dmat4& parent, int depth) {
    const std::string where = path + ": nodes[" + std::to_string(index) + "]";
    gltf::requireChecked(index, model.nodes.size(), where);
    if (depth > kMaxNodeDepth) throw badInput(where, "node hierarchy deeper than " + std::to_string(kMaxNodeDepth));
    if (!onPath.insert(index).second) throw badInput(where, "the node hierarchy has a cycle");
    const tinygltf::Node& node = model.nodes[index];
    const glm::dmat4 world = parent * localMatrix(node, [&] { return where; });
    if (!finiteMatrix(world)) throw badInput(where, "transform is not finite");
    if (node.camera >= 0) readCamera(node.camera, world, where);
    if (node.mesh >= 0) {
      gltf::requireChecked(node.mesh, model.meshes.size(), where + ": mesh");
      const bool skinned = node.skin >= 0;  // then the joints place it, not the node
      const double det = glm::determinant(glm::dmat3(world));
      if (!skinned && !(std::fabs(det) > 0.0)) throw badInput(where, "transform is not invertible");
      const auto& primitives = model.meshes[node.mesh].primitives;
      const std::vector<double>& weights = node.weights.empty() ? model.meshes[node.mesh].weights : node.weights;
      std::vector<Mesh> parts;
      std::size_t triangles = 0;
      for (std::size_t i = 0; i < primitives.size(); ++i) {
        // tinygltf gives TRIANGLES where the file has no mode; checkFields has refused any but 0 to 6.
        const int mode = primitives[i].mode;
        const std::string at = path + ": meshes[" + std::to_string(node.mesh) + "].primitives[" + std::to_string(i) + "]";
        if (mode < TINYGLTF_MODE_TRIANGLES) continue;  // points and lines: no surface
        // Nor a primitive without positions, which the specification says to skip (3.7.2.1).
        if (primitives[i].attributes.count("POSITION") == 0) continue;
        parts.push_back(readPrimitive(primitives[i], weights, at));
        if (skinned) applySkin(node.skin, primitives[i], parts.back(), at);
        triangles += parts.back().triangleCount();
      }
      // A skinned mesh is placed by its joints alone (and is not instanced).
      const std::vector<glm::dmat4> placements = skinned ? std::vector<glm::dmat4>{glm::dmat4(1.0)} : instancesOf(node, world, triangles, where);
      // instancesOf keeps placements x triangles within 2^26: the product does not overflow.
      checkTriangleBudget(budget.have + content.mesh.triangleCount(), placements.size() * triangles, budget.limit,
                          [&] { return where; }, [&] { return "placing meshes[" + std::to_string(node.mesh) + "]"; });
      for (const glm::dmat4& m : placements) {
        for (const Mesh& part : parts) appendMesh(content.mesh, part, m);
      }
    }
    for (int child : node.children) visit(child, world, depth + 1);
    onPath.erase(index);
  }
};

}  // namespace

GltfContent loadGltf(const std::string& path, TriangleBudget budget) {
  const PlaneVector<char> file = readLargeInputFile(path);
  const std::string_view bytes(file.data(), file.size());
  const bool binary = bytes.substr(0, 4) == "glTF";
  const std::string chunk = binary ? gltf::glbJsonChunk(bytes, path) : std::string();
  const std::string_view json = binary ? std::string_view(chunk) : bytes;
  gltf::EmbeddedData embedded = gltf::takeDataUris(json, path);
  nlohmann::json doc = gltf::parseJson(json, embedded, path);
  gltf::checkUris(doc, embedded, path);
  gltf::checkFields(doc, path);
  const gltf::MeshoptPlan meshopt = gltf::planMeshopt(std::move(doc), path);
  // The JSON tinygltf reads: the meshopt plan's, else the one without data URIs, else the file's.
  const std::string& newJson = meshopt.changed ? meshopt.json : embedded.json;
  const std::string input = newJson.empty() ? std::string() : binary ? gltf::replaceGlbJson(bytes, newJson) : newJson;
  const std::string_view text = newJson.empty() ? bytes : std::string_view(input);

  std::error_code ec;
  gltf::LoaderFiles files{std::filesystem::weakly_canonical(std::filesystem::absolute(path), ec).parent_path().string(),
                          std::move(embedded.buffers)};
  tinygltf::TinyGLTF loader;
  gltf::confineLoader(loader, &files);
  tinygltf::Model model;
  std::string err, warn;
  const bool ok = binary ? loader.LoadBinaryFromMemory(&model, &err, &warn, reinterpret_cast<const unsigned char*>(text.data()),
                                                       unsigned(text.size()), files.folder)
                         : loader.LoadASCIIFromString(&model, &err, &warn, text.data(), unsigned(text.size()), files.folder);
  if (!ok) throw badInput(path, "not a valid glTF 2.0 file: " + gltf::clippedLines(err));
  if (model.asset.version.rfind("2.", 0) != 0) throw badInput(path + ": /asset/version", "'" + model.asset.version + "' is not 2.x");
  std::string unread;
  for (const std::string& e : model.extensionsRequired) {
    if (!honouredExtension(e)) unread += (unread.empty() ? "" : ", ") + e;
  }
  if (!unread.empty()) throw badInput(path + ": /extensionsRequired", "needs extensions rastercheck does not read: " + unread);
  gltf::decodeMeshopt(model, meshopt, path);

  Walker walker{model, path, gltf::AccessorReader(model, path), {}, {}, {}, {}, budget};
  std::vector<int> roots;
  if (!model.scenes.empty()) {
    const int scene = model.defaultScene >= 0 ? model.defaultScene : 0;
    gltf::requireChecked(scene, model.scenes.size(), path + ": /scene");
    roots = model.scenes[scene].nodes;
  } else {  // no scenes: every node that is nobody's child
    std::vector<bool> child(model.nodes.size(), false);
    for (const auto& node : model.nodes) {
      for (int c : node.children) {
        if (c >= 0 && std::size_t(c) < child.size()) child[c] = true;
      }
    }
    for (std::size_t i = 0; i < child.size(); ++i) {
      if (!child[i]) roots.push_back(int(i));
    }
  }
  for (int root : roots) walker.visit(root, glm::dmat4(1.0), 0);
  if (walker.content.mesh.triangles.empty()) {
    throw badInput(path, "no triangle primitives in the scene (points, lines and primitives without POSITION draw none)");
  }
  validateMesh(walker.content.mesh, path);
  // A file whose every mesh claims to bound a solid (as `rastercheck export` writes a closed
  // built-in scene) is believed once the scene it makes passes the check; else its back faces
  // are drawn, which is always safe.
  const bool claimed = std::all_of(model.meshes.begin(), model.meshes.end(), [](const tinygltf::Mesh& m) {
    return m.extras.IsObject() && m.extras.Has("rastercheck_closed_solid") && m.extras.Get("rastercheck_closed_solid").IsBool() &&
           m.extras.Get("rastercheck_closed_solid").Get<bool>();
  });
  walker.content.mesh.closedSolid = claimed && closedSolidProblem(walker.content.mesh).empty();
  return std::move(walker.content);
}

}  // namespace rc
