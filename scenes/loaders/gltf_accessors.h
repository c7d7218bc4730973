// Bounds-checked reads of a glTF file's accessors, after gltf_checks.h's field checks.
#pragma once

#include <tiny_gltf.h>

#include <cstdint>
#include <string>

#include "core/plane_allocator.h"

namespace rc::gltf {

// What an accessor is read for: it decides the component types allowed.
// kMatrix: float only (inverse bind matrices, instance translations and scales); kRotation:
// float or normalised signed integers (EXT_mesh_gpu_instancing's ROTATION).
enum class Use { kPosition, kNormal, kTangent, kTexcoord, kColor, kIndices, kJoints, kWeights, kMatrix, kCustom, kRotation };

// Bounds-checked accessor reads (64-bit arithmetic throughout). An accessor without a
// bufferView holds zeros; sparse storage then replaces the elements it names (indices strictly
// increasing and below the count, as the specification requires). Component types follow the
// glTF 2.0 tables, widened by KHR_mesh_quantization's when the file lists it in extensionsUsed;
// normalised integers are converted as the specification says (c / 255, max(c / 127, -1)...).
// Errors are badInput("path: accessors[i]" or "...accessors[i].sparse.indices", ...); an index
// past the file's accessors is requireChecked's internal error.
class AccessorReader {
 public:
  // The most elements an accessor without a bufferView (zeros, perhaps sparse) may have: such
  // elements take no bytes in the file, so a small file could otherwise ask for any amount.
  static constexpr std::uint64_t kMaxZeroElements = std::uint64_t(1) << 24;

  AccessorReader(const tinygltf::Model& model, const std::string& path);

  // `components` per element, converted to float; `displacement` for a morph target's values.
  HugeVector<float> floats(int index, Use use, int components, bool displacement = false) const;
  // Vertex indices, each checked against `vertexCount`.
  HugeVector<unsigned> indices(int index, std::size_t vertexCount) const;
  bool quantized() const { return quantized_; }

 private:
  std::string where(int index) const;
  const tinygltf::Accessor& accessor(int index) const;
  // The elements of accessor `index` (one accessor() has found) packed tightly, sparse
  // replacements applied.
  HugeVector<unsigned char> elements(int index, int components) const;
  struct Range {
    const unsigned char* base;
    std::uint64_t stride;
  };
  // Where `count` elements start in a buffer view, after checking that they lie inside it.
  Range locate(int viewIndex, long long byteOffset, std::uint64_t count, std::uint64_t element, bool strided,
               const std::string& where) const;
  static void copy(const Range& range, std::uint64_t count, std::uint64_t element, unsigned char* out);

  const tinygltf::Model& model_;
  const std::string& path_;
  bool quantized_ = false;
};

}  // namespace rc::gltf
