// Checks made on a glTF file before and while tinygltf reads it: the GLB container, the URIs
// it may name, and bounds-checked accessor reads.
#pragma once

#include <tiny_gltf.h>

#include <nlohmann/json.hpp>

#include <cstdint>
#include <map>
#include <string>
#include <string_view>
#include <vector>

#include "core/plane_allocator.h"
#include "scenes/loaders/gltf_data_uris.h"

namespace rc::gltf {

// For a GLB: checks magic, version 2, the declared length against the file size and the JSON
// chunk's bounds; returns the JSON chunk. Throws badInput naming the byte offset.
std::string glbJsonChunk(std::string_view bytes, const std::string& path);

// Parses the JSON: takeDataUris's when it changed it, the file's own otherwise. A syntax error
// is reported at its place in the file's own text: badInput(path, "invalid JSON: ...").
nlohmann::json parseJson(std::string_view original, const EmbeddedData& embedded, const std::string& path);

// Refuses (badInput naming the JSON path) any buffer or image URI that is not a data: URI or a
// plain relative path inside the file's folder: absolute paths, "..", schemes such as file://
// or http://, backslashes, and shell or expansion characters. A buffer whose data: URI
// takeDataUris took must hold at least one byte, and as many as its byteLength says.
void checkUris(const nlohmann::json& doc, const EmbeddedData& embedded, const std::string& path);

// Refuses (badInput naming the JSON pointer) a field rastercheck reads that is missing where
// glTF requires it or holds what glTF does not allow there, before tinygltf reads the file:
// tinygltf reads a negative index as absent, drops a node's translation of two numbers or a
// byteOffset of -4 without a word, and refuses a missing count without saying which accessor's.
// The fields: every index followed (a scene's nodes, a node's mesh, camera, skin and children, a
// primitive's indices and attributes, an accessor's bufferView...), the containers that hold
// them, a node's transform and morph weights, the accessor, buffer view and buffer fields that
// place the data (counts, offsets, strides, component and element types), and the extensions
// used and required (tinygltf ignored an extensionsRequired that is a string, so a file that
// needs Draco loaded).
void checkFields(const nlohmann::json& doc, const std::string& path);

// Guards a read at an index checkFields has already held below its array's size: past the end
// here would be a gap in those checks, so it is an internal error, not the file's.
void requireChecked(int index, std::size_t size, const std::string& where);

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

// tinygltf's error text, without its last newline, each line cut to `width` characters: it
// quotes a data: URI it cannot decode whole, which can be megabytes.
std::string clippedLines(const std::string& text, std::size_t width = 300);

struct LoaderFiles {
  std::string folder;  // the glTF file's folder, canonical
  std::map<std::string, std::vector<unsigned char>> embedded;  // EmbeddedData::buffers
};

// Installs file callbacks that read only files inside `files->folder`, and the bytes of
// `files->embedded` for their names (moved out: each is read once), and a no-op image decoder.
void confineLoader(tinygltf::TinyGLTF& loader, LoaderFiles* files);

}  // namespace rc::gltf
