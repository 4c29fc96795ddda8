// Machine: seed 003's direct measurements of one component error, simulated and fitted.
#include <pybind11/stl.h>

#include "bindings.hpp"
#include "mtacc/core/input_error.hpp"
#include "mtacc/workflows/component_fit.hpp"
#include "mtacc/workflows/identified_errors.hpp"

namespace mtacc::python {

void exposeDirectMeasurements(MachineClass& machine) {
  machine
      .def("fit_component", [](const PythonMachine& s, const OptionValues& options, const std::string& errorsOut) {
        const ComponentFitRequest r = componentFitRequest(options);
        const auto study = fitComponentFile(s, r);
        if (!errorsOut.empty()) writeIdentifiedErrors(errorsOut, *study.machine, study.errors, identificationRecord(study), "errors_out");
        return toPython(toJson(study));
      })
      .def("simulate_component", [](const PythonMachine& s, const OptionValues& options) {
        simulateComponentFile(s, componentSimulationRequest(options));
      });
}

}  // namespace mtacc::python
