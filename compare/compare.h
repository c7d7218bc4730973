// Comparing a test render against a reference render, both in the channel layout of
// core/channels.h: pixel classes, error statistics per channel family, and the gate's verdict.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "compare/statistics.h"
#include "core/framebuffer.h"

namespace rc {

enum class PixelClass : std::uint32_t {
  kBothEmpty = 0,
  kSameTriangle = 1,
  kDifferentTriangle = 2,
  kTestOnly = 3,       // covered in the test image only
  kReferenceOnly = 4,  // covered in the reference only
};
inline constexpr int kPixelClassCount = 5;
const char* pixelClassName(PixelClass c);

// Gate thresholds. Each default sits well above the largest error the default rasterizer
// (float, perspective, 8 subpixel bits) was measured to make on the built-in scenes; the
// barycentric one also sits below the smallest error affine interpolation makes there
// (docs/compare.md has the table and the reasoning).
struct Thresholds {
  double bary = 2e-4;          // max |b_test - b_ref| over components, same-triangle pixels
  double depth = 2e-5;         // max |d_test - d_ref| / |d_ref|
  double attribute = 1e-4;     // max |a_test - a_ref| / (range of a in the reference)
  double disagreement = 5e-3;  // different-triangle pixels / pixels covered by either image
  double coverage = 1e-3;      // one-side-only pixels / pixels covered by either image
};

struct FamilyReport {
  std::string name;    // "bary", "depth" or "attr.<name>"
  std::string unit;    // "absolute", "relative" (depth) or "absolute" with `range`
  double range = 0.0;  // attributes: max - min of the reference values over covered pixels
  double threshold = 0.0;
  double gated = 0.0;  // the value compared with the threshold (max, or max / range)
  FamilyStats stats;
};

struct CompareReport {
  std::string testPath, referencePath;
  int width = 0, height = 0;
  std::size_t classCounts[kPixelClassCount] = {};
  std::size_t coveredEither = 0;
  double disagreementFraction = 0.0;
  double coverageFraction = 0.0;
  std::vector<FamilyReport> families;
  Thresholds thresholds;
  bool pass = false;
  std::vector<std::string> reasons;  // why it failed; empty when it passed
};

// Throws badInput (naming the file and channel) when the images are not comparable: sizes
// differ, a required or attribute channel is missing in one of them, or has the wrong type.
// `heatmap`, when non-null, receives error.* channels, class.id and a false-colour RGB.
CompareReport compareImages(const Framebuffer& test, const std::string& testPath,
                            const Framebuffer& reference, const std::string& referencePath,
                            const Thresholds& thresholds, Framebuffer* heatmap);

}  // namespace rc
