// Thermal drift tests (CSV, ISO 230-3): read, then evaluated as `mtacc drift` does (the mandrel's
// drift, extremes, hysteresis and the stepwise regression on the temperatures and the first axis's position).
#include "fuzz_input.hpp"
#include "mtacc/io/drift_test_csv.hpp"
#include "mtacc/thermal/drift_regression.hpp"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  using namespace mtacc;
  return fuzz::asTheFrontEndsDo([&] {
    const auto test = parseDriftTestCsv(fuzz::text(data, size), "fuzz.csv");
    const auto drift = mandrelDrift(test.probes);
    for (const auto direction : kDriftDirections) {
      const auto& series = drift[direction];
      if (!series) continue;
      driftExtremes(*series, test.time);
      if (test.temperatures.cols() > 0) {
        driftHysteresis(*series, test.temperatures.col(0));
        const Eigen::VectorXd position = test.axes.empty() ? Eigen::VectorXd() : Eigen::VectorXd(test.positions.col(0));
        selectSensors({test.temperatures, *series, position}, {.folds = 2, .maximumSensors = 3});
      }
    }
  });
}
