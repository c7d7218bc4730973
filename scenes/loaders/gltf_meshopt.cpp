// EXT_meshopt_compression through meshoptimizer's decoders (Debian: libmeshoptimizer-dev).
#include "scenes/loaders/gltf_meshopt.h"

#include <meshoptimizer.h>

#include <algorithm>
#include <cstring>
#include <nlohmann/json.hpp>

#include "core/error.h"
#include "scenes/loaders/read_file.h"

namespace rc::gltf {
namespace {

constexpr const char* kExtension = "EXT_meshopt_compression";

const nlohmann::json* extensionOf(const nlohmann::json& item) {
  if (!item.is_object() || !item.contains("extensions") || !item["extensions"].is_object()) return nullptr;
  const nlohmann::json& extensions = item["extensions"];
  return extensions.contains(kExtension) ? &extensions[kExtension] : nullptr;
}

std::uint64_t unsignedField(const nlohmann::json& object, const char* name, bool required, const std::string& where) {
  if (!object.contains(name)) {
    if (required) throw badInput(where, std::string("has no ") + name);
    return 0;
  }
  const nlohmann::json& v = object[name];
  if (!v.is_number_unsigned() && !(v.is_number_integer() && v.get<long long>() >= 0)) {
    throw badInput(where + "/" + name, "is not a non-negative integer");
  }
  return v.get<std::uint64_t>();
}

// The value of the string field `name` among `options` (`fallback` when absent, if given).
template <typename E>
E choose(const nlohmann::json& object, const char* name, const char* fallback,
         std::initializer_list<std::pair<const char*, E>> options, const std::string& where) {
  const nlohmann::json* v = object.contains(name) ? &object[name] : nullptr;
  const std::string value = v && v->is_string() ? v->get<std::string>() : !v && fallback ? fallback : "";
  std::string names;
  for (const auto& [text, e] : options) {
    if (value == text) return e;
    names += std::string(names.empty() ? "" : ", ") + text;
  }
  throw badInput(where + "/" + name, "is not one of " + names);
}

}  // namespace

MeshoptPlan planMeshopt(nlohmann::json doc, const std::string& path) {
  MeshoptPlan plan;
  if (!doc.is_object()) return plan;  // tinygltf reports it
  if (doc.contains("bufferViews") && doc["bufferViews"].is_array()) {
    const nlohmann::json& views = doc["bufferViews"];
    for (std::size_t i = 0; i < views.size(); ++i) {
      const nlohmann::json* e = extensionOf(views[i]);
      if (!e) continue;
      const std::string where = path + ": /bufferViews/" + std::to_string(i) + "/extensions/" + kExtension;
      if (!e->is_object()) throw badInput(where, "is not an object");
      MeshoptView v;
      v.view = int(i);
      const std::uint64_t buffer = unsignedField(*e, "buffer", true, where);
      if (buffer > (1u << 30)) throw badInput(where + "/buffer", "is out of range");
      v.buffer = int(buffer);
      v.byteOffset = unsignedField(*e, "byteOffset", false, where);
      v.byteLength = unsignedField(*e, "byteLength", true, where);
      v.byteStride = unsignedField(*e, "byteStride", true, where);
      v.count = unsignedField(*e, "count", true, where);
      v.mode = choose<MeshoptView::Mode>(*e, "mode", nullptr,
                                         {{"ATTRIBUTES", MeshoptView::Mode::kAttributes},
                                          {"TRIANGLES", MeshoptView::Mode::kTriangles},
                                          {"INDICES", MeshoptView::Mode::kIndices}},
                                         where);
      v.filter = choose<MeshoptView::Filter>(*e, "filter", "NONE",
                                             {{"NONE", MeshoptView::Filter::kNone},
                                              {"OCTAHEDRAL", MeshoptView::Filter::kOctahedral},
                                              {"QUATERNION", MeshoptView::Filter::kQuaternion},
                                              {"EXPONENTIAL", MeshoptView::Filter::kExponential}},
                                             where);
      const std::string filter = e->value("filter", "NONE");
      // The decoders' own limits, and the specification's.
      const bool attributes = v.mode == MeshoptView::Mode::kAttributes;
      if (attributes ? (v.byteStride == 0 || v.byteStride % 4 != 0 || v.byteStride > 256)
                     : (v.byteStride != 2 && v.byteStride != 4)) {
        throw badInput(where + "/byteStride", std::to_string(v.byteStride) + (attributes ? " is not a multiple of 4 up to 256"
                                                                                           : " is not 2 or 4"));
      }
      if (v.mode == MeshoptView::Mode::kTriangles && v.count % 3 != 0) {
        throw badInput(where + "/count", std::to_string(v.count) + " is not a multiple of 3");
      }
      if (v.filter != MeshoptView::Filter::kNone && !attributes) throw badInput(where + "/filter", "applies to ATTRIBUTES only");
      if ((v.filter == MeshoptView::Filter::kOctahedral && v.byteStride != 4 && v.byteStride != 8) ||
          (v.filter == MeshoptView::Filter::kQuaternion && v.byteStride != 8)) {
        throw badInput(where + "/byteStride", std::to_string(v.byteStride) + " does not suit the " + filter + " filter");
      }
      if (v.count > (std::uint64_t(1) << 32)) throw badInput(where + "/count", "is over 2^32");
      plan.views.push_back(v);
    }
  }
  if (doc.contains("buffers") && doc["buffers"].is_array()) {
    nlohmann::json& buffers = doc["buffers"];
    for (std::size_t i = 0; i < buffers.size(); ++i) {
      const nlohmann::json* e = extensionOf(buffers[i]);
      if (!e || !e->is_object() || !e->contains("fallback") || (*e)["fallback"] != true) continue;
      plan.fallbackBuffers.push_back(int(i));
      buffers[i].erase("uri");
      buffers[i]["uri"] = "data:application/octet-stream;base64,AAAAAA==";
      buffers[i]["byteLength"] = 4;
      plan.changed = true;
    }
  }
  if (plan.changed) plan.json = doc.dump();
  return plan;
}

std::string replaceGlbJson(std::string_view glb, const std::string& json) {
  std::uint32_t oldLength;
  std::memcpy(&oldLength, glb.data() + 12, 4);  // checked by glbJsonChunk
  const std::string_view rest = glb.substr(20 + std::size_t(oldLength));
  const std::size_t padded = (json.size() + 3) / 4 * 4;
  const std::uint32_t header[5] = {0x46546C67u, 2, std::uint32_t(20 + padded + rest.size()), std::uint32_t(padded), 0x4E4F534Au};
  std::string out;
  out.reserve(sizeof header + padded + rest.size());
  out.append(reinterpret_cast<const char*>(header), sizeof header);
  out += json;
  out.append(padded - json.size(), ' ');
  out += rest;
  return out;
}

void decodeMeshopt(tinygltf::Model& model, const MeshoptPlan& plan, const std::string& path) {
  for (const MeshoptView& v : plan.views) {
    const std::string where = path + ": bufferViews[" + std::to_string(v.view) + "]";
    if (std::size_t(v.view) >= model.bufferViews.size()) continue;  // tinygltf read another document: cannot happen
    if (std::size_t(v.buffer) >= model.buffers.size() ||
        std::find(plan.fallbackBuffers.begin(), plan.fallbackBuffers.end(), v.buffer) != plan.fallbackBuffers.end()) {
      throw badInput(where, std::string(kExtension) + " names buffer " + std::to_string(v.buffer) + ", which holds no data");
    }
    const std::vector<unsigned char>& source = model.buffers[std::size_t(v.buffer)].data;
    if (v.byteOffset > source.size() || v.byteLength > source.size() - v.byteOffset) {
      throw badInput(where, "its compressed range runs past the end of buffer " + std::to_string(v.buffer));
    }
    const std::uint64_t size = v.count * v.byteStride;  // at most 2^32 * 256
    tinygltf::BufferView& view = model.bufferViews[std::size_t(v.view)];
    if (view.byteLength != size) {
      throw badInput(where, "byteLength " + std::to_string(view.byteLength) + " is not count x byteStride (" +
                                std::to_string(size) + ") of its compressed data");
    }
    // meshoptimizer's codecs shrink data at most 64 times (a 2-bit header for 16 zero bytes), so a
    // larger claim is not a stream they wrote: refusing it bounds what a small file can allocate.
    if (size > kMaxInputFileBytes || size > 128 * v.byteLength + 65536) {
      throw badInput(where, "claims " + std::to_string(size) + " bytes decoded from " + std::to_string(v.byteLength) +
                                " compressed, more than meshoptimizer's codecs can expand");
    }
    tinygltf::Buffer decoded;
    decoded.data.resize(std::size_t(size));
    const unsigned char* bytes = source.data() + v.byteOffset;
    int status = 0;
    switch (v.mode) {
      case MeshoptView::Mode::kAttributes:
        status = meshopt_decodeVertexBuffer(decoded.data.data(), v.count, v.byteStride, bytes, v.byteLength);
        break;
      case MeshoptView::Mode::kTriangles:
        status = meshopt_decodeIndexBuffer(decoded.data.data(), v.count, v.byteStride, bytes, v.byteLength);
        break;
      case MeshoptView::Mode::kIndices:
        status = meshopt_decodeIndexSequence(decoded.data.data(), v.count, v.byteStride, bytes, v.byteLength);
        break;
    }
    if (status != 0) throw badInput(where, "its compressed data is invalid (meshoptimizer's decoder returned " + std::to_string(status) + ")");
    switch (v.filter) {
      case MeshoptView::Filter::kNone: break;
      case MeshoptView::Filter::kOctahedral: meshopt_decodeFilterOct(decoded.data.data(), v.count, v.byteStride); break;
      case MeshoptView::Filter::kQuaternion: meshopt_decodeFilterQuat(decoded.data.data(), v.count, v.byteStride); break;
      case MeshoptView::Filter::kExponential: meshopt_decodeFilterExp(decoded.data.data(), v.count, v.byteStride); break;
    }
    model.buffers.push_back(std::move(decoded));
    view.buffer = int(model.buffers.size()) - 1;
    view.byteOffset = 0;
  }
  for (std::size_t i = 0; i < model.bufferViews.size(); ++i) {
    const int buffer = model.bufferViews[i].buffer;
    if (std::find(plan.fallbackBuffers.begin(), plan.fallbackBuffers.end(), buffer) != plan.fallbackBuffers.end()) {
      throw badInput(path + ": bufferViews[" + std::to_string(i) + "]",
                     "reads buffer " + std::to_string(buffer) + ", a fallback that holds no data, without " + kExtension);
    }
  }
}

}  // namespace rc::gltf
