// Measurement conditions, and the uncertainty budget of a positioning test computed from them.
#include "fuzz_input.hpp"
#include "mtacc/io/measurement_conditions_yaml.hpp"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  using namespace mtacc;
  static const PositioningTest test = [] {
    PositioningTest t;
    t.targets = {0, 100, 200};
    t.forward = Eigen::MatrixXd::Constant(3, 2, 1e-3);
    t.forward(1, 1) = 2e-3;
    t.backward = -t.forward;
    return t;
  }();
  static const PositioningResult result = evaluatePositioning(test);
  return fuzz::asTheFrontEndsDo([&] {
    const auto conditions = parseMeasurementConditions(fuzz::text(data, size), "fuzz.yaml");
    positioningUncertainty(test, result, conditions);
  });
}
