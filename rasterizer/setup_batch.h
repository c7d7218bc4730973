// setupCoverage and setupShade (setup.h) for four whole triangles at once, in lanes of double
// (and int64).
//
// Each lane runs setupCoverage's operations in the same order (no FMA), so every record it
// accepts has the same bits as setupCoverage's, and every ShadeSetup as setupShade's
// (SetupBatch.*BitForBit), with snapping or without (subpixelBits 0: exact orientations, the
// lanes that the filter leaves open decided one by one).
// Compiled for the x86-64 baseline and with the AVX2 target; the coverage half also with
// AVX-512 (one instruction per int64 multiply, minimum and maximum), which the AVX-512 tile
// kernels' level runs (docs/rasterizer.md, "SIMD and instruction sets").
#pragma once

#include <cstdint>
#include <glm/glm.hpp>

#include "rasterizer/setup.h"

namespace rc::batch {

constexpr int kLanes = 4;

// The triangles tris[0..4), given as vertex indices into per-vertex clip positions and raster
// positions, each vertex inside the view volume (outcode 0). Writes c[k] for every lane k that
// setupCoverage would accept, and returns those lanes as bits (bit k for lane k). Each name has
// an overload for float and one for double records.
#define RC_COVERAGE_BATCH(name)                                                                              \
  unsigned name(const glm::uvec3 tris[kLanes], const glm::dvec4* clip, const glm::dvec2* raster,            \
                const SetupContext& ctx, CoverageSetup<float> c[kLanes]);                                    \
  unsigned name(const glm::uvec3 tris[kLanes], const glm::dvec4* clip, const glm::dvec2* raster,            \
                const SetupContext& ctx, CoverageSetup<double> c[kLanes]);
// With snapping (ctx.subpixelBits 1 to 16).
RC_COVERAGE_BATCH(setupCoverageSse2)
RC_COVERAGE_BATCH(setupCoverageAvx2)
RC_COVERAGE_BATCH(setupCoverageAvx512)  // one instruction per int64 multiply, minimum and maximum
// Without snapping (ctx.subpixelBits 0: setup.cpp's setupUnsnapped), kept apart so that the
// snapped batch holds no test of the setting. No AVX-512 build: it has no int64 lanes.
RC_COVERAGE_BATCH(setupUnsnappedSse2)
RC_COVERAGE_BATCH(setupUnsnappedAvx2)
#undef RC_COVERAGE_BATCH

// setupShade for four whole triangles (innerEdges 0, not clipped) with their accepted
// CoverageSetups: s[k] from tris[k] and *c[k], all but the triangle and clipMap fields.
void setupShadeSse2(const glm::uvec3 tris[kLanes], const glm::dvec4* clip, const glm::dvec2* raster,
                    const SetupContext& ctx, const CoverageSetup<float>* const c[kLanes],
                    ShadeSetup<float>* const s[kLanes]);
void setupShadeSse2(const glm::uvec3 tris[kLanes], const glm::dvec4* clip, const glm::dvec2* raster,
                    const SetupContext& ctx, const CoverageSetup<double>* const c[kLanes],
                    ShadeSetup<double>* const s[kLanes]);
void setupShadeAvx2(const glm::uvec3 tris[kLanes], const glm::dvec4* clip, const glm::dvec2* raster,
                    const SetupContext& ctx, const CoverageSetup<float>* const c[kLanes],
                    ShadeSetup<float>* const s[kLanes]);
void setupShadeAvx2(const glm::uvec3 tris[kLanes], const glm::dvec4* clip, const glm::dvec2* raster,
                    const SetupContext& ctx, const CoverageSetup<double>* const c[kLanes],
                    ShadeSetup<double>* const s[kLanes]);

}  // namespace rc::batch
