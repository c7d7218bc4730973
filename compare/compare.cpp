// compareImages: compatibility checks, pixel classes, family statistics, gate, heatmap.
#include "compare/compare.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <map>

#include "compare/colormap.h"
#include "core/channels.h"
#include "core/error.h"

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

namespace {

const Channel& require(const Framebuffer& fb, const std::string& path, const std::string& name,
                       ChannelType type, const std::string& otherPath) {
  const Channel* c = fb.find(name);
  if (!c) {
    throw badInput(path + ": channel " + name,
                   otherPath.empty() ? "missing" : "missing (present in " + otherPath + ")");
  }
  if (c->type != type) {
    throw badInput(path + ": channel " + name, std::string("is ") + channelTypeName(c->type) +
                                                   ", expected " + channelTypeName(type));
  }
  return *c;
}

// A channel family: the planes of one quantity in both images (e.g. attr.uv.x and attr.uv.y).
struct Family {
  std::string name;
  enum Kind { kBary, kDepth, kAttribute } kind;
  std::vector<const float*> test, reference;
};

std::vector<Family> collectFamilies(const Framebuffer& test, const std::string& testPath,
                                    const Framebuffer& ref, const std::string& refPath) {
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
  for (const Framebuffer* fb : {&test, &ref}) {
    for (const Channel& c : fb->channels()) {
      if (c.name.rfind(prefix, 0) != 0) continue;
      const std::string family = c.name.substr(0, c.name.rfind('.'));
      auto& names = attributes[family];
      if (std::find(names.begin(), names.end(), c.name) == names.end()) names.push_back(c.name);
    }
  }
  for (auto& [family, names] : attributes) {
    std::sort(names.begin(), names.end());
    Family f{family, Family::kAttribute, {}, {}};
    for (const std::string& name : names) {
      f.test.push_back(require(test, testPath, name, ChannelType::kFloat, refPath).floats.data());
      f.reference.push_back(require(ref, refPath, name, ChannelType::kFloat, testPath).floats.data());
    }
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

double attributeRange(const Family& f, const std::vector<PixelClass>& classes) {
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

}  // namespace

CompareReport compareImages(const Framebuffer& test, const std::string& testPath,
                            const Framebuffer& ref, const std::string& refPath,
                            const Thresholds& thresholds, Framebuffer* heatmap) {
  if (test.width() != ref.width() || test.height() != ref.height()) {
    throw badInput(testPath, "size " + std::to_string(test.width()) + "x" +
                                 std::to_string(test.height()) + " differs from " + refPath + " (" +
                                 std::to_string(ref.width()) + "x" + std::to_string(ref.height()) + ")");
  }
  const auto& testIds = require(test, testPath, channels::kTriangleId, ChannelType::kUint, "").uints;
  const auto& refIds = require(ref, refPath, channels::kTriangleId, ChannelType::kUint, "").uints;
  const std::vector<Family> families = collectFamilies(test, testPath, ref, refPath);

  CompareReport report;
  report.testPath = testPath;
  report.referencePath = refPath;
  report.width = test.width();
  report.height = test.height();
  report.thresholds = thresholds;
  const std::size_t n = test.pixelCount();
  std::vector<PixelClass> classes(n);
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
  const double covered = double(std::max<std::size_t>(report.coveredEither, 1));
  report.disagreementFraction = double(report.classCounts[int(PixelClass::kDifferentTriangle)]) / covered;
  report.coverageFraction = double(report.classCounts[int(PixelClass::kTestOnly)] +
                                    report.classCounts[int(PixelClass::kReferenceOnly)]) / covered;

  std::vector<float*> errorPlanes;
  if (heatmap) {
    *heatmap = Framebuffer(test.width(), test.height());
    for (const Family& f : families) errorPlanes.push_back(heatmap->addFloat("error." + f.name));
  }
  std::vector<bool> nonFinite(n, false);
  const int width = test.width();
  for (std::size_t fi = 0; fi < families.size(); ++fi) {
    const Family& f = families[fi];
    StatsAccumulator acc;
    for (std::size_t i = 0; i < n; ++i) {
      const PixelClass c = classes[i];
      if (c == PixelClass::kBothEmpty) continue;
      bool bad = false;
      if (c != PixelClass::kReferenceOnly) bad |= countNonFinite(f.test, i, acc);
      if (!bad && c != PixelClass::kTestOnly) bad |= countNonFinite(f.reference, i, acc);
      if (bad) nonFinite[i] = true;
      if (bad || c != PixelClass::kSameTriangle) continue;
      double error = -1.0, tv = 0.0, rv = 0.0;
      for (std::size_t k = 0; k < f.test.size(); ++k) {
        const double t = f.test[k][i], r = f.reference[k][i];
        double e = std::fabs(t - r);
        if (f.kind == Family::kDepth && r != 0.0) e /= std::fabs(r);
        if (e > error) error = e, tv = t, rv = r;
      }
      acc.addError(error, int(i % width), int(i / width), tv, rv);
      if (heatmap) errorPlanes[fi][i] = float(error);
    }
    FamilyReport fr;
    fr.name = f.name;
    fr.stats = acc.finish();
    fr.unit = f.kind == Family::kDepth ? "relative" : "absolute";
    fr.threshold = f.kind == Family::kBary    ? thresholds.bary
                   : f.kind == Family::kDepth ? thresholds.depth
                                              : thresholds.attribute;
    fr.gated = fr.stats.max;
    if (f.kind == Family::kAttribute) {
      fr.range = attributeRange(f, classes);
      if (fr.range > 0.0) fr.gated = fr.stats.max / fr.range;
    }
    report.families.push_back(fr);
  }

  // The gate. Every comparison is written !(value <= limit) so that a NaN fails it.
  for (const FamilyReport& f : report.families) {
    if (f.stats.nanCount + f.stats.infCount > 0) {
      report.reasons.push_back(f.name + ": " + std::to_string(f.stats.nanCount) + " NaN and " +
                               std::to_string(f.stats.infCount) + " Inf pixels");
    }
    if (!(f.gated <= f.threshold)) {
      report.reasons.push_back(f.name + ": max error " + std::to_string(f.gated) +
                               (f.range > 0.0 ? " of range" : "") + " exceeds " +
                               std::to_string(f.threshold));
    }
  }
  if (!(report.disagreementFraction <= thresholds.disagreement)) {
    report.reasons.push_back("different triangle at " + std::to_string(report.disagreementFraction) +
                             " of covered pixels, limit " + std::to_string(thresholds.disagreement));
  }
  if (!(report.coverageFraction <= thresholds.coverage)) {
    report.reasons.push_back("one-side-only coverage at " + std::to_string(report.coverageFraction) +
                             " of covered pixels, limit " + std::to_string(thresholds.coverage));
  }
  report.pass = report.reasons.empty();

  if (heatmap) {
    std::uint32_t* classPlane = heatmap->addUint("class.id");
    float* rgb[3] = {heatmap->addFloat("R"), heatmap->addFloat("G"), heatmap->addFloat("B")};
    const float* baryError = heatmap->find("error.bary")->floats.data();
    for (std::size_t i = 0; i < n; ++i) {
      classPlane[i] = std::uint32_t(classes[i]);
      Rgb colour = nonFinite[i]                                   ? kColourNonFinite
                   : classes[i] == PixelClass::kBothEmpty         ? kColourBackground
                   : classes[i] == PixelClass::kDifferentTriangle ? kColourDifferentTriangle
                   : classes[i] != PixelClass::kSameTriangle      ? kColourOneSideOnly
                                                                  : heatColour(baryError[i]);
      colour = linearFromSrgb(colour);
      for (int k = 0; k < 3; ++k) rgb[k][i] = colour[k];
    }
    heatmap->attributes["rastercheck.heatmap"] =
        "RGB: error.bary on a log10 magma scale from 1e-8 to 1e-1; green: different triangle; "
        "cyan: one side only; magenta: NaN/Inf; grey: empty";
    heatmap->attributes["rastercheck.test"] = testPath;
    heatmap->attributes["rastercheck.reference"] = refPath;
  }
  return report;
}

}  // namespace rc
