// Checks made on a glTF file before and while tinygltf reads it: the GLB container, the URIs
// it may name, and bounds-checked accessor reads.
#pragma once

#include <tiny_gltf.h>

#include <string>
#include <vector>

namespace rc::gltf {

// For a GLB: checks magic, version 2, the declared length against the file size and the JSON
// chunk's bounds; returns the JSON chunk. Throws badInput naming the byte offset.
std::string glbJsonChunk(const std::string& bytes, const std::string& path);

// Refuses (badInput naming the JSON path) any buffer or image URI that is not a data: URI or a
// plain relative path inside the file's folder: absolute paths, "..", schemes such as file://
// or http://, backslashes, and shell or expansion characters.
void checkUris(const std::string& json, const std::string& path);

// Reads accessor `index` as floats, `components` per element (converting normalised unsigned
// bytes and shorts when `normalizedOk`). Throws badInput("path: accessors[i]", ...) for a bad
// index, type, sparse storage or a range outside its buffer view or buffer.
std::vector<float> readFloats(const tinygltf::Model& model, int index, int components,
                              bool normalizedOk, const std::string& path);

// Reads accessor `index` as vertex indices, each checked against `vertexCount`.
std::vector<unsigned> readIndices(const tinygltf::Model& model, int index, std::size_t vertexCount,
                                  const std::string& path);

// Installs file callbacks that read only files inside `folder` and a no-op image decoder.
void confineLoader(tinygltf::TinyGLTF& loader, const std::string* folder);

}  // namespace rc::gltf
