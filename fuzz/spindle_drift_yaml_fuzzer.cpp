// A spindle drift model (YAML): read, then evaluated with its prediction's uncertainty at its
// reference temperatures plus 10 K.
#include "fuzz_input.hpp"
#include "mtacc/io/spindle_drift_yaml.hpp"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  using namespace mtacc;
  return fuzz::asTheFrontEndsDo([&] {
    const auto model = parseSpindleDriftModel(fuzz::text(data, size), "fuzz.yaml");
    const Eigen::VectorXd warm = Eigen::VectorXd::Constant(static_cast<long>(model.sensors.size()), 30.0);
    spindleDrift(model, warm);
    spindleDriftUncertainty(model, warm);
  });
}
