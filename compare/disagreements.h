// The pixels on which the two images disagree (compareImages' part in disagreements.cpp): each
// pixel's class by the two images' triangle ids, what the images' diagnostics give, and each
// disagreement's explanation (docs/compare.md: with the diagnostics, and without them).
#pragma once

#include <cmath>
#include <cstdint>

#include "compare/compare.h"
#include "core/framebuffer.h"
#include "core/plane_allocator.h"

namespace rc {

// What the two images' diagnostics give (docs/numerics.md): per-pixel bounds and edge distances,
// depth ties, and each path's edge band and depth resolution from its header. Any of them may be
// absent: a pointer is null and a number NaN then.
struct Diagnostics {
  const float* boundTest[2];  // barycentric, depth
  const float* boundRef[2];
  bool bounded;  // all four bounds: the gate holds errors to them
  const float *edgeTest, *edgeRef, *tieTest, *tieRef;
  double bandTest, bandRef, resolutionTest, resolutionRef;
  // Enough to explain a disagreement: both edge distances and bands, and each side's depth
  // resolution per pixel or from its header.
  bool explains() const {
    return edgeTest && edgeRef && std::isfinite(bandTest) && std::isfinite(bandRef) &&
           (tieTest || std::isfinite(resolutionTest)) && (tieRef || std::isfinite(resolutionRef));
  }
};

// The diagnostics of both images, each absent one null or NaN.
Diagnostics diagnosticsOf(const Framebuffer& test, const Framebuffer& ref);

// Each pixel's class, by the triangle each image has there, counted into the report with the
// fractions of the covered pixels that disagree and that one side alone covers.
PlaneVector<PixelClass> classifyPixels(const PlaneVector<std::uint32_t>& testIds, const PlaneVector<std::uint32_t>& refIds,
                                       CompareReport& report);

// Each disagreement explained, counted into the report with the first unexplained pixel and the
// fractions with the depth ties left out. With the diagnostics (report.explained): within the
// edge band, or a depth tie within the paths' resolutions. Without them: at an edge of either
// image's ids, or a depth tie within `depthLimit` (relative). A depth tie is with the other
// surface, or with a clipping plane. Else unexplained.
PlaneVector<Explanation> explainDisagreements(const Framebuffer& test, const Framebuffer& ref,
                                              const PlaneVector<std::uint32_t>& testIds,
                                              const PlaneVector<std::uint32_t>& refIds,
                                              const PlaneVector<PixelClass>& classes, const Diagnostics& d,
                                              double depthLimit, CompareReport& report);

}  // namespace rc
