#include "mtacc/io/tolerances_yaml.hpp"

#include <fmt/format.h>

#include <fmt/ranges.h>

#include <algorithm>

#include "mtacc/core/input_error.hpp"
#include "mtacc/core/text.hpp"
#include "mtacc/core/text_file.hpp"
#include "yaml_input.hpp"

namespace mtacc {
namespace {

const std::vector<std::string> kPositioningQuantities{"A", "A_forward", "A_backward", "B", "E", "E_forward",
                                                       "E_backward", "M", "R", "R_forward", "R_backward"};

bool startsWith(const std::string& text, const std::string& prefix) { return text.rfind(prefix, 0) == 0; }

// "<T> for <L0>": the value and, when given, the length it is for.
std::pair<double, double> valueForLength(const std::string& text, Dimension dimension, const std::string& key) {
  const auto at = text.find(" for ");
  const double value = parseQuantityAs(trim(text.substr(0, at)), dimension, key);
  if (at == std::string::npos) return {value, 0.0};
  return {value, parseQuantityAs(trim(text.substr(at + 5)), Dimension::Length, key)};
}

void requirePositive(double v, const std::string& what, const std::string& key) {
  if (!(v > 0)) throw InputError({"", 0, key}, what + " must be positive");
}

}  // namespace

const std::vector<ToleranceTest>& toleranceTests() {
  static const std::vector<ToleranceTest> tests{{"positioning", Dimension::Length, kPositioningQuantities, true},
                                                {"positioning_rotary", Dimension::Angle, kPositioningQuantities, false},
                                                {"rotary_rtest", Dimension::Length, {"radial", "tangential", "axial"}, false},
                                                {"rotary_ballbar", Dimension::Length, {"length"}, false},
                                                {"straightness", Dimension::Length, {"end_point", "least_squares"}, true},
                                                {"angular_deviation", Dimension::Angle, {"range"}, false},
                                                {"positional_deviation", Dimension::Length, {"range"}, true},
                                                {"circular", Dimension::Length, {"G", "H", "F"}, true},
                                                {"thermal_drift", Dimension::Length, {"X", "Y", "Z"}, false}};
  return tests;
}

Tolerance parseTolerance(const std::string& text, Dimension dimension, const std::string& key, bool lengthDependent) {
  Tolerance t;
  t.text = trim(text);
  if (!lengthDependent && (t.text.find(" for ") != std::string::npos || t.text.find("up to") != std::string::npos))
    throw InputError({"", 0, key}, "this test's tolerance is one value, not length-dependent");
  if (t.text.find("up to") != std::string::npos) {
    t.form = Tolerance::Form::Stepped;
    for (const auto& step : splitList(t.text, ';')) {
      const auto at = step.find("up to");
      if (at == std::string::npos) throw InputError({"", 0, key}, fmt::format("expected 'T up to L' in '{}'", trim(step)));
      t.stepValues.push_back(parseQuantityAs(trim(step.substr(0, at)), dimension, key));
      t.stepLengths.push_back(parseQuantityAs(trim(step.substr(at + 5)), Dimension::Length, key));
      requirePositive(t.stepValues.back(), "a tolerance", key);
      if (t.stepLengths.size() > 1 && !(t.stepLengths.back() > t.stepLengths[t.stepLengths.size() - 2]))
        throw InputError({"", 0, key}, "the lengths of 'T up to L' steps must increase");
    }
    requirePositive(t.stepLengths.front(), "a length", key);
    return t;
  }
  const auto parts = splitList(t.text);
  if (parts.empty()) throw InputError({"", 0, key}, "expected a tolerance, e.g. '0.010 mm for 1000 mm'");
  const auto [value, length] = valueForLength(trim(parts[0]), dimension, key);
  t.value = value;
  t.length = length;
  requirePositive(t.value, "a tolerance", key);
  const bool forLength = parts[0].find(" for ") != std::string::npos;
  if (forLength) requirePositive(t.length, "the length a tolerance is for", key);
  t.form = forLength ? Tolerance::Form::Proportional : Tolerance::Form::Constant;
  for (size_t i = 1; i < parts.size(); ++i) {
    const auto part = trim(parts[i]);
    if (startsWith(part, "+")) {
      if (t.form != Tolerance::Form::Proportional)
        throw InputError({"", 0, key}, "an increment '+ dT per additional dL' follows 'T for L' (once)");
      const auto per = part.find(" per ");
      if (per == std::string::npos) throw InputError({"", 0, key}, fmt::format("expected '+ dT per additional dL' in '{}'", part));
      t.increment = parseQuantityAs(trim(part.substr(1, per - 1)), dimension, key);
      auto lengthText = trim(part.substr(per + 5));
      if (startsWith(lengthText, "additional ")) lengthText = trim(lengthText.substr(11));
      t.incrementLength = parseQuantityAs(lengthText, Dimension::Length, key);
      requirePositive(t.increment, "an increment", key);
      requirePositive(t.incrementLength, "the length of an increment", key);
      t.form = Tolerance::Form::Increment;
    } else if (startsWith(part, "max ") || startsWith(part, "min ")) {
      double& bound = part[1] == 'a' ? t.maximum : t.minimum;
      if (bound > 0) throw InputError({"", 0, key}, fmt::format("'{}' given twice", part.substr(0, 3)));
      bound = parseQuantityAs(trim(part.substr(4)), dimension, key);
      requirePositive(bound, "a bound", key);
    } else {
      throw InputError({"", 0, key}, fmt::format("expected '+ dT per additional dL', 'max T' or 'min T' after the comma, not '{}'", part));
    }
  }
  if (t.form == Tolerance::Form::Constant && (t.minimum > 0 || t.maximum > 0))
    throw InputError({"", 0, key}, "min and max bound a length-dependent tolerance ('T for L, max Tm')");
  if (t.minimum > 0 && t.maximum > 0 && t.minimum > t.maximum) throw InputError({"", 0, key}, "min is above max");
  return t;
}

const ToleranceEntry* ToleranceSet::find(const std::string& test, const std::string& quantity) const {
  for (const auto& e : entries)
    if (e.test == test && e.quantity == quantity) return &e;
  return nullptr;
}

ToleranceSet loadTolerances(const std::string& path) { return parseTolerances(readTextFile(path), path); }

ToleranceSet parseTolerances(const std::string& yamlText, const std::string& sourceName) {
  const yamlin::Context ctx{sourceName};
  const auto root = yamlin::loadText(yamlText, sourceName);
  if (!yamlin::isMap(root)) ctx.fail(root, "", "expected a mapping: decision_rule and a tolerance map per test (docs/file-formats.md)");
  ToleranceSet set;
  set.file = sourceName;
  std::string testNames;
  for (const auto& t : toleranceTests()) testNames += fmt::format("{}{}", testNames.empty() ? "" : ", ", t.name);
  for (const auto& kv : root) {
    const auto name = kv.first.as<std::string>();
    if (name == "decision_rule") {
      const auto rule = yamlin::scalar(ctx, kv.second, name);
      if (rule == "iso14253-1") set.rule = DecisionRule::Iso14253_1;
      else if (rule == "simple") set.rule = DecisionRule::Simple;
      else ctx.fail(kv.second, name, "expected iso14253-1 or simple");
      continue;
    }
    const auto test = std::find_if(toleranceTests().begin(), toleranceTests().end(), [&](const ToleranceTest& t) { return name == t.name; });
    if (test == toleranceTests().end()) ctx.fail(kv.first, name, "unknown test (decision_rule, " + testNames + ")");
    if (!yamlin::isMap(kv.second)) ctx.fail(kv.second, name, "expected a mapping of quantity: tolerance");
    for (const auto& q : kv.second) {
      const auto quantity = q.first.as<std::string>();
      const std::string key = name + "." + quantity;
      if (std::find(test->quantities.begin(), test->quantities.end(), quantity) == test->quantities.end())
        ctx.fail(q.first, key, fmt::format("unknown quantity of {} (one of {})", name, fmt::join(test->quantities, ", ")));
      ToleranceEntry entry{name, quantity, {}, ctx.at(q.second, key).line};
      try {
        entry.tolerance = parseTolerance(yamlin::scalar(ctx, q.second, key), test->dimension, key, test->lengthDependent);
      } catch (const InputError& e) {
        ctx.fail(q.second, key, e.reason());
      }
      set.entries.push_back(std::move(entry));
    }
  }
  return set;
}

}  // namespace mtacc
