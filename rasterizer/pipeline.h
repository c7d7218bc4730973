// Stages 1 to 3 of the rasterizer (rasterizer.cpp runs stage 4, the tiles): the working memory
// of a frame (Frame), which the Rasterizer keeps from frame to frame, and the Pipeline that fills
// it: the transform, clipping and coverage set-up per block of triangles, and the bins per tile.
#pragma once

#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <vector>

#include <glm/glm.hpp>

#include "core/plane_allocator.h"
#include "rasterizer/clip.h"
#include "rasterizer/rasterizer.h"
#include "rasterizer/setup.h"
#include "rasterizer/transform.h"
#include "scenes/scene.h"

namespace rc {

// A block's coverage set-ups, in order. They go into the block's slice of one frame-wide
// array (in huge pages: the slices of a million-triangle frame are 64 MB, a fault per 4 KB page
// otherwise) and spill into a vector of the block's own in the rare block whose clipped
// triangles make more set-ups than the slice holds. Either way they are contiguous.
template <typename T>
class SetupList {
 public:
  void reset(T* slice, std::size_t capacity) {
    slice_ = data_ = slice;
    capacity_ = capacity;
    size_ = 0;
  }
  void push_back(const T& value) {
    if (size_ == capacity_) spill();
    data_[size_++] = value;
  }
  T& back() { return data_[size_ - 1]; }
  T& operator[](std::size_t i) { return data_[i]; }
  const T& operator[](std::size_t i) const { return data_[i]; }
  T* data() { return data_; }
  const T* data() const { return data_; }
  std::size_t size() const { return size_; }

 private:
  void spill() {
    if (data_ == slice_) spill_.assign(slice_, slice_ + size_);
    spill_.resize(std::max<std::size_t>(2 * size_, 64));
    data_ = spill_.data();
    capacity_ = spill_.size();
  }
  T* slice_ = nullptr;
  T* data_ = nullptr;
  std::size_t capacity_ = 0, size_ = 0;
  std::vector<T> spill_;
};

// One block of triangles' set-ups, its clipped sub-triangles, and its share of the bins.
template <typename Real>
struct SetupBlock {
  SetupList<CoverageSetup<Real>> coverage;
  std::vector<ClippedTriangle> clipped;
  std::vector<std::size_t> tileCursor;         // per tile: count, then where this block's list goes
  std::vector<std::uint32_t> tileBox;          // per set-up: tileBoxOf()
  double clippedShift = 0.0;  // the largest rasterShift of the clipped sub-triangles' vertices
};

// The working memory of a frame's stages 1 to 3, which the Rasterizer keeps from frame to frame.
template <typename Real>
struct Frame {
  // The frame-sized arrays come in huge pages where the kernel allows (PlaneAllocator): a first
  // frame faults them in, and in 4 KB pages that cost more than rendering it
  // (docs/rasterizer.md, "A first frame"). Every element is written before it is read.
  PlaneVector<glm::dvec4> clip;       // per mesh vertex
  PlaneVector<glm::dvec2> raster;     // per mesh vertex, when its outcode is 0
  PlaneVector<std::uint8_t> outcode;  // per mesh vertex (clip.h)
  std::vector<VertexFacts> vertexFacts;  // per transform block
  VertexFacts vertices;                   // all of them
  bool allInside = false;         // every vertex inside the view volume: every triangle whole
  std::vector<SetupBlock<Real>> blocks;
  // The blocks' coverage slices (SetupList), blockSize records each; unwritten until set up.
  PlaneVector<CoverageSetup<Real>> coverageSlices;
  std::vector<const CoverageSetup<Real>*> blockCoverage;
  std::vector<const ClippedTriangle*> blockClipped;
  std::vector<std::size_t> tileTotal;  // per tile: set-ups binned to it
  std::vector<std::size_t> binStart;  // per tile + 1
  PlaneVector<std::uint32_t> binned;  // set-up names, tile by tile
  std::vector<int> blockWorker;        // per block: the worker that set it up
  std::vector<std::size_t> tileShare;  // per worker and tile: set-ups it made binned there
  std::vector<std::vector<int>> blockQueues, tileQueues;  // per worker (parallelForQueues)
};

// One frame's stages 1 to 3 over `frame` (pipeline.cpp). Throws usageError where the image or
// the mesh does not fit the set-up's integer ranges.
template <typename Real>
struct Pipeline {
  const Scene& scene;
  const RasterOptions& options;
  Frame<Real>& frame;
  KernelIsa isa;  // options.isa as resolved on this CPU, once per frame
  int width, height, tilesX, tilesY;
  std::size_t blockSize;  // triangles per block
  ClipVolume<double> volume;
  SetupContext context{};
  // The batch set-up for the kernels' instruction set.
  unsigned (*batchSetup)(const glm::uvec3*, const glm::dvec4*, const glm::dvec2*, const SetupContext&,
                         CoverageSetup<Real>*);

  Pipeline(const Scene& s, const RasterOptions& o, Frame<Real>& workspace);
  int tileCount() const { return tilesX * tilesY; }
  glm::dvec2 rasterOf(const glm::dvec4& c) const { return rc::rasterOf(scene.camera, c); }

  // Stage 1: every vertex to clip space, and to raster space where it lies inside the view
  // volume; the vertices' facts, the clip error bound, and whether back faces are culled.
  void transform();
  // Stages 2 and 3: the set-ups of every block of triangles, then each tile's list of them.
  void setupAndBin(StageTimes& times);
  // The header's edge band, in pixels; after set-up.
  double edgeBand() const;

  // The parts of the stages.
  double rasterShift(const glm::dvec4& c, const glm::dvec2& r) const;
  double insideShift() const;
  void emit(SetupBlock<Real>& block, std::uint32_t triangle, const glm::dvec4 sub[3], const glm::dvec2 raster[3],
            int clipped) const;
  static void append(SetupBlock<Real>& block, const CoverageSetup<Real>& c, std::uint32_t triangle, int clipped);
  template <typename IdOf>
  void setupWhole(const glm::uvec3 tris[], std::size_t n, IdOf&& idOf, CoverageSetup<Real> c[],
                  SetupBlock<Real>& block) const;
  void setupTriangleRange(std::size_t begin, std::size_t end, SetupBlock<Real>& block) const;
  void setupAllInside(std::size_t begin, std::size_t end, SetupBlock<Real>& block) const;
  void setupClipped(std::uint32_t id, const glm::uvec3& tri, unsigned outcodes, SetupBlock<Real>& block) const;
  static std::uint32_t tileBoxOf(const CoverageSetup<Real>& s);
  template <typename Fn>
  void forEachTile(std::uint32_t box, Fn&& fn) const;
  void breakFillRule(SetupBlock<Real>& block) const;
  void setupBlocks(int workers);
  void binBlocks(int workers);
  void assignTiles(int workers);
};

extern template struct Pipeline<float>;
extern template struct Pipeline<double>;

}  // namespace rc
