// The pixels on which the two images disagree (disagreements.h): their classes, the images'
// diagnostics, and each disagreement's explanation.
#include "compare/disagreements.h"

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <limits>
#include <string>
#include <string_view>
#include <vector>

#include "core/channels.h"

namespace rc {

namespace {

const float* optionalFloat(const Framebuffer& fb, const char* name) {
  const Channel* c = fb.find(name);
  return c && c->type == ChannelType::kFloat ? c->floats.data() : nullptr;
}

// A header number (a renderer's band or resolution), or NaN when absent or malformed.
double headerNumber(const Framebuffer& fb, const char* key) {
  const auto it = fb.attributes.find(key);
  if (it == fb.attributes.end()) return std::numeric_limits<double>::quiet_NaN();
  char* end = nullptr;
  const double value = std::strtod(it->second.c_str(), &end);
  return end && *end == '\0' && std::isfinite(value) && value >= 0.0 ? value : std::numeric_limits<double>::quiet_NaN();
}

// The depths of the clipping planes a render's camera drew between, from its header's camera
// line ("... near=N far=F ..."): those finite and above 0; none without the line.
std::vector<double> clipDepths(const Framebuffer& fb) {
  std::vector<double> depths;
  const auto it = fb.attributes.find(channels::header::kCamera);
  if (it == fb.attributes.end()) return depths;
  for (const std::string_view key : {" near=", " far="}) {
    const std::size_t at = it->second.find(key);
    if (at == std::string::npos) continue;
    const double depth = std::strtod(it->second.c_str() + at + key.size(), nullptr);
    if (std::isfinite(depth) && depth > 0.0) depths.push_back(depth);
  }
  return depths;
}

// The pixels one image alone covers.
std::size_t oneSideOnly(const CompareReport& r) {
  return r.classCounts[int(PixelClass::kTestOnly)] + r.classCounts[int(PixelClass::kReferenceOnly)];
}

// `count` pixels as a fraction of those either image covers (0 when none is).
double ofCovered(const CompareReport& r, std::size_t count) {
  return double(count) / double(std::max<std::size_t>(r.coveredEither, 1));
}

// Whether pixel i lies at an edge of `ids`: one of its eight neighbours holds another id (no
// triangle being one), or it is on the image's border, beyond which nothing is known.
bool atIdEdge(const PlaneVector<std::uint32_t>& ids, std::size_t i, int width, int height) {
  const int x = int(i % std::size_t(width)), y = int(i / std::size_t(width));
  if (x == 0 || y == 0 || x == width - 1 || y == height - 1) return true;
  const std::uint32_t id = ids[i];
  for (int dy = -1; dy <= 1; ++dy) {
    const std::uint32_t* row = &ids[std::size_t(y + dy) * std::size_t(width) + std::size_t(x)];
    if (row[-1] != id || row[0] != id || row[1] != id) return true;
  }
  return false;
}

}  // namespace

PlaneVector<PixelClass> classifyPixels(const PlaneVector<std::uint32_t>& testIds, const PlaneVector<std::uint32_t>& refIds,
                                       CompareReport& report) {
  const std::size_t n = testIds.size();
  // Per-pixel arrays in huge pages where the kernel allows (core/plane_allocator.h).
  PlaneVector<PixelClass> classes(n);  // every element is assigned below
  for (std::size_t i = 0; i < n; ++i) {
    const bool t = testIds[i] != channels::kNoTriangle, r = refIds[i] != channels::kNoTriangle;
    classes[i] = !t && !r ? PixelClass::kBothEmpty
                 : t && r ? (testIds[i] == refIds[i] ? PixelClass::kSameTriangle
                                                     : PixelClass::kDifferentTriangle)
                 : t      ? PixelClass::kTestOnly
                          : PixelClass::kReferenceOnly;
    ++report.classCounts[int(classes[i])];
  }
  report.coveredEither = n - report.classCounts[int(PixelClass::kBothEmpty)];
  report.disagreementFraction = ofCovered(report, report.classCounts[int(PixelClass::kDifferentTriangle)]);
  report.coverageFraction = ofCovered(report, oneSideOnly(report));
  return classes;
}

Diagnostics diagnosticsOf(const Framebuffer& test, const Framebuffer& ref) {
  Diagnostics d{{optionalFloat(test, channels::kBaryBound), optionalFloat(test, channels::kDepthBound)},
                {optionalFloat(ref, channels::kBaryBound), optionalFloat(ref, channels::kDepthBound)},
                false,
                optionalFloat(test, channels::kEdgeDistance),
                optionalFloat(ref, channels::kEdgeDistance),
                optionalFloat(test, channels::kDepthTie),
                optionalFloat(ref, channels::kDepthTie),
                headerNumber(test, channels::header::kEdgeBand),
                headerNumber(ref, channels::header::kEdgeBand),
                headerNumber(test, channels::header::kDepthResolution),
                headerNumber(ref, channels::header::kDepthResolution)};
  d.bounded = d.boundTest[0] && d.boundTest[1] && d.boundRef[0] && d.boundRef[1];
  return d;
}

// docs/numerics.md has the diagnostics' tolerances; docs/compare.md, "Without the diagnostics",
// the rule without them.
PlaneVector<Explanation> explainDisagreements(const Framebuffer& test, const Framebuffer& ref,
                                              const PlaneVector<std::uint32_t>& testIds,
                                              const PlaneVector<std::uint32_t>& refIds,
                                              const PlaneVector<PixelClass>& classes, const Diagnostics& d,
                                              double depthLimit, CompareReport& report) {
  const std::size_t n = classes.size();
  const int width = test.width(), height = test.height();
  PlaneVector<Explanation> explanations(n, Explanation::kUnexplained);
  const float* depthTest = test.find(channels::kDepth)->floats.data();
  const float* depthRef = ref.find(channels::kDepth)->floats.data();
  std::vector<double> clips = clipDepths(test);
  for (double depth : clipDepths(ref)) clips.push_back(depth);
  std::size_t tied[2] = {};  // depth ties: different triangle, one side only
  for (std::size_t i = 0; i < n; ++i) {
    const PixelClass c = classes[i];
    if (c == PixelClass::kBothEmpty || c == PixelClass::kSameTriangle) continue;
    const bool t = c != PixelClass::kReferenceOnly, r = c != PixelClass::kTestOnly;
    Explanation e = Explanation::kUnexplained;
    double tie = depthLimit;  // how far apart, relative to the larger, two depths still tie
    if (report.explained && ((t && double(d.edgeTest[i]) <= report.edgeBand) || (r && double(d.edgeRef[i]) <= report.edgeBand))) {
      e = Explanation::kEdgeBand;
    } else if (report.explained) {
      // Each path's depth-test resolution at the pixel: its depth.tie there (0 where it drew
      // nothing), else its header's. The winner's own resolution is known here; the loser's
      // is taken to be at most as large again (the factor 2), the other path's is added.
      tie = 2.0 * ((d.tieTest ? double(d.tieTest[i]) : d.resolutionTest) + (d.tieRef ? double(d.tieRef[i]) : d.resolutionRef));
    }
    // Without the diagnostics a depth tie comes before the ids' edges: either answer is right
    // there, and the fractions leave it out.
    if (e == Explanation::kUnexplained && t && r) {
      const double zt = depthTest[i], zr = depthRef[i];
      if (std::fabs(zt - zr) <= tie * std::max(std::fabs(zt), std::fabs(zr))) e = Explanation::kDepthTie;
    } else if (e == Explanation::kUnexplained) {
      // One side only (with the diagnostics, off every edge): a surface at the near or the far
      // plane, which one path keeps and the other clips, tied with that plane within the same
      // tolerance.
      const double z = t ? depthTest[i] : depthRef[i];
      for (double clip : clips) {
        if (std::fabs(z - clip) <= tie * std::fabs(z)) e = Explanation::kDepthTie;
      }
    }
    if (e == Explanation::kUnexplained && !report.explained &&
        (atIdEdge(testIds, i, width, height) || atIdEdge(refIds, i, width, height))) {
      e = Explanation::kIdEdge;
    }
    if (e == Explanation::kDepthTie) ++tied[c == PixelClass::kDifferentTriangle ? 0 : 1];
    explanations[i] = e;
    ++report.explanationCounts[int(e)];
    if (e == Explanation::kUnexplained && report.firstUnexplained.x < 0) {
      report.firstUnexplained = {int(i % width), int(i / width), double(testIds[i]), double(refIds[i])};
    }
  }
  report.untiedDisagreementFraction = ofCovered(report, report.classCounts[int(PixelClass::kDifferentTriangle)] - tied[0]);
  report.untiedCoverageFraction = ofCovered(report, oneSideOnly(report) - tied[1]);
  return explanations;
}

}  // namespace rc
