#include "mtacc/workflows/verdicts.hpp"

#include <algorithm>

#include "mtacc/core/input_error.hpp"

namespace mtacc {

Verdict Conformance::overall() const {
  std::vector<Verdict> each;
  for (const auto& v : verdicts) each.push_back(v.verdict);
  return combined(each);
}

Conformance judge(const UncertaintyBudget& budget, const ToleranceSet& tolerances, const std::string& test) {
  Conformance c;
  c.toleranceFile = tolerances.file;
  c.rule = tolerances.rule;
  for (const auto& q : budget.quantities) {
    const auto* entry = tolerances.find(test, q.quantity);
    if (!entry) continue;
    QuantityVerdict v{q.quantity, q.value, q.expanded, 0, entry->tolerance.text, Verdict::Undecided};
    try {
      v.tolerance = entry->tolerance.at(budget.measuredLength);
    } catch (const InputError& e) {
      throw InputError({tolerances.file, entry->line, test + "." + q.quantity}, e.reason());
    }
    v.verdict = decide(v.value, v.expanded, v.tolerance, c.rule);
    c.verdicts.push_back(v);
  }
  if (c.verdicts.empty() && tolerances.entries.empty()) throw InputError({tolerances.file, 0, test}, "no tolerance for the " + test + " test");
  if (c.verdicts.empty()) {
    const auto& first = tolerances.entries.front();
    throw InputError({tolerances.file, first.line, first.test + "." + first.quantity},
                     "a tolerance of " + first.test + "; the file has none for the " + test + " test evaluated");
  }
  return c;
}

nlohmann::json toJson(const Conformance& c, double scale) {
  nlohmann::json verdicts = nlohmann::json::array();
  for (const auto& v : c.verdicts)
    verdicts.push_back({{"quantity", v.quantity},
                        {"value", v.value * scale},
                        {"U", v.expanded * scale},
                        {"tolerance", v.tolerance * scale},
                        {"tolerance_text", v.toleranceText},
                        {"verdict", toString(v.verdict)}});
  return {{"tolerance_file", c.toleranceFile},
          {"decision_rule", toString(c.rule)},
          {"decision_rule_text", describe(c.rule)},
          {"verdicts", verdicts},
          {"overall", toString(c.overall())}};
}

nlohmann::json toJson(const UncertaintyBudget& b, double scale) {
  nlohmann::json contributors = nlohmann::json::array();
  for (const auto& k : b.contributors)
    contributors.push_back(
        {{"symbol", k.symbol}, {"source", k.source}, {"u", k.standard * scale}, {"defaulted", k.defaulted}, {"quantities", k.quantities}});
  nlohmann::json quantities = nlohmann::json::object();
  for (const auto& q : b.quantities)
    quantities[q.quantity] = {{"value", q.value * scale}, {"u_cycles", q.statistical * scale}, {"u_c", q.combined * scale}, {"U", q.expanded * scale}};
  return {{"coverage_factor", 2}, {"contributors", contributors}, {"quantities", quantities}};
}

}  // namespace mtacc
