// GLB container checks, URI vetting, bounds-checked accessor reads, confined file callbacks.
#include "scenes/loaders/gltf_checks.h"

#include <cstring>
#include <filesystem>
#include <nlohmann/json.hpp>

#include "core/error.h"
#include "scenes/loaders/read_file.h"

namespace rc::gltf {
namespace {

namespace fs = std::filesystem;

std::uint32_t readU32(const std::string& bytes, std::size_t offset) {
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

std::string glbJsonChunk(const std::string& bytes, const std::string& path) {
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
  return bytes.substr(20, std::size_t(chunkLength));
}

void checkUris(const std::string& json, const std::string& path) {
  nlohmann::json doc;
  try {
    doc = nlohmann::json::parse(json);
  } catch (const nlohmann::json::exception& e) {
    throw badInput(path, std::string("invalid JSON: ") + e.what());
  }
  for (const char* array : {"buffers", "images"}) {
    if (!doc.contains(array) || !doc[array].is_array()) continue;
    for (std::size_t i = 0; i < doc[array].size(); ++i) {
      const nlohmann::json& item = doc[array][i];
      if (!item.is_object() || !item.contains("uri")) continue;
      const std::string where = path + ": /" + array + "/" + std::to_string(i) + "/uri";
      if (!item["uri"].is_string()) throw badInput(where, "is not a string");
      const std::string uri = item["uri"].get<std::string>();
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

std::vector<float> readFloats(const tinygltf::Model& model, int index, int components,
                              bool normalizedOk, const std::string& path) {
  const std::string where = path + ": accessors[" + std::to_string(index) + "]";
  if (index < 0 || std::size_t(index) >= model.accessors.size()) throw badInput(path, "accessor index " + std::to_string(index) + " out of range");
  const tinygltf::Accessor& a = model.accessors[index];
  if (a.sparse.isSparse) throw badInput(where, "sparse accessors are not supported");
  if (tinygltf::GetNumComponentsInType(a.type) != components) {
    throw badInput(where, "has " + std::to_string(tinygltf::GetNumComponentsInType(a.type)) + " components, expected " + std::to_string(components));
  }
  const int componentSize = tinygltf::GetComponentSizeInBytes(a.componentType);
  const bool isFloat = a.componentType == TINYGLTF_COMPONENT_TYPE_FLOAT;
  const bool isNormalized = normalizedOk && a.normalized &&
                            (a.componentType == TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE ||
                             a.componentType == TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT);
  if (!isFloat && !isNormalized) throw badInput(where, "unsupported component type " + std::to_string(a.componentType));
  if (a.bufferView < 0 || std::size_t(a.bufferView) >= model.bufferViews.size()) throw badInput(where, "has no valid bufferView");
  const tinygltf::BufferView& view = model.bufferViews[a.bufferView];
  if (view.buffer < 0 || std::size_t(view.buffer) >= model.buffers.size()) throw badInput(where, "its bufferView names no valid buffer");
  const std::vector<unsigned char>& buffer = model.buffers[view.buffer].data;
  const std::uint64_t element = std::uint64_t(componentSize) * components;
  const std::uint64_t stride = view.byteStride ? view.byteStride : element;
  const std::uint64_t count = a.count;
  if (stride < element) throw badInput(where, "byteStride smaller than an element");
  const std::uint64_t start = std::uint64_t(view.byteOffset) + a.byteOffset;
  const std::uint64_t end = count == 0 ? start : start + stride * (count - 1) + element;
  if (count > (std::uint64_t(1) << 32) || a.byteOffset + (count ? stride * (count - 1) + element : 0) > view.byteLength ||
      std::uint64_t(view.byteOffset) + view.byteLength > buffer.size() || end > buffer.size()) {
    throw badInput(where, "range of " + std::to_string(count) + " elements exceeds its buffer view or buffer");
  }
  std::vector<float> values(std::size_t(count) * components);
  for (std::uint64_t i = 0; i < count; ++i) {
    const unsigned char* p = buffer.data() + start + i * stride;
    for (int c = 0; c < components; ++c) {
      float v;
      if (isFloat) {
        std::memcpy(&v, p + 4 * c, 4);
      } else if (a.componentType == TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE) {
        v = float(p[c]) / 255.0f;
      } else {
        std::uint16_t s;
        std::memcpy(&s, p + 2 * c, 2);
        v = float(s) / 65535.0f;
      }
      values[std::size_t(i) * components + c] = v;
    }
  }
  return values;
}

std::vector<unsigned> readIndices(const tinygltf::Model& model, int index, std::size_t vertexCount,
                                  const std::string& path) {
  const std::string where = path + ": accessors[" + std::to_string(index) + "]";
  if (index < 0 || std::size_t(index) >= model.accessors.size()) throw badInput(path, "index accessor " + std::to_string(index) + " out of range");
  const tinygltf::Accessor& a = model.accessors[index];
  if (a.sparse.isSparse) throw badInput(where, "sparse accessors are not supported");
  if (a.type != TINYGLTF_TYPE_SCALAR) throw badInput(where, "indices must be SCALAR");
  int size = 0;
  switch (a.componentType) {
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE: size = 1; break;
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT: size = 2; break;
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT: size = 4; break;
    default: throw badInput(where, "unsupported index component type " + std::to_string(a.componentType));
  }
  if (a.bufferView < 0 || std::size_t(a.bufferView) >= model.bufferViews.size()) throw badInput(where, "has no valid bufferView");
  const tinygltf::BufferView& view = model.bufferViews[a.bufferView];
  if (view.buffer < 0 || std::size_t(view.buffer) >= model.buffers.size()) throw badInput(where, "its bufferView names no valid buffer");
  const std::vector<unsigned char>& buffer = model.buffers[view.buffer].data;
  const std::uint64_t stride = view.byteStride ? view.byteStride : std::uint64_t(size);
  const std::uint64_t count = a.count;
  const std::uint64_t span = count ? stride * (count - 1) + size : 0;
  if (stride < std::uint64_t(size) || count > (std::uint64_t(1) << 32) || a.byteOffset + span > view.byteLength ||
      std::uint64_t(view.byteOffset) + view.byteLength > buffer.size()) {
    throw badInput(where, "range of " + std::to_string(count) + " indices exceeds its buffer view or buffer");
  }
  std::vector<unsigned> indices(count);
  const unsigned char* base = buffer.data() + view.byteOffset + a.byteOffset;
  for (std::uint64_t i = 0; i < count; ++i) {
    std::uint32_t v = 0;
    std::memcpy(&v, base + i * stride, std::size_t(size));
    if (v >= vertexCount) {
      throw badInput(where, "index " + std::to_string(v) + " at element " + std::to_string(i) + " is not below the vertex count " + std::to_string(vertexCount));
    }
    indices[i] = v;
  }
  return indices;
}

void confineLoader(tinygltf::TinyGLTF& loader, const std::string* folder) {
  tinygltf::FsCallbacks callbacks;
  callbacks.user_data = const_cast<std::string*>(folder);
  callbacks.FileExists = [](const std::string& file, void* user) {
    std::error_code ec;
    return insideFolder(file, *static_cast<std::string*>(user)) && fs::is_regular_file(file, ec);
  };
  callbacks.ExpandFilePath = [](const std::string& file, void*) { return file; };  // never expand
  callbacks.ReadWholeFile = [](std::vector<unsigned char>* out, std::string* err, const std::string& file, void* user) {
    if (!insideFolder(file, *static_cast<std::string*>(user))) {
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
