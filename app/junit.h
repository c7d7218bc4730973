// `check --junit FILE`: the gate's verdicts as JUnit XML, the test report that CI systems
// (GitLab, Jenkins, Azure Pipelines, GitHub actions that read it) show per test: one test
// case per scene, a failure with the gate's reasons where it failed.
#pragma once

#include <string>
#include <vector>

namespace rc::app {

struct JUnitCase {
  std::string name;                  // the scene as named on the command line
  double seconds = 0;                // what checking it took, rendering both paths and comparing
  std::vector<std::string> reasons;  // why it failed the gate; empty when it passed
  std::string summary;               // its figures, one line, shown as the case's output
};

// The document: a <testsuites> with one <testsuite> named `suite`, its `settings` as a
// property, and the cases in order. Text is escaped and made valid UTF-8.
std::string junitXml(const std::string& suite, const std::string& settings, const std::vector<JUnitCase>& cases);

}  // namespace rc::app
