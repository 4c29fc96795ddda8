// Module functions of the thermal and positioning tests: ISO 230-2 positioning, the thermal
// state of a machine, and the ISO 230-3 spindle drift test.
#include <pybind11/stl.h>

#include "bindings.hpp"
#include "mtacc/workflows/positioning.hpp"
#include "mtacc/workflows/thermal_drift.hpp"
#include "mtacc/workflows/thermal_state_summary.hpp"

namespace mtacc::python {

void exposeThermal(py::module_& mod) {
  mod.def("positioning", [](const OptionValues& options) {
    return toPython(toJson(evaluatePositioningFile(positioningRequest(options))));
  });
  mod.def("thermal_state", [](const std::string& machine, const std::string& thermal, int points) {
    return toPython(thermalStateSummary({machine, "", "", std::nullopt, thermal}, points));
  });
  mod.def("drift_test", [](const OptionValues& options, size_t seriesPoints) {
    const DriftTestRequest request = driftTestRequest(options);
    DriftTestEvaluation evaluation;
    {
      py::gil_scoped_release release;
      evaluation = evaluateDriftTest(request);
    }
    return toPython(toJson(evaluation, seriesPoints));
  });
}

}  // namespace mtacc::python
