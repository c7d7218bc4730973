// Checks made on a glTF file before and while tinygltf reads it: the GLB container, the URIs
// it may name, the fields rastercheck reads, and the files tinygltf may open. The accessors'
// bounds-checked reads are gltf_accessors.h's.
#pragma once

#include <tiny_gltf.h>

#include <nlohmann/json.hpp>

#include <map>
#include <string>
#include <string_view>
#include <vector>

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
