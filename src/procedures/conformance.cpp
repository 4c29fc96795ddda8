#include "mtacc/procedures/conformance.hpp"

#include <fmt/format.h>

#include <algorithm>

#include "mtacc/core/input_error.hpp"

namespace mtacc {

double Tolerance::at(double measuredLength) const {
  double t = value;
  switch (form) {
    case Form::Constant:
      break;
    case Form::Proportional:
      t = value * measuredLength / length;
      break;
    case Form::Increment:
      t = value + increment * std::max(0.0, measuredLength - length) / incrementLength;
      break;
    case Form::Stepped: {
      const auto step = std::lower_bound(stepLengths.begin(), stepLengths.end(), measuredLength);
      if (step == stepLengths.end())
        throw InvalidInput(fmt::format("tolerance '{}': the measured length {:g} mm is beyond its last length {:g} mm", text,
                                       measuredLength, stepLengths.back()));
      t = stepValues[static_cast<size_t>(step - stepLengths.begin())];
      break;
    }
  }
  if (minimum > 0) t = std::max(t, minimum);
  if (maximum > 0) t = std::min(t, maximum);
  return t;
}

const char* toString(DecisionRule rule) { return rule == DecisionRule::Iso14253_1 ? "iso14253-1" : "simple"; }

const char* toString(Verdict verdict) {
  switch (verdict) {
    case Verdict::Pass:
      return "pass";
    case Verdict::Fail:
      return "fail";
    case Verdict::Undecided:
      return "undecided";
  }
  return "undecided";
}

const char* describe(DecisionRule rule) {
  if (rule == DecisionRule::Iso14253_1)
    return "ISO 14253-1: pass only when the result plus its expanded uncertainty U (k = 2) is within the tolerance, fail only "
           "when the result minus U exceeds it; otherwise undecided";
  return "simple acceptance: pass when the result is within the tolerance, the uncertainty not taken into account";
}

Verdict decide(double result, double expandedUncertainty, double tolerance, DecisionRule rule) {
  const double guard = rule == DecisionRule::Iso14253_1 ? expandedUncertainty : 0.0;
  if (result + guard <= tolerance) return Verdict::Pass;
  if (result - guard > tolerance) return Verdict::Fail;
  return Verdict::Undecided;
}

Verdict combined(const std::vector<Verdict>& verdicts) {
  const auto any = [&](Verdict v) { return std::find(verdicts.begin(), verdicts.end(), v) != verdicts.end(); };
  if (any(Verdict::Fail)) return Verdict::Fail;
  if (any(Verdict::Undecided)) return Verdict::Undecided;
  return Verdict::Pass;
}

}  // namespace mtacc
