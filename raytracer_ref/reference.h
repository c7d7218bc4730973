// The ray-traced reference: one Embree ray through each pixel centre decides which triangle
// is hit; barycentrics, depth and attributes are then recomputed in double for that triangle
// and the camera's double-precision ray. Same entry shape as the rasterizer.
#pragma once

#include <memory>
#include <string>

#include "core/framebuffer.h"
#include "scenes/scene.h"

namespace rc {

// The quality of Embree's BVH build (RTCBuildQuality). At 1M triangles (blob, 1920x1080, 2
// threads, avx2) low builds in 57 ms and traces in 78, medium in 158 and 72: low is the faster
// reference for one frame, medium (Embree's default; high measured the same) for many frames of
// one scene. Only which triangle wins a tie in Embree moves with it (a pixel on an edge or in
// a depth tie), never a recomputed value.
enum class EmbreeBuild { kLow, kMedium, kHigh };
const char* embreeBuildName(EmbreeBuild build);  // "low", "medium", "high"

struct ReferenceOptions {
  int threads = 0;           // worker threads; 0 = all cores
  std::string isa = "avx2";  // Embree ISA pinned in the device config: sse2, sse4.2, avx, avx2,
                             // avx512; results differ between ISAs, so it is never left to Embree
  EmbreeBuild build = EmbreeBuild::kLow;  // check and render trace one frame a scene
  bool avx2Recompute = true;  // the double recomputation in AVX2 where the CPU has it, else the
                              // x86-64 baseline; both give the same bits (a switch for the tests)
};

// The reference in its two phases, so they can be timed apart: construction builds Embree's
// BVH, trace() shoots the rays. The scene must outlive the tracer.
// Both throw usageError when the CPU lacks the pinned ISA, internalError when Embree fails.
class ReferenceTracer {
 public:
  ReferenceTracer(const Scene& scene, const ReferenceOptions& options);
  ~ReferenceTracer();
  ReferenceTracer(const ReferenceTracer&) = delete;
  ReferenceTracer& operator=(const ReferenceTracer&) = delete;
  // Traces into `target`, writing every pixel of every channel (so a target of the same size
  // is reused without touching new memory) and the header attributes; no RGB preview.
  void trace(Framebuffer& target) const;
  // trace() into a new framebuffer, plus the RGB preview.
  Framebuffer trace() const;

 private:
  struct Impl;  // keeps Embree out of this header
  std::unique_ptr<Impl> impl_;
};

// The widest Embree ISA this CPU runs: avx512, avx2, avx, sse4.2 or sse2. bench traces with it
// unless told otherwise, so the speed-ups are against Embree's fastest mode on the machine.
std::string fastestEmbreeIsa();

// The version of the Embree library the program runs with, as a device reports it ("3.13.5").
std::string embreeVersion();

// Build and trace in one call.
Framebuffer renderReference(const Scene& scene, const ReferenceOptions& options);

}  // namespace rc
