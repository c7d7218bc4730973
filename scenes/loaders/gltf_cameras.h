// The cameras of a glTF file, as rastercheck can render through them (gltf_loader.h's
// GltfCamera): each read from the file, and the names messages give them.
#pragma once

#include <tiny_gltf.h>

#include <glm/glm.hpp>
#include <string>

#include "scenes/loaders/gltf_loader.h"

namespace rc {

// The camera `index` of the file at `path`, placed at a node's `world` transform (where()
// names the node): its spec where it can be used, otherwise its refusal naming the file and
// the camera or node. Only perspective cameras can be; the exact camera `rastercheck export`
// keeps in the extras replaces the one the glTF fields give where the two agree.
GltfCamera gltfCamera(const tinygltf::Camera& camera, int index, const glm::dmat4& world, const std::string& path,
                      const std::string& where);

}  // namespace rc
