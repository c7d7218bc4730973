// EXT_meshopt_compression (what gltfpack -c writes): buffer views stored compressed by
// meshoptimizer, decoded with its library before any accessor is read.
#pragma once

#include <tiny_gltf.h>

#include <nlohmann/json.hpp>

#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

namespace rc::gltf {

// One compressed buffer view, as its extension object describes it.
struct MeshoptView {
  int view = -1;          // index into bufferViews
  int buffer = -1;        // where the compressed bytes are
  std::uint64_t byteOffset = 0, byteLength = 0, byteStride = 0, count = 0;
  enum class Mode { kAttributes, kTriangles, kIndices } mode = Mode::kAttributes;
  enum class Filter { kNone, kOctahedral, kQuaternion, kExponential } filter = Filter::kNone;
};

struct MeshoptPlan {
  std::string json;                  // the glTF JSON with every fallback buffer replaced by a 4-byte stub
  std::vector<MeshoptView> views;    // the compressed buffer views
  std::vector<int> fallbackBuffers;  // buffers that hold no data ("fallback": true)
  bool changed = false;              // json differs from the input
};

// Reads the extension objects from the parsed JSON (checkUris's document), checking each field's type and range (errors name
// the JSON path, e.g. "/bufferViews/3/extensions/EXT_meshopt_compression/mode"). A fallback
// buffer has no bytes of its own; tinygltf cannot load such a buffer, so the JSON it gets gives
// it a stub instead.
MeshoptPlan planMeshopt(nlohmann::json doc, const std::string& path);

// For a GLB: the same file with its JSON chunk replaced by `json` (the other chunks as they were).
std::string replaceGlbJson(std::string_view glb, const std::string& json);

// Decodes every compressed view into a buffer of its own and points the view at it, so that the
// model reads as an uncompressed one. Refuses (badInput naming the view) a compressed range
// outside its buffer, data the decoder rejects, a decoded size that differs from the view's
// byteLength, and any other view that reads a fallback buffer.
void decodeMeshopt(tinygltf::Model& model, const MeshoptPlan& plan, const std::string& path);

}  // namespace rc::gltf
