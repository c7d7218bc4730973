// A comparison report of made-up figures, each one distinct, for the tests of what prints it
// (the table, the JSON, the HTML report): a figure shown in another's place, or not at all, is
// seen. Two families: bary, gated against its bound, and attr.uv, against a limit of its range.
#pragma once

#include "compare/compare.h"

namespace rc::testing {

inline CompareReport madeUpReport(bool pass) {
  CompareReport r;
  r.width = 8, r.height = 4;
  r.pass = pass;
  if (!pass) r.reasons = {"bary: max error 0.5 over its bound", "depth: 2 NaN <pixels>"};
  r.coveredEither = 29;
  r.classCounts[int(PixelClass::kBothEmpty)] = 3;
  r.classCounts[int(PixelClass::kSameTriangle)] = 19;
  r.classCounts[int(PixelClass::kDifferentTriangle)] = 5;
  r.classCounts[int(PixelClass::kTestOnly)] = 3;
  r.classCounts[int(PixelClass::kReferenceOnly)] = 2;
  r.disagreementFraction = 0.125, r.coverageFraction = 0.0625;
  r.explained = true;
  r.explanationCounts[int(Explanation::kEdgeBand)] = 11;
  r.explanationCounts[int(Explanation::kDepthTie)] = 13;
  r.explanationCounts[int(Explanation::kUnexplained)] = 17;
  r.edgeBand = 0.0055;
  FamilyReport bary;
  bary.name = "bary", bary.unit = "absolute";
  bary.bounded = true;
  bary.threshold = 1.0, bary.gated = 0.75;
  bary.stats.count = 24, bary.stats.nanCount = 1, bary.stats.infCount = 2;
  bary.stats.max = 0.00125, bary.stats.mean = 0.00025, bary.stats.rms = 0.00035, bary.stats.p50 = 4.5e-05;
  bary.stats.p99 = 0.00055, bary.stats.p999 = 0.00065;
  bary.stats.worst = {6, 1, 0.25, 0.375};
  bary.ulps.max = 42.5, bary.ulps.p999 = 37.5;
  bary.ratio.max = 0.75, bary.ratio.p999 = 0.625, bary.ratio.worst = {5, 2, 0.0, 0.0};
  FamilyReport uv;
  uv.name = "attr.uv", uv.unit = "absolute";
  uv.range = 2.5, uv.threshold = 0.004, uv.gated = 0.0008;
  uv.stats.count = 27, uv.stats.max = 0.002, uv.stats.mean = 0.0003, uv.stats.rms = 0.0004, uv.stats.p50 = 5e-05;
  uv.stats.p99 = 0.0006, uv.stats.p999 = 0.0007;
  uv.stats.worst = {2, 3, 1.5, 1.498};
  uv.ulps.max = 52.5, uv.ulps.p999 = 47.5;
  r.families = {bary, uv};
  return r;
}

}  // namespace rc::testing
