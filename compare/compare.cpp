// compareImages: compatibility checks, family statistics, gate, heatmap; the pixel classes and
// the disagreements' explanations in disagreements.cpp.
#include "compare/compare.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <map>
#include <optional>
#include <string_view>
#include <utility>
#include <vector>

#include "compare/colormap.h"
#include "compare/disagreements.h"
#include "compare/report.h"
#include "core/channels.h"
#include "core/error.h"
#include "core/parallel.h"
#include "core/plane_allocator.h"

namespace rc {

const char* pixelClassName(PixelClass c) {
  switch (c) {
    case PixelClass::kBothEmpty: return "both_empty";
    case PixelClass::kSameTriangle: return "same_triangle";
    case PixelClass::kDifferentTriangle: return "different_triangle";
    case PixelClass::kTestOnly: return "test_only";
    default: return "reference_only";
  }
}

const char* explanationName(Explanation e) {
  switch (e) {
    case Explanation::kEdgeBand: return "edge_band";
    case Explanation::kDepthTie: return "depth_tie";
    case Explanation::kIdEdge: return "id_edge";
    default: return "unexplained";
  }
}

namespace {

std::string formatPixel(const WorstPixel& p) {
  return p.x < 0 ? std::string("-") : "(" + std::to_string(p.x) + "," + std::to_string(p.y) + ")";
}

HeatScale heatScale(HeatmapQuantity q) {
  return heatScaleByKey(q == HeatmapQuantity::kUlps ? "ulps" : q == HeatmapQuantity::kBoundRatio ? "bound" : "error");
}

// "VALUE exceeds LIMIT" (or "VALUE, limit LIMIT") in as few significant digits as tell the two
// apart, at least 3: fixed decimals printed 1.9e-7 against 1e-9 as 0.000000 against 0.000000.
std::string overLimit(double value, double limit, const char* joint) {
  const auto [a, b] = formatApart(value, limit);
  return a + joint + b;
}

// "uv" of the attribute family "attr.uv" (collectFamilies refuses a channel without a name).
std::string attributeName(const std::string& family) {
  return family.substr(std::string_view(channels::kAttributePrefix).size());
}

// Adds `head` + "VALUE" + `joint` + "LIMIT" to `to` when `value` is beyond `limit` (a NaN is):
// the gate's reasons and the warnings, worded alike.
void addIfOver(std::vector<std::string>& to, const std::string& head, double value, double limit, const char* joint) {
  if (!(value <= limit)) to.push_back(head + overLimit(value, limit, joint));
}

// The warning limits a report's measured values exceed (Thresholds::warn): the same values
// the fixed limits take (a family's max error, of its range for an attribute that has one).
std::vector<std::string> warningsOf(const CompareReport& r, const Thresholds::Warnings& w) {
  std::vector<std::string> warnings;
  for (const FamilyReport& f : r.families) {
    const std::optional<double> limit = f.name == "bary"    ? w.bary
                                        : f.name == "depth" ? w.depth
                                                            : w.attributeLimit(attributeName(f.name));
    const bool ofRange = f.isAttribute() && f.range > 0.0;
    if (limit) {
      addIfOver(warnings, f.name + ": max error ", ofRange ? f.stats.max / f.range : f.stats.max, *limit,
                ofRange ? " of range exceeds the warning limit " : " exceeds the warning limit ");
    }
  }
  if (w.disagreement) {
    addIfOver(warnings, "different triangle at ", r.disagreementFraction, *w.disagreement,
              " of covered pixels, warning limit ");
  }
  if (w.coverage) {
    addIfOver(warnings, "one-side-only coverage at ", r.coverageFraction, *w.coverage,
              " of covered pixels, warning limit ");
  }
  return warnings;
}

const Channel& require(const Framebuffer& fb, const std::string& path, const std::string& name,
                       ChannelType type, const std::string& otherPath, const std::string& hint = "") {
  const Channel* c = fb.find(name);
  if (!c) {
    throw badInput(path + ": channel " + name,
                   otherPath.empty() ? "missing" : "missing (present in " + otherPath + hint + ")");
  }
  if (c->type != type) {
    throw badInput(path + ": channel " + name, std::string("is ") + channelTypeName(c->type) +
                                                   ", expected " + channelTypeName(type));
  }
  return *c;
}

// Spacing of floats at |x| (the smallest subnormal at 0).
double floatUlp(double x) {
  const float f = std::fabs(float(x));
  return double(std::nextafter(f, std::numeric_limits<float>::infinity())) - double(f);
}

// A channel family: the planes of one quantity in both images (e.g. attr.uv.x and attr.uv.y).
struct Family {
  std::string name;
  enum Kind { kBary, kDepth, kAttribute } kind;
  std::vector<const float*> test, reference;
  // An attribute's: the reference's spread.NAME (channels::spreadChannel), or null.
  const float* spread = nullptr;
};

std::vector<Family> collectFamilies(const Framebuffer& test, const std::string& testPath,
                                    const Framebuffer& ref, const std::string& refPath,
                                    const Thresholds& thresholds, std::vector<std::string>& leftOut) {
  const std::vector<std::string>& selection = thresholds.attributes;
  std::vector<Family> families;
  Family bary{"bary", Family::kBary, {}, {}};
  for (const char* name : channels::kBary) {
    bary.test.push_back(require(test, testPath, name, ChannelType::kFloat, "").floats.data());
    bary.reference.push_back(require(ref, refPath, name, ChannelType::kFloat, "").floats.data());
  }
  families.push_back(bary);
  families.push_back({"depth", Family::kDepth,
                      {require(test, testPath, channels::kDepth, ChannelType::kFloat, "").floats.data()},
                      {require(ref, refPath, channels::kDepth, ChannelType::kFloat, "").floats.data()}});
  // Attribute channels: the union over both images, each required in both.
  std::map<std::string, std::vector<std::string>> attributes;  // family -> channel names
  const std::string prefix = channels::kAttributePrefix;
  for (const auto& [fb, path] : {std::pair{&test, &testPath}, std::pair{&ref, &refPath}}) {
    for (const Channel& c : fb->channels()) {
      if (c.name.rfind(prefix, 0) != 0) continue;
      // attr.NAME.COMPONENT: a name, not empty, before the last dot (attr.x has none).
      const std::size_t dot = c.name.rfind('.');
      if (dot <= prefix.size()) {
        throw badInput(*path + ": channel " + c.name, "names no attribute (attribute channels are attr.NAME.x, .y, .z, .w)");
      }
      const std::string family = c.name.substr(0, dot);
      auto& names = attributes[family];
      if (std::find(names.begin(), names.end(), c.name) == names.end()) names.push_back(c.name);
    }
  }
  // An option naming an attribute family neither image carries is a usage error (a typo).
  const auto requireCarried = [&](const std::string& option, const std::string& name) {
    if (attributes.count(prefix + name) != 0) return;
    std::string carried;
    for (const auto& entry : attributes) carried += (carried.empty() ? "" : ", ") + entry.first.substr(prefix.size());
    throw usageError(option + " " + name + ": neither " + testPath + " nor " + refPath + " carries it" +
                     (carried.empty() ? std::string(" (they carry no attributes)") : " (they carry " + carried + ")"));
  };
  for (const auto& [name, limit] : thresholds.attributeByName) requireCarried("--max-attr", name);
  for (const auto& [name, limit] : thresholds.warn.attributeByName) requireCarried("--warn-attr", name);
  if (!selection.empty()) {
    std::map<std::string, std::vector<std::string>> chosen;
    for (const std::string& name : selection) {
      requireCarried("--attributes", name);
      chosen.insert(*attributes.find(prefix + name));
    }
    for (const auto& entry : attributes) {
      if (chosen.count(entry.first) == 0) leftOut.push_back(entry.first);
    }
    // A limit for a family --attributes leaves out would gate nothing: say so.
    for (const auto& [option, limits] : {std::pair{"--max-attr", &thresholds.attributeByName},
                                         std::pair{"--warn-attr", &thresholds.warn.attributeByName}}) {
      for (const auto& [name, limit] : *limits) {
        if (chosen.count(prefix + name) == 0) {
          throw usageError(std::string(option) + " " + name + ": --attributes leaves it out, so it is not compared");
        }
      }
    }
    attributes = std::move(chosen);
  }
  for (auto& [family, names] : attributes) {
    std::sort(names.begin(), names.end());
    Family f{family, Family::kAttribute, {}, {}};
    // An attribute one image lacks: say how to compare the rest.
    const std::string hint = selection.empty() ? "; --attributes compares only those named" : "";
    for (const std::string& name : names) {
      f.test.push_back(require(test, testPath, name, ChannelType::kFloat, refPath, hint).floats.data());
      f.reference.push_back(require(ref, refPath, name, ChannelType::kFloat, testPath, hint).floats.data());
    }
    const std::string spread = channels::spreadChannel(family.substr(prefix.size()));
    if (ref.find(spread)) f.spread = require(ref, refPath, spread, ChannelType::kFloat, "").floats.data();
    families.push_back(f);
  }
  return families;
}

// Counts a non-finite value of `values` at `pixel`; returns true if there was one.
bool countNonFinite(const std::vector<const float*>& planes, std::size_t pixel,
                    StatsAccumulator& acc) {
  bool nan = false, inf = false;
  for (const float* plane : planes) {
    nan |= std::isnan(plane[pixel]);
    inf |= std::isinf(plane[pixel]);
  }
  if (nan) acc.addNan();
  else if (inf) acc.addInf();
  return nan || inf;
}

double attributeRange(const Family& f, const PlaneVector<PixelClass>& classes) {
  double lo = std::numeric_limits<double>::infinity(), hi = -lo;
  for (std::size_t i = 0; i < classes.size(); ++i) {
    if (classes[i] == PixelClass::kBothEmpty || classes[i] == PixelClass::kTestOnly) continue;
    for (const float* plane : f.reference) {
      if (std::isfinite(plane[i])) {
        lo = std::min(lo, double(plane[i]));
        hi = std::max(hi, double(plane[i]));
      }
    }
  }
  return hi > lo ? hi - lo : 0.0;
}

// The heatmap planes of one family, each null where not made: its error, its error over its
// bound, the barycentrics' error in ulps, and the pixels where it holds a NaN or Inf.
struct FamilyPlanes {
  float* error = nullptr;
  float* ratio = nullptr;
  float* ulps = nullptr;
  std::uint8_t* nonFinite = nullptr;
};

// One family's statistics over the pixels both images give the same triangle, in pixel order
// (its sums are added in the same order whatever the thread count), and its gated figure.
FamilyReport measureFamily(const Family& f, const PlaneVector<PixelClass>& classes, const Diagnostics& d,
                           const Thresholds& thresholds, std::size_t sameTriangle, int width, const FamilyPlanes& planes) {
  const bool bounded = d.bounded;
  const std::size_t n = classes.size();
  FamilyReport fr;
  fr.name = f.name;
  fr.bounded = bounded;
  if (f.kind == Family::kAttribute) fr.range = attributeRange(f, classes);
  StatsAccumulator acc, ulps, ratios;
  acc.reserve(sameTriangle);
  ulps.reserve(sameTriangle);
  if (bounded) ratios.reserve(sameTriangle);
  for (std::size_t i = 0; i < n; ++i) {
    const PixelClass c = classes[i];
    if (c == PixelClass::kBothEmpty) continue;
    bool bad = false;
    if (c != PixelClass::kReferenceOnly) bad |= countNonFinite(f.test, i, acc);
    if (!bad && c != PixelClass::kTestOnly) bad |= countNonFinite(f.reference, i, acc);
    if (bad && planes.nonFinite) planes.nonFinite[i] = 1;
    if (bad || c != PixelClass::kSameTriangle) continue;
    double error = -1.0, tv = 0.0, rv = 0.0, ratio = 0.0, ulp = 0.0;
    for (std::size_t k = 0; k < f.test.size(); ++k) {
      const double t = f.test[k][i], r = f.reference[k][i];
      double e = std::fabs(t - r);
      if (f.kind == Family::kDepth && r != 0.0) e /= std::fabs(r);
      if (e > error) error = e, tv = t, rv = r;
      // Ulps: 2^-24 for barycentrics (the spacing of floats just below 1, where a barycentric
      // near 1 lies), of the value for depth (e is relative), of the range.
      const double unit = f.kind == Family::kBary    ? floatUlp(1.0) / 2.0
                          : f.kind == Family::kDepth ? floatUlp(r) / std::max(std::fabs(r), 1e-300)
                                                     : floatUlp(std::max(fr.range, std::fabs(r)));
      ulp = std::max(ulp, e / unit);
      if (bounded) {
        // The bound of docs/numerics.md: barycentrics and depth add the two paths' bounds;
        // an attribute adds their barycentric bounds times three times its spread (the sum
        // of |db_i| |a_i - c| over a triangle's vertices) and float rounding of the sums. The
        // spread is the triangle's, where the reference gives it, else the image's range;
        // never below the range, which a triangle's values may exceed but rarely fall short of.
        const double bary = double(d.boundTest[0][i]) + double(d.boundRef[0][i]);
        const double spread = f.spread ? std::max(fr.range, double(f.spread[i])) : fr.range;
        const double bound = f.kind == Family::kBary    ? bary
                             : f.kind == Family::kDepth ? double(d.boundTest[1][i]) + double(d.boundRef[1][i])
                                                        : 3.0 * bary * spread + 0x1p-21 * (std::fabs(r) + spread);
        const double q = bound > 0.0 ? e / bound : (e > 0.0 ? std::numeric_limits<double>::infinity() : 0.0);
        ratio = std::max(ratio, q);
      }
    }
    const int px = int(i % width), py = int(i / width);
    acc.addError(error, px, py, tv, rv);
    ulps.addError(ulp, px, py, tv, rv);
    if (bounded) ratios.addError(ratio, px, py, tv, rv);
    if (planes.error) planes.error[i] = float(error);
    if (planes.ratio) planes.ratio[i] = float(ratio);
    if (planes.ulps) planes.ulps[i] = float(ulp);
  }
  fr.stats = acc.finish();
  fr.ulps = ulps.finish();
  fr.ratio = ratios.finish();
  fr.unit = f.kind == Family::kDepth ? "relative" : "absolute";
  fr.threshold = bounded                     ? 1.0
                 : f.kind == Family::kBary   ? thresholds.bary
                 : f.kind == Family::kDepth  ? thresholds.depth
                                             : thresholds.attributeLimit(attributeName(f.name));
  fr.gated = bounded ? fr.ratio.max : fr.stats.max;
  if (!bounded && f.kind == Family::kAttribute && fr.range > 0.0) fr.gated = fr.stats.max / fr.range;
  return fr;
}

// The gate's reasons, and the verdict and warnings that follow from them. Every comparison is
// written !(value <= limit) so that a NaN fails it.
void gate(CompareReport& report, const Thresholds& thresholds) {
  if (report.coveredEither == 0 && !thresholds.allowEmpty) {
    report.reasons.push_back("neither image covers a pixel, so nothing was compared (--allow-empty lets such a pair pass)");
  }
  for (const FamilyReport& f : report.families) {
    if (f.stats.nanCount + f.stats.infCount > 0) {
      report.reasons.push_back(f.name + ": " + std::to_string(f.stats.nanCount) + " NaN and " +
                               std::to_string(f.stats.infCount) + " Inf pixels");
    }
    if (f.bounded && !(f.gated <= 1.0)) {
      report.reasons.push_back(f.name + ": error reaches " + formatNumber(f.gated) + "x its bound at " +
                               formatPixel(f.ratio.worst));
    } else if (!f.bounded) {
      addIfOver(report.reasons, f.name + ": max error ", f.gated, f.threshold,
                f.range > 0.0 ? " of range exceeds " : " exceeds ");
    }
  }
  const std::size_t unexplained = report.explanationCounts[int(Explanation::kUnexplained)];
  if (unexplained > 0) {
    report.reasons.push_back(std::to_string(unexplained) +
                             (report.explained ? " disagreements neither in the edge band nor a depth tie, first at "
                                               : " disagreements away from every edge of both images' ids and not a depth tie, first at ") +
                             formatPixel(report.firstUnexplained));
  }
  if (!report.explained) {
    addIfOver(report.reasons, "different triangle (depth ties left out) at ", report.untiedDisagreementFraction,
              thresholds.disagreement, " of covered pixels, limit ");
    addIfOver(report.reasons, "one-side-only coverage (clip ties left out) at ", report.untiedCoverageFraction,
              thresholds.coverage, " of covered pixels, limit ");
  }
  report.pass = report.reasons.empty();
  report.warnings = warningsOf(report, thresholds.warn);
  report.settleWarnings();
}

// The heatmap's class and explanation planes, and its RGB: each pixel's colour by its class,
// its explanation and its non-finite values, else the chosen quantity on the magma scale.
void paintHeatmap(Framebuffer& heatmap, const CompareReport& report, const Thresholds& thresholds,
                  const PlaneVector<PixelClass>& classes, const PlaneVector<Explanation>& explanations,
                  const std::vector<PlaneVector<std::uint8_t>>& nonFiniteOf, bool bounded, int workers) {
  const std::size_t n = classes.size();
  const int width = heatmap.width();
  std::uint32_t* classPlane = heatmap.addUint("class.id");
  std::uint32_t* explanationPlane = heatmap.addUint("explanation.id");
  float* rgb[3] = {heatmap.addFloat("R"), heatmap.addFloat("G"), heatmap.addFloat("B")};
  const HeatmapQuantity quantity = thresholds.heatmap == HeatmapQuantity::kBoundRatio && !bounded
                                       ? HeatmapQuantity::kError
                                       : thresholds.heatmap;
  const HeatScale scale = heatScale(quantity);
  const float* shown = heatmap.find(quantity == HeatmapQuantity::kError  ? "error.bary"
                                    : quantity == HeatmapQuantity::kUlps ? "ulps.bary"
                                                                         : "ratio.bary")
                           ->floats.data();
  const int rows = heatmap.height();
  parallelFor((rows + 15) / 16, workers, [&](int band) {
    const std::size_t first = std::size_t(band) * 16 * width;
    const std::size_t last = std::min(n, first + std::size_t(16) * width);
    for (std::size_t i = first; i < last; ++i) {
      classPlane[i] = std::uint32_t(classes[i]);
      const bool disagree = classes[i] != PixelClass::kBothEmpty && classes[i] != PixelClass::kSameTriangle;
      explanationPlane[i] = disagree ? std::uint32_t(explanations[i]) : kNothingToExplain;
      const bool nonFinite =
          std::any_of(nonFiniteOf.begin(), nonFiniteOf.end(), [i](const auto& flags) { return flags[i] != 0; });
      Rgb colour = nonFinite                                      ? kColourNonFinite
                   : classes[i] == PixelClass::kBothEmpty         ? kColourBackground
                   : disagree && explanations[i] == Explanation::kUnexplained ? kColourUnexplained
                   : classes[i] == PixelClass::kDifferentTriangle ? kColourDifferentTriangle
                   : disagree                                     ? kColourOneSideOnly
                                                                  : heatColour(shown[i], scale);
      colour = linearFromSrgb(colour);
      for (int k = 0; k < 3; ++k) rgb[k][i] = colour[k];
    }
  });
  heatmap.attributes["rastercheck.heatmap"] =
      std::string("RGB: ") + scale.title + " on a log10 magma scale from 1e" + std::to_string(int(scale.logMin)) +
      " to 1e" + std::to_string(int(scale.logMax)) +
      "; green: different triangle; cyan: one side only; red: unexplained disagreement; magenta: NaN/Inf; grey: empty";
  heatmap.attributes["rastercheck.heatmapQuantity"] = scale.key;
  heatmap.attributes["rastercheck.test"] = report.testPath;
  heatmap.attributes["rastercheck.reference"] = report.referencePath;
}

}  // namespace

CompareReport compareImages(const Framebuffer& test, const std::string& testPath,
                            const Framebuffer& ref, const std::string& refPath,
                            const Thresholds& thresholds, Framebuffer* heatmap, int threads) {
  if (test.width() != ref.width() || test.height() != ref.height()) {
    throw badInput(testPath, "size " + std::to_string(test.width()) + "x" +
                                 std::to_string(test.height()) + " differs from " + refPath + " (" +
                                 std::to_string(ref.width()) + "x" + std::to_string(ref.height()) + ")");
  }
  // Both renderers record their camera (docs/channels.md); two renders through different
  // cameras have no pixel in common, and comparing them would blame each error on a bound.
  const auto testCamera = test.attributes.find(channels::header::kCamera);
  const auto refCamera = ref.attributes.find(channels::header::kCamera);
  if (testCamera != test.attributes.end() && refCamera != ref.attributes.end() && testCamera->second != refCamera->second) {
    throw badInput(testPath + ": " + channels::header::kCamera,
                   "'" + testCamera->second + "' is not " + refPath + "'s '" + refCamera->second +
                       "': the images were rendered through different cameras");
  }
  const auto& testIds = require(test, testPath, channels::kTriangleId, ChannelType::kUint, "").uints;
  const auto& refIds = require(ref, refPath, channels::kTriangleId, ChannelType::kUint, "").uints;
  CompareReport report;
  const std::vector<Family> families = collectFamilies(test, testPath, ref, refPath, thresholds, report.leftOut);
  report.testPath = testPath;
  report.referencePath = refPath;
  report.width = test.width();
  report.height = test.height();
  if (refCamera != ref.attributes.end()) {
    report.camera = refCamera->second;
  } else if (testCamera != test.attributes.end()) {
    report.camera = testCamera->second;
  }
  report.thresholds = thresholds;
  const std::size_t n = test.pixelCount();
  const PlaneVector<PixelClass> classes = classifyPixels(testIds, refIds, report);
  const Diagnostics diagnostics = diagnosticsOf(test, ref);
  const bool bounded = diagnostics.bounded;
  report.explained = diagnostics.explains();
  report.edgeBand = report.explained ? diagnostics.bandTest + diagnostics.bandRef : 0.0;

  std::vector<FamilyPlanes> planes(families.size());
  // A pixel where some family holds a NaN or Inf, per family (they run in parallel), for the
  // heatmap's colours only.
  std::vector<PlaneVector<std::uint8_t>> nonFiniteOf(heatmap ? families.size() : 0);
  if (heatmap) {
    *heatmap = Framebuffer(test.width(), test.height());
    for (std::size_t fi = 0; fi < families.size(); ++fi) planes[fi].error = heatmap->addFloat("error." + families[fi].name);
    if (bounded) {
      for (std::size_t fi = 0; fi < families.size(); ++fi) planes[fi].ratio = heatmap->addFloat("ratio." + families[fi].name);
    }
    float* ulpPlane = heatmap->addFloat("ulps.bary");
    for (std::size_t fi = 0; fi < families.size(); ++fi) {
      nonFiniteOf[fi].assign(n, 0);
      planes[fi].nonFinite = nonFiniteOf[fi].data();
      if (families[fi].kind == Family::kBary) planes[fi].ulps = ulpPlane;
    }
  }
  const std::size_t sameTriangle = report.classCounts[int(PixelClass::kSameTriangle)];
  report.families.resize(families.size());
  // Each family on one thread. The heaviest (bary: three components) comes first.
  // Below about a 256x256 image a thread costs more than it saves.
  const int workers = n < (std::size_t(1) << 16) ? 1 : threads;
  parallelFor(int(families.size()), workers, [&](int index) {
    const std::size_t fi = std::size_t(index);
    report.families[fi] = measureFamily(families[fi], classes, diagnostics, thresholds, sameTriangle, test.width(), planes[fi]);
  });
  const PlaneVector<Explanation> explanations =
      explainDisagreements(test, ref, testIds, refIds, classes, diagnostics, thresholds.depth, report);
  gate(report, thresholds);
  if (heatmap) paintHeatmap(*heatmap, report, thresholds, classes, explanations, nonFiniteOf, bounded, workers);
  return report;
}

}  // namespace rc
