// `check --junit FILE`: the gate's verdicts as JUnit XML, the test report that CI systems
// (GitLab, Jenkins, Azure Pipelines, GitHub actions that read it) show per test: one test
// case per scene, a failure with the gate's reasons where it failed.
#pragma once

#include <string>
#include <utility>
#include <vector>

#include "compare/compare.h"

namespace rc::app {

// A comparison's figures on one line, for a case's output: "640x480: bary max 2.38e-07,
// p99.9 1.19e-07; depth max 2.38e-07; disagreement 1.3e-05".
std::string gateFigures(const CompareReport& report);

struct JUnitCase {
  std::string name;                  // the scene as named on the command line
  double seconds = 0;                // what checking it took, rendering both paths and comparing
  std::vector<std::string> reasons;   // why it failed the gate; empty when it passed
  std::string summary;                // its figures, one line, shown as the case's output
  std::vector<std::string> warnings;  // warning limits exceeded, added to the output
};

// The document: a <testsuites> with one <testsuite> named `suite`, its `properties` (name,
// value), and the cases in order. Text is escaped and made valid UTF-8.
std::string junitXml(const std::string& suite, const std::vector<std::pair<std::string, std::string>>& properties,
                     const std::vector<JUnitCase>& cases);

}  // namespace rc::app
