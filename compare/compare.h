// Comparing a test render against a reference render, both in the channel layout of
// core/channels.h: pixel classes, error statistics per channel family, and the gate's verdict.
#pragma once

#include <cstdint>
#include <map>
#include <optional>
#include <string>
#include <vector>

#include "compare/statistics.h"
#include "core/framebuffer.h"

namespace rc {

enum class PixelClass : std::uint8_t {
  kBothEmpty = 0,
  kSameTriangle = 1,
  kDifferentTriangle = 2,
  kTestOnly = 3,       // covered in the test image only
  kReferenceOnly = 4,  // covered in the reference only
};
inline constexpr int kPixelClassCount = 5;
const char* pixelClassName(PixelClass c);

// Why the two paths disagree on the triangle at a pixel (docs/numerics.md, "Disagreements").
enum class Explanation : std::uint8_t {
  kEdgeBand = 0,     // the centre is within both paths' edge bands of an edge of either triangle
  kDepthTie = 1,     // both hit, and the two depths are within the paths' depth resolutions
  kUnexplained = 2,
  // Without the diagnostics (docs/compare.md, "Without the diagnostics"): a neighbour of the
  // pixel, of the eight, holds another id in either image, or the pixel is on the border. A
  // depth tie is then within the depth limit, and kUnexplained lies inside both images' ids.
  kIdEdge = 3,
};
inline constexpr int kExplanationCount = 4;
// The heatmap's explanation.id where the two images agree (both empty, or the same triangle).
inline constexpr std::uint32_t kNothingToExplain = 0xFFFFFFFFu;
const char* explanationName(Explanation e);

// What the heatmap's colours show, for the barycentric family.
enum class HeatmapQuantity {
  kError,       // |b_test - b_ref|, log scale 1e-8..1e-1
  kUlps,        // the same in float ulps just below 1 (2^-24), log scale 1e-1..1e6
  kBoundRatio,  // error / (sum of the two paths' bounds), log scale 1e-4..1e2; > 1 fails
};

// Gate thresholds. Each default sits well above the largest error the default rasterizer
// (float, perspective, 8 subpixel bits) was measured to make on the built-in scenes; the
// barycentric one also sits below the smallest error affine interpolation makes there
// (docs/compare.md has the table and the reasoning).
// These fixed thresholds apply only to images without the diagnostics of docs/numerics.md
// (bound.*, edge.dist): both renderers write them, and then the gate is the bound rule.
struct Thresholds {
  double bary = 2e-4;          // max |b_test - b_ref| over components, same-triangle pixels
  double depth = 2e-5;         // max |d_test - d_ref| / |d_ref|
  double attribute = 1e-4;     // max |a_test - a_ref| / (range of a in the reference)
  // Without the diagnostics, each disagreement must also lie at an edge of either image's ids
  // or be a depth tie within `depth` (Explanation::kIdEdge, docs/compare.md).
  double disagreement = 5e-3;  // different-triangle pixels not tied in depth / pixels covered by either image
  double coverage = 1e-3;      // one-side-only pixels not tied with a clipping plane / the same
  // A pair in which neither image covers a pixel compares nothing: it fails the gate (a camera
  // that misses the mesh) unless this says it may pass.
  bool allowEmpty = false;
  HeatmapQuantity heatmap = HeatmapQuantity::kError;
  // The attribute families compared, by name ("uv" for attr.uv.*): each must be in both
  // images, and the others either image carries are left out. Empty: every one either image
  // carries, each required in both.
  std::vector<std::string> attributes = {};
  // Per attribute family, by name ("color"): its own limit in place of `attribute`. Each name
  // must be an attribute family compared, or compareImages refuses it as a usage error.
  std::map<std::string, double> attributeByName = {};

  // The limit of attribute family `name` ("uv", without "attr."): its own, else `attribute`.
  double attributeLimit(const std::string& name) const {
    const auto it = attributeByName.find(name);
    return it == attributeByName.end() ? attribute : it->second;
  }

  // Warning limits (--warn-*), on the measured values whatever gates them (the bounds or the
  // limits above), in the same units: a value beyond one is a warning, printed and reported,
  // which never fails the gate. Unset: no warning. For a CI that wants to hear of an error
  // that grew but still passes.
  struct Warnings {
    std::optional<double> bary, depth, attribute, disagreement, coverage;
    std::map<std::string, double> attributeByName = {};  // as attributeByName above
    // --fail-on-warnings: every warning (these limits', a baseline's) fails the gate instead,
    // as one of its reasons.
    bool fail = false;

    // As Thresholds::attributeLimit: attribute `name`'s own warning limit, else `attribute`.
    std::optional<double> attributeLimit(const std::string& name) const {
      const auto it = attributeByName.find(name);
      return it == attributeByName.end() ? attribute : it->second;
    }
  } warn = {};
};

// Whether a channel family's name ("bary", "depth", "attr.uv") is an attribute's.
inline bool isAttributeFamily(const std::string& name) { return name != "bary" && name != "depth"; }

struct FamilyReport {
  std::string name;    // "bary", "depth" or "attr.<name>"
  std::string unit;    // "absolute", "relative" (depth) or "absolute" with `range`
  double range = 0.0;  // attributes: max - min of the reference values over covered pixels
  bool bounded = false;  // gated per pixel against the two paths' bounds (else `threshold`)
  double threshold = 0.0;
  double gated = 0.0;  // the value compared with the limit: max / bound, or max (/ range)
  FamilyStats stats;   // errors
  FamilyStats ulps;    // errors in float ulps: just below 1, 2^-24 (bary), of the value (depth), of the range
  FamilyStats ratio;   // errors / bound, when bounded

  bool isAttribute() const { return isAttributeFamily(name); }
};

// The earlier report a comparison was held to (--baseline, compare/baseline.h), and the factor
// by which a figure may grow before it is a warning.
struct BaselineUse {
  std::string file;
  double factor = 2.0;
};

struct CompareReport {
  std::string testPath, referencePath;
  int width = 0, height = 0;
  // The camera the images were rendered through, as their rastercheck.camera headers record it
  // (the reference's, or the test's when only it records one); empty when neither does.
  std::string camera;
  std::size_t classCounts[kPixelClassCount] = {};
  std::size_t coveredEither = 0;
  double disagreementFraction = 0.0;
  double coverageFraction = 0.0;
  // The fractions the fixed limits gate without the diagnostics: those above without the
  // pixels tied in depth (with the other surface, or a clipping plane), where either is right.
  double untiedDisagreementFraction = 0.0;
  double untiedCoverageFraction = 0.0;
  bool explained = false;  // disagreements classified (both images carry edge.dist and bands)
  // Without: classified by what the ids and depths show (Explanation::kIdEdge).
  std::size_t explanationCounts[kExplanationCount] = {};
  double edgeBand = 0.0;  // pixels: the sum of the two paths' bands
  WorstPixel firstUnexplained;
  std::vector<FamilyReport> families;
  std::vector<std::string> leftOut;  // attribute families an image carries that --attributes left out
  Thresholds thresholds;
  bool pass = false;
  std::vector<std::string> reasons;   // why it failed; empty when it passed
  std::vector<std::string> warnings;  // the warning limits exceeded (Thresholds::warn); never fail
  std::optional<BaselineUse> baseline;  // with --baseline: its warnings are among `warnings`

  // With thresholds.warn.fail, moves the warnings to the reasons: each fails the gate.
  void settleWarnings() {
    if (!thresholds.warn.fail || warnings.empty()) return;
    reasons.insert(reasons.end(), warnings.begin(), warnings.end());
    warnings.clear();
    pass = false;
  }
};

// Throws badInput (naming the file and channel) when the images are not comparable: sizes
// differ, a required or attribute channel is missing in one of them, or has the wrong type.
// `heatmap`, when non-null, receives error.* channels, class.id and a false-colour RGB.
// The channel families are measured on up to `threads` threads (0: all cores), each family on
// one, in pixel order, so every figure is the same whatever the thread count.
CompareReport compareImages(const Framebuffer& test, const std::string& testPath,
                            const Framebuffer& reference, const std::string& referencePath,
                            const Thresholds& thresholds, Framebuffer* heatmap, int threads = 0);

}  // namespace rc
