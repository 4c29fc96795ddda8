#pragma once
// Tolerances as the machine-tool standards write them and the decision whether a result conforms
// (ISO 14253-1:2017). Every tolerance here is an upper limit of a non-negative result (a range, a
// repeatability, a straightness): conformance is proven only when the result plus its expanded
// uncertainty lies inside it, non-conformance only when the result minus it lies outside; between
// the two the verdict is undecided.
#include <string>
#include <vector>

namespace mtacc {

// A tolerance that may depend on the measured length L (mm):
//  - constant:                        T
//  - proportional (ISO 230-1):        T0 for L0            T0 L / L0
//  - with an increment:               T0 for L0, + dT per additional dL    T0 + dT max(0, L - L0) / dL
//  - stepped by length ranges:        T1 up to L1; T2 up to L2; ...        the first Ti with L <= Li
// each optionally bounded by min and max. Values in mm or rad, as the result's.
struct Tolerance {
  enum class Form { Constant, Proportional, Increment, Stepped };
  Form form = Form::Constant;
  double value = 0, length = 0;                 // T or T0, and L0
  double increment = 0, incrementLength = 0;    // dT per dL
  std::vector<double> stepValues, stepLengths;  // Ti up to Li, Li increasing
  double minimum = 0, maximum = 0;              // 0: none
  std::string text;                             // as written

  // The tolerance for a measured length; throws InvalidInput when L is beyond a stepped table.
  double at(double measuredLength) const;
};

enum class DecisionRule { Iso14253_1, Simple };  // Simple: the result against the tolerance alone
enum class Verdict { Pass, Fail, Undecided };

const char* toString(DecisionRule rule);
const char* toString(Verdict verdict);
const char* describe(DecisionRule rule);  // one sentence for a report

Verdict decide(double result, double expandedUncertainty, double tolerance, DecisionRule rule);
// The verdict of several together: fail if any fails, else undecided if any is, else pass.
Verdict combined(const std::vector<Verdict>& verdicts);

}  // namespace mtacc
