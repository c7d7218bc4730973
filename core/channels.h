// The channel layout both renderers write and compare reads (docs/channels.md).
// Names follow OpenEXR's layer.channel convention; ground truth is FLOAT, ids are UINT.
#pragma once

#include <cstdint>
#include <string>

namespace rc::channels {

inline constexpr const char* kTriangleId = "tri.id";  // UINT: source triangle index
inline constexpr std::uint32_t kNoTriangle = 0xFFFFFFFFu;  // tri.id where nothing was hit
inline constexpr const char* kBary[3] = {"bary.b0", "bary.b1", "bary.b2"};  // FLOAT
inline constexpr const char* kDepth = "depth.z";  // FLOAT: view-space distance along forward
inline constexpr const char* kPreview[3] = {"R", "G", "B"};  // FLOAT: for image viewers
inline constexpr const char* kAttributePrefix = "attr.";  // attr.<name>.<x|y|z|w>

// Diagnostics (docs/numerics.md), FLOAT, written by both renderers for compare's bounds and
// classification; compare falls back to fixed thresholds for images without them.
inline constexpr const char* kBaryBound = "bound.bary";    // this path's error bound on bary.*
inline constexpr const char* kDepthBound = "bound.depth";  // ... on depth.z, relative
inline constexpr const char* kEdgeDistance = "edge.dist";  // pixels from the centre to the
                                                           // nearest edge of tri.id on screen
inline constexpr const char* kDepthTie = "depth.tie";  // rasterizer: relative depth difference
                                                       // its depth test cannot order here

// The reference's, per attribute: the largest spread, over the attribute's components, of its
// values at the three vertices of the triangle hit (max - min), for compare's attribute bound,
// which it holds to the triangle's values rather than to the image's range ("spread.uv").
inline std::string spreadChannel(const std::string& attribute) { return "spread." + attribute; }

// "attr.uv.x" for component 0 of attribute "uv".
inline std::string attributeChannel(const std::string& attribute, int component) {
  static const char* kComponents[4] = {"x", "y", "z", "w"};
  return std::string(kAttributePrefix) + attribute + "." + kComponents[component];
}

// Header attribute keys (provenance), all strings.
namespace header {
inline constexpr const char* kRenderer = "rastercheck.renderer";    // "raster" | "reference"
inline constexpr const char* kMode = "rastercheck.mode";            // "perspective" | "affine" | "exact"
inline constexpr const char* kPrecision = "rastercheck.precision";  // "float" | "double"
inline constexpr const char* kScene = "rastercheck.scene";
inline constexpr const char* kCamera = "rastercheck.camera";        // Camera::describe()
inline constexpr const char* kVersion = "rastercheck.version";
// Distance in pixels within which this path may decide a pixel centre differently from the
// exact answer (snapping for the rasterizer, Embree's float test for the reference).
inline constexpr const char* kEdgeBand = "rastercheck.edgeBand";
// Relative depth difference within which this path's depth test may order two surfaces wrongly.
inline constexpr const char* kDepthResolution = "rastercheck.depthResolution";
// A float frame's pixels whose values its rasterizer computed in double: set-ups whose own
// error bound says float learns next to nothing there (docs/rasterizer.md).
inline constexpr const char* kPromotedPixels = "rastercheck.promotedPixels";
}  // namespace header

}  // namespace rc::channels
