#pragma once
// Reading a tolerance file: per test and quantity the tolerance, in the standards' length-dependent
// forms, and the decision rule (docs/file-formats.md "Tolerances").
#include <string>
#include <vector>

#include "mtacc/core/units.hpp"
#include "mtacc/procedures/conformance.hpp"

namespace mtacc {

struct ToleranceEntry {
  std::string test, quantity;
  Tolerance tolerance;
  int line = 0;
};

struct ToleranceSet {
  std::string file;
  DecisionRule rule = DecisionRule::Iso14253_1;
  std::vector<ToleranceEntry> entries;

  const ToleranceEntry* find(const std::string& test, const std::string& quantity) const;
};

// The tests a tolerance file names and the quantities of each.
struct ToleranceTest {
  const char* name;
  Dimension dimension;  // of its results
  std::vector<std::string> quantities;
  bool lengthDependent;  // its tolerances may depend on the measured length
};
const std::vector<ToleranceTest>& toleranceTests();

// Throws InputError naming file, line and key.
ToleranceSet loadTolerances(const std::string& path);
ToleranceSet parseTolerances(const std::string& yamlText, const std::string& sourceName);
// One tolerance in the forms of procedures/conformance.hpp (lengthDependent false: a constant
// only); throws InputError naming `key`.
Tolerance parseTolerance(const std::string& text, Dimension dimension, const std::string& key, bool lengthDependent);

}  // namespace mtacc
