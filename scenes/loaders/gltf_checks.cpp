// GLB container checks, URI vetting, field checks, confined file callbacks.
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
