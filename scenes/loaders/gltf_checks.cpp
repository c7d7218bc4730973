// GLB container checks, URI vetting, bounds-checked accessor reads, confined file callbacks.
#include "scenes/loaders/gltf_checks.h"

#include <algorithm>
#include <cstdint>
#include <cstring>
#include <filesystem>
#include <string_view>
#include <nlohmann/json.hpp>

#include "core/error.h"
#include "scenes/loaders/read_file.h"

namespace rc::gltf {
namespace {

namespace fs = std::filesystem;

std::uint32_t readU32(std::string_view bytes, std::size_t offset) {
  std::uint32_t value;
  std::memcpy(&value, bytes.data() + offset, 4);  // GLB is little-endian, as is x86-64
  return value;
}

std::string at(const std::string& path, std::size_t offset) {
  return path + ": byte " + std::to_string(offset);
}

bool insideFolder(const std::string& file, const std::string& folder) {
  std::error_code ec;
  const fs::path canonical = fs::weakly_canonical(file, ec);
  if (ec) return false;
  const fs::path relative = canonical.lexically_relative(folder);
  return !relative.empty() && *relative.begin() != ".." && !relative.is_absolute();
}

}  // namespace

std::string glbJsonChunk(std::string_view bytes, const std::string& path) {
  if (bytes.size() < 20) throw badInput(at(path, 0), "too short for a GLB header and JSON chunk");
  if (readU32(bytes, 0) != 0x46546C67u) throw badInput(at(path, 0), "wrong magic, not 'glTF'");
  if (readU32(bytes, 4) != 2) throw badInput(at(path, 4), "GLB version " + std::to_string(readU32(bytes, 4)) + ", expected 2");
  if (readU32(bytes, 8) != bytes.size()) {
    throw badInput(at(path, 8), "declared length " + std::to_string(readU32(bytes, 8)) + " is not the file size " +
                                    std::to_string(bytes.size()));
  }
  const std::uint64_t chunkLength = readU32(bytes, 12);
  if (readU32(bytes, 16) != 0x4E4F534Au) throw badInput(at(path, 16), "first chunk is not JSON");
  if (20 + chunkLength > bytes.size()) {
    throw badInput(at(path, 12), "JSON chunk length " + std::to_string(chunkLength) + " runs past the end of the file");
  }
  return std::string(bytes.substr(20, std::size_t(chunkLength)));
}

nlohmann::json parseJson(std::string_view original, const EmbeddedData& embedded, const std::string& path) {
  try {
    return nlohmann::json::parse(embedded.changed() ? std::string_view(embedded.json) : original);
  } catch (const nlohmann::json::exception& e) {
    if (!embedded.changed()) throw badInput(path, std::string("invalid JSON: ") + e.what());
  }
  try {  // the error's place in the file's own text
    return nlohmann::json::parse(original);
  } catch (const nlohmann::json::exception& e) {
    throw badInput(path, std::string("invalid JSON: ") + e.what());
  }
}

void checkUris(const nlohmann::json& doc, const EmbeddedData& embedded, const std::string& path) {
  if (!doc.is_object()) return;  // tinygltf reports it
  for (const char* array : {"buffers", "images"}) {
    if (!doc.contains(array) || !doc[array].is_array()) continue;
    for (std::size_t i = 0; i < doc[array].size(); ++i) {
      const nlohmann::json& item = doc[array][i];
      if (!item.is_object() || !item.contains("uri")) continue;
      const std::string where = path + ": /" + array + "/" + std::to_string(i) + "/uri";
      if (!item["uri"].is_string()) throw badInput(where, "is not a string");
      const std::string uri = item["uri"].get<std::string>();
      if (const auto taken = embedded.buffers.find(uri); taken != embedded.buffers.end() && std::string_view(array) == "buffers") {
        const std::size_t size = taken->second.size();
        if (size == 0) throw badInput(where, "is a data: URI that holds no bytes");
        const nlohmann::json* length = item.contains("byteLength") ? &item["byteLength"] : nullptr;
        if (length && length->is_number_unsigned() && length->get<std::uint64_t>() != size) {
          throw badInput(path + ": /buffers/" + std::to_string(i) + "/byteLength",
                         "is " + std::to_string(length->get<std::uint64_t>()) + ", but the buffer's data: URI holds " +
                             std::to_string(size) + " bytes");
        }
        continue;  // otherwise tinygltf reports a byteLength that is missing or not a count
      }
      if (uri.rfind("data:", 0) == 0) continue;
      if (uri.empty() || uri[0] == '/' || uri.find('\\') != std::string::npos ||
          uri.find(':') != std::string::npos) {
        throw badInput(where, "'" + uri + "' is not a relative path (no absolute paths, drives or schemes such as file:// or http://)");
      }
      if (uri.find_first_of("`$~|;&<>*?{}[]'\"\n\r") != std::string::npos || uri.find('%') != std::string::npos) {
        throw badInput(where, "'" + uri + "' holds characters a file name here may not (shell, expansion or percent escapes)");
      }
      for (const fs::path& part : fs::path(uri)) {
        if (part == "..") throw badInput(where, "'" + uri + "' leaves the file's folder");
      }
    }
  }
}

namespace {

// What a field must hold, and how a refusal says so.
struct Rule {
  const char* what;  // "an index (a whole number from 0)"
  bool (*holds)(const nlohmann::json&);
};

bool isWhole(const nlohmann::json& v) { return v.is_number_unsigned(); }
bool isNumber(const nlohmann::json& v) { return v.is_number(); }

template <std::size_t N>
bool isNumbers(const nlohmann::json& v) {
  return v.is_array() && (N == 0 || v.size() == N) && std::all_of(v.begin(), v.end(), isNumber);
}

const Rule kIndex{"an index (a whole number from 0)", isWhole};
const Rule kWhole{"a whole number from 0", isWhole};
const Rule kCount{"a count (a whole number from 1)", [](const nlohmann::json& v) { return isWhole(v) && v.get<std::uint64_t>() >= 1; }};
const Rule kStride{"a byteStride (a multiple of 4 from 4 to 252)", [](const nlohmann::json& v) {
                     // 0, which glTF 1.0 wrote for tightly packed, means what an absent byteStride does.
                     return isWhole(v) && v.get<std::uint64_t>() <= 252 && v.get<std::uint64_t>() % 4 == 0;
                   }};
const Rule kComponentType{"a componentType (5120 BYTE, 5121 UNSIGNED_BYTE, 5122 SHORT, 5123 UNSIGNED_SHORT, 5125 UNSIGNED_INT or 5126 FLOAT)",
                          [](const nlohmann::json& v) {
                            const std::uint64_t types[] = {5120, 5121, 5122, 5123, 5125, 5126};
                            return isWhole(v) && std::find(std::begin(types), std::end(types), v.get<std::uint64_t>()) != std::end(types);
                          }};
const Rule kAccessorType{"an accessor type (SCALAR, VEC2, VEC3, VEC4, MAT2, MAT3 or MAT4)", [](const nlohmann::json& v) {
                           const char* types[] = {"SCALAR", "VEC2", "VEC3", "VEC4", "MAT2", "MAT3", "MAT4"};
                           return v.is_string() && std::find(std::begin(types), std::end(types), v.get<std::string>()) != std::end(types);
                         }};
const Rule kTopology{"a topology (a whole number from 0 to 6)", [](const nlohmann::json& v) { return isWhole(v) && v.get<std::uint64_t>() <= 6; }};
const Rule kBoolean{"true or false", [](const nlohmann::json& v) { return v.is_boolean(); }};
const Rule kString{"a string", [](const nlohmann::json& v) { return v.is_string(); }};
const Rule kObject{"an object", [](const nlohmann::json& v) { return v.is_object(); }};
const Rule kArray{"an array", [](const nlohmann::json& v) { return v.is_array(); }};
const Rule kNonEmptyArray{"an array of at least one element", [](const nlohmann::json& v) { return v.is_array() && !v.empty(); }};
const Rule kNumbers{"an array of numbers", isNumbers<0>};
const Rule kVec3{"an array of 3 numbers", isNumbers<3>};
const Rule kVec4{"an array of 4 numbers", isNumbers<4>};
const Rule kMat4{"an array of 16 numbers", isNumbers<16>};

// A field rastercheck reads: its place ("[]" steps into each element of an array, "{}" into each
// member of an object), what it must hold, and whether glTF requires it. Containers come before
// what they hold, so that "[]" and "{}" only ever step into the shape their rule checked, and
// an array comes before the indices into it.
struct Field {
  std::vector<const char*> steps;
  const Rule* rule;
  bool required = false;
  const char* names = nullptr;  // for an index: the array whose elements it names
};

const std::vector<Field> kFields = {
    {{"scenes"}, &kArray},
    {{"nodes"}, &kArray},
    {{"cameras"}, &kArray},
    {{"meshes"}, &kArray},
    {{"accessors"}, &kArray},
    {{"bufferViews"}, &kArray},
    {{"buffers"}, &kArray},
    {{"skins"}, &kArray},
    {{"extensionsUsed"}, &kArray},
    {{"extensionsUsed", "[]"}, &kString},
    {{"extensionsRequired"}, &kArray},
    {{"extensionsRequired", "[]"}, &kString},
    {{"asset"}, &kObject, true},
    {{"asset", "version"}, &kString, true},
    {{"scene"}, &kIndex, false, "scenes"},
    {{"scenes", "[]"}, &kObject},
    {{"scenes", "[]", "nodes"}, &kArray},
    {{"scenes", "[]", "nodes", "[]"}, &kIndex, false, "nodes"},
    {{"nodes", "[]"}, &kObject},
    {{"nodes", "[]", "camera"}, &kIndex, false, "cameras"},
    {{"nodes", "[]", "mesh"}, &kIndex, false, "meshes"},
    {{"nodes", "[]", "skin"}, &kIndex, false, "skins"},
    {{"nodes", "[]", "children"}, &kArray},
    {{"nodes", "[]", "children", "[]"}, &kIndex, false, "nodes"},
    {{"nodes", "[]", "matrix"}, &kMat4},
    {{"nodes", "[]", "translation"}, &kVec3},
    {{"nodes", "[]", "rotation"}, &kVec4},
    {{"nodes", "[]", "scale"}, &kVec3},
    {{"nodes", "[]", "weights"}, &kNumbers},
    {{"nodes", "[]", "extensions", "EXT_mesh_gpu_instancing", "attributes"}, &kObject},
    {{"nodes", "[]", "extensions", "EXT_mesh_gpu_instancing", "attributes", "{}"}, &kIndex, false, "accessors"},
    {{"meshes", "[]"}, &kObject},
    {{"meshes", "[]", "primitives"}, &kNonEmptyArray, true},
    {{"meshes", "[]", "primitives", "[]"}, &kObject},
    {{"meshes", "[]", "primitives", "[]", "attributes"}, &kObject, true},
    {{"meshes", "[]", "primitives", "[]", "attributes", "{}"}, &kIndex, false, "accessors"},
    {{"meshes", "[]", "primitives", "[]", "indices"}, &kIndex, false, "accessors"},
    {{"meshes", "[]", "primitives", "[]", "mode"}, &kTopology},
    {{"meshes", "[]", "primitives", "[]", "targets"}, &kArray},
    {{"meshes", "[]", "primitives", "[]", "targets", "[]"}, &kObject},
    {{"meshes", "[]", "primitives", "[]", "targets", "[]", "{}"}, &kIndex, false, "accessors"},
    {{"meshes", "[]", "weights"}, &kNumbers},
    {{"accessors", "[]"}, &kObject},
    {{"accessors", "[]", "bufferView"}, &kIndex, false, "bufferViews"},
    {{"accessors", "[]", "byteOffset"}, &kWhole},
    {{"accessors", "[]", "componentType"}, &kComponentType, true},
    {{"accessors", "[]", "normalized"}, &kBoolean},
    {{"accessors", "[]", "count"}, &kCount, true},
    {{"accessors", "[]", "type"}, &kAccessorType, true},
    {{"accessors", "[]", "sparse"}, &kObject},
    {{"accessors", "[]", "sparse", "count"}, &kWhole, true},
    {{"accessors", "[]", "sparse", "indices"}, &kObject, true},
    {{"accessors", "[]", "sparse", "indices", "bufferView"}, &kIndex, true, "bufferViews"},
    {{"accessors", "[]", "sparse", "indices", "byteOffset"}, &kWhole},
    {{"accessors", "[]", "sparse", "indices", "componentType"}, &kWhole, true},
    {{"accessors", "[]", "sparse", "values"}, &kObject, true},
    {{"accessors", "[]", "sparse", "values", "bufferView"}, &kIndex, true, "bufferViews"},
    {{"accessors", "[]", "sparse", "values", "byteOffset"}, &kWhole},
    {{"bufferViews", "[]"}, &kObject},
    {{"bufferViews", "[]", "buffer"}, &kIndex, true, "buffers"},
    {{"bufferViews", "[]", "byteOffset"}, &kWhole},
    {{"bufferViews", "[]", "byteLength"}, &kCount, true},
    {{"bufferViews", "[]", "byteStride"}, &kStride},
    {{"buffers", "[]"}, &kObject},
    {{"buffers", "[]", "byteLength"}, &kCount, true},
    {{"skins", "[]"}, &kObject},
    {{"skins", "[]", "inverseBindMatrices"}, &kIndex, false, "accessors"},
    {{"skins", "[]", "skeleton"}, &kIndex, false, "nodes"},
    {{"skins", "[]", "joints"}, &kNonEmptyArray, true},
    {{"skins", "[]", "joints", "[]"}, &kIndex, false, "nodes"},
};

// A member name as a JSON pointer spells it (RFC 6901): "~" as "~0" and "/" as "~1", so that an
// attribute "_a/b" is "/attributes/_a~1b", not a member b of a member _a.
std::string pointerToken(const std::string& name) {
  std::string token;
  for (const char c : name) token += c == '~' ? "~0" : c == '/' ? "~1" : std::string(1, c);
  return token;
}

void checkField(const nlohmann::json& doc, const nlohmann::json& node, const Field& field, std::size_t step,
                const std::string& pointer, const std::string& path) {
  if (step == field.steps.size()) {
    if (!field.rule->holds(node)) {
      std::string value = node.is_object() ? "an object" : node.dump(-1, ' ', false, nlohmann::json::error_handler_t::replace);
      if (value.size() > 40) value = node.is_array() ? "an array of " + std::to_string(node.size()) + " elements" : value.substr(0, 40) + "...";
      throw badInput(path + ": " + pointer, value + " is not " + field.rule->what);
    }
    const std::size_t size = field.names && doc.contains(field.names) ? doc[field.names].size() : 0;
    if (field.names && node.get<std::uint64_t>() >= size) {
      throw badInput(path + ": " + pointer, node.dump() + " is past the end of /" + field.names + " (it holds " +
                                                 std::to_string(size) + (size == 1 ? " element)" : " elements)"));
    }
    return;
  }
  const std::string_view key = field.steps[step];
  if (key == "[]" || key == "{}") {  // the shape was checked by the container's own field
    if (key == "[]" ? !node.is_array() : !node.is_object()) return;
    for (const auto& [name, item] : node.items()) {
      checkField(doc, item, field, step + 1, pointer + "/" + pointerToken(name), path);
    }
  } else if (node.is_object() && node.contains(key)) {
    checkField(doc, node[std::string(key)], field, step + 1, pointer + "/" + std::string(key), path);
  } else if (field.required && step + 1 == field.steps.size() && node.is_object()) {
    throw badInput(path + ": " + pointer + "/" + std::string(key), "is missing; glTF requires " + std::string(field.rule->what) + " here");
  }
}

}  // namespace

void checkFields(const nlohmann::json& doc, const std::string& path) {
  if (!doc.is_object()) throw badInput(path, "the JSON is not an object, as a glTF file's must be");
  for (const Field& field : kFields) checkField(doc, doc, field, 0, "", path);
}

void requireChecked(int index, std::size_t size, const std::string& where) {
  if (index < 0 || std::size_t(index) >= size) {
    throw internalError(where + ": index " + std::to_string(index) + " read past the end (" + std::to_string(size) +
                        "), which checkFields refuses");
  }
}

namespace {

const char* typeName(int componentType) {
  switch (componentType) {
    case TINYGLTF_COMPONENT_TYPE_BYTE: return "BYTE";
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE: return "UNSIGNED_BYTE";
    case TINYGLTF_COMPONENT_TYPE_SHORT: return "SHORT";
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT: return "UNSIGNED_SHORT";
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT: return "UNSIGNED_INT";
    case TINYGLTF_COMPONENT_TYPE_FLOAT: return "FLOAT";
    default: return "an unknown type";
  }
}

const char* useName(Use use) {
  switch (use) {
    case Use::kPosition: return "POSITION";
    case Use::kNormal: return "NORMAL";
    case Use::kTangent: return "TANGENT";
    case Use::kTexcoord: return "TEXCOORD_n";
    case Use::kColor: return "COLOR_n";
    case Use::kIndices: return "indices";
    case Use::kJoints: return "JOINTS";
    case Use::kWeights: return "WEIGHTS";
    case Use::kMatrix: return "inverseBindMatrices";
    case Use::kCustom: return "an application-specific attribute";
    case Use::kRotation: return "ROTATION";
  }
  return "";
}

bool isSigned(int type) { return type == TINYGLTF_COMPONENT_TYPE_BYTE || type == TINYGLTF_COMPONENT_TYPE_SHORT; }
bool isSmallInteger(int type) {
  return isSigned(type) || type == TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE || type == TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT;
}

// The glTF 2.0 specification's tables of accessor component types for vertex attributes and for
// morph targets (whose values are displacements), widened by KHR_mesh_quantization's.
bool allowedType(Use use, bool displacement, int type, bool normalized, bool quantized) {
  if (type == TINYGLTF_COMPONENT_TYPE_FLOAT) return use != Use::kJoints;
  if (!isSmallInteger(type)) return false;
  switch (use) {
    case Use::kJoints: return !normalized && !isSigned(type);
    case Use::kWeights: return normalized && !isSigned(type);
    case Use::kMatrix: return false;
    case Use::kCustom: return normalized;  // any normalised 8- or 16-bit integer
    case Use::kRotation: return normalized && isSigned(type);
    case Use::kPosition:  // KHR_mesh_quantization: any 8- or 16-bit integer; signed ones for displacements
      return quantized && (!displacement || isSigned(type));
    case Use::kNormal:  // KHR_mesh_quantization: signed normalised
    case Use::kTangent:
      return quantized && normalized && isSigned(type);
    case Use::kTexcoord:
      if (normalized && (displacement || !isSigned(type))) return true;  // the core tables
      return quantized && (!displacement || isSigned(type));
    case Use::kColor:
      return normalized && (displacement || !isSigned(type));
    case Use::kIndices: return false;
  }
  return false;
}

}  // namespace

AccessorReader::AccessorReader(const tinygltf::Model& model, const std::string& path)
    : model_(model), path_(path) {
  for (const std::string& e : model.extensionsUsed) quantized_ = quantized_ || e == "KHR_mesh_quantization";
}

std::string AccessorReader::where(int index) const { return path_ + ": accessors[" + std::to_string(index) + "]"; }

const tinygltf::Accessor& AccessorReader::accessor(int index) const {
  requireChecked(index, model_.accessors.size(), path_ + ": accessors");
  return model_.accessors[std::size_t(index)];
}

AccessorReader::Range AccessorReader::locate(int viewIndex, long long byteOffset, std::uint64_t count, std::uint64_t element,
                                             bool strided, const std::string& where) const {
  if (viewIndex < 0 || std::size_t(viewIndex) >= model_.bufferViews.size()) throw badInput(where, "has no valid bufferView");
  const tinygltf::BufferView& view = model_.bufferViews[std::size_t(viewIndex)];
  if (view.buffer < 0 || std::size_t(view.buffer) >= model_.buffers.size()) throw badInput(where, "its bufferView names no valid buffer");
  const std::vector<unsigned char>& buffer = model_.buffers[std::size_t(view.buffer)].data;
  if (view.byteOffset > buffer.size() || view.byteLength > buffer.size() - view.byteOffset) {
    throw badInput(where, "its bufferView " + std::to_string(viewIndex) + " runs past the end of its buffer");
  }
  if (view.byteStride != 0 && !strided) throw badInput(where, "its bufferView " + std::to_string(viewIndex) + " has a byteStride, which sparse storage may not");
  if (view.byteStride != 0 && (view.byteStride < element || view.byteStride > 252)) {
    throw badInput(where, "byteStride " + std::to_string(view.byteStride) + " is not between the element size " +
                              std::to_string(element) + " and 252");
  }
  // count is at most 2^32 and stride and element at most 252 bytes, so this cannot overflow.
  const std::uint64_t stride = view.byteStride ? view.byteStride : element;
  const std::uint64_t span = count ? stride * (count - 1) + element : 0;
  if (byteOffset < 0 || std::uint64_t(byteOffset) > view.byteLength || span > view.byteLength - std::uint64_t(byteOffset)) {
    throw badInput(where, "range of " + std::to_string(count) + " elements exceeds its buffer view or buffer");
  }
  return {buffer.data() + view.byteOffset + std::uint64_t(byteOffset), stride};
}

void AccessorReader::copy(const Range& range, std::uint64_t count, std::uint64_t element, unsigned char* out) {
  if (range.stride == element) {
    if (count) std::memcpy(out, range.base, std::size_t(count * element));
    return;
  }
  for (std::uint64_t i = 0; i < count; ++i) std::memcpy(out + i * element, range.base + i * range.stride, std::size_t(element));
}

HugeVector<unsigned char> AccessorReader::elements(int index, int components) const {
  const tinygltf::Accessor& a = model_.accessors[std::size_t(index)];
  const std::string at = where(index);
  if (tinygltf::GetNumComponentsInType(std::uint32_t(a.type)) != components) {
    throw badInput(at, "has " + std::to_string(tinygltf::GetNumComponentsInType(std::uint32_t(a.type))) +
                           " components, expected " + std::to_string(components));
  }
  const int size = tinygltf::GetComponentSizeInBytes(std::uint32_t(a.componentType));
  if (size != 1 && size != 2 && size != 4) throw badInput(at, "has component type " + std::to_string(a.componentType) + ", which glTF does not allow here");
  const std::uint64_t element = std::uint64_t(size) * std::uint64_t(components);
  if (a.count > (std::uint64_t(1) << 32)) throw badInput(at, "count " + std::to_string(a.count) + " is over 2^32");
  // Without a bufferView the elements are zeros, which sparse storage may then replace. They
  // need no bytes in the file, so their number is bounded on its own.
  if (a.bufferView < 0 && a.count > kMaxZeroElements) {
    throw badInput(at, "count " + std::to_string(a.count) + " of elements without a bufferView is over " +
                           std::to_string(kMaxZeroElements));
  }
  if (a.bufferView < -1) throw badInput(at, "has no valid bufferView");  // -1: none given
  Range dense{};
  if (a.bufferView >= 0) {  // checked before anything is allocated
    if (a.byteOffset > (std::uint64_t(1) << 62)) throw badInput(at, "byteOffset " + std::to_string(a.byteOffset) + " is out of range");
    dense = locate(a.bufferView, (long long)a.byteOffset, a.count, element, true, at);
  }
  HugeVector<unsigned char> bytes(std::size_t(a.count * element), 0);
  if (a.bufferView >= 0) copy(dense, a.count, element, bytes.data());
  if (!a.sparse.isSparse) return bytes;

  const std::string sparse = at + ".sparse";
  const long long count = a.sparse.count;
  if (count < 1 || std::uint64_t(count) > a.count) {
    throw badInput(sparse, "count " + std::to_string(count) + " is not between 1 and the accessor's count " + std::to_string(a.count));
  }
  const int indexType = a.sparse.indices.componentType;
  const int indexSize = indexType == TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE    ? 1
                        : indexType == TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT ? 2
                        : indexType == TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT   ? 4
                                                                              : 0;
  if (!indexSize) throw badInput(sparse + ".indices", "component type " + std::to_string(indexType) + " is not an unsigned byte, short or int");
  const Range indexRange = locate(a.sparse.indices.bufferView, a.sparse.indices.byteOffset, std::uint64_t(count),
                                  std::uint64_t(indexSize), false, sparse + ".indices");
  const Range valueRange = locate(a.sparse.values.bufferView, a.sparse.values.byteOffset, std::uint64_t(count), element, false,
                                  sparse + ".values");
  std::vector<unsigned char> indices(std::size_t(count) * std::size_t(indexSize));
  copy(indexRange, std::uint64_t(count), std::uint64_t(indexSize), indices.data());
  std::vector<unsigned char> values(std::size_t(std::uint64_t(count) * element));
  copy(valueRange, std::uint64_t(count), element, values.data());
  std::uint64_t previous = 0;
  for (long long k = 0; k < count; ++k) {
    std::uint32_t target = 0;
    std::memcpy(&target, indices.data() + std::size_t(k) * std::size_t(indexSize), std::size_t(indexSize));  // little-endian
    if (target >= a.count) {
      throw badInput(sparse + ".indices", "index " + std::to_string(target) + " at element " + std::to_string(k) +
                                              " is not below the accessor's count " + std::to_string(a.count));
    }
    if (k > 0 && target <= previous) {
      throw badInput(sparse + ".indices", "element " + std::to_string(k) + " (" + std::to_string(target) +
                                              ") does not increase strictly");
    }
    previous = target;
    std::memcpy(bytes.data() + target * element, values.data() + std::size_t(k) * element, std::size_t(element));
  }
  return bytes;
}

HugeVector<float> AccessorReader::floats(int index, Use use, int components, bool displacement) const {
  const tinygltf::Accessor& a = accessor(index);
  const int type = a.componentType;
  if (!allowedType(use, displacement, type, a.normalized, quantized_)) {
    std::string why = std::string(a.normalized ? "normalised " : "") + typeName(type) + " components are not allowed for " +
                      (displacement ? "a morph target's " : "") + useName(use);
    if (!quantized_ && isSmallInteger(type) && allowedType(use, displacement, type, a.normalized, true)) {
      why += " unless the file lists KHR_mesh_quantization in extensionsUsed";
    }
    throw badInput(where(index), why);
  }
  const HugeVector<unsigned char> bytes = elements(index, components);
  const bool normalized = a.normalized && type != TINYGLTF_COMPONENT_TYPE_FLOAT;
  HugeVector<float> values(std::size_t(a.count) * std::size_t(components));
  const unsigned char* p = bytes.data();
  for (float& v : values) {
    switch (type) {
      case TINYGLTF_COMPONENT_TYPE_FLOAT: std::memcpy(&v, p, 4); p += 4; break;
      case TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE: v = normalized ? float(*p) / 255.0f : float(*p); p += 1; break;
      case TINYGLTF_COMPONENT_TYPE_BYTE: {
        const float c = float(std::int8_t(*p));
        v = normalized ? std::max(c / 127.0f, -1.0f) : c;
        p += 1;
        break;
      }
      case TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT: {
        std::uint16_t s;
        std::memcpy(&s, p, 2);
        v = normalized ? float(s) / 65535.0f : float(s);
        p += 2;
        break;
      }
      default: {  // SHORT
        std::int16_t s;
        std::memcpy(&s, p, 2);
        v = normalized ? std::max(float(s) / 32767.0f, -1.0f) : float(s);
        p += 2;
        break;
      }
    }
  }
  return values;
}

HugeVector<unsigned> AccessorReader::indices(int index, std::size_t vertexCount) const {
  const tinygltf::Accessor& a = accessor(index);
  const std::string at = where(index);
  if (a.type != TINYGLTF_TYPE_SCALAR) throw badInput(at, "indices must be SCALAR");
  const int type = a.componentType;
  if (type != TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE && type != TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT &&
      type != TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT) {
    throw badInput(at, "unsupported index component type " + std::to_string(type) + " (" + typeName(type) + ")");
  }
  const HugeVector<unsigned char> bytes = elements(index, 1);
  const std::size_t size = std::size_t(tinygltf::GetComponentSizeInBytes(std::uint32_t(type)));
  HugeVector<unsigned> out(std::size_t(a.count));
  for (std::size_t i = 0; i < out.size(); ++i) {
    std::uint32_t v = 0;
    std::memcpy(&v, bytes.data() + i * size, size);  // little-endian, as is x86-64
    if (v >= vertexCount) {
      throw badInput(at, "index " + std::to_string(v) + " at element " + std::to_string(i) + " is not below the vertex count " +
                             std::to_string(vertexCount));
    }
    out[i] = v;
  }
  return out;
}

std::string clippedLines(const std::string& text, std::size_t width) {
  std::string out;
  std::size_t start = 0;
  while (start < text.size()) {
    std::size_t end = text.find('\n', start);
    if (end == std::string::npos) end = text.size();
    if (!out.empty()) out += '\n';
    if (end - start <= width) {
      out.append(text, start, end - start);
    } else {
      out.append(text, start, width);
      out += "... (" + std::to_string(end - start - width) + " more characters)";
    }
    start = end + 1;
  }
  return out;
}

void confineLoader(tinygltf::TinyGLTF& loader, LoaderFiles* files) {
  tinygltf::FsCallbacks callbacks;
  callbacks.user_data = files;
  // tinygltf asks for a buffer's URI joined to the folder; a name of takeDataUris is answered
  // with its bytes, from memory.
  static constexpr auto embeddedOf = [](const std::string& file, LoaderFiles& f) {
    const std::size_t n = f.folder.size();
    const bool inFolder = file.size() > n + 1 && file.compare(0, n, f.folder) == 0 && file[n] == '/';
    return inFolder ? f.embedded.find(file.substr(n + 1)) : f.embedded.end();
  };
  callbacks.FileExists = [](const std::string& file, void* user) {
    LoaderFiles& f = *static_cast<LoaderFiles*>(user);
    if (embeddedOf(file, f) != f.embedded.end()) return true;
    std::error_code ec;
    return insideFolder(file, f.folder) && fs::is_regular_file(file, ec);
  };
  callbacks.ExpandFilePath = [](const std::string& file, void*) { return file; };  // never expand
  callbacks.ReadWholeFile = [](std::vector<unsigned char>* out, std::string* err, const std::string& file, void* user) {
    LoaderFiles& f = *static_cast<LoaderFiles*>(user);
    if (const auto e = embeddedOf(file, f); e != f.embedded.end()) {
      *out = std::move(e->second);  // each buffer is read once
      return true;
    }
    if (!insideFolder(file, f.folder)) {
      if (err) *err += "refused to read '" + file + "': outside the glTF file's folder\n";
      return false;
    }
    try {
      const std::string bytes = readInputFile(file);
      out->assign(bytes.begin(), bytes.end());
      return true;
    } catch (const Error& e) {
      if (err) *err += std::string(e.what()) + "\n";
      return false;
    }
  };
  callbacks.WriteWholeFile = [](std::string* err, const std::string&, const std::vector<unsigned char>&, void*) {
    if (err) *err += "writing is disabled\n";
    return false;
  };
  loader.SetFsCallbacks(callbacks);
  // Images are never decoded: rastercheck reads geometry and vertex attributes only.
  loader.SetImageLoader([](tinygltf::Image*, const int, std::string*, std::string*, int, int,
                           const unsigned char*, int, void*) { return true; },
                        nullptr);
}

}  // namespace rc::gltf
