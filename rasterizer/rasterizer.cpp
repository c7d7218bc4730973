// The rasterizer pipeline. Stages, each in its own loop so that per-triangle work never
// enters the pixel loops:
//   1. transform: world -> clip, in double through the camera;
//   2. clip + set-up in double, in parallel blocks of triangles, concatenated in triangle
//      order; only the per-pixel coefficients are rounded to Real (setup.h);
//   3. binning of set-ups into 64x64 tiles, in set-up order;
//   4. per tile (in parallel): coverage + depth test into a tile-local visibility buffer
//      (set-up index + 1/w), then resolve: barycentrics, depth and attributes for the winner.
// Tiles own disjoint pixels and visit set-ups in triangle order, so the output does not depend
// on the thread count; depth ties go to the lower triangle index.
#include "rasterizer/rasterizer.h"

#include <algorithm>
#include <array>
#include <cstdio>
#include <type_traits>
#include <cmath>
#include <limits>

#include "core/channels.h"
#include "core/error.h"
#include "core/parallel.h"
#include "core/preview.h"
#include "rasterizer/clip.h"
#include "rasterizer/interpolate.h"
#include "rasterizer/setup.h"

namespace rc {

const char* interpolationName(Interpolation mode) {
  return mode == Interpolation::kPerspective ? "perspective" : "affine";
}
const char* precisionName(Precision precision) {
  return precision == Precision::kFloat ? "float" : "double";
}
const char* depthMappingName(DepthMapping mapping) {
  return mapping == DepthMapping::kInverseW ? "inverse-w" : "standard";
}

namespace {

constexpr int kTileSize = 64;
constexpr int kTrianglesPerBlock = 8192;
constexpr std::uint32_t kEmpty = 0xFFFFFFFFu;

template <typename Real>
struct SetupBlock {
  std::vector<TriangleSetup<Real>> setups;
  std::vector<glm::mat<3, 3, Real>> clipMaps;  // columns: source barycentrics of sub-vertices
};

template <typename Real>
struct Pipeline {
  const Scene& scene;
  const RasterOptions& options;
  int width, height;
  ClipVolume<double> volume;
  std::vector<glm::dvec4> clip;  // per mesh vertex
  std::vector<TriangleSetup<Real>> setups;
  std::vector<glm::mat<3, 3, Real>> clipMaps;
  SetupContext context{};

  Pipeline(const Scene& s, const RasterOptions& o)
      : scene(s), options(o), width(s.camera.width()), height(s.camera.height()) {
    // Guard band: 2^(28 - bits) pixels from the viewport centre, so that snapped positions
    // stay below 2^29 grid steps (coverage.h); the viewport must fit inside it.
    const double guardPixels = std::ldexp(1.0, 28 - o.subpixelBits);
    if (std::max(width, height) > guardPixels) {
      throw usageError("--subpixel-bits " + std::to_string(o.subpixelBits) +
                       " is too fine for a " + std::to_string(width) + "x" +
                       std::to_string(height) + " image (exact int64 edges need at most " +
                       std::to_string(28 - int(std::ceil(std::log2(std::max(width, height))))) +
                       " bits)");
    }
    volume.zNear = s.camera.zNear();
    volume.zFar = s.camera.zFar();
    volume.guard = 2.0 * guardPixels / std::max(width, height);
    context.width = width;
    context.height = height;
    context.subpixelBits = o.subpixelBits;
    context.unitRoundoff = std::is_same_v<Real, float> ? 0x1p-24 : 0x1p-53;
    const double n = s.camera.zNear(), f = s.camera.zFar();
    if (o.depthMapping == DepthMapping::kInverseW) {
      context.keyA = 0.0, context.keyB = 1.0;
    } else if (std::isinf(f)) {
      context.keyA = -1.0, context.keyB = n;
    } else {
      context.keyA = -f / (f - n), context.keyB = f * n / (f - n);
    }
  }

  void transform() {
    const glm::dmat4 clipFromWorld = scene.camera.clipFromWorld();
    const auto& positions = scene.mesh.positions;
    clip.resize(positions.size());
    const int blocks = int((positions.size() + kTrianglesPerBlock - 1) / kTrianglesPerBlock);
    std::vector<double> largest(blocks, 1.0);  // max |world coordinate| per block, at least 1
    parallelFor(blocks, options.threads, [&](int b) {
      const std::size_t end = std::min(positions.size(), std::size_t(b + 1) * kTrianglesPerBlock);
      for (std::size_t i = std::size_t(b) * kTrianglesPerBlock; i < end; ++i) {
        const glm::dvec3 p(positions[i]);
        clip[i] = clipFromWorld * glm::dvec4(p, 1.0);
        largest[b] = std::max({largest[b], std::fabs(p.x), std::fabs(p.y), std::fabs(p.z)});
      }
    });
    // Each clip coordinate is a 4-term dot product in double (p_3 = 1):
    // error <= 4 u sum_j |M_rj| |p_j| <= 4 u (max|p| sum_{j<3} |M_rj| + |M_r3|).
    const double maxCoordinate = largest.empty() ? 1.0 : *std::max_element(largest.begin(), largest.end());
    double bound = 0.0;
    for (int r = 0; r < 4; ++r) {
      double linear = 0.0;
      for (int c = 0; c < 3; ++c) linear += std::fabs(clipFromWorld[c][r]);
      bound = std::max(bound, linear * maxCoordinate + std::fabs(clipFromWorld[3][r]));
    }
    context.clipError = 4.0 * 0x1p-53 * bound;
  }

  void emit(SetupBlock<Real>& block, std::uint32_t triangle, const glm::dvec4 sub[3],
            int clipMap, unsigned innerEdges) const {
    glm::dvec2 raster[3];
    for (int i = 0; i < 3; ++i) {
      raster[i].x = scene.camera.rasterXFromNdc(sub[i].x / sub[i].w);
      raster[i].y = scene.camera.rasterYFromNdc(sub[i].y / sub[i].w);
    }
    TriangleSetup<Real> s;
    if (!setupTriangle(sub, raster, innerEdges, clipMap >= 0, context, s)) return;
    s.triangle = triangle;
    s.clipMap = clipMap;
    block.setups.push_back(s);
  }

  void setupTriangleRange(std::size_t begin, std::size_t end, SetupBlock<Real>& block) const {
    const auto& triangles = scene.mesh.triangles;
    for (std::size_t t = begin; t < end; ++t) {
      const glm::dvec4 v[3] = {clip[triangles[t].x], clip[triangles[t].y], clip[triangles[t].z]};
      const unsigned c0 = volume.outcode(v[0]), c1 = volume.outcode(v[1]), c2 = volume.outcode(v[2]);
      if (c0 & c1 & c2) continue;  // all outside one plane: nothing visible
      const auto id = static_cast<std::uint32_t>(t);
      if ((c0 | c1 | c2) == 0) {
        emit(block, id, v, -1, 0u);
        continue;
      }
      const ClipVertex<double> in[3] = {{v[0], {1, 0, 0}}, {v[1], {0, 1, 0}}, {v[2], {0, 0, 1}}};
      ClipVertex<double> poly[kMaxClipVertices];
      const int n = clipPolygon(in, volume, c0 | c1 | c2, poly);
      for (int k = 1; k + 1 < n; ++k) {  // fan around poly[0]
        const glm::dvec4 sub[3] = {poly[0].clip, poly[k].clip, poly[k + 1].clip};
        block.clipMaps.push_back(
            glm::mat<3, 3, Real>(glm::dmat3(poly[0].bary, poly[k].bary, poly[k + 1].bary)));
        // The fan's diagonals poly[0]-poly[k] (opposite vertex 2) and poly[k+1]-poly[0]
        // (opposite vertex 1) run inside the polygon, except its first and last edges.
        const unsigned inner = (k > 1 ? 4u : 0u) | (k + 2 < n ? 2u : 0u);
        emit(block, id, sub, int(block.clipMaps.size()) - 1, inner);
      }
    }
  }

  void setupAll() {
    const std::size_t count = scene.mesh.triangles.size();
    const int blocks = int((count + kTrianglesPerBlock - 1) / kTrianglesPerBlock);
    std::vector<SetupBlock<Real>> parts(blocks);
    parallelFor(blocks, options.threads, [&](int b) {
      const std::size_t begin = std::size_t(b) * kTrianglesPerBlock;
      parts[b].setups.reserve(kTrianglesPerBlock);
      setupTriangleRange(begin, std::min(count, begin + kTrianglesPerBlock), parts[b]);
    });
    std::size_t total = 0;
    for (const SetupBlock<Real>& part : parts) total += part.setups.size();
    setups.reserve(total);
    for (SetupBlock<Real>& part : parts) {  // in block order: triangle order is kept
      const int offset = int(clipMaps.size());
      for (TriangleSetup<Real>& s : part.setups) {
        if (s.clipMap >= 0) s.clipMap += offset;
        setups.push_back(s);
      }
      clipMaps.insert(clipMaps.end(), part.clipMaps.begin(), part.clipMaps.end());
    }
  }
};

// Output planes, resolved once before the pixel loops.
struct OutputPlanes {
  std::uint32_t* id;
  float* bary[3];
  float* depth;
  float* baryBound;
  float* depthBound;
  float* edgeDistance;
  float* depthTie;
  struct AttributeOut {
    const float* values;  // per vertex, `components` each
    int components;
    float* out[4];
  };
  std::vector<AttributeOut> attributes;
};

OutputPlanes addOutputChannels(Framebuffer& fb, const Mesh& mesh) {
  OutputPlanes planes;
  planes.id = fb.addUint(channels::kTriangleId, channels::kNoTriangle);
  for (int i = 0; i < 3; ++i) planes.bary[i] = fb.addFloat(channels::kBary[i]);
  planes.depth = fb.addFloat(channels::kDepth);
  planes.baryBound = fb.addFloat(channels::kBaryBound);
  planes.depthBound = fb.addFloat(channels::kDepthBound);
  planes.edgeDistance = fb.addFloat(channels::kEdgeDistance);
  planes.depthTie = fb.addFloat(channels::kDepthTie);
  for (const Attribute& a : mesh.attributes) {
    OutputPlanes::AttributeOut out{a.values.data(), a.components, {}};
    for (int c = 0; c < a.components; ++c) {
      out.out[c] = fb.addFloat(channels::attributeChannel(a.name, c));
    }
    planes.attributes.push_back(out);
  }
  return planes;
}

template <typename Real>
void renderTile(const Pipeline<Real>& p, const std::uint32_t* binBegin, const std::uint32_t* binEnd,
                int tileX, int tileY, const OutputPlanes& out) {
  const int x0 = tileX * kTileSize, y0 = tileY * kTileSize;
  const int x1 = std::min(p.width, x0 + kTileSize) - 1, y1 = std::min(p.height, y0 + kTileSize) - 1;
  std::array<std::uint32_t, kTileSize * kTileSize> winner;
  std::array<Real, kTileSize * kTileSize> nearest;  // 1/w of the winner: larger is nearer
  winner.fill(kEmpty);
  nearest.fill(-std::numeric_limits<Real>::infinity());

  for (const std::uint32_t* it = binBegin; it != binEnd; ++it) {
    const std::uint32_t index = *it;
    const TriangleSetup<Real>& s = p.setups[index];
    EdgeFunctions edges{};
    const std::int64_t xf[3] = {s.xFixed[0], s.xFixed[1], s.xFixed[2]};
    const std::int64_t yf[3] = {s.yFixed[0], s.yFixed[1], s.yFixed[2]};
    makeEdgeFunctions(xf, yf, edges);
    forEachCoveredPixel(edges, p.options.subpixelBits, std::max(x0, s.minX), std::max(y0, s.minY),
                        std::min(x1, s.maxX), std::min(y1, s.maxY), [&](int x, int y) {
                          const Real z = depthKeyAt(s, offsetX(s, x), offsetY(s, y));
                          const int local = (y - y0) * kTileSize + (x - x0);
                          if (z > nearest[local]) {  // strict: the earlier triangle keeps a tie
                            nearest[local] = z;
                            winner[local] = index;
                          }
                        });
  }

  const bool perspective = p.options.interpolation == Interpolation::kPerspective;
  const auto& triangles = p.scene.mesh.triangles;
  for (int y = y0; y <= y1; ++y) {
    for (int x = x0; x <= x1; ++x) {
      const std::uint32_t index = winner[(y - y0) * kTileSize + (x - x0)];
      if (index == kEmpty) continue;
      const TriangleSetup<Real>& s = p.setups[index];
      const Real px = offsetX(s, x), py = offsetY(s, y);
      Real l[3];
      screenBarycentrics(s, px, py, l);
      const Recovered<Real> r = perspective ? perspectiveCorrect(l, s.invW) : affineWeights(l, s.w);
      glm::vec<3, Real> b(r.b[0], r.b[1], r.b[2]);
      if (s.clipMap >= 0) b = p.clipMaps[s.clipMap] * b;  // sub-triangle -> source triangle
      const std::size_t pixel = std::size_t(y) * p.width + x;
      out.id[pixel] = s.triangle;
      for (int i = 0; i < 3; ++i) out.bary[i][pixel] = float(b[i]);
      out.depth[pixel] = float(r.depth);
      out.baryBound[pixel] = s.baryBound;
      out.depthBound[pixel] = s.depthBound;
      out.edgeDistance[pixel] = edgeDistanceAt(s, l);
      out.depthTie[pixel] = depthTieAt(s, px, py, p.context.unitRoundoff, p.context.keyB, double(r.depth));
      const glm::uvec3& tri = triangles[s.triangle];
      for (const OutputPlanes::AttributeOut& a : out.attributes) {
        const float* v0 = a.values + std::size_t(tri.x) * a.components;
        const float* v1 = a.values + std::size_t(tri.y) * a.components;
        const float* v2 = a.values + std::size_t(tri.z) * a.components;
        for (int c = 0; c < a.components; ++c) {
          a.out[c][pixel] = float(b[0] * Real(v0[c]) + b[1] * Real(v1[c]) + b[2] * Real(v2[c]));
        }
      }
    }
  }
}

template <typename Real>
Framebuffer rasterizeAs(const Scene& scene, const RasterOptions& options) {
  Pipeline<Real> p(scene, options);
  p.transform();
  p.setupAll();

  // Binning by counting sort: one pass counts set-ups per tile, a prefix sum places each
  // tile's list in one flat array, a second pass fills it in set-up (= triangle) order.
  const int tilesX = (p.width + kTileSize - 1) / kTileSize;
  const int tilesY = (p.height + kTileSize - 1) / kTileSize;
  std::vector<std::size_t> binStart(std::size_t(tilesX) * tilesY + 1, 0);
  const auto forEachTile = [&](const TriangleSetup<Real>& s, auto&& fn) {
    for (int ty = s.minY / kTileSize; ty <= s.maxY / kTileSize; ++ty) {
      for (int tx = s.minX / kTileSize; tx <= s.maxX / kTileSize; ++tx) fn(std::size_t(ty) * tilesX + tx);
    }
  };
  for (const TriangleSetup<Real>& s : p.setups) forEachTile(s, [&](std::size_t t) { ++binStart[t + 1]; });
  for (std::size_t t = 1; t < binStart.size(); ++t) binStart[t] += binStart[t - 1];
  std::vector<std::uint32_t> binned(binStart.back());
  std::vector<std::size_t> cursor(binStart.begin(), binStart.end() - 1);
  for (std::size_t i = 0; i < p.setups.size(); ++i) {
    forEachTile(p.setups[i], [&](std::size_t t) { binned[cursor[t]++] = std::uint32_t(i); });
  }

  Framebuffer fb(p.width, p.height);
  const OutputPlanes out = addOutputChannels(fb, scene.mesh);
  parallelFor(tilesX * tilesY, options.threads, [&](int tile) {
    const std::uint32_t* begin = binned.data() + binStart[tile];
    renderTile(p, begin, begin + (binStart[tile + 1] - binStart[tile]), tile % tilesX, tile / tilesX, out);
  });
  return fb;
}

void checkSubpixelBits(const RasterOptions& options) {
  if (options.subpixelBits < 1 || options.subpixelBits > 16) {
    throw usageError("--subpixel-bits must be 1..16, got " + std::to_string(options.subpixelBits));
  }
}

template <typename Real>
std::vector<std::pair<std::uint32_t, std::uint32_t>> coveredPixelsAs(const Scene& scene, const RasterOptions& options) {
  Pipeline<Real> p(scene, options);
  p.transform();
  p.setupAll();
  std::vector<std::pair<std::uint32_t, std::uint32_t>> pairs;
  for (const TriangleSetup<Real>& s : p.setups) {
    EdgeFunctions edges{};
    const std::int64_t xf[3] = {s.xFixed[0], s.xFixed[1], s.xFixed[2]};
    const std::int64_t yf[3] = {s.yFixed[0], s.yFixed[1], s.yFixed[2]};
    makeEdgeFunctions(xf, yf, edges);
    forEachCoveredPixel(edges, options.subpixelBits, s.minX, s.minY, s.maxX, s.maxY, [&](int x, int y) {
      pairs.emplace_back(s.triangle, std::uint32_t(y) * std::uint32_t(p.width) + std::uint32_t(x));
    });
  }
  return pairs;
}

}  // namespace

std::vector<std::pair<std::uint32_t, std::uint32_t>> coveredPixels(const Scene& scene, const RasterOptions& options) {
  checkSubpixelBits(options);
  return options.precision == Precision::kFloat ? coveredPixelsAs<float>(scene, options)
                                                : coveredPixelsAs<double>(scene, options);
}

Framebuffer rasterize(const Scene& scene, const RasterOptions& options) {
  checkSubpixelBits(options);
  Framebuffer fb = options.precision == Precision::kFloat ? rasterizeAs<float>(scene, options)
                                                          : rasterizeAs<double>(scene, options);
  addPreview(fb);
  fb.attributes[channels::header::kRenderer] = "raster";
  fb.attributes[channels::header::kMode] = interpolationName(options.interpolation);
  fb.attributes[channels::header::kPrecision] = precisionName(options.precision);
  fb.attributes["rastercheck.subpixelBits"] = std::to_string(options.subpixelBits);
  fb.attributes["rastercheck.depthMapping"] = depthMappingName(options.depthMapping);
  // Snapping moves each vertex by at most sqrt(2)/2 grid steps, and so every edge; the double
  // raster positions themselves are far more accurate than that.
  char band[32];
  std::snprintf(band, sizeof band, "%.6g", 0.7072 * std::ldexp(1.0, -options.subpixelBits));
  fb.attributes[channels::header::kEdgeBand] = band;
  fb.attributes[channels::header::kScene] = scene.name;
  fb.attributes[channels::header::kCamera] = scene.camera.describe();
  return fb;
}

}  // namespace rc
