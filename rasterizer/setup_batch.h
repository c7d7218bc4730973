// setupCoverage and setupShade (setup.h) for four whole triangles at once, in lanes of double
// (and int64).
//
// Each lane runs setupCoverage's operations in the same order (no FMA), so every record it
// accepts has the same bits as setupCoverage's, and every ShadeSetup as setupShade's
// (SetupBatch.*BitForBit).
// Compiled like the tile kernels: once for the x86-64 baseline, once with the AVX2 target.
#pragma once

#include <cstdint>
#include <glm/glm.hpp>

#include "rasterizer/setup.h"

namespace rc::batch {

constexpr int kLanes = 4;

// The triangles tris[0..4), given as vertex indices into per-vertex clip positions and raster
// positions, each vertex inside the view volume (outcode 0). Writes c[k] for every lane k that
// setupCoverage would accept, and returns those lanes as bits (bit k for lane k).
unsigned setupCoverageSse2(const glm::uvec3 tris[kLanes], const glm::dvec4* clip, const glm::dvec2* raster,
                           const SetupContext& ctx, CoverageSetup<float> c[kLanes]);
unsigned setupCoverageSse2(const glm::uvec3 tris[kLanes], const glm::dvec4* clip, const glm::dvec2* raster,
                           const SetupContext& ctx, CoverageSetup<double> c[kLanes]);
unsigned setupCoverageAvx2(const glm::uvec3 tris[kLanes], const glm::dvec4* clip, const glm::dvec2* raster,
                           const SetupContext& ctx, CoverageSetup<float> c[kLanes]);
unsigned setupCoverageAvx2(const glm::uvec3 tris[kLanes], const glm::dvec4* clip, const glm::dvec2* raster,
                           const SetupContext& ctx, CoverageSetup<double> c[kLanes]);

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
