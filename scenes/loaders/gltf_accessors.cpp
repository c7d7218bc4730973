// Bounds-checked accessor reads (gltf_accessors.h).
#include "scenes/loaders/gltf_accessors.h"

#include <cstring>

#include "core/error.h"
#include "scenes/loaders/gltf_checks.h"

namespace rc::gltf {

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

}  // namespace rc::gltf
